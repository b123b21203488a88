//! `jaus.Message` (a decoded or built message: name, code, fields as attributes): the
//! type and what the crate reads of it; its Python methods and the messages built
//! from Python values are in `message_py`.
//!
//! A message decoded from a packet is made from the packet's checked body and decodes
//! it when first needed (a field read, `to_dict`, `==`, encoding), once; its fields
//! become Python objects as they are read. A packet holds its message (`packet` is
//! above this module). Below it: `body`, `catalog`, `convert`, `errors`.

use crate::body::Body;
use crate::catalog::Catalog;
use crate::convert::{value_to_py, Form};
use crate::errors::decode_error;
use jaus::codec::DecodeError;
use jaus::{Address, CommandCode};
use jaus_dynamic::{DynMessage, Value};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use std::sync::{Arc, OnceLock};

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
    name: &'static str,
    code: CommandCode,
    /// The body it is decoded from, checked (a message decoded from a packet).
    body: Option<Body>,
    /// The decoded message: given, or decoded from `body` when first needed.
    decoded: OnceLock<Result<DynMessage, DecodeError>>,
    /// The Python values of the fields read so far, by position in the decoded
    /// fields: a field is made a Python object when first read (immutable ones are
    /// kept).
    cache: OnceLock<Box<[OnceLock<Py<PyAny>>]>>,
}

impl Message {
    /// The message `msg`, decoded or built.
    pub(crate) fn new(cat: Arc<Catalog>, msg: DynMessage) -> Message {
        Message {
            cat,
            name: msg.name,
            code: msg.code,
            body: None,
            decoded: OnceLock::from(Ok(msg)),
            cache: OnceLock::new(),
        }
    }

    /// The message `name` (code `code`) of the body `body`, which
    /// `jaus_dynamic::Schema::check` has passed: decoded when first needed.
    pub(crate) fn checked(
        cat: Arc<Catalog>,
        name: &'static str,
        code: CommandCode,
        body: Body,
    ) -> Message {
        Message {
            cat,
            name,
            code,
            body: Some(body),
            decoded: OnceLock::new(),
            cache: OnceLock::new(),
        }
    }

    /// The message's name.
    pub(crate) fn name(&self) -> &'static str {
        self.name
    }

    /// Its command code.
    pub(crate) fn code(&self) -> CommandCode {
        self.code
    }

    /// The decoded message: decoded now from the checked body if it was not yet (a
    /// body that passed the check decodes: the check is the decode's own walk).
    pub(crate) fn msg(&self, py: Python<'_>) -> PyResult<&DynMessage> {
        let decoded = self.decoded.get_or_init(|| {
            let body = self.body.as_ref().map_or(&[][..], |b| b.bytes(py));
            self.cat.schema.decode(self.code, body)
        });
        decoded.as_ref().map_err(|e| decode_error(py, e))
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
    pub(crate) fn known_field<'py>(
        &self,
        py: Python<'py>,
        name: &str,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        if let Value::Record(f) = &self.msg(py)?.fields {
            if let Some(i) = f.iter().position(|(k, _)| *k == name) {
                return self.field_at(py, f, i).map(Some);
            }
        }
        if self.cat.field_names(self.name).iter().any(|f| f == name) {
            return Ok(Some(py.None().into_bound(py)));
        }
        Ok(None)
    }

    fn no_field(&self, name: &str) -> String {
        let names = self.cat.field_names(self.name);
        if names.is_empty() {
            format!("{} has no field `{name}`: it has no fields", self.name)
        } else {
            format!(
                "{} has no field `{name}`; its fields: {}",
                self.name,
                names.join(", ")
            )
        }
    }

    /// The field `name` as Python: its value, None for an optional field that is
    /// absent, or an error naming the fields there are.
    pub(crate) fn field<'py>(
        &self,
        py: Python<'py>,
        name: &str,
    ) -> Result<Bound<'py, PyAny>, String> {
        match self.known_field(py, name) {
            Ok(Some(v)) => Ok(v),
            Ok(None) => Err(self.no_field(name)),
            Err(e) => Err(e.to_string()),
        }
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
