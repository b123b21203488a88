//! The template context of AS-4 services (`services:` of the definitions): per service
//! a trait of its guards and actions (with its parent's trait as supertrait), its
//! internal events as structs, a `Trigger` enum, and its state machines (merged with the
//! inherited ones) as static tables for the SDK's engine (`jaus::hsm`). Guards are parsed
//! here into expression trees and emitted as data; the template only iterates.

mod emit;
pub(crate) mod guard;
mod methods;
pub(crate) mod model;

use serde::Serialize;

pub use emit::build_services;

/// Every service of a definition set.
#[derive(Debug, Clone, Serialize, Default)]
pub struct ServicesCtx {
    /// The services, in definition order.
    pub services: Vec<ServiceCtx>,
    /// Whether some method takes `args: &[Arg]` (then the enum `Arg` is generated).
    pub has_args: bool,
    /// Variants of the shared `Arg` enum (arguments of guards and actions whose call
    /// sites pass different types).
    pub args: Vec<ArgVariantCtx>,
    /// `<'a>` when `Arg` borrows, else empty.
    pub args_lt: String,
}

/// A variant of `Arg`.
#[derive(Debug, Clone, Serialize)]
pub struct ArgVariantCtx {
    /// Variant name.
    pub name: String,
    /// The type it borrows (path from the services module).
    pub ty: String,
}

/// One service.
#[derive(Debug, Clone, Serialize)]
pub struct ServiceCtx {
    /// Trait name.
    pub name: String,
    /// Module name.
    pub module: String,
    /// Its URI and version.
    pub id: String,
    /// Documentation lines.
    pub doc: Vec<String>,
    /// `file:line` of the definition.
    pub origin: String,
    /// The parent's trait (`super::events::Events`), if it inherits one of the set's
    /// own services.
    pub supertrait: Option<String>,
    /// The nearest service of the base definitions it inherits, if the set is built on
    /// base definitions: its inherited guards and actions run on an implementation of
    /// that service's trait.
    pub inherited: Option<InheritedCtx>,
    /// The base crate's path (`::jaus_as4`) when a `Hosted` adapter is generated: the
    /// service inherits a base service and its messages arrive with Transport's
    /// `Receive` data alone.
    pub hosted: Option<String>,
    /// Whether the hosting crate's `Message` carries the service's messages raw (a set
    /// on base definitions), so `Hosted` decodes them with the set's own.
    pub hosted_raw: bool,
    /// Its URI (`urn:acme:Lamp`).
    pub uri: String,
    /// Its major version.
    pub major: u8,
    /// Its minor version.
    pub minor: u8,
    /// Its internal events.
    pub events: Vec<EventCtx>,
    /// Its trait's methods (the guards, then the actions), by name.
    pub methods: Vec<MethodCtx>,
    /// The triggers of its machines.
    pub triggers: Vec<TriggerCtx>,
    /// `<'a>` when `Trigger` borrows, else empty.
    pub lt: String,
    /// `<'_>` when `Trigger` borrows, else empty.
    pub lt_anon: String,
    /// Guard call sites, by number.
    pub guards: Vec<SiteCtx>,
    /// Action call sites, by number.
    pub actions: Vec<SiteCtx>,
    /// Its machines (merged with the inherited ones).
    /// How a received message becomes its trigger, when every trigger carrying a
    /// message has the same other parameters (the JSIDL convention: the message and
    /// Transport's `Receive` data).
    pub received: Option<ReceivedCtx>,
    pub machines: Vec<MachineCtx>,
    /// Number of states over its machines.
    pub state_count: usize,
    /// Number of transitions over its machines.
    pub transition_count: usize,
}

/// An internal event: a struct.
#[derive(Debug, Clone, Serialize)]
pub struct EventCtx {
    /// Struct name.
    pub name: String,
    /// Documentation lines.
    pub doc: Vec<String>,
    /// Its fields.
    pub fields: Vec<FieldCtx>,
}

