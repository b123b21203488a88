//! How the judge talks: AS-4 messages sent and received through the session, each
//! kept as the running check's evidence; queries with their reports; and the two
//! things the judge does in the background all run long: Query Identification every
//! few seconds (answered each time, counted for `as4.discovery.periodic`) and Request
//! Control again before the vehicle's control timeout runs out (AS-4 Access Control
//! lets control lapse unless the client renews it).

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::net::as5669a::{As4Id, As4Message};
use jaus::CommandCode;
use jaus_as4::messages::{
    ComponentState, IdentificationType, Message, QueryIdentification, QueryStatus, RequestControl,
};

use super::session::{Arrival, As4Session};
use super::As4Options;
use crate::check::Exchange;
use crate::engine::Evidence;

/// Most periodic queries waiting for their answer at once.
const MAX_PENDING: usize = 64;

/// The id every AS-4 component hears: subsystem, node and component all broadcast.
pub const BROADCAST: As4Id = As4Id::new(0xFFFF, 0xFF, 0xFF);

/// Message IDs the background work looks for.
const REPORT_IDENTIFICATION: u16 = 0x4B00;
const CONFIRM_CONTROL: u16 = 0x000F;
const REJECT_CONTROL: u16 = 0x0010;

/// The report answering query `id`: AS-4 numbers every report 0x2000 above its query
/// (Query Status 0x2002 → Report Status 0x4002, Query Identification 0x2B00 → 0x4B00).
pub(super) fn report_of(id: u16) -> u16 {
    id.wrapping_add(0x2000)
}

/// A message's title (`Query Identification`), or its id in hex.
pub(super) fn title(id: u16) -> String {
    jaus_as4::MESSAGES
        .iter()
        .find(|m| m.code.0 == id)
        .map_or_else(|| format!("0x{id:04X}"), |m| m.title.to_string())
}

/// A message's name and fields as JSON, or `raw 0x....` and its bytes in hex.
pub(super) fn describe(message_id: u16, body: &[u8]) -> (String, serde_json::Value) {
    match Message::decode(CommandCode(message_id), body) {
        Ok(Message::Raw(_)) => (
            format!("raw 0x{message_id:04X}"),
            serde_json::json!({ "hex": jaus::hex::encode(body) }),
        ),
        Ok(m) => {
            let fields = serde_json::to_value(&m)
                .ok()
                .and_then(|mut v| v.get_mut("fields").map(std::mem::take))
                .unwrap_or(serde_json::Value::Null);
            (m.name().to_string(), fields)
        }
        Err(e) => (
            format!("raw 0x{message_id:04X}"),
            serde_json::json!({ "hex": jaus::hex::encode(body), "decode": e.to_string() }),
        ),
    }
}

/// Query Identification every few seconds, and what came of it.
#[derive(Debug)]
pub(super) struct Periodic {
    /// Whom it asks (`None`: not running).
    to: Option<As4Id>,
    next: Instant,
    pending: VecDeque<Instant>,
    /// Queries sent.
    pub sent: u32,
    /// Queries answered within the answer wait.
    pub answered: u32,
    /// Queries answered, but later than the answer wait.
    pub late: u32,
    /// Queries not answered (given up on after the answer wait, or left unanswered).
    pub missed: u32,
    /// The longest time to an answer.
    pub worst: Duration,
    /// The queries and their answers (timed from the first).
    pub evidence: Evidence,
}

/// Request Control again before control lapses, and what came of it.
#[derive(Debug)]
pub(super) struct Keepalive {
    every: Option<Duration>,
    next: Instant,
    authority: u8,
    /// Requests sent again.
    pub sent: u32,
    /// Confirm Control with Control Accepted for them.
    pub confirmed: u32,
    /// Other answers to them (the response codes).
    pub refused: Vec<String>,
    /// Reject Control received while the judge held control.
    pub rejected: u32,
}

