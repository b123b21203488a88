//! Events (`urn:jaus:jss:core:Events` 1.1): subscriptions to the reports of any query
//! the component answers, sent periodically or on every change.
//!
//! * Create Event names a query (message ID and body). The component runs it as if the
//!   subscriber had sent it; a query nobody answers is refused (Reject Event Request
//!   `MessageNotSupported`), as is a body that does not decode or a message that is not
//!   a query (`InvalidEventSetup`, `MessageNotSupported`). A Create Event matching an
//!   event of the same subscriber (same type and query) updates that event.
//! * Periodic events are confirmed at the requested rate rounded to 0.01 Hz and
//!   clamped to [[`MIN_RATE`], [`MAX_RATE`]] Hz (a requested rate of 0 is
//!   `InvalidEventSetup`);
//!   reports are not queued: a late tick sends one report and the schedule moves on.
//! * Every-change events are confirmed at rate 0; the component runs their query every
//!   [`CoreConfig::change_period`](super::CoreConfig::change_period) (default
//!   [`DEFAULT_CHANGE_PERIOD`], 20 Hz) and sends the report when its bytes differ from
//!   the last one sent.
//! * Both kinds send their first report as soon as they are created. Each Event carries
//!   a sequence number per event, from 0, wrapping after 255.
//! * Update Event and Cancel Event name an event id that must exist and belong to the
//!   sender (`InvalidEventIdForUpdate` otherwise).
//! * With an event timeout (minutes, as Report Event Timeout gives it; 0 = none), an
//!   event not renewed by a Create or Update Event within it lapses and its subscriber
//!   gets a Confirm Event Request for it, as for a cancel.
//! * At most [`CoreConfig::max_events`](super::CoreConfig::max_events) events (and 255):
//!   more are refused with `ConnectionRefused` and counted.
//! * Create Command Event carries a command (message ID and body). The component checks
//!   it ([`command_of`]: it decodes, its message ID is a command's, it is not an Events
//!   message itself, and the Core or a service receives it), confirms it with a Confirm
//!   Event Request (an event id no subscription holds, rate 0), runs the command as if
//!   the client had sent it, and sends the client a Command Event: `Successful` when the
//!   Core or a service took it and it is done, `Unsuccessful` when it was refused (no
//!   control, not Ready, a guard) or taken by none. A command a service is still
//!   carrying out (`Service::in_progress`: Execute List until the list is done) keeps
//!   its event (and its id) until it is done (`Successful`), its
//!   `maximum_allowed_duration` (seconds; 0: none) lapses, or the component leaves
//!   Ready (`Unsuccessful`); running command events count against the events' bound.
//!   A command event that fails the check is refused (`MessageNotSupported` or
//!   `InvalidEventSetup`, with why).

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;

use crate::embedded;
use crate::messages::{
    CommandEvent, CommandResult, ConfirmEventRequest, Event, EventInfo, EventRejection, EventType,
    EventsFilter, Message, RejectEventRequest, ReportEventTimeout, ReportEvents,
};
use crate::outgoing::Outgoing;

/// Lowest periodic rate confirmed, Hz.
pub const MIN_RATE: f64 = 0.1;
/// Highest periodic rate confirmed, Hz.
pub const MAX_RATE: f64 = 50.0;
/// How often every-change events run their query (20 Hz).
pub const DEFAULT_CHANGE_PERIOD: Duration = Duration::from_millis(50);

/// A refusal: the reason code and a text for the log and the error message field.
pub type Rejection = (EventRejection, String);

/// The query of a Create or Update Event, decoded and checked to be a query.
pub fn query_of(bytes: &[u8]) -> Result<Message, Rejection> {
    let m = embedded::decode(bytes).map_err(|e| {
        (
            EventRejection::InvalidEventSetup,
            format!("query does not decode: {e}"),
        )
    })?;
    // A query by the definitions: a message that names its report, or of the query
    // class. A message outside them (a vendor's, undecoded) may be anything: whether
    // something answers it decides.
    let code = m.code();
    let info = crate::messages::MESSAGES.iter().find(|i| i.code == code);
    if info.is_some_and(|i| i.report.is_none() && i.class != jaus::wire::MessageClass::Query) {
        return Err((
            EventRejection::MessageNotSupported,
            format!("{} ({:#06X}) is not a query", m.name(), code.0),
        ));
    }
    Ok(m)
}

