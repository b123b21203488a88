//! A simulated UDP network with a virtual clock: nodes exchange datagrams that may be
//! dropped, duplicated and delayed (hence reordered), with a seeded RNG so that a run is
//! exactly reproducible. For deterministic multi-node tests.

use std::collections::BTreeMap;
use std::net::{Ipv4Addr, SocketAddr, SocketAddrV4};
use std::time::{Duration, Instant};

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};

use jaus::net::{Node, Participant};

/// Links whose order of arrival is followed (for [`SimStats::reordered`]).
const MAX_LINKS: usize = 4096;

/// How the links misbehave.
#[derive(Debug, Clone, Copy)]
pub struct LinkModel {
    /// Probability a datagram is lost.
    pub drop: f64,
    /// Probability a datagram is delivered twice.
    pub duplicate: f64,
    /// Smallest one-way delay.
    pub min_delay: Duration,
    /// Largest one-way delay (uniform between the two: datagrams get reordered).
    pub max_delay: Duration,
}

impl Default for LinkModel {
    fn default() -> Self {
        Self {
            drop: 0.0,
            duplicate: 0.0,
            min_delay: Duration::from_micros(200),
            max_delay: Duration::from_micros(200),
        }
    }
}

/// Counters of the simulated network.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SimStats {
    /// Datagrams sent by nodes.
    pub sent: u64,
    /// Datagrams delivered.
    pub delivered: u64,
    /// Datagrams lost on purpose.
    pub dropped: u64,
    /// Extra copies delivered.
    pub duplicated: u64,
    /// Datagrams (copies included) due before one sent earlier on the same link (from,
    /// to): they overtake it, so the receiver sees the two out of order.
    pub reordered: u64,
    /// Datagrams to an address with no node.
    pub unreachable: u64,
}

/// Nodes on a simulated network. Node `i` has the address 10.0.0.(i+1):3794.
#[derive(Debug)]
pub struct SimNet {
    now: Instant,
    nodes: Vec<Option<Box<dyn Participant>>>,
    addrs: Vec<SocketAddr>,
    in_flight: BTreeMap<(Instant, u64), (SocketAddr, SocketAddr, Vec<u8>)>,
    /// The latest arrival time given to a datagram of each link (from, to).
    latest: BTreeMap<(SocketAddr, SocketAddr), Instant>,
    seq: u64,
    rng: StdRng,
    model: LinkModel,
    stats: SimStats,
}

impl SimNet {
    /// An empty network at `start` with `model` links and RNG `seed`.
    pub fn new(start: Instant, model: LinkModel, seed: u64) -> Self {
        Self {
            now: start,
            nodes: Vec::new(),
            addrs: Vec::new(),
            in_flight: BTreeMap::new(),
            latest: BTreeMap::new(),
            seq: 0,
            rng: StdRng::seed_from_u64(seed),
            model,
            stats: SimStats::default(),
        }
    }

    /// The address of node slot `i`.
    pub fn addr(i: usize) -> SocketAddr {
        SocketAddr::V4(SocketAddrV4::new(
            Ipv4Addr::new(10, 0, 0, (i + 1) as u8),
            3794,
        ))
    }

    /// Adds a node at [`SimNet::addr`] of its slot; returns the slot.
    pub fn add(&mut self, node: impl Participant) -> usize {
        let at = Self::addr(self.nodes.len());
        self.add_at(at, node)
    }

    /// Adds a participant (a node, attached components, ...) at a socket address of
    /// its own, e.g. another port on a node's host; returns its slot.
    pub fn add_at(&mut self, at: SocketAddr, participant: impl Participant) -> usize {
        self.nodes.push(Some(Box::new(participant)));
        self.addrs.push(at);
        self.nodes.len() - 1
    }

    /// The socket address of slot `i`.
    pub fn address_of(&self, i: usize) -> Option<SocketAddr> {
        self.addrs.get(i).copied()
    }

    /// Removes slot `i` from the network (a crash): it receives and sends nothing more.
    pub fn kill(&mut self, i: usize) -> Option<Box<dyn Participant>> {
        self.nodes.get_mut(i).and_then(Option::take)
    }

    /// The node in slot `i`.
    pub fn node(&self, i: usize) -> Option<&Node> {
        self.get(i)
    }

