//! Runs planned checks through the judge's client: each sends what its step says and
//! judges the answers by the definitions. Every wait is bounded by the run's answer
//! wait (and settle time); nothing from the network is trusted to be well formed.

use std::time::Duration;

use jaus::CommandCode;
use jaus::JausMessage;
use jaus_as4::messages::{
    CancelEvent, ComponentState, ConfirmControl, ConfirmEventRequest, ControlConfirmation,
    CreateEvent, Event, EventType, Message, QueryControl, RejectControl, RejectEventRequest,
    ReleaseControl, RequestControl,
};
use jaus_dynamic::DynMessage;

use super::defs::Definitions;
use super::plan::Step;
use super::sample;
use crate::as4::talk::Judge;
use crate::engine::{fail, inconclusive as unsure, pass, Found};

// The ids of the answers waited for, from the generated messages (one home: the
// definitions).
const CONFIRM_CONTROL: u16 = ConfirmControl::CODE.0;
const REJECT_CONTROL: u16 = RejectControl::CODE.0;
const CONFIRM_EVENT: u16 = ConfirmEventRequest::CODE.0;
const REJECT_EVENT: u16 = RejectEventRequest::CODE.0;
const EVENT: u16 = Event::CODE.0;
/// The rate asked of a periodic event, Hz.
const EVENT_RATE: f64 = 5.0;

/// What a read-back gave, the command with those values moved a little, and the fields
/// it sets with their values ([`Runner::nudged`]).
pub(super) type Nudged = (DynMessage, DynMessage, Vec<(String, f64)>);

/// What came back for a message sent.
enum Answer {
    /// The message expected: its body.
    Expected(Vec<u8>),
    /// Others only (their names).
    Others(Vec<String>),
    /// Nothing within the wait.
    Silence,
}

/// The judge's client with the definitions.
pub(super) struct Runner<'a> {
    pub j: Judge<'a>,
    pub defs: &'a Definitions,
    pub(super) request: u8,
}

impl<'a> Runner<'a> {
    pub fn new(j: Judge<'a>, defs: &'a Definitions) -> Self {
        Runner {
            j,
            defs,
            request: 0,
        }
    }

    fn name_of(&self, id: u16) -> String {
        self.defs
            .schema()
            .by_code(CommandCode(id))
            .map_or_else(|| format!("0x{id:04X}"), |l| l.name.to_string())
    }

    fn code(&self, name: &str) -> Result<u16, String> {
        self.defs
            .schema()
            .message(name)
            .map(|l| l.code.0)
            .ok_or_else(|| format!("{name} is not in the definitions"))
    }

    fn send_dyn(&mut self, m: &DynMessage) -> Result<(), String> {
        let body = self
            .defs
            .schema()
            .encode(m)
            .map_err(|e| format!("{} does not encode: {e}", m.name))?;
        self.j.send_raw(m.code.0, body);
        Ok(())
    }

    /// Waits the answer wait for message `want` from the component; what else came.
    fn answer(&mut self, want: u16) -> Answer {
        let deadline = self.j.now() + self.j.opts.wait;
        let (peer, me) = (self.j.peer, self.j.me);
        let mut others = Vec::new();
        while let Some(a) = self.j.next(deadline) {
            let m = &a.message;
            if m.source != peer || m.destination != me {
                continue;
            }
            if m.message_id == want {
                return Answer::Expected(a.message.body);
            }
            if m.message_id != EVENT && others.len() < 16 {
                others.push(self.name_of(m.message_id));
            }
        }
        if others.is_empty() {
            Answer::Silence
        } else {
            Answer::Others(others)
        }
    }

    /// Decodes `body` as `report`; that its length is the one the definitions give.
    fn decode(&self, report: &str, body: &[u8]) -> Result<DynMessage, String> {
        let code = self.code(report)?;
        let m = self
            .defs
            .schema()
            .decode(CommandCode(code), body)
            .map_err(|e| format!("{report} does not decode by the definitions: {e}"))?;
        match self.defs.schema().encode(&m) {
            Ok(b) if b.len() == body.len() => Ok(m),
            Ok(b) => Err(format!(
                "{report} is {} bytes where its fields take {} by the definitions",
                body.len(),
                b.len()
            )),
            Err(e) => Err(format!("{report} decoded but does not encode back: {e}")),
        }
    }