/// The judge's client: its id, the vehicle's component under test, the evidence of
/// the running check, and the background work.
pub(super) struct Judge<'a> {
    session: &'a mut dyn As4Session,
    /// The judge's id (42.1.1 at the IOP challenge).
    pub me: As4Id,
    /// The component under test.
    pub peer: As4Id,
    /// The run's options.
    pub opts: As4Options,
    /// The running check's evidence.
    pub evidence: Evidence,
    /// Query Identification every few seconds.
    pub periodic: Periodic,
    /// Request Control again.
    pub keepalive: Keepalive,
    /// Definitions loaded at run time, read for the evidence of messages jaus-as4's
    /// own do not define (a vendor's).
    schema: Option<&'a jaus_dynamic::Schema>,
}

impl std::fmt::Debug for Judge<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Judge")
            .field("me", &self.me)
            .field("peer", &self.peer)
            .finish_non_exhaustive()
    }
}

impl<'a> Judge<'a> {
    /// The judge on `session`, testing `peer` (a placeholder until discovery).
    pub fn new(session: &'a mut dyn As4Session, opts: As4Options, peer: As4Id) -> Self {
        let now = session.now();
        Judge {
            session,
            me: opts.me,
            peer,
            opts,
            evidence: Evidence::new(now),
            periodic: Periodic {
                to: None,
                next: now,
                pending: VecDeque::new(),
                sent: 0,
                answered: 0,
                late: 0,
                missed: 0,
                worst: Duration::ZERO,
                evidence: Evidence::new(now),
            },
            keepalive: Keepalive {
                every: None,
                next: now,
                authority: opts.authority,
                sent: 0,
                confirmed: 0,
                refused: Vec::new(),
                rejected: 0,
            },
            schema: None,
        }
    }

    /// Reads the evidence of messages jaus-as4 does not define with `schema` too.
    pub fn with_schema(mut self, schema: &'a jaus_dynamic::Schema) -> Self {
        self.schema = Some(schema);
        self
    }

    /// The session's clock.
    pub fn now(&self) -> Instant {
        self.session.now()
    }

    /// Messages the session dropped (a full inbox).
    pub fn dropped(&self) -> u64 {
        self.session.dropped()
    }

    /// Adds `more` to the running check's evidence.
    pub fn add_evidence(&mut self, more: Vec<Exchange>) {
        self.evidence.extend(more);
    }

    /// Starts Query Identification to `to` every [`As4Options::periodic`].
    pub fn start_periodic(&mut self, to: As4Id) {
        let now = self.session.now();
        self.periodic.to = Some(to);
        self.periodic.evidence.begin(now);
        self.periodic.next = now + self.opts.periodic;
    }

    /// Stops the periodic queries (the pending ones are given the answer wait first);
    /// whether any were ever started.
    pub fn stop_periodic(&mut self) -> bool {
        if self.periodic.to.is_none() && self.periodic.sent == 0 {
            return false;
        }
        // Whatever is still due before the minimum count, then the last answers.
        while self.periodic.to.is_some() && self.periodic.sent < self.opts.periodic_min {
            let until = self.periodic.next + Duration::from_millis(1);
            self.drain_until(until);
        }
        let last = self.session.now() + self.opts.wait;
        while !self.periodic.pending.is_empty() && self.session.now() < last {
            self.drain_until(last.min(self.session.now() + self.opts.wait));
            self.expire_periodic(self.session.now());
        }
        self.periodic.missed += self.periodic.pending.len() as u32;
        self.periodic.pending.clear();
        self.periodic.to = None;
        true
    }

    /// Sends Request Control again every `every` (`None`: stop).
    pub fn keep_control(&mut self, every: Option<Duration>) {
        self.keepalive.every = every;
        if let Some(e) = every {
            self.keepalive.next = self.session.now() + e;
        }
    }

