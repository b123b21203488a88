//! Core component states, component modes, and the typed errors of illegal transitions.

use std::fmt;

use crate::messages::ComponentState;

/// The core state of every JAUS component (RA 3.3; docs/wire.md §5.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CoreState {
    /// Starting up; no commands are executed.
    Initialize,
    /// Executing commands.
    Ready,
    /// Up, but holding still; commands that set targets are stored, motion waits for Ready.
    Standby,
    /// Stopped for good.
    Shutdown,
    /// A fault the component cannot recover from by itself.
    Failure,
    /// Emergency stop: nothing moves until every Set Emergency is cleared.
    Emergency,
}

/// What drives a core state change.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CoreTransition {
    /// Initialisation finished (Initialize → Standby).
    Initialized,
    /// Standby message (Ready → Standby).
    Standby,
    /// Resume message (Standby → Ready).
    Resume,
    /// Shutdown message (any → Shutdown).
    Shutdown,
    /// Reset message (→ Initialize; never out of Emergency or Shutdown).
    Reset,
    /// A fault (Initialize/Ready/Standby → Failure).
    Fail,
    /// Set Emergency (any but Shutdown → Emergency).
    SetEmergency,
    /// The last Clear Emergency (Emergency → Standby).
    ClearEmergency,
}

impl CoreState {
    /// The state reached by `t`, or a typed error when `t` is not allowed in `self`.
    ///
    /// Transitions that leave the state unchanged (Resume while Ready) are allowed.
    /// Emergency is left only by clearing it (or by Shutdown): Reset, Resume and
    /// Standby do not end an emergency. The rules are the generated table of
    /// `jaus-spec/defs/core_states.yaml`, run by [`crate::hsm`].
    pub fn apply(self, t: CoreTransition) -> Result<CoreState, TransitionError> {
        let def = &crate::messages::services::core_states::CORE_STATE_FSM;
        crate::hsm::state_id(def, self.path())
            .and_then(|from| crate::hsm::next_state(def, from, t.key()))
            .and_then(|to| def.states.get(usize::from(to)))
            .and_then(|s| CoreState::from_name(s.name))
            .ok_or(TransitionError {
                machine: "core state",
                from: self.name(),
                transition: t.name(),
            })
    }

    /// Its path in the core states' machine (`Live.Ready`; `Shutdown`).
    fn path(self) -> &'static str {
        match self {
            CoreState::Initialize => "Live.Initialize",
            CoreState::Ready => "Live.Ready",
            CoreState::Standby => "Live.Standby",
            CoreState::Shutdown => "Shutdown",
            CoreState::Failure => "Live.Failure",
            CoreState::Emergency => "Live.Emergency",
        }
    }

    /// The state named `name` (as Part 1 writes it).
    pub fn from_name(name: &str) -> Option<CoreState> {
        [
            CoreState::Initialize,
            CoreState::Ready,
            CoreState::Standby,
            CoreState::Shutdown,
            CoreState::Failure,
            CoreState::Emergency,
        ]
        .into_iter()
        .find(|s| s.name() == name)
    }

    /// The name as Part 1 writes it.
    pub fn name(self) -> &'static str {
        match self {
            CoreState::Initialize => "Initialize",
            CoreState::Ready => "Ready",
            CoreState::Standby => "Standby",
            CoreState::Shutdown => "Shutdown",
            CoreState::Failure => "Failure",
            CoreState::Emergency => "Emergency",
        }
    }

    /// The primary status code sent in Report Component Status.
    pub fn to_wire(self) -> ComponentState {
        match self {
            CoreState::Initialize => ComponentState::Initialize,
            CoreState::Ready => ComponentState::Ready,
            CoreState::Standby => ComponentState::Standby,
            CoreState::Shutdown => ComponentState::Shutdown,
            CoreState::Failure => ComponentState::Failure,
            CoreState::Emergency => ComponentState::Emergency,
        }
    }

    /// The state a Report Component Status names, if it names one.
    pub fn from_wire(s: ComponentState) -> Option<CoreState> {
        Some(match s {
            ComponentState::Initialize => CoreState::Initialize,
            ComponentState::Ready => CoreState::Ready,
            ComponentState::Standby => CoreState::Standby,
            ComponentState::Shutdown => CoreState::Shutdown,
            ComponentState::Failure => CoreState::Failure,
            ComponentState::Emergency => CoreState::Emergency,
            ComponentState::Unknown(_) => return None,
        })
    }
}

