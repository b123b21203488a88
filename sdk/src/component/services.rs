//! The core messages the runtime handles itself: core state commands, authority,
//! control, time, service connections (provider and requester side) and events.

use std::time::{Duration, Instant};

use super::{
    Behaviour, Component, Controller, CoreState, CoreTransition, Interface, Refusal, Refused,
};
use crate::messages::*;
use crate::{Address, CommandCode, Header};

/// JAUS rates are scaled u16 over [0, 1092] Hz.
const MAX_JAUS_RATE: f64 = 1092.0;

fn period_of(rate_hz: f64) -> Duration {
    Duration::from_secs_f64(1.0 / rate_hz)
}

/// One service connection this component serves.
#[derive(Debug, Clone)]
struct ServedConnection {
    requester: Address,
    report: CommandCode,
    instance: u8,
    presence: u32,
    query: Message,
    period: Duration,
    next_due: Instant,
    active: bool,
    sequence: u16,
}

#[derive(Debug, Default)]
pub(super) struct ProviderTable {
    served: Vec<ServedConnection>,
}

impl ProviderTable {
    pub(super) fn len(&self) -> usize {
        self.served.len()
    }

    pub(super) fn next_due(&self) -> Option<Instant> {
        self.served
            .iter()
            .filter(|s| s.active)
            .map(|s| s.next_due)
            .min()
    }

    pub(super) fn remove_requester(&mut self, gone: Address) {
        self.served.retain(|s| s.requester != gone);
    }

    fn find(
        &mut self,
        requester: Address,
        report: u16,
        instance: u8,
    ) -> Option<&mut ServedConnection> {
        self.served
            .iter_mut()
            .find(|s| s.requester == requester && s.report.0 == report && s.instance == instance)
    }
}

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
struct ServedEvent {
    requester: Address,
    id: u8,
    report: CommandCode,
    event_type: EventType,
    query: Message,
    trigger: Trigger,
    last: Option<Vec<u8>>,
    sequence: u8,
    setup: EventRecord,
}

#[derive(Debug, Default)]
pub(super) struct EventTable {
    events: Vec<ServedEvent>,
}

impl EventTable {
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

    fn free_id(&self) -> Option<u8> {
        (0..=254u8).find(|id| !self.events.iter().any(|e| e.id == *id))
    }
}

/// A service connection this component asked for.
#[derive(Debug, Clone)]
struct Subscription {
    provider: Address,
    report: CommandCode,
    instance: Option<u8>,
}

#[derive(Debug, Default)]
pub(super) struct RequesterTable {
    subs: Vec<Subscription>,
}

impl RequesterTable {
    pub(super) fn add(
        &mut self,
        provider: Address,
        report: CommandCode,
        _rate: f64,
        _pv: u32,
        max: usize,
    ) -> bool {
        if self
            .subs
            .iter()
            .any(|s| s.provider == provider && s.report == report)
        {
            return true;
        }
        if self.subs.len() >= max {
            return false;
        }
        self.subs.push(Subscription {
            provider,
            report,
            instance: None,
        });
        true
    }

    pub(super) fn remove(&mut self, provider: Address, report: CommandCode) -> Option<u8> {
        let i = self
            .subs
            .iter()
            .position(|s| s.provider == provider && s.report == report)?;
        self.subs.remove(i).instance
    }

    pub(super) fn is_active(&self, provider: Address, report: CommandCode) -> bool {
        self.subs
            .iter()
            .any(|s| s.provider == provider && s.report == report && s.instance.is_some())
    }
}

/// The query whose report a service connection or event streams, built from the
/// report code and a presence vector: the query body is the presence vector in the
/// query's own width (0, 1, 2 or 4 bytes, whichever decodes), so no per-message table
/// is needed.
fn query_for(report: CommandCode, presence: u32) -> Option<Message> {
    let code = report.complement()?;
    if report.0 < 0x4000 {
        return None;
    }
    let bytes = presence.to_le_bytes();
    [0usize, 1, 2, 4]
        .into_iter()
        .find_map(|n| Message::decode(code, &bytes[..n]).ok())
}

