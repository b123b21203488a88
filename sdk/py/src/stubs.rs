//! The type stubs of the package `jaus` (`python/jaus/__init__.pyi`), generated from the
//! message definitions the codec uses: a class per message with its fields as typed
//! attributes and keyword arguments, `jaus.message(NAME)` typed per name, and
//! `Client.query`/`watch` typed per query with its report. `jaus._jaus._stubs()`
//! returns the text; the pytest suite checks that the committed file equals it
//! (`UPDATE_GOLDEN=1` rewrites the file).

use std::fmt::Write as _;

use crate::message::MESSAGE_MEMBERS;
use jaus_spec::{Field, Spec, TypeKind, Wire};

/// Python's keywords: not attribute or argument names.
const KEYWORDS: &[&str] = &[
    "False", "None", "True", "and", "as", "assert", "async", "await", "break", "class", "continue",
    "def", "del", "elif", "else", "except", "finally", "for", "from", "global", "if", "import",
    "in", "is", "lambda", "nonlocal", "not", "or", "pass", "raise", "return", "try", "while",
    "with", "yield",
];

const HEAD: &str = r#""""Type stubs of the package ``jaus``, GENERATED from the SDK's message definitions
by ``jaus._jaus._stubs()`` (sdk/py/src/stubs.rs): do not edit; the pytest suite checks
this file is up to date (``UPDATE_GOLDEN=1`` rewrites it).

