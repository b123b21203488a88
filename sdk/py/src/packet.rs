//! `jaus.Packet`: a whole JAUS packet, its RA 3.3 header fields as attributes, its
//! body and the message it holds.

use crate::catalog::Catalog;
use crate::convert::{json_to_py, object_to_dict};
use crate::message::Message;
use jaus::{Address, Header};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyString};
use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;
use std::sync::Arc;

/// A JAUS packet: the 16-byte header's fields as attributes (`priority`, `ack_nak`,
/// `source`, ...), the `body` bytes and the `message` they hold (None for a command
/// code the schema does not define, or a part of a multi-packet message).
#[pyclass(module = "jaus", frozen)]
#[derive(Debug)]
pub struct Packet {
    packet: jaus::Packet,
    message: Option<Py<Message>>,
}

impl Packet {
    /// The packet of `header` and `body`, its body decoded when it is a whole message
    /// of the schema.
    pub(crate) fn decode(
        py: Python<'_>,
        cat: &Arc<Catalog>,
        header: Header,
        body: Vec<u8>,
    ) -> PyResult<Packet> {
        let whole = header.data_flag == jaus::wire::DataFlag::Single;
        let message = match cat.schema.by_code(header.command_code) {
            Some(_) if whole => {
                let m = cat.decode(py, header.command_code.0, &body)?;
                Some(Py::new(py, Message::new(cat.clone(), m))?)
            }
            _ => None,
        };
        Ok(Packet {
            packet: jaus::Packet { header, body },
            message,
        })
    }

    /// The packet.
    pub(crate) fn packet(&self) -> &jaus::Packet {
        &self.packet
    }

    fn header(&self) -> &Header {
        &self.packet.header
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
        PyBytes::new(py, &self.packet.body)
    }
    /// The message the body holds, or None.
    #[getter]
    fn message(&self, py: Python<'_>) -> Option<Py<Message>> {
        self.message.as_ref().map(|m| m.clone_ref(py))
    }
    /// The message's name, `"Raw"` when the schema does not define the code.
    #[getter]
    fn name(&self) -> &'static str {
        self.message.as_ref().map_or("Raw", |m| m.get().msg.name)
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
        match &self.message {
            Some(m) => {
                let m = m.get();
                d.set_item("message", PyString::new(py, m.msg.name))?;
                d.set_item("fields", object_to_dict(py, &m.msg.fields)?)?;
            }
            None => {
                let raw = jaus::RawMessage {
                    code: self.header().command_code,
                    body: self.packet.body.clone(),
                };
                let json =
                    serde_json::to_value(&raw).map_err(|e| PyTypeError::new_err(e.to_string()))?;
                d.set_item("message", "Raw")?;
                d.set_item("fields", json_to_py(py, &json)?)?;
            }
        }
        Ok(d)
    }

    /// The line `jaus decode` prints, text for text.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&Line(self)).map_err(|e| PyTypeError::new_err(e.to_string()))
    }

    /// The packet's bytes (the header's data size recomputed from the body).
    fn encode<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let p = jaus::Packet::new(self.packet.header, self.packet.body.clone());
        let bytes = jaus::codec::Encode::to_bytes(&p)
            .map_err(|e| crate::errors::encode_error(py, Some(self.name()), &e))?;
        Ok(PyBytes::new(py, &bytes))
    }

    fn __repr__(&self) -> String {
        let a = |a: Address| format!("{a}");
        format!(
            "<jaus.Packet {} ({}) {} -> {}, {} byte(s)>",
            self.name(),
            self.header().command_code,
            a(self.header().source),
            a(self.header().destination),
            self.packet.body.len()
        )
    }
}

/// `{"header": ..., "message": ..., "fields": ...}`, as `jaus decode` prints it.
struct Line<'a>(&'a Packet);

impl Serialize for Line<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let p = self.0;
        let mut map = s.serialize_map(Some(3))?;
        map.serialize_entry("header", p.header())?;
        match &p.message {
            Some(m) => {
                let m = m.get();
                map.serialize_entry("message", m.msg.name)?;
                map.serialize_entry("fields", &m.msg.fields)?;
            }
            None => {
                map.serialize_entry("message", "Raw")?;
                map.serialize_entry(
                    "fields",
                    &jaus::RawMessage {
                        code: p.header().command_code,
                        body: p.packet.body.clone(),
                    },
                )?;
            }
        }
        map.end()
    }
}

/// An address given from Python: `(subsystem, node, component, instance)` or
/// `"s.n.c.i"`.
pub(crate) fn address(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Address> {
    if let Ok(s) = obj.extract::<String>() {
        return s
            .parse::<Address>()
            .map_err(|e| PyValueError::new_err(format!("{what}: {}", e.0)));
    }
    match obj.extract::<(u8, u8, u8, u8)>() {
        Ok((subsystem, node, component, instance)) => Ok(Address {
            subsystem,
            node,
            component,
            instance,
        }),
        Err(_) => Err(PyTypeError::new_err(format!(
            "{what}: an address is (subsystem, node, component, instance), each 0-255, or \"s.n.c.i\""
        ))),
    }
}