impl fmt::Display for CoreState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl CoreTransition {
    /// The trigger of the core states' machine (`jaus-spec/defs/core_states.yaml`).
    pub fn key(self) -> &'static str {
        match self {
            CoreTransition::Initialized => "Initialized",
            CoreTransition::Standby => "Standby",
            CoreTransition::Resume => "Resume",
            CoreTransition::Shutdown => "Shutdown",
            CoreTransition::Reset => "Reset",
            CoreTransition::Fail => "Fail",
            CoreTransition::SetEmergency => "SetEmergency",
            CoreTransition::ClearEmergency => "ClearEmergency",
        }
    }

    /// The name of the transition.
    pub fn name(self) -> &'static str {
        match self {
            CoreTransition::Initialized => "initialized",
            CoreTransition::Standby => "standby",
            CoreTransition::Resume => "resume",
            CoreTransition::Shutdown => "shutdown",
            CoreTransition::Reset => "reset",
            CoreTransition::Fail => "fail",
            CoreTransition::SetEmergency => "set emergency",
            CoreTransition::ClearEmergency => "clear emergency",
        }
    }
}

/// A transition that is not allowed from the current state.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{machine}: transition `{transition}` is not allowed in {from}")]
pub struct TransitionError {
    /// The state machine (`core state`, or the component whose modes these are).
    pub machine: &'static str,
    /// The state it was in.
    pub from: &'static str,
    /// The transition refused.
    pub transition: &'static str,
}

/// Component-specific sub-states of Ready, generated from the `modes:` of a component
/// definition. The runtime returns to [`Modes::INITIAL`] whenever the component leaves
/// Ready.
pub trait Modes: Copy + Eq + fmt::Debug + Send + 'static {
    /// The transitions between modes.
    type Transition: Copy + Eq + fmt::Debug + Send + 'static;
    /// The mode on entering Ready.
    const INITIAL: Self;
    /// The component these modes belong to (for errors).
    const MACHINE: &'static str;
    /// The mode name as the definition writes it.
    fn name(self) -> &'static str;
    /// The mode `t` leads to from `self`, or `None` if `t` is not allowed in `self`.
    fn next(self, t: Self::Transition) -> Option<Self>;
    /// The transition name as the definition writes it.
    fn transition_name(t: Self::Transition) -> &'static str;
    /// The core state the component enters with `t`, if any.
    fn core_effect(t: Self::Transition) -> Option<CoreTransition>;

    /// The mode `t` leads to, or a typed error.
    fn apply(self, t: Self::Transition) -> Result<Self, TransitionError> {
        self.next(t).ok_or(TransitionError {
            machine: Self::MACHINE,
            from: self.name(),
            transition: Self::transition_name(t),
        })
    }
}

/// The modes of a component without sub-states: just Ready.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NoModes {
    /// The only mode.
    Ready,
}

/// No transitions exist between [`NoModes`] (this type has no values).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NoTransition {}

impl Modes for NoModes {
    type Transition = NoTransition;
    const INITIAL: Self = NoModes::Ready;
    const MACHINE: &'static str = "component";
    fn name(self) -> &'static str {
        "Ready"
    }
    fn next(self, t: NoTransition) -> Option<Self> {
        match t {}
    }
    fn transition_name(t: NoTransition) -> &'static str {
        match t {}
    }
    fn core_effect(t: NoTransition) -> Option<CoreTransition> {
        match t {}
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use CoreState::*;
    use CoreTransition as T;

    const ALL: [CoreState; 6] = [Initialize, Ready, Standby, Shutdown, Failure, Emergency];

    #[test]
    fn emergency_is_left_only_by_clearing_or_shutdown() {
        for t in [T::Standby, T::Resume, T::Reset, T::Fail, T::Initialized] {
            let e = Emergency.apply(t).unwrap_err();
            assert_eq!(e.from, "Emergency");
        }
        assert_eq!(Emergency.apply(T::ClearEmergency), Ok(Standby));
        assert_eq!(Emergency.apply(T::Shutdown), Ok(Shutdown));
    }

    #[test]
    fn shutdown_is_final_and_emergency_reachable_from_every_live_state() {
        for s in ALL {
            let e = s.apply(T::SetEmergency);
            if s == Shutdown {
                assert!(e.is_err());
            } else {
                assert_eq!(e, Ok(Emergency));
            }
            assert_eq!(s.apply(T::Shutdown), Ok(Shutdown));
        }
        assert_eq!(Ready.apply(T::Standby), Ok(Standby));
        assert_eq!(Standby.apply(T::Resume), Ok(Ready));
        assert!(Initialize.apply(T::Resume).is_err());
        assert!(Failure.apply(T::Resume).is_err());
        assert_eq!(Failure.apply(T::Reset), Ok(Initialize));
        assert_eq!(
            Initialize.apply(T::Resume).unwrap_err().to_string(),
            "core state: transition `resume` is not allowed in Initialize"
        );
    }

    #[test]
    fn wire_states_round_trip() {
        for s in ALL {
            assert_eq!(CoreState::from_wire(s.to_wire()), Some(s));
        }
        assert_eq!(CoreState::from_wire(ComponentState::Unknown(9)), None);
    }
}
