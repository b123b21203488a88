//! What the proxy's AS-4 side ([`As4Proxy`](super::As4Proxy)) and its RA 3.3
//! components share: where each Mobility service of the vehicle is, the latest AS-4
//! reports, AS-4 control and status of the vehicle's components, and the AS-4 messages
//! the RA 3.3 components want sent (bounded, counted when full).
//!
//! Both sides run on the node's thread; the [`Mutex`] only makes the sharing `Send`.
//! A lock is never held across a call into the other side.

use std::collections::{HashMap, HashSet, VecDeque};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Instant;

use jaus::net::as5669a::As4Id;
use jaus::CommandCode;

use super::Role;
use crate::messages::{ComponentState, ControlConfirmation, Message};
use crate::ra33::Frame;

/// Most AS-4 messages waiting to leave (more are dropped and counted).
pub const MAX_OUTBOX: usize = 1024;

/// Where the proxy's AS-4 control of one of the vehicle's components stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum As4Control {
    /// Not held, not asked for.
    None,
    /// Request Control sent at that time; no answer yet.
    Requested(Instant),
    /// Confirm Control accepted.
    Granted,
    /// Confirm Control refused (with the response code).
    Refused(ControlConfirmation),
    /// Held, then taken away (Reject Control, or Report Control naming another client).
    Lost,
}

/// Counters of a proxy.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ProxyStats {
    /// AS-4 messages sent to the vehicle.
    pub sent: u64,
    /// AS-4 messages received from it.
    pub received: u64,
    /// Received messages whose body did not decode.
    pub decode_errors: u64,
    /// AS-4 messages dropped: the outbox was full.
    pub outbox_full: u64,
    /// AS-4 messages not sent: the body did not encode.
    pub encode_errors: u64,
    /// Received messages the proxy has no use for.
    pub ignored: u64,
    /// Elements the vehicle's List Manager refused (Reject Element Request).
    pub elements_refused: u64,
    /// Sensor queries polled (sent because their event is not confirmed).
    pub sensor_queries: u64,
    /// Events received whose sensor report was kept.
    pub events_received: u64,
    /// Events whose embedded report did not decode or was not a sensor report
    /// (dropped).
    pub events_malformed: u64,
    /// Create Events refused (Reject Event Request) or unanswered within 1 s: the query
    /// is polled instead.
    pub events_refused: u64,
    /// Confirmed events that went silent (the query polled again, the event created
    /// again).
    pub events_lapsed: u64,
}

/// The state both sides share (see the module's documentation).
#[derive(Debug)]
pub struct Shared {
    /// The proxy's own AS-4 id.
    pub me: As4Id,
    services: HashMap<Role, As4Id>,
    reports: HashMap<(As4Id, CommandCode), (Instant, Message)>,
    control: HashMap<As4Id, As4Control>,
    wants: HashSet<Role>,
    status: HashMap<As4Id, ComponentState>,
    executing: HashSet<As4Id>,
    outbox: VecDeque<(As4Id, Message)>,
    /// Bumped whenever control, status or the services found change: the RA 3.3
    /// components look again.
    changes: u64,
    /// The vehicle's name (Report Identification), once known.
    pub name: Option<String>,
    /// The AS-4 local frame relative to the RA 3.3 one (identity unless configured).
    pub frame: Frame,
    /// Counters.
    pub stats: ProxyStats,
}

/// The shared state as the two sides hold it.
pub type SharedRef = Arc<Mutex<Shared>>;

/// Locks `s` (a panic elsewhere while it was held leaves plain data: taken as it is).
pub fn lock(s: &Mutex<Shared>) -> MutexGuard<'_, Shared> {
    s.lock().unwrap_or_else(|e| e.into_inner())
}

impl Shared {
    /// Nothing known yet, for the proxy with AS-4 id `me`.
    pub fn new(me: As4Id, frame: Frame) -> Self {
        Self {
            me,
            services: HashMap::new(),
            reports: HashMap::new(),
            control: HashMap::new(),
            wants: HashSet::new(),
            status: HashMap::new(),
            executing: HashSet::new(),
            outbox: VecDeque::new(),
            changes: 0,
            name: None,
            frame,
            stats: ProxyStats::default(),
        }
    }

    /// The AS-4 component offering `role`'s service, once found.
    pub fn service(&self, role: Role) -> Option<As4Id> {
        self.services.get(&role).copied()
    }