    /// Sends query `query`, returns its report decoded (or why not).
    pub(super) fn read(&mut self, query: &str, report: &str) -> Result<DynMessage, String> {
        let q = sample::query(self.defs, query, report)?;
        self.send_dyn(&q)?;
        let want = self.code(report)?;
        match self.answer(want) {
            Answer::Expected(body) => self.decode(report, &body),
            Answer::Others(o) => Err(format!(
                "{query} answered with {} where the definitions give {report}",
                o.join(", ")
            )),
            Answer::Silence => Err(format!(
                "no answer to {query} within {:.1} s",
                self.j.opts.wait.as_secs_f64()
            )),
        }
    }

    /// Runs one step.
    pub fn run(&mut self, step: &Step) -> Found {
        match step {
            Step::Query {
                query,
                report,
                guarded,
            } => self.query(query, report, *guarded),
            Step::Outsider { command, readback } => self.outsider(command, readback.as_deref()),
            Step::Controller {
                command,
                readback,
                needs_ready,
            } => self.controller(command, readback, *needs_ready),
            Step::Event { query, report } => self.event(query, report),
            Step::CommandEvent { command, readback } => self.command_event(command, readback),
        }
    }

    fn query(&mut self, query: &str, report: &str, guarded: bool) -> Found {
        let q = match sample::query(self.defs, query, report) {
            Ok(q) => q,
            Err(e) => return unsure(e),
        };
        if let Err(e) = self.send_dyn(&q) {
            return unsure(e);
        }
        let want = match self.code(report) {
            Ok(c) => c,
            Err(e) => return unsure(e),
        };
        match self.answer(want) {
            Answer::Expected(body) => match self.decode(report, &body) {
                Ok(m) => pass(format!(
                    "{report}, {} bytes: {}",
                    body.len(),
                    sample::text(&m.fields)
                )),
                Err(e) => fail(e),
            },
            Answer::Others(o) => fail(format!(
                "{query} answered with {} where the definitions give {report}",
                o.join(", ")
            )),
            Answer::Silence if guarded => unsure(format!(
                "no answer within {:.1} s: the transition is guarded, its condition may not hold now",
                self.j.opts.wait.as_secs_f64()
            )),
            Answer::Silence => fail(format!(
                "no answer within {:.1} s",
                self.j.opts.wait.as_secs_f64()
            )),
        }
    }

    /// Reads `query` (answered by `report`), then builds `command` carrying the fields
    /// `shared` with the values read moved a little: what was read, the command and what
    /// it sets, or why not (an inconclusive verdict).
    pub(super) fn nudged(
        &mut self,
        command: &str,
        query: &str,
        report: &str,
        shared: &[sample::Shared],
    ) -> Result<Nudged, String> {
        let r0 = self
            .read(query, report)
            .map_err(|e| format!("before: {e}"))?;
        let (cmd, sent) = sample::command(self.defs, command, shared, Some(&r0.fields), true)?;
        Ok((r0, cmd, sent))
    }

    /// The read-back query of `command`, its report, and the fields they share.
    pub(super) fn readback(
        &self,
        command: &str,
        query: &str,
    ) -> Option<(String, Vec<sample::Shared>)> {
        let report = super::plan::report_name(self.defs, query)?;
        let shared = sample::shared(self.defs, command, &report);
        (!shared.is_empty()).then_some((report, shared))
    }

    /// Whoever holds control and the component's state, as Query Control and Query
    /// Status give them.
    fn status(&mut self) -> Result<(String, ComponentState), String> {
        let control = match self.j.ask(QueryControl {}.into())? {
            Message::ReportControl(r) => format!("{:?}", r),
            m => return Err(format!("Query Control answered by {}", m.name())),
        };
        Ok((control, self.j.status()?))
    }

    /// Confirmations (`Confirm...`) among what arrives during the settle time.
    pub(super) fn settle_confirmations(&mut self) -> Vec<String> {
        let deadline = self.j.now() + self.j.opts.settle;
        let (peer, me) = (self.j.peer, self.j.me);
        let mut seen = Vec::new();
        while let Some(a) = self.j.next(deadline) {
            let m = &a.message;
            if m.source == peer && m.destination == me && m.message_id != CONFIRM_CONTROL {
                let name = self.name_of(m.message_id);
                if name.starts_with("Confirm") && seen.len() < 8 {
                    seen.push(name);
                }
            }
        }
        seen
    }

