//! The runtime state of a component apart from the vendor behaviour: address, core state,
//! control, emergency senders, clock, outbox, service connections and events, and the
//! sends every part of the runtime shares.

use std::collections::VecDeque;
use std::time::Instant;

use super::connections::{ProviderTable, RequesterTable};
use super::events::EventTable;
use super::{
    Config, ControlPolicy, CoreState, CoreTransition, Interface, Modes, Stats, TransitionError,
    Transmit,
};
use crate::clock::Clock;
use crate::messages::*;
use crate::wire::AckNak;
use crate::{Address, CommandCode, Header, MessageSet};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct Controller {
    pub(super) address: Address,
    pub(super) authority: u8,
}

/// The runtime state of a component, apart from the vendor behaviour.
pub(super) struct Runtime<I: Interface> {
    pub(super) address: Address,
    pub(super) config: Config,
    pub(super) now: Instant,
    pub(super) started: bool,
    pub(super) needs_init: bool,
    pub(super) state: CoreState,
    pub(super) mode: I::Modes,
    pub(super) authority: u8,
    pub(super) controller: Option<Controller>,
    /// The controller the behaviour last knew of (to tell it when control is lost).
    pub(super) known_controller: Option<Address>,
    /// The last controller displaced by a higher authority, and when: its commands
    /// that crossed the Reject Component Control are refused quietly.
    pub(super) displaced: Option<(Address, Instant)>,
    pub(super) emergencies: Vec<Address>,
    /// Components that confirmed this one's control, each with the state it last
    /// reported (Report Component Status), if any since control was granted.
    pub(super) held_control: Vec<(Address, Option<CoreState>)>,
    pub(super) clock: Clock,
    pub(super) source: Option<Address>,
    pub(super) outbox: VecDeque<Transmit<I::Messages>>,
    pub(super) stats: Stats,
    pub(super) next_heartbeat: Option<Instant>,
    pub(super) next_tick: Instant,
    pub(super) changes: VecDeque<(CoreState, CoreState)>,
    pub(super) provider: ProviderTable<I::Messages>,
    pub(super) events: EventTable<I::Messages>,
    pub(super) requester: RequesterTable,
    /// How the commands it sent ended (its node's reliable delivery), for the
    /// behaviour to take ([`Context::take_settled`](super::Context::take_settled)).
    pub(super) settled: VecDeque<super::Settled>,
    /// The last sequence number it gave a command itself
    /// ([`Context::forward_numbered`](super::Context::forward_numbered)).
    pub(super) sequence: u16,
}

impl<I: Interface> Runtime<I> {
    pub(super) fn new(address: Address, config: Config, now: Instant) -> Self {
        Self {
            address,
            authority: config.authority,
            now,
            started: false,
            needs_init: true,
            state: CoreState::Initialize,
            mode: <I::Modes as Modes>::INITIAL,
            controller: None,
            known_controller: None,
            displaced: None,
            emergencies: Vec::new(),
            held_control: Vec::new(),
            clock: Clock::default(),
            source: None,
            outbox: VecDeque::new(),
            stats: Stats::default(),
            next_heartbeat: None,
            next_tick: now,
            changes: VecDeque::new(),
            provider: ProviderTable::default(),
            events: EventTable::default(),
            requester: RequesterTable::default(),
            settled: VecDeque::new(),
            sequence: first_sequence(address),
            config,
        }
    }

    /// The next sequence number of its own (1-65535).
    pub(super) fn next_sequence(&mut self) -> u16 {
        self.sequence = self.sequence.wrapping_add(1).max(1);
        self.sequence
    }

    pub(super) fn header(&self, code: CommandCode, to: Address) -> Header {
        Header::new(code, to, self.address)
    }

    pub(super) fn push(&mut self, t: Transmit<I::Messages>) {
        if self.outbox.len() >= self.config.outbox_capacity {
            self.stats.outbox_dropped += 1;
            tracing::warn!(
                component = I::NAME,
                address = %self.address,
                message = t.message.as_ref().map_or("ack/nak", |m| m.name()),
                "outgoing queue full ({}): message dropped",
                self.config.outbox_capacity
            );
            return;
        }
        self.outbox.push_back(t);
    }

    /// Sends a standard message (the runtime's own: reports, confirmations, ...).
    pub(super) fn send(&mut self, to: Address, message: Message, sc: bool, seq: u16) {
        self.send_set(to, I::Messages::from_standard(message), sc, seq);
    }

    /// Sends any message of the component's set.
    pub(super) fn send_set(&mut self, to: Address, message: I::Messages, sc: bool, seq: u16) {
        let mut header = self.header(message.code(), to);
        header.service_connection = sc;
        header.sequence_number = seq;
        self.push(Transmit {
            header,
            message: Some(message),
        });
    }

    pub(super) fn ack(&mut self, request: &Header, ok: bool) {
        if request.ack_nak != AckNak::Request {
            return;
        }
        self.push(Transmit {
            header: request.acknowledgement(self.address, ok),
            message: None,
        });
    }

    pub(super) fn set_state(&mut self, t: CoreTransition) -> Result<CoreState, TransitionError> {
        let from = self.state;
        let to = from.apply(t)?;
        if to != from {
            self.state = to;
            self.mode = <I::Modes as Modes>::INITIAL;
            tracing::info!(component = I::NAME, address = %self.address, "{from} -> {to} ({})", t.name());
            if self.changes.len() < 64 {
                self.changes.push_back((from, to));
            }
        }
        Ok(to)
    }

    pub(super) fn may_command(&self, source: Address) -> bool {
        match (self.controller, self.config.control) {
            (Some(c), _) => c.address == source,
            (None, ControlPolicy::Open) => true,
            (None, ControlPolicy::ControllerOnly) => false,
        }
    }

    pub(super) fn subscribe(
        &mut self,
        provider: Address,
        report: CommandCode,
        rate: f64,
        pv: u32,
    ) -> bool {
        if !self
            .requester
            .add(provider, report, rate, pv, self.config.max_subscriptions)
        {
            self.stats.subscriptions_refused += 1;
            return false;
        }
        let msg = CreateServiceConnection {
            service_connection_command_code: report.0,
            requested_periodic_update_rate: rate,
            presence_vector: pv,
        };
        self.send(provider, msg.into(), true, 0);
        true
    }

    /// Asks again for the service connections whose reports stopped.
    pub(super) fn renew_silent_subscriptions(&mut self) {
        while let Some((provider, report, rate, pv)) = self.requester.due_again(self.now) {
            tracing::debug!(address = %self.address, %provider, %report, "service connection silent: asked for again");
            let msg = CreateServiceConnection {
                service_connection_command_code: report.0,
                requested_periodic_update_rate: rate,
                presence_vector: pv,
            };
            self.send(provider, msg.into(), true, 0);
            self.stats.subscriptions_renewed += 1;
        }
    }

    pub(super) fn unsubscribe(&mut self, provider: Address, report: CommandCode) {
        if let Some(instance) = self.requester.remove(provider, report) {
            let msg = TerminateServiceConnection {
                service_connection_command_code: report.0,
                instance_id: instance,
            };
            self.send(provider, msg.into(), true, 0);
        }
    }
}

/// Where a component's own sequence numbers start: different in every process and
/// every component (std's randomly keyed hasher; no clock read), so that a restarted
/// component's numbers are not taken for retransmissions of its earlier ones.
fn first_sequence(address: Address) -> u16 {
    use std::hash::BuildHasher;
    (std::collections::hash_map::RandomState::new().hash_one(address) as u16).max(1)
}
