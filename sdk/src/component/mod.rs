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

mod clock;
mod connections;
mod context;
mod control;
mod endpoint;
mod events;
pub mod local;
mod refusal;
mod runtime;
mod state;

use std::marker::PhantomData;
use std::time::{Duration, Instant};

pub use context::{Context, CoreMessage};
pub use endpoint::{Endpoint, Endpoints, Outgoing};
pub use refusal::refusal_report;
use refusal::{Refusal, DISPLACED_GRACE};
pub use state::{CoreState, CoreTransition, Modes, NoModes, NoTransition, TransitionError};

use crate::codec::EncodeError;
use crate::messages::*;
use crate::wire::AckNak;
use crate::{Address, CommandCode, Header, MessageSet};
use runtime::{Controller, Runtime};

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

/// Why a component did not act on a message.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Refused {
    /// The vendor did not implement this message.
    #[error("not supported by this component")]
    Unsupported,
    /// The message is understood but its content cannot be executed (NaN, an unknown
    /// waypoint, a mission that is running, ...).
    #[error("{0}")]
    Invalid(String),
    /// A field's value is outside what this component accepts (its own limit, which
    /// may be narrower than the field's range on the wire).
    #[error(
        "field `{field}` = {value} {unit} is outside this component's limit [{min}, {max}] {unit}"
    )]
    OutOfRange {
        /// The field, as named in the message definition.
        field: &'static str,
        /// The value received.
        value: f64,
        /// Lowest accepted value.
        min: f64,
        /// Highest accepted value.
        max: f64,
        /// Unit of the values.
        unit: &'static str,
    },
}

impl Refused {
    /// `value` if it lies in `[min, max]`, else the [`Refused::OutOfRange`] naming
    /// `field` (NaN is out of every range).
    pub fn check_range(
        field: &'static str,
        value: f64,
        min: f64,
        max: f64,
        unit: &'static str,
    ) -> Result<f64, Refused> {
        if value >= min && value <= max {
            Ok(value)
        } else {
            Err(Refused::OutOfRange {
                field,
                value,
                min,
                max,
                unit,
            })
        }
    }
}

/// Why [`Context::create_service_connection`] sent no request.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ServiceConnectionError {
    /// [`Config::max_subscriptions`] connections are already open or asked for.
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
    fn initialize(&mut self, ctx: &mut Context<'_, Self::Interface>) -> Result<(), String> {
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

/// Who may send the controlled commands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ControlPolicy {
    /// Only the component in control (none when nobody holds control).
    #[default]
    ControllerOnly,
    /// The component in control, or anyone while nobody holds control (OpenJAUS 3.3).
    Open,
}

/// Settings of one component.
#[derive(Debug, Clone)]
pub struct Config {
    /// The component's own authority (Set Component Authority changes it). Default 0.
    pub authority: u8,
    /// Who may send controlled commands. Default [`ControlPolicy::ControllerOnly`].
    pub control: ControlPolicy,
    /// Period of Report Heartbeat Pulse to the node manager (`None`: no heartbeat).
    /// Default 1 s.
    pub heartbeat: Option<Duration>,
    /// Where heartbeats go (`None`, the default: component 1, instance 1 of this node).
    pub node_manager: Option<Address>,
    /// Period of [`Behaviour::tick`] and of the "every change" event checks. Default
    /// 50 ms.
    pub tick: Duration,
    /// Highest rate granted to a service connection or periodic event, Hz. Default
    /// 100 Hz (the wire carries up to 1092 Hz).
    pub max_rate_hz: f64,
    /// Most service connections served at once. Default 32.
    pub max_service_connections: usize,
    /// Most events served at once. Default 32.
    pub max_events: usize,
    /// Most service connections this component requests at once. Default 32.
    pub max_subscriptions: usize,
    /// Most messages waiting in the outgoing queue (more are dropped and counted in
    /// `Stats::outbox_dropped`). Default 1024.
    pub outbox_capacity: usize,
    /// Most distinct emergency senders remembered (more are counted in
    /// `Stats::emergency_overflow`; the emergency still holds). Default 16.
    pub max_emergency_senders: usize,
    /// Identification text (`None`, the default: the component name).
    pub identification: Option<String>,
    /// UTC (since 1970-01-01) at the first instant the component sees, if known.
    /// Default `None`: the I/O shell's wall clock when it runs on a real network
    /// ([`Component::wall_clock`], e.g. `jaus::net::udp::run`), else Set Time.
    pub utc: Option<Duration>,
}

