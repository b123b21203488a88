//! `jaus.Schema`: the messages of a definition set (the SDK's, or the SDK's with a
//! vendor's overlays loaded at run time), with the codec, the docs and the capture
//! reader over them. The module's own functions use the SDK's schema.

use crate::body::Body;
use crate::catalog::{sdk, Catalog};
use crate::errors::{decode_error, encode_error, fields_error, DecodeError, JausError, SpecError};
use crate::message::{address, Message};
use crate::message_py::build;
use crate::packet::Packet;
use jaus::{CommandCode, Header};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};
use std::path::PathBuf;
use std::sync::Arc;

/// The messages of a definition set: the SDK's (`Schema.sdk()`), or the SDK's with a
/// vendor's overlay files on them (`Schema.load([...])`). Decodes and encodes every
/// message of the set; `jaus.decode` and the other module functions use the SDK's.
#[pyclass(module = "jaus", frozen)]
#[derive(Debug)]
pub struct Schema {
    pub(crate) cat: Arc<Catalog>,
}

#[pymethods]
impl Schema {
    /// The SDK's own messages.
    #[staticmethod]
    fn sdk() -> PyResult<Schema> {
        Ok(Schema { cat: sdk()? })
    }

    /// The SDK's messages with the vendor overlay files `overlays` (YAML) on them, as
    /// a vendor's build loads them. Raises `jaus.SpecError` naming the file and line.
    #[staticmethod]
    fn load(overlays: Vec<PathBuf>) -> PyResult<Schema> {
        if overlays.is_empty() {
            return Schema::sdk();
        }
        let spec =
            jaus_spec::load_overlays(&overlays).map_err(|e| SpecError::new_err(e.to_string()))?;
        Ok(Schema {
            cat: Arc::new(Catalog::from_spec(spec)),
        })
    }

    /// The names of every message, in definition order.
    fn messages(&self) -> Vec<&'static str> {
        self.cat.schema.messages().map(|m| m.name).collect()
    }

    /// The command code of message `name`.
    fn code(&self, name: &str) -> PyResult<u16> {
        self.cat
            .schema
            .message(name)
            .map(|m| m.code.0)
            .ok_or_else(|| unknown(self, name))
    }

    /// The name of the message with command code `code`, or None.
    fn name(&self, code: u16) -> Option<&'static str> {
        self.cat.schema.by_code(CommandCode(code)).map(|m| m.name)
    }

    /// The fields of message `name` in wire order (optional ones included).
    fn fields(&self, name: &str) -> PyResult<Vec<String>> {
        self.cat
            .schema
            .message(name)
            .map(|m| self.cat.field_names(m.name).to_vec())
            .ok_or_else(|| unknown(self, name))
    }

    /// What `jaus messages NAME` prints: the message's code, meaning, fields (type,
    /// unit, range, presence bit, description) and an example.
    fn doc(&self, name: &str) -> PyResult<String> {
        self.cat.doc(name)
    }

    /// Decodes the body of the message with command code `code`.
    fn decode(&self, py: Python<'_>, body: &[u8], code: u16) -> PyResult<Message> {
        let msg = self.cat.decode(py, code, body)?;
        Ok(Message::new(self.cat.clone(), msg))
    }

    /// Decodes a whole packet: the 16-byte header and the body.
    fn decode_packet(&self, py: Python<'_>, packet: &Bound<'_, PyBytes>) -> PyResult<Packet> {
        decode_packet(py, &self.cat, packet)
    }

    /// Decodes every packet of `packets` (an iterable of `bytes`, a capture's
    /// datagrams): a list of `jaus.Packet`, in order. With `strict=True` the first that
    /// does not decode raises its `jaus.DecodeError` (`.index` its position); with
    /// `strict=False` that error takes the packet's place in the list.
    #[pyo3(signature = (packets, *, strict = true))]
    fn decode_many<'py>(
        &self,
        py: Python<'py>,
        packets: &Bound<'py, PyAny>,
        strict: bool,
    ) -> PyResult<Bound<'py, PyList>> {
        decode_many(py, &self.cat, packets, strict)
    }

    /// The body of `message`.
    fn encode<'py>(&self, py: Python<'py>, message: &Message) -> PyResult<Bound<'py, PyBytes>> {
        encode(py, &self.cat, message)
    }

    /// The packet of `message` from `source` to `destination` (addresses as
    /// `(subsystem, node, component, instance)` or `"s.n.c.i"`).
    #[pyo3(signature = (message, source, destination, *, priority = 6, ack_nak = "none", service_connection = false, experimental = false, sequence_number = 0))]
    #[allow(clippy::too_many_arguments)]
    fn encode_packet<'py>(
        &self,
        py: Python<'py>,
        message: &Message,
        source: &Bound<'py, PyAny>,
        destination: &Bound<'py, PyAny>,
        priority: u8,
        ack_nak: &str,
        service_connection: bool,
        experimental: bool,
        sequence_number: u16,
    ) -> PyResult<Bound<'py, PyBytes>> {
        let opts = HeaderOptions {
            priority,
            ack_nak,
            service_connection,
            experimental,
            sequence_number,
        };
        encode_packet(py, &self.cat, message, source, destination, &opts)
    }

    /// The message `name` with the fields given as keywords, in the JSON form.
    #[pyo3(signature = (name, /, **fields))]
    fn message(
        &self,
        py: Python<'_>,
        name: &str,
        fields: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Message> {
        let msg = build(py, &self.cat, name, fields)?;
        Ok(Message::new(self.cat.clone(), msg))
    }

    /// The message `name` with the fields of the dict `fields` (as `to_dict()` gives
    /// them).
    #[pyo3(name = "from_dict", signature = (name, fields = None))]
    fn dict_message(
        &self,
        py: Python<'_>,
        name: &str,
        fields: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Message> {
        self.message(py, name, fields)
    }

    /// Every JAUS message of a pcap or pcapng capture of JUDP traffic, as
    /// `(time, source, destination, packet)`: `time` in seconds since 1970, the
    /// sockets as `(ip, port)`. Multi-packet messages are reassembled. With
    /// `strict=False`, datagrams that are not JAUS messages of this schema are skipped
    /// instead of raising `jaus.DecodeError`.
    #[pyo3(signature = (path, *, strict = true))]
    fn read_pcap<'py>(
        &self,
        py: Python<'py>,
        path: PathBuf,
        strict: bool,
    ) -> PyResult<Vec<crate::pcap::Entry>> {
        crate::pcap::read(py, &self.cat, &path, strict)
    }

    fn __repr__(&self) -> String {
        format!(
            "<jaus.Schema of {} messages>",
            self.cat.schema.messages().count()
        )
    }
}

