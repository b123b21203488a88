//! `jaus.Message` (a decoded or built message: name, code, fields as attributes) and
//! `jaus.Packet` (a whole JAUS packet, its RA 3.3 header fields as attributes, its
//! body and the message it holds), and a message built from Python values
//! ([`build`]).
//!
//! The two types share a module because they hold each other: a packet holds its
//! message, and a message's fields may be given a packet (`Message.from_dict`,
//! [`py_to_json`]). Below this module: `catalog`, `convert`, `errors`.

use crate::catalog::{sdk, Catalog};
use crate::convert::{
    generic_getattr, json_to_py, may_be_entry, object_to_dict, value_to_py, Form, Record,
};
use crate::errors::{decode_error, fields_error};
use jaus::json::JsonError;
use jaus::{Address, Header};
use jaus_dynamic::{DynMessage, Value};
use pyo3::exceptions::{PyAttributeError, PyKeyError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{
    PyBool, PyByteArray, PyBytes, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple,
};
use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;
use serde_json::{Map, Number, Value as Json};
use std::sync::{Arc, Mutex, OnceLock};

/// The members of `jaus.Message` (methods and properties): an attribute of one of these
/// names is the member, not a field (a field of that name is read as `m["name"]`).
pub(crate) const MESSAGE_MEMBERS: &[&str] = &[
    "name",
    "code",
    "fields",
    "to_dict",
    "to_json",
    "encode",
    "doc",
    "from_dict",
];

/// Whether the Python form of `v` is immutable (a number, text, a `jaus.Record`), so
/// that a message may hand out the same object on every read. Lists and embedded
/// packets (dicts) are made anew on each read, as before.
fn immutable(v: &Value) -> bool {
    !matches!(v, Value::List(_) | Value::Packet(_))
}

/// A JAUS message: `.name`, `.code`, and its fields as attributes (`m.speed`), in
/// the units and forms of the CLI's JSON lines. An optional field that is absent
/// reads as None.
#[pyclass(module = "jaus", frozen)]
#[derive(Debug)]
pub struct Message {
    pub(crate) cat: Arc<Catalog>,
    pub(crate) msg: DynMessage,
    /// The Python values of the fields read so far, by position in `msg.fields`: a
    /// field is made a Python object when first read (immutable ones are kept).
    cache: OnceLock<Box<[OnceLock<Py<PyAny>>]>>,
}

impl Message {
    pub(crate) fn new(cat: Arc<Catalog>, msg: DynMessage) -> Message {
        Message {
            cat,
            msg,
            cache: OnceLock::new(),
        }
    }

    /// The Python value of the field at position `i` of the record `fields` (this
    /// message's), from the cache or made now.
    fn field_at<'py>(
        &self,
        py: Python<'py>,
        fields: &[(&'static str, Value)],
        i: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let cache = self
            .cache
            .get_or_init(|| fields.iter().map(|_| OnceLock::new()).collect());
        let slot = &cache[i];
        if let Some(o) = slot.get() {
            return Ok(o.bind(py).clone());
        }
        let v = &fields[i].1;
        let o = value_to_py(py, v, Form::Objects)?;
        if !immutable(v) {
            return Ok(o);
        }
        // The first value kept is the one every read gives.
        let _ = slot.set(o.unbind());
        Ok(slot
            .get()
            .map_or_else(|| py.None().into_bound(py), |o| o.bind(py).clone()))
    }

    /// The field `name` when it is one: its value, or None for an optional field that
    /// is absent.
    fn known_field<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        if let Value::Record(f) = &self.msg.fields {
            if let Some(i) = f.iter().position(|(k, _)| *k == name) {
                return self.field_at(py, f, i).map(Some);
            }
        }
        if self
            .cat
            .field_names(self.msg.name)
            .iter()
            .any(|f| f == name)
        {
            return Ok(Some(py.None().into_bound(py)));
        }
        Ok(None)
    }

    fn no_field(&self, name: &str) -> String {
        let names = self.cat.field_names(self.msg.name);
        if names.is_empty() {
            format!("{} has no field `{name}`: it has no fields", self.msg.name)
        } else {
            format!(
                "{} has no field `{name}`; its fields: {}",
                self.msg.name,
                names.join(", ")
            )
        }
    }

    /// The field `name` as Python: its value, None for an optional field that is
    /// absent, or an error naming the fields there are.
    fn field<'py>(&self, py: Python<'py>, name: &str) -> Result<Bound<'py, PyAny>, String> {
        match self.known_field(py, name) {
            Ok(Some(v)) => Ok(v),
            Ok(None) => Err(self.no_field(name)),
            Err(e) => Err(e.to_string()),
        }
    }
}

