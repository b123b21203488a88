//! [`Context`]: what a behaviour sees of the runtime while it handles a message or a tick,
//! and the core messages any component may send.

use std::marker::PhantomData;
use std::time::{Duration, Instant};

use super::runtime::Runtime;
use super::{CoreState, CoreTransition, EmittedBy, Interface, Modes, TransitionError};
use crate::messages::*;
use crate::{Address, CommandCode, JausMessage};

/// What a behaviour sees of the runtime while it handles a message or a tick.
pub struct Context<'a, I: Interface> {
    pub(super) rt: &'a mut Runtime<I>,
    pub(super) _i: PhantomData<I>,
}

impl<I: Interface> std::fmt::Debug for Context<'_, I> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Context")
            .field("component", &I::NAME)
            .field("address", &self.rt.address)
            .field("state", &self.rt.state)
            .field("mode", &self.rt.mode)
            .finish()
    }
}

impl<I: Interface> Context<'_, I> {
    /// The current (virtual or real) instant.
    pub fn now(&self) -> Instant {
        self.rt.now
    }

    /// This component's address.
    pub fn address(&self) -> Address {
        self.rt.address
    }

    /// The sender of the message being handled (`None` in ticks and initialisation).
    pub fn source(&self) -> Option<Address> {
        self.rt.source
    }

    /// The core state.
    pub fn state(&self) -> CoreState {
        self.rt.state
    }

    /// The component mode (meaningful in Ready; the initial mode otherwise).
    pub fn mode(&self) -> I::Modes {
        self.rt.mode
    }

    /// The component in control, if any.
    pub fn controller(&self) -> Option<Address> {
        self.rt.controller.map(|c| c.address)
    }

    /// Whether `target` has confirmed this component's control request.
    pub fn has_control_of(&self, target: Address) -> bool {
        self.rt.held_control.iter().any(|(a, _)| *a == target)
    }

    /// The state `target`, a component this one controls, reported last (Report
    /// Component Status) since it granted control; `None` when it has not reported one
    /// or is not controlled.
    pub fn controlled_state(&self, target: Address) -> Option<CoreState> {
        self.rt
            .held_control
            .iter()
            .find(|(a, _)| *a == target)
            .and_then(|(_, s)| *s)
    }

    /// Whether `requester` holds an event of this component on `report` (Create Event
    /// confirmed, not cancelled, its requester not gone).
    pub fn has_subscriber(&self, requester: Address, report: CommandCode) -> bool {
        self.rt.events.has(requester, report)
    }

    /// Current UTC (since 1970-01-01), when the clock is set.
    pub fn utc(&self) -> Option<Duration> {
        self.rt.clock.utc(self.rt.now)
    }

    /// The JAUS time and date stamps of now, when the clock is set.
    pub fn time_stamps(&self) -> Option<(TimeStamp, DateStamp)> {
        self.rt
            .clock
            .stamps(self.rt.now)
            .map(|(t, d)| (t.into(), d.into()))
    }

    /// Sends `msg` to `to`. Only messages the interface may emit compile here.
    pub fn send<M: EmittedBy<I>>(&mut self, to: Address, msg: M) {
        self.rt.send_set(to, msg.into_set(), false, 0);
    }

    /// Sends a message whose type is only known at run time, such as an element of a
    /// spooled mission. Unlike [`send`](Self::send) this is not checked against the
    /// interface's `emits:`; use it only to pass on messages the component was given.
    pub fn forward(&mut self, to: Address, msg: I::Messages) {
        self.rt.send_set(to, msg, false, 0);
    }

    /// [`forward`](Self::forward) with a sequence number of the component's own, returned:
    /// when the node makes commands arrive, the outcome of the command comes back
    /// with that number ([`take_settled`](Self::take_settled)), and sending it again
    /// with [`forward_again`](Self::forward_again) under the same number lets the
    /// destination drop it as a retransmission if the first copy did arrive.
    pub fn forward_numbered(&mut self, to: Address, msg: I::Messages) -> u16 {
        let seq = self.rt.next_sequence();
        self.rt.send_set(to, msg, false, seq);
        seq
    }

    /// [`forward`](Self::forward) under sequence number `sequence` (a command sent again,
    /// see [`forward_numbered`](Self::forward_numbered)).
    pub fn forward_again(&mut self, to: Address, msg: I::Messages, sequence: u16) {
        self.rt.send_set(to, msg, false, sequence);
    }

    /// [`send`](Self::send) with a sequence number of the component's own, returned (see
    /// [`forward_numbered`](Self::forward_numbered)).
    pub fn send_numbered<M: EmittedBy<I>>(&mut self, to: Address, msg: M) -> u16 {
        let seq = self.rt.next_sequence();
        self.rt.send_set(to, msg.into_set(), false, seq);
        seq
    }

    /// The next outcome of a command this component sent to another node, oldest
    /// first (`None`: none waiting). Only a node making commands arrive
    /// (`jaus::net::NodeConfig::reliable`) reports them, and only for commands it
    /// tracked: a destination known never to acknowledge (OpenJAUS 3.3) gets its
    /// commands once and reports nothing.
    pub fn take_settled(&mut self) -> Option<super::Settled> {
        self.rt.settled.pop_front()
    }

    /// Moves to another mode. Allowed only in Ready and along a transition of the
    /// definition; a transition with a core effect (e.g. back to Standby at the final
    /// waypoint) also changes the core state.
    pub fn transition(
        &mut self,
        t: <I::Modes as Modes>::Transition,
    ) -> Result<I::Modes, TransitionError> {
        if self.rt.state != CoreState::Ready {
            return Err(TransitionError {
                machine: I::NAME,
                from: self.rt.state.name(),
                transition: <I::Modes as Modes>::transition_name(t),
            });
        }
        let next = self.rt.mode.apply(t)?;
        self.rt.mode = next;
        if let Some(core) = <I::Modes as Modes>::core_effect(t) {
            self.rt.set_state(core)?;
        }
        Ok(self.rt.mode)
    }

    /// Reports a fault: the component enters Failure.
    pub fn fail(&mut self, reason: &str) -> Result<CoreState, TransitionError> {
        tracing::warn!(component = I::NAME, address = %self.rt.address, "failure: {reason}");
        self.rt.set_state(CoreTransition::Fail)
    }

    /// Asks `target` for control with this component's authority.
    pub fn request_control(&mut self, target: Address) {
        let authority = self.rt.authority;
        self.request_control_with(target, authority);
    }

    /// Asks `target` for control with `authority` (an operator station choosing the
    /// authority it commands with, per target).
    pub fn request_control_with(&mut self, target: Address, authority: u8) {
        self.rt.send(
            target,
            RequestComponentControl {
                authority_code: authority,
            }
            .into(),
            false,
            0,
        );
    }

    /// Gives control of `target` back.
    pub fn release_control(&mut self, target: Address) {
        self.rt.held_control.retain(|(a, _)| *a != target);
        self.rt
            .send(target, ReleaseComponentControl {}.into(), false, 0);
    }

    /// Sends `msg` to a component this one controls (or tries to): core commands such as
    /// Resume, Standby and Set Emergency, and core queries.
    pub fn send_core<M: CoreMessage>(&mut self, to: Address, msg: M) {
        self.rt.send(to, msg.into(), false, 0);
    }

    /// Asks `provider` for a service connection streaming report `report` at `rate_hz`
    /// with presence vector `presence`. The reports arrive as ordinary messages. Refused,
    /// with nothing sent, when the rate is not in (0, 1092] Hz (what the message's
    /// scaled field carries) or when
    /// [`Config::max_subscriptions`](super::Config::max_subscriptions) are already open
    /// (counted in `Stats::subscriptions_refused`).
    pub fn create_service_connection(
        &mut self,
        provider: Address,
        report: CommandCode,
        rate_hz: f64,
        presence: u32,
    ) -> Result<(), ServiceConnectionError> {
        let max = super::connections::MAX_JAUS_RATE;
        if !(rate_hz > 0.0 && rate_hz <= max) {
            self.rt.stats.subscriptions_refused += 1;
            return Err(ServiceConnectionError::Rate { rate: rate_hz, max });
        }
        if self.rt.subscribe(provider, report, rate_hz, presence) {
            Ok(())
        } else {
            Err(ServiceConnectionError::TooMany {
                max: self.rt.config.max_subscriptions,
            })
        }
    }

    /// Ends the service connection on `report` from `provider`.
    pub fn terminate_service_connection(&mut self, provider: Address, report: CommandCode) {
        self.rt.unsubscribe(provider, report);
    }

    /// Whether `provider` confirmed a service connection on `report`.
    pub fn service_connection_active(&self, provider: Address, report: CommandCode) -> bool {
        self.rt.requester.is_active(provider, report)
    }
}

