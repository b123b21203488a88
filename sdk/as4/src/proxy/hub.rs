//! [`As4Proxy`]: the AS-4 side of a proxy, an AS-4 client of one vehicle on the node's
//! socket. It finds the vehicle's services (Discovery), subscribes to its sensors'
//! reports with AS-4 periodic events ([`SensorEvents`]: Create Event once a sensor is
//! found; a sensor whose event is refused, unanswered or gone silent is polled every
//! poll period instead), polls the drivers' status and controller and the active list
//! element while a list runs, asks for and gives up AS-4 control as the RA 3.3 side
//! wants, and sends what the RA 3.3 components queue ([`Shared`](super::Shared)).

use std::time::{Duration, Instant};

use jaus::net::as5669a::{As4Endpoint, As4Id, As4Message, As4Send};
use jaus::net::PeerAddr;
use jaus::CommandCode;

use super::events::{sensor_query, SensorEvents, SENSORS};
use super::presence;
use super::shared::{lock, As4Control, ProxyStats, SharedRef};
use super::{ProxyConfig, Role};
use crate::messages::{
    ControlConfirmation, IdentificationType, Message, NodeServicesQuery, QueryActiveElement,
    QueryControl, QueryIdentification, QueryServices, QueryStatus, QueryWrenchEffort,
    ReleaseControl, RequestControl,
};

/// How long a Request Control may go unanswered before it is sent again.
const CONTROL_RETRY: Duration = Duration::from_secs(2);

/// Once the vehicle has listed its services, how often it is asked again for the
/// presented services it did not list (a vehicle may register them later); until then
/// it is asked every status period.
const REDISCOVER: Duration = Duration::from_secs(5);

/// Every component of every node and subsystem (Discovery without a known id).
const EVERYONE: As4Id = As4Id::new(0xFFFF, 0xFF, 0xFF);

/// The AS-4 side of a proxy (see the [module](super) documentation).
#[derive(Debug)]
pub struct As4Proxy<A: PeerAddr> {
    config: ProxyConfig,
    peer: A,
    shared: SharedRef,
    next_poll: Instant,
    next_status: Instant,
    /// When Discovery is next due (see [`REDISCOVER`]).
    next_discovery: Instant,
    /// The sensors' events.
    events: SensorEvents,
    /// The latest time it was given (what it answers `poll_timeout` with when it has
    /// something to send at once).
    last_now: Instant,
}

impl<A: PeerAddr> As4Proxy<A> {
    /// The AS-4 side for the vehicle at `peer`, sharing `shared` with the RA 3.3
    /// components ([`install`](super::install) builds both).
    pub fn new(config: ProxyConfig, peer: A, shared: SharedRef, now: Instant) -> Self {
        Self {
            peer,
            shared,
            next_poll: now,
            next_status: now,
            next_discovery: now,
            events: SensorEvents::new(config.poll_period),
            last_now: now,
            config,
        }
    }

    /// Its AS-4 id.
    pub fn id(&self) -> As4Id {
        self.config.me
    }

    /// The vehicle's address.
    pub fn peer(&self) -> A {
        self.peer
    }

    /// Counters.
    pub fn stats(&self) -> ProxyStats {
        lock(&self.shared).stats
    }

    /// The AS-4 component offering `role`'s service, once found.
    pub fn service(&self, role: Role) -> Option<As4Id> {
        lock(&self.shared).service(role)
    }

    /// AS-4 control of the component offering `role`'s service.
    pub fn control(&self, role: Role) -> As4Control {
        let s = lock(&self.shared);
        s.service(role).map_or(As4Control::None, |at| s.control(at))
    }

    /// The vehicle's name (Report Identification), once known.
    pub fn name(&self) -> Option<String> {
        lock(&self.shared).name.clone()
    }

    /// The sensors' events (where each stands).
    pub fn events(&self) -> &SensorEvents {
        &self.events
    }

    /// The state it shares with the RA 3.3 components (a handle to it: e.g. to read the
    /// counters once the proxy is on a socket).
    pub fn shared(&self) -> SharedRef {
        self.shared.clone()
    }

