"""Type stubs of the extension module ``jaus._jaus`` (re-exported by ``jaus``)."""

import os
from typing import (
    Any,
    Dict,
    Generic,
    Iterable,
    Iterator,
    List,
    Literal,
    Optional,
    Sequence,
    Tuple,
    TypeVar,
    Union,
    overload,
)

Address = Union[Tuple[int, int, int, int], str]
"""``(subsystem, node, component, instance)``, or ``"s.n.c.i"``."""

Socket = Tuple[str, int]
"""``(ip, port)``."""

_Path = Union[str, "os.PathLike[str]"]

class JausError(ValueError):
    """Every error of the jaus package."""

    message: Optional[str]
    """The message being decoded or encoded, when known."""
    field: Optional[str]
    """The field (``Message.field``, or a path into it), when known."""
    path: List[str]
    """Decoding: the field and the fields that hold it, innermost first."""
    offset: Optional[int]
    """Decoding: the byte offset in the body."""

class DecodeError(JausError):
    """Bytes that are not a message."""

    index: int
    """``decode_many`` only: the position of the packet in the packets given."""

class EncodeError(JausError):
    """A message that cannot be encoded, or fields that do not fit a message."""

class SpecError(JausError):
    """Definition files (vendor overlays) that do not load."""

class ClientError(JausError):
    """What ``jaus.Client`` could not do: no answer, a NAK, a refused watch, a closed
    client."""

    address: Optional[str]
    """The component the message went to, when known."""
    response_code: Optional[str]
    """``jaus.ControlRefused`` only: the response code."""
    outcome: str
    """``send(..., confirm=True)`` only: ``"refused"`` or ``"not_confirmed"``."""
    detail: str
    """``send(..., confirm=True)`` only: what is known (the refusal's reason, what the
    read-back showed, whether the component acknowledges)."""

class ControlRefused(ClientError):
    """A control request refused: ``response_code`` is ``"InsufficientAuthority"`` or
    ``"NotAvailable"`` (Confirm Component Control), or ``"Rejected"`` (Reject Component
    Control)."""

class Record:
    """A record inside a message (or a bit field, a union with a value, an unknown
    enumeration value): its entries as attributes and items."""

    def __getattr__(self, name: str) -> Any: ...
    def __getitem__(self, key: str) -> Any: ...
    def __contains__(self, key: object) -> bool: ...
    def __len__(self) -> int: ...
    def __iter__(self) -> Iterator[str]: ...
    def keys(self) -> List[str]: ...
    def to_dict(self) -> Dict[str, Any]:
        """The JSON form as a dict."""
    def to_json(self) -> str:
        """The JSON form as text."""

class Message:
    """A JAUS message: its fields are attributes, in the units of the CLI's JSON."""

    @property
    def name(self) -> str: ...
    @property
    def code(self) -> int: ...
    @property
    def fields(self) -> List[str]:
        """The names of the fields present, in wire order."""
    def __getattr__(self, name: str) -> Any: ...
    def __getitem__(self, name: str) -> Any: ...
    def __contains__(self, name: object) -> bool: ...
    def to_dict(self) -> Dict[str, Any]:
        """The ``"fields"`` of the line ``jaus decode`` prints."""
    def to_json(self) -> str:
        """The ``"fields"`` of the line ``jaus decode`` prints, as text."""
    def encode(self) -> bytes:
        """The body."""
    def doc(self) -> str:
        """The description ``jaus messages NAME`` prints."""
    @staticmethod
    def from_dict(name: str, fields: Optional[Dict[str, Any]] = None) -> "Message":
        """The SDK's message ``name`` with ``fields`` in the form ``to_dict()`` gives."""

class Packet:
    """A JAUS packet: the header's fields, the body, the message it holds."""

    @property
    def priority(self) -> int: ...
    @property
    def ack_nak(self) -> str:
        """``"none"``, ``"request"``, ``"nak"`` or ``"ack"``."""
    @property
    def service_connection(self) -> bool: ...
    @property
    def experimental(self) -> bool: ...
    @property
    def version(self) -> int: ...
    @property
    def reserved(self) -> int: ...
    @property
    def command_code(self) -> int: ...
    @property
    def destination(self) -> Tuple[int, int, int, int]: ...
    @property
    def source(self) -> Tuple[int, int, int, int]: ...
    @property
    def data_size(self) -> int: ...
    @property
    def data_flag(self) -> str:
        """``"single"``, ``"first"``, ``"normal"``, ``"retransmit"`` or ``"last"``."""
    @property
    def sequence_number(self) -> int: ...
    @property
    def body(self) -> bytes: ...
    @property
    def message(self) -> Optional[Message]:
        """The message, or None (a code the schema does not define, a part of a
        multi-packet message)."""
    @property
    def name(self) -> str:
        """The message's name, ``"Raw"`` without one."""
    def header_dict(self) -> Dict[str, Any]: ...
    def to_dict(self) -> Dict[str, Any]:
        """The line ``jaus decode`` prints, as a dict."""
    def to_json(self) -> str:
        """The line ``jaus decode`` prints."""
    def encode(self) -> bytes:
        """The packet's bytes."""