/// The command of a Create Command Event, decoded, or why it cannot be one: it does not
/// decode (`InvalidEventSetup`), its message ID is not a command's (0x0000–0x1FFF) nor an
/// experimental one, or it is an Events message itself (`MessageNotSupported`). Whether something receives it is the
/// component's to say.
pub fn command_of(bytes: &[u8]) -> Result<Message, Rejection> {
    let m = embedded::decode(bytes).map_err(|e| {
        (
            EventRejection::InvalidEventSetup,
            format!("command does not decode: {e}"),
        )
    })?;
    let code = m.code();
    let not = |what: &str| {
        Err((
            EventRejection::MessageNotSupported,
            format!("{} ({:#06X}) {what}", m.name(), code.0),
        ))
    };
    if matches!(
        m,
        Message::CreateEvent(_)
            | Message::UpdateEvent(_)
            | Message::CancelEvent(_)
            | Message::CreateCommandEvent(_)
    ) {
        return not("is an Events message: not run as a command event");
    }
    // A command by its message ID, as AS-4 classes messages: the published sets mark
    // some commands `is_command="false"` (Mobility's Execute List), which says whether
    // they need control, not what they are. An experimental ID (0xD000 and up, a
    // vendor's) has no class: the component takes it when a service that receives it
    // says it needs control.
    use jaus::wire::MessageClass;
    if !matches!(
        code.class(),
        MessageClass::Command | MessageClass::Experimental
    ) {
        return not("is not a command");
    }
    Ok(m)
}

/// A command event confirmed, its command not run yet (or still running).
#[derive(Debug, Clone)]
pub struct PendingCommand {
    /// The client that asked for it: the command runs as if it had sent it.
    pub client: As4Id,
    /// The event id confirmed.
    pub event_id: u8,
    /// The command.
    pub command: Message,
    /// The longest the command may run, seconds (0: no limit).
    pub max_duration: u32,
}

/// How often running commands are looked at when nothing else happens.
pub const COMMAND_CHECK_PERIOD: Duration = Duration::from_millis(100);

impl PendingCommand {
    /// The Command Event that reports its outcome to the client.
    pub fn completed(&self, successful: bool) -> Outgoing {
        let command_result = if successful {
            CommandResult::Successful
        } else {
            CommandResult::Unsuccessful
        };
        Outgoing::new(
            self.client,
            CommandEvent {
                event_id: self.event_id,
                command_result,
            },
        )
    }
}

/// Reject Event Request for `request_id` to `to`.
pub fn reject(to: As4Id, request_id: u8, (code, text): Rejection) -> Outgoing {
    let mut text = text;
    text.truncate(80);
    Outgoing::new(
        to,
        RejectEventRequest {
            request_id,
            response_code: Some(code),
            error_message: Some(text),
        },
    )
}

#[derive(Debug, Clone)]
struct Subscription {
    subscriber: As4Id,
    kind: EventType,
    rate: f64,
    query_bytes: Vec<u8>,
    query: Message,
    sequence: u8,
    next_due: Instant,
    last_report: Option<Vec<u8>>,
    renewed: Instant,
    request_id: u8,
}

/// The events a component maintains.
#[derive(Debug, Clone)]
pub struct Events {
    subs: BTreeMap<u8, Subscription>,
    /// The command of the command event just confirmed, for the component to run.
    command: Option<PendingCommand>,
    /// Command events whose command is still being carried out, with their deadline.
    running: Vec<(PendingCommand, Option<Instant>)>,
    /// When the running commands are next looked at.
    next_check: Option<Instant>,
    max: usize,
    timeout_minutes: u8,
    change_period: Duration,
}

