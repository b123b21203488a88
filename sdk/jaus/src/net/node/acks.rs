//! The node's side of commands that arrive ([`crate::net::reliable`]): commands
//! leaving over the carrier ask for an acknowledgement and are resent until answered
//! ([`NodeConfig::reliable`](super::NodeConfig::reliable)); retransmissions arriving
//! are carried out once, their answer repeated.
//!
//! A tracked message is keyed by its destination, command code and sequence number;
//! the node gives every command it tracks a sequence number of its own (1-65535, 0
//! left to senders that number nothing), and an answer carries the request's number
//! back ([`Header::acknowledgement`]). An answer from a peer that leaves the number 0
//! settles the oldest message of that code to that peer. A component may number a
//! command itself (`Context::forward_numbered`): the node keeps that number, so the
//! component recognises the outcome the node hands back ([`Endpoint::settled`],
//! [`NodeEvent::Settled`](super::NodeEvent::Settled) for a companion).
//!
//! [`Endpoint::settled`]: crate::component::Endpoint::settled

use std::time::Instant;

use super::route::Origin;
use super::Node;
use crate::component::Settled;
use crate::net::framing::MAX_PACKET_BODY;
use crate::net::reliable::{content_hash, Arrival, Delivery, ReliableStats, Tracked};
use crate::net::PeerAddr;
use crate::wire::{AckNak, DataFlag, Header, MessageClass};
use crate::{Address, CommandCode};

/// A tracked message: its peer (the destination), command code and sequence number.
pub type AckKey = (Address, CommandCode, u16);

/// A received message that asked for an acknowledgement: its source, command code,
/// sequence number and the hash of its body.
pub(super) type SeenKey = (Address, CommandCode, u16, u64);

/// What the node keeps of a tracked message to send it again.
pub(super) type Kept = (Header, Vec<u8>);

/// Most outcomes kept for [`Node::poll_delivery`].
const MAX_OUTCOMES: usize = 4096;

/// Most (component, command code) pairs sent once ([`Node::send_once`]).
pub const MAX_STREAMS: usize = 256;

fn is_unicast(a: Address) -> bool {
    a.subsystem != 255 && a.node != 255 && a.component != 255 && a.instance != 255
}

impl<A: PeerAddr> Node<A> {
    /// How the tracked messages ended, oldest first ([`NodeConfig::reliable`](super::NodeConfig::reliable)).
    /// Each is also handed to the component (local or companion) that sent the
    /// message ([`Endpoint::settled`](crate::component::Endpoint::settled),
    /// [`NodeEvent::Settled`](super::NodeEvent::Settled)).
    pub fn poll_delivery(&mut self) -> Option<Delivery<AckKey>> {
        self.outcomes.pop_front()
    }

    /// Counters of both sides of commands that arrive.
    pub fn reliable_stats(&self) -> ReliableStats {
        let mut s = self.sender.stats();
        self.receiver.add_stats(&mut s);
        s.outcomes_dropped += self.outcomes_dropped;
        s
    }

    /// Messages with command code `code` from component `source` of this node (local or
    /// companion) are sent once, never asked for an acknowledgement nor resent, even
    /// with [`NodeConfig::reliable`](super::NodeConfig::reliable): a stream of
    /// set-points (Set Wrench Effort), where the next value replaces a lost one, and a
    /// late copy of an old one would only undo a newer one (and held behind each other,
    /// one at a time per peer, the stream would fall behind). At most
    /// [`MAX_STREAMS`] pairs; more are refused (false).
    pub fn send_once(&mut self, source: Address, code: CommandCode) -> bool {
        if self.streams.contains(&(source, code)) {
            return true;
        }
        if self.streams.len() >= MAX_STREAMS {
            tracing::warn!(%source, %code, "set-point streams table full: this one is tracked like any command");
            return false;
        }
        self.streams.push((source, code));
        true
    }

    /// Whether `a` has acknowledged anything (commands to it are resent until
    /// acknowledged, and it drops the retransmissions).
    pub fn known_to_answer(&self, a: Address) -> bool {
        self.sender.known_to_answer(a)
    }

    /// Hands each outcome the sender settled to the component that sent the command
    /// and keeps it for [`poll_delivery`](Self::poll_delivery).
    pub(super) fn settle_outcomes(&mut self) {
        while let Some(d) = self.sender.poll_delivery() {
            let (to, code, sequence) = d.key;
            if let Some(source) = self.ack_sources.remove(&d.key) {
                let settled = Settled {
                    to,
                    code,
                    sequence,
                    outcome: d.outcome,
                    attempts: d.attempts,
                    elapsed: d.elapsed,
                    peer_known: self.sender.known_to_answer(to),
                };
                if d.outcome != crate::component::Outcome::Acknowledged {
                    tracing::debug!(%source, destination = %to, %code, sequence, outcome = %d.outcome,
                        attempts = d.attempts, "command not acknowledged");
                }
                if let Some(e) = self.locals.endpoint_mut(source) {
                    e.settled(self.now, settled);
                } else if self.companions.contains(source) {
                    self.settled_companion(source, settled);
                }
            }
            if self.outcomes.len() >= MAX_OUTCOMES {
                self.outcomes.pop_front();
                self.outcomes_dropped += 1;
            }
            self.outcomes.push_back(d);
        }
    }