    fn exchange(&self, log: &Evidence, dir: &'static str, m: &As4Message) -> Exchange {
        let (mut message, mut fields) = describe(m.message_id, &m.body);
        if message.starts_with("raw ") {
            if let Some(d) = self
                .schema
                .and_then(|s| s.decode(CommandCode(m.message_id), &m.body).ok())
            {
                message = d.name.to_string();
                fields = serde_json::to_value(&d.fields).unwrap_or(serde_json::Value::Null);
            }
        }
        Exchange {
            t_ms: log.t_ms(self.session.now()),
            dir,
            from: m.source.to_string(),
            to: m.destination.to_string(),
            message,
            fields,
        }
    }

    fn record(&mut self, dir: &'static str, m: &As4Message) {
        let e = self.exchange(&self.evidence, dir, m);
        self.evidence.keep(e);
    }

    /// Sends `msg` to `to` (a broadcast id goes out as a global broadcast:
    /// [`As4Message::new`] marks it).
    pub fn send_to(&mut self, to: As4Id, msg: &Message) {
        let Ok(body) = msg.to_bytes() else {
            tracing::warn!(message = msg.name(), "jaus conform --as4: cannot encode");
            return;
        };
        let m = As4Message::new(msg.code().0, to, self.me, body);
        self.record("sent", &m);
        self.session.send(m);
    }

    /// Sends message `id` with `body` to the component under test.
    pub fn send_raw(&mut self, id: u16, body: Vec<u8>) {
        let m = As4Message::new(id, self.peer, self.me, body);
        self.record("sent", &m);
        self.session.send(m);
    }

    /// Sends `msg` to the component under test.
    pub fn send(&mut self, msg: &Message) {
        self.send_to(self.peer, msg);
    }

    /// Sends what is due in the background.
    fn tick(&mut self) {
        let now = self.session.now();
        self.expire_periodic(now);
        if let Some(to) = self.periodic.to {
            if now >= self.periodic.next {
                let q: Message = QueryIdentification {
                    query_type: IdentificationType::Subsystem,
                }
                .into();
                if let Ok(body) = q.to_bytes() {
                    let m = As4Message::new(q.code().0, to, self.me, body);
                    let e = self.exchange(&self.periodic.evidence, "sent", &m);
                    self.periodic.evidence.keep(e);
                    self.session.send(m);
                    self.periodic.sent += 1;
                    if self.periodic.pending.len() < MAX_PENDING {
                        self.periodic.pending.push_back(now);
                    } else {
                        self.periodic.missed += 1;
                    }
                }
                self.periodic.next = now + self.opts.periodic;
            }
        }
        if let Some(every) = self.keepalive.every {
            if now >= self.keepalive.next {
                let r: Message = RequestControl {
                    authority_code: self.keepalive.authority,
                }
                .into();
                self.send(&r);
                self.keepalive.sent += 1;
                self.keepalive.next = now + every;
            }
        }
    }

    /// Periodic queries older than the answer wait count as missed.
    fn expire_periodic(&mut self, now: Instant) {
        while let Some(t) = self.periodic.pending.front() {
            if now.saturating_duration_since(*t) > self.opts.wait {
                self.periodic.pending.pop_front();
                self.periodic.missed += 1;
            } else {
                break;
            }
        }
    }

    fn next_tick(&self) -> Option<Instant> {
        let p = self.periodic.to.map(|_| self.periodic.next);
        let k = self.keepalive.every.map(|_| self.keepalive.next);
        let oldest = self.periodic.pending.front().map(|t| *t + self.opts.wait);
        [p, k, oldest].into_iter().flatten().min()
    }

    /// Whether `a` answers a periodic query (then it is kept in that check's evidence).
    fn periodic_answer(&mut self, a: &Arrival) -> bool {
        let m = &a.message;
        if m.message_id != REPORT_IDENTIFICATION
            || Some(m.source) != self.periodic.to
            || m.destination != self.me
        {
            return false;
        }
        let Some(sent) = self.periodic.pending.pop_front() else {
            return false;
        };
        let took = a.at.saturating_duration_since(sent);
        self.periodic.worst = self.periodic.worst.max(took);
        if took > self.opts.wait {
            self.periodic.late += 1;
        } else {
            self.periodic.answered += 1;
        }
        let e = self.exchange(&self.periodic.evidence, "received", m);
        self.periodic.evidence.keep(e);
        true
    }

