//! Components in a process of their own, attached to a node they do not run: every
//! message goes to, and comes from, that node's socket, and the node's manager routes
//! them like its built-in components (see [`Node`](super::Node): a datagram from the
//! node's own subsystem and node registers an external component). No node manager
//! runs here, so nothing speaks for the node but the node itself; the components'
//! runtime heartbeats to `subsystem.node.1.1` keep them registered.
//!
//! This is how a tool joins a running subsystem as one of its components (the `jaus`
//! CLI with `--me` on the node it talks to), and how a vendor runs a component in its
//! own process beside a node.

use std::collections::VecDeque;
use std::net::SocketAddr;
use std::time::Instant;

use super::framing::{split, Framing, Reassembler, ReassemblyLimits, ReassemblyStats};
use super::Datagram;
use super::{NetError, Participant};
use crate::component::{Endpoint, Endpoints};
use crate::wire::Header;
use crate::Address;

/// Settings of [`Attached`].
#[derive(Debug, Clone)]
pub struct AttachedConfig {
    /// Subsystem id of the node joined.
    pub subsystem: u8,
    /// Node id of the node joined.
    pub node: u8,
    /// The node's socket.
    pub node_socket: SocketAddr,
    /// Framing the node speaks.
    pub framing: Framing,
    /// Reassembly limits.
    pub reassembly: ReassemblyLimits,
    /// Most datagrams (and local deliveries) waiting.
    pub max_outbox: usize,
}

/// Counters of [`Attached`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct AttachedStats {
    /// Datagrams received.
    pub received: u64,
    /// Datagrams sent.
    pub sent: u64,
    /// Dropped: not from the node's socket.
    pub foreign: u64,
    /// Dropped: bad framing or header.
    pub bad_packet: u64,
    /// Dropped: no hosted component matches the destination.
    pub no_such_component: u64,
    /// Dropped: a queue was full.
    pub outbox_full: u64,
    /// Dropped: a message that could not be encoded or split.
    pub encode_errors: u64,
}

/// Components attached to a node through its socket (sans-IO).
pub struct Attached {
    config: AttachedConfig,
    now: Instant,
    components: Endpoints,
    reassembler: Reassembler,
    outbox: VecDeque<Datagram>,
    local_queue: VecDeque<(Header, Vec<u8>)>,
    stats: AttachedStats,
}

impl std::fmt::Debug for Attached {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Attached")
            .field("node", &(self.config.subsystem, self.config.node))
            .field("node_socket", &self.config.node_socket)
            .field("components", &self.components.len())
            .field("stats", &self.stats)
            .finish()
    }
}

impl Attached {
    /// Nothing attached yet, starting at `now`.
    pub fn new(config: AttachedConfig, now: Instant) -> Self {
        Self {
            reassembler: Reassembler::new(config.reassembly),
            config,
            now,
            components: Endpoints::default(),
            outbox: VecDeque::new(),
            local_queue: VecDeque::new(),
            stats: AttachedStats::default(),
        }
    }

    /// Adds a component; its address must be on the node joined (and not the node
    /// manager's).
    pub fn add(&mut self, endpoint: impl Endpoint) -> Result<Address, NetError> {
        self.add_boxed(Box::new(endpoint))
    }

    /// [`add`](Self::add) for a component already boxed (e.g. one of
    /// `jaus_node::host`).
    pub fn add_boxed(&mut self, endpoint: Box<dyn Endpoint>) -> Result<Address, NetError> {
        let a = endpoint.address();
        let taken = self.components.contains(a);
        NetError::check_join(a, self.config.subsystem, self.config.node, taken)?;
        self.components.push(endpoint);
        Ok(a)
    }

