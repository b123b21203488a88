//! [`SensorEvents`]: how the proxy's AS-4 side ([`As4Proxy`](super::As4Proxy)) gets the
//! vehicle's sensor reports with AS-4 Events (`urn:jaus:jss:core:Events`) rather than by
//! polling.
//!
//! For each of the three sensor queries (Query Velocity State, Query Global Pose, Query
//! Local Pose) of a role the proxy presents, once the vehicle's component offering it is
//! found, the proxy sends Create Event: periodic, at `1 / poll_period` Hz clamped to
//! [[`MIN_RATE`], [`MAX_RATE`]], the query embedded (message ID and body, as
//! [`embedded`] writes it).
//!
//! * **Confirm Event Request** (matched by request id and component): the event id and
//!   the confirmed rate are kept, and that query is no longer polled.
//! * **Reject Event Request**, or no answer within [`CONFIRM_TIMEOUT`]: the query is
//!   polled as before (counted in [`ProxyStats::events_refused`]); Create Event is tried
//!   again after [`RETRY_REFUSED`] or [`RETRY_UNANSWERED`].
//! * **Event**: its embedded report is taken as a polled one would be (counted in
//!   [`ProxyStats::events_received`]); a report that does not decode, or is not a sensor
//!   report, is counted in [`ProxyStats::events_malformed`] and dropped.
//! * **Liveness.** A confirmed event that sends nothing for 3 periods +
//!   [`SILENCE_MARGIN`] (the vehicle restarted and lost it, or cancelled it) lapses
//!   (counted in [`ProxyStats::events_lapsed`]): the query is polled again, the proxy
//!   sends Cancel Event for the old event id and creates the event again, at most one
//!   Create Event per query per [`MIN_CREATE_INTERVAL`].
//!
//! The state is three slots, one per query: bounded whatever the vehicle sends.
//!
//! [`ProxyStats::events_refused`]: super::ProxyStats::events_refused
//! [`ProxyStats::events_received`]: super::ProxyStats::events_received
//! [`ProxyStats::events_malformed`]: super::ProxyStats::events_malformed
//! [`ProxyStats::events_lapsed`]: super::ProxyStats::events_lapsed

use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;

use super::presence;
use super::shared::Shared;
use super::Role;
use crate::core::events::{MAX_RATE, MIN_RATE};
use crate::embedded;
use crate::messages::{
    CancelEvent, ConfirmEventRequest, CreateEvent, Event, EventType, Message, QueryGlobalPose,
    QueryLocalPose, QueryVelocityState, RejectEventRequest,
};

/// How long a Create Event may go unanswered before the query is polled instead.
pub const CONFIRM_TIMEOUT: Duration = Duration::from_secs(1);

/// After a Reject Event Request, when Create Event is tried again (a vehicle just
/// started may refuse a query its services do not answer yet).
pub const RETRY_REFUSED: Duration = Duration::from_secs(5);

/// After a Create Event nobody answered, when it is tried again.
pub const RETRY_UNANSWERED: Duration = Duration::from_secs(5);

/// Added to 3 periods of a confirmed event: the silence after which it has lapsed.
pub const SILENCE_MARGIN: Duration = Duration::from_millis(500);

/// At most one Create Event per query within this interval.
pub const MIN_CREATE_INTERVAL: Duration = Duration::from_secs(1);

/// The sensor roles whose query is carried by an event, in slot order.
pub const SENSORS: [Role; 3] = [
    Role::VelocityStateSensor,
    Role::GlobalPoseSensor,
    Role::LocalPoseSensor,
];

/// The query of sensor `role` (every field its report defines asked for:
/// [`presence`]), or `None` for a role that is not one of [`SENSORS`].
pub fn sensor_query(role: Role) -> Option<Message> {
    match role {
        Role::VelocityStateSensor => Some(
            QueryVelocityState {
                presence_vector: presence::velocity_state(),
            }
            .into(),
        ),
        Role::GlobalPoseSensor => Some(
            QueryGlobalPose {
                presence_vector: presence::global_pose(),
            }
            .into(),
        ),
        Role::LocalPoseSensor => Some(
            QueryLocalPose {
                presence_vector: presence::local_pose(),
            }
            .into(),
        ),
        _ => None,
    }
}

