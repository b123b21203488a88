//! Values from Rust to Python, and `jaus.Record`.
//!
//! A decoded [`Value`] becomes the Python form of its JSON (the CLI's JSON lines,
//! field for field, in wire order): numbers, strings, lists, and dicts for records,
//! bit fields, unions with a value and unknown enumeration values. For attribute
//! access those objects are [`Record`]s instead of dicts. JSON itself (the AS-4
//! client's, the system tree, a packet's header) becomes dicts and lists
//! ([`json_to_py`]).
//!
//! The other way, Python values into the JSON form of a message's fields, is
//! `message_py::py_to_json`: a field may be given a `jaus.Packet`, whose module
//! is above this one. This module builds on no other of the crate but `errors`.

use jaus_dynamic::Value;
use pyo3::exceptions::{PyAttributeError, PyKeyError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyIterator, PyList, PyString};
use serde_json::Value as Json;

/// Records (and the other JSON objects) as dicts, or as [`Record`]s.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Form {
    /// `to_dict()`: plain dicts.
    Dict,
    /// Attribute access: `Record` objects.
    Objects,
}

/// The Python form of a decoded value.
pub(crate) fn value_to_py<'py>(
    py: Python<'py>,
    v: &Value,
    form: Form,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        Value::UInt(x) => x.into_pyobject(py)?.into_any(),
        Value::Int(x) => x.into_pyobject(py)?.into_any(),
        Value::F32(x) => float_to_py(py, f64::from(*x), jaus::codec::serde_float::Float::text(*x)),
        Value::F64(x) => float_to_py(py, *x, jaus::codec::serde_float::Float::text(*x)),
        // serde_json writes a non-finite number as null.
        Value::Real(x) if !x.is_finite() => py.None().into_bound(py),
        Value::Real(x) => PyFloat::new(py, *x).into_any(),
        Value::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Value::Text(s) => PyString::new(py, s).into_any(),
        Value::Bytes(b) => PyString::new(py, &jaus::hex::encode(b)).into_any(),
        Value::List(items) => {
            let list = PyList::empty(py);
            for i in items {
                list.append(value_to_py(py, i, form)?)?;
            }
            list.into_any()
        }
        Value::Enum(name, _) | Value::Union(name, None) => PyString::new(py, name).into_any(),
        Value::Record(_) | Value::Bits(..) | Value::Union(_, Some(_)) | Value::UnknownEnum(_) => {
            match form {
                Form::Dict => object_to_dict(py, v)?.into_any(),
                Form::Objects => Bound::new(py, Record::new(v.clone()))?.into_any(),
            }
        }
        Value::Packet(p) => {
            let json = serde_json::to_value(p).map_err(|e| PyTypeError::new_err(e.to_string()))?;
            json_to_py(py, &json)?
        }
    })
}

fn float_to_py(py: Python<'_>, v: f64, text: String) -> Bound<'_, PyAny> {
    if v.is_finite() {
        PyFloat::new(py, v).into_any()
    } else {
        PyString::new(py, &text).into_any()
    }
}

/// The entries of a value that is a JSON object, in JSON order (`None` for a value
/// that is not one).
pub(crate) fn entries(v: &Value) -> Option<Vec<(&str, &Value)>> {
    static ZERO: Value = Value::UInt(0);
    match v {
        Value::Record(f) => Some(f.iter().map(|(k, v)| (*k, v)).collect()),
        Value::Bits(members, reserved) => {
            let mut out: Vec<(&str, &Value)> = members.iter().map(|(k, v)| (*k, v)).collect();
            if *reserved != 0 {
                // The reserved bits are read through `entry`; the placeholder keeps
                // the key's position.
                out.push(("reserved", &ZERO));
            }
            Some(out)
        }
        Value::Union(name, Some(inner)) => Some(vec![(*name, inner.as_ref())]),
        Value::UnknownEnum(_) => Some(vec![("Unknown", &ZERO)]),
        _ => None,
    }
}

/// The entry `key` of a value that is a JSON object, as Python.
pub(crate) fn entry<'py>(
    py: Python<'py>,
    v: &Value,
    key: &str,
    form: Form,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    match (v, key) {
        (Value::Bits(_, reserved), "reserved") if *reserved != 0 => {
            Ok(Some(reserved.into_pyobject(py)?.into_any()))
        }
        (Value::UnknownEnum(n), "Unknown") => Ok(Some(n.into_pyobject(py)?.into_any())),
        // Looked up in place (no list of the entries made).
        (Value::Record(f), _) | (Value::Bits(f, _), _) => match f.iter().find(|(k, _)| *k == key) {
            Some((_, x)) => value_to_py(py, x, form).map(Some),
            None => Ok(None),
        },
        (Value::Union(name, Some(inner)), _) if *name == key => {
            value_to_py(py, inner, form).map(Some)
        }
        _ => Ok(None),
    }
}