    fn take(&mut self, now: Instant, from: As4Id, msg: Message) {
        let mut s = lock(&self.shared);
        match msg {
            Message::ReportServices(r) => {
                self.next_discovery = now + REDISCOVER;
                for n in &r.nodes {
                    for c in &n.components {
                        let at = As4Id::new(from.subsystem, n.node_id, c.component_id);
                        for svc in &c.services {
                            let Some(role) = Role::of_uri(&svc.uri) else {
                                continue;
                            };
                            if self.config.roles.contains(&role) {
                                s.found(role, at);
                            }
                        }
                    }
                }
            }
            Message::ReportIdentification(r) => {
                if s.name.is_none() {
                    tracing::info!(vehicle = %from, name = %r.identification, "AS-4 vehicle identified");
                }
                s.name = Some(r.identification);
            }
            Message::ConfirmControl(c) => {
                let state = if c.response_code == ControlConfirmation::ControlAccepted {
                    As4Control::Granted
                } else {
                    tracing::warn!(component = %from, code = ?c.response_code, "AS-4 control refused");
                    As4Control::Refused(c.response_code)
                };
                if s.wanted(from) || state != As4Control::Granted {
                    s.set_control(from, state);
                } else {
                    // Granted after the RA 3.3 side gave up: give it back.
                    s.send(from, ReleaseControl {});
                    s.set_control(from, As4Control::None);
                }
            }
            Message::RejectControl(_) => {
                if s.control(from) == As4Control::Granted {
                    tracing::warn!(component = %from, "AS-4 control taken away");
                    s.set_control(from, As4Control::Lost);
                } else {
                    s.set_control(from, As4Control::None);
                }
            }
            Message::ReportControl(r) => {
                let c = r.controller;
                let holder = As4Id::new(c.subsystem_id, c.node_id, c.component_id);
                if s.control(from) == As4Control::Granted && holder != self.config.me {
                    tracing::warn!(component = %from, %holder, "AS-4 control held by another client");
                    s.set_control(from, As4Control::Lost);
                }
            }
            Message::ReportStatus(r) => s.set_status(from, r.status),
            Message::RejectElementRequest(r) => {
                s.stats.elements_refused += 1;
                tracing::warn!(component = %from, code = ?r.response_code, "AS-4 list elements refused");
            }
            m @ (Message::ReportVelocityState(_)
            | Message::ReportGlobalPose(_)
            | Message::ReportLocalPose(_)
            | Message::ReportWrenchEffort(_)
            | Message::ReportActiveElement(_)) => s.keep(now, from, m),
            Message::ConfirmElementRequest(_) => {}
            Message::Event(e) => self.events.event(now, from, &e, &mut s),
            Message::ConfirmEventRequest(c) => {
                // A confirmation of a Cancel Event (or of nothing asked) needs nothing.
                self.events.confirmed(now, from, &c);
            }
            Message::RejectEventRequest(r) => {
                if !self.events.rejected(now, from, &r, &mut s) {
                    tracing::debug!(component = %from, code = ?r.response_code, "event request refused (not a Create Event pending)");
                }
            }
            _ => s.stats.ignored += 1,
        }
    }

