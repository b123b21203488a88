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
        let ack = self.command(o, &message(s));
        self.drain(self.opts.settle);
        match self.status() {
            Some(now) if now == before => {
                let refused = format!(
                    "still {now:?} after {} from {o}; {}",
                    s.name(),
                    ack_text(ack)
                );
                self.compare_with_controller(s, before, refused)
            }
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
