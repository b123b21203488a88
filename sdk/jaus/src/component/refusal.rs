//! Why a component refused a message, and the SDK's Report Refusal that tells the sender.

use std::time::Duration;

use super::CoreState;
use crate::messages::{RefusalReason, ReportRefusal};
use crate::{Address, CommandCode};

/// How long after a higher authority took control the former controller's commands are
/// taken to have crossed the Reject Component Control (refused all the same, logged at
/// debug instead of warn).
pub(super) const DISPLACED_GRACE: Duration = Duration::from_secs(1);

/// Why a message was not acted on.
#[derive(Debug)]
pub(super) enum Refusal {
    NotController,
    State(CoreState),
    Vendor(Refused),
    /// Clear Emergency from a sender that set none, while these senders' emergencies
    /// stand.
    ForeignClear(Vec<Address>),
}

impl Refusal {
    pub(super) fn reason(&self) -> RefusalReason {
        match self {
            Refusal::NotController => RefusalReason::NotController,
            Refusal::State(_) => RefusalReason::WrongState,
            Refusal::Vendor(Refused::Unsupported) => RefusalReason::Unsupported,
            Refusal::Vendor(Refused::Invalid(_)) => RefusalReason::Invalid,
            Refusal::Vendor(Refused::OutOfRange { .. }) => RefusalReason::OutOfRange,
            Refusal::ForeignClear(_) => RefusalReason::ForeignClearEmergency,
        }
    }
}

impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Refusal::NotController => f.write_str("sender is not the component in control"),
            Refusal::State(s) => write!(f, "not allowed in {s}"),
            Refusal::Vendor(r) => write!(f, "{r}"),
            Refusal::ForeignClear(by) => {
                f.write_str("this sender set no emergency; only the sender that set an emergency may clear it (set by ")?;
                for (i, a) in by.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "{a}")?;
                }
                f.write_str(")")
            }
        }
    }
}

/// The SDK's experimental Report Refusal (0xDF01) for a refused message with code
/// `refused`: sent, before the NAK, to a sender that asked for an acknowledgement, by the
/// component runtime and by a node's access policy. `text` is cut to the 255 Latin-1
/// characters the field carries.
pub fn refusal_report(refused: CommandCode, reason: RefusalReason, text: &str) -> ReportRefusal {
    ReportRefusal {
        refused_code: refused.0,
        reason,
        text: crate::codec::fit_latin1(text, 255),
    }
}

/// Why a component did not act on a message.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Refused {
    /// The vendor did not implement this message.
    #[error("not supported by this component")]
    Unsupported,
    /// The message is understood but its content cannot be executed (NaN, an unknown
    /// waypoint, a mission that is running, ...).
    #[error("{0}")]
    Invalid(String),
    /// A field's value is outside what this component accepts (its own limit, which
    /// may be narrower than the field's range on the wire).
    #[error(
        "field `{field}` = {value} {unit} is outside this component's limit [{min}, {max}] {unit}"
    )]
    OutOfRange {
        /// The field, as named in the message definition.
        field: &'static str,
        /// The value received.
        value: f64,
        /// Lowest accepted value.
        min: f64,
        /// Highest accepted value.
        max: f64,
        /// Unit of the values.
        unit: &'static str,
    },
}

impl Refused {
    /// `value` if it lies in `[min, max]`, else the [`Refused::OutOfRange`] naming
    /// `field` (NaN is out of every range).
    pub fn check_range(
        field: &'static str,
        value: f64,
        min: f64,
        max: f64,
        unit: &'static str,
    ) -> Result<f64, Refused> {
        if value >= min && value <= max {
            Ok(value)
        } else {
            Err(Refused::OutOfRange {
                field,
                value,
                min,
                max,
                unit,
            })
        }
    }
}
