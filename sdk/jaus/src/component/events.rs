//! Events: the event table, Create/Update/Cancel Event, Query Events, and the periodic,
//! one-time and every-change events sent from it.

use std::time::{Duration, Instant};

use super::connections::{period_of, query_for, MAX_JAUS_RATE};
use super::{Behaviour, Component, Interface, Refused};
use crate::messages::*;
use crate::{Address, CommandCode, MessageSet};

/// What kind of event is served.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Trigger {
    /// Every period; `only_changed` for "periodic without replacement".
    Periodic {
        period: Duration,
        next_due: Instant,
        only_changed: bool,
    },
    /// Whenever the report changes (checked every tick).
    EveryChange,
}

#[derive(Debug, Clone)]
struct ServedEvent<M> {
    requester: Address,
    id: u8,
    report: CommandCode,
    event_type: EventType,
    query: M,
    trigger: Trigger,
    last: Option<Vec<u8>>,
    sequence: u8,
    setup: EventRecord,
}

#[derive(Debug)]
pub(super) struct EventTable<M> {
    events: Vec<ServedEvent<M>>,
}

impl<M> Default for EventTable<M> {
    fn default() -> Self {
        Self { events: Vec::new() }
    }
}

impl<M> EventTable<M> {
    pub(super) fn len(&self) -> usize {
        self.events.len()
    }

    pub(super) fn next_due(&self) -> Option<Instant> {
        self.events
            .iter()
            .filter_map(|e| match e.trigger {
                Trigger::Periodic { next_due, .. } => Some(next_due),
                Trigger::EveryChange => None,
            })
            .min()
    }

    pub(super) fn remove_requester(&mut self, gone: Address) {
        self.events.retain(|e| e.requester != gone);
    }

    pub(super) fn report(&self, q: &QueryEvents) -> ReportEvents {
        let events = self
            .events
            .iter()
            .filter(|e| q.message_code.is_none_or(|c| c == e.report.0))
            .filter(|e| q.event_type.is_none_or(|t| t == e.event_type))
            .filter(|e| q.event_id.is_none_or(|i| i == e.id))
            .map(|e| e.setup.clone())
            .collect();
        ReportEvents { events }
    }

    /// Whether `requester` holds an event on `report`.
    pub(super) fn has(&self, requester: Address, report: CommandCode) -> bool {
        self.events
            .iter()
            .any(|e| e.requester == requester && e.report == report)
    }

    fn free_id(&self) -> Option<u8> {
        (0..=254u8).find(|id| !self.events.iter().any(|e| e.id == *id))
    }
}

