//! Management (`urn:jaus:jss:core:Management` 1.1): the component's life-cycle state.
//!
//! The life cycle is the state machine of `defs/core_services.yaml` (run by
//! [`super::machine`]); the component's state ([`ComponentState`]) is read off the
//! machine's current state ([`state_of`]). This module keeps what its guards read and its
//! actions change: the emergencies in effect, as (client, code) pairs.
//!
//! What the machine says, in short: a component starts in Standby; only the controller
//! resumes (Standby → Ready), stands by, shuts down or resets it (control ends with
//! Reject Control `ControlReleased`; Reset passes through Initialize to Standby); losing
//! control takes Ready to Standby; any client may declare an emergency and the component
//! returns to the state it left when the last declaring client clears its own; control is
//! kept through an emergency, Shutdown and Reset are ignored during one; a failure
//! declared by the owner ends control and leaves the component in Failure (after the
//! emergency, if one is in effect).

use std::collections::BTreeSet;

use jaus::net::as5669a::As4Id;

use crate::messages::{ComponentState, EmergencyCode, ReportStatus};

/// Most (client, code) pairs of emergencies kept.
pub const MAX_EMERGENCIES: usize = 64;

/// The component's state when the Management machine is in the state at `path`
/// (`Receiving.Ready.Controlled.Available.Ready` is Ready): the innermost state names it.
pub fn state_of(path: &str) -> ComponentState {
    match path.rsplit('.').next().unwrap_or(path) {
        "Ready" => ComponentState::Ready,
        "Init" => ComponentState::Initialize,
        "Shutdown" => ComponentState::Shutdown,
        "Failure" => ComponentState::Failure,
        "Emergency" => ComponentState::Emergency,
        _ => ComponentState::Standby,
    }
}

/// The data of Management.
#[derive(Debug, Clone, Default)]
pub struct Management {
    state: ComponentState,
    emergencies: BTreeSet<(As4Id, u16)>,
    failed_in_emergency: bool,
}

impl Management {
    /// A component that has initialised: Standby, no emergency.
    pub fn new() -> Self {
        Self {
            state: ComponentState::Standby,
            ..Self::default()
        }
    }

    /// The current state.
    pub fn state(&self) -> ComponentState {
        self.state
    }

    /// The machine moved: its state's path.
    pub(crate) fn moved(&mut self, path: &str) {
        self.state = state_of(path);
    }

    /// Whether Access Control is available (Standby or Ready): not in Emergency,
    /// Shutdown, Failure or Initialize.
    pub fn available(&self) -> bool {
        matches!(self.state, ComponentState::Standby | ComponentState::Ready)
    }

    /// The emergencies in effect, as (client, code) pairs.
    pub fn emergencies(&self) -> impl Iterator<Item = (As4Id, EmergencyCode)> + '_ {
        self.emergencies.iter().map(|&(id, c)| (id, code_of(c)))
    }

    /// Records `from`'s emergency `code`: `false` when the bound on pairs is reached
    /// (the component is in Emergency all the same).
    pub(crate) fn store(&mut self, from: As4Id, code: EmergencyCode) -> bool {
        let key = (from, code_value(code));
        if self.emergencies.len() >= MAX_EMERGENCIES && !self.emergencies.contains(&key) {
            return false;
        }
        self.emergencies.insert(key);
        true
    }

    /// Whether `from` declared emergency `code`.
    pub fn is_stored(&self, from: As4Id, code: EmergencyCode) -> bool {
        self.emergencies.contains(&(from, code_value(code)))
    }

    /// Whether `from`'s `code` is the only emergency in effect.
    pub fn is_last(&self, from: As4Id, code: EmergencyCode) -> bool {
        self.emergencies.len() == 1 && self.is_stored(from, code)
    }

    /// Forgets `from`'s emergency `code`.
    pub(crate) fn delete(&mut self, from: As4Id, code: EmergencyCode) {
        self.emergencies.remove(&(from, code_value(code)));
    }

    /// A failure declared during an emergency: Failure once it is cleared.
    pub(crate) fn fail_after_emergency(&mut self) {
        self.failed_in_emergency = true;
    }

    /// Takes the failure declared during an emergency, once no emergency is in effect.
    pub(crate) fn take_pending_failure(&mut self) -> bool {
        if self.emergencies.is_empty() && self.state != ComponentState::Emergency {
            std::mem::take(&mut self.failed_in_emergency)
        } else {
            false
        }
    }

    /// Report Status.
    pub fn report(&self) -> ReportStatus {
        ReportStatus {
            status: self.state,
            reserved: 0,
        }
    }
}

fn code_of(v: u16) -> EmergencyCode {
    if v == 1 {
        EmergencyCode::Stop
    } else {
        EmergencyCode::Unknown(v)
    }
}

fn code_value(c: EmergencyCode) -> u16 {
    match c {
        EmergencyCode::Stop => 1,
        EmergencyCode::Unknown(v) => v,
    }
}