    fn outsider(&mut self, command: &str, readback: Option<&str>) -> Found {
        let rb = readback.and_then(|q| self.readback(command, q).map(|r| (q.to_string(), r)));
        let Some((query, (report, shared))) = rb else {
            return self.outsider_by_status(command);
        };
        let (r0, cmd, sent) = match self.nudged(command, &query, &report, &shared) {
            Ok(n) => n,
            Err(e) => return unsure(e),
        };
        if sent.is_empty() {
            return self.outsider_by_status(command);
        }
        if let Err(e) = self.send_dyn(&cmd) {
            return unsure(e);
        }
        let confirmed = self.settle_confirmations();
        let r1 = match self.read(&query, &report) {
            Ok(r) => r,
            Err(e) => return unsure(format!("after: {e}")),
        };
        let moved = sample::moved(&r0.fields, &r1.fields, &sent);
        if !moved.is_empty() {
            return fail(format!(
                "carried out without control: {} by {query}",
                moved.join("; ")
            ));
        }
        if !confirmed.is_empty() {
            return fail(format!(
                "confirmed without control: {}",
                confirmed.join(", ")
            ));
        }
        pass(format!(
            "{query} unchanged after {command} {} from a client without control",
            sample::text(&cmd.fields)
        ))
    }

    fn outsider_by_status(&mut self, command: &str) -> Found {
        let before = match self.status() {
            Ok(s) => s,
            Err(e) => return unsure(format!("before: {e}")),
        };
        let cmd = match sample::command(self.defs, command, &[], None, false) {
            Ok((c, _)) => c,
            Err(e) => return unsure(e),
        };
        if let Err(e) = self.send_dyn(&cmd) {
            return unsure(e);
        }
        let confirmed = self.settle_confirmations();
        let after = match self.status() {
            Ok(s) => s,
            Err(e) => return unsure(format!("after: {e}")),
        };
        if !confirmed.is_empty() {
            return fail(format!(
                "confirmed without control: {}",
                confirmed.join(", ")
            ));
        }
        if before != after {
            return fail(format!(
                "the component changed without control: {before:?} → {after:?}"
            ));
        }
        pass(format!(
            "no confirmation; Query Control and Query Status unchanged ({:?}); no read-back query in the definitions",
            after.1
        ))
    }

    /// Request Control at the run's authority: whether it was accepted.
    fn take_control(&mut self) -> Result<(), String> {
        let a = self.j.opts.authority;
        self.j.send(&RequestControl { authority_code: a }.into());
        let peer = Some(self.j.peer);
        match self
            .j
            .wait_for(self.j.opts.wait, peer, &[CONFIRM_CONTROL, REJECT_CONTROL])
        {
            Some(a) => match Message::decode(CommandCode(a.message.message_id), &a.message.body) {
                Ok(Message::ConfirmControl(c))
                    if c.response_code == ControlConfirmation::ControlAccepted =>
                {
                    Ok(())
                }
                Ok(m) => Err(format!("Request Control answered by {m:?}")),
                Err(e) => Err(format!(
                    "the answer to Request Control does not decode: {e}"
                )),
            },
            None => Err("no answer to Request Control".into()),
        }
    }

    fn give_back(&mut self) {
        self.j.send(&ReleaseControl {}.into());
        let peer = Some(self.j.peer);
        let _ = self.j.wait_for(self.j.opts.wait, peer, &[REJECT_CONTROL]);
    }

    fn controller(&mut self, command: &str, readback: &str, needs_ready: bool) -> Found {
        let Some((report, shared)) = self.readback(command, readback) else {
            return unsure(format!("{readback} shares no field with {command}"));
        };
        if let Err(e) = self.take_control() {
            return unsure(format!("control not taken: {e}"));
        }
        let found = self.controlled(command, readback, &report, &shared, needs_ready);
        self.give_back();
        found
    }

    fn controlled(
        &mut self,
        command: &str,
        query: &str,
        report: &str,
        shared: &[sample::Shared],
        needs_ready: bool,
    ) -> Found {
        if needs_ready {
            match self.j.status() {
                Ok(ComponentState::Ready) => {}
                Ok(s) => {
                    return unsure(format!(
                        "{command} needs the component Ready; it is {s:?} (the planner does not change it)"
                    ))
                }
                Err(e) => return unsure(e),
            }
        }
        let r0 = match self.read(query, report) {
            Ok(r) => r,
            Err(e) => return unsure(format!("before: {e}")),
        };
        let (cmd, sent) = match sample::command(self.defs, command, shared, Some(&r0.fields), true)
        {
            Ok(c) => c,
            Err(e) => return unsure(e),
        };
        if sent.is_empty() {
            return unsure(format!(
                "{report} carries none of the fields {command} sets"
            ));
        }
        if let Err(e) = self.send_dyn(&cmd) {
            return unsure(e);
        }
        self.j.drain(self.j.opts.settle);
        let r1 = self.read(query, report);
        // Put back what was read first, whatever the outcome.
        if let Ok((back, _)) = sample::command(self.defs, command, shared, Some(&r0.fields), false)
        {
            if self.send_dyn(&back).is_ok() {
                self.j.drain(self.j.opts.settle);
            }
        }
        let r1 = match r1 {
            Ok(r) => r,
            Err(e) => return unsure(format!("after: {e}")),
        };
        let moved = sample::moved(&r0.fields, &r1.fields, &sent);
        if moved.is_empty() {
            fail(format!(
                "{query} does not show {command} {}: {}",
                sample::text(&cmd.fields),
                sample::text(&r1.fields)
            ))
        } else {
            pass(format!(
                "{}; the value read first was put back",
                moved.join("; ")
            ))
        }
    }

