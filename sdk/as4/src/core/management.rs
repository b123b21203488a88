//! Management (`urn:jaus:jss:core:Management` 1.1): the component's life-cycle state.
//!
//! States ([`ComponentState`]): Initialize, Ready, Standby, Shutdown, Failure,
//! Emergency. The behaviour, from the public JSIDL of the service:
//!
//! * A component starts in Initialize and goes to **Standby** once initialised; this
//!   runtime has nothing to wait for, so a new component is in Standby.
//! * Resume (Standby → Ready) and Standby (Ready → Standby) are obeyed from the
//!   controlling client only.
//! * Shutdown from the controller: state Shutdown and control ends (the controller gets
//!   Reject Control `ControlReleased`); nothing but an emergency leaves Shutdown.
//! * Reset from the controller: control ends the same way and the component
//!   initialises again, ending in Standby.
//! * Losing control (release, timeout) takes a Ready component to Standby.
//! * Set Emergency from any client enters Emergency and remembers (client, code);
//!   Clear Emergency from a client that set one removes its pair; the component leaves
//!   Emergency for the state it was in when the last pair is cleared. Control is kept
//!   through an emergency; Shutdown and Reset are ignored during one.
//! * The owner may declare a failure ([`Core::fail`](super::Core::fail)): state
//!   Failure, control ends; only an emergency leaves Failure (and returns to it).

use std::collections::BTreeSet;

use jaus::net::as5669a::As4Id;

use crate::messages::{ComponentState, EmergencyCode, ReportStatus};

/// Most (client, code) pairs of emergencies kept.
pub const MAX_EMERGENCIES: usize = 64;

/// The state of Management.
#[derive(Debug, Clone)]
pub struct Management {
    state: ComponentState,
    before_emergency: ComponentState,
    emergencies: BTreeSet<(As4Id, u16)>,
}

impl Default for Management {
    fn default() -> Self {
        Self::new()
    }
}

impl Management {
    /// A component that has initialised: Standby.
    pub fn new() -> Self {
        Self {
            state: ComponentState::Standby,
            before_emergency: ComponentState::Standby,
            emergencies: BTreeSet::new(),
        }
    }

    /// The current state.
    pub fn state(&self) -> ComponentState {
        self.state
    }

    /// Whether Access Control is available (Standby or Ready): not in Emergency,
    /// Shutdown or Failure.
    pub fn available(&self) -> bool {
        matches!(self.state, ComponentState::Standby | ComponentState::Ready)
    }

    /// The emergencies in effect, as (client, code) pairs.
    pub fn emergencies(&self) -> impl Iterator<Item = (As4Id, EmergencyCode)> + '_ {
        self.emergencies.iter().map(|&(id, c)| (id, code_of(c)))
    }

    /// Resume from the controller: Standby → Ready. `Err` names why nothing changed.
    pub fn resume(&mut self) -> Result<(), String> {
        match self.state {
            ComponentState::Standby => {
                self.state = ComponentState::Ready;
                Ok(())
            }
            ComponentState::Ready => Ok(()),
            s => Err(format!("cannot resume from {s:?}")),
        }
    }

    /// Standby from the controller: Ready → Standby.
    pub fn standby(&mut self) -> Result<(), String> {
        match self.state {
            ComponentState::Ready | ComponentState::Standby => {
                self.state = ComponentState::Standby;
                Ok(())
            }
            s => Err(format!("cannot go to standby from {s:?}")),
        }
    }

    /// Shutdown or Reset from the controller: `Err` during an emergency (ignored).
    /// Reset passes through Initialize and ends in Standby.
    pub fn shutdown(&mut self, reset: bool) -> Result<(), String> {
        if self.state == ComponentState::Emergency {
            return Err("ignored during an emergency".into());
        }
        self.state = if reset {
            ComponentState::Standby
        } else {
            ComponentState::Shutdown
        };
        Ok(())
    }

    /// Control ended: Ready becomes Standby.
    pub fn control_lost(&mut self) {
        if self.state == ComponentState::Ready {
            self.state = ComponentState::Standby;
        }
    }

    /// The owner declares a failure.
    pub fn fail(&mut self) {
        if self.state == ComponentState::Emergency {
            self.before_emergency = ComponentState::Failure;
        } else {
            self.state = ComponentState::Failure;
        }
    }

    /// Set Emergency from `from`. `Err` when the bound on pairs is reached (the state
    /// is Emergency all the same).
    pub fn set_emergency(&mut self, from: As4Id, code: EmergencyCode) -> Result<(), String> {
        if self.state != ComponentState::Emergency {
            self.before_emergency = self.state;
            self.state = ComponentState::Emergency;
        }
        let key = (from, code_value(code));
        if self.emergencies.len() >= MAX_EMERGENCIES && !self.emergencies.contains(&key) {
            return Err(format!("more than {MAX_EMERGENCIES} emergencies"));
        }
        self.emergencies.insert(key);
        Ok(())
    }

    /// Clear Emergency from `from`: `Err` when it set no such emergency.
    pub fn clear_emergency(&mut self, from: As4Id, code: EmergencyCode) -> Result<(), String> {
        if !self.emergencies.remove(&(from, code_value(code))) {
            return Err(format!("{from} set no emergency {code:?}"));
        }
        if self.emergencies.is_empty() && self.state == ComponentState::Emergency {
            self.state = self.before_emergency;
        }
        Ok(())
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