/// A value that is a JSON object as a dict.
pub(crate) fn object_to_dict<'py>(py: Python<'py>, v: &Value) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (k, _) in entries(v).unwrap_or_default() {
        if let Some(x) = entry(py, v, k, Form::Dict)? {
            d.set_item(k, x)?;
        }
    }
    Ok(d)
}

/// JSON as Python (dicts for objects).
pub(crate) fn json_to_py<'py>(py: Python<'py>, j: &Json) -> PyResult<Bound<'py, PyAny>> {
    Ok(match j {
        Json::Null => py.None().into_bound(py),
        Json::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Json::Number(n) => {
            if let Some(u) = n.as_u64() {
                u.into_pyobject(py)?.into_any()
            } else if let Some(i) = n.as_i64() {
                i.into_pyobject(py)?.into_any()
            } else {
                PyFloat::new(py, n.as_f64().unwrap_or(f64::NAN)).into_any()
            }
        }
        Json::String(s) => PyString::new(py, s).into_any(),
        Json::Array(items) => {
            let list = PyList::empty(py);
            for i in items {
                list.append(json_to_py(py, i)?)?;
            }
            list.into_any()
        }
        Json::Object(o) => {
            let d = PyDict::new(py);
            for (k, v) in o {
                d.set_item(k, json_to_py(py, v)?)?;
            }
            d.into_any()
        }
    })
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

/// `object.__getattribute__`: the members of a message or record, when the name is not
/// one of its fields.
pub(crate) fn generic_getattr<'py>(
    slf: &Bound<'py, PyAny>,
    name: &Bound<'py, PyString>,
) -> PyResult<Bound<'py, PyAny>> {
    static GETATTRIBUTE: pyo3::sync::PyOnceLock<Py<PyAny>> = pyo3::sync::PyOnceLock::new();
    let py = slf.py();
    let f = GETATTRIBUTE.get_or_try_init(py, || {
        py.get_type::<pyo3::types::PyAny>()
            .getattr("__getattribute__")
            .map(Bound::unbind)
    })?;
    f.bind(py).call1((slf, name))
}

/// The members of `jaus.Record`: an attribute of one of these names is the member, not
/// an entry (an entry of that name is read as `r["keys"]`).
const RECORD_MEMBERS: &[&str] = &["keys", "to_dict", "to_json"];

/// Whether an attribute name may name an entry (a field of a message, an entry of a
/// record): not a dunder, not one of the object's `members`, which come first.
pub(crate) fn may_be_entry(name: &str, members: &[&str]) -> bool {
    !name.starts_with("__") && !members.contains(&name)
}

#[pymethods]
impl Record {
    /// An entry by attribute (`r.hour`): looked up before the generic attribute lookup,
    /// which would first fail (an AttributeError made and dropped) for every entry.
    /// The members and dunders come first, as they always did.
    fn __getattribute__<'py>(
        slf: &Bound<'py, Self>,
        name: &Bound<'py, PyString>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let n = name.to_cow()?;
        let n: &str = &n;
        if may_be_entry(n, RECORD_MEMBERS) {
            if let Some(v) = slf.get().get_entry(slf.py(), n)? {
                return Ok(v);
            }
        }
        generic_getattr(slf.as_any(), name)
    }

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
        out.extend(RECORD_MEMBERS.iter().map(|s| s.to_string()));
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