#[pymethods]
impl Message {
    /// The message's name (`"ReportGlobalPose"`).
    #[getter]
    fn name(&self) -> &'static str {
        self.msg.name
    }

    /// Its command code.
    #[getter]
    fn code(&self) -> u16 {
        self.msg.code.0
    }

    /// The names of the fields present, in wire order.
    #[getter]
    fn fields(&self) -> Vec<&'static str> {
        match &self.msg.fields {
            Value::Record(f) => f.iter().map(|(k, _)| *k).collect(),
            _ => Vec::new(),
        }
    }

    /// A field by attribute (`m.speed`): looked up before the generic attribute lookup,
    /// which would first fail (an AttributeError made and dropped) for every field.
    /// The members (`name`, `to_dict`, ...) and dunders come first, as they always did.
    fn __getattribute__<'py>(
        slf: &Bound<'py, Self>,
        name: &Bound<'py, PyString>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let n = name.to_cow()?;
        let n: &str = &n;
        let py = slf.py();
        let this = slf.get();
        match n {
            // The properties without the generic lookup's call.
            "name" => return Ok(PyString::new(py, this.msg.name).into_any()),
            "code" => return Ok(this.msg.code.0.into_pyobject(py)?.into_any()),
            "fields" => return Ok(PyList::new(py, this.fields())?.into_any()),
            _ => {}
        }
        if may_be_entry(n, MESSAGE_MEMBERS) {
            if let Some(v) = this.known_field(py, n)? {
                return Ok(v);
            }
        }
        generic_getattr(slf.as_any(), name)
    }

    fn __getattr__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        self.field(py, name).map_err(PyAttributeError::new_err)
    }

    fn __getitem__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        self.field(py, name).map_err(PyKeyError::new_err)
    }

    /// Whether the field `name` is present.
    fn __contains__(&self, name: &str) -> bool {
        self.msg.fields.field(name).is_some()
    }

    fn __dir__(&self) -> Vec<String> {
        let mut out: Vec<String> = MESSAGE_MEMBERS.iter().map(|s| s.to_string()).collect();
        out.extend(self.cat.field_names(self.msg.name).iter().cloned());
        out
    }

    /// The fields as a dict: exactly the `"fields"` of the line `jaus decode` prints.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        object_to_dict(py, &self.msg.fields)
    }

    /// The fields as JSON text: exactly the `"fields"` of the line `jaus decode`
    /// prints.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.msg.fields)
            .map_err(|e| crate::errors::EncodeError::new_err(e.to_string()))
    }

    /// The message's body (as `jaus.encode(message)`).
    fn encode<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let body = self.cat.encode(py, &self.msg)?;
        Ok(PyBytes::new(py, &body))
    }

    /// The message's description (`jaus messages NAME`).
    fn doc(&self) -> PyResult<String> {
        self.cat.doc(self.msg.name)
    }

    /// The SDK's message `name` with the fields of the dict `fields` (the form
    /// `to_dict()` gives). A vendor's message: `Schema.load([...]).from_dict(...)`.
    #[staticmethod]
    #[pyo3(signature = (name, fields = None))]
    fn from_dict(
        py: Python<'_>,
        name: &str,
        fields: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Message> {
        let cat = sdk()?;
        let msg = build(py, &cat, name, fields)?;
        Ok(Message::new(cat, msg))
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        match other.cast::<Message>() {
            Ok(o) => {
                let o = o.get();
                o.msg == self.msg
            }
            Err(_) => false,
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "jaus.Message({:?}, {})",
            self.msg.name,
            serde_json::to_string(&self.msg.fields).unwrap_or_default()
        )
    }
}

