//! The Python methods of `jaus.Message`, and a message built from Python values
//! ([`build`]).
//!
//! A message's fields may be given a `jaus.Packet` (`Message.from_dict`,
//! [`py_to_json`]), and a packet holds its message: this module is above both
//! `message` and `packet`.

use crate::catalog::{sdk, Catalog};
use crate::convert::{generic_getattr, may_be_entry, object_to_dict, Record};
use crate::errors::fields_error;
use crate::message::{Message, MESSAGE_MEMBERS};
use crate::packet::Packet;
use jaus::json::JsonError;
use jaus_dynamic::{DynMessage, Value};
use pyo3::exceptions::{PyAttributeError, PyKeyError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{
    PyBool, PyByteArray, PyBytes, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple,
};
use serde_json::{Map, Number, Value as Json};

#[pymethods]
impl Message {
    /// The message's name (`"ReportGlobalPose"`).
    #[getter(name)]
    fn get_name(&self) -> &'static str {
        self.name()
    }

    /// Its command code.
    #[getter(code)]
    fn get_code(&self) -> u16 {
        self.code().0
    }

    /// The names of the fields present, in wire order.
    #[getter]
    fn fields(&self, py: Python<'_>) -> PyResult<Vec<&'static str>> {
        Ok(match &self.msg(py)?.fields {
            Value::Record(f) => f.iter().map(|(k, _)| *k).collect(),
            _ => Vec::new(),
        })
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
            "name" => return Ok(PyString::new(py, this.name()).into_any()),
            "code" => return Ok(this.code().0.into_pyobject(py)?.into_any()),
            "fields" => return Ok(PyList::new(py, this.fields(py)?)?.into_any()),
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
    fn __contains__(&self, py: Python<'_>, name: &str) -> PyResult<bool> {
        Ok(self.msg(py)?.fields.field(name).is_some())
    }

    fn __dir__(&self) -> Vec<String> {
        let mut out: Vec<String> = MESSAGE_MEMBERS.iter().map(|s| s.to_string()).collect();
        out.extend(self.cat.field_names(self.name()).iter().cloned());
        out
    }

    /// The fields as a dict: exactly the `"fields"` of the line `jaus decode` prints.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        object_to_dict(py, &self.msg(py)?.fields)
    }

    /// The fields as JSON text: exactly the `"fields"` of the line `jaus decode`
    /// prints.
    fn to_json(&self, py: Python<'_>) -> PyResult<String> {
        serde_json::to_string(&self.msg(py)?.fields)
            .map_err(|e| crate::errors::EncodeError::new_err(e.to_string()))
    }

    /// The message's body (as `jaus.encode(message)`).
    fn encode<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let body = self.cat.encode(py, self.msg(py)?)?;
        Ok(PyBytes::new(py, &body))
    }

    /// The message's description (`jaus messages NAME`).
    fn doc(&self) -> PyResult<String> {
        self.cat.doc(self.name())
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

    fn __eq__(&self, py: Python<'_>, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        match other.cast::<Message>() {
            Ok(o) => Ok(o.get().msg(py)? == self.msg(py)?),
            Err(_) => Ok(false),
        }
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        Ok(format!(
            "jaus.Message({:?}, {})",
            self.name(),
            serde_json::to_string(&self.msg(py)?.fields).unwrap_or_default()
        ))
    }
}

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