/// Core messages any component may send with [`Context::send_core`].
pub trait CoreMessage: JausMessage + Into<Message> {}
macro_rules! core_messages {
    ($($t:ty),* $(,)?) => { $(impl CoreMessage for $t {})* };
}
core_messages!(
    Shutdown,
    Standby,
    Resume,
    Reset,
    SetEmergency,
    ClearEmergency,
    SetComponentAuthority,
    SetTime,
    QueryComponentAuthority,
    QueryComponentStatus,
    QueryComponentControl,
    QueryTime,
    QueryServices,
    QueryIdentification,
    QueryHeartbeatPulse,
    CreateEvent,
    UpdateEvent,
    CancelEvent,
    QueryEvents,
);

/// Why [`Context::create_service_connection`] sent no request.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ServiceConnectionError {
    /// [`Config::max_subscriptions`](super::Config::max_subscriptions) connections are
    /// already open or asked for.
    #[error("{max} service connections are already open or asked for")]
    TooMany {
        /// The configured limit.
        max: usize,
    },
    /// The rate cannot be carried by Create Service Connection: the field is a scaled
    /// u16 over 0 to 1092 Hz, and a rate must be above 0 (and a number).
    #[error("rate {rate} Hz is outside (0, {max}] Hz, what Create Service Connection carries")]
    Rate {
        /// The rate asked for.
        rate: f64,
        /// The largest rate the message carries.
        max: f64,
    },
}