    fn event(&mut self, query: &str, report: &str) -> Found {
        let q = match sample::query(self.defs, query, report) {
            Ok(q) => q,
            Err(e) => return unsure(e),
        };
        let body = match self.defs.schema().encode(&q) {
            Ok(b) => b,
            Err(e) => return unsure(e.to_string()),
        };
        let Ok(report_code) = self.code(report) else {
            return unsure(format!("{report} is not in the definitions"));
        };
        let mut query_message = q.code.0.to_le_bytes().to_vec();
        query_message.extend_from_slice(&body);
        self.request = self.request.wrapping_add(1);
        let request_id = self.request;
        self.j.send(
            &CreateEvent {
                request_id,
                event_type: EventType::Periodic,
                requested_periodic_rate: EVENT_RATE,
                query_message,
            }
            .into(),
        );
        let peer = Some(self.j.peer);
        let Some(a) = self
            .j
            .wait_for(self.j.opts.wait, peer, &[CONFIRM_EVENT, REJECT_EVENT])
        else {
            return fail(format!(
                "no answer to Create Event within {:.1} s",
                self.j.opts.wait.as_secs_f64()
            ));
        };
        let (event_id, rate) =
            match Message::decode(CommandCode(a.message.message_id), &a.message.body) {
                Ok(Message::ConfirmEventRequest(c)) if c.request_id == request_id => {
                    (c.event_id, c.confirmed_periodic_rate)
                }
                Ok(Message::RejectEventRequest(r)) => {
                    return fail(format!("Create Event refused: {r:?}"))
                }
                Ok(m) => return fail(format!("Create Event answered by {m:?}")),
                Err(e) => return fail(format!("the answer to Create Event does not decode: {e}")),
            };
        let period = if rate > 0.0 {
            Duration::from_secs_f64((1.0 / rate).min(10.0))
        } else {
            Duration::ZERO
        };
        let found = self.first_event(event_id, report, report_code, self.j.opts.wait + period);
        self.j.send(
            &CancelEvent {
                request_id,
                event_id,
            }
            .into(),
        );
        let _ = self
            .j
            .wait_for(self.j.opts.wait, peer, &[CONFIRM_EVENT, REJECT_EVENT]);
        match found {
            Ok(d) => pass(format!("confirmed at {rate:.1} Hz (event {event_id}); {d}")),
            Err(e) => fail(e),
        }
    }

    /// Waits `within` for an Event of `event_id` carrying `report`.
    fn first_event(
        &mut self,
        event_id: u8,
        report: &str,
        report_code: u16,
        within: Duration,
    ) -> Result<String, String> {
        let deadline = self.j.now() + within;
        let peer = Some(self.j.peer);
        while self.j.now() < deadline {
            let left = deadline.saturating_duration_since(self.j.now());
            let Some(a) = self.j.wait_for(left, peer, &[EVENT]) else {
                break;
            };
            let Ok(Message::Event(e)) = Message::decode(Event::CODE, &a.message.body) else {
                return Err("an Event that does not decode".into());
            };
            if e.event_id != event_id {
                continue;
            }
            let r = &e.report_message;
            let id = match r.get(..2) {
                Some(b) => u16::from_le_bytes([b[0], b[1]]),
                None => return Err("an Event whose report is shorter than its message ID".into()),
            };
            if id != report_code {
                return Err(format!(
                    "the Event carries {} where the definitions give {report}",
                    self.name_of(id)
                ));
            }
            return self.decode(report, &r[2..]).map(|m| {
                format!(
                    "Event {} carries {report}: {}",
                    e.sequence_number,
                    sample::text(&m.fields)
                )
            });
        }
        Err(format!("no Event within {:.1} s", within.as_secs_f64()))
    }
}