    /// Every role found, with its component.
    pub fn services(&self) -> impl Iterator<Item = (Role, As4Id)> + '_ {
        self.services.iter().map(|(r, c)| (*r, *c))
    }

    /// `role`'s service is on `at` (first finding only; later ones are ignored).
    pub fn found(&mut self, role: Role, at: As4Id) {
        if let std::collections::hash_map::Entry::Vacant(e) = self.services.entry(role) {
            tracing::info!(%at, ?role, "AS-4 service found");
            e.insert(at);
            self.changes += 1;
        }
    }

    /// The latest report `code` from the component offering `role`, with when it came.
    pub fn report(&self, role: Role, code: CommandCode) -> Option<(Instant, &Message)> {
        let at = self.service(role)?;
        self.reports.get(&(at, code)).map(|(t, m)| (*t, m))
    }

    /// Keeps `report` from `from`.
    pub fn keep(&mut self, now: Instant, from: As4Id, report: Message) {
        self.reports.insert((from, report.code()), (now, report));
    }

    /// AS-4 control of component `at`.
    pub fn control(&self, at: As4Id) -> As4Control {
        self.control.get(&at).copied().unwrap_or(As4Control::None)
    }

    /// Sets AS-4 control of `at` (a change is announced to the RA 3.3 side).
    pub fn set_control(&mut self, at: As4Id, c: As4Control) {
        if self.control(at) != c {
            self.control.insert(at, c);
            self.changes += 1;
        }
    }

    /// Whether the proxy holds AS-4 control of the component offering `role`.
    pub fn holds(&self, role: Role) -> bool {
        self.service(role)
            .is_some_and(|at| self.control(at) == As4Control::Granted)
    }

    /// An RA 3.3 client wants (or no longer wants) `role`'s driver: AS-4 control of its
    /// component is asked for while any driver on it is wanted. Asking again after a
    /// refusal or a loss starts over.
    pub fn want(&mut self, role: Role, want: bool) {
        if want {
            self.wants.insert(role);
            if let Some(at) = self.service(role) {
                if matches!(self.control(at), As4Control::Refused(_) | As4Control::Lost) {
                    self.set_control(at, As4Control::None);
                }
            }
        } else {
            self.wants.remove(&role);
        }
    }

    /// Whether some RA 3.3 driver on component `at` is wanted.
    pub fn wanted(&self, at: As4Id) -> bool {
        self.wants.iter().any(|r| self.service(*r) == Some(at))
    }

    /// The last state component `at` reported.
    pub fn status(&self, at: As4Id) -> Option<ComponentState> {
        self.status.get(&at).copied()
    }

    /// Component `at` reported state `s`.
    pub fn set_status(&mut self, at: As4Id, s: ComponentState) {
        if self.status(at) != Some(s) {
            self.status.insert(at, s);
            self.changes += 1;
        }
    }

    /// Whether a waypoint list runs on `at` (its active element is then polled).
    pub fn set_executing(&mut self, at: As4Id, on: bool) {
        if on {
            self.executing.insert(at);
        } else {
            self.executing.remove(&at);
        }
    }

    /// The components running a waypoint list.
    pub fn executing(&self) -> impl Iterator<Item = As4Id> + '_ {
        self.executing.iter().copied()
    }

    /// The change counter (see [`Shared`]).
    pub fn changes(&self) -> u64 {
        self.changes
    }

    /// Queues `message` for component `to` (dropped and counted when the outbox is
    /// full).
    pub fn send(&mut self, to: As4Id, message: impl Into<Message>) {
        if self.outbox.len() >= MAX_OUTBOX {
            self.stats.outbox_full += 1;
            tracing::warn!(%to, "AS-4 outbox of the proxy full: message dropped");
            return;
        }
        self.outbox.push_back((to, message.into()));
    }

    /// Queues `message` for the component offering `role`, if found; false if not.
    pub fn send_to(&mut self, role: Role, message: impl Into<Message>) -> bool {
        match self.service(role) {
            Some(at) => {
                self.send(at, message);
                true
            }
            None => false,
        }
    }

    /// Whether messages wait to leave.
    pub fn has_outgoing(&self) -> bool {
        !self.outbox.is_empty()
    }

    /// Takes every message waiting to leave.
    pub fn take_outgoing(&mut self) -> Vec<(As4Id, Message)> {
        self.outbox.drain(..).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::messages::Resume;

    #[test]
    fn outbox_is_bounded_and_control_is_per_component() {
        let me = As4Id::new(200, 1, 1);
        let at = As4Id::new(1, 1, 1);
        let mut s = Shared::new(me, Frame::default());
        for _ in 0..MAX_OUTBOX + 3 {
            s.send(at, Resume {});
        }
        assert_eq!(s.stats.outbox_full, 3);
        assert!(!s.send_to(Role::GlobalWaypointDriver, Resume {}));
        s.found(Role::GlobalWaypointDriver, at);
        s.found(Role::PrimitiveDriver, at);
        s.want(Role::PrimitiveDriver, true);
        assert!(s.wanted(at));
        s.set_control(at, As4Control::Lost);
        // Asking again after a loss starts over.
        s.want(Role::GlobalWaypointDriver, true);
        assert_eq!(s.control(at), As4Control::None);
        s.want(Role::PrimitiveDriver, false);
        s.want(Role::GlobalWaypointDriver, false);
        assert!(!s.wanted(at));
    }
}