/// A JAUS packet: the 16-byte header's fields as attributes (`priority`, `ack_nak`,
/// `source`, ...), the `body` bytes and the `message` they hold (None for a command
/// code the schema does not define, or a part of a multi-packet message).
///
/// The body is decoded, and so checked, when the packet is: a packet that is not a
/// message raises then. What is kept is the decoded message; its Python object, and
/// each of its fields', is made when first read.
#[pyclass(module = "jaus", frozen)]
#[derive(Debug)]
pub struct Packet {
    header: Header,
    body: Body,
    message: Option<Held>,
}

/// A packet's body.
#[derive(Debug)]
pub(crate) enum Body {
    /// Bytes of its own.
    Owned(Vec<u8>),
    /// The whole packet's bytes as given (`bytes` are immutable): the body is from byte
    /// 16 on.
    Shared(Py<PyBytes>),
}

impl Body {
    fn bytes<'a>(&'a self, py: Python<'_>) -> &'a [u8] {
        match self {
            Body::Owned(b) => b,
            Body::Shared(p) => p.as_bytes(py).get(jaus::wire::HEADER_LEN..).unwrap_or(&[]),
        }
    }
}

/// The message a packet holds: decoded, its `jaus.Message` made on first read.
struct Held {
    name: &'static str,
    cat: Arc<Catalog>,
    /// The decoded message until its `jaus.Message` is made (moved into it then).
    pending: Mutex<Option<DynMessage>>,
    object: pyo3::sync::PyOnceLock<Py<Message>>,
}

impl std::fmt::Debug for Held {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Held")
            .field("name", &self.name)
            .finish_non_exhaustive()
    }
}

impl Held {
    fn object<'a>(&'a self, py: Python<'_>) -> PyResult<&'a Py<Message>> {
        // The lock runs the maker once; a packet's message is made once.
        self.object.get_or_try_init(py, || {
            let msg = self
                .pending
                .lock()
                .map_err(|_| PyTypeError::new_err("a packet's message was lost"))?
                .take()
                .ok_or_else(|| PyTypeError::new_err("a packet's message was lost"))?;
            Py::new(py, Message::new(self.cat.clone(), msg))
        })
    }
}