/// Where the event of one sensor query stands.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EventState {
    /// Not asked for yet (the service is not found yet); the query is polled once found.
    Idle,
    /// Create Event `request_id` sent to `at` at `sent`; the query is polled meanwhile.
    Pending {
        /// The component asked.
        at: As4Id,
        /// The request id of the Create Event.
        request_id: u8,
        /// When it was sent.
        sent: Instant,
    },
    /// Confirmed: the reports come as events; the query is not polled.
    Confirmed {
        /// The component sending the events.
        at: As4Id,
        /// The event id it gave.
        event_id: u8,
        /// The period of the confirmed rate.
        period: Duration,
        /// When the confirmation or the latest Event came.
        last: Instant,
    },
    /// Refused, unanswered or lapsed: the query is polled; Create Event is sent again at
    /// `retry`.
    Polling {
        /// When to try Create Event again.
        retry: Instant,
    },
}

/// The events of the three sensor queries (see the module documentation).
#[derive(Debug, Clone)]
pub struct SensorEvents {
    rate: f64,
    slots: [EventState; 3],
    last_create: [Option<Instant>; 3],
    next_request: u8,
}

/// The rate asked for when the sensors would be polled every `poll_period`.
pub fn rate_for(poll_period: Duration) -> f64 {
    let secs = poll_period.as_secs_f64();
    if secs > 0.0 {
        (1.0 / secs).clamp(MIN_RATE, MAX_RATE)
    } else {
        MAX_RATE
    }
}

impl SensorEvents {
    /// No event asked for yet; they will be asked at the rate of `poll_period`
    /// ([`rate_for`]).
    pub fn new(poll_period: Duration) -> Self {
        Self {
            rate: rate_for(poll_period),
            slots: [EventState::Idle; 3],
            last_create: [None; 3],
            next_request: 0,
        }
    }

    /// The rate asked for, Hz.
    pub fn rate(&self) -> f64 {
        self.rate
    }

    /// Where the event of sensor `role` stands (`None`: not a sensor of [`SENSORS`]).
    pub fn state(&self, role: Role) -> Option<EventState> {
        slot_of(role).map(|i| self.slots[i])
    }

    /// Whether sensor `role`'s query is to be polled (its event is not confirmed).
    pub fn polls(&self, role: Role) -> bool {
        !matches!(self.state(role), Some(EventState::Confirmed { .. }))
    }

    /// Creates, times out and renews the events at `now` for the sensors among `roles`
    /// whose service is found, queueing what is to be sent in `s`.
    pub fn due(&mut self, now: Instant, roles: &[Role], s: &mut Shared) {
        for (i, role) in SENSORS.into_iter().enumerate() {
            if !roles.contains(&role) {
                continue;
            }
            let Some(at) = s.service(role) else {
                continue;
            };
            match self.slots[i] {
                EventState::Idle => self.create(now, i, at, s),
                EventState::Pending { sent, .. } if now >= sent + CONFIRM_TIMEOUT => {
                    s.stats.events_refused += 1;
                    tracing::debug!(component = %at, ?role, "Create Event unanswered: the query is polled");
                    self.slots[i] = EventState::Polling {
                        retry: now + RETRY_UNANSWERED,
                    };
                }
                EventState::Confirmed {
                    at: was,
                    event_id,
                    period,
                    last,
                } if now >= last + period * 3 + SILENCE_MARGIN => {
                    s.stats.events_lapsed += 1;
                    tracing::warn!(component = %was, ?role, event = event_id, "event silent: the query is polled, the event created again");
                    let request_id = self.request_id();
                    s.send(
                        was,
                        CancelEvent {
                            request_id,
                            event_id,
                        },
                    );
                    let earliest = self.last_create[i].map_or(now, |t| t + MIN_CREATE_INTERVAL);
                    if now >= earliest {
                        self.create(now, i, at, s);
                    } else {
                        self.slots[i] = EventState::Polling { retry: earliest };
                    }
                }
                EventState::Polling { retry } if now >= retry => self.create(now, i, at, s),
                _ => {}
            }
        }
    }

    fn request_id(&mut self) -> u8 {
        let id = self.next_request;
        self.next_request = self.next_request.wrapping_add(1);
        id
    }

    fn create(&mut self, now: Instant, i: usize, at: As4Id, s: &mut Shared) {
        let Some(query) = sensor_query(SENSORS[i]) else {
            return;
        };
        let query_message = match embedded::encode(&query) {
            Ok(b) => b,
            Err(e) => {
                s.stats.encode_errors += 1;
                tracing::warn!(
                    query = query.name(),
                    "query of Create Event not encoded: {e}"
                );
                self.slots[i] = EventState::Polling {
                    retry: now + RETRY_REFUSED,
                };
                return;
            }
        };
        let request_id = self.request_id();
        s.send(
            at,
            CreateEvent {
                request_id,
                event_type: EventType::Periodic,
                requested_periodic_rate: self.rate,
                query_message,
            },
        );
        self.last_create[i] = Some(now);
        self.slots[i] = EventState::Pending {
            at,
            request_id,
            sent: now,
        };
    }