impl<B: Behaviour> Component<B> {
    /// Handles a core message; `None` when `msg` is not one.
    pub(super) fn core_message(
        &mut self,
        header: &Header,
        msg: &Message,
    ) -> Option<Result<(), Refusal>> {
        let source = header.source;
        let controlled = |c: &Self| {
            if c.core.may_command(source) {
                Ok(())
            } else {
                Err(Refusal::NotController)
            }
        };
        let transition = |c: &mut Self, t: CoreTransition| -> Result<(), Refusal> {
            controlled(c)?;
            c.core
                .set_state(t)
                .map(|_| ())
                .map_err(|_| Refusal::State(c.core.state))
        };
        let r = match msg {
            Message::SetComponentAuthority(m) => controlled(self).map(|()| {
                self.core.authority = m.authority_code;
            }),
            Message::Shutdown(_) => transition(self, CoreTransition::Shutdown),
            Message::Standby(_) => transition(self, CoreTransition::Standby),
            Message::Resume(_) => transition(self, CoreTransition::Resume),
            Message::Reset(_) => transition(self, CoreTransition::Reset),
            Message::SetEmergency(_) => {
                self.set_emergency(source);
                Ok(())
            }
            Message::ClearEmergency(_) => {
                self.clear_emergency(source);
                Ok(())
            }
            Message::SetTime(m) => controlled(self).and_then(|()| {
                let now = self.core.now;
                if self
                    .core
                    .clock
                    .apply(now, m.time_stamp.as_ref(), m.date_stamp.as_ref())
                {
                    Ok(())
                } else {
                    Err(Refusal::Vendor(Refused::Invalid(
                        "Set Time carries an impossible date or time".into(),
                    )))
                }
            }),
            Message::RequestComponentControl(m) => {
                self.request_control(source, m.authority_code);
                Ok(())
            }
            Message::ReleaseComponentControl(_) => match self.core.controller {
                Some(c) if c.address == source => {
                    self.core.controller = None;
                    Ok(())
                }
                _ => Err(Refusal::NotController),
            },
            Message::ConfirmComponentControl(m) => {
                if m.response_code == ControlResponse::ControlAccepted {
                    if !self.core.held_control.contains(&source)
                        && self.core.held_control.len() < 64
                    {
                        self.core.held_control.push(source);
                    }
                } else {
                    self.core.held_control.retain(|a| *a != source);
                }
                return Some(self.pass_on(header, msg));
            }
            Message::RejectComponentControl(_) => {
                self.core.held_control.retain(|a| *a != source);
                return Some(self.pass_on(header, msg));
            }
            Message::CreateServiceConnection(m) => {
                self.create_sc(source, m);
                Ok(())
            }
            Message::ActivateServiceConnection(m) => self.sc_set_active(
                source,
                m.service_connection_command_code,
                m.instance_id,
                true,
            ),
            Message::SuspendServiceConnection(m) => self.sc_set_active(
                source,
                m.service_connection_command_code,
                m.instance_id,
                false,
            ),
            Message::TerminateServiceConnection(m) => {
                let (code, inst) = (m.service_connection_command_code, m.instance_id);
                let before = self.core.provider.served.len();
                self.core.provider.served.retain(|s| {
                    !(s.requester == source && s.report.0 == code && s.instance == inst)
                });
                if before == self.core.provider.served.len() {
                    // A provider ending a connection this component requested.
                    self.core.requester.subs.retain(|s| {
                        !(s.provider == source && s.report.0 == code && s.instance == Some(inst))
                    });
                }
                Ok(())
            }
            Message::ConfirmServiceConnection(m) => {
                self.confirm_sc(source, m);
                return Some(self.pass_on(header, msg));
            }
            Message::CreateEvent(m) => {
                self.create_event(source, m.request_id, EventSetup::from_create(m), None);
                Ok(())
            }
            Message::UpdateEvent(m) => {
                self.create_event(
                    source,
                    m.request_id,
                    EventSetup::from_update(m),
                    Some(m.event_id),
                );
                Ok(())
            }
            Message::CancelEvent(m) => {
                self.cancel_event(source, m);
                Ok(())
            }
            Message::QueryIdentification(q) if q.query_field != QueryLevel::Component => {
                return None;
            }
            m => {
                let reply = self.core_report(m)?;
                self.core.send(source, reply, false, 0);
                Ok(())
            }
        };
        Some(r)
    }

