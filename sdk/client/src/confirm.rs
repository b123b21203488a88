//! Confirmation by effect: whether a command took effect at a component that may never
//! acknowledge (OpenJAUS 3.3's components send no ACK/NAK).
//!
//! A command ends as one [`Confirmation`]: acknowledged (ACK), confirmed by read-back
//! (no ACK, but the effect is seen), refused (a NAK, Report Refusal or a control
//! refusal) or not confirmed (with what is known). Without an acknowledgement the effect
//! is read back ([`Check`]):
//!
//! * a command whose definition names a `readback:` query (Set Travel Speed → Query
//!   Travel Speed) is confirmed when the report carries every field of the command
//!   with the value sent, a scaled field within one step of its wire scaling;
//! * Standby, Resume, Shutdown, Reset, Set Emergency and Clear Emergency are confirmed
//!   by Query Component Status (Resume → Ready, Standby → Standby, ...): a driver that
//!   stays in Standby after Resume is "still Standby after Resume";
//! * Request Component Control is confirmed by its own answer (Confirm Component
//!   Control with ControlAccepted; anything else is a refusal).
//!
//! Whether a component acknowledges is learnt per component ([`Habits`]): once it let a
//! command go unacknowledged while its effect was seen, the next commands to it are
//! read back at once instead of waiting for an ACK first.
//!
//! `jaus conform`'s read-back check (`sdk/conform/src/engine/readback.rs`) compares
//! within one count the same way; its comparison is private to its engine, so this
//! module keeps its own (to merge).

use std::collections::HashMap;
use std::fmt;
use std::sync::OnceLock;
use std::time::{Duration, Instant};

use jaus::messages as m;
use jaus::{Address, CommandCode, JausMessage};
use jaus_dynamic::Schema;
use jaus_spec::{Spec, Wire};
use serde_json::{Map, Value};

/// How long a command to a component not known to acknowledge waits for its ACK
/// before its effect is read back.
pub const ACK_WAIT: Duration = Duration::from_millis(1000);
/// How long a command to a component known never to acknowledge is given to take
/// effect before the first read-back.
pub const SETTLE: Duration = Duration::from_millis(150);
/// The read-back query is asked again this often until its answer shows the effect.
pub const ASK_EVERY: Duration = Duration::from_millis(300);
/// How long a command may be held by its node before it leaves (the node keeps a
/// component's commands in order: one behind an unanswered command to a component not
/// known to acknowledge waits 2 s at most, `RetryPolicy::hold_unknown`). The
/// read-back is timed from the command's departure ([`Confirming::departed`]); this
/// bounds the wait when the departure is not seen.
pub const HELD_AT_MOST: Duration = Duration::from_millis(2500);
/// Most components whose habit is remembered.
const MAX_HABITS: usize = 1024;

const QUERY_COMPONENT_STATUS: CommandCode = <m::QueryComponentStatus as JausMessage>::CODE;
const REPORT_COMPONENT_STATUS: CommandCode = <m::ReportComponentStatus as JausMessage>::CODE;
const REQUEST_COMPONENT_CONTROL: CommandCode = <m::RequestComponentControl as JausMessage>::CODE;
const CONFIRM_COMPONENT_CONTROL: CommandCode = <m::ConfirmComponentControl as JausMessage>::CODE;
const REJECT_COMPONENT_CONTROL: CommandCode = <m::RejectComponentControl as JausMessage>::CODE;

/// How a command ended, as far as its sender can tell.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Confirmation {
    /// The component acknowledged it (ACK).
    Acknowledged,
    /// No acknowledgement, but its effect was seen: what the read-back showed.
    ReadBack(String),
    /// The component refused it: the reason (a NAK, Report Refusal, or a refused
    /// control request).
    Refused(String),
    /// Neither acknowledged nor seen to take effect: what is known.
    NotConfirmed(String),
}