    fn pending(&self, from: As4Id, request_id: u8) -> Option<usize> {
        self.slots.iter().position(|st| {
            matches!(st, EventState::Pending { at, request_id: r, .. } if *at == from && *r == request_id)
        })
    }

    /// Confirm Event Request from `from`: true if it answers one of its Create Events.
    pub fn confirmed(&mut self, now: Instant, from: As4Id, c: &ConfirmEventRequest) -> bool {
        let Some(i) = self.pending(from, c.request_id) else {
            return false;
        };
        // A rate of 0 (every change) is taken as the one asked for; the wire's steps of
        // 1092/65535 Hz may put a confirmed 0.1 Hz just below the range.
        let rate = if c.confirmed_periodic_rate > 0.0 {
            c.confirmed_periodic_rate.clamp(MIN_RATE, MAX_RATE)
        } else {
            self.rate
        };
        tracing::debug!(component = %from, role = ?SENSORS[i], event = c.event_id, rate, "event confirmed");
        self.slots[i] = EventState::Confirmed {
            at: from,
            event_id: c.event_id,
            period: Duration::from_secs_f64(1.0 / rate),
            last: now,
        };
        true
    }

    /// Reject Event Request from `from`: true if it answers one of its Create Events
    /// (the query is then polled; counted in `s`).
    pub fn rejected(
        &mut self,
        now: Instant,
        from: As4Id,
        r: &RejectEventRequest,
        s: &mut Shared,
    ) -> bool {
        let Some(i) = self.pending(from, r.request_id) else {
            return false;
        };
        s.stats.events_refused += 1;
        tracing::debug!(component = %from, role = ?SENSORS[i], code = ?r.response_code, reason = ?r.error_message, "Create Event refused: the query is polled");
        self.slots[i] = EventState::Polling {
            retry: now + RETRY_REFUSED,
        };
        true
    }

    /// Event from `from`: its report is kept in `s` as a polled one would be, and the
    /// matching confirmed event is alive. A report that does not decode or is not a
    /// sensor report is counted and dropped.
    pub fn event(&mut self, now: Instant, from: As4Id, e: &Event, s: &mut Shared) {
        let report = match e.report() {
            Ok(
                m @ (Message::ReportVelocityState(_)
                | Message::ReportGlobalPose(_)
                | Message::ReportLocalPose(_)),
            ) => m,
            Ok(other) => {
                s.stats.events_malformed += 1;
                tracing::debug!(component = %from, event = e.event_id, message = other.name(), "event report not a sensor report: dropped");
                return;
            }
            Err(err) => {
                s.stats.events_malformed += 1;
                tracing::debug!(component = %from, event = e.event_id, "event report does not decode: {err}");
                return;
            }
        };
        s.stats.events_received += 1;
        for st in &mut self.slots {
            if let EventState::Confirmed {
                at, event_id, last, ..
            } = st
            {
                if *at == from && *event_id == e.event_id {
                    *last = now;
                }
            }
        }
        s.keep(now, from, report);
    }

    /// The earliest time [`due`](Self::due) has something to do (a confirmation
    /// overdue, a confirmed event silent too long, a retry).
    pub fn next_timeout(&self) -> Option<Instant> {
        self.slots
            .iter()
            .filter_map(|st| match *st {
                EventState::Idle => None,
                EventState::Pending { sent, .. } => Some(sent + CONFIRM_TIMEOUT),
                EventState::Confirmed { period, last, .. } => {
                    Some(last + period * 3 + SILENCE_MARGIN)
                }
                EventState::Polling { retry } => Some(retry),
            })
            .min()
    }
}