    /// The hosted component at `a`, as a `T`.
    pub fn get<T: 'static>(&self, a: Address) -> Option<&T> {
        self.components.get(a)
    }

    /// The hosted component at `a`, as a mutable `T`.
    pub fn get_mut<T: 'static>(&mut self, a: Address) -> Option<&mut T> {
        self.components.get_mut(a)
    }

    /// Sends a message as if a hosted component sent it.
    pub fn send(&mut self, now: Instant, header: Header, body: Vec<u8>) {
        self.advance(now);
        self.route(header, body);
        self.pump();
    }

    /// Counters.
    pub fn stats(&self) -> AttachedStats {
        self.stats
    }

    /// Reassembly counters and bytes buffered.
    pub fn reassembly(&self) -> (ReassemblyStats, usize) {
        (self.reassembler.stats(), self.reassembler.buffered())
    }

    fn advance(&mut self, now: Instant) {
        if now > self.now {
            self.now = now;
        }
    }

    fn hosted(&self, d: Address) -> bool {
        (d.subsystem == self.config.subsystem || d.subsystem == 255)
            && (d.node == self.config.node || d.node == 255)
            && self.components.any_matches(d)
    }

    /// From a hosted component: to a sibling directly, to everyone else (broadcasts
    /// included) through the node.
    fn route(&mut self, header: Header, body: Vec<u8>) {
        let d = header.destination;
        let only_sibling = d.component != 255
            && d.instance != 255
            && d.subsystem == self.config.subsystem
            && d.node == self.config.node
            && self.hosted(d);
        if !only_sibling {
            self.send_to_node(&header, &body);
        }
        if self.hosted(d) {
            self.queue_local(header, body);
        }
    }

    fn queue_local(&mut self, header: Header, body: Vec<u8>) {
        if self.local_queue.len() >= self.config.max_outbox {
            self.stats.outbox_full += 1;
        } else {
            self.local_queue.push_back((header, body));
        }
    }

    fn send_to_node(&mut self, header: &Header, body: &[u8]) {
        match split(header, body) {
            Ok(packets) => {
                for p in &packets {
                    if self.outbox.len() >= self.config.max_outbox {
                        self.stats.outbox_full += 1;
                        return;
                    }
                    self.outbox.push_back(Datagram {
                        to: self.config.node_socket,
                        bytes: self.config.framing.encode(p),
                        via: super::Via::Network,
                    });
                }
            }
            Err(e) => {
                self.stats.encode_errors += 1;
                tracing::warn!(code = %header.command_code, source = %header.source, "not sent: {e}");
            }
        }
    }

    fn pump(&mut self) {
        for _ in 0..100_000 {
            let mut out = Vec::new();
            self.components.drain_transmits(&mut out);
            for t in out {
                match t.body {
                    Ok(body) => self.route(t.header, body),
                    Err(e) => {
                        self.stats.encode_errors += 1;
                        tracing::warn!(message = t.name, code = %t.header.command_code, source = %t.header.source, "not sent: {e}");
                    }
                }
            }
            let Some((h, body)) = self.local_queue.pop_front() else {
                return;
            };
            if !self.components.deliver(self.now, &h, &body) {
                self.stats.no_such_component += 1;
            }
        }
        tracing::warn!("routing loop limit reached; the rest waits for the next event");
    }
}

impl Participant for Attached {
    fn handle_datagram(&mut self, now: Instant, peer: SocketAddr, datagram: &[u8]) {
        self.advance(now);
        self.stats.received += 1;
        if peer != self.config.node_socket {
            self.stats.foreign += 1;
            tracing::debug!(%peer, "datagram not from the node joined ({}): dropped", self.config.node_socket);
            return;
        }
        let (header, body) = match self.config.framing.packet(datagram) {
            Ok(p) => p,
            Err(e) => {
                self.stats.bad_packet += 1;
                tracing::debug!(%peer, "datagram dropped: {e}");
                return;
            }
        };
        let Some((header, body)) = self.reassembler.message(now, &header, body) else {
            return;
        };
        if self.hosted(header.destination) {
            self.queue_local(header, body);
        } else {
            self.stats.no_such_component += 1;
        }
        self.pump();
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.advance(now);
        self.reassembler.expire(self.now);
        self.components.run_due(self.now);
        self.pump();
    }

    fn poll_transmit(&mut self) -> Option<Datagram> {
        let d = self.outbox.pop_front()?;
        self.stats.sent += 1;
        Some(d)
    }

    fn poll_timeout(&self) -> Option<Instant> {
        [
            self.components.next_timeout(),
            self.reassembler.next_timeout(),
        ]
        .into_iter()
        .flatten()
        .min()
    }

    fn wall_clock(&mut self, now: Instant, utc: std::time::Duration) {
        self.components.wall_clock(now, utc);
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}
