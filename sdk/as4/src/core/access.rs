//! Access Control (`urn:jaus:jss:core:AccessControl` 1.1): who controls the component.
//!
//! The service keeps a *default* authority (configured) and a *current* one (the
//! controller's). The behaviour, from the public JSIDL of the service:
//!
//! * Request Control while nobody controls the component: granted (Confirm Control
//!   `ControlAccepted`) when the requester's authority is at least the default one,
//!   otherwise `InsufficientAuthority`.
//! * Request Control from another client while controlled: granted when its authority is
//!   higher than the current one, and the old controller is told Reject Control
//!   `ControlReleased`; otherwise `InsufficientAuthority`.
//! * Request Control from the controller: renews control (and the timer) and takes the
//!   new authority when it is at least the default one; an authority below the default
//!   ends control (Reject Control `ControlReleased`).
//! * Release Control from the controller ends control with Reject Control
//!   `ControlReleased`; so does any Release Control while nobody controls the
//!   component. A Release Control from a client that is not the controller is ignored.
//! * Set Authority from the controller changes the current authority when the value
//!   lies between the default and the current authority.
//! * With a timeout (seconds, 0 = none) the controller must send Request Control again
//!   within it; otherwise control lapses with Reject Control `ControlReleased`.
//! * While the component is not available (Management: Emergency, Shutdown, Failure),
//!   Request Control is answered `NotAvailable`, a release by the controller with
//!   Reject Control `NotAvailable`, and the timer does not run out.

use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;

use crate::messages::{
    ComponentAddress, ConfirmControl, ControlConfirmation, ControlRejection, RejectControl,
    ReportAuthority, ReportControl, ReportTimeout,
};
use crate::service::Outgoing;

/// The state of Access Control.
#[derive(Debug, Clone)]
pub struct Access {
    default_authority: u8,
    authority: u8,
    controller: Option<As4Id>,
    timeout: u8,
    deadline: Option<Instant>,
}

fn confirm(to: As4Id, response_code: ControlConfirmation) -> Outgoing {
    Outgoing::new(to, ConfirmControl { response_code })
}

fn reject(to: As4Id, response_code: ControlRejection) -> Outgoing {
    Outgoing::new(to, RejectControl { response_code })
}

impl Access {
    /// Nobody in control; `default_authority` and `timeout` (seconds, 0 = never).
    pub fn new(default_authority: u8, timeout: u8) -> Self {
        Self {
            default_authority,
            authority: default_authority,
            controller: None,
            timeout,
            deadline: None,
        }
    }

    /// The controlling client.
    pub fn controller(&self) -> Option<As4Id> {
        self.controller
    }

    /// The current authority (the default one while nobody controls).
    pub fn authority(&self) -> u8 {
        self.authority
    }

    /// The default authority.
    pub fn default_authority(&self) -> u8 {
        self.default_authority
    }

    /// The control timeout in seconds (0: control never lapses).
    pub fn timeout(&self) -> u8 {
        self.timeout
    }

    /// When control lapses unless renewed.
    pub fn deadline(&self) -> Option<Instant> {
        self.deadline
    }

    fn rearm(&mut self, now: Instant) {
        self.deadline = (self.timeout > 0 && self.controller.is_some())
            .then(|| now + Duration::from_secs(u64::from(self.timeout)));
    }

    /// Request Control from `from` with `authority`; `available` is false in
    /// Emergency, Shutdown and Failure. The answers (to the requester and perhaps a
    /// Reject Control to the preempted controller).
    pub fn request(
        &mut self,
        now: Instant,
        from: As4Id,
        authority: u8,
        available: bool,
    ) -> Vec<Outgoing> {
        if !available {
            return vec![confirm(from, ControlConfirmation::NotAvailable)];
        }
        match self.controller {
            None if authority < self.default_authority => {
                vec![confirm(from, ControlConfirmation::InsufficientAuthority)]
            }
            Some(c) if c == from && authority < self.default_authority => {
                self.end();
                vec![reject(from, ControlRejection::ControlReleased)]
            }
            Some(c) if c != from && authority <= self.authority => {
                vec![confirm(from, ControlConfirmation::InsufficientAuthority)]
            }
            old => {
                let mut out = Vec::new();
                if let Some(c) = old.filter(|c| *c != from) {
                    out.push(reject(c, ControlRejection::ControlReleased));
                }
                self.controller = Some(from);
                self.authority = authority;
                self.rearm(now);
                out.push(confirm(from, ControlConfirmation::ControlAccepted));
                out
            }
        }
    }

    /// Release Control from `from`. `Err` names why it was ignored.
    pub fn release(&mut self, from: As4Id, available: bool) -> Result<Vec<Outgoing>, String> {
        match self.controller {
            None => Ok(vec![reject(from, ControlRejection::ControlReleased)]),
            Some(c) if c != from => Err(format!("{from} does not hold control ({c} does)")),
            Some(_) if !available => Ok(vec![reject(from, ControlRejection::NotAvailable)]),
            Some(_) => {
                self.end();
                Ok(vec![reject(from, ControlRejection::ControlReleased)])
            }
        }
    }

    /// Set Authority from the controller: `Err` names why it was refused.
    pub fn set_authority(&mut self, authority: u8) -> Result<(), String> {
        if authority < self.default_authority || authority > self.authority {
            return Err(format!(
                "authority {authority} outside [{}, {}]",
                self.default_authority, self.authority
            ));
        }
        self.authority = authority;
        Ok(())
    }

    /// Ends control (Shutdown, Reset, Failure, timeout): the Reject Control for the
    /// controller, if there was one.
    pub fn revoke(&mut self) -> Option<Outgoing> {
        let c = self.controller?;
        self.end();
        Some(reject(c, ControlRejection::ControlReleased))
    }

    fn end(&mut self) {
        self.controller = None;
        self.authority = self.default_authority;
        self.deadline = None;
    }

    /// Time passed: control lapses past the deadline (while available; otherwise the
    /// timer starts again).
    pub fn handle_timeout(&mut self, now: Instant, available: bool) -> Option<Outgoing> {
        if self.deadline.is_none_or(|d| d > now) {
            return None;
        }
        if !available {
            self.rearm(now);
            return None;
        }
        self.revoke()
    }

    /// Report Control: the controller and its authority, all zero when free.
    pub fn report_control(&self) -> ReportControl {
        let c = self.controller.unwrap_or_default();
        ReportControl {
            controller: ComponentAddress {
                subsystem_id: c.subsystem,
                node_id: c.node,
                component_id: c.component,
            },
            authority_code: if self.controller.is_some() {
                self.authority
            } else {
                0
            },
        }
    }

    /// Report Authority.
    pub fn report_authority(&self) -> ReportAuthority {
        ReportAuthority {
            authority_code: self.authority,
        }
    }

    /// Report Timeout.
    pub fn report_timeout(&self) -> ReportTimeout {
        ReportTimeout {
            timeout: self.timeout,
        }
    }
}