fn slot_of(role: Role) -> Option<usize> {
    SENSORS.iter().position(|r| *r == role)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::messages::{EventRejection, ReportVelocityState};
    use crate::ra33::Frame;

    const ME: As4Id = As4Id::new(2, 1, 200);
    const AT: As4Id = As4Id::new(1, 1, 1);

    fn setup(t0: Instant) -> (SensorEvents, Shared) {
        let mut s = Shared::new(ME, Frame::default());
        for r in SENSORS {
            s.found(r, AT);
        }
        let mut ev = SensorEvents::new(Duration::from_millis(100));
        ev.due(t0, &SENSORS, &mut s);
        (ev, s)
    }

    fn creates(s: &mut Shared) -> Vec<CreateEvent> {
        s.take_outgoing()
            .into_iter()
            .filter_map(|(_, m)| match m {
                Message::CreateEvent(c) => Some(c),
                _ => None,
            })
            .collect()
    }

    /// Query Local Pose asks for bits 0-8 (what Report Local Pose defines), not 0xFFFF.
    #[test]
    fn the_sensor_queries_ask_for_the_defined_bits_only() {
        let asked = |role| match sensor_query(role) {
            Some(Message::QueryVelocityState(q)) => q.presence_vector,
            Some(Message::QueryGlobalPose(q)) => q.presence_vector,
            Some(Message::QueryLocalPose(q)) => q.presence_vector,
            other => panic!("{other:?}"),
        };
        for role in SENSORS {
            assert_eq!(asked(role), 0x01FF, "{role:?}");
        }
        assert_eq!(sensor_query(Role::PrimitiveDriver), None);
    }

    #[test]
    fn rate_is_clamped() {
        assert_eq!(rate_for(Duration::from_millis(100)), 10.0);
        assert_eq!(rate_for(Duration::from_millis(1)), MAX_RATE);
        assert_eq!(rate_for(Duration::from_secs(60)), MIN_RATE);
        assert_eq!(rate_for(Duration::ZERO), MAX_RATE);
    }

    #[test]
    fn confirm_reject_timeout_and_lapse() {
        let t0 = Instant::now();
        let (mut ev, mut s) = setup(t0);
        let c = creates(&mut s);
        assert_eq!(c.len(), 3);
        assert!(c.iter().all(|c| c.event_type == EventType::Periodic));
        assert_eq!(
            embedded::decode(&c[0].query_message).unwrap(),
            sensor_query(Role::VelocityStateSensor).unwrap()
        );
        // Velocity confirmed, global pose refused, local pose unanswered.
        let conf = ConfirmEventRequest {
            request_id: c[0].request_id,
            event_id: 7,
            confirmed_periodic_rate: 10.0,
        };
        assert!(!ev.confirmed(t0, As4Id::new(9, 9, 9), &conf));
        assert!(ev.confirmed(t0, AT, &conf));
        assert!(!ev.polls(Role::VelocityStateSensor));
        let rej = RejectEventRequest {
            request_id: c[1].request_id,
            response_code: Some(EventRejection::MessageNotSupported),
            error_message: None,
        };
        assert!(ev.rejected(t0, AT, &rej, &mut s));
        assert!(ev.polls(Role::GlobalPoseSensor));
        assert_eq!(s.stats.events_refused, 1);

        // Events keep the velocity event alive; a malformed one is counted.
        let report = embedded::encode(&ReportVelocityState::default().into()).unwrap();
        let mut t = t0;
        for n in 0..10u8 {
            t += Duration::from_millis(100);
            let e = Event {
                event_id: 7,
                sequence_number: n,
                report_message: report.clone(),
            };
            ev.event(t, AT, &e, &mut s);
            ev.due(t, &SENSORS, &mut s);
        }
        assert_eq!(s.stats.events_received, 10);
        assert!(!ev.polls(Role::VelocityStateSensor));
        // Local pose unanswered for a second: polled.
        ev.due(t, &SENSORS, &mut s);
        assert!(ev.polls(Role::LocalPoseSensor));
        assert!(matches!(
            ev.state(Role::LocalPoseSensor),
            Some(EventState::Polling { .. })
        ));
        assert_eq!(s.stats.events_refused, 2);
        let bad = Event {
            event_id: 7,
            sequence_number: 10,
            report_message: vec![0x04],
        };
        ev.event(t, AT, &bad, &mut s);
        assert_eq!(s.stats.events_malformed, 1);
        assert_eq!(s.stats.events_received, 10);

        // Silence: polled again, cancelled and created again.
        s.take_outgoing();
        ev.due(t + Duration::from_millis(850), &SENSORS, &mut s);
        assert!(ev.polls(Role::VelocityStateSensor));
        assert_eq!(s.stats.events_lapsed, 1);
        let out = s.take_outgoing();
        assert!(out
            .iter()
            .any(|(_, m)| matches!(m, Message::CancelEvent(c) if c.event_id == 7)));
        assert_eq!(
            out.iter()
                .filter(|(_, m)| matches!(m, Message::CreateEvent(_)))
                .count(),
            1
        );
        assert!(ev.next_timeout().is_some());
    }
}
