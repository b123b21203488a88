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

See docs/python.md of the SDK for the whole API.
"""

from ._jaus import (
    DecodeError,
    EncodeError,
    JausError,
    Message,
    Packet,
    Record,
    Schema,
    SpecError,
    decode,
    decode_packet,
    doc,
    encode,
    encode_packet,
    message,
    messages,
    read_pcap,
)

__all__ = [
    "DecodeError",
    "EncodeError",
    "JausError",
    "Message",
    "Packet",
    "Record",
    "Schema",
    "SpecError",
    "decode",
    "decode_packet",
    "doc",
    "encode",
    "encode_packet",
    "message",
    "messages",
    "read_pcap",
]