    /// Hands a core message the runtime has already acted on to the behaviour too
    /// (replies to requests the component made).
    fn pass_on(&mut self, header: &Header, msg: &Message) -> Result<(), Refusal> {
        let _ = header;
        let r = self.behaviour.handle(
            &mut super::Context {
                core: &mut self.core,
                _i: std::marker::PhantomData,
            },
            msg,
        );
        match r {
            Ok(_) | Err(Refused::Unsupported) => Ok(()),
            Err(e) => Err(Refusal::Vendor(e)),
        }
    }

    fn set_emergency(&mut self, source: Address) {
        let c = &mut self.core;
        if !c.emergencies.contains(&source) {
            if c.emergencies.len() < c.config.max_emergency_senders {
                c.emergencies.push(source);
            } else {
                c.stats.emergency_overflow += 1;
            }
        }
        tracing::warn!(component = <B::Interface as Interface>::NAME, address = %c.address, source = %source, "emergency set");
        if c.set_state(CoreTransition::SetEmergency).is_err() {
            c.stats.wrong_state += 1;
        }
    }

    fn clear_emergency(&mut self, source: Address) {
        let c = &mut self.core;
        let before = c.emergencies.len();
        c.emergencies.retain(|a| *a != source);
        if c.emergencies.len() == before {
            c.stats.foreign_clear_emergency += 1;
            tracing::warn!(
                component = <B::Interface as Interface>::NAME,
                address = %c.address,
                source = %source,
                "Clear Emergency ignored: this sender set no emergency"
            );
            return;
        }
        if c.emergencies.is_empty() && c.state == CoreState::Emergency {
            let _ = c.set_state(CoreTransition::ClearEmergency);
        }
    }

    /// Request Component Control (WIRE.md §5.3, plus the own-authority check).
    fn request_control(&mut self, source: Address, authority: u8) {
        let c = &mut self.core;
        let confirm =
            |r: ControlResponse| -> Message { ConfirmComponentControl { response_code: r }.into() };
        if c.state == CoreState::Shutdown {
            c.send(source, confirm(ControlResponse::NotAvailable), false, 0);
            return;
        }
        if authority < c.authority {
            c.send(
                source,
                confirm(ControlResponse::InsufficientAuthority),
                false,
                0,
            );
            return;
        }
        match c.controller {
            None => {
                c.controller = Some(Controller {
                    address: source,
                    authority,
                });
                c.send(source, confirm(ControlResponse::ControlAccepted), false, 0);
            }
            Some(cur) if cur.address == source => {
                c.controller = Some(Controller {
                    address: source,
                    authority,
                });
                c.send(source, confirm(ControlResponse::ControlAccepted), false, 0);
            }
            Some(cur) if authority > cur.authority => {
                c.send(cur.address, RejectComponentControl {}.into(), false, 0);
                c.controller = Some(Controller {
                    address: source,
                    authority,
                });
                c.send(source, confirm(ControlResponse::ControlAccepted), false, 0);
            }
            Some(_) => c.send(source, RejectComponentControl {}.into(), false, 0),
        }
    }