impl Confirmation {
    /// `acknowledged`, `confirmed_by_readback`, `refused` or `not_confirmed`.
    pub fn outcome(&self) -> &'static str {
        match self {
            Confirmation::Acknowledged => "acknowledged",
            Confirmation::ReadBack(_) => "confirmed_by_readback",
            Confirmation::Refused(_) => "refused",
            Confirmation::NotConfirmed(_) => "not_confirmed",
        }
    }

    /// What was seen (empty for an acknowledgement).
    pub fn detail(&self) -> &str {
        match self {
            Confirmation::Acknowledged => "",
            Confirmation::ReadBack(d)
            | Confirmation::Refused(d)
            | Confirmation::NotConfirmed(d) => d,
        }
    }

    /// Whether the command is known to have taken effect.
    pub fn confirmed(&self) -> bool {
        matches!(self, Confirmation::Acknowledged | Confirmation::ReadBack(_))
    }
}

impl fmt::Display for Confirmation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Confirmation::Acknowledged => write!(f, "acknowledged"),
            Confirmation::ReadBack(d) => write!(f, "confirmed by read-back: {d}"),
            Confirmation::Refused(d) => write!(f, "refused: {d}"),
            Confirmation::NotConfirmed(d) => write!(f, "not confirmed: {d}"),
        }
    }
}

/// A field of a command and the value its read-back must show.
#[derive(Debug, Clone, PartialEq)]
pub struct Expected {
    /// The field (named alike in the command and its report).
    pub field: String,
    /// The value the command carries (as the wire carries it).
    pub value: Value,
    /// One step of the field's scaling (0 for a field compared exactly).
    pub step: f64,
    /// Its unit, for the text.
    pub unit: Option<String>,
}

/// The states of Report Component Status that confirm a state command.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Wanted {
    /// One of these.
    Is(&'static [&'static str]),
    /// Any but this one.
    Not(&'static str),
}

impl Wanted {
    fn accepts(self, state: &str) -> bool {
        match self {
            Wanted::Is(s) => s.contains(&state),
            Wanted::Not(s) => s != state,
        }
    }

    fn text(self) -> String {
        match self {
            Wanted::Is(s) => s.join(" or "),
            Wanted::Not(s) => format!("not {s}"),
        }
    }
}

/// How a command's effect is seen when it is not acknowledged.
#[derive(Debug, Clone, PartialEq)]
pub enum Check {
    /// Its read-back query (code, body, name) answered by `report`, whose fields must
    /// show `expect`.
    ReadBack {
        /// The query's code.
        query: CommandCode,
        /// The query's body.
        body: Vec<u8>,
        /// The query's title (`Query Travel Speed`).
        query_title: String,
        /// The report's code.
        report: CommandCode,
        /// The report's title (`Report Travel Speed`).
        report_title: String,
        /// The fields to compare.
        expect: Vec<Expected>,
    },
    /// Query Component Status must report a state `wanted` accepts.
    State(Wanted),
    /// Request Component Control: its own answer says.
    Control,
    /// Nothing shows the effect: why.
    Nothing(String),
}

/// The definitions the checks are made from (the SDK's), loaded once.
#[derive(Debug)]
pub struct Checks {
    spec: Spec,
    schema: Schema,
}

/// The SDK's checks (`None` if its own definitions failed to load, which its tests
/// rule out).
pub fn checks() -> Option<&'static Checks> {
    static CHECKS: OnceLock<Option<Checks>> = OnceLock::new();
    CHECKS
        .get_or_init(|| {
            let spec = jaus_spec::load_sdk().ok()?;
            let schema = Schema::from_spec(&spec);
            Some(Checks { spec, schema })
        })
        .as_ref()
}

/// One step of a scaled wire form (0 for any other).
fn step_of(w: &Wire) -> f64 {
    match w {
        Wire::Scaled { int, lo, hi } => (hi - lo) / ((2f64).powi(8 * int.bytes() as i32) - 1.0),
        _ => 0.0,
    }
}