impl<B: Behaviour> Component<B> {
    pub(super) fn create_event(
        &mut self,
        source: Address,
        request_id: u8,
        setup: EventSetup,
        update_of: Option<u8>,
    ) {
        let reject = |c: &mut Self, code: EventResponseCode, why: &str| {
            c.rt.stats.subscriptions_refused += 1;
            tracing::debug!(
                component = <B::Interface as Interface>::NAME,
                source = %source,
                "event request {request_id} rejected: {why}"
            );
            let msg = RejectEventRequest {
                request_id,
                response_code: code,
                error_message: Some(why.to_string()),
            };
            c.rt.send(source, msg.into(), false, 0);
        };
        let report = CommandCode(setup.report_code);
        let query = match &setup.query {
            Some(body) => match <I<B> as Interface>::Messages::query_of(report)
                .map(|q| <I<B> as Interface>::Messages::decode(q, body))
            {
                Some(Ok(q)) => q,
                _ => {
                    return reject(
                        self,
                        EventResponseCode::InvalidEventSetup,
                        "the query message does not decode as the query of the report code",
                    )
                }
            },
            None => match query_for(report, u32::MAX) {
                Some(q) => q,
                None => {
                    return reject(
                        self,
                        EventResponseCode::MessageNotSupported,
                        "no query answers this report code",
                    )
                }
            },
        };
        match self.answer(source, &query) {
            Ok(_) => {}
            Err(Refused::Unsupported) => {
                return reject(
                    self,
                    EventResponseCode::MessageNotSupported,
                    "this component does not answer that query",
                )
            }
            Err(why) => {
                return reject(self, EventResponseCode::InvalidEventSetup, &why.to_string())
            }
        }
        let now = self.rt.now;
        let rate = setup
            .rate
            .or(setup.minimum_rate)
            .map(|r| r.min(self.rt.config.max_rate_hz).min(MAX_JAUS_RATE));
        let trigger = match setup.event_type {
            EventType::Periodic | EventType::PeriodicWithoutReplacement => match rate {
                Some(r) if r.is_finite() && r > 0.0 => Trigger::Periodic {
                    period: period_of(r),
                    next_due: now,
                    only_changed: setup.event_type == EventType::PeriodicWithoutReplacement,
                },
                _ => {
                    return reject(
                        self,
                        EventResponseCode::InvalidEventSetup,
                        "a periodic event needs a rate above 0 Hz",
                    )
                }
            },
            EventType::EveryChange => Trigger::EveryChange,
            EventType::OneTime => Trigger::Periodic {
                period: Duration::ZERO,
                next_due: now,
                only_changed: false,
            },
            _ => {
                return reject(
                    self,
                    EventResponseCode::ChangeBasedEventsNotSupported,
                    "boundary events (first change, in and out of boundary) are not supported",
                )
            }
        };
        let table = &mut self.rt.events;
        let id = match update_of {
            Some(id) => {
                let Some(i) = table
                    .events
                    .iter()
                    .position(|e| e.id == id && e.requester == source)
                else {
                    return reject(
                        self,
                        EventResponseCode::InvalidEventSetup,
                        "no such event to update",
                    );
                };
                table.events.remove(i);
                id
            }
            None => {
                if table.events.len() >= self.rt.config.max_events {
                    return reject(
                        self,
                        EventResponseCode::ConnectionRefused,
                        "event table full",
                    );
                }
                match table.free_id() {
                    Some(id) => id,
                    None => {
                        return reject(
                            self,
                            EventResponseCode::ConnectionRefused,
                            "no free event id",
                        )
                    }
                }
            }
        };
        // The baseline for change detection is the report now.
        let last = match trigger {
            Trigger::EveryChange => self
                .answer(source, &query)
                .ok()
                .and_then(|r| r.to_bytes_opt()),
            Trigger::Periodic { .. } => None,
        };
        let record = EventRecord {
            message_code: report.0,
            event_type: setup.event_type,
            event_boundary: setup.boundary,
            limit_data_field: setup.limit_field,
            lower_limit: setup.lower.clone(),
            upper_limit: setup.upper.clone(),
            state_limit: setup.state.clone(),
            event_id: Some(id),
            query_message: None,
        };
        self.rt.events.events.push(ServedEvent {
            requester: source,
            id,
            report,
            event_type: setup.event_type,
            query,
            trigger,
            last,
            sequence: 0,
            setup: record,
        });
        let msg = ConfirmEventRequest {
            request_id,
            message_code: report.0,
            event_id: id,
            confirmed_update_rate: Some(rate.unwrap_or(0.0)),
            response_code: EventResponseCode::Successful,
        };
        self.rt.send(source, msg.into(), false, 0);
    }

    pub(super) fn cancel_event(&mut self, source: Address, m: &CancelEvent) {
        let t = &mut self.rt.events.events;
        let pos = t.iter().position(|e| {
            e.requester == source
                && m.event_id.is_none_or(|id| id == e.id)
                && m.message_code.is_none_or(|c| {
                    c == e.report.0
                        || Some(CommandCode(c)) == <I<B> as Interface>::Messages::query_of(e.report)
                })
                && (m.event_id.is_some() || m.message_code.is_some())
        });
        let reply: Message = match pos {
            Some(i) => {
                let e = t.remove(i);
                ConfirmEventRequest {
                    request_id: m.request_id,
                    message_code: e.report.0,
                    event_id: e.id,
                    confirmed_update_rate: None,
                    response_code: EventResponseCode::Successful,
                }
                .into()
            }
            None => RejectEventRequest {
                request_id: m.request_id,
                response_code: EventResponseCode::InvalidEventSetup,
                error_message: Some("no such event".into()),
            }
            .into(),
        };
        self.rt.send(source, reply, false, 0);
    }