    fn create_sc(&mut self, source: Address, m: &CreateServiceConnection) {
        let report = CommandCode(m.service_connection_command_code);
        let rate = m.requested_periodic_update_rate;
        let refuse = |c: &mut Self, code: ServiceConnectionResponse| {
            c.core.stats.subscriptions_refused += 1;
            let msg = ConfirmServiceConnection {
                service_connection_command_code: report.0,
                instance_id: 0,
                confirmed_periodic_update_rate: 0.0,
                response_code: code,
            };
            c.core.send(source, msg.into(), true, 0);
        };
        let Some(query) = query_for(report, m.presence_vector) else {
            return refuse(self, ServiceConnectionResponse::ComponentNotCapable);
        };
        if !(rate.is_finite() && rate > 0.0) {
            return refuse(self, ServiceConnectionResponse::InvalidParameter);
        }
        match self.answer(source, &query) {
            Ok(_) => {}
            Err(Refused::Unsupported) => {
                return refuse(self, ServiceConnectionResponse::ComponentNotCapable)
            }
            Err(_) => return refuse(self, ServiceConnectionResponse::InvalidParameter),
        }
        let granted = rate.min(self.core.config.max_rate_hz).min(MAX_JAUS_RATE);
        let now = self.core.now;
        let table = &mut self.core.provider.served;
        // Same requester, code and presence vector: re-initialise that connection.
        let existing = table.iter().position(|s| {
            s.requester == source && s.report == report && s.presence == m.presence_vector
        });
        let instance = match existing {
            Some(i) => table[i].instance,
            None => {
                if table.len() >= self.core.config.max_service_connections {
                    return refuse(self, ServiceConnectionResponse::ConnectionRefused);
                }
                match (0..=255u8).find(|i| {
                    !table
                        .iter()
                        .any(|s| s.requester == source && s.report == report && s.instance == *i)
                }) {
                    Some(i) => i,
                    None => return refuse(self, ServiceConnectionResponse::ConnectionRefused),
                }
            }
        };
        let served = ServedConnection {
            requester: source,
            report,
            instance,
            presence: m.presence_vector,
            query,
            period: period_of(granted),
            next_due: now,
            active: true,
            sequence: 0,
        };
        match existing {
            Some(i) => table[i] = served,
            None => table.push(served),
        }
        let msg = ConfirmServiceConnection {
            service_connection_command_code: report.0,
            instance_id: instance,
            confirmed_periodic_update_rate: granted,
            response_code: ServiceConnectionResponse::Successful,
        };
        self.core.send(source, msg.into(), true, 0);
    }

    fn sc_set_active(
        &mut self,
        source: Address,
        code: u16,
        instance: u8,
        active: bool,
    ) -> Result<(), Refusal> {
        let now = self.core.now;
        match self.core.provider.find(source, code, instance) {
            Some(s) => {
                if active && !s.active {
                    s.next_due = now;
                }
                s.active = active;
                Ok(())
            }
            None => Err(Refusal::Vendor(Refused::Invalid(format!(
                "no service connection 0x{code:04X}/{instance} from {source}"
            )))),
        }
    }

    fn confirm_sc(&mut self, source: Address, m: &ConfirmServiceConnection) {
        let code = CommandCode(m.service_connection_command_code);
        let sub = self
            .core
            .requester
            .subs
            .iter_mut()
            .find(|s| s.provider == source && s.report == code);
        match (sub, m.response_code) {
            (Some(s), ServiceConnectionResponse::Successful) => s.instance = Some(m.instance_id),
            (Some(_), _) => {
                self.core
                    .requester
                    .subs
                    .retain(|s| !(s.provider == source && s.report == code));
            }
            (None, ServiceConnectionResponse::Successful) => {
                // A connection nobody here asked for: end it (as OpenJAUS does).
                let t = TerminateServiceConnection {
                    service_connection_command_code: code.0,
                    instance_id: m.instance_id,
                };
                self.core.send(source, t.into(), true, 0);
            }
            (None, _) => {}
        }
    }