class Schema:
    """The messages of a definition set: the SDK's, or the SDK's with vendor overlays."""

    @staticmethod
    def sdk() -> "Schema": ...
    @staticmethod
    def load(overlays: Sequence[_Path]) -> "Schema": ...
    def messages(self) -> List[str]: ...
    def code(self, name: str) -> int: ...
    def name(self, code: int) -> Optional[str]: ...
    def fields(self, name: str) -> List[str]: ...
    def doc(self, name: str) -> str: ...
    def decode(self, body: bytes, code: int) -> Message: ...
    def decode_packet(self, packet: bytes) -> Packet: ...
    @overload
    def decode_many(
        self, packets: Iterable[bytes], *, strict: Literal[True] = True
    ) -> List[Packet]: ...
    @overload
    def decode_many(
        self, packets: Iterable[bytes], *, strict: bool
    ) -> List[Union[Packet, DecodeError]]: ...
    def encode(self, message: Message) -> bytes: ...
    def encode_packet(
        self,
        message: Message,
        source: Address,
        destination: Address,
        *,
        priority: int = 6,
        ack_nak: str = "none",
        service_connection: bool = False,
        experimental: bool = False,
        sequence_number: int = 0,
    ) -> bytes: ...
    def message(self, name: str, /, **fields: Any) -> Message: ...
    def from_dict(self, name: str, fields: Optional[Dict[str, Any]] = None) -> Message: ...
    def read_pcap(
        self, path: _Path, *, strict: bool = True
    ) -> List[Tuple[float, Socket, Socket, Packet]]: ...

def decode(body: bytes, code: int) -> Message:
    """Decodes the body of the SDK's message with command code ``code``."""

def decode_packet(packet: bytes) -> Packet:
    """Decodes a whole packet: the 16-byte header and the body (checked now; the
    message's fields become Python objects as they are read)."""

@overload
def decode_many(packets: Iterable[bytes], *, strict: Literal[True] = True) -> List[Packet]:
    """Decodes every packet, in order; the first that does not decode raises its
    ``DecodeError`` (``.index`` its position)."""
@overload
def decode_many(packets: Iterable[bytes], *, strict: bool) -> List[Union[Packet, DecodeError]]:
    """``strict=False``: a packet that does not decode is its ``DecodeError`` (with
    ``.index``) in the list."""

def encode(message: Message) -> bytes:
    """The body of ``message``."""

def encode_packet(
    message: Message,
    source: Address,
    destination: Address,
    *,
    priority: int = 6,
    ack_nak: str = "none",
    service_connection: bool = False,
    experimental: bool = False,
    sequence_number: int = 0,
) -> bytes:
    """The packet of ``message`` from ``source`` to ``destination``."""

def message(name: str, /, **fields: Any) -> Message:
    """The SDK's message ``name`` with the fields given as keywords."""

def messages() -> List[str]:
    """The names of the SDK's messages, in definition order."""

def doc(name: str) -> str:
    """The description of message ``name`` (``jaus messages NAME``)."""

def read_pcap(
    path: _Path, *, strict: bool = True
) -> List[Tuple[float, Socket, Socket, Packet]]:
    """Every JAUS message of a pcap/pcapng capture: ``(time, source, destination, packet)``."""

def _stubs() -> str:
    """The text of ``jaus/__init__.pyi``, generated from the SDK's definitions."""

_M = TypeVar("_M", bound=Message)
_C = TypeVar("_C", bound="Client")

class Watch(Generic[_M]):
    """The reports of ``Client.watch``: iterate (blocking, the GIL released), ``get``,
    ``close`` (also on ``with`` exit, garbage collection and the client's close)."""

    def __iter__(self) -> "Watch[_M]": ...
    def __next__(self) -> _M: ...
    def get(self, timeout: Optional[float] = None) -> Optional[_M]:
        """The next report; None when none came within ``timeout`` or the watch ended."""
    @property
    def closed(self) -> bool: ...
    @property
    def end_reason(self) -> Optional[str]: ...
    @property
    def dropped(self) -> int:
        """Reports dropped because the queue was full."""
    def close(self) -> None:
        """Ends the service connection or event at the provider."""
    def __enter__(self) -> "Watch[_M]": ...
    def __exit__(self, *args: Any) -> bool: ...

