//! Read-back checks, from the definitions alone: for a command with `readback: Query`,
//! the current value is asked, the command is built from it (fields named alike) with
//! one scaled field moved, and the value the query reports afterwards is compared
//! within one count of that field's scaling. The same command from a component not in
//! control must change nothing.
//!
//! The messages are built, encoded and decoded through the loaded definitions
//! ([`jaus_dynamic::Schema`]), so a vendor overlay's commands and queries (`--spec`)
//! are exchanged on the wire as the SDK's are.

use jaus::messages::ComponentState;
use jaus::wire::AckNak;
use jaus::Address;
use jaus_dynamic::DynMessage;
use jaus_spec::{Int, Wire};
use serde_json::{Map, Value};

use super::core::ack_text;
use super::watch::{changes, Poll};
use super::Ra33Voice;
use crate::check::Verdict;

use crate::engine::Found;

/// A command ready to send, and how to judge what is read back.
struct Trial {
    /// The command with the moved value.
    moved: DynMessage,
    /// The command restoring what was read first, when it could be built.
    restore: Option<DynMessage>,
    /// The field moved.
    field: String,
    /// Its value before (as read back), when the report carried it.
    before: Option<f64>,
    /// The value sent, as the wire carries it.
    sent: f64,
    /// One count of the field's scaling.
    count: f64,
}

/// The largest value of integer type `ty` (`u8`, `i16`, ...).
fn int_max(ty: &str) -> Option<u64> {
    Int::parse(ty).map(|i| {
        let bits = 8 * i.bytes() as u32 - u32::from(!i.unsigned());
        if bits >= 64 {
            u64::MAX
        } else {
            (1u64 << bits) - 1
        }
    })
}

/// A value read back, or that the report left it out.
fn shown(v: Option<f64>) -> String {
    v.map_or_else(|| "absent".to_string(), |v| v.to_string())
}

