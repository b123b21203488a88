//! The seam between the Core services and the other services of an AS-4 component
//! (Mobility, a vendor's): the [`Service`] trait, what a service is handed
//! ([`Request`], [`Cx`]) and what it answers.
//!
//! A component ([`crate::component::As4Component`]) runs the Core services itself
//! (Transport, Events, Access Control, Management, Time, Liveness, Discovery, List
//! Manager) and offers every other message to its services in turn. The Core decides
//! what a service never sees: a command from a client that does not hold control, a
//! command while the component is not Ready (Standby, Emergency, Shutdown, ...). A
//! service answers queries from its state and carries out commands; it is told when the
//! component's state or its controller changes, and when its timer is due.
//!
//! A service generated from definitions built on jaus-as4's (`extends: as4`, the
//! services inheriting Access Control or Management) is a [`GeneratedService`]: its
//! generated machines decide, the Core's own services answer its inherited guards and
//! actions, and it runs here as every other service does.
//!
//! Services are generic over an environment `E` that the component's owner supplies and
//! hands to every call through [`Cx::env`]: nothing for a standalone AS-4 component
//! (`()`), the RA 3.3 side of a gateway (its outbox and the reports it keeps) for the
//! Mobility services over RA 3.3 components. The trait stays sans-IO: no socket, thread
//! or clock; time is the `now` of each call.

use std::fmt;
use std::time::Instant;

use jaus::net::as5669a::As4Id;
use jaus::CommandCode;

use crate::core::machine::Host;
use crate::core::CoreParts;
use crate::messages::{ComponentState, Message};

mod generated;

pub use crate::outgoing::{receive_of, sender_of, Outgoing, ServiceId};
pub use generated::{GeneratedService, Outbox, Taken};

/// Whether message `code` needs control: the catalogue's `needs_control` (AS-4's
/// `is_command` of the definitions), and true for a code outside them (safe: a vendor's
/// command at 0xF012 is protected until its service says otherwise).
pub fn needs_control(code: CommandCode) -> bool {
    crate::messages::MESSAGES
        .iter()
        .find(|m| m.code == code)
        .is_none_or(|m| m.needs_control)
}

/// A message handed to a service.
#[derive(Debug, Clone, Copy)]
pub struct Request<'a> {
    /// When it arrived.
    pub now: Instant,
    /// Its sender.
    pub from: As4Id,
    /// The message.
    pub message: &'a Message,
    /// Whether the sender holds control of the component (Access Control).
    pub from_controller: bool,
    /// The component's state (Management) when it arrived.
    pub state: ComponentState,
}

/// What a service does with a message.
// The message catalogue is as large as its largest message (UGV's Report Platform
// Specifications, 456 bytes: 27 optional scaled fields); boxing it would allocate for
// every answer, where moving it costs a copy.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum Handled {
    /// Not one of the service's messages: offer it to the next service.
    NotMine,
    /// Done; nothing to answer (a command carried out).
    Done,
    /// Done; this goes back to the sender (a query's report, a confirmation).
    Reply(Message),
    /// Refused: the reason is logged with the message and its sender, and counted; no
    /// answer goes back (AS-4 has no general refusal; a service with a typed refusal,
    /// such as the List Manager's Reject Element Request, replies with it instead).
    Refused(String),
}

/// What a service may use besides its own state during a call.
///
/// Besides its fields, a service built on the Core's generated services (a
/// [`GeneratedService`]) reaches the Core's guards and actions ([`Cx::with_core`]) and
/// sends beyond its reply ([`Cx::send`]).
pub struct Cx<'a, E> {
    /// The time of the call.
    pub now: Instant,
    /// This component's id.
    pub me: As4Id,
    /// The component's state (Management).
    pub state: ComponentState,
    /// The client holding control of the component, if any.
    pub controller: Option<As4Id>,
    /// The component's list manager (element lists kept by UID).
    pub lists: &'a mut crate::core::lists::Lists,
    /// The owner's environment (`()` for a standalone component; the RA 3.3 side of a
    /// gateway).
    pub env: &'a mut E,
    /// The Core's data, for [`Cx::with_core`].
    pub(crate) core: CoreParts<'a>,
    /// What the call sends besides its reply.
    pub(crate) out: &'a mut Vec<Outgoing>,
}

