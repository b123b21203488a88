//! `jaus.Packet`: a whole JAUS packet, its RA 3.3 header fields as attributes, its
//! body and the message it holds.
//!
//! Decoding a packet checks its body against the message's layout
//! (`jaus_dynamic::Schema::check`: every check of the decode, the same errors) and
//! keeps the bytes; nothing else is made until it is read: the `jaus.Message` when
//! `.message` is first read, its values when a field is (`message`).

use crate::body::Body;
use crate::catalog::Catalog;
use crate::convert::{json_to_py, object_to_dict};
use crate::errors::decode_error;
use crate::message::Message;
use jaus::{Address, Header};
use jaus_dynamic::DynMessage;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyString};
use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;
use std::sync::Arc;

/// A JAUS packet: the 16-byte header's fields as attributes (`priority`, `ack_nak`,
/// `source`, ...), the `body` bytes and the `message` they hold (None for a command
/// code the schema does not define, or a part of a multi-packet message).
///
/// The body is checked when the packet is decoded: a packet that is not a message
/// raises then. What is kept is the bytes; the message's Python object is made when
/// first read, its values when its fields are.
#[pyclass(module = "jaus", frozen)]
#[derive(Debug)]
pub struct Packet {
    header: Header,
    body: Body,
    message: Option<Held>,
}

/// The message a packet holds: checked, its `jaus.Message` made on first read.
struct Held {
    name: &'static str,
    cat: Arc<Catalog>,
    object: pyo3::sync::PyOnceLock<Py<Message>>,
}

impl std::fmt::Debug for Held {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Held")
            .field("name", &self.name)
            .finish_non_exhaustive()
    }
}

impl Packet {
    /// The packet of `header` and `body`, its body checked when it is a whole message
    /// of the schema.
    pub(crate) fn decode(
        py: Python<'_>,
        cat: &Arc<Catalog>,
        header: Header,
        body: Body,
    ) -> PyResult<Packet> {
        let whole = header.data_flag == jaus::wire::DataFlag::Single;
        let message = if whole {
            match cat.schema.check(header.command_code, body.bytes(py)) {
                Ok(m) => Some(Held {
                    name: m.name,
                    cat: cat.clone(),
                    object: pyo3::sync::PyOnceLock::new(),
                }),
                // A code the schema does not define: a raw packet.
                Err(e)
                    if matches!(
                        e.kind(),
                        jaus::codec::DecodeErrorKind::UnknownCommandCode { code }
                            if *code == header.command_code.0
                    ) =>
                {
                    None
                }
                Err(e) => return Err(decode_error(py, &e)),
            }
        } else {
            None
        };
        Ok(Packet {
            header,
            body,
            message,
        })
    }

    /// The packet.
    pub(crate) fn packet(&self, py: Python<'_>) -> jaus::Packet {
        jaus::Packet {
            header: self.header,
            body: self.body.bytes(py).to_vec(),
        }
    }

    fn header(&self) -> &Header {
        &self.header
    }

    /// The message's object, when the packet holds one (made on the first call).
    fn message_object<'a>(&'a self, py: Python<'_>) -> PyResult<Option<&'a Py<Message>>> {
        let Some(held) = &self.message else {
            return Ok(None);
        };
        // The lock runs the maker once; a packet's message is made once.
        held.object
            .get_or_try_init(py, || {
                let m = Message::checked(
                    held.cat.clone(),
                    held.name,
                    self.header.command_code,
                    self.body.clone_ref(py),
                );
                Py::new(py, m)
            })
            .map(Some)
    }

    fn raw(&self, py: Python<'_>) -> jaus::RawMessage {
        jaus::RawMessage {
            code: self.header().command_code,
            body: self.body.bytes(py).to_vec(),
        }
    }
}

fn address_tuple(a: Address) -> (u8, u8, u8, u8) {
    (a.subsystem, a.node, a.component, a.instance)
}

/// The JSON text of a serde value (the header's enumerations).
fn json_text<T: Serialize>(v: &T) -> String {
    match serde_json::to_value(v) {
        Ok(serde_json::Value::String(s)) => s,
        Ok(other) => other.to_string(),
        Err(e) => e.to_string(),
    }
}

