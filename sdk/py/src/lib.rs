//! # jaus-py — `import jaus`
//!
//! The SDK's codec from Python, built by maturin into the extension module
//! `jaus._jaus` of the Python package `jaus` (`python/jaus`): every message of the
//! SDK's definitions, and of a vendor's overlays loaded at run time, decoded and
//! encoded through `jaus-dynamic` (one codec, byte-exact with the generated types and
//! OpenJAUS); fields in the names, units and forms of the CLI's JSON lines; pcap and
//! pcapng captures read into messages; errors as Python exceptions naming the
//! message, field and byte offset; and `jaus.Client`, a member of a live system as
//! the `jaus` CLI joins it (discovery, heartbeats, control kept, queries, watches),
//! its I/O on a Rust thread of its own.
//!
//! The module's functions ([`decode`], [`encode`], ...) use the SDK's definitions;
//! `jaus.Schema.load([...])` gives the same methods over a vendor's overlays. The
//! Python API is documented in docs/python.md; the tests are the pytest suite in
//! `tests/`.

mod as4;
mod body;
mod catalog;
mod client;
mod convert;
mod errors;
mod message;
mod message_py;
mod packet;
mod pcap;
mod schema;
pub mod stubs;

pub use client::{Client, Control, Watch};
pub use convert::Record;
pub use errors::{ClientError, ControlRefused, DecodeError, EncodeError, JausError, SpecError};
pub use message::Message;
pub use packet::Packet;
pub use schema::Schema;

use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyList};
use std::path::PathBuf;

/// Decodes the body of the message with command code `code` (SDK messages).
#[pyfunction]
fn decode(py: Python<'_>, body: &[u8], code: u16) -> PyResult<Message> {
    let cat = catalog::sdk()?;
    let m = cat.decode(py, code, body)?;
    Ok(Message::new(cat, m))
}

/// Decodes a whole packet: the 16-byte RA 3.3 header and the body. The body is
/// checked now (a packet that is not a message raises now); the message's values and
/// Python objects are made as they are read.
#[pyfunction]
fn decode_packet(py: Python<'_>, packet: &Bound<'_, PyBytes>) -> PyResult<Packet> {
    schema::decode_packet(py, catalog::sdk_ref()?, packet)
}

/// Decodes every packet of `packets` (an iterable of `bytes`): a list of
/// `jaus.Packet`, in order. `strict=True`: the first that does not decode raises its
/// `jaus.DecodeError` (`.index` its position); `strict=False`: that error takes the
/// packet's place in the list.
#[pyfunction]
#[pyo3(signature = (packets, *, strict = true))]
fn decode_many<'py>(
    py: Python<'py>,
    packets: &Bound<'py, PyAny>,
    strict: bool,
) -> PyResult<Bound<'py, PyList>> {
    schema::decode_many(py, catalog::sdk_ref()?, packets, strict)
}

/// The body of `message` (by the schema it was made with).
#[pyfunction]
fn encode<'py>(py: Python<'py>, message: &Message) -> PyResult<Bound<'py, PyBytes>> {
    schema::encode(py, &catalog::sdk()?, message)
}

/// The packet of `message` from `source` to `destination`.
#[pyfunction]
#[pyo3(signature = (message, source, destination, *, priority = 6, ack_nak = "none", service_connection = false, experimental = false, sequence_number = 0))]
#[allow(clippy::too_many_arguments)]
fn encode_packet<'py>(
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
    let opts = schema::HeaderOptions {
        priority,
        ack_nak,
        service_connection,
        experimental,
        sequence_number,
    };
    schema::encode_packet(py, &catalog::sdk()?, message, source, destination, &opts)
}

/// The SDK's message `name` with the fields given as keywords.
#[pyfunction]
#[pyo3(name = "message", signature = (name, /, **fields))]
fn make_message(
    py: Python<'_>,
    name: &str,
    fields: Option<&Bound<'_, PyDict>>,
) -> PyResult<Message> {
    let cat = catalog::sdk()?;
    let m = message_py::build(py, &cat, name, fields)?;
    Ok(Message::new(cat, m))
}

/// The names of the SDK's messages, in definition order.
#[pyfunction]
fn messages() -> PyResult<Vec<&'static str>> {
    Ok(catalog::sdk()?.schema.messages().map(|m| m.name).collect())
}

/// The description of the SDK's message `name` (`jaus messages NAME`).
#[pyfunction]
fn doc(name: &str) -> PyResult<String> {
    catalog::sdk()?.doc(name)
}

/// Every JAUS message of a pcap/pcapng capture (SDK messages).
#[pyfunction]
#[pyo3(signature = (path, *, strict = true))]
fn read_pcap(py: Python<'_>, path: PathBuf, strict: bool) -> PyResult<Vec<pcap::Entry>> {
    pcap::read(py, &catalog::sdk()?, &path, strict)
}

/// The text of the package's type stubs (`python/jaus/__init__.pyi`), generated from
/// the SDK's definitions ([`stubs::render`]).
#[pyfunction]
fn _stubs() -> PyResult<String> {
    let spec = jaus_spec::load_sdk().map_err(|e| SpecError::new_err(e.to_string()))?;
    Ok(stubs::render(&spec))
}

/// The extension module `jaus._jaus` (the package `jaus` re-exports it).
#[pymodule]
fn _jaus(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_function(wrap_pyfunction!(decode, m)?)?;
    m.add_function(wrap_pyfunction!(decode_packet, m)?)?;
    m.add_function(wrap_pyfunction!(decode_many, m)?)?;
    m.add_function(wrap_pyfunction!(encode, m)?)?;
    m.add_function(wrap_pyfunction!(encode_packet, m)?)?;
    m.add_function(wrap_pyfunction!(make_message, m)?)?;
    m.add_function(wrap_pyfunction!(messages, m)?)?;
    m.add_function(wrap_pyfunction!(doc, m)?)?;
    m.add_function(wrap_pyfunction!(read_pcap, m)?)?;
    m.add_function(wrap_pyfunction!(_stubs, m)?)?;
    m.add_class::<Message>()?;
    m.add_class::<Record>()?;
    m.add_class::<Packet>()?;
    m.add_class::<Schema>()?;
    m.add_class::<Client>()?;
    m.add_class::<Control>()?;
    m.add_class::<Watch>()?;
    m.add_class::<client::Confirmation>()?;
    m.add_class::<as4::As4Client>()?;
    m.add("JausError", py.get_type::<JausError>())?;
    m.add("DecodeError", py.get_type::<DecodeError>())?;
    m.add("EncodeError", py.get_type::<EncodeError>())?;
    m.add("SpecError", py.get_type::<SpecError>())?;
    m.add("ClientError", py.get_type::<ClientError>())?;
    m.add("ControlRefused", py.get_type::<ControlRefused>())?;
    Ok(())
}