/// What a Create or Update Event asks for.
#[derive(Debug, Clone)]
pub struct Setup<'a> {
    /// The client's request id.
    pub request_id: u8,
    /// Periodic or every change.
    pub kind: EventType,
    /// Requested rate, Hz.
    pub rate: f64,
    /// The query as sent.
    pub query_bytes: &'a [u8],
    /// The query decoded.
    pub query: Message,
}

impl Events {
    /// No events; at most `max` of them, lapsing after `timeout_minutes` (0 = never),
    /// every-change queries run every `change_period`.
    pub fn new(max: usize, timeout_minutes: u8, change_period: Duration) -> Self {
        Self {
            subs: BTreeMap::new(),
            command: None,
            running: Vec::new(),
            next_check: None,
            max: max.min(255),
            timeout_minutes,
            change_period: change_period.max(Duration::from_millis(1)),
        }
    }

    /// Number of events.
    pub fn len(&self) -> usize {
        self.subs.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.subs.is_empty()
    }

    fn confirmed_rate(setup: &Setup<'_>) -> Result<f64, Rejection> {
        match setup.kind {
            EventType::EveryChange => Ok(0.0),
            // The wire carries rates in steps of 1092/65535 Hz: 10 Hz arrives as
            // 9.9997 Hz. Rounded to 0.01 Hz, the rate is the one the client meant.
            EventType::Periodic if setup.rate > 0.0 => {
                Ok(((setup.rate * 100.0).round() / 100.0).clamp(MIN_RATE, MAX_RATE))
            }
            EventType::Periodic => Err((
                EventRejection::InvalidEventSetup,
                "periodic event at rate 0".into(),
            )),
            EventType::Unknown(t) => Err((
                EventRejection::InvalidEventSetup,
                format!("unknown event type {t}"),
            )),
        }
    }

    /// Create Event from `from` whose query the component answers.
    pub fn create(&mut self, now: Instant, from: As4Id, setup: Setup<'_>) -> Outgoing {
        let request_id = setup.request_id;
        let rate = match Self::confirmed_rate(&setup) {
            Ok(r) => r,
            Err(r) => return reject(from, request_id, r),
        };
        let existing = self.subs.iter().find_map(|(id, s)| {
            (s.subscriber == from && s.kind == setup.kind && s.query_bytes == setup.query_bytes)
                .then_some(*id)
        });
        let id = match existing {
            Some(id) => id,
            None if self.subs.len() >= self.max => {
                return reject(
                    from,
                    request_id,
                    (
                        EventRejection::ConnectionRefused,
                        format!("at most {} events", self.max),
                    ),
                )
            }
            None => match (0..=254u8).find(|i| !self.subs.contains_key(i)) {
                Some(id) => id,
                None => {
                    return reject(
                        from,
                        request_id,
                        (EventRejection::ConnectionRefused, "no free event id".into()),
                    )
                }
            },
        };
        self.install(now, from, id, rate, setup);
        Self::confirm(from, request_id, id, rate)
    }

    /// Update Event from `from` for event `event_id`.
    pub fn update(
        &mut self,
        now: Instant,
        from: As4Id,
        event_id: u8,
        setup: Setup<'_>,
    ) -> Outgoing {
        let request_id = setup.request_id;
        if self
            .subs
            .get(&event_id)
            .is_none_or(|s| s.subscriber != from)
        {
            return reject(from, request_id, no_event(event_id));
        }
        let rate = match Self::confirmed_rate(&setup) {
            Ok(r) => r,
            Err(r) => return reject(from, request_id, r),
        };
        self.install(now, from, event_id, rate, setup);
        Self::confirm(from, request_id, event_id, rate)
    }

    fn install(&mut self, now: Instant, from: As4Id, id: u8, rate: f64, setup: Setup<'_>) {
        let sequence = self.subs.get(&id).map_or(0, |s| s.sequence);
        self.subs.insert(
            id,
            Subscription {
                subscriber: from,
                kind: setup.kind,
                rate,
                query_bytes: setup.query_bytes.to_vec(),
                query: setup.query,
                sequence,
                next_due: now,
                last_report: None,
                renewed: now,
                request_id: setup.request_id,
            },
        );
    }