impl Packet {
    /// The packet of `header` and `body`, its body decoded when it is a whole message
    /// of the schema.
    pub(crate) fn decode(
        py: Python<'_>,
        cat: &Arc<Catalog>,
        header: Header,
        body: Body,
    ) -> PyResult<Packet> {
        let whole = header.data_flag == jaus::wire::DataFlag::Single;
        let message = if whole {
            match cat.schema.decode(header.command_code, body.bytes(py)) {
                Ok(m) => Some(Held {
                    name: m.name,
                    cat: cat.clone(),
                    pending: Mutex::new(Some(m)),
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

    /// The message's object, when the packet holds one.
    fn message_object<'a>(&'a self, py: Python<'_>) -> PyResult<Option<&'a Py<Message>>> {
        self.message.as_ref().map(|h| h.object(py)).transpose()
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
                let m = m.get();
                d.set_item("message", PyString::new(py, m.msg.name))?;
                d.set_item("fields", object_to_dict(py, &m.msg.fields)?)?;
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
        let message = self.message_object(py)?.map(|m| m.get());
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
    message: Option<&'a Message>,
    /// The body as a raw message (a packet without a message).
    raw: Option<jaus::RawMessage>,
}

impl Serialize for Line<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(3))?;
        map.serialize_entry("header", self.packet.header())?;
        match self.message {
            Some(m) => {
                map.serialize_entry("message", m.msg.name)?;
                map.serialize_entry("fields", &m.msg.fields)?;
            }
            None => {
                map.serialize_entry("message", "Raw")?;
                map.serialize_entry("fields", &self.raw)?;
            }
        }
        map.end()
    }
}

// Built from Python values.

/// The message `name` of `cat` with `fields` (Python values of the JSON form).
pub(crate) fn build(
    py: Python<'_>,
    cat: &Catalog,
    name: &str,
    fields: Option<&Bound<'_, PyDict>>,
) -> PyResult<DynMessage> {
    let json = match fields {
        Some(f) => py_to_json(f.as_any(), name)?,
        None => serde_json::Value::Object(Default::default()),
    };
    cat.schema.from_json(name, &json).map_err(|e| match e {
        JsonError::Fields { message, error } => {
            // `error` is "Message.field.path: what was wrong".
            // A path into the body (`Message.field`), not the body itself.
            let field = error
                .split(": ")
                .next()
                .filter(|p| p.len() > message.len() && p.starts_with(message.as_str()))
                .map(str::to_string);
            fields_error(
                py,
                format!("{message}: {error}"),
                Some(&message),
                field.as_deref(),
            )
        }
        other => fields_error(py, other.to_string(), None, None),
    })
}

/// A Python value as the JSON form of a field. Accepted: None, bool, int, float
/// (non-finite as the JSON form's `"NaN"`, `"inf"`, `"-inf"`), str, bytes (as hex),
/// lists and tuples, dicts with str keys, `jaus.Record` and `jaus.Packet`.
pub(crate) fn py_to_json(obj: &Bound<'_, PyAny>, path: &str) -> PyResult<Json> {
    if obj.is_none() {
        return Ok(Json::Null);
    }
    if let Ok(b) = obj.cast::<PyBool>() {
        return Ok(Json::Bool(b.is_true()));
    }
    if obj.is_instance_of::<PyInt>() {
        if let Ok(u) = obj.extract::<u64>() {
            return Ok(Json::Number(u.into()));
        }
        if let Ok(i) = obj.extract::<i64>() {
            return Ok(Json::Number(i.into()));
        }
        return Err(PyTypeError::new_err(format!(
            "{path}: {} does not fit a 64-bit integer",
            obj.str()?
        )));
    }
    if let Ok(f) = obj.cast::<PyFloat>() {
        let v = f.value();
        return Ok(match Number::from_f64(v) {
            Some(n) => Json::Number(n),
            None => Json::String(jaus::codec::serde_float::Float::text(v)),
        });
    }
    if let Ok(s) = obj.cast::<PyString>() {
        return Ok(Json::String(s.extract::<String>()?));
    }
    if let Ok(b) = obj.cast::<PyBytes>() {
        return Ok(Json::String(jaus::hex::encode(b.as_bytes())));
    }
    if let Ok(b) = obj.cast::<PyByteArray>() {
        return Ok(Json::String(jaus::hex::encode(&b.to_vec())));
    }
    if let Ok(r) = obj.cast::<Record>() {
        return serde_json::to_value(&r.get().value)
            .map_err(|e| PyTypeError::new_err(e.to_string()));
    }
    if let Ok(p) = obj.cast::<Packet>() {
        return serde_json::to_value(p.get().packet(obj.py()))
            .map_err(|e| PyTypeError::new_err(e.to_string()));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut out = Map::new();
        for (k, v) in d.iter() {
            let key = k.cast::<PyString>().map_err(|_| {
                PyTypeError::new_err(format!(
                    "{path}: a key is not a str: {}",
                    k.repr().map(|r| r.to_string()).unwrap_or_default()
                ))
            })?;
            let key = key.extract::<String>()?;
            let value = py_to_json(&v, &format!("{path}.{key}"))?;
            out.insert(key, value);
        }
        return Ok(Json::Object(out));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut out = Vec::new();
        for (i, x) in obj.try_iter()?.enumerate() {
            out.push(py_to_json(&x?, &format!("{path}[{i}]"))?);
        }
        return Ok(Json::Array(out));
    }
    Err(PyTypeError::new_err(format!(
        "{path}: a value of type {} is not a field value (give numbers, str, bytes, lists, dicts or jaus.Record)",
        obj.get_type().name()?
    )))
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