/// The defaults the field documentation states:
///
/// ```
/// use std::time::Duration;
/// use jaus::component::{Config, ControlPolicy};
///
/// let c = Config::default();
/// assert_eq!((c.authority, c.control), (0, ControlPolicy::ControllerOnly));
/// assert_eq!((c.heartbeat, c.node_manager), (Some(Duration::from_secs(1)), None));
/// assert_eq!((c.tick, c.max_rate_hz), (Duration::from_millis(50), 100.0));
/// assert_eq!((c.max_service_connections, c.max_events, c.max_subscriptions), (32, 32, 32));
/// assert_eq!((c.outbox_capacity, c.max_emergency_senders), (1024, 16));
/// assert_eq!((c.identification, c.utc), (None, None));
/// ```
impl Default for Config {
    fn default() -> Self {
        Self {
            authority: 0,
            control: ControlPolicy::ControllerOnly,
            heartbeat: Some(Duration::from_secs(1)),
            node_manager: None,
            tick: Duration::from_millis(50),
            max_rate_hz: 100.0,
            max_service_connections: 32,
            max_events: 32,
            max_subscriptions: 32,
            outbox_capacity: 1024,
            max_emergency_senders: 16,
            identification: None,
            utc: None,
        }
    }
}

/// Counters of what the component received, did and dropped.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Stats {
    /// Messages received.
    pub received: u64,
    /// Messages sent (taken from the outgoing queue).
    pub sent: u64,
    /// Bodies that did not decode.
    pub decode_errors: u64,
    /// Messages addressed to another component.
    pub misaddressed: u64,
    /// Messages the vendor did not implement.
    pub unsupported: u64,
    /// Controlled commands from a component not in control.
    pub not_controller: u64,
    /// Messages refused in the current core state (or illegal core transitions asked).
    pub wrong_state: u64,
    /// Messages refused as invalid by the vendor code.
    pub invalid: u64,
    /// Clear Emergency from a component that set no emergency.
    pub foreign_clear_emergency: u64,
    /// Emergency senders not remembered because the set was full.
    pub emergency_overflow: u64,
    /// Outgoing messages dropped because the queue was full.
    pub outbox_dropped: u64,
    /// Reports a service connection or event could not produce.
    pub report_failures: u64,
    /// Service connections or events refused.
    pub subscriptions_refused: u64,
    /// Service connections this component asked for again because their reports
    /// stopped (the provider restarted, its node was forgotten, the link was down).
    pub subscriptions_renewed: u64,
    /// Service-connection reports not sent because the component was run too late
    /// for their period (a busy or starved process): counted, never sent late.
    pub reports_missed: u64,
}

/// A message to send: its header (destination, flags, sequence number) and its body.
/// `message` is `None` for an acknowledgement (ACK/NAK carry no body).
#[derive(Debug, Clone, PartialEq)]
pub struct Transmit<M = Message> {
    /// Header; the data size is set when encoded.
    pub header: Header,
    /// The message.
    pub message: Option<M>,
}

impl<M: MessageSet> Transmit<M> {
    /// The encoded body.
    pub fn body(&self) -> Result<Vec<u8>, EncodeError> {
        match &self.message {
            Some(m) => m.to_bytes(),
            None => Ok(Vec::new()),
        }
    }
}

/// A component: the runtime around a behaviour.
pub struct Component<B: Behaviour> {
    rt: Runtime<B::Interface>,
    behaviour: B,
}

impl<B: Behaviour> std::fmt::Debug for Component<B> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Component")
            .field("name", &<B::Interface as Interface>::NAME)
            .field("address", &self.rt.address)
            .field("state", &self.rt.state)
            .field("mode", &self.rt.mode)
            .field("controller", &self.rt.controller)
            .field("stats", &self.rt.stats)
            .finish()
    }
}

impl<B: Behaviour> Component<B> {
    /// A component at `address` (its component id should be the interface id) that
    /// starts at `now` in Initialize.
    pub fn new(address: Address, behaviour: B, config: Config, now: Instant) -> Self {
        let mut rt = Runtime::new(address, config, now);
        if let Some(utc) = rt.config.utc {
            rt.clock.set(now, utc);
        }
        Self { rt, behaviour }
    }

