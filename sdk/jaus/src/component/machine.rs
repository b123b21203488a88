//! The [`Component`]: the runtime around a behaviour, driven sans-IO (messages in,
//! timeouts, messages out), with what it counts ([`Stats`]) and what it sends
//! ([`Transmit`]).

use std::marker::PhantomData;
use std::time::{Duration, Instant};

use super::runtime::Runtime;
use super::{
    refusal_report, Behaviour, Config, Context, CoreState, CoreTransition, Interface, Set,
    StopReason,
};
use crate::codec::EncodeError;
use crate::messages::*;
use crate::wire::AckNak;
use crate::{Address, Header, MessageSet};

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
    /// Outcomes of sent commands ([`Settled`](super::Settled)) dropped because the
    /// behaviour did not take them ([`MAX_SETTLED`](super::MAX_SETTLED) kept).
    pub settled_dropped: u64,
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
    pub(super) rt: Runtime<B::Interface>,
    pub(super) behaviour: B,
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
            rt.clock.set_utc(now, utc);
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

    /// How a command it sent ended (its node's reliable delivery): kept for the
    /// behaviour, which takes it in its next tick or message
    /// ([`Context::take_settled`]); the oldest is dropped (counted) beyond
    /// [`MAX_SETTLED`](super::MAX_SETTLED).
    pub fn settled(&mut self, settled: super::Settled) {
        if self.rt.settled.len() >= super::MAX_SETTLED {
            self.rt.settled.pop_front();
            self.rt.stats.settled_dropped += 1;
        }
        self.rt.settled.push_back(settled);
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
        if !self.rt.clock.is_set() {
            self.rt.clock.set_utc(now, utc);
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
}

/// The next due time after `due` with `period`, never in the past of `now` (a component
/// that was not woken for a while does not burst to catch up).
pub(super) fn next_after(due: Instant, period: Duration, now: Instant) -> Instant {
    let next = due + period;
    if next <= now {
        now + period
    } else {
        next
    }
}
