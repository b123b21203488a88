//! The component runtime: everything a JAUS component does whatever its function.
//!
//! A [`Component`] wraps a [`Behaviour`] (the generated `Dispatch` of a component
//! trait, see [`crate::components`]) and handles the core of RA 3.3 itself: the core
//! states, Set/Query Component Authority, component control, Query Component Status,
//! Set/Query Time, the heartbeat, service connections (provider and requester side) and
//! events. It is sans-IO in the manner of `quinn-proto`: it is fed
//! [`handle`](Component::handle)`(now, header, body)` and
//! [`handle_timeout`](Component::handle_timeout)`(now)`, and hands back messages to
//! send ([`poll_transmit`](Component::poll_transmit)) and the next time it wants to be
//! woken ([`poll_timeout`](Component::poll_timeout)). No socket, thread or wall clock
//! is used, so a whole system runs deterministically on a virtual clock
//! ([`local::LocalBus`]).
//!
//! # Rules this runtime applies (and why)
//!
//! * **Control.** The commands of a component interface (`commands:` in its
//!   definition) and the core commands Set Component Authority, Shutdown, Standby,
//!   Resume, Reset, Set Time and Release Component Control are executed only when sent by
//!   the component in control ([`ControlPolicy::ControllerOnly`], the default, as the
//!   successor standard requires). [`ControlPolicy::Open`] instead accepts them from
//!   anyone while no component holds control, as OpenJAUS 3.3 does. Request Component
//!   Control follows OpenJAUS (docs/wire.md §5.3) with one addition: a requester whose
//!   authority is below the component's own authority gets Confirm Component Control
//!   "insufficient authority".
//! * **Emergency.** Set Emergency is honoured from **any** sender, controller or not:
//!   an emergency stop that can be refused is not one. The runtime remembers who set it;
//!   the component leaves Emergency (to Standby) only when every one of them has sent
//!   Clear Emergency. A Clear Emergency from a component that did not set one is ignored
//!   and counted. While in Emergency, Reset, Standby and Resume are refused and no
//!   interface command is executed.
//! * **Service connections asked for are kept.** A connection whose reports stop for
//!   five periods (at least 3 s), or whose provider leaves the system tree, is asked
//!   for again with Create Service Connection until the reports come back (counted in
//!   `Stats::subscriptions_renewed`): a provider that restarted, or a link that was down
//!   longer than the subsystem timeout, needs nothing from the component's own code.
//! * **Controlled components' states are kept.** Each Report Component Status from a
//!   component this one controls is remembered ([`Context::controlled_state`]); the stock
//!   drivers use it to resume their output after an emergency is cleared.
//! * **Refusals.** A refused message is counted in [`Stats`] and logged with its name,
//!   sender and reason; if the sender asked for an acknowledgement it gets a NAK. Nothing
//!   a vendor has not implemented crashes the component: it is counted as unsupported.
//! * **Bounds.** The outgoing queue, the service connections, the events and the set of
//!   emergency senders all have a configured capacity; what does not fit is refused (with
//!   the JAUS response code for it) or dropped and counted.
//!
//! # Where things are
//!
//! This file holds the traits a component is made of ([`Interface`], [`Emits`],
//! [`Behaviour`]); the [`Component`] itself, what it counts and what it sends are in
//! `machine` (the sans-IO surface: handle, timeouts, polls) and `dispatch` (one message:
//! core messages, refusals, the behaviour, the core reports); its settings in `config`;
//! the runtime state in `runtime`; control and emergencies in `control`; service
//! connections and events in `connections` and `events`; refusals in `refusal`.

mod config;
mod connections;
mod context;
mod control;
mod dispatch;
mod endpoint;
mod events;
mod info;
mod init_error;
pub mod local;
mod machine;
mod refusal;
mod runtime;
mod settled;
mod state;

pub use config::{Config, ControlPolicy};
pub use context::{Context, CoreMessage, ServiceConnectionError};
pub use endpoint::{Endpoint, Endpoints, Outgoing};
pub use info::{ComponentInfo, Hardware, StockInfo};
pub use init_error::InitError;
pub use machine::{Component, Stats, Transmit};
pub use refusal::{refusal_report, Refused};
pub use settled::{Outcome, Settled, MAX_SETTLED};
pub use state::{CoreState, CoreTransition, Modes, NoModes, NoTransition, TransitionError};

use crate::{Address, CommandCode, MessageSet};
use machine::next_after;
use refusal::Refusal;
use runtime::Controller;

