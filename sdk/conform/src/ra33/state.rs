//! Core state commands: from the controller they are carried out, from anyone else
//! refused; Set/Clear Emergency from anyone.

use jaus::messages::{
    ComponentState, Message, QueryComponentStatus, ReportComponentStatus, Reset, Resume, Shutdown,
    Standby,
};

use super::core::ack_text;
use super::watch::{changes, Poll};
use super::Ra33Voice;
use crate::check::{StateCommand, Verdict};
use jaus::codec::Encode;
use jaus::JausMessage;

use crate::engine::Found;

fn message(s: StateCommand) -> Message {
    match s {
        StateCommand::Standby => Standby {}.into(),
        StateCommand::Resume => Resume {}.into(),
        StateCommand::Shutdown => Shutdown {}.into(),
        StateCommand::Reset => Reset {}.into(),
    }
}

impl Ra33Voice<'_> {
    /// Holds control and brings the target to `state`; `Err` when it cannot.
    pub(super) fn prepare(&mut self, state: Option<ComponentState>) -> Result<(), String> {
        self.hold_control()?;
        if let Some(want) = state {
            if !self.set_state(self.voices.controller, want) {
                return Err(format!(
                    "the controller could not bring the component to {want:?} (now {:?})",
                    self.status()
                ));
            }
        }
        Ok(())
    }

    pub(super) fn state_from_controller(&mut self, s: StateCommand) -> Found {
        let (from, to) = match s {
            StateCommand::Standby => (ComponentState::Ready, ComponentState::Standby),
            StateCommand::Resume => (ComponentState::Standby, ComponentState::Ready),
            // Never sent by the controller (not planned): nothing to decide.
            StateCommand::Shutdown | StateCommand::Reset => {
                return (Verdict::Inconclusive, "not sent by the controller".into())
            }
        };
        if let Err(e) = self.prepare(Some(from)) {
            return (Verdict::Inconclusive, e);
        }
        let ack = self.command(self.voices.controller, &message(s));
        match self.status() {
            Some(now) if now == to => (
                Verdict::Pass,
                format!("{from:?} → {to:?}; {}", ack_text(ack)),
            ),
            Some(now) => (
                Verdict::Fail,
                format!(
                    "still {now:?} after {} from the controller ({})",
                    s.name(),
                    ack_text(ack)
                ),
            ),
            None => (Verdict::Fail, "no status after the command".into()),
        }
    }

    /// The command from the outsider must leave the state as it was; that counts only
    /// when the same command from the controller then changes it (a component that
    /// ignores the command from everyone proves nothing: inconclusive). Shutdown is
    /// not sent by the controller (it cannot be undone): Standby from the controller
    /// stands in for it, showing that the component obeys its controller's state
    /// commands, and Resume brings it back.
    pub(super) fn state_from_outsider(&mut self, s: StateCommand) -> Found {
        let before = match s {
            StateCommand::Resume => ComponentState::Standby,
            _ => ComponentState::Ready,
        };
        if let Err(e) = self.prepare(Some(before)) {
            return (Verdict::Inconclusive, e);
        }
        let o = self.voices.outsider;
        let m = message(s);
        let Ok(body) = m.to_bytes() else {
            return (
                Verdict::Inconclusive,
                format!("{} does not encode", s.name()),
            );
        };
        let poll = Poll {
            code: QueryComponentStatus::CODE,
            body: Vec::new(),
            report: ReportComponentStatus::CODE,
        };
        let w = self.watch(
            o,
            m.code(),
            body,
            &poll,
            |_, body| match Message::decode_known(ReportComponentStatus::CODE, body) {
                Ok(Message::ReportComponentStatus(r)) => Some(r.primary_status_code),
                _ => None,
            },
        );
        let how = w.how("Query Component Status");
        if let Some(change) = changes(&w.seen, |v| format!("{v:?}"), |v| *v != before) {
            let now = w.seen.last().map(|(_, v)| *v);
            if now != Some(before) {
                // Bring it back for the checks after this one, where it can be.
                self.set_state(self.voices.controller, before);
            }
            return (
                Verdict::Fail,
                format!(
                    "{} from {o} (not in control), in {before:?}: the component {change}; {} ({how})",
                    s.name(),
                    ack_text(w.ack)
                ),
            );
        }
        match w.seen.last() {
            Some((_, now)) => {
                let refused = format!(
                    "still {now:?} after {} from {o}, in every answer ({how}); {}",
                    s.name(),
                    ack_text(w.ack)
                );
                self.compare_with_controller(s, before, refused)
            }
            None => (
                Verdict::Fail,
                format!("no status after {} from {o} ({how})", s.name()),
            ),
        }
    }

    /// After the outsider's `s` was refused in state `before` (`refused` says how),
    /// sends the same command from the controller (Standby for Shutdown): a pass when it
    /// changes the state, inconclusive when it does not.
    fn compare_with_controller(
        &mut self,
        s: StateCommand,
        before: ComponentState,
        refused: String,
    ) -> Found {
        let c = self.voices.controller;
        let sent = match s {
            StateCommand::Shutdown => StateCommand::Standby,
            other => other,
        };
        let ack = self.command(c, &message(sent));
        self.drain(self.opts.settle);
        let now = self.status();
        if s == StateCommand::Shutdown {
            // Back to Ready for the checks after this one (and the teardown).
            self.set_state(c, ComponentState::Ready);
        }
        match now {
            Some(now) if now != before => {
                let stand_in = if s == StateCommand::Shutdown {
                    " (Shutdown itself is not sent: it cannot be undone)"
                } else {
                    ""
                };
                (
                    Verdict::Pass,
                    format!(
                        "{refused}; {} from the controller {c} took it {before:?} → {now:?}{stand_in} ({})",
                        sent.name(),
                        ack_text(ack)
                    ),
                )
            }
            Some(now) => (
                Verdict::Inconclusive,
                format!(
                    "{refused}; the controller's own {} had no effect either: nothing to compare (still {now:?}; {})",
                    sent.name(),
                    ack_text(ack)
                ),
            ),
            None => (
                Verdict::Inconclusive,
                format!(
                    "{refused}; no status after the controller's own {}: nothing to compare",
                    sent.name()
                ),
            ),
        }
    }

    pub(super) fn emergency_set(&mut self) -> Found {
        if let Err(e) = self.prepare(None) {
            return (Verdict::Inconclusive, e);
        }
        let o = self.voices.outsider;
        self.set_emergency(o);
        let found = match self.status() {
            Some(ComponentState::Emergency) => (
                Verdict::Pass,
                format!("Emergency after Set Emergency from {o}"),
            ),
            Some(now) => (
                Verdict::Fail,
                format!("{now:?}, not Emergency, after Set Emergency from {o} (not in control)"),
            ),
            None => (Verdict::Fail, "no status after Set Emergency".into()),
        };
        self.clear_emergency(o);
        found
    }

    pub(super) fn emergency_clear(&mut self) -> Found {
        if let Err(e) = self.prepare(None) {
            return (Verdict::Inconclusive, e);
        }
        let o = self.voices.outsider;
        self.set_emergency(o);
        if self.status() != Some(ComponentState::Emergency) {
            return (
                Verdict::Inconclusive,
                "Set Emergency did not bring the component to Emergency".into(),
            );
        }
        self.clear_emergency(o);
        match self.status() {
            Some(ComponentState::Emergency) => (
                Verdict::Fail,
                format!("still Emergency after Clear Emergency from {o}"),
            ),
            Some(now) => (
                Verdict::Pass,
                format!("{now:?} after Clear Emergency from {o}"),
            ),
            None => (Verdict::Fail, "no status after Clear Emergency".into()),
        }
    }
}
