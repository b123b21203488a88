//! The `services:` section of a definition file: services with their message sets,
//! internal events and protocol behaviour (hierarchical state machines), as the SAE
//! AS-4 service sets define them in JSIDL (AS5684). Validation checks its names and
//! references; jaus-gen generates from it a trait of the service's guards and actions
//! and the tables of its state machines, which `jaus::hsm` runs.

use super::FieldDef;
use serde::Deserialize;

/// A service (`services:` of a file).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ServiceDef {
    /// PascalCase name, unique in the set.
    pub name: String,
    /// The service's URI (`urn:jaus:jss:core:AccessControl`).
    pub id: String,
    /// Its version (`"1.1"`).
    pub version: String,
    /// What the service does.
    #[serde(default)]
    pub description: Option<String>,
    /// What it assumes of its environment.
    #[serde(default)]
    pub assumptions: Option<String>,
    /// The service it inherits from: its messages, events and behaviour.
    #[serde(default)]
    pub inherits: Option<ServiceRef>,
    /// Services it is a client of (it sends them messages).
    #[serde(default)]
    pub client_of: Vec<ServiceRef>,
    /// Messages it receives (message names of the set).
    #[serde(default)]
    pub inputs: Vec<String>,
    /// Messages it sends (message names of the set).
    #[serde(default)]
    pub outputs: Vec<String>,
    /// Internal events: triggers of transitions that are not received messages.
    #[serde(default)]
    pub events: Vec<EventDef>,
    /// Its protocol behaviour.
    #[serde(default)]
    pub behaviour: Option<BehaviourDef>,
}

/// A reference to another service, by URI and version (`inherits:` of a service).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ServiceRef {
    /// The local name the definitions use for it (`events`), the prefix of the names of
    /// its state machines and events in the inheriting service (`events.transport.Send`).
    pub name: String,
    /// Its URI.
    pub id: String,
    /// Its version.
    pub version: String,
}

/// An internal event of a service.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EventDef {
    /// PascalCase name.
    pub name: String,
    /// When it occurs.
    #[serde(default)]
    pub description: Option<String>,
    /// The data it carries, in order. An internal event is never sent, so its fields
    /// need no count or length: only their types must be known.
    #[serde(default)]
    pub fields: Vec<FieldDef>,
}

/// The protocol behaviour of a service.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BehaviourDef {
    /// The service keeps no state between messages.
    #[serde(default)]
    pub stateless: bool,
    /// Where each state machine starts.
    #[serde(default)]
    pub start: Vec<StartDef>,
    /// The state machines.
    pub machines: Vec<MachineDef>,
}

/// The start state of one state machine.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StartDef {
    /// The state machine's name.
    pub machine: String,
    /// The state's path from the machine's top (`Receiving.Ready.NotControlled`).
    pub state: String,
}

/// A state machine.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MachineDef {
    /// Its name; a name with dots (`events.transport.ReceiveFSM`) is the machine of an
    /// inherited service, which this one extends.
    pub name: String,
    /// What it does (JSIDL's interpretation).
    #[serde(default)]
    pub description: Option<String>,
    /// It extends the machine of the same name of the inherited service: its states
    /// and transitions add to (or, with `redefine`, replace) the parent's.
    #[serde(default)]
    pub extends: bool,
    /// Its top-level states.
    pub states: Vec<StateDef>,
    /// Transitions taken in any state for a trigger no state handles.
    #[serde(default)]
    pub default: Option<DefaultStateDef>,
}

/// A state, possibly with sub-states.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StateDef {
    /// Its name (unique among its siblings).
    pub name: String,
    /// What it means.
    #[serde(default)]
    pub description: Option<String>,
    /// The sub-state entered when this state is entered (needs `states`).
    #[serde(default)]
    pub initial: Option<String>,
    /// It redefines the inherited state of the same path, to extend it.
    #[serde(default)]
    pub redefine: bool,
    /// Actions on entering the state.
    #[serde(default)]
    pub entry: Vec<ActionDef>,
    /// Actions on leaving the state.
    #[serde(default)]
    pub exit: Vec<ActionDef>,
    /// Transitions out of (or inside) this state.
    #[serde(default)]
    pub transitions: Vec<ServiceTransitionDef>,
    /// Transitions for any trigger no transition of this state handles.
    #[serde(default)]
    pub default_transitions: Vec<ServiceTransitionDef>,
    /// Sub-states.
    #[serde(default)]
    pub states: Vec<StateDef>,
    /// Transitions for any trigger no sub-state handles.
    #[serde(default)]
    pub default: Option<DefaultStateDef>,
}

/// The default state of a machine or state: transitions taken when no state handles a
/// trigger.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DefaultStateDef {
    /// What it does.
    #[serde(default)]
    pub description: Option<String>,
    /// Transitions by trigger.
    #[serde(default)]
    pub transitions: Vec<ServiceTransitionDef>,
    /// Transitions for any trigger.
    #[serde(default)]
    pub default_transitions: Vec<ServiceTransitionDef>,
}

/// What a transition does to the state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TransitionKind {
    /// Runs its actions and stays: no exit or entry actions run.
    Internal,
    /// Leaves the state for `to` (or re-enters the same state without `to`).
    #[default]
    Simple,
    /// Enters `to`, remembering the current state for a later `pop`.
    Push,
    /// Returns to the state remembered by the last `push`.
    Pop,
}

/// A transition of a service's state machine.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ServiceTransitionDef {
    /// The trigger: an internal event, or an inherited service's event
    /// (`events.transport.Receive`, whose parameters name the message); absent for a
    /// default transition.
    #[serde(default)]
    pub on: Option<String>,
    /// What it means.
    #[serde(default)]
    pub description: Option<String>,
    /// The trigger's parameters: their types (a message or event name, or a field path
    /// such as `Receive.Body.ReceiveRec`) and the names the guard and actions use.
    #[serde(default)]
    pub parameters: Vec<ParamDef>,
    /// The condition under which it is taken.
    #[serde(default)]
    pub guard: Option<GuardDef>,
    /// What it does to the state.
    #[serde(default)]
    pub kind: TransitionKind,
    /// The state it leads to (a path from the machine's top), for `simple` and `push`.
    #[serde(default)]
    pub to: Option<String>,
    /// For `pop`: the trigger it raises on returning, and that trigger's arguments.
    #[serde(default)]
    pub pop: Option<ActionDef>,
    /// Actions, in order.
    #[serde(default)]
    pub actions: Vec<ActionDef>,
}

/// A parameter of a transition's trigger.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParamDef {
    /// Its type as written.
    #[serde(rename = "type")]
    pub ty: String,
    /// The name guards and actions use for it.
    pub name: String,
    /// What it is.
    #[serde(default)]
    pub description: Option<String>,
}

/// A guard: a boolean expression over guard functions and the parameters.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GuardDef {
    /// The expression as written (`isControllingClient(transportData) && !isDefault()`).
    pub condition: String,
    /// What it tests.
    #[serde(default)]
    pub description: Option<String>,
}

/// An action (or a `send` action) with its arguments.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActionDef {
    /// Its name (dotted for an inherited service's action: `events.transport.Send`).
    pub name: String,
    /// What it does.
    #[serde(default)]
    pub description: Option<String>,
    /// Its arguments as written: a parameter name, or a quoted constant (`'CONTROL_ACCEPTED'`).
    #[serde(default)]
    pub args: Vec<String>,
    /// It sends a message (JSIDL's `send_action`).
    #[serde(default)]
    pub send: bool,
}