/// The static description of a component interface, generated from its definition.
pub trait Interface: Send + 'static {
    /// Component name.
    const NAME: &'static str;
    /// Component id (Part 1).
    const ID: u8;
    /// The Part 1 function text.
    const FUNCTION: &'static str;
    /// Commands executed only for the controlling component.
    const COMMANDS: &'static [CommandCode];
    /// Messages accepted from anyone (queries it answers, reports it consumes).
    const ACCEPTS: &'static [CommandCode];
    /// Messages it sends on its own initiative.
    const EMITS: &'static [CommandCode];
    /// Takes and sends any message (command and control components).
    const ANY_MESSAGE: bool;
    /// Its sub-states of Ready.
    type Modes: Modes;
    /// The messages it speaks: [`crate::messages::Message`] for the SDK's components, a
    /// vendor's generated set (which wraps the standard one) for a vendor's.
    type Messages: MessageSet;
}

/// Implemented by an interface for every message its definition lets it send
/// (`emits:`), with the conversion into the interface's message set:
/// [`Context::send`] does not compile for any other message.
#[diagnostic::on_unimplemented(
    message = "`{Self}` does not emit `{M}`",
    label = "`{M}` is not among the messages this component may send",
    note = "add the message to `emits:` of the component definition (YAML) if the component really sends it, or use `Context::send_core` for core messages"
)]
pub trait Emits<M>: Interface {
    /// `msg` as a message of the interface's set.
    fn wrap(msg: M) -> Self::Messages;
}

/// [`Emits`] seen from the message (`M: EmittedBy<I>` whenever `I: Emits<M>`), so that a
/// message a component may not send is reported with its own name.
#[diagnostic::on_unimplemented(
    message = "`{I}` does not emit `{Self}`",
    label = "`{Self}` is not among the messages this component may send",
    note = "add the message to `emits:` of the component definition (YAML) if the component really sends it, or use `Context::send_core` for core messages"
)]
pub trait EmittedBy<I: Interface> {
    /// The message as one of the interface's set.
    fn into_set(self) -> I::Messages;
}

impl<M, I: Emits<M>> EmittedBy<I> for M {
    fn into_set(self) -> I::Messages {
        I::wrap(self)
    }
}

/// Why the runtime asks a component that commands motion to stop ([`Behaviour::stop`],
/// the `stop` method of every driver's generated trait).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// Set Emergency arrived (from anyone); the component is in Emergency.
    Emergency,
    /// The component left Ready for Standby (Standby command, or its own transition).
    Standby,
    /// The component is shutting down.
    Shutdown,
    /// The component entered Failure.
    Failure,
    /// The component in control released it, was preempted by a higher authority, or
    /// disappeared from the system: nobody commands the motion any more.
    ControlLost {
        /// The component that was in control.
        controller: Address,
    },
}

impl std::fmt::Display for StopReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StopReason::Emergency => f.write_str("emergency"),
            StopReason::Standby => f.write_str("standby"),
            StopReason::Shutdown => f.write_str("shutdown"),
            StopReason::Failure => f.write_str("failure"),
            StopReason::ControlLost { controller } => write!(f, "control lost by {controller}"),
        }
    }
}

/// What the generated `Dispatch` of a component trait implements; the runtime drives
/// it.
pub trait Behaviour: Send + 'static {
    /// The interface this behaviour serves.
    type Interface: Interface;

    /// Handles a message that is not a core message. Returns the report answering a
    /// query (sent back by the runtime), `None` for anything else.
    #[allow(clippy::type_complexity)]
    fn handle(
        &mut self,
        ctx: &mut Context<'_, Self::Interface>,
        msg: &<Self::Interface as Interface>::Messages,
    ) -> Result<Option<<Self::Interface as Interface>::Messages>, Refused>;

    /// Called in Initialize; an error puts the component in Failure.
    fn initialize(&mut self, ctx: &mut Context<'_, Self::Interface>) -> Result<(), InitError> {
        let _ = ctx;
        Ok(())
    }

    /// Called after every core state change.
    fn state_changed(
        &mut self,
        ctx: &mut Context<'_, Self::Interface>,
        from: CoreState,
        to: CoreState,
    ) {
        let _ = (ctx, from, to);
    }

    /// Called every [`Config::tick`] (except in Shutdown).
    fn tick(&mut self, ctx: &mut Context<'_, Self::Interface>) {
        let _ = ctx;
    }

    /// Stop all motion now: called by the runtime on entering Emergency (from any
    /// state), on leaving Ready for Standby, Shutdown or Failure, and when the component
    /// in control releases it, is preempted or disappears. Components that command
    /// motion (`safe_stop: true` in their definition) must implement it.
    fn stop(&mut self, ctx: &mut Context<'_, Self::Interface>, reason: StopReason) {
        let _ = (ctx, reason);
    }
}

/// The message set of a behaviour's interface.
type Set<B> = <<B as Behaviour>::Interface as Interface>::Messages;
