//! The services a gateway presents over RA 3.3 components, on their generated machines:
//! the Mobility services (`defs/mobility_services.yaml`, [`crate::mobility`]) and the
//! Manipulator services (`defs/manipulator_services.yaml`, [`crate::manipulator`]).
//!
//! Each service's data (the RA 3.3 component behind it, a list being driven) implements
//! [`Machined`]; [`OnMachines`] runs it as a [`Service`] of the gateway's component:
//!
//! 1. a message of the service's own (not one the Core takes) arrives and the service
//!    claims it ([`Machined::claims`]: of two list drivers on one list, the one whose
//!    kind the list holds);
//! 2. its machine follows the Core's (the inherited states are the Core's), as it also
//!    does whenever the Core's state or controller changes, running the service's own
//!    exit and entry actions of the states it leaves and enters (the Parking Brake
//!    Driver's `engageBrake` on leaving Ready, the list drivers' `resetTravelSpeed`);
//! 3. the trigger runs: the inherited guards (`isControllingClient`) on the Core, the
//!    service's own guards and actions on an [`On`], which lends them the service's data,
//!    the RA 3.3 side and the list manager;
//! 4. what the actions sent leaves (the first message to the sender is the reply), a
//!    refusal an action recorded is the answer, and no transition taken is a refusal
//!    naming the state.
//!
//! Which messages need control and Ready is the machines' to say (a transition under
//! `Controlled.Available.Ready` guarded by `isControllingClient`), not the component's.

use std::fmt;
use std::time::Instant;

use jaus::net::as5669a::As4Id;
use jaus::CommandCode;

use crate::core::lists::Lists;
use crate::core::machine::Host;
use crate::messages::services::transport::event::Receive;
use crate::outgoing::{receive_of, sender_of};
use crate::ra33::Ra33Side;
use crate::service::{Cx, Handled, Outgoing, Request, Service, ServiceId};
use crate::{ComponentState, Message};

/// What a gateway service's own guards and actions are given during one trigger: the
/// generated trait of the service is implemented for `On<'_, T>` of its data `T`.
#[derive(Debug)]
pub struct On<'a, T> {
    /// The service's data.
    pub svc: &'a mut T,
    /// The RA 3.3 side of the gateway.
    pub env: &'a mut Ra33Side,
    /// The component's list manager.
    pub lists: &'a mut Lists,
    /// The time of the trigger.
    pub now: Instant,
    out: Vec<Outgoing>,
    refused: Option<String>,
}

impl<T> On<'_, T> {
    /// Sends `message` back to the sender of the trigger (`transport` is its Transport
    /// `Receive` data).
    pub fn reply(&mut self, transport: &Receive, message: impl Into<Message>) {
        self.out.push(Outgoing {
            to: sender_of(transport),
            message: message.into(),
        });
    }

    /// Refuses the trigger's message: the component logs and counts `why` with the
    /// message and its sender.
    pub fn refuse(&mut self, why: impl Into<String>) {
        self.refused = Some(why.into());
    }
}

/// A gateway service's data, run on its generated machines by [`OnMachines`].
pub trait Machined: fmt::Debug + Send + Sized + 'static {
    /// The service's generated machines.
    type Machines: fmt::Debug + Send + Default + 'static;
    /// Its URI and version.
    const ID: ServiceId;
    /// The messages its machines take (the generated `RECEIVES`, with the inherited).
    const RECEIVES: &'static [CommandCode];
    /// The messages of the service it inherits (the Core takes those first).
    const INHERITED: &'static [CommandCode];

    /// The engine's machines inside [`Self::Machines`].
    fn hsm(m: &mut Self::Machines) -> &mut jaus::hsm::Machines;

    /// Offers `message` to the machines: the service's own guards and actions on `on`,
    /// the inherited on `core` (the generated `Machines::receive`).
    fn run(
        m: &mut Self::Machines,
        on: &mut On<'_, Self>,
        core: &mut Host<'_>,
        message: &Message,
        transport: &Receive,
    ) -> Option<bool>;

    /// Makes the machines follow the Core's, now at `path`, running the service's own
    /// exit and entry actions on `on` (the generated `Machines::follow`).
    fn follow(m: &mut Self::Machines, on: &mut On<'_, Self>, path: &str) -> bool;

    /// Whether this service answers `message` at all (default: yes); false leaves it to
    /// the component's next service.
    fn claims(&self, lists: &Lists, message: &Message) -> bool {
        let _ = (lists, message);
        true
    }

    /// The component's state changed ([`Service::state_changed`]).
    fn state_changed(
        &mut self,
        cx: &mut Cx<'_, Ra33Side>,
        from: ComponentState,
        to: ComponentState,
    ) {
        let _ = (cx, from, to);
    }

    /// Its timer is due or the RA 3.3 side changed ([`Service::tick`]).
    fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
        let _ = cx;
    }

    /// When its [`tick`](Self::tick) is next due on its own ([`Service::poll_timeout`];
    /// default: never, it ticks when the RA 3.3 side changes).
    fn poll_timeout(&self) -> Option<Instant> {
        None
    }

    /// Whether the command `code` it took is still being carried out
    /// ([`Service::in_progress`]).
    fn in_progress(&self, code: CommandCode) -> bool {
        let _ = code;
        false
    }
}