Each message is a class here (``jaus.ReportGlobalPose``): at run time calling it builds
the message (``jaus.message(NAME, **fields)``) and ``isinstance`` checks the message's
name; every message object is a ``jaus.Message``."""

from typing import Any, AsyncIterator, Dict, Generic, Iterator, List, Literal, Mapping, Optional, TypeVar, Union, overload

from ._jaus import Address as Address
from ._jaus import ClientError as ClientError
from ._jaus import Control as Control
from ._jaus import ControlRefused as ControlRefused
from ._jaus import DecodeError as DecodeError
from ._jaus import EncodeError as EncodeError
from ._jaus import JausError as JausError
from ._jaus import Message as Message
from ._jaus import Packet as Packet
from ._jaus import Record as Record
from ._jaus import Schema as Schema
from ._jaus import SpecError as SpecError
from ._jaus import Watch as Watch
from ._jaus import decode as decode
from ._jaus import decode_many as decode_many
from ._jaus import decode_packet as decode_packet
from ._jaus import doc as doc
from ._jaus import encode as encode
from ._jaus import encode_packet as encode_packet
from ._jaus import messages as messages
from ._jaus import read_pcap as read_pcap
from ._jaus import Client as _Client

_M = TypeVar("_M", bound=Message)

_RecordIn = Union[Record, Mapping[str, Any]]
"""A record, bit field or union given to a constructor: a ``jaus.Record`` or a dict of
the JSON form."""

class AsyncWatch(Generic[_M]):
    """The reports of a ``jaus.Watch`` for ``async for``; ``async with`` ends it."""

    @property
    def watch(self) -> Watch[_M]: ...
    def __aiter__(self) -> AsyncIterator[_M]: ...
    async def __anext__(self) -> _M: ...
    async def aclose(self) -> None: ...
    async def __aenter__(self) -> "AsyncWatch[_M]": ...
    async def __aexit__(self, *exc: Any) -> bool: ...
"#;

fn escape_doc(s: &str) -> String {
    s.replace('\\', "\\\\")
        .replace("\"\"\"", "\\\"\\\"\\\"")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// The Python type of a value of wire form `w` as a decoded message gives it; `input`:
/// as a constructor takes it.
fn py_type(spec: &Spec, w: &Wire, input: bool) -> String {
    let record = if input { "_RecordIn" } else { "Record" };
    match w {
        Wire::Int(_) => "int".into(),
        Wire::F32 | Wire::F64 | Wire::Scaled { .. } => "float".into(),
        Wire::Str(_) | Wire::Bytes(_) => "str".into(),
        Wire::Flag => "bool".into(),
        Wire::Packet { .. } => "Dict[str, Any]".into(),
        Wire::List { elem, .. } | Wire::ListField { elem, .. } => {
            format!("List[{}]", py_type(spec, elem, input))
        }
        Wire::Named { name, kind, .. } => match kind {
            TypeKind::Record | TypeKind::Bitfield => record.into(),
            TypeKind::Union => format!("Union[str, {record}]"),
            TypeKind::Enum => {
                let names: Vec<String> = spec
                    .ty(name)
                    .map(|t| {
                        t.def
                            .values
                            .iter()
                            .map(|v| format!("{:?}", v.name))
                            .collect()
                    })
                    .unwrap_or_default();
                if names.is_empty() {
                    format!("Union[str, {record}]")
                } else {
                    format!("Union[Literal[{}], {record}]", names.join(", "))
                }
            }
        },
    }
}

fn optional(f: &Field) -> bool {
    f.def.bit.is_some() || f.def.present_if.is_some()
}

fn usable(name: &str) -> bool {
    !MESSAGE_MEMBERS.contains(&name) && !KEYWORDS.contains(&name)
}

fn field_doc(f: &Field) -> String {
    let mut parts = Vec::new();
    if let Some(u) = &f.def.unit {
        parts.push(format!("Unit: {u}."));
    }
    if let Some(b) = f.def.bit {
        parts.push(format!("Optional: presence bit {b}."));
    }
    if let Some(d) = &f.def.description {
        parts.push(d.clone());
    }
    escape_doc(&parts.join(" "))
}

/// The text of `__init__.pyi` for the messages of `spec`.
pub fn render(spec: &Spec) -> String {
    let mut out = String::from(HEAD);
    for m in &spec.messages {
        let name = &m.def.name;
        let _ = writeln!(out, "\nclass {name}(Message):");
        let doc = m.def.description.as_deref().unwrap_or(name);
        let _ = writeln!(
            out,
            "    \"\"\"{} (code 0x{:04X}).\"\"\"\n",
            escape_doc(doc.trim_end_matches('.')),
            m.def.code.0
        );
        let fields: Vec<&Field> = m.fields.iter().filter(|f| usable(&f.def.name)).collect();
        for f in &fields {
            let t = py_type(spec, &f.wire, false);
            let t = if optional(f) {
                format!("Optional[{t}]")
            } else {
                t
            };
            let _ = writeln!(out, "    {}: {t}", f.def.name);
            let d = field_doc(f);
            if !d.is_empty() {
                let _ = writeln!(out, "    \"\"\"{d}\"\"\"");
            }
        }
        let params: Vec<String> = fields
            .iter()
            .map(|f| format!("{}: {} = ...", f.def.name, py_type(spec, &f.wire, true)))
            .collect();
        if params.is_empty() {
            let _ = writeln!(out, "    def __init__(self) -> None: ...");
        } else {
            let _ = writeln!(
                out,
                "    def __init__(self, *, {}) -> None: ...",
                params.join(", ")
            );
        }
    }
    out.push('\n');
    for m in &spec.messages {
        let _ = writeln!(
            out,
            "@overload\ndef message(name: Literal[{:?}], /, **fields: Any) -> {}: ...",
            m.def.name, m.def.name
        );
    }
    out.push_str("@overload\ndef message(name: str, /, **fields: Any) -> Message: ...\n\n");
    out.push_str("class Client(_Client):\n    \"\"\"A member of a JAUS system (see docs/python.md); `query` and `watch` are\n    typed per query with the report that answers it.\"\"\"\n\n");
    let pairs: Vec<(&str, &str)> = spec
        .messages
        .iter()
        .filter(|m| m.def.is_query())
        .filter_map(|q| {
            Some((
                q.def.name.as_str(),
                spec.report_of(&q.def)?.def.name.as_str(),
            ))
        })
        .collect();
    let common = "*, timeout: Optional[float] = ..., report: Optional[str] = ...";
    let watch = "*, periodic_hz: Optional[float] = ..., presence: Optional[int] = ..., queue: int = ..., timeout: Optional[float] = ..., report: Optional[str] = ...";
    for (q, r) in &pairs {
        let _ = writeln!(
            out,
            "    @overload\n    def query(self, dest: Address, message: {q}, {common}) -> {r}: ..."
        );
    }
    let _ = writeln!(out, "    @overload\n    def query(self, dest: Address, message: Message, {common}) -> Message: ...");
    for (q, r) in &pairs {
        let _ = writeln!(out, "    @overload\n    def watch(self, dest: Address, query: {q}, {watch}) -> Watch[{r}]: ...");
    }
    let _ = writeln!(out, "    @overload\n    def watch(self, dest: Address, query: Message, {watch}) -> Watch[Message]: ...");
    for (q, r) in &pairs {
        let _ = writeln!(out, "    @overload\n    def watch_async(self, dest: Address, query: {q}, {watch}) -> AsyncWatch[{r}]: ...");
    }
    let _ = writeln!(out, "    @overload\n    def watch_async(self, dest: Address, query: Message, {watch}) -> AsyncWatch[Message]: ...");
    out
}
