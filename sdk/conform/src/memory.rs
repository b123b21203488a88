//! A [`Session`] without sockets: the target is a [`Node`] in the same process, the
//! tester's node beside it, datagrams handed between the two at once, time virtual
//! (a check's one-second wait takes no time). For the tester's own tests and for
//! vendors testing their components before they field them.

use std::net::{Ipv4Addr, SocketAddr, SocketAddrV4};
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::net::{Framing, Node, NodeConfig};
use jaus::{Address, Header, Packet};

use crate::capture::{wall_now, Tap};
use crate::session::{dropped, pop, tester_node, Inbox, Incoming, Session, Voices};

/// The target node's (pretend) socket.
pub const TARGET: SocketAddr = SocketAddr::V4(SocketAddrV4::new(Ipv4Addr::new(10, 0, 0, 1), 3794));
/// The tester node's (pretend) socket: give it as a peer of the target node.
pub const TESTER: SocketAddr = SocketAddr::V4(SocketAddrV4::new(Ipv4Addr::new(10, 0, 0, 2), 3794));

/// The target node and the tester's node on a virtual clock.
#[derive(Debug)]
pub struct MemorySession {
    now: Instant,
    target: Node,
    tester: Node,
    inbox: Inbox,
    /// The first instant and the wall-clock time it stands for (captures are stamped
    /// with virtual time on the wall clock's scale).
    t0: Instant,
    wall0: Duration,
    tap: Tap,
}

/// Most datagrams handed over in one pump (two nodes answering each other forever
/// cannot hang the session).
const MAX_PUMP: usize = 100_000;

impl MemorySession {
    /// A session with `target` (a node whose peers include [`TESTER`]), the tester's
    /// node at `voices`' subsystem and node, both at `t0`; the two nodes first spend a
    /// virtual second finding each other.
    pub fn new(target: Node, voices: &Voices, t0: Instant) -> Result<Self, String> {
        let inbox = Inbox::default();
        let config = NodeConfig {
            subsystem: voices.controller.subsystem,
            node: voices.controller.node,
            framing: Framing::Judp,
            peers: vec![TARGET],
            ..NodeConfig::default()
        };
        let tester = tester_node(config, voices, &inbox, t0)?;
        let mut s = MemorySession {
            now: t0,
            target,
            tester,
            inbox,
            t0,
            wall0: wall_now(),
            tap: Tap::default(),
        };
        // The target's components know the time of day on the virtual clock's scale,
        // as a node's shell gives it from the host's clock.
        jaus::net::Participant::wall_clock(&mut s.target, t0, s.wall0);
        s.run_until(t0 + Duration::from_secs(1), false);
        if let Ok(mut q) = s.inbox.lock() {
            q.clear();
        }
        Ok(s)
    }

    /// The target node (to look at its components after a run).
    pub fn target(&mut self) -> &mut Node {
        &mut self.target
    }

    fn keep(&mut self, from: SocketAddr, to: SocketAddr, bytes: &[u8]) {
        let time = self.wall0 + self.now.saturating_duration_since(self.t0);
        self.tap.push(time, from, to, bytes);
    }

    fn pump(&mut self) {
        for _ in 0..MAX_PUMP {
            let mut moved = false;
            while let Some(d) = self.target.poll_transmit() {
                moved = true;
                if d.to == TESTER {
                    self.keep(TARGET, TESTER, &d.bytes);
                    self.tester.handle_datagram(self.now, TARGET, &d.bytes);
                }
            }
            while let Some(d) = self.tester.poll_transmit() {
                moved = true;
                if d.to == TARGET {
                    self.keep(TESTER, TARGET, &d.bytes);
                    self.target.handle_datagram(self.now, TESTER, &d.bytes);
                }
            }
            if !moved {
                return;
            }
        }
    }

    fn has_mail(&self) -> bool {
        self.inbox.lock().is_ok_and(|q| !q.is_empty())
    }

    /// Runs both nodes until `deadline`, or until a voice has mail when `stop_on_mail`.
    fn run_until(&mut self, deadline: Instant, stop_on_mail: bool) {
        for _ in 0..MAX_PUMP {
            self.pump();
            if (stop_on_mail && self.has_mail()) || self.now >= deadline {
                return;
            }
            let next = [self.target.poll_timeout(), self.tester.poll_timeout()]
                .into_iter()
                .flatten()
                .min()
                .unwrap_or(deadline);
            // Virtual time moves by at least a microsecond, so a timer that stays due
            // cannot stall the loop.
            self.now = next.max(self.now + Duration::from_micros(1)).min(deadline);
            self.target.handle_timeout(self.now);
            self.tester.handle_timeout(self.now);
        }
    }
}

impl Session for MemorySession {
    fn now(&self) -> Instant {
        self.now
    }
    fn utc(&self) -> Duration {
        self.wall0 + self.now.saturating_duration_since(self.t0)
    }
    fn send(&mut self, header: Header, body: Vec<u8>) {
        self.tester.send(self.now, header, body);
        self.pump();
    }
    fn send_raw(&mut self, _to: Address, packet: Vec<u8>) {
        let bytes = Framing::Judp.encode(&packet);
        self.keep(TESTER, TARGET, &bytes);
        self.target.handle_datagram(self.now, TESTER, &bytes);
        self.pump();
    }
    fn tap(&mut self) -> &mut Tap {
        &mut self.tap
    }
    fn dropped(&self) -> u64 {
        dropped(&self.inbox)
    }
    fn recv(&mut self, deadline: Instant) -> Option<Incoming> {
        if let Some(p) = pop(&self.inbox) {
            return Some(p);
        }
        self.run_until(deadline, true);
        pop(&self.inbox)
    }
}

/// A packet's bytes with its header's data size as given (for malformed packets).
pub(crate) fn packet_bytes(header: Header, body: &[u8], data_size: Option<u16>) -> Vec<u8> {
    let mut bytes = Packet::new(header, body.to_vec())
        .to_bytes()
        .unwrap_or_default();
    if let (Some(size), true) = (data_size, bytes.len() >= 16) {
        // Bytes 12-13: the data control word, data size in its low 12 bits.
        let word = u16::from_le_bytes([bytes[12], bytes[13]]);
        let word = (word & 0xF000) | (size & 0x0FFF);
        bytes[12..14].copy_from_slice(&word.to_le_bytes());
    }
    bytes
}