    /// Whether the component at `a` is asked for acknowledgements (false once it was
    /// learnt never to answer them).
    pub fn acknowledges(&self, a: Address) -> bool {
        self.sender.acknowledges(a)
    }

    /// A message leaving over the carrier: with reliability on, a unicast
    /// single-packet command from here asks for an acknowledgement (unless its peer is
    /// known not to give one), gets a sequence number and is kept to be resent.
    /// Returns the header to send now, or `None` when it is held behind an earlier
    /// command to the same component (sent when that one is answered).
    pub(super) fn outgoing(
        &mut self,
        header: &Header,
        body: &[u8],
        origin: Origin,
    ) -> Option<Header> {
        let mut h = *header;
        if self.config.reliable.is_none()
            || origin != Origin::Local
            || (h.ack_nak == AckNak::None && self.streams.contains(&(h.source, h.command_code)))
            || h.data_flag != DataFlag::Single
            || body.len() > MAX_PACKET_BODY
            || !is_unicast(h.destination)
        {
            return Some(h);
        }
        let command = h.command_code.class() == MessageClass::Command;
        match h.ack_nak {
            AckNak::None if command => {
                if !self.sender.ask(h.destination) {
                    return Some(h);
                }
                h.ack_nak = AckNak::Request;
            }
            AckNak::Request => {}
            _ => return Some(h),
        }
        if h.sequence_number == 0 {
            self.ack_sequence = self.ack_sequence.wrapping_add(1).max(1);
            h.sequence_number = self.ack_sequence;
        }
        let key = (h.destination, h.command_code, h.sequence_number);
        tracing::trace!(destination = %h.destination, code = %h.command_code, sequence = h.sequence_number, "tracked");
        let tracked = self
            .sender
            .track(self.now, key, h.destination, (h, body.to_vec()));
        if tracked != Tracked::Untracked {
            // Bounded as the sender's waiting messages: removed when settled.
            self.ack_sources.insert(key, h.source);
        }
        match tracked {
            Tracked::Send | Tracked::Untracked => Some(h),
            Tracked::Held => None,
        }
    }

    /// A message arrived over the carrier: an answer settles what waits for it; a
    /// retransmission already carried out is dropped (false) and its answer sent
    /// again. True when the message goes on to its destination.
    pub(super) fn incoming(&mut self, header: &Header, body: &[u8]) -> bool {
        match header.ack_nak {
            AckNak::Ack | AckNak::Nak => {
                if self.sender.waiting() > 0 {
                    let ok = header.ack_nak == AckNak::Ack;
                    let (peer, code) = (header.source, header.command_code);
                    let key = (peer, code, header.sequence_number);
                    let seq0 = header.sequence_number == 0;
                    let settled = self.sender.answered(self.now, key, peer, ok, |k| {
                        seq0 && k.0 == peer && k.1 == code
                    });
                    if settled {
                        // What waited behind it goes now.
                        self.resend_due(self.now);
                    }
                }
                true
            }
            AckNak::Request
                if header.sequence_number != 0 && header.data_flag == DataFlag::Single =>
            {
                let key = (
                    header.source,
                    header.command_code,
                    header.sequence_number,
                    content_hash(body),
                );
                match self.receiver.arrived(self.now, key) {
                    Arrival::New => true,
                    Arrival::Duplicate(answer) => {
                        tracing::debug!(source = %header.source, code = %header.command_code,
                            sequence = header.sequence_number, "retransmission dropped: carried out once");
                        if let Some(a) = answer {
                            // From the component that answered: routed as its own.
                            if self.route_common(&a, &[], Origin::Local) {
                                self.enqueue(a, Vec::new());
                            }
                        }
                        false
                    }
                }
            }
            _ => true,
        }
    }

    /// An answer a component here gives: kept for the retransmissions of the message
    /// it answers.
    pub(super) fn answer_given(&mut self, header: &Header) {
        if matches!(header.ack_nak, AckNak::Ack | AckNak::Nak) && header.sequence_number != 0 {
            let (to, code, seq) = (
                header.destination,
                header.command_code,
                header.sequence_number,
            );
            self.receiver
                .answered_matching(|k| k.0 == to && k.1 == code && k.2 == seq, *header);
        }
    }

    /// Sends what is due (a held command's first copy, another copy), and gives up what
    /// is out of attempts.
    pub(super) fn resend_due(&mut self, now: Instant) {
        if self.sender.next_timeout().is_none_or(|t| t > now) {
            return;
        }
        let mut due: Vec<Kept> = Vec::new();
        self.sender.poll(now, |_, (h, b)| due.push((*h, b.clone())));
        for (h, b) in due {
            let decision = self.scope.decide(h.source, h.destination, Origin::Local);
            if let Some(hop) = decision.network {
                self.send_network(&h, &b, hop);
            }
        }
    }
}