/// The largest value of an integer query field (a presence vector asks for all).
fn all_ones(w: &Wire) -> Option<u64> {
    match w {
        Wire::Int(i) if i.unsigned() => Some(if i.bytes() >= 8 {
            u64::MAX
        } else {
            (1u64 << (8 * i.bytes())) - 1
        }),
        _ => None,
    }
}

impl Checks {
    /// The fields of a body of message `code`, as JSON (`jaus decode`'s form).
    pub fn fields(&self, code: CommandCode, body: &[u8]) -> Option<Map<String, Value>> {
        let m = self.schema.decode(code, body).ok()?;
        match serde_json::to_value(&m.fields).ok()? {
            Value::Object(o) => Some(o),
            _ => Some(Map::new()),
        }
    }

    /// How the effect of command `code` with `body` is seen.
    pub fn of(&self, code: CommandCode, body: &[u8]) -> Check {
        let wanted = match code.0 {
            0x0002 => Some(Wanted::Is(&["Shutdown"])),
            0x0003 => Some(Wanted::Is(&["Standby"])),
            0x0004 => Some(Wanted::Is(&["Ready"])),
            0x0005 => Some(Wanted::Is(&["Initialize", "Standby"])),
            0x0006 => Some(Wanted::Is(&["Emergency"])),
            0x0007 => Some(Wanted::Not("Emergency")),
            _ => None,
        };
        if let Some(w) = wanted {
            return Check::State(w);
        }
        if code == REQUEST_COMPONENT_CONTROL {
            return Check::Control;
        }
        let Some(cmd) = self.spec.message_by_code(code.0) else {
            return Check::Nothing(format!("{code} is not in the SDK's definitions"));
        };
        let name = &cmd.def.name;
        let Some(qname) = &cmd.def.readback else {
            return Check::Nothing(format!(
                "{name} names no read-back query in the definitions"
            ));
        };
        let (Some(q), Some(sent)) = (self.spec.message(qname), self.fields(code, body)) else {
            return Check::Nothing(format!("{name}: its read-back {qname} is not usable"));
        };
        let Some(r) = self.spec.report_of(&q.def) else {
            return Check::Nothing(format!("{qname} has no report"));
        };
        // The query asks for every field (presence vectors all ones); a query that
        // selects an item cannot be asked without knowing which.
        let mut qfields = Map::new();
        for f in &q.fields {
            match all_ones(&f.wire) {
                Some(v) if f.def.name.contains("presence") => {
                    qfields.insert(f.def.name.clone(), v.into());
                }
                _ => {
                    return Check::Nothing(format!(
                        "{qname} selects by `{}`: not asked",
                        f.def.name
                    ))
                }
            }
        }
        let query = match self
            .schema
            .from_json(qname, &Value::Object(qfields))
            .map_err(|e| e.to_string())
            .and_then(|m| self.schema.encode(&m).map_err(|e| e.to_string()))
        {
            Ok(b) => b,
            Err(e) => return Check::Nothing(format!("{qname}: {e}")),
        };
        let expect: Vec<Expected> = cmd
            .fields
            .iter()
            .filter_map(|f| {
                let value = sent.get(&f.def.name)?.clone();
                let rf = r.fields.iter().find(|x| x.def.name == f.def.name)?;
                Some(Expected {
                    field: f.def.name.clone(),
                    value,
                    step: step_of(&f.wire).max(step_of(&rf.wire)),
                    unit: f.def.unit.clone(),
                })
            })
            .collect();
        if expect.is_empty() {
            return Check::Nothing(format!(
                "{} carries none of the fields {name} sets",
                r.def.name
            ));
        }
        Check::ReadBack {
            query: CommandCode(q.def.code.0),
            body: query,
            query_title: jaus_spec::title_of(qname),
            report: CommandCode(r.def.code.0),
            report_title: jaus_spec::title_of(&r.def.name),
            expect,
        }
    }
}