/// A field (of an event struct or a trigger variant).
#[derive(Debug, Clone, Serialize)]
pub struct FieldCtx {
    /// Field name.
    pub name: String,
    /// Rust type.
    pub ty: String,
    /// Documentation lines.
    pub doc: Vec<String>,
}

/// A trait method.
#[derive(Debug, Clone, Serialize)]
pub struct MethodCtx {
    /// The signature, without `;` (`fn is_x(&self, msg: &RequestControl) -> bool`).
    pub sig: String,
    /// Documentation lines.
    pub doc: Vec<String>,
}

/// The generated dispatch of received messages: `Trigger::received(message, ...)`.
#[derive(Debug, Clone, Serialize)]
pub struct ReceivedCtx {
    /// The parameters besides the message (name, type without the borrow).
    pub params: Vec<FieldCtx>,
    /// One arm per message trigger.
    pub arms: Vec<ReceivedArm>,
}

/// A base service a service inherits (a set built on base definitions).
#[derive(Debug, Clone, Serialize)]
pub struct InheritedCtx {
    /// Its name (`AccessControl`).
    pub name: String,
    /// Its trait's path (`::jaus_as4::messages::services::access_control::AccessControl`).
    pub path: String,
    /// Its `Machines`' path.
    pub machines: String,
    /// Its `MACHINES` tables' path (the machines the inherited states follow).
    pub tables: String,
}

/// One arm of the dispatch.
#[derive(Debug, Clone, Serialize)]
pub struct ReceivedArm {
    /// The pattern over the set's `Message` binding the message to the field.
    pub pattern: String,
    /// The message's variant of the `Message` enum (and the trigger's).
    pub message: String,
    /// The trigger field that carries the message.
    pub field: String,
}

/// A variant of `Trigger`.
#[derive(Debug, Clone, Serialize)]
pub struct TriggerCtx {
    /// Variant name, also the key the tables use.
    pub variant: String,
    /// Documentation lines.
    pub doc: Vec<String>,
    /// Its parameters.
    pub fields: Vec<FieldCtx>,
}

/// A guard or action call site: the match arm that runs it.
#[derive(Debug, Clone, Serialize)]
pub struct SiteCtx {
    /// Pattern over `(number, trigger)`.
    pub pattern: String,
    /// The call.
    pub call: String,
    /// A call of the service's own without a trigger (an entry or exit action, a
    /// default transition's): run too when its machines follow the inherited ones.
    pub follows: bool,
}

/// A state machine's table.
#[derive(Debug, Clone, Serialize)]
pub struct MachineCtx {
    /// Its name.
    pub name: String,
    /// The static's name.
    pub ident: String,
    /// Documentation lines.
    pub doc: Vec<String>,
    /// Start state id.
    pub start: usize,
    /// States, parents first.
    pub states: Vec<StateCtx>,
    /// Transitions of its default state.
    pub transitions: Vec<TransCtx>,
    /// Default transitions of its default state.
    pub defaults: Vec<TransCtx>,
}

/// A state's row.
#[derive(Debug, Clone, Serialize)]
pub struct StateCtx {
    /// Name.
    pub name: String,
    /// Path from the machine's top.
    pub path: String,
    /// `Some(n)` or `None`.
    pub parent: String,
    /// `Some(n)` or `None`.
    pub initial: String,
    /// `&[…]` of action call sites.
    pub entry: String,
    /// `&[…]` of action call sites.
    pub exit: String,
    /// Transitions by trigger.
    pub transitions: Vec<TransCtx>,
    /// Default transitions.
    pub defaults: Vec<TransCtx>,
}

/// A transition's row: each field a Rust expression.
#[derive(Debug, Clone, Serialize)]
pub struct TransCtx {
    /// `Some("Key")` or `None`.
    pub trigger: String,
    /// `Some(&Expr::…)` or `None`.
    pub guard: String,
    /// `Internal`, `Simple`, `Push` or `Pop`.
    pub kind: String,
    /// `Some(n)` or `None`.
    pub target: String,
    /// `&[…]` of action call sites.
    pub actions: String,
    /// `Some("Key")` or `None`.
    pub raise: String,
    /// A comment: where it is defined.
    pub origin: String,
}