#[pymethods]
impl Packet {
    /// Priority 0-15.
    #[getter]
    fn priority(&self) -> u8 {
        self.header().priority
    }
    /// `"none"`, `"request"`, `"nak"` or `"ack"`.
    #[getter]
    fn ack_nak(&self) -> String {
        json_text(&self.header().ack_nak)
    }
    /// The service-connection flag.
    #[getter]
    fn service_connection(&self) -> bool {
        self.header().service_connection
    }
    /// The experimental flag.
    #[getter]
    fn experimental(&self) -> bool {
        self.header().experimental
    }
    /// The header version (2 for RA 3.2/3.3).
    #[getter]
    fn version(&self) -> u8 {
        self.header().version
    }
    /// The two reserved bits of the properties word.
    #[getter]
    fn reserved(&self) -> u8 {
        self.header().reserved
    }
    /// The command code.
    #[getter]
    fn command_code(&self) -> u16 {
        self.header().command_code.0
    }
    /// `(subsystem, node, component, instance)`.
    #[getter]
    fn destination(&self) -> (u8, u8, u8, u8) {
        address_tuple(self.header().destination)
    }
    /// `(subsystem, node, component, instance)`.
    #[getter]
    fn source(&self) -> (u8, u8, u8, u8) {
        address_tuple(self.header().source)
    }
    /// The body size the header gives.
    #[getter]
    fn data_size(&self) -> u16 {
        self.header().data_size
    }
    /// `"single"`, `"first"`, `"normal"`, `"retransmit"` or `"last"`.
    #[getter]
    fn data_flag(&self) -> String {
        json_text(&self.header().data_flag)
    }
    /// The sequence number.
    #[getter]
    fn sequence_number(&self) -> u16 {
        self.header().sequence_number
    }
    /// The body bytes.
    #[getter]
    fn body<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        PyBytes::new(py, self.body.bytes(py))
    }
    /// The message the body holds, or None.
    #[getter]
    fn message(&self, py: Python<'_>) -> PyResult<Option<Py<Message>>> {
        Ok(self.message_object(py)?.map(|m| m.clone_ref(py)))
    }
    /// The message's name, `"Raw"` when the schema does not define the code.
    #[getter]
    fn name(&self) -> &'static str {
        self.message.as_ref().map_or("Raw", |m| m.name)
    }

    /// The header as a dict (the `"header"` of `jaus decode`'s line).
    fn header_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let json =
            serde_json::to_value(self.header()).map_err(|e| PyTypeError::new_err(e.to_string()))?;
        let d = PyDict::new(py);
        // In the header's field order.
        for k in [
            "priority",
            "ack_nak",
            "service_connection",
            "experimental",
            "version",
            "reserved",
            "command_code",
            "destination",
            "source",
            "data_size",
            "data_flag",
            "sequence_number",
        ] {
            if let Some(v) = json.get(k) {
                d.set_item(k, json_to_py(py, v)?)?;
            }
        }
        Ok(d)
    }

    /// The line `jaus decode` prints, as a dict: `{"header", "message", "fields"}`.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("header", self.header_dict(py)?)?;
        match self.message_object(py)? {
            Some(m) => {
                let m = m.get().msg(py)?;
                d.set_item("message", PyString::new(py, m.name))?;
                d.set_item("fields", object_to_dict(py, &m.fields)?)?;
            }
            None => {
                let raw = self.raw(py);
                let json =
                    serde_json::to_value(&raw).map_err(|e| PyTypeError::new_err(e.to_string()))?;
                d.set_item("message", "Raw")?;
                d.set_item("fields", json_to_py(py, &json)?)?;
            }
        }
        Ok(d)
    }

    /// The line `jaus decode` prints, text for text.
    fn to_json(&self, py: Python<'_>) -> PyResult<String> {
        let message = match self.message_object(py)? {
            Some(m) => Some(m.get().msg(py)?),
            None => None,
        };
        let raw = message.is_none().then(|| self.raw(py));
        let line = Line {
            packet: self,
            message,
            raw,
        };
        serde_json::to_string(&line).map_err(|e| PyTypeError::new_err(e.to_string()))
    }

    /// The packet's bytes (the header's data size recomputed from the body).
    fn encode<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let p = jaus::Packet::new(self.header, self.body.bytes(py).to_vec());
        let bytes = jaus::codec::Encode::to_bytes(&p)
            .map_err(|e| crate::errors::encode_error(py, Some(self.name()), &e))?;
        Ok(PyBytes::new(py, &bytes))
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let a = |a: Address| format!("{a}");
        format!(
            "<jaus.Packet {} ({}) {} -> {}, {} byte(s)>",
            self.name(),
            self.header().command_code,
            a(self.header().source),
            a(self.header().destination),
            self.body.bytes(py).len()
        )
    }
}

/// `{"header": ..., "message": ..., "fields": ...}`, as `jaus decode` prints it.
struct Line<'a> {
    packet: &'a Packet,
    message: Option<&'a DynMessage>,
    /// The body as a raw message (a packet without a message).
    raw: Option<jaus::RawMessage>,
}

impl Serialize for Line<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(3))?;
        map.serialize_entry("header", self.packet.header())?;
        match self.message {
            Some(m) => {
                map.serialize_entry("message", m.name)?;
                map.serialize_entry("fields", &m.fields)?;
            }
            None => {
                map.serialize_entry("message", "Raw")?;
                map.serialize_entry("fields", &self.raw)?;
            }
        }
        map.end()
    }
}