    /// The address.
    pub fn address(&self) -> Address {
        self.rt.address
    }

    /// The core state.
    pub fn state(&self) -> CoreState {
        self.rt.state
    }

    /// The mode.
    pub fn mode(&self) -> <B::Interface as Interface>::Modes {
        self.rt.mode
    }

    /// The component in control and its authority.
    pub fn controller(&self) -> Option<(Address, u8)> {
        self.rt.controller.map(|c| (c.address, c.authority))
    }

    /// The component's own authority.
    pub fn authority(&self) -> u8 {
        self.rt.authority
    }

    /// Counters.
    pub fn stats(&self) -> Stats {
        self.rt.stats
    }

    /// Number of service connections served.
    pub fn service_connections(&self) -> usize {
        self.rt.provider.len()
    }

    /// Number of events served.
    pub fn events(&self) -> usize {
        self.rt.events.len()
    }

    /// The vendor behaviour.
    pub fn behaviour(&self) -> &B {
        &self.behaviour
    }

    /// The vendor behaviour, mutably.
    pub fn behaviour_mut(&mut self) -> &mut B {
        &mut self.behaviour
    }

    /// The wall clock from an I/O shell: UTC (since 1970-01-01) at `now`. Taken only if
    /// nobody set the component's clock yet (`Config::utc`, Set Time), so that its time
    /// stamps carry the system's time; the sans-IO runtime reads no clock of its own.
    pub fn wall_clock(&mut self, now: Instant, utc: Duration) {
        if self.rt.clock.utc(now).is_none() {
            self.rt.clock.set(now, utc);
        }
    }

    /// Forgets everything about `gone` (the node layer calls this when a component
    /// disappears): control held by it, its service connections and events.
    pub fn forget(&mut self, gone: Address) {
        if self.rt.controller.is_some_and(|c| c.address == gone) {
            self.rt.controller = None;
        }
        self.rt.provider.remove_requester(gone);
        self.rt.events.remove_requester(gone);
        self.rt.held_control.retain(|(a, _)| *a != gone);
        // Connections it provided are gone with it: asked for again once it is back.
        self.rt.requester.provider_gone(gone);
        self.notify_changes();
    }