    fn send_event(&mut self, i: usize, body: Vec<u8>) {
        let e = &mut self.rt.events.events[i];
        let msg = Event {
            event_id: e.id,
            report_message_code: e.report.0,
            event_sequence_number: e.sequence,
            report_message: body.clone(),
        };
        e.sequence = e.sequence.wrapping_add(1);
        e.last = Some(body);
        let to = e.requester;
        self.rt.send(to, msg.into(), false, 0);
    }

    pub(super) fn run_periodic_events(&mut self, now: Instant) {
        let mut i = 0;
        while i < self.rt.events.events.len() {
            let e = &self.rt.events.events[i];
            let Trigger::Periodic {
                period,
                next_due,
                only_changed,
            } = e.trigger
            else {
                i += 1;
                continue;
            };
            if next_due > now {
                i += 1;
                continue;
            }
            let (requester, query) = (e.requester, e.query.clone());
            let body = self
                .answer(requester, &query)
                .ok()
                .and_then(|r| r.to_bytes_opt());
            let one_time = period.is_zero();
            match body {
                Some(b) => {
                    let changed = self.rt.events.events[i].last.as_ref() != Some(&b);
                    if !only_changed || changed {
                        self.send_event(i, b);
                    }
                }
                None => self.rt.stats.report_failures += 1,
            }
            if one_time {
                self.rt.events.events.remove(i);
                continue;
            }
            if let Trigger::Periodic { next_due, .. } = &mut self.rt.events.events[i].trigger {
                *next_due = super::next_after(*next_due, period, now);
            }
            i += 1;
        }
    }

    pub(super) fn check_change_events(&mut self) {
        for i in 0..self.rt.events.events.len() {
            let e = &self.rt.events.events[i];
            if e.trigger != Trigger::EveryChange {
                continue;
            }
            let (requester, query) = (e.requester, e.query.clone());
            match self
                .answer(requester, &query)
                .ok()
                .and_then(|r| r.to_bytes_opt())
            {
                Some(b) if self.rt.events.events[i].last.as_ref() != Some(&b) => {
                    self.send_event(i, b)
                }
                Some(_) => {}
                None => self.rt.stats.report_failures += 1,
            }
        }
    }
}

/// The fields Create Event and Update Event share.
pub(super) struct EventSetup {
    report_code: u16,
    event_type: EventType,
    boundary: Option<EventBoundary>,
    limit_field: Option<u8>,
    lower: Option<EventLimit>,
    upper: Option<EventLimit>,
    state: Option<EventLimit>,
    minimum_rate: Option<f64>,
    rate: Option<f64>,
    query: Option<Vec<u8>>,
}

/// Create Event and Update Event carry the same set-up fields (Update adds the event id).
macro_rules! event_setup_from {
    ($($m:ty => $f:ident),*) => {
        impl EventSetup {
            $(pub(super) fn $f(m: &$m) -> Self {
                Self {
                    report_code: m.report_message_code,
                    event_type: m.event_type,
                    boundary: m.event_boundary,
                    limit_field: m.limit_data_field,
                    lower: m.lower_limit.clone(),
                    upper: m.upper_limit.clone(),
                    state: m.state_limit.clone(),
                    minimum_rate: m.requested_minimum_rate,
                    rate: m.requested_update_rate,
                    query: m.query_message.clone(),
                }
            })*
        }
    };
}
event_setup_from!(CreateEvent => from_create, UpdateEvent => from_update);

trait ToBytesOpt {
    fn to_bytes_opt(&self) -> Option<Vec<u8>>;
}

impl<M: MessageSet> ToBytesOpt for M {
    fn to_bytes_opt(&self) -> Option<Vec<u8>> {
        self.to_bytes().ok()
    }
}

/// The interface of a behaviour.
type I<B> = <B as Behaviour>::Interface;
