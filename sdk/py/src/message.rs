//! `jaus.Message` (a decoded or built message: name, code, fields as attributes) and
//! `jaus.Record` (a nested record, bit field or union of one, read the same way).

use crate::catalog::{sdk, Catalog};
use crate::convert::{entries, entry, object_to_dict, value_to_py, Form};
use jaus_dynamic::{DynMessage, Value};
use pyo3::exceptions::{PyAttributeError, PyKeyError};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyIterator, PyList};
use std::sync::Arc;

/// A JAUS message: `.name`, `.code`, and its fields as attributes (`m.speed`), in
/// the units and forms of the CLI's JSON lines. An optional field that is absent
/// reads as None.
#[pyclass(module = "jaus", frozen)]
#[derive(Debug)]
pub struct Message {
    pub(crate) cat: Arc<Catalog>,
    pub(crate) msg: DynMessage,
}

impl Message {
    pub(crate) fn new(cat: Arc<Catalog>, msg: DynMessage) -> Message {
        Message { cat, msg }
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
        if let Some(v) = self.msg.fields.field(name) {
            return value_to_py(py, v, Form::Objects).map_err(|e| e.to_string());
        }
        if self
            .cat
            .field_names(self.msg.name)
            .iter()
            .any(|f| f == name)
        {
            return Ok(py.None().into_bound(py));
        }
        Err(self.no_field(name))
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
        let mut out: Vec<String> = [
            "name",
            "code",
            "fields",
            "to_dict",
            "to_json",
            "encode",
            "doc",
            "from_dict",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
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
        let msg = cat.build(py, name, fields)?;
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

/// A record inside a message (or a bit field, a union with a value, an unknown
/// enumeration value): its entries as attributes and items, `to_dict()` for the
/// JSON form.
#[pyclass(module = "jaus", frozen)]
#[derive(Debug)]
pub struct Record {
    pub(crate) value: Value,
}

impl Record {
    pub(crate) fn new(value: Value) -> Record {
        Record { value }
    }

    fn keys_of(&self) -> Vec<&str> {
        entries(&self.value)
            .unwrap_or_default()
            .into_iter()
            .map(|(k, _)| k)
            .collect()
    }

    fn get_entry<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        entry(py, &self.value, key, Form::Objects)
    }

    fn missing(&self, key: &str) -> String {
        format!("no entry `{key}`; present: {}", self.keys_of().join(", "))
    }
}

#[pymethods]
impl Record {
    fn __getattr__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        self.get_entry(py, name)?
            .ok_or_else(|| PyAttributeError::new_err(self.missing(name)))
    }

    fn __getitem__<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        self.get_entry(py, key)?
            .ok_or_else(|| PyKeyError::new_err(self.missing(key)))
    }

    fn __contains__(&self, key: &str) -> bool {
        self.keys_of().contains(&key)
    }

    fn __len__(&self) -> usize {
        self.keys_of().len()
    }

    fn __iter__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyIterator>> {
        PyList::new(py, self.keys_of())?.try_iter()
    }

    /// The entry names, in JSON order.
    fn keys(&self) -> Vec<String> {
        self.keys_of().into_iter().map(str::to_string).collect()
    }

    fn __dir__(&self) -> Vec<String> {
        let mut out = self.keys();
        out.extend(["keys", "to_dict", "to_json"].iter().map(|s| s.to_string()));
        out
    }

    /// The JSON form as a dict.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        object_to_dict(py, &self.value)
    }

    /// The JSON form as text.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.value)
            .map_err(|e| crate::errors::EncodeError::new_err(e.to_string()))
    }

    /// Equal to a Record of the same value, or to a dict of its JSON form.
    fn __eq__(&self, py: Python<'_>, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        if let Ok(o) = other.cast::<Record>() {
            return Ok(o.get().value == self.value);
        }
        if other.is_instance_of::<PyDict>() {
            return self.to_dict(py)?.as_any().eq(other);
        }
        Ok(false)
    }

    fn __repr__(&self) -> String {
        format!(
            "jaus.Record({})",
            serde_json::to_string(&self.value).unwrap_or_default()
        )
    }
}