impl Ra33Voice<'_> {
    /// The message `name` of the definitions with `fields` (JSON, as `jaus decode`
    /// prints them).
    fn build(&self, name: &str, fields: Map<String, Value>) -> Result<DynMessage, String> {
        self.schema
            .from_json(name, &Value::Object(fields))
            .map_err(|e| format!("{name}: {e}"))
    }

    /// The fields of a body of the definitions' message `code`, as JSON.
    fn fields(&self, code: jaus::CommandCode, body: &[u8]) -> Option<Map<String, Value>> {
        let m = self.schema.decode(code, body).ok()?;
        match serde_json::to_value(&m.fields).ok()? {
            Value::Object(o) => Some(o),
            _ => Some(Map::new()),
        }
    }

    /// Sends `q` from `from` and waits for its report (named by the definitions); the
    /// report's fields.
    fn ask_def(&mut self, from: Address, q: &DynMessage) -> Option<(String, Map<String, Value>)> {
        let r = self.spec.report_of(&self.spec.message(q.name)?.def)?;
        let (report, code) = (r.def.name.clone(), jaus::CommandCode(r.def.code.0));
        let body = self.schema.encode(q).ok()?;
        self.send_body(from, q.code, body, false);
        let target = self.target;
        let p = self.wait_for(self.opts.wait, |p| {
            p.header.source == target
                && p.header.destination == from
                && p.header.command_code == code
                && !matches!(p.header.ack_nak, AckNak::Ack | AckNak::Nak)
        })?;
        Some((report, self.fields(code, &p.body)?))
    }

    /// Sends command `m` from `from` asking for an acknowledgement.
    fn command_def(&mut self, from: Address, m: &DynMessage) -> Option<AckNak> {
        let body = self.schema.encode(m).ok()?;
        self.command_body(from, m.code, body)
    }

    /// The read-back query, its presence vectors all ones, its other integers zero.
    fn query(&self, query: &str) -> Result<DynMessage, String> {
        let def = self
            .spec
            .message(query)
            .ok_or_else(|| format!("query `{query}` is not defined"))?;
        let mut fields = Map::new();
        for f in &def.def.fields {
            let max = int_max(&f.ty).ok_or_else(|| {
                format!(
                    "{query}.{}: only integer query fields are filled in",
                    f.name
                )
            })?;
            // Presence vectors ask for every field; a selector (a camera, a waypoint
            // number) asks for the first one.
            let v = if f.name.contains("presence") { max } else { 1 };
            fields.insert(f.name.clone(), v.into());
        }
        self.build(query, fields)
    }

    /// A query the definitions give the component is answered with its report.
    pub(super) fn query_answered(&mut self, query: &str) -> Found {
        let q = match self.query(query) {
            Ok(q) => q,
            Err(e) => return (Verdict::Inconclusive, e),
        };
        let selectors: Vec<String> = self
            .spec
            .message(query)
            .map(|m| {
                m.def
                    .fields
                    .iter()
                    .filter(|f| !f.name.contains("presence"))
                    .map(|f| format!("{} = 1", f.name))
                    .collect()
            })
            .unwrap_or_default();
        match self.ask_def(self.voices.outsider, &q) {
            Some((r, _)) => (Verdict::Pass, format!("answered with {r}")),
            // The component may hold no such item: not decided.
            None if !selectors.is_empty() => (
                Verdict::Inconclusive,
                format!(
                    "no answer to {query} asking for {} (the component may hold none)",
                    selectors.join(", ")
                ),
            ),
            None => (
                Verdict::Fail,
                format!("no answer to {query} within {:?}", self.opts.wait),
            ),
        }
    }

    /// Reads the current value and prepares the trial.
    fn trial(&mut self, command: &str, query: &DynMessage) -> Result<Option<Trial>, String> {
        let cmd = self
            .spec
            .message(command)
            .ok_or_else(|| format!("command `{command}` is not defined"))?;
        let Some((_, now)) = self.ask_def(self.voices.outsider, query) else {
            return Ok(None);
        };
        let mut fields = Map::new();
        for f in &cmd.def.fields {
            if let Some(v) = now.get(&f.name) {
                fields.insert(f.name.clone(), v.clone());
            }
        }
        let restore = self.build(command, fields.clone()).ok();
        // The field moved: the first scaled one the report carries, else the first
        // integer (moved by one, compared exactly); never a field the query selects
        // the item by (a tank, a waypoint number).
        let selectors: Vec<String> = self
            .spec
            .message(query.name)
            .map(|q| q.def.fields.iter().map(|f| f.name.clone()).collect())
            .unwrap_or_default();
        let carried = |f: &&jaus_spec::Field| {
            (now.contains_key(&f.def.name) || f.def.bit.is_some())
                && !selectors.contains(&f.def.name)
        };
        let scaled = cmd
            .fields
            .iter()
            .filter(carried)
            .find_map(|f| match &f.wire {
                Wire::Scaled { int, lo, hi } => Some((f.def.name.clone(), *lo, *hi, *int)),
                _ => None,
            });
        let (field, value, count, before) = match scaled {
            Some((field, lo, hi, int)) => {
                let count = (hi - lo) / ((2f64).powi(8 * int.bytes() as i32) - 1.0);
                let before = now.get(&field).and_then(Value::as_f64);
                // A modest value (a platform may refuse speeds beyond what it can do),
                // at least three counts from the current one.
                let value = [1.0, 0.5, 2.0, lo + (hi - lo) * 0.0013, (lo + hi) / 2.0]
                    .into_iter()
                    .filter(|v| (lo..=hi).contains(v))
                    .find(|v| before.is_none_or(|b| (v - b).abs() > 3.0 * count))
                    .unwrap_or(lo);
                (field, Value::from(value), count, before)
            }
            None => {
                let (field, max) = cmd
                    .fields
                    .iter()
                    .filter(carried)
                    .find_map(|f| match &f.wire {
                        Wire::Int(i) => int_max(i.rust()).map(|m| (f.def.name.clone(), m)),
                        _ => None,
                    })
                    .ok_or_else(|| {
                        format!("{command} has no scaled or integer field its report carries")
                    })?;
                let b = now.get(&field).and_then(Value::as_u64).unwrap_or(0);
                let v = if b < max { b + 1 } else { b - 1 };
                (field, Value::from(v), 0.0, Some(b as f64))
            }
        };
        fields.insert(field.clone(), value.clone());
        let moved = self.build(command, fields)?;
        // The value as the wire carries it.
        let bytes = self
            .schema
            .encode(&moved)
            .map_err(|e| format!("{command}: {e}"))?;
        let sent = self
            .fields(moved.code, &bytes)
            .ok_or_else(|| format!("{command}: its own encoding does not decode"))?
            .get(&field)
            .and_then(Value::as_f64)
            .or(value.as_f64())
            .unwrap_or(0.0);
        Ok(Some(Trial {
            moved,
            restore,
            field,
            before,
            sent,
            count,
        }))
    }

    /// The read-back query `q` as a [`Poll`] for a watch.
    fn poll_of(&self, q: &DynMessage) -> Option<Poll> {
        let r = self.spec.report_of(&self.spec.message(q.name)?.def)?;
        Some(Poll {
            code: q.code,
            body: self.schema.encode(q).ok()?,
            report: jaus::CommandCode(r.def.code.0),
        })
    }

    /// The field's value in a fresh read-back.
    fn read(&mut self, query: &DynMessage, field: &str) -> Option<Option<f64>> {
        let (_, r) = self.ask_def(self.voices.outsider, query)?;
        Some(r.get(field).and_then(Value::as_f64))
    }

    /// What both read-back checks start with: the component in Ready under the
    /// tester's control, the query, and the trial command built from what it reads now.
    /// `Err` is the verdict when that fails: inconclusive, the query not answered
    /// included (the read-back query is advisory: without its answer nothing can be
    /// compared, which `query.<name>` reports on its own).
    fn setup(&mut self, command: &str, query: &str) -> Result<(DynMessage, Trial), Found> {
        // Commands are carried out in Ready (a driver in Standby may refuse them).
        self.prepare(Some(ComponentState::Ready))
            .map_err(|e| (Verdict::Inconclusive, e))?;
        let q = self.query(query).map_err(|e| (Verdict::Inconclusive, e))?;
        match self.trial(command, &q) {
            Ok(Some(t)) => Ok((q, t)),
            Ok(None) => Err((
                Verdict::Inconclusive,
                format!(
                    "the read-back query {query} was not answered (within {:?}): {command} was not sent, nothing can be read back",
                    self.opts.wait
                ),
            )),
            Err(e) => Err((Verdict::Inconclusive, e)),
        }
    }

    pub(super) fn readback(&mut self, command: &str, query: &str) -> Found {
        let (q, t) = match self.setup(command, query) {
            Ok(x) => x,
            Err(found) => return found,
        };
        let c = self.voices.controller;
        let ack = self.command_def(c, &t.moved);
        let found = match self.read(&q, &t.field) {
            None => (
                Verdict::Fail,
                format!("no answer to {query} after {command} ({})", ack_text(ack)),
            ),
            Some(None) => (
                Verdict::Fail,
                format!(
                    "{query}'s report does not carry `{}` after {command} set it",
                    t.field
                ),
            ),
            Some(Some(v)) if (v - t.sent).abs() <= t.count * 1.01 + 1e-12 => (
                Verdict::Pass,
                format!(
                    "{} = {v} read back ({} sent, one count {:.3e}); {}",
                    t.field,
                    t.sent,
                    t.count,
                    ack_text(ack)
                ),
            ),
            Some(Some(v)) => (
                Verdict::Fail,
                format!(
                    "{} = {v} read back, {} sent (one count {:.3e}); {}",
                    t.field,
                    t.sent,
                    t.count,
                    ack_text(ack)
                ),
            ),
        };
        if let Some(r) = &t.restore {
            self.command_def(c, r);
        }
        found
    }

    /// The command from the outsider must leave the value as it was; that counts only
    /// when the same command from the controller then changes it (a component that
    /// ignores the command from everyone proves nothing: inconclusive).
    pub(super) fn outsider_command(&mut self, command: &str, query: &str) -> Found {
        let (q, t) = match self.setup(command, query) {
            Ok(x) => x,
            Err(found) => return found,
        };
        let (o, c) = (self.voices.outsider, self.voices.controller);
        let (Some(poll), Ok(body)) = (self.poll_of(&q), self.schema.encode(&t.moved)) else {
            return (
                Verdict::Inconclusive,
                format!("{command} or {query} does not encode"),
            );
        };
        let (report, field) = (poll.report, t.field.clone());
        let w = self.watch(o, t.moved.code, body, &poll, |e, body| {
            Some(e.fields(report, body)?.get(&field).and_then(Value::as_f64))
        });
        let how = w.how(query);
        let ack = w.ack;
        let (sent, count) = (t.sent, t.count);
        let moved = |v: &Option<f64>| v.is_some_and(|v| (v - sent).abs() <= count * 1.01 + 1e-12);
        if let Some(change) = changes(&w.seen, |v| format!("{} = {}", t.field, shown(*v)), moved) {
            if let Some(r) = &t.restore {
                self.command_def(c, r);
            }
            return (
                Verdict::Fail,
                format!(
                    "{command} from {o} (not in control), {} was {}: the component {change}; {} ({how})",
                    t.field,
                    shown(t.before),
                    ack_text(ack)
                ),
            );
        }
        let after = match w.seen.last() {
            None => {
                return (
                    Verdict::Inconclusive,
                    format!("no answer to {query} after {command} from {o} ({how})"),
                )
            }
            Some((_, v)) => *v,
        };
        // The same command from the controller: the comparison the refusal needs.
        let own = self.command_def(c, &t.moved);
        self.drain(self.opts.settle);
        let found = match self.read(&q, &t.field) {
            Some(Some(v)) if (v - t.sent).abs() <= t.count * 1.01 + 1e-12 => (
                Verdict::Pass,
                format!(
                    "{} = {} after {command} from {o}, in every answer ({how}; {} sent; {}); the same from the controller {c} set it to {v} ({})",
                    t.field,
                    shown(after),
                    t.sent,
                    ack_text(ack),
                    ack_text(own)
                ),
            ),
            Some(v) => (
                Verdict::Inconclusive,
                format!(
                    "{} = {} after {command} from {o} ({}); the controller's own {command} had no effect either: nothing to compare ({} = {} after it, {} sent; {})",
                    t.field,
                    shown(after),
                    ack_text(ack),
                    t.field,
                    shown(v),
                    t.sent,
                    ack_text(own)
                ),
            ),
            None => (
                Verdict::Inconclusive,
                format!(
                    "{} = {} after {command} from {o} ({}); no answer to {query} after the controller's own {command}: nothing to compare",
                    t.field,
                    shown(after),
                    ack_text(ack)
                ),
            ),
        };
        if let Some(r) = &t.restore {
            self.command_def(c, r);
        }
        found
    }
}