/// Implements [`Machined`] for a service's data `$data` over its generated module
/// `$module` (`crate::messages::services::NAME`), inheriting `$inherited`'s messages;
/// items in braces are added to the implementation (`claims`, `state_changed`, `tick`,
/// `poll_timeout`).
macro_rules! machined {
    ($data:ty, $module:ident, $id:expr, $inherited:ident $({ $($extra:item)* })?) => {
        impl $crate::machined::Machined for $data {
            type Machines = $crate::messages::services::$module::Machines;
            const ID: $crate::service::ServiceId = $id;
            const RECEIVES: &'static [::jaus::CommandCode] =
                $crate::messages::services::$module::RECEIVES;
            const INHERITED: &'static [::jaus::CommandCode] =
                $crate::messages::services::$inherited::RECEIVES;

            fn hsm(m: &mut Self::Machines) -> &mut ::jaus::hsm::Machines {
                &mut m.0
            }

            fn run(
                m: &mut Self::Machines,
                on: &mut $crate::machined::On<'_, Self>,
                core: &mut $crate::core::machine::Host<'_>,
                message: &$crate::Message,
                transport: &$crate::messages::services::transport::event::Receive,
            ) -> Option<bool> {
                m.receive(on, core, message, transport)
            }

            fn follow(
                m: &mut Self::Machines,
                on: &mut $crate::machined::On<'_, Self>,
                path: &str,
            ) -> bool {
                m.follow(on, path)
            }

            $($($extra)*)?
        }
    };
}
pub(crate) use machined;

/// A gateway service running on its generated machines.
#[derive(Debug)]
pub struct OnMachines<T: Machined> {
    imp: T,
    machines: T::Machines,
}

impl<T: Machined> OnMachines<T> {
    /// The service over `imp`, its machines not started (they start following the Core
    /// at the first message).
    pub fn from_impl(imp: T) -> Self {
        Self {
            imp,
            machines: T::Machines::default(),
        }
    }

    /// Makes the machines follow the Core's state, running the service's own exit and
    /// entry actions of the states left and entered (`engageBrake` on leaving Ready);
    /// what they send leaves with the component's output.
    fn follow(&mut self, cx: &mut Cx<'_, Ra33Side>) {
        let path = cx.core_state();
        let now = cx.now;
        let (imp, machines) = (&mut self.imp, &mut self.machines);
        let out = cx.with_core_env(|_, env, lists| {
            let mut on = On {
                svc: imp,
                env,
                lists,
                now,
                out: Vec::new(),
                refused: None,
            };
            T::follow(machines, &mut on, path);
            if let Some(why) = on.refused {
                tracing::warn!(service = %T::ID, state = path, "{why}");
            }
            on.out
        });
        for o in out {
            cx.send(o);
        }
    }

    /// The service's data.
    pub fn inner(&self) -> &T {
        &self.imp
    }

    /// Its machines' current states, `machine: path`.
    pub fn states(&mut self) -> Vec<(&'static str, &'static str)> {
        T::hsm(&mut self.machines)
            .iter()
            .map(|m| (m.def().name, m.path()))
            .collect()
    }
}

impl<T: Machined> Service<Ra33Side> for OnMachines<T> {
    fn id(&self) -> ServiceId {
        T::ID
    }

    fn receives(&self, code: CommandCode) -> bool {
        T::RECEIVES.contains(&code) && !T::INHERITED.contains(&code)
    }

    fn needs_control(&self, _code: CommandCode) -> bool {
        // The machines decide (`isControllingClient`).
        false
    }

    fn needs_ready(&self, _code: CommandCode) -> bool {
        // The machines decide (a transition under `Ready`).
        false
    }

    fn handle(&mut self, cx: &mut Cx<'_, Ra33Side>, request: &Request<'_>) -> Handled {
        if !self.imp.claims(cx.lists, request.message) {
            return Handled::NotMine;
        }
        self.follow(cx);
        let transport = receive_of(request.from);
        let now = cx.now;
        let (imp, machines) = (&mut self.imp, &mut self.machines);
        let (taken, out, refused) = cx.with_core_env(|core, env, lists| {
            let mut on = On {
                svc: imp,
                env,
                lists,
                now,
                out: Vec::new(),
                refused: None,
            };
            let taken = T::run(machines, &mut on, core, request.message, &transport);
            (taken, on.out, on.refused)
        });
        let mut reply = None;
        for o in out {
            if reply.is_none() && o.to == request.from {
                reply = Some(o.message);
            } else {
                cx.send(o);
            }
        }
        match (taken, refused) {
            (None, _) => Handled::NotMine,
            (Some(true), Some(why)) => Handled::Refused(why),
            (Some(true), None) => reply.map_or(Handled::Done, Handled::Reply),
            (Some(false), _) => {
                let state = T::hsm(&mut self.machines)
                    .iter()
                    .next()
                    .map_or("", |m| m.path());
                Handled::Refused(format!(
                    "{}: no transition for {} in state {state}",
                    T::ID,
                    request.message.name()
                ))
            }
        }
    }

    fn state_changed(
        &mut self,
        cx: &mut Cx<'_, Ra33Side>,
        from: ComponentState,
        to: ComponentState,
    ) {
        self.follow(cx);
        self.imp.state_changed(cx, from, to);
    }

    fn controller_changed(&mut self, cx: &mut Cx<'_, Ra33Side>, _controller: Option<As4Id>) {
        // Controlled and NotControlled are states of the Core's machine too.
        self.follow(cx);
    }

    fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
        self.imp.tick(cx);
    }

    fn poll_timeout(&self) -> Option<Instant> {
        self.imp.poll_timeout()
    }

    fn in_progress(&self, code: CommandCode) -> bool {
        self.imp.in_progress(code)
    }
}