fn unknown(s: &Schema, name: &str) -> PyErr {
    let near = jaus::json::closest_of(name, s.cat.schema.messages().map(|m| m.name));
    if near.is_empty() {
        JausError::new_err(format!("no message named `{name}`"))
    } else {
        JausError::new_err(format!(
            "no message named `{name}`; did you mean {}?",
            near.join(", ")
        ))
    }
}

/// Decodes a whole packet (the packet's bytes are kept, not copied: `bytes` do not
/// change).
pub(crate) fn decode_packet(
    py: Python<'_>,
    cat: &Arc<Catalog>,
    bytes: &Bound<'_, PyBytes>,
) -> PyResult<Packet> {
    let header = jaus::PacketRef::parse(bytes.as_bytes())
        .map_err(|e| decode_error(py, &e))?
        .header;
    Packet::decode(py, cat, header, Body::Shared(bytes.clone().unbind()))
}

/// Decodes every packet of `packets` (an iterable of `bytes`). `strict`: the first
/// that does not decode raises its `jaus.DecodeError`, with `.index` its position;
/// otherwise that error (with `.index`) takes the packet's place in the list.
pub(crate) fn decode_many<'py>(
    py: Python<'py>,
    cat: &Arc<Catalog>,
    packets: &Bound<'py, PyAny>,
    strict: bool,
) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for (i, item) in packets.try_iter()?.enumerate() {
        let item = item?;
        let bytes = item.cast::<PyBytes>().map_err(|_| {
            PyTypeError::new_err(format!(
                "decode_many: packet {i} is a {}, not bytes",
                item.get_type()
                    .name()
                    .map(|n| n.to_string())
                    .unwrap_or_default()
            ))
        })?;
        match decode_packet(py, cat, bytes) {
            Ok(p) => out.append(Bound::new(py, p)?)?,
            Err(e) if e.is_instance_of::<DecodeError>(py) => {
                e.value(py).setattr("index", i)?;
                if strict {
                    return Err(e);
                }
                out.append(e.value(py))?;
            }
            Err(e) => return Err(e),
        }
    }
    Ok(out)
}

/// The body of `message` (by the schema it was made with).
pub(crate) fn encode<'py>(
    py: Python<'py>,
    _cat: &Arc<Catalog>,
    message: &Message,
) -> PyResult<Bound<'py, PyBytes>> {
    let body = message.cat.encode(py, message.msg(py)?)?;
    Ok(PyBytes::new(py, &body))
}

/// The header fields of `encode_packet` other than the addresses.
#[derive(Debug)]
pub(crate) struct HeaderOptions<'a> {
    pub(crate) priority: u8,
    pub(crate) ack_nak: &'a str,
    pub(crate) service_connection: bool,
    pub(crate) experimental: bool,
    pub(crate) sequence_number: u16,
}

/// The packet of `message`.
pub(crate) fn encode_packet<'py>(
    py: Python<'py>,
    _cat: &Arc<Catalog>,
    message: &Message,
    source: &Bound<'py, PyAny>,
    destination: &Bound<'py, PyAny>,
    o: &HeaderOptions<'_>,
) -> PyResult<Bound<'py, PyBytes>> {
    let body = message.cat.encode(py, message.msg(py)?)?;
    let mut h = Header::new(
        message.code(),
        address(destination, "destination")?,
        address(source, "source")?,
    );
    if o.priority > 15 {
        return Err(fields_error(
            py,
            format!("priority {} is not 0-15", o.priority),
            Some(message.name()),
            None,
        ));
    }
    h.priority = o.priority;
    h.ack_nak =
        serde_json::from_value(serde_json::Value::String(o.ack_nak.to_string())).map_err(|_| {
            fields_error(
                py,
                format!(
                    "ack_nak `{}` is not one of none, request, nak, ack",
                    o.ack_nak
                ),
                Some(message.name()),
                None,
            )
        })?;
    h.service_connection = o.service_connection;
    h.experimental = o.experimental;
    h.sequence_number = o.sequence_number;
    let bytes = jaus::codec::Encode::to_bytes(&jaus::Packet::new(h, body))
        .map_err(|e| encode_error(py, Some(message.name()), &e))?;
    Ok(PyBytes::new(py, &bytes))
}
