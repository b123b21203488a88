//! The body of a `jaus.Packet`, and of the `jaus.Message` decoded from it: the bytes
//! both keep, shared. Below `message` and `packet`.

use pyo3::prelude::*;
use pyo3::types::PyBytes;
use std::sync::Arc;

/// A packet's body (and a message's, decoded from one).
#[derive(Debug)]
pub(crate) enum Body {
    /// Bytes of its own (shared by the packet and its message).
    Owned(Arc<[u8]>),
    /// The whole packet's bytes as given (`bytes` are immutable): the body is from byte
    /// 16 on.
    Shared(Py<PyBytes>),
}

impl Body {
    pub(crate) fn bytes<'a>(&'a self, py: Python<'_>) -> &'a [u8] {
        match self {
            Body::Owned(b) => b,
            Body::Shared(p) => p.as_bytes(py).get(jaus::wire::HEADER_LEN..).unwrap_or(&[]),
        }
    }

    pub(crate) fn clone_ref(&self, py: Python<'_>) -> Body {
        match self {
            Body::Owned(b) => Body::Owned(b.clone()),
            Body::Shared(p) => Body::Shared(p.clone_ref(py)),
        }
    }
}
