//! `jaus.Confirmation`: what `Client.send(..., confirm=True)` returns.

use pyo3::prelude::*;

/// How a command sent with `Client.send(..., confirm=True)` took effect:
/// `.outcome` is `"acknowledged"` (the component sent an ACK) or
/// `"confirmed_by_readback"` (no ACK, but its read-back query or Query Component Status
/// shows the effect; `.detail` says what it showed, e.g. `"Report Travel Speed 2.44
/// m/s"`). A refused or unconfirmed command raises `jaus.ClientError` instead.
#[pyclass(module = "jaus", frozen)]
#[derive(Debug, Clone)]
pub struct Confirmation {
    outcome: &'static str,
    detail: String,
}

impl Confirmation {
    /// The Python value of a confirmed command's end.
    pub(crate) fn of(end: &jaus_client::confirm::Confirmation) -> Confirmation {
        Confirmation {
            outcome: end.outcome(),
            detail: end.detail().to_string(),
        }
    }
}

#[pymethods]
impl Confirmation {
    /// `"acknowledged"` or `"confirmed_by_readback"`.
    #[getter]
    fn outcome(&self) -> &'static str {
        self.outcome
    }

    /// What the read-back showed (empty for an acknowledgement).
    #[getter]
    fn detail(&self) -> String {
        self.detail.clone()
    }

    fn __str__(&self) -> String {
        match self.outcome {
            "acknowledged" => "acknowledged".into(),
            _ => format!("confirmed by read-back: {}", self.detail),
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "jaus.Confirmation(outcome={:?}, detail={:?})",
            self.outcome, self.detail
        )
    }
}