impl<E> Cx<'_, E> {
    /// Runs `f` on the Core's services (Transport, Events, Access Control, Management):
    /// [`Host`] implements their generated traits, so a generated service's inherited
    /// guards (`isControllingClient`) read the Core's state and its inherited actions
    /// act on it. What they send leaves with the component's output.
    pub fn with_core<R>(&mut self, f: impl FnOnce(&mut Host<'_>) -> R) -> R {
        self.with_core_env(|host, _, _| f(host))
    }

    /// [`with_core`](Self::with_core), lending the owner's environment and the list
    /// manager beside the Core (a service over an environment runs its own guards and
    /// actions on them while the inherited ones run on the Core).
    pub fn with_core_env<R>(
        &mut self,
        f: impl FnOnce(&mut Host<'_>, &mut E, &mut crate::core::lists::Lists) -> R,
    ) -> R {
        let mut host = Host::new(
            self.now,
            &mut *self.core.access,
            &mut *self.core.management,
            &mut *self.core.events,
            &mut *self.out,
            None,
        );
        f(&mut host, &mut *self.env, &mut *self.lists)
    }

    /// The state of the Core's machine, by path
    /// (`Receiving.Ready.Controlled.Available.Ready`).
    pub fn core_state(&self) -> &'static str {
        self.core.path
    }

    /// Sends `o` with the component's output (besides the call's reply).
    pub fn send(&mut self, o: Outgoing) {
        self.out.push(o);
    }
}

impl<E> fmt::Debug for Cx<'_, E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Cx")
            .field("me", &self.me)
            .field("state", &self.state)
            .field("controller", &self.controller)
            .finish_non_exhaustive()
    }
}

/// A service of an AS-4 component other than the Core services.
pub trait Service<E>: fmt::Debug + Send + 'static {
    /// Its URI and version (Discovery's Report Services).
    fn id(&self) -> ServiceId;

    /// Whether `code` is one of the messages this service receives (its input set).
    fn receives(&self, code: CommandCode) -> bool;

    /// Whether message `code` needs control. Default: what the definitions say
    /// ([`needs_control`]); a vendor's message outside jaus-as4's definitions (it arrives
    /// undecoded, as [`Message::Raw`]) needs control unless the service says otherwise.
    fn needs_control(&self, code: CommandCode) -> bool {
        needs_control(code)
    }

    /// Whether command `code` also needs the component Ready (besides control). Default:
    /// every command does, as for the services that inherit Management (the drivers).
    /// A service that inherits only Access Control answers false for its commands (the
    /// pose sensors' Set Local/Global Pose are obeyed from the controller in Standby).
    fn needs_ready(&self, code: CommandCode) -> bool {
        let _ = code;
        true
    }

    /// A message of its input set. Messages that need control
    /// ([`needs_control`](Self::needs_control)) reach it only from the controlling client, and only while the component is Ready when
    /// [`needs_ready`](Self::needs_ready) says so (the component checks); queries reach
    /// it from anyone.
    fn handle(&mut self, cx: &mut Cx<'_, E>, request: &Request<'_>) -> Handled;

    /// The component's state changed (`from` → `to`); leaving Ready must stop any
    /// motion the service commands.
    fn state_changed(&mut self, cx: &mut Cx<'_, E>, from: ComponentState, to: ComponentState) {
        let _ = (cx, from, to);
    }

    /// The component's controller changed (`None`: no client holds control).
    fn controller_changed(&mut self, cx: &mut Cx<'_, E>, controller: Option<As4Id>) {
        let _ = (cx, controller);
    }

    /// Its timer is due ([`poll_timeout`](Self::poll_timeout)), or the environment
    /// changed (the owner calls this after handing the environment new data).
    fn tick(&mut self, cx: &mut Cx<'_, E>) {
        let _ = cx;
    }

    /// When [`tick`](Self::tick) is next due (default: never on its own).
    fn poll_timeout(&self) -> Option<Instant> {
        None
    }

    /// Whether the command `code` this service took is still being carried out (a list
    /// being executed): a Core v1.1 command event of it completes when this turns false
    /// (checked at the component's ticks and timeouts), or expires after its maximum
    /// duration. Default: a command is done once taken.
    fn in_progress(&self, code: CommandCode) -> bool {
        let _ = code;
        false
    }
}