    /// Queues the queries and control requests due at `now`.
    fn due(&mut self, now: Instant) {
        let mut s = lock(&self.shared);
        let roles = &self.config.roles;
        self.events.due(now, roles, &mut s);
        if now >= self.next_poll {
            self.next_poll = now + self.config.poll_period;
            for role in SENSORS {
                if !roles.contains(&role) || !self.events.polls(role) {
                    continue;
                }
                if let Some(q) = sensor_query(role) {
                    if s.send_to(role, q) {
                        s.stats.sensor_queries += 1;
                    }
                }
            }
            let running: Vec<As4Id> = s.executing().collect();
            for at in running {
                s.send(at, QueryActiveElement {});
            }
        }
        if now >= self.next_status {
            self.next_status = now + self.config.status_period;
            if now >= self.next_discovery && roles.iter().any(|r| s.service(*r).is_none()) {
                self.next_discovery = now + self.config.status_period;
                let to = self.config.vehicle.unwrap_or(EVERYONE);
                let (node_id, component_ids) = if to.node == 0xFF || to.component == 0xFF {
                    (255, vec![255])
                } else {
                    (to.node, vec![to.component])
                };
                s.send(
                    to,
                    QueryIdentification {
                        query_type: IdentificationType::Subsystem,
                    },
                );
                s.send(
                    to,
                    QueryServices {
                        nodes: vec![NodeServicesQuery {
                            node_id,
                            component_ids,
                        }],
                    },
                );
            }
            let mut drivers: Vec<As4Id> = roles
                .iter()
                .filter(|r| r.is_driver())
                .filter_map(|r| s.service(*r))
                .collect();
            drivers.sort();
            drivers.dedup();
            for at in drivers {
                s.send(at, QueryStatus {});
                if s.control(at) == As4Control::Granted {
                    s.send(at, QueryControl {});
                }
            }
            if roles.contains(&Role::PrimitiveDriver) {
                s.send_to(
                    Role::PrimitiveDriver,
                    QueryWrenchEffort {
                        presence_vector: presence::wrench_effort(),
                    },
                );
            }
        }
        let mut components: Vec<As4Id> = s.services().map(|(_, at)| at).collect();
        components.sort();
        components.dedup();
        for at in components {
            let wanted = s.wanted(at);
            let retry = |t: Instant| now.saturating_duration_since(t) >= CONTROL_RETRY;
            match s.control(at) {
                As4Control::None if wanted => {
                    s.send(
                        at,
                        RequestControl {
                            authority_code: self.config.authority,
                        },
                    );
                    s.set_control(at, As4Control::Requested(now));
                }
                As4Control::Requested(t) if wanted && retry(t) => {
                    s.send(
                        at,
                        RequestControl {
                            authority_code: self.config.authority,
                        },
                    );
                    s.set_control(at, As4Control::Requested(now));
                }
                As4Control::Granted | As4Control::Requested(_) if !wanted => {
                    s.send(at, ReleaseControl {});
                    s.set_control(at, As4Control::None);
                }
                _ => {}
            }
        }
    }

    /// What waits in the outbox, encoded for the vehicle.
    fn flush(&mut self) -> Vec<As4Send<A>> {
        let mut s = lock(&self.shared);
        let me = self.config.me;
        let mut out = Vec::new();
        for (to, m) in s.take_outgoing() {
            match m.body().to_bytes() {
                Ok(body) => {
                    s.stats.sent += 1;
                    out.push(As4Send {
                        to: self.peer,
                        message: As4Message::new(m.code().0, to, me, body),
                    });
                }
                Err(e) => {
                    s.stats.encode_errors += 1;
                    tracing::warn!(message = m.name(), %to, "not encoded: {e}");
                }
            }
        }
        out
    }
}

impl<A: PeerAddr> As4Endpoint<A> for As4Proxy<A> {
    fn handle(&mut self, now: Instant, from: A, messages: Vec<As4Message>) -> Vec<As4Message> {
        self.last_now = self.last_now.max(now);
        for m in messages {
            if from != self.peer {
                lock(&self.shared).stats.ignored += 1;
                tracing::debug!(%from, "AS-4 message for the proxy from another address ignored");
                continue;
            }
            lock(&self.shared).stats.received += 1;
            match Message::decode(CommandCode(m.message_id), &m.body) {
                Ok(msg) => self.take(now, m.source, msg),
                Err(e) => {
                    lock(&self.shared).stats.decode_errors += 1;
                    tracing::debug!(
                        id = %format_args!("{:#06X}", m.message_id),
                        from = %m.source,
                        "AS-4 message to the proxy does not decode: {e}"
                    );
                }
            }
        }
        // Answers (control requests that follow a refusal, …) leave on the next timer.
        Vec::new()
    }

    fn handle_timeout(&mut self, now: Instant) -> Vec<As4Send<A>> {
        self.last_now = self.last_now.max(now);
        self.due(now);
        self.flush()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        let s = lock(&self.shared);
        let urgent = s.has_outgoing()
            || s.services().any(|(_, at)| {
                matches!(
                    (s.wanted(at), s.control(at)),
                    (true, As4Control::None)
                        | (false, As4Control::Granted | As4Control::Requested(_))
                )
            });
        if urgent {
            // At once: an RA 3.3 client waits for what follows.
            return Some(self.last_now);
        }
        let next = self.next_poll.min(self.next_status);
        Some(self.events.next_timeout().map_or(next, |e| e.min(next)))
    }

    /// Messages for its own AS-4 id only.
    fn serves(&self, destination: As4Id) -> bool {
        destination == self.config.me
    }
}