    /// Create Command Event from `from` whose command the component takes: a Confirm
    /// Event Request under an event id no subscription holds, the command queued for
    /// the component ([`take_command`](Self::take_command)); refused with
    /// `ConnectionRefused` when every id is held.
    pub fn create_command(
        &mut self,
        from: As4Id,
        request_id: u8,
        command: Message,
        max_duration: u32,
    ) -> Outgoing {
        if self.subs.len() + self.running.len() >= self.max {
            let why = (
                EventRejection::ConnectionRefused,
                format!("at most {} events", self.max),
            );
            return reject(from, request_id, why);
        }
        let held = |i: &u8| {
            self.subs.contains_key(i) || self.running.iter().any(|(p, _)| p.event_id == *i)
        };
        let Some(event_id) = (0..=254u8).find(|i| !held(i)) else {
            let why = (EventRejection::ConnectionRefused, "no free event id".into());
            return reject(from, request_id, why);
        };
        self.command = Some(PendingCommand {
            client: from,
            event_id,
            command,
            max_duration,
        });
        Self::confirm(from, request_id, event_id, 0.0)
    }

    /// `pending`'s command was taken at `now` and is still being carried out: its
    /// Command Event waits ([`finish_running`](Self::finish_running)), at most its
    /// maximum duration (none when 0).
    pub fn keep_running(&mut self, now: Instant, pending: PendingCommand) {
        let deadline = (pending.max_duration > 0)
            .then(|| now + Duration::from_secs(u64::from(pending.max_duration)));
        self.running.push((pending, deadline));
        self.next_check = Some(now + COMMAND_CHECK_PERIOD);
    }

    /// Command events still running.
    pub fn running_commands(&self) -> usize {
        self.running.len()
    }

    /// The Command Events of the running commands that ended at `now`: `Successful` for
    /// one no longer `in_progress`, `Unsuccessful` for one past its maximum duration or
    /// interrupted (the component not `ready` any more).
    pub fn finish_running(
        &mut self,
        now: Instant,
        ready: bool,
        in_progress: impl Fn(jaus::CommandCode) -> bool,
    ) -> Vec<Outgoing> {
        if self.running.is_empty() {
            self.next_check = None;
            return Vec::new();
        }
        let mut out = Vec::new();
        self.running.retain(|(p, deadline)| {
            let expired = deadline.is_some_and(|d| now >= d);
            let done = !in_progress(p.command.code());
            let outcome = if !ready || expired {
                Some(false)
            } else if done {
                Some(true)
            } else {
                None
            };
            match outcome {
                Some(ok) => {
                    tracing::debug!(
                        event_id = p.event_id,
                        command = p.command.name(),
                        ok,
                        expired,
                        "command event ended"
                    );
                    out.push(p.completed(ok));
                    false
                }
                None => true,
            }
        });
        self.next_check = (!self.running.is_empty()).then(|| now + COMMAND_CHECK_PERIOD);
        out
    }

    /// The command of the command event just confirmed, to run once.
    pub fn take_command(&mut self) -> Option<PendingCommand> {
        self.command.take()
    }

    /// Cancel Event from `from`.
    pub fn cancel(&mut self, from: As4Id, request_id: u8, event_id: u8) -> Outgoing {
        match self.subs.get(&event_id) {
            Some(s) if s.subscriber == from => {
                let rate = s.rate;
                self.subs.remove(&event_id);
                Self::confirm(from, request_id, event_id, rate)
            }
            _ => reject(from, request_id, no_event(event_id)),
        }
    }

    fn confirm(to: As4Id, request_id: u8, event_id: u8, rate: f64) -> Outgoing {
        Outgoing::new(
            to,
            ConfirmEventRequest {
                request_id,
                event_id,
                confirmed_periodic_rate: rate,
            },
        )
    }