    pub(super) fn run_service_connections(&mut self, now: Instant) {
        for i in 0..self.core.provider.served.len() {
            let s = &self.core.provider.served[i];
            if !s.active || s.next_due > now {
                continue;
            }
            let (requester, query) = (s.requester, s.query.clone());
            let result = self.answer(requester, &query);
            let s = &mut self.core.provider.served[i];
            s.next_due = super::next_after(s.next_due, s.period, now);
            match result {
                Ok(report) => {
                    let seq = s.sequence;
                    s.sequence = s.sequence.wrapping_add(1);
                    self.core.send(requester, report, true, seq);
                }
                Err(_) => self.core.stats.report_failures += 1,
            }
        }
    }

    fn create_event(
        &mut self,
        source: Address,
        request_id: u8,
        setup: EventSetup,
        update_of: Option<u8>,
    ) {
        let reject = |c: &mut Self, code: EventResponseCode, why: &str| {
            c.core.stats.subscriptions_refused += 1;
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
            c.core.send(source, msg.into(), false, 0);
        };
        let report = CommandCode(setup.report_code);
        let query = match &setup.query {
            Some(body) => match report.complement().map(|q| Message::decode(q, body)) {
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
        let now = self.core.now;
        let rate = setup
            .rate
            .or(setup.minimum_rate)
            .map(|r| r.min(self.core.config.max_rate_hz).min(MAX_JAUS_RATE));
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
        let table = &mut self.core.events;
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
                if table.events.len() >= self.core.config.max_events {
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
        self.core.events.events.push(ServedEvent {
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
        self.core.send(source, msg.into(), false, 0);
    }

    fn cancel_event(&mut self, source: Address, m: &CancelEvent) {
        let t = &mut self.core.events.events;
        let pos = t.iter().position(|e| {
            e.requester == source
                && m.event_id.is_none_or(|id| id == e.id)
                && m.message_code.is_none_or(|c| {
                    c == e.report.0 || Some(CommandCode(c)) == e.report.complement()
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
        self.core.send(source, reply, false, 0);
    }

    fn send_event(&mut self, i: usize, body: Vec<u8>) {
        let e = &mut self.core.events.events[i];
        let msg = Event {
            event_id: e.id,
            report_message_code: e.report.0,
            event_sequence_number: e.sequence,
            report_message: body.clone(),
        };
        e.sequence = e.sequence.wrapping_add(1);
        e.last = Some(body);
        let to = e.requester;
        self.core.send(to, msg.into(), false, 0);
    }

    pub(super) fn run_periodic_events(&mut self, now: Instant) {
        let mut i = 0;
        while i < self.core.events.events.len() {
            let e = &self.core.events.events[i];
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
                    let changed = self.core.events.events[i].last.as_ref() != Some(&b);
                    if !only_changed || changed {
                        self.send_event(i, b);
                    }
                }
                None => self.core.stats.report_failures += 1,
            }
            if one_time {
                self.core.events.events.remove(i);
                continue;
            }
            if let Trigger::Periodic { next_due, .. } = &mut self.core.events.events[i].trigger {
                *next_due = super::next_after(*next_due, period, now);
            }
            i += 1;
        }
    }

    pub(super) fn check_change_events(&mut self) {
        for i in 0..self.core.events.events.len() {
            let e = &self.core.events.events[i];
            if e.trigger != Trigger::EveryChange {
                continue;
            }
            let (requester, query) = (e.requester, e.query.clone());
            match self
                .answer(requester, &query)
                .ok()
                .and_then(|r| r.to_bytes_opt())
            {
                Some(b) if self.core.events.events[i].last.as_ref() != Some(&b) => {
                    self.send_event(i, b)
                }
                Some(_) => {}
                None => self.core.stats.report_failures += 1,
            }
        }
    }
}

/// The fields Create Event and Update Event share.
struct EventSetup {
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
            $(fn $f(m: &$m) -> Self {
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

impl ToBytesOpt for Message {
    fn to_bytes_opt(&self) -> Option<Vec<u8>> {
        use crate::codec::Encode;
        self.to_bytes().ok()
    }
}
