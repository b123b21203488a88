//! Liveness (`urn:jaus:jss:core:Liveness` 1.1): Query Heartbeat Pulse is answered with
//! Report Heartbeat Pulse, from anyone, in every state.

use crate::messages::{Message, ReportHeartbeatPulse};

/// The answer to Query Heartbeat Pulse.
pub fn heartbeat() -> Message {
    ReportHeartbeatPulse {}.into()
}