    /// The events whose query is due at `now`: (event id, subscriber, query).
    pub fn due(&self, now: Instant) -> Vec<(u8, As4Id, Message)> {
        self.subs
            .iter()
            .filter(|(_, s)| s.next_due <= now)
            .map(|(id, s)| (*id, s.subscriber, s.query.clone()))
            .collect()
    }

    /// Event `id`'s query was run at `now` and gave `report` (`None`: nobody answered
    /// it this time). The Event to send, if any; the schedule moves on either way.
    pub fn fire(&mut self, now: Instant, id: u8, report: Option<&Message>) -> Option<Outgoing> {
        let period = self.change_period;
        let s = self.subs.get_mut(&id)?;
        let step = match s.kind {
            EventType::Periodic => Duration::from_secs_f64(1.0 / s.rate.max(MIN_RATE)),
            _ => period,
        };
        s.next_due += step;
        if s.next_due <= now {
            s.next_due = now + step;
        }
        let bytes = match report.map(embedded::encode) {
            Some(Ok(b)) => b,
            Some(Err(e)) => {
                tracing::warn!(event = id, "event report not encoded: {e}");
                return None;
            }
            None => return None,
        };
        if s.kind == EventType::EveryChange && s.last_report.as_deref() == Some(&bytes[..]) {
            return None;
        }
        let sequence_number = s.sequence;
        s.sequence = s.sequence.wrapping_add(1);
        s.last_report = Some(bytes.clone());
        Some(Outgoing::new(
            s.subscriber,
            Event {
                event_id: id,
                sequence_number,
                report_message: bytes,
            },
        ))
    }

    /// Events not renewed within the timeout lapse: a Confirm Event Request to each
    /// subscriber.
    pub fn expire(&mut self, now: Instant) -> Vec<Outgoing> {
        let Some(limit) = self.lifetime() else {
            return Vec::new();
        };
        let gone: Vec<u8> = self
            .subs
            .iter()
            .filter(|(_, s)| s.renewed + limit <= now)
            .map(|(id, _)| *id)
            .collect();
        gone.into_iter()
            .filter_map(|id| {
                let s = self.subs.remove(&id)?;
                tracing::debug!(event = id, subscriber = %s.subscriber, "event lapsed");
                Some(Self::confirm(s.subscriber, s.request_id, id, s.rate))
            })
            .collect()
    }

    fn lifetime(&self) -> Option<Duration> {
        (self.timeout_minutes > 0)
            .then(|| Duration::from_secs(60 * u64::from(self.timeout_minutes)))
    }

    /// When [`due`](Self::due) or [`expire`](Self::expire) next has something.
    pub fn next_timeout(&self) -> Option<Instant> {
        let lifetime = self.lifetime();
        self.subs
            .values()
            .flat_map(|s| [Some(s.next_due), lifetime.map(|l| s.renewed + l)])
            .flatten()
            .chain(self.next_check)
            .chain(self.running.iter().filter_map(|(_, d)| *d))
            .min()
    }

    /// Removes every event of `subscriber`.
    pub fn forget(&mut self, subscriber: As4Id) {
        self.subs.retain(|_, s| s.subscriber != subscriber);
    }

    /// Report Events for `filter`.
    pub fn report(&self, filter: &EventsFilter) -> ReportEvents {
        let events = self
            .subs
            .iter()
            .filter(|(id, s)| match filter {
                EventsFilter::MessageCode(c) => s.query.code().0 == *c,
                EventsFilter::EventType(t) => s.kind == *t,
                EventsFilter::EventId(e) => *id == e,
                EventsFilter::AllEvents(_) => true,
            })
            .map(|(id, s)| EventInfo {
                event_type: s.kind,
                event_id: *id,
                query_message: s.query_bytes.clone(),
            })
            .collect();
        ReportEvents { events }
    }

    /// Report Event Timeout (minutes).
    pub fn report_timeout(&self) -> ReportEventTimeout {
        ReportEventTimeout {
            timeout: self.timeout_minutes,
        }
    }
}

fn no_event(event_id: u8) -> Rejection {
    (
        EventRejection::InvalidEventIdForUpdate,
        format!("no event {event_id} of the sender"),
    )
}
