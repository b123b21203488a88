//! The package's exceptions: `jaus.JausError` (a `ValueError`) and its kinds, each
//! with attributes naming where the failure is (message, field, byte offset).

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

pyo3::create_exception!(
    jaus,
    JausError,
    PyValueError,
    "Every error of the jaus package (a ValueError)."
);
pyo3::create_exception!(
    jaus,
    DecodeError,
    JausError,
    "Bytes that are not a message: `.message`, `.field`, `.path` and `.offset` say where."
);
pyo3::create_exception!(
    jaus,
    EncodeError,
    JausError,
    "A message that cannot be encoded, or fields that do not fit a message: `.message` and `.field` say which."
);
pyo3::create_exception!(
    jaus,
    SpecError,
    JausError,
    "Definition files (vendor overlays) that do not load: the message names the file and line."
);

pyo3::create_exception!(
    jaus,
    ClientError,
    JausError,
    "What `jaus.Client` could not do: no answer, a NAK, a refused watch, a closed client. `.message` names the message, `.address` the component."
);
pyo3::create_exception!(
    jaus,
    ControlRefused,
    ClientError,
    "A control request refused: `.response_code` is `InsufficientAuthority` or `NotAvailable` (Confirm Component Control), or `Rejected` (Reject Component Control)."
);

/// A `jaus.ClientError` (or `jaus.ControlRefused` with a response code) about
/// `message` sent to `address`.
pub(crate) fn client_error(
    py: Python<'_>,
    text: String,
    message: Option<&str>,
    address: Option<String>,
    response_code: Option<String>,
) -> PyErr {
    let err = match &response_code {
        Some(_) => ControlRefused::new_err(text),
        None => ClientError::new_err(text),
    };
    let err = with_attrs(py, err, message, None, None, None);
    let value = err.value(py);
    let _ = value.setattr("address", address);
    let _ = value.setattr("response_code", response_code);
    err
}

/// A `jaus.DecodeError` from the codec's error, with its context as attributes.
pub(crate) fn decode_error(py: Python<'_>, e: &jaus::codec::DecodeError) -> PyErr {
    let offset = if matches!(
        e.kind(),
        jaus::codec::DecodeErrorKind::UnknownCommandCode { .. }
    ) {
        None
    } else {
        Some(e.offset())
    };
    with_attrs(
        py,
        DecodeError::new_err(e.to_string()),
        e.message(),
        e.field(),
        Some(e.path().to_vec()),
        offset,
    )
}

/// A `jaus.DecodeError` with a message of its own (a packet that is not one).
pub(crate) fn decode_error_text(py: Python<'_>, text: String, offset: Option<usize>) -> PyErr {
    with_attrs(py, DecodeError::new_err(text), None, None, None, offset)
}

/// A `jaus.EncodeError` of message `message` (when known).
pub(crate) fn encode_error(
    py: Python<'_>,
    message: Option<&str>,
    e: &jaus::codec::EncodeError,
) -> PyErr {
    let text = match message {
        Some(m) => format!("{m}: {e}"),
        None => e.to_string(),
    };
    with_attrs(
        py,
        EncodeError::new_err(text),
        message,
        encode_field(e),
        None,
        None,
    )
}

/// A `jaus.EncodeError` with a message of its own: fields that do not fit the message
/// (`field` is the path of the offending field, `ReportTanks.tanks[1].level`).
pub(crate) fn fields_error(
    py: Python<'_>,
    text: String,
    message: Option<&str>,
    field: Option<&str>,
) -> PyErr {
    with_attrs(py, EncodeError::new_err(text), message, field, None, None)
}

fn with_attrs(
    py: Python<'_>,
    err: PyErr,
    message: Option<&str>,
    field: Option<&str>,
    path: Option<Vec<&str>>,
    offset: Option<usize>,
) -> PyErr {
    let value = err.value(py);
    // Setting attributes on a fresh exception instance does not fail; if it did, the
    // error would still carry its text.
    let _ = value.setattr("message", message);
    let _ = value.setattr("field", field);
    let _ = value.setattr("path", path.unwrap_or_default());
    let _ = value.setattr("offset", offset);
    err
}

/// The field an encode error names, if any.
fn encode_field(e: &jaus::codec::EncodeError) -> Option<&'static str> {
    use jaus::codec::EncodeError as E;
    match e {
        E::CountOverflow { field, .. }
        | E::TooLong { field, .. }
        | E::MissingVariable { field, .. }
        | E::CountMismatch { field, .. }
        | E::PresenceMismatch { field, .. }
        | E::TagMismatch { field, .. }
        | E::NulInText { field }
        | E::BitsOverflow { field, .. }
        | E::NotLatin1 { field, .. }
        | E::ValueKind { field } => Some(field),
        E::OutOfRange { scaled, .. } => Some(scaled.field),
        _ => None,
    }
}
