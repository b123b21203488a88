//! Access Control (`urn:jaus:jss:core:AccessControl` 1.1): who controls the component.
//!
//! The decisions (who gets control, when it ends, what is refused while the component is
//! not available) are the state machine of `defs/core_services.yaml`, run by
//! [`super::machine`]; this module keeps what the machine's guards read and its actions
//! change: the default and current authority, the controlling client and the control
//! timer.
//!
//! * The service keeps a *default* authority (configured) and a *current* one (the
//!   controller's); a client below the default never gets control, a client above the
//!   current one takes it from the controller.
//! * With a timeout (seconds, 0 = none) the controller must send Request Control again
//!   within it; otherwise the owner raises `Timedout` and control lapses.

use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;

use crate::messages::{ComponentAddress, ReportAuthority, ReportControl, ReportTimeout};

/// The state of Access Control.
#[derive(Debug, Clone)]
pub struct Access {
    default_authority: u8,
    authority: u8,
    controller: Option<As4Id>,
    timeout: u8,
    deadline: Option<Instant>,
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

    /// Whether `authority` lies in `[default, current]` (Set Authority's rule).
    pub fn is_valid(&self, authority: u8) -> bool {
        (self.default_authority..=self.authority).contains(&authority)
    }

    /// `client` becomes the controller.
    pub(crate) fn store(&mut self, client: As4Id) {
        self.controller = Some(client);
    }

    /// The current authority becomes `authority`.
    pub(crate) fn set_authority(&mut self, authority: u8) {
        self.authority = authority;
    }

    /// Control lapses a timeout after `now` (never with timeout 0 or no controller).
    pub(crate) fn rearm(&mut self, now: Instant) {
        self.deadline = (self.timeout > 0 && self.controller.is_some())
            .then(|| now + Duration::from_secs(u64::from(self.timeout)));
    }

    /// Nobody controls the component: the default authority, no timer.
    pub(crate) fn reset(&mut self) {
        self.controller = None;
        self.authority = self.default_authority;
        self.deadline = None;
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