/// A value as the text shows it: a scaled one to the decimals its step resolves.
fn shown(v: &Value, step: f64, unit: Option<&str>) -> String {
    let text = match (v.as_f64(), v) {
        (Some(x), _) if step > 0.0 => {
            let decimals = (-step.log10()).ceil().max(0.0) as usize + 1;
            format!("{x:.prec$}", prec = decimals.min(9))
        }
        (_, Value::String(s)) => s.clone(),
        _ => v.to_string(),
    };
    match unit {
        Some(u) if !u.is_empty() => format!("{text} {u}"),
        _ => text,
    }
}

/// Whether `got` shows `e`: a scaled value within one step (1 % slack for rounding),
/// anything else equal.
fn shows(e: &Expected, got: &Value) -> bool {
    match (e.value.as_f64(), got.as_f64()) {
        (Some(a), Some(b)) if e.step > 0.0 => (a - b).abs() <= e.step * 1.01 + 1e-12,
        (Some(a), Some(b)) => a == b,
        _ => e.value == *got,
    }
}

/// Compares a read-back report's fields with what the command set: `Ok` with what it
/// shows when every field matches, `Err` naming what differs.
pub fn compare(
    expect: &[Expected],
    report_title: &str,
    got: &Map<String, Value>,
) -> Result<String, String> {
    let one = expect.len() == 1;
    let mut seen = Vec::new();
    let mut wrong = Vec::new();
    for e in expect {
        let unit = e.unit.as_deref();
        let name = if one {
            String::new()
        } else {
            format!("{} ", e.field)
        };
        match got.get(&e.field) {
            Some(v) if shows(e, v) => seen.push(format!("{name}{}", shown(v, e.step, unit))),
            Some(v) => wrong.push(format!(
                "{}{}, not the {} sent",
                if one { "" } else { &name },
                shown(v, e.step, unit),
                shown(&e.value, e.step, unit)
            )),
            None => wrong.push(format!(
                "no `{}` (the {} sent)",
                e.field,
                shown(&e.value, e.step, unit)
            )),
        }
    }
    if wrong.is_empty() {
        Ok(format!("{report_title} {}", seen.join(", ")))
    } else {
        Err(format!("{report_title} {}", wrong.join(", ")))
    }
}

/// What is known of a component's acknowledgements.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Habit {
    /// Nothing yet.
    Unknown,
    /// It acknowledged a command.
    Acknowledges,
    /// It let a command go unacknowledged whose effect was seen (or its node learnt
    /// that it never answers requests for one).
    Silent,
}

/// The habits of the components commanded, learnt as commands end (bounded).
#[derive(Debug, Default, Clone)]
pub struct Habits {
    map: HashMap<Address, bool>,
}

impl Habits {
    /// What is known of `a`.
    pub fn of(&self, a: Address) -> Habit {
        match self.map.get(&a) {
            None => Habit::Unknown,
            Some(true) => Habit::Acknowledges,
            Some(false) => Habit::Silent,
        }
    }

    /// `a` acknowledged (true) or let a command go unacknowledged while its effect was
    /// seen (false).
    pub fn learn(&mut self, a: Address, acknowledges: bool) {
        if self.map.len() < MAX_HABITS || self.map.contains_key(&a) {
            self.map.insert(a, acknowledges);
        }
    }
}

/// What a [`Confirming`] asks of its caller.
#[derive(Debug, Clone, PartialEq)]
pub enum Step {
    /// Nothing now.
    Idle,
    /// Send this query (code, body) to the component.
    Ask(CommandCode, Vec<u8>),
    /// The command ended so.
    Done(Confirmation),
}

/// One command being confirmed: sans-IO, driven by its caller's loop.
#[derive(Debug)]
pub struct Confirming {
    /// The component commanded.
    pub to: Address,
    /// The command's code.
    pub code: CommandCode,
    /// The command's name.
    pub name: String,
    check: Check,
    habit: Habit,
    ack_wait: Duration,
    wait: Duration,
    left: bool,
    read_from: Instant,
    until: Instant,
    /// The effect seen before the acknowledgement was given up on (a control
    /// request's answer): the end once it is.
    effect: Option<Confirmation>,
    next_ask: Option<Instant>,
    seen: Option<String>,
    answered: bool,
    acked: bool,
    done: Option<Confirmation>,
}

