"""JAUS (SAE AS5669A, RA 3.3) messages from Python.

Every message of the SDK's definitions, and of a vendor's overlays loaded at run
time, decoded and encoded by the SDK's Rust codec: byte-exact with OpenJAUS, with
fields in the names, units and forms of the ``jaus`` CLI's JSON lines.

>>> import jaus
>>> m = jaus.message("SetTravelSpeed", speed=2.0)
>>> jaus.encode(m)
b'\\r\\x00'
>>> round(jaus.decode(b"\\r\\x00", m.code).speed, 2)
1.98

A live system: ``jaus.Client`` joins it as the ``jaus`` CLI does (discovery,
heartbeats, control kept) with ``send``, ``query``, ``control`` and ``watch``.

See docs/python.md of the SDK for the whole API.
"""

from . import _jaus
from ._aio import AsyncWatch
from ._jaus import (
    As4Client,
    ClientError,
    Confirmation,
    Control,
    ControlRefused,
    DecodeError,
    EncodeError,
    JausError,
    Message,
    Packet,
    Record,
    Schema,
    SpecError,
    Watch,
    decode,
    decode_many,
    decode_packet,
    doc,
    encode,
    encode_packet,
    message,
    messages,
    read_pcap,
)


class Client(_jaus.Client):
    """A member of a JAUS system (see ``jaus._jaus.Client``), with ``watch_async``."""

    def watch_async(self, dest, query, **kwargs):
        """``watch(...)`` as an async iterator of reports (``async for``)."""
        return AsyncWatch(self.watch(dest, query, **kwargs))


class _MessageClass(type):
    """The type of ``jaus.ReportGlobalPose`` and the other message names: calling it
    builds the message, ``isinstance`` checks a ``jaus.Message``'s name."""

    def __call__(cls, **fields):
        return message(cls.__name__, **fields)

    def __instancecheck__(cls, obj):
        return isinstance(obj, Message) and obj.name == cls.__name__


def _message_classes():
    made = {}
    for name in messages():
        made[name] = _MessageClass(
            name, (), {"__module__": __name__, "__doc__": f"The message {name}: jaus.doc({name!r})."}
        )
    return made


globals().update(_message_classes())

__all__ = [
    "AsyncWatch",
    "Client",
    "ClientError",
    "Control",
    "ControlRefused",
    "DecodeError",
    "EncodeError",
    "JausError",
    "Message",
    "Packet",
    "Record",
    "Schema",
    "SpecError",
    "Watch",
    "decode",
    "decode_many",
    "decode_packet",
    "doc",
    "encode",
    "encode_packet",
    "message",
    "messages",
    "read_pcap",
] + messages()