class Control:
    """Control of one component (``Client.control``): ``with`` it, or ``acquire()`` and
    ``release()``."""

    @property
    def address(self) -> str: ...
    @property
    def held(self) -> bool: ...
    def acquire(self) -> None:
        """Requests control and waits until granted; raises ``ControlRefused``."""
    def release(self) -> None:
        """Gives control back."""
    def __enter__(self) -> "Control": ...
    def __exit__(self, *args: Any) -> bool: ...

class Confirmation:
    """How a command sent with ``Client.send(..., confirm=True)`` took effect."""

    @property
    def outcome(self) -> Literal["acknowledged", "confirmed_by_readback"]:
        """``"acknowledged"`` (an ACK) or ``"confirmed_by_readback"`` (no ACK; the
        read-back shows the effect)."""
    @property
    def detail(self) -> str:
        """What the read-back showed (``"Report Travel Speed 2.44 m/s"``); empty for an
        acknowledgement."""

class As4Client:
    """An SAE AS-4 client (AS5669A over UDP) naming any message of the AS-4 definitions:
    jaus-as4's (Core v1.1, Mobility), a vendor's YAML on them (``spec``), or imported JSIDL
    (``jsidl``). Answers are dicts ``{"t", "from", "message", "fields"}``."""

    def __init__(
        self,
        peer: str,
        me: str = "42.1.7",
        *,
        bind: str = "0.0.0.0:0",
        spec: list[str] = ...,
        jsidl: list[str] = ...,
        timeout: float = 2.0,
    ) -> None: ...
    def send(self, to: str, name: str, **fields: Any) -> None:
        """Sends message ``name`` with ``fields`` to component ``to`` (``"S.N.C"``)."""
    def query(self, to: str, name: str, *, timeout: float | None = None, **fields: Any) -> dict[str, Any]:
        """Sends ``name`` and returns the component's first answer; ``ClientError``
        when none comes within ``timeout``."""
    def receive(self, to: str, *, timeout: float | None = None) -> list[dict[str, Any]]:
        """What ``to`` sends within ``timeout``, oldest first."""
    def take_control(self, to: str, authority: int) -> None:
        """Request Control; ``ClientError`` naming the answer when refused."""
    def release_control(self, to: str) -> None:
        """Release Control."""

class Client:
    """A member of a JAUS system, joined as the ``jaus`` CLI joins it."""

    def __init__(
        self,
        peer: Union[str, Sequence[str], None] = None,
        me: Optional[Address] = None,
        *,
        bind: Optional[str] = None,
        timeout: float = 5.0,
        mode: str = "auto",
        schema: Optional[Schema] = None,
        name: str = "jaus Python client",
    ) -> None: ...
    @property
    def me(self) -> str: ...
    @property
    def local(self) -> Socket: ...
    @property
    def joined(self) -> bool: ...
    @property
    def closed(self) -> bool: ...
    def tree(self) -> Dict[str, Any]:
        """The system tree as ``jaus discover --json`` prints it."""
    @overload
    def send(
        self,
        dest: Address,
        message: Message,
        *,
        ack: bool = False,
        confirm: Literal[False] = False,
        timeout: Optional[float] = None,
    ) -> None: ...
    @overload
    def send(
        self,
        dest: Address,
        message: Message,
        *,
        ack: bool = False,
        confirm: Literal[True],
        timeout: Optional[float] = None,
    ) -> Confirmation: ...
    def query(
        self,
        dest: Address,
        message: Message,
        *,
        timeout: Optional[float] = None,
        report: Optional[str] = None,
    ) -> Message: ...
    def control(
        self, dest: Address, *, authority: Optional[int] = None, timeout: Optional[float] = None
    ) -> Control: ...
    def watch(
        self,
        dest: Address,
        query: Message,
        *,
        periodic_hz: Optional[float] = None,
        presence: Optional[int] = None,
        queue: int = 64,
        timeout: Optional[float] = None,
        report: Optional[str] = None,
    ) -> Watch[Message]: ...
    def stats(self) -> Dict[str, int]:
        """The client's counters (datagrams, messages, drops, NAKs, control lost)."""
    def close(self) -> None:
        """Ends every watch, gives control back, stops the client's thread."""
    def __enter__(self: _C) -> _C: ...
    def __exit__(self, *args: Any) -> bool: ...