impl Confirming {
    /// Command `name` (`code`) given to the node for `to` at `now`, its effect seen by
    /// `check`; `habit` is what is known of `to`; `wait` bounds the read-back. The
    /// caller tells when the command leaves ([`departed`](Self::departed)).
    pub fn new(
        to: Address,
        code: CommandCode,
        name: &str,
        check: Check,
        habit: Habit,
        now: Instant,
        wait: Duration,
    ) -> Confirming {
        let ack_wait = match habit {
            Habit::Silent => SETTLE,
            Habit::Acknowledges => wait,
            Habit::Unknown => ACK_WAIT.min(wait),
        };
        let read_from = now + HELD_AT_MOST + ack_wait;
        let wait = wait.max(ASK_EVERY);
        Confirming {
            to,
            code,
            name: name.to_string(),
            check,
            habit,
            ack_wait,
            wait,
            left: false,
            read_from,
            until: read_from + wait,
            effect: None,
            next_ask: None,
            seen: None,
            answered: false,
            acked: false,
            done: None,
        }
    }

    /// The command left at `now` (its first copy went out): the acknowledgement is
    /// waited for, and the effect read back, from then.
    pub fn departed(&mut self, now: Instant) {
        if !self.left {
            self.left = true;
            self.read_from = now + self.ack_wait;
            self.until = self.read_from + self.wait;
        }
    }

    /// A datagram leaving at `now` (framed with `framing`): the command's departure
    /// when it carries the command.
    pub fn leaving(&mut self, framing: jaus::net::Framing, datagram: &[u8], now: Instant) {
        if self.left {
            return;
        }
        if let Ok((h, _)) = framing.packet(datagram) {
            if h.destination == self.to
                && h.command_code == self.code
                && !matches!(h.ack_nak, jaus::wire::AckNak::Ack | jaus::wire::AckNak::Nak)
            {
                self.departed(now);
            }
        }
    }

    /// An ACK (or a NAK, with the receiver's reason when it gave one) for the command.
    pub fn ack(&mut self, nak: bool, reason: Option<&str>) {
        if self.done.is_some() {
            return;
        }
        self.acked = true;
        self.done = Some(if nak {
            Confirmation::Refused(format!(
                "NAK from {}: {}",
                self.to,
                reason.unwrap_or("refused (the receiver gave no reason)")
            ))
        } else {
            Confirmation::Acknowledged
        });
    }

    /// A Report Refusal of the command from the component.
    pub fn refused(&mut self, text: &str) {
        if self.done.is_none() {
            self.done = Some(Confirmation::Refused(format!(
                "Report Refusal from {}: {text}",
                self.to
            )));
        }
    }

