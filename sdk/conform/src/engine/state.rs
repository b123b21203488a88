//! Core state commands: from the controller they are carried out, from anyone else
//! refused; Set/Clear Emergency from anyone.

use jaus::messages::{ComponentState, Message, Reset, Resume, Shutdown, Standby};

use super::core::ack_text;
use super::Engine;
use crate::check::{StateCommand, Verdict};

type Found = (Verdict, String);

fn message(s: StateCommand) -> Message {
    match s {
        StateCommand::Standby => Standby {}.into(),
        StateCommand::Resume => Resume {}.into(),
        StateCommand::Shutdown => Shutdown {}.into(),
        StateCommand::Reset => Reset {}.into(),
    }
}

impl Engine<'_> {
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

    pub(super) fn state_from_outsider(&mut self, s: StateCommand) -> Found {
        let before = match s {
            StateCommand::Resume => ComponentState::Standby,
            _ => ComponentState::Ready,
        };
        if let Err(e) = self.prepare(Some(before)) {
            return (Verdict::Inconclusive, e);
        }
        let o = self.voices.outsider;
        let ack = self.command(o, &message(s));
        self.drain(self.opts.settle);
        match self.status() {
            Some(now) if now == before => (
                Verdict::Pass,
                format!(
                    "still {now:?} after {} from {o}; {}",
                    s.name(),
                    ack_text(ack)
                ),
            ),
            Some(now) => (
                Verdict::Fail,
                format!(
                    "{before:?} → {now:?} after {} from {o}, which is not in control ({})",
                    s.name(),
                    ack_text(ack)
                ),
            ),
            None => (
                Verdict::Fail,
                format!("no status after {} from {o}", s.name()),
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
