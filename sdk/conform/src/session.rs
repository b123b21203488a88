//! The seam between the checks and the network (as quinn-proto is to quinn): a
//! [`Session`] sends packets from the tester's voices, sends malformed packets, and
//! hands back what arrives for the voices by a deadline. The engine and its checks use
//! nothing else, so they run without sockets over [`crate::memory::MemorySession`] (a
//! target node in the same process, on a virtual clock) and over UDP with
//! [`crate::udp::UdpSession`].
//!
//! The tester speaks with four voices: System Commanders on the tester's node at
//! instances 1-4 of component 40 ([`Voices`]), so that it can be a controller, a second
//! requester at the same authority, a requester at a higher one, and a component that
//! never holds control.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use jaus::component::{Endpoint, Outgoing};
use jaus::{Address, Header};

/// A packet received by one of the tester's voices.
#[derive(Debug, Clone, PartialEq)]
pub struct Incoming {
    /// When it arrived (the session's clock).
    pub at: Instant,
    /// Its header (an acknowledgement has `ack_nak` set and an empty body).
    pub header: Header,
    /// Its body.
    pub body: Vec<u8>,
}

/// The network as the engine sees it.
pub trait Session {
    /// The session's clock (virtual for [`crate::memory::MemorySession`]).
    fn now(&self) -> Instant;
    /// UTC (since 1970-01-01) now on the session's clock: what the target's clock is
    /// compared with (`core.time`).
    fn utc(&self) -> Duration;
    /// Sends `body` under `header` (its data size is set from the body) from the voice
    /// named by `header.source`.
    fn send(&mut self, header: Header, body: Vec<u8>);
    /// Sends one packet exactly as given (a 16-byte header and whatever follows, right
    /// or wrong) to the node of `to`, framed for the carrier.
    fn send_raw(&mut self, to: Address, packet: Vec<u8>);
    /// The next packet for any voice, waiting until `deadline` at most.
    fn recv(&mut self, deadline: Instant) -> Option<Incoming>;
    /// Packets for the voices not kept because the inbox was full (a flooding target).
    fn dropped(&self) -> u64;
    /// The session's recording of the datagrams it exchanges.
    fn tap(&mut self) -> &mut crate::capture::Tap;
    /// Keeps every datagram exchanged from now on (for a pcap file).
    fn record(&mut self) {
        self.tap().start();
    }
    /// The datagrams kept since [`record`](Session::record), leaving an empty recording.
    fn take_recording(&mut self) -> crate::capture::Recording {
        self.tap().take()
    }
}

/// The tester's addresses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Voices {
    /// The controller.
    pub controller: Address,
    /// A second requester at the controller's authority.
    pub rival: Address,
    /// A requester at a higher authority.
    pub senior: Address,
    /// A component that never asks for control.
    pub outsider: Address,
}

impl Voices {
    /// The four voices on node `subsystem`.`node`: 40.1 to 40.4.
    pub fn on(subsystem: u8, node: u8) -> Self {
        let a = |i| Address::new(subsystem, node, 40, i);
        Voices {
            controller: a(1),
            rival: a(2),
            senior: a(3),
            outsider: a(4),
        }
    }

    /// All four.
    pub fn all(&self) -> [Address; 4] {
        [self.controller, self.rival, self.senior, self.outsider]
    }
}

/// What the voices received and not yet read, at most [`MAX_INBOX`] packets.
#[derive(Debug, Default)]
pub struct Mailbox {
    queue: VecDeque<Incoming>,
    /// Packets not kept because the mailbox was full.
    pub dropped: u64,
}

impl Mailbox {
    /// Whether nothing waits.
    pub fn is_empty(&self) -> bool {
        self.queue.is_empty()
    }
    /// Forgets what waits (the drop count stays).
    pub fn clear(&mut self) {
        self.queue.clear();
    }
    fn push(&mut self, p: Incoming) {
        if self.queue.len() < MAX_INBOX {
            self.queue.push_back(p);
        } else {
            self.dropped += 1;
        }
    }
}

/// What the voices received, shared by the voices' endpoints and the session.
pub type Inbox = Arc<Mutex<Mailbox>>;

/// A voice on the tester's node: keeps every packet addressed to it (acknowledgements
/// included) in the shared inbox, sends nothing of its own.
#[derive(Debug)]
pub struct Ear {
    address: Address,
    inbox: Inbox,
}

impl Ear {
    /// A voice at `address` keeping what it hears in `inbox`.
    pub fn new(address: Address, inbox: Inbox) -> Self {
        Ear { address, inbox }
    }
}

/// Most packets kept unread (a flood from the target cannot grow the tester without
/// bound).
pub const MAX_INBOX: usize = 10_000;

impl Endpoint for Ear {
    fn address(&self) -> Address {
        self.address
    }
    fn handle(&mut self, now: Instant, header: &Header, body: &[u8]) {
        if let Ok(mut q) = self.inbox.lock() {
            q.push(Incoming {
                at: now,
                header: *header,
                body: body.to_vec(),
            });
        }
    }
    fn handle_timeout(&mut self, _now: Instant) {}
    fn poll_transmit(&mut self) -> Option<Outgoing> {
        None
    }
    fn poll_timeout(&self) -> Option<Instant> {
        None
    }
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}

/// Takes the oldest packet from `inbox`.
pub(crate) fn pop(inbox: &Inbox) -> Option<Incoming> {
    inbox.lock().ok().and_then(|mut q| q.queue.pop_front())
}

/// How many packets `inbox` dropped.
pub(crate) fn dropped(inbox: &Inbox) -> u64 {
    inbox.lock().map_or(0, |q| q.dropped)
}

/// A tester node hosting the four voices.
pub(crate) fn tester_node<A: jaus::net::PeerAddr>(
    config: jaus::net::NodeConfig<A>,
    voices: &Voices,
    inbox: &Inbox,
    now: Instant,
) -> Result<jaus::net::Node<A>, String> {
    let mut node = jaus::net::Node::new(config, now);
    for a in voices.all() {
        node.add(Ear::new(a, inbox.clone()))
            .map_err(|e| format!("tester voice {a}: {e}"))?;
    }
    Ok(node)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_full_inbox_counts_what_it_drops() {
        let inbox = Inbox::default();
        let mut ear = Ear::new(Address::new(1, 1, 40, 1), inbox.clone());
        let h = Header::new(
            jaus::CommandCode(0x4002),
            Address::new(1, 1, 40, 1),
            Address::new(2, 1, 33, 1),
        );
        let now = Instant::now();
        for _ in 0..MAX_INBOX + 2 {
            ear.handle(now, &h, &[0; 5]);
        }
        assert_eq!(dropped(&inbox), 2);
        assert!(pop(&inbox).is_some());
    }
}