    /// The node in slot `i`, mutably.
    pub fn node_mut(&mut self, i: usize) -> Option<&mut Node> {
        self.get_mut(i)
    }

    /// The participant in slot `i`, as a `T`.
    pub fn get<T: 'static>(&self, i: usize) -> Option<&T> {
        self.nodes
            .get(i)
            .and_then(Option::as_ref)
            .and_then(|p| p.as_any().downcast_ref())
    }

    /// The participant in slot `i`, as a mutable `T`.
    pub fn get_mut<T: 'static>(&mut self, i: usize) -> Option<&mut T> {
        self.nodes
            .get_mut(i)
            .and_then(Option::as_mut)
            .and_then(|p| p.as_any_mut().downcast_mut())
    }

    /// Changes how the links misbehave, for the datagrams sent from now on.
    pub fn set_model(&mut self, model: LinkModel) {
        self.model = model;
    }

    /// Counters.
    pub fn stats(&self) -> SimStats {
        self.stats
    }

    /// The virtual time.
    pub fn now(&self) -> Instant {
        self.now
    }

    /// Injects a raw datagram (garbage, in a test) to node `i` from `from`.
    pub fn inject(&mut self, i: usize, from: SocketAddr, bytes: Vec<u8>) {
        let at = self.now + self.model.min_delay;
        self.in_flight
            .insert((at, self.seq), (from, self.addrs[i], bytes));
        self.seq += 1;
    }

    fn random(&mut self) -> f64 {
        self.rng.gen::<f64>()
    }

    fn collect(&mut self) {
        for i in 0..self.nodes.len() {
            let mut out = Vec::new();
            if let Some(n) = self.nodes[i].as_mut() {
                while let Some(d) = n.poll_transmit() {
                    out.push(d);
                }
            }
            for d in out {
                self.stats.sent += 1;
                if self.random() < self.model.drop {
                    self.stats.dropped += 1;
                    continue;
                }
                let copies = if self.random() < self.model.duplicate {
                    2
                } else {
                    1
                };
                self.stats.duplicated += copies - 1;
                for _ in 0..copies {
                    let span = self.model.max_delay.saturating_sub(self.model.min_delay);
                    let delay = self.model.min_delay + span.mul_f64(self.random());
                    let at = self.now + delay;
                    let link = (self.addrs[i], d.to);
                    match self.latest.get_mut(&link) {
                        Some(latest) if at < *latest => self.stats.reordered += 1,
                        Some(latest) => *latest = at,
                        None => {
                            if self.latest.len() < MAX_LINKS {
                                self.latest.insert(link, at);
                            }
                        }
                    }
                    self.in_flight
                        .insert((at, self.seq), (link.0, link.1, d.bytes.clone()));
                    self.seq += 1;
                }
            }
        }
    }

    /// Runs for `d` of virtual time.
    pub fn run_for(&mut self, d: Duration) {
        let end = self.now + d;
        loop {
            self.collect();
            let next_packet = self.in_flight.keys().next().map(|k| k.0);
            let next_timer = self
                .nodes
                .iter()
                .flatten()
                .filter_map(|n| n.poll_timeout())
                .min();
            let next = match (next_packet, next_timer) {
                (Some(a), Some(b)) => a.min(b),
                (a, b) => match a.or(b) {
                    Some(t) => t,
                    None => break,
                },
            };
            if next > end {
                break;
            }
            self.now = self.now.max(next);
            let now = self.now;
            if next_packet.is_some_and(|p| p <= now) {
                if let Some((_, (from, to, bytes))) = self.in_flight.pop_first() {
                    let slot = self.addrs.iter().position(|a| *a == to);
                    match slot.and_then(|i| self.nodes[i].as_mut()) {
                        Some(n) => {
                            n.handle_datagram(now, from, &bytes);
                            self.stats.delivered += 1;
                        }
                        None => self.stats.unreachable += 1,
                    }
                }
                continue;
            }
            for n in self.nodes.iter_mut().flatten() {
                if n.poll_timeout().is_some_and(|t| t <= now) {
                    n.handle_timeout(now);
                }
            }
        }
        self.now = self.now.max(end);
    }
}
