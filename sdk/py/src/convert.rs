//! Values between Rust and Python.
//!
//! Out: a decoded [`Value`] becomes the Python form of its JSON (the CLI's JSON lines,
//! field for field, in wire order): numbers, strings, lists, and dicts for records,
//! bit fields, unions with a value and unknown enumeration values. For attribute
//! access those objects are [`Record`]s instead of dicts.
//!
//! In: Python values become that JSON (`serde_json::Value`), which `jaus-dynamic`
//! checks against the message's layout: one reading of the JSON form for the CLI and
//! for Python.

use crate::message::Record;
use crate::packet::Packet;
use jaus_dynamic::Value;
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{
    PyBool, PyByteArray, PyBytes, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple,
};
use serde_json::{Map, Number, Value as Json};

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
        _ => {
            match entries(v).and_then(|e| e.into_iter().find(|(k, _)| *k == key).map(|(_, v)| v)) {
                Some(x) => value_to_py(py, x, form).map(Some),
                None => Ok(None),
            }
        }
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
        return serde_json::to_value(p.get().packet())
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