    /// A message `code` with `body` from `from`: true when it was the read-back (or
    /// control answer) this waits for.
    pub fn message(
        &mut self,
        checks: &Checks,
        from: Address,
        code: CommandCode,
        body: &[u8],
    ) -> bool {
        if self.done.is_some() || !self.to.matches(&from) {
            return false;
        }
        match &self.check {
            Check::ReadBack {
                report,
                report_title,
                expect,
                ..
            } if *report == code => {
                let Some(got) = checks.fields(code, body) else {
                    return false;
                };
                self.answered = true;
                match compare(expect, report_title, &got) {
                    Ok(shown) => self.done = Some(Confirmation::ReadBack(shown)),
                    Err(seen) => self.seen = Some(seen),
                }
                true
            }
            Check::State(wanted) if code == REPORT_COMPONENT_STATUS => {
                let Some(got) = checks.fields(code, body) else {
                    return false;
                };
                let state = match got.get("primary_status_code") {
                    Some(Value::String(s)) => s.clone(),
                    Some(other) => other.to_string(),
                    None => "?".into(),
                };
                self.answered = true;
                if wanted.accepts(&state) {
                    self.done = Some(Confirmation::ReadBack(format!(
                        "Report Component Status {state}"
                    )));
                } else {
                    self.seen = Some(format!(
                        "still {state} after {} ({} expected)",
                        self.name,
                        wanted.text()
                    ));
                }
                true
            }
            Check::Control if code == CONFIRM_COMPONENT_CONTROL => {
                let response = checks
                    .fields(code, body)
                    .and_then(|f| f.get("response_code").cloned())
                    .map_or("?".to_string(), |v| shown(&v, 0.0, None));
                self.answered = true;
                if response == "ControlAccepted" {
                    // An acknowledgement may still come: it says more.
                    self.effect = Some(Confirmation::ReadBack(format!(
                        "Confirm Component Control {response}"
                    )));
                } else {
                    self.done = Some(Confirmation::Refused(format!(
                        "Confirm Component Control from {}: {response}",
                        self.to
                    )));
                }
                true
            }
            Check::Control if code == REJECT_COMPONENT_CONTROL => {
                self.answered = true;
                self.done = Some(Confirmation::Refused(format!(
                    "Reject Component Control from {} (another component holds control with an equal or higher authority)",
                    self.to
                )));
                true
            }
            _ => false,
        }
    }

    /// What to do at `now`.
    pub fn poll(&mut self, now: Instant) -> Step {
        if let Some(d) = self.done.take() {
            return Step::Done(d);
        }
        if now < self.read_from {
            return Step::Idle;
        }
        if let Some(e) = self.effect.take() {
            return Step::Done(e);
        }
        let (query, body) = match &self.check {
            Check::Nothing(why) => {
                return Step::Done(Confirmation::NotConfirmed(format!(
                    "{}; nothing shows {}'s effect ({why})",
                    self.ack_text(),
                    self.name
                )))
            }
            Check::ReadBack { query, body, .. } => (*query, body.clone()),
            Check::State(_) => (QUERY_COMPONENT_STATUS, Vec::new()),
            Check::Control => {
                if now < self.until {
                    return Step::Idle;
                }
                return Step::Done(Confirmation::NotConfirmed(format!(
                    "{}; no Confirm Component Control came",
                    self.ack_text()
                )));
            }
        };
        if now >= self.until {
            let read = match &self.check {
                Check::ReadBack { query_title, .. } => format!("the read-back ({query_title})"),
                _ => "the read-back (Query Component Status)".to_string(),
            };
            let what = match (&self.seen, self.answered) {
                (Some(seen), _) => format!("{read} shows {seen}"),
                _ => format!("{read} was not answered"),
            };
            return Step::Done(Confirmation::NotConfirmed(format!(
                "{}; {what}",
                self.ack_text()
            )));
        }
        if self.next_ask.is_none_or(|t| now >= t) {
            self.next_ask = Some(now + ASK_EVERY);
            return Step::Ask(query, body);
        }
        Step::Idle
    }

    /// What this command taught of its component: acknowledged (true), or its effect
    /// seen without an acknowledgement (false).
    pub fn learnt(&self) -> Option<bool> {
        if self.acked {
            Some(true)
        } else if self.answered {
            Some(false)
        } else {
            None
        }
    }

    /// What is known of the acknowledgement.
    fn ack_text(&self) -> String {
        match self.habit {
            Habit::Silent => format!(
                "{} never acknowledges (OpenJAUS 3.3 components send no ACK/NAK)",
                self.to
            ),
            _ => format!(
                "{} did not acknowledge {} within {:.1} s",
                self.to,
                self.name,
                self.ack_wait.as_secs_f64()
            ),
        }
    }
}

#[cfg(test)]
#[path = "confirm_tests.rs"]
mod tests;
