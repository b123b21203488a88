//! The definitions the module reads messages with ([`Catalog`]): a compiled schema
//! for the codec and the definitions behind it, for field names and docs. The SDK's
//! own, compiled once ([`sdk`]). The codec's bytes in and out, lookups and docs;
//! no Python objects are made here (a message from Python values is
//! `message_py::build`). The modules above build on it; it builds on `errors` alone.

use crate::errors::{decode_error, encode_error, JausError, SpecError};
use jaus::CommandCode;
use jaus_dynamic::DynMessage;
use pyo3::prelude::*;
use std::collections::HashMap;
use std::sync::{Arc, OnceLock};

/// A definition set compiled for the codec, with what the docs and attribute access
/// read from its definitions.
#[derive(Debug)]
pub(crate) struct Catalog {
    pub(crate) schema: jaus_dynamic::Schema,
    spec: jaus_spec::Spec,
    /// Every field name of each message, in wire order.
    fields: HashMap<&'static str, Vec<String>>,
}

impl Catalog {
    pub(crate) fn from_spec(spec: jaus_spec::Spec) -> Catalog {
        let schema = jaus_dynamic::Schema::from_spec(&spec);
        let fields = schema
            .messages()
            .map(|m| {
                let names = spec
                    .messages
                    .iter()
                    .find(|d| d.def.name == m.name)
                    .map(|d| d.fields.iter().map(|f| f.def.name.clone()).collect())
                    .unwrap_or_default();
                (m.name, names)
            })
            .collect();
        Catalog {
            schema,
            spec,
            fields,
        }
    }

    /// The field names of message `name`, in wire order.
    pub(crate) fn field_names(&self, name: &str) -> &[String] {
        self.fields.get(name).map_or(&[], Vec::as_slice)
    }

    /// The description of message `name` (`jaus messages NAME`).
    pub(crate) fn doc(&self, name: &str) -> PyResult<String> {
        jaus_client::describe::describe(&self.spec, name).map_err(JausError::new_err)
    }

    /// Decodes a body of the message with command code `code`.
    pub(crate) fn decode(&self, py: Python<'_>, code: u16, body: &[u8]) -> PyResult<DynMessage> {
        self.schema
            .decode(CommandCode(code), body)
            .map_err(|e| decode_error(py, &e))
    }

    /// Encodes a message's body.
    pub(crate) fn encode(&self, py: Python<'_>, m: &DynMessage) -> PyResult<Vec<u8>> {
        self.schema
            .encode(m)
            .map_err(|e| encode_error(py, Some(m.name), &e))
    }
}

static SDK: OnceLock<Arc<Catalog>> = OnceLock::new();

/// The SDK's own definitions, compiled once.
pub(crate) fn sdk() -> PyResult<Arc<Catalog>> {
    sdk_ref().cloned()
}

/// The SDK's own definitions, compiled once, by reference (no count taken: the
/// decoding functions' fast path).
pub(crate) fn sdk_ref() -> PyResult<&'static Arc<Catalog>> {
    if let Some(c) = SDK.get() {
        return Ok(c);
    }
    let spec = jaus_spec::load_sdk().map_err(|e| SpecError::new_err(e.to_string()))?;
    Ok(SDK.get_or_init(|| Arc::new(Catalog::from_spec(spec))))
}