    /// Hands a received message (header and body) to the component.
    pub fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        self.advance(now);
        self.rt.stats.received += 1;
        if !header.destination.matches(&self.rt.address) {
            self.rt.stats.misaddressed += 1;
            return;
        }
        if header.ack_nak == AckNak::Ack || header.ack_nak == AckNak::Nak {
            return;
        }
        let msg = match Set::<B>::decode(header.command_code, body) {
            Ok(m) => m,
            Err(e) => {
                self.rt.stats.decode_errors += 1;
                tracing::warn!(
                    component = <B::Interface as Interface>::NAME,
                    address = %self.rt.address,
                    source = %header.source,
                    code = %header.command_code,
                    "undecodable message dropped: {e}"
                );
                if header.ack_nak == AckNak::Request {
                    let text = format!("undecodable: {e}");
                    let report =
                        refusal_report(header.command_code, RefusalReason::Undecodable, &text);
                    self.rt.send(header.source, report.into(), false, 0);
                }
                self.rt.ack(header, false);
                return;
            }
        };
        self.rt
            .requester
            .heard(header.source, header.command_code, self.rt.now);
        let ok = self.dispatch(header, &msg);
        self.rt.ack(header, ok);
        self.notify_changes();
    }

    /// Hands a typed message to the component (as if decoded from `header`).
    pub fn handle_message(&mut self, now: Instant, header: &Header, msg: &Set<B>) {
        self.advance(now);
        self.rt.stats.received += 1;
        if !header.destination.matches(&self.rt.address) {
            self.rt.stats.misaddressed += 1;
            return;
        }
        self.rt
            .requester
            .heard(header.source, header.command_code, self.rt.now);
        let ok = self.dispatch(header, msg);
        self.rt.ack(header, ok);
        self.notify_changes();
    }

    /// Runs what is due at `now`: initialisation, heartbeat, tick, service connections,
    /// events.
    pub fn handle_timeout(&mut self, now: Instant) {
        self.advance(now);
        let now = self.rt.now;
        if self.rt.state == CoreState::Shutdown {
            return;
        }
        if let (Some(due), Some(period)) = (self.rt.next_heartbeat, self.rt.config.heartbeat) {
            if due <= now {
                let nm = self.rt.config.node_manager.unwrap_or(Address {
                    component: 1,
                    instance: 1,
                    ..self.rt.address
                });
                if <B::Interface as Interface>::ID != 1 {
                    self.rt.send(nm, ReportHeartbeatPulse {}.into(), false, 0);
                }
                self.rt.next_heartbeat = Some(next_after(due, period, now));
            }
        }
        if self.rt.next_tick <= now {
            self.rt.next_tick = next_after(self.rt.next_tick, self.rt.config.tick, now);
            self.rt.renew_silent_subscriptions();
            self.rt.source = None;
            self.behaviour.tick(&mut Context {
                rt: &mut self.rt,
                _i: PhantomData,
            });
            self.notify_changes();
            self.check_change_events();
        }
        self.run_service_connections(now);
        self.run_periodic_events(now);
        self.notify_changes();
    }

    /// The next instant [`handle_timeout`](Self::handle_timeout) must be called.
    pub fn poll_timeout(&self) -> Option<Instant> {
        if !self.rt.started || self.rt.needs_init {
            return Some(self.rt.now);
        }
        if self.rt.state == CoreState::Shutdown {
            return None;
        }
        let mut t = self.rt.next_tick;
        if let Some(h) = self.rt.next_heartbeat {
            t = t.min(h);
        }
        if let Some(s) = self.rt.provider.next_due() {
            t = t.min(s);
        }
        if let Some(e) = self.rt.events.next_due() {
            t = t.min(e);
        }
        Some(t)
    }

    /// The next message to send.
    pub fn poll_transmit(&mut self) -> Option<Transmit<Set<B>>> {
        let t = self.rt.outbox.pop_front()?;
        self.rt.stats.sent += 1;
        Some(t)
    }

    fn advance(&mut self, now: Instant) {
        if now > self.rt.now {
            self.rt.now = now;
        }
        if !self.rt.started {
            self.rt.started = true;
            self.rt.next_heartbeat = self.rt.config.heartbeat.map(|_| self.rt.now);
            self.rt.next_tick = self.rt.now;
        }
        if self.rt.needs_init && self.rt.state == CoreState::Initialize {
            self.rt.needs_init = false;
            self.rt.source = None;
            let r = self.behaviour.initialize(&mut Context {
                rt: &mut self.rt,
                _i: PhantomData,
            });
            let t = match r {
                Ok(()) => CoreTransition::Initialized,
                Err(reason) => {
                    tracing::error!(
                        component = <B::Interface as Interface>::NAME,
                        address = %self.rt.address,
                        "initialisation failed: {reason}"
                    );
                    CoreTransition::Fail
                }
            };
            // Initialize -> Standby/Failure is always legal unless the vendor changed
            // the state meanwhile; then the vendor's state stands.
            let _ = self.rt.set_state(t);
            self.notify_changes();
        }
    }

    fn notify_changes(&mut self) {
        while let Some((from, to)) = self.rt.changes.pop_front() {
            if to == CoreState::Initialize {
                self.rt.needs_init = true;
            }
            self.rt.source = None;
            let reason = match to {
                CoreState::Emergency => Some(StopReason::Emergency),
                CoreState::Standby if from == CoreState::Ready => Some(StopReason::Standby),
                CoreState::Shutdown => Some(StopReason::Shutdown),
                CoreState::Failure => Some(StopReason::Failure),
                _ => None,
            };
            if let Some(reason) = reason {
                self.stop(reason);
            }
            self.behaviour.state_changed(
                &mut Context {
                    rt: &mut self.rt,
                    _i: PhantomData,
                },
                from,
                to,
            );
        }
        let now = self.rt.controller.map(|c| c.address);
        if let Some(lost) = self.rt.known_controller.filter(|k| Some(*k) != now) {
            self.stop(StopReason::ControlLost { controller: lost });
        }
        self.rt.known_controller = now;
    }

    fn stop(&mut self, reason: StopReason) {
        tracing::info!(
            component = <B::Interface as Interface>::NAME,
            address = %self.rt.address,
            "stop: {reason}"
        );
        self.rt.source = None;
        self.behaviour.stop(
            &mut Context {
                rt: &mut self.rt,
                _i: PhantomData,
            },
            reason,
        );
    }

    fn refuse(&mut self, header: &Header, msg: &Set<B>, why: Refusal) -> bool {
        let s = &mut self.rt.stats;
        match &why {
            Refusal::NotController => s.not_controller += 1,
            Refusal::State(_) => s.wrong_state += 1,
            Refusal::Vendor(Refused::Unsupported) => s.unsupported += 1,
            Refusal::Vendor(Refused::Invalid(_) | Refused::OutOfRange { .. }) => s.invalid += 1,
            // Counted where it is found.
            Refusal::ForeignClear(_) => {}
        }
        if header.ack_nak == AckNak::Request {
            let report = refusal_report(header.command_code, why.reason(), &why.to_string());
            self.rt.send(header.source, report.into(), false, 0);
        }
        let (component, address, source) = (
            <B::Interface as Interface>::NAME,
            self.rt.address,
            header.source,
        );
        // A command from the controller a higher authority just displaced crossed the
        // Reject Component Control on its way here: normal in JAUS, not a fault.
        let crossed = matches!(why, Refusal::NotController)
            && self.rt.displaced.is_some_and(|(a, t)| {
                a == source && self.rt.now.saturating_duration_since(t) < DISPLACED_GRACE
            });
        if crossed {
            tracing::debug!(component, %address, %source, message = msg.name(),
                "refused: {why} (it lost control to a higher authority; this crossed the Reject Component Control)");
        } else if matches!(why, Refusal::Vendor(Refused::Unsupported)) {
            // Normal when peers probe what a component offers.
            tracing::debug!(component, %address, %source, message = msg.name(), "refused: {why}");
        } else {
            tracing::warn!(component, %address, %source, message = msg.name(), "refused: {why}");
        }
        false
    }

    /// Runs one message; returns whether it was accepted (for ACK/NAK).
    fn dispatch(&mut self, header: &Header, msg: &Set<B>) -> bool {
        let source = header.source;
        self.rt.source = Some(source);
        if let Some(r) = self.core_message(header, msg) {
            return match r {
                Ok(()) => true,
                Err(why) => self.refuse(header, msg, why),
            };
        }
        if let Some(Message::Event(ev)) = msg.standard() {
            // An event notification carries a report: handle the report as if it had
            // arrived directly.
            return match Set::<B>::decode(CommandCode(ev.report_message_code), &ev.report_message) {
                Ok(inner) => {
                    let h = Header {
                        command_code: inner.code(),
                        ..*header
                    };
                    self.dispatch(&h, &inner)
                }
                Err(e) => {
                    self.rt.stats.decode_errors += 1;
                    tracing::warn!(
                        component = <B::Interface as Interface>::NAME,
                        source = %source,
                        "event {} carries an undecodable report: {e}",
                        ev.event_id
                    );
                    false
                }
            };
        }
        let state = self.rt.state;
        if state == CoreState::Shutdown {
            return self.refuse(header, msg, Refusal::State(state));
        }
        let code = msg.code();
        if <B::Interface as Interface>::COMMANDS.contains(&code) {
            if !self.rt.may_command(source) {
                return self.refuse(header, msg, Refusal::NotController);
            }
            if !matches!(state, CoreState::Ready | CoreState::Standby) {
                return self.refuse(header, msg, Refusal::State(state));
            }
        }
        let r = self.behaviour.handle(
            &mut Context {
                rt: &mut self.rt,
                _i: PhantomData,
            },
            msg,
        );
        match r {
            Ok(Some(reply)) => {
                self.rt.send_set(source, reply, false, 0);
                true
            }
            Ok(None) => true,
            Err(e) => self.refuse(header, msg, Refusal::Vendor(e)),
        }
    }

    /// Answers a query for a service connection or an event: core queries by the
    /// runtime, the others by the behaviour.
    fn answer(&mut self, requester: Address, query: &Set<B>) -> Result<Set<B>, Refused> {
        if let Some(r) = query.standard().and_then(|q| self.core_report(q)) {
            return Ok(Set::<B>::from_standard(r));
        }
        let code = query.code();
        let iface_ok = <B::Interface as Interface>::ANY_MESSAGE
            || <B::Interface as Interface>::ACCEPTS.contains(&code);
        if !iface_ok || self.rt.state == CoreState::Shutdown {
            return Err(Refused::Unsupported);
        }
        self.rt.source = Some(requester);
        let r = self.behaviour.handle(
            &mut Context {
                rt: &mut self.rt,
                _i: PhantomData,
            },
            query,
        );
        match r {
            Ok(Some(report)) => Ok(report),
            Ok(None) => Err(Refused::Unsupported),
            Err(e) => Err(e),
        }
    }

    /// The report of a core query, answered by the runtime.
    fn core_report(&self, query: &Message) -> Option<Message> {
        let c = &self.rt;
        Some(match query {
            Message::QueryComponentAuthority(_) => ReportComponentAuthority {
                authority_code: c.authority,
            }
            .into(),
            Message::QueryComponentStatus(_) => ReportComponentStatus {
                primary_status_code: c.state.to_wire(),
                secondary_status_code: 0,
            }
            .into(),
            Message::QueryComponentControl(_) => {
                let (a, auth) = c
                    .controller
                    .map_or((Address::default(), 0), |k| (k.address, k.authority));
                ReportComponentControl {
                    subsystem_id: a.subsystem,
                    node_id: a.node,
                    component_id: a.component,
                    instance_id: a.instance,
                    authority_code: auth,
                }
                .into()
            }
            Message::QueryTime(q) => {
                let stamps = c.clock.stamps(c.now);
                ReportTime {
                    time_stamp: stamps.filter(|_| q.presence_vector & 1 != 0).map(|s| s.0),
                    date_stamp: stamps.filter(|_| q.presence_vector & 2 != 0).map(|s| s.1),
                }
                .into()
            }
            Message::QueryHeartbeatPulse(_) => ReportHeartbeatPulse {}.into(),
            Message::QueryServices(_) => self.services().into(),
            Message::QueryIdentification(q) if q.query_field == QueryLevel::Component => {
                ReportIdentification {
                    query_type: QueryLevel::Component,
                    authority: c.authority,
                    identification_type: 0,
                    identification: c
                        .config
                        .identification
                        .clone()
                        .unwrap_or_else(|| <B::Interface as Interface>::NAME.to_string()),
                }
                .into()
            }
            Message::QueryEvents(q) => self.rt.events.report(q).into(),
            _ => return None,
        })
    }

    fn services(&self) -> ReportServices {
        let entry = |code: &CommandCode| ServiceCommand {
            command_code: code.0,
            presence_vector: 0,
        };
        let core = JausService {
            service_type: 0,
            input_commands: jaus_core_inputs().iter().map(entry).collect(),
            output_commands: jaus_core_outputs().iter().map(entry).collect(),
        };
        type I<B> = <B as Behaviour>::Interface;
        let inputs: Vec<ServiceCommand> = I::<B>::COMMANDS
            .iter()
            .chain(I::<B>::ACCEPTS)
            .map(entry)
            .collect();
        let outputs: Vec<ServiceCommand> = I::<B>::EMITS
            .iter()
            .copied()
            .chain(
                I::<B>::ACCEPTS
                    .iter()
                    .filter_map(|c| <I<B> as Interface>::Messages::report_of(*c)),
            )
            .map(|c| entry(&c))
            .collect();
        ReportServices {
            services: vec![
                core,
                JausService {
                    service_type: u16::from(I::<B>::ID),
                    input_commands: inputs,
                    output_commands: outputs,
                },
            ],
        }
    }
}

/// The message set of a behaviour's interface.
type Set<B> = <<B as Behaviour>::Interface as Interface>::Messages;

/// The next due time after `due` with `period`, never in the past of `now` (a component
/// that was not woken for a while does not burst to catch up).
fn next_after(due: Instant, period: Duration, now: Instant) -> Instant {
    let next = due + period;
    if next <= now {
        now + period
    } else {
        next
    }
}

/// The core inputs listed in Report Services (service type 0), as OpenJAUS lists them:
/// the messages the definitions mark `runtime: [handles]` or `[shares]`.
fn jaus_core_inputs() -> &'static [CommandCode] {
    crate::messages::RUNTIME_INPUTS
}

/// The core outputs listed in Report Services: the messages the definitions mark
/// `runtime: [emits]`.
fn jaus_core_outputs() -> &'static [CommandCode] {
    crate::messages::RUNTIME_OUTPUTS
}