    /// Counts the vehicle's answers to the renewed control requests.
    fn observe_control(&mut self, m: &As4Message) {
        if m.source != self.peer || m.destination != self.me {
            return;
        }
        match m.message_id {
            CONFIRM_CONTROL if self.keepalive.every.is_some() => match m.body.first() {
                Some(0) => self.keepalive.confirmed += 1,
                code => self.keepalive.refused.push(format!("{code:?}")),
            },
            REJECT_CONTROL if self.keepalive.every.is_some() => self.keepalive.rejected += 1,
            _ => {}
        }
    }

    /// The next message by `deadline` (kept as evidence), doing the background work
    /// while waiting.
    pub fn next(&mut self, deadline: Instant) -> Option<Arrival> {
        loop {
            self.tick();
            let until = self.next_tick().map_or(deadline, |t| t.min(deadline));
            match self.session.recv(until) {
                Some(a) => {
                    if self.periodic_answer(&a) {
                        continue;
                    }
                    self.observe_control(&a.message);
                    self.record("received", &a.message);
                    return Some(a);
                }
                None if self.session.now() >= deadline => return None,
                None => {}
            }
        }
    }

    /// Takes whatever arrives until `deadline`.
    pub fn drain_until(&mut self, deadline: Instant) {
        while self.next(deadline).is_some() {}
    }

    /// Takes whatever arrives for `d` (the settle time after a command).
    pub fn drain(&mut self, d: Duration) {
        let deadline = self.session.now() + d;
        self.drain_until(deadline);
    }

    /// Waits `within` for a message from `from` to the judge with message ID `id`.
    pub fn wait_for(
        &mut self,
        within: Duration,
        from: Option<As4Id>,
        ids: &[u16],
    ) -> Option<Arrival> {
        let deadline = self.session.now() + within;
        while let Some(a) = self.next(deadline) {
            let m = &a.message;
            if from.is_none_or(|f| f == m.source)
                && m.destination == self.me
                && ids.contains(&m.message_id)
            {
                return Some(a);
            }
        }
        None
    }

    /// Sends query `q` to `to` and waits for its report; the report's message and the
    /// raw body (for a look at its presence vector), or why not.
    pub fn ask_raw(&mut self, to: As4Id, q: Message) -> Result<(Message, Vec<u8>, As4Id), String> {
        let report = report_of(q.code().0);
        let name = title(q.code().0);
        self.send_to(to, &q);
        let from = (to != BROADCAST).then_some(to);
        let Some(a) = self.wait_for(self.opts.wait, from, &[report]) else {
            return Err(format!(
                "no answer to {name} within {:.1} s",
                self.opts.wait.as_secs_f64()
            ));
        };
        match Message::decode(CommandCode(report), &a.message.body) {
            Ok(m) => Ok((m, a.message.body, a.message.source)),
            Err(e) => Err(format!("the answer to {name} does not decode: {e}")),
        }
    }

    /// Sends query `q` to the component under test; its report, or why not.
    pub fn ask(&mut self, q: Message) -> Result<Message, String> {
        self.ask_raw(self.peer, q).map(|(m, _, _)| m)
    }

    /// The component's state (Query Status), or why not.
    pub fn status(&mut self) -> Result<ComponentState, String> {
        match self.ask(QueryStatus {}.into())? {
            Message::ReportStatus(r) => Ok(r.status),
            other => Err(format!("Query Status answered by {}", other.name())),
        }
    }

    /// Sends command `msg` to the component and waits the settle time.
    pub fn command(&mut self, msg: Message) {
        self.send(&msg);
        self.drain(self.opts.settle);
    }
}
