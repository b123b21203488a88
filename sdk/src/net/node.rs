//! A node, sans-IO: its node manager and local components, routing between them and
//! one UDP interface. Components in other processes join through the same socket: a
//! datagram whose source is this node's subsystem and node (and not a built-in id)
//! registers an external component at the datagram's address; it is routed like a
//! built-in component and removed after [`NodeConfig::external_timeout`] of silence. Inputs are `(now, peer, datagram)` and timeouts; outputs are
//! datagrams for peers and the next wake-up time.

use std::collections::{HashMap, VecDeque};
use std::net::SocketAddr;
use std::time::Instant;

use super::framing::{
    split, DatagramError, Framing, Reassembler, ReassemblyLimits, ReassemblyStats, MAX_PACKET_BODY,
};
use super::manager::{ManagerConfig, StockNodeManager, SystemTree};
use super::policy::{PolicyState, Verdict};
use super::{NetError, Participant};
use crate::component::{Component, Config};
use crate::component::{Endpoint, Endpoints, Outgoing};
use crate::components::node_manager;
use crate::wire::{DataFlag, Header, HEADER_LEN};
use crate::Address;

/// Settings of a node.
#[derive(Debug, Clone)]
pub struct NodeConfig {
    /// Subsystem id (1-254). Default 1.
    pub subsystem: u8,
    /// Node id (1-254). Default 1.
    pub node: u8,
    /// Node manager settings (names, heartbeat, node timeout; defaults there).
    pub manager: ManagerConfig,
    /// Framing of the UDP interface. Default JUDP.
    pub framing: Framing,
    /// Peers always sent broadcasts and messages to nodes not yet located. Default
    /// none.
    pub peers: Vec<SocketAddr>,
    /// Reassembly limits (defaults there: 1 MiB per message, 2 MiB per source, 16 MiB
    /// in all, 2 s).
    pub reassembly: ReassemblyLimits,
    /// Most datagrams waiting to be sent (more are dropped and counted). Default 8192.
    pub max_outbox: usize,
    /// Settings of the node manager component (the component defaults).
    pub component: Config,
    /// Most external components (other processes using this node's socket). Default
    /// 64.
    pub max_external: usize,
    /// An external component not heard from for this long is removed (they heartbeat
    /// every second). Default 3 s.
    pub external_timeout: std::time::Duration,
    /// Multicast discovery (docs/wire.md §9.5): messages to every subsystem or every
    /// node (heartbeats, broadcast queries) go to this group (e.g. 224.1.0.1:3794)
    /// and the configured peers, instead of to every node learned. Default `None`
    /// (off, as in OpenJAUS's default configuration). The I/O shell joins the group.
    pub multicast: Option<SocketAddr>,
    /// The subsystem's Communicator (Part 1 §5.2.1 and Figure 5-1: the single point of
    /// entry into the subsystem), on this node or another node of the subsystem.
    /// When set, every message for another subsystem goes through it: on this node it
    /// is handed, packet by packet, to the communicator's endpoint
    /// ([`Endpoint::gateway_send`], e.g. `jaus::stock::communicator::CommunicatorEndpoint`)
    /// instead of to a UDP peer, and the packets it receives from its data links are
    /// routed as if received (to the components here and the other nodes of the
    /// subsystem); on another node, such messages are sent to that node. Datagrams on
    /// the UDP interface from other subsystems are then dropped (counted in
    /// [`NetStats::not_via_communicator`]) unless a node relays them from its
    /// communicator. Default `None`: other subsystems are reached over UDP like nodes.
    pub communicator: Option<Address>,
    /// Who may command the components here, take control of them and with what
    /// authority ([`Policy`](super::policy::Policy)), checked before a message from
    /// outside the node reaches a component. Default `None`: open, as RA 3.3 is.
    pub policy: Option<super::policy::Policy>,
}

/// The defaults the field documentation states:
///
/// ```
/// let n = jaus::net::NodeConfig::default();
/// assert_eq!((n.subsystem, n.node, n.framing), (1, 1, jaus::net::Framing::Judp));
/// assert!(n.peers.is_empty());
/// assert_eq!((n.max_outbox, n.max_external), (8192, 64));
/// assert_eq!(n.external_timeout, std::time::Duration::from_secs(3));
/// assert!(n.multicast.is_none());
/// assert!(n.communicator.is_none());
/// assert!(n.policy.is_none());
/// ```
impl Default for NodeConfig {
    fn default() -> Self {
        Self {
            subsystem: 1,
            node: 1,
            manager: ManagerConfig::default(),
            framing: Framing::Judp,
            peers: Vec::new(),
            reassembly: ReassemblyLimits::default(),
            max_outbox: 8192,
            component: Config::default(),
            max_external: 64,
            external_timeout: std::time::Duration::from_secs(3),
            multicast: None,
            communicator: None,
            policy: None,
        }
    }
}

/// A datagram to send.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Datagram {
    /// The peer.
    pub to: SocketAddr,
    /// Framed bytes.
    pub bytes: Vec<u8>,
    /// The socket it leaves from.
    pub via: Via,
}

/// Which socket of a node a datagram leaves from: the network interface, or one of the
/// two sockets of OpenJAUS's local component interface ([`oj`](super::oj)), which a
/// node serves when its shell binds them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Via {
    /// The node's JAUS socket (JUDP or "JAUS01.0").
    #[default]
    Network,
    /// The component data socket (raw packets, port 24629).
    ComponentData,
    /// The component control socket (8-byte control datagrams, port 24627).
    ComponentControl,
}

/// Counters of the interface and the routing.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct NetStats {
    /// Datagrams received.
    pub received: u64,
    /// Datagrams sent (taken from the queue).
    pub sent: u64,
    /// Messages delivered to local components (from anywhere).
    pub delivered_local: u64,
    /// Dropped: bad transport framing.
    pub bad_framing: u64,
    /// Dropped: bad JAUS header or data size not matching the datagram.
    pub bad_packet: u64,
    /// Dropped: looped back from this very node.
    pub from_self: u64,
    /// Dropped: addressed to another node (nothing is forwarded between nodes).
    pub not_for_us: u64,
    /// Dropped: no local component matches the destination.
    pub no_such_component: u64,
    /// Dropped: the outgoing queue was full.
    pub outbox_full: u64,
    /// Dropped: a message that could not be encoded or split.
    pub encode_errors: u64,
    /// Messages sent to every peer because their node is not located yet.
    pub flooded: u64,
    /// External components refused (table full, or an id a built-in component has).
    pub external_refused: u64,
    /// External components removed after their timeout.
    pub external_timed_out: u64,
    /// Packets handed to this node's communicator, leaving the subsystem
    /// ([`NodeConfig::communicator`]).
    pub to_communicator: u64,
    /// Packets this node's communicator received from its data links.
    pub from_communicator: u64,
    /// Dropped: a datagram from another subsystem that did not come through the
    /// subsystem's communicator.
    pub not_via_communicator: u64,
    /// Messages refused by the node's policy ([`NodeConfig::policy`]; per rule in
    /// [`Node::policy`]).
    pub policy_refused: u64,
}

/// Where a message being routed comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Origin {
    /// A component of this node (built-in or external).
    Local,
    /// Another node, through the UDP interface.
    Network,
    /// Another subsystem, through this node's communicator.
    Link,
}

impl Origin {
    fn name(self) -> &'static str {
        match self {
            Origin::Local => "here",
            Origin::Network => "network",
            Origin::Link => "communicator",
        }
    }
}

type Manager = Component<node_manager::Dispatch<StockNodeManager>>;

/// A node: node manager, local components, one UDP interface.
pub struct Node {
    config: NodeConfig,
    now: Instant,
    manager: Manager,
    locals: Endpoints,
    /// Components of this node in other processes: address → (socket, last heard,
    /// the socket of ours that reaches them).
    external: HashMap<Address, (SocketAddr, Instant, Via)>,
    /// Addresses given out by OpenJAUS check-ins, until the component is heard or
    /// checks out (→ when given).
    checked_in: HashMap<Address, Instant>,
    peers: HashMap<(u8, u8), SocketAddr>,
    reassembler: Reassembler,
    outbox: VecDeque<Datagram>,
    local_queue: VecDeque<(Header, Vec<u8>)>,
    /// Byte buffers for bodies and datagrams, reused: the shell hands sent datagrams
    /// back ([`Node::recycle`]), so that routing a message allocates nothing once the
    /// pool is warm. Bounded by [`POOL_BUFFERS`].
    pool: Vec<Vec<u8>>,
    /// What the components want to send, collected before routing (kept for its
    /// capacity).
    transmits: Vec<Outgoing>,
    stats: NetStats,
    policy: Option<PolicyState>,
}

/// Most byte buffers a node keeps for reuse.
const POOL_BUFFERS: usize = 256;
/// Largest buffer kept for reuse (bigger ones, of multi-packet messages, are freed).
const POOL_BUFFER_BYTES: usize = 8 + HEADER_LEN + MAX_PACKET_BODY + 64;

impl std::fmt::Debug for Node {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Node")
            .field("address", &self.manager.address())
            .field("locals", &self.locals.len())
            .field("peers", &self.peers)
            .field("stats", &self.stats)
            .finish()
    }
}

/// Most packets taken from the communicator's data links in one wake-up (the rest wait
/// for the next, which is due at once).
const MAX_LINK_PACKETS: usize = 1024;

/// Most local deliveries in one run of the routing loop (two local components that
/// answer each other forever cannot starve the node).
const MAX_LOCAL_ROUNDS: usize = 100_000;

impl Node {
    /// A node starting at `now` with its node manager at `subsystem.node.1.1`.
    pub fn new(config: NodeConfig, now: Instant) -> Self {
        let me = Address::new(config.subsystem, config.node, 1, 1);
        let stock = StockNodeManager::new(me, config.manager.clone());
        let manager = node_manager::component(me, stock, config.component.clone(), now);
        let policy = config.policy.clone().map(PolicyState::new);
        Self {
            reassembler: Reassembler::new(config.reassembly),
            config,
            now,
            manager,
            locals: Endpoints::default(),
            external: HashMap::new(),
            checked_in: HashMap::new(),
            peers: HashMap::new(),
            outbox: VecDeque::new(),
            local_queue: VecDeque::new(),
            pool: Vec::new(),
            transmits: Vec::new(),
            stats: NetStats::default(),
            policy,
        }
    }

    /// The node manager's address.
    pub fn address(&self) -> Address {
        self.manager.address()
    }

    /// Adds a local component; it must be on this node.
    pub fn add(&mut self, endpoint: impl Endpoint) -> Result<Address, NetError> {
        self.add_boxed(Box::new(endpoint))
    }

    /// Adds a boxed local component; it must be on this node.
    pub fn add_boxed(&mut self, endpoint: Box<dyn Endpoint>) -> Result<Address, NetError> {
        let a = endpoint.address();
        if a.subsystem != self.config.subsystem
            || a.node != self.config.node
            || !a.is_valid()
            || a.component == 1
        {
            return Err(NetError::NotOnThisNode {
                component: a,
                subsystem: self.config.subsystem,
                node: self.config.node,
            });
        }
        if self.locals.contains(a) {
            return Err(NetError::Duplicate(a));
        }
        self.manager.behaviour_mut().0.add_local(a);
        self.locals.push(endpoint);
        Ok(a)
    }

    /// The system tree.
    pub fn tree(&self) -> &SystemTree {
        self.manager.behaviour().0.tree()
    }

    /// Moves whenever the system tree may have changed (see
    /// [`StockNodeManager::tree_version`](super::manager::StockNodeManager::tree_version)).
    pub fn tree_version(&self) -> u64 {
        self.manager.behaviour().0.tree_version()
    }

    /// The runtime counters of the node manager and of every local component.
    pub fn component_stats(&self) -> impl Iterator<Item = (Address, crate::component::Stats)> + '_ {
        std::iter::once((self.manager.address(), self.manager.stats())).chain(self.locals.stats())
    }

    /// Counters of the interface and the routing.
    pub fn stats(&self) -> NetStats {
        self.stats
    }

    /// The node's policy and its refusals per rule, when it has one.
    pub fn policy(&self) -> Option<&PolicyState> {
        self.policy.as_ref()
    }

    /// Reassembly counters.
    pub fn reassembly(&self) -> (ReassemblyStats, usize) {
        (self.reassembler.stats(), self.reassembler.buffered())
    }

    /// Peers located so far, by (subsystem, node).
    pub fn peers(&self) -> &HashMap<(u8, u8), SocketAddr> {
        &self.peers
    }

    /// The local component at `a`, as a `T`.
    pub fn get<T: 'static>(&self, a: Address) -> Option<&T> {
        self.locals.get(a)
    }

    /// The local component at `a`, as a mutable `T`.
    pub fn get_mut<T: 'static>(&mut self, a: Address) -> Option<&mut T> {
        self.locals.get_mut(a)
    }

    /// Queues a message from a local address (as if that component sent it).
    pub fn send(&mut self, now: Instant, header: Header, body: Vec<u8>) {
        self.advance(now);
        self.route(header, body, Origin::Local);
        self.pump();
    }

    /// A datagram arrived from `peer`.
    pub fn handle_datagram(&mut self, now: Instant, peer: SocketAddr, datagram: &[u8]) {
        self.advance(now);
        self.stats.received += 1;
        let (header, body) = match self.config.framing.packet(datagram) {
            Ok(p) => p,
            Err(e) => {
                match e {
                    DatagramError::Framing(_) => self.stats.bad_framing += 1,
                    _ => self.stats.bad_packet += 1,
                }
                tracing::debug!(%peer, "datagram dropped: {e}");
                return;
            }
        };
        let src = header.source;
        let mine = src.subsystem == self.config.subsystem && src.node == self.config.node;
        if mine && !self.accept_external(now, src, peer, Via::Network) {
            self.stats.from_self += 1;
            return;
        }
        if !src.is_valid() || src.subsystem == 255 || src.node == 255 {
            self.stats.bad_packet += 1;
            return;
        }
        let foreign = src.subsystem != self.config.subsystem;
        if let Some(comm) = self.config.communicator.filter(|_| foreign) {
            // Figure 5-1: other subsystems come in through the communicator only (a
            // node other than the communicator's takes what that node relays).
            let relayed = comm.node != self.config.node
                && self.peers.get(&(self.config.subsystem, comm.node)) == Some(&peer);
            if !relayed {
                self.stats.not_via_communicator += 1;
                tracing::debug!(%peer, source = %src, code = %header.command_code, communicator = %comm,
                    "datagram from another subsystem dropped: not through the communicator");
                return;
            }
        }
        // Learn where that node is (another subsystem's node is reached through the
        // communicator when there is one).
        if !(mine || foreign && self.config.communicator.is_some()) {
            self.peers.insert((src.subsystem, src.node), peer);
        }
        // A message of an external component is routed like one of a built-in component.
        let origin = if mine { Origin::Local } else { Origin::Network };
        if header.data_flag == DataFlag::Single {
            // Straight from the datagram: copied only if it must wait in the queue.
            self.route_borrowed(header, body, origin);
        } else if let Some((header, body)) = self.reassembler.push(now, &header, body) {
            self.route(header, body, origin);
        }
        self.pump();
    }

    /// Hands back the bytes of a datagram taken with [`poll_transmit`](Self::poll_transmit)
    /// once it is sent, for reuse: a shell that does so routes without allocating.
    pub fn recycle(&mut self, mut bytes: Vec<u8>) {
        if self.pool.len() < POOL_BUFFERS && bytes.capacity() <= POOL_BUFFER_BYTES {
            bytes.clear();
            self.pool.push(bytes);
        }
    }

    /// An empty buffer from the pool (a new one when the pool is empty).
    fn buffer(&mut self) -> Vec<u8> {
        self.pool.pop().unwrap_or_default()
    }

    /// A datagram with this node's subsystem and node as its source: an external
    /// component (another process using this node's socket) unless the id belongs to
    /// the node manager or a built-in component, or the table is full.
    fn accept_external(&mut self, now: Instant, src: Address, peer: SocketAddr, via: Via) -> bool {
        if !src.is_valid()
            || src.component == 255
            || src.instance == 255
            || src == self.manager.address()
            || self.locals.contains(src)
        {
            return false;
        }
        if let Some(e) = self.external.get_mut(&src) {
            *e = (peer, now, via);
            return true;
        }
        if self.external.len() >= self.config.max_external {
            self.stats.external_refused += 1;
            return false;
        }
        tracing::info!(component = %src, %peer, "external component joined");
        self.checked_in.remove(&src);
        self.external.insert(src, (peer, now, via));
        self.manager.behaviour_mut().0.add_local(src);
        true
    }

    /// External components of this node and where they are.
    pub fn external(&self) -> impl Iterator<Item = (Address, SocketAddr)> + '_ {
        self.external.iter().map(|(a, (p, ..))| (*a, *p))
    }

    /// Time passed.
    pub fn handle_timeout(&mut self, now: Instant) {
        self.advance(now);
        self.reassembler.expire(self.now);
        let limit = self.config.external_timeout;
        let now = self.now;
        let gone: Vec<Address> = self
            .external
            .iter()
            .filter(|(_, (_, t, _))| now.saturating_duration_since(*t) >= limit)
            .map(|(a, _)| *a)
            .collect();
        // A check-in never followed by a packet gives its address back.
        self.checked_in
            .retain(|_, t| now.saturating_duration_since(*t) < limit * 2);
        for a in gone {
            self.external.remove(&a);
            self.stats.external_timed_out += 1;
            self.manager.behaviour_mut().0.remove_local(a);
            tracing::info!(component = %a, "external component timed out");
        }
        if self.manager.poll_timeout().is_some_and(|t| t <= self.now) {
            self.manager.handle_timeout(self.now);
        }
        self.locals.run_due(self.now);
        self.drain_communicator();
        self.pump();
    }

    /// Routes what this node's communicator received from its data links (bounded per
    /// wake-up).
    fn drain_communicator(&mut self) {
        let Some(comm) = self.config.communicator else {
            return;
        };
        if comm.node != self.config.node || comm.subsystem != self.config.subsystem {
            return;
        }
        let now = self.now;
        for _ in 0..MAX_LINK_PACKETS {
            let buf = self.buffer();
            let Some(e) = self.locals.endpoint_mut(comm) else {
                self.recycle(buf);
                return;
            };
            let packet = match e.gateway_recv(now, buf) {
                Ok(p) => p,
                Err(buf) => {
                    self.recycle(buf);
                    return;
                }
            };
            self.stats.from_communicator += 1;
            self.route_link_packet(comm, &packet);
            self.recycle(packet);
            self.pump();
        }
    }

    /// One packet from another subsystem, through the communicator `comm`.
    fn route_link_packet(&mut self, comm: Address, packet: &[u8]) {
        let (header, body) = match Framing::Raw.packet(packet) {
            Ok(p) => p,
            Err(e) => {
                self.stats.bad_packet += 1;
                tracing::debug!(communicator = %comm, "packet from a data link dropped: {e}");
                return;
            }
        };
        let src = header.source;
        if src.subsystem == self.config.subsystem {
            // Our own traffic looped back by a link.
            self.stats.from_self += 1;
            return;
        }
        if !src.is_valid() || src.subsystem == 255 || src.node == 255 {
            self.stats.bad_packet += 1;
            tracing::debug!(communicator = %comm, source = %src, code = %header.command_code,
                "packet from a data link dropped: bad source address");
            return;
        }
        if header.data_flag == DataFlag::Single {
            self.route_borrowed(header, body, Origin::Link);
        } else if let Some((header, body)) = self.reassembler.push(self.now, &header, body) {
            self.route(header, body, Origin::Link);
        }
    }

    /// Hands a message leaving the subsystem to the communicator `comm` on this node,
    /// packet by packet.
    fn send_gateway(&mut self, comm: Address, header: &Header, body: &[u8]) {
        if body.len() <= MAX_PACKET_BODY {
            let mut bytes = self.buffer();
            match Framing::Raw.write_packet(&mut bytes, header, body) {
                Ok(()) => self.gateway_packet(comm, header, &bytes),
                Err(e) => {
                    self.stats.encode_errors += 1;
                    tracing::warn!(code = %header.command_code, destination = %header.destination, "not sent: {e}");
                }
            }
            self.recycle(bytes);
            return;
        }
        match split(header, body) {
            Ok(packets) => {
                for p in &packets {
                    self.gateway_packet(comm, header, p);
                }
            }
            Err(e) => {
                self.stats.encode_errors += 1;
                tracing::warn!(code = %header.command_code, destination = %header.destination, "not sent: {e}");
            }
        }
    }

    fn gateway_packet(&mut self, comm: Address, header: &Header, packet: &[u8]) {
        let now = self.now;
        let taken = self
            .locals
            .endpoint_mut(comm)
            .is_some_and(|e| e.gateway_send(now, packet));
        if taken {
            self.stats.to_communicator += 1;
        } else {
            self.stats.no_such_component += 1;
            tracing::debug!(communicator = %comm, code = %header.command_code, destination = %header.destination,
                "not sent to another subsystem: the communicator is not a gateway on this node");
        }
    }

    /// A control datagram on OpenJAUS's component control socket (port 24627) from
    /// `peer` (docs/wire.md §8.5): check-in (an address for a component id: this node's
    /// subsystem and node, the lowest free instance), check-out, and lookups in the
    /// system tree; the answer goes back to `peer` through [`Via::ComponentControl`].
    /// Anything else is counted as a bad packet and dropped.
    pub fn handle_component_control(&mut self, now: Instant, peer: SocketAddr, datagram: &[u8]) {
        use super::oj::{matches_wildcard, Control};
        self.advance(now);
        self.stats.received += 1;
        let request = match Control::decode(datagram) {
            Ok(c) => c,
            Err(e) => {
                self.stats.bad_packet += 1;
                tracing::debug!(%peer, "OpenJAUS control datagram dropped: {e}");
                return;
            }
        };
        let tree = self.manager.behaviour().0.tree();
        let known = |a: Address| tree.components().contains(&a);
        let reply = match request {
            Control::CheckIn { component, .. } => {
                // Like OpenJAUS: no answer when the id is not a component's or no
                // instance is free.
                if component < 2 || component == 255 {
                    None
                } else {
                    let (ss, node) = (self.config.subsystem, self.config.node);
                    let free = (1..=254u8)
                        .map(|i| Address::new(ss, node, component, i))
                        .find(|a| {
                            !self.locals.contains(*a)
                                && !self.external.contains_key(a)
                                && !self.checked_in.contains_key(a)
                        });
                    free.map(|a| {
                        self.checked_in.insert(a, self.now);
                        tracing::info!(component = %a, %peer, "OpenJAUS component checked in");
                        Control::ReportAddress(a)
                    })
                }
            }
            Control::CheckOut(a) => {
                self.checked_in.remove(&a);
                if self.external.remove(&a).is_some() {
                    self.manager.behaviour_mut().0.remove_local(a);
                    tracing::info!(component = %a, "OpenJAUS component checked out");
                }
                None
            }
            Control::VerifyAddress(a) => Some(Control::AddressVerified(known(a))),
            Control::GetComponentAddressList { component } => Some(Control::ComponentAddressList(
                tree.components()
                    .into_iter()
                    .find(|a| a.component == component),
            )),
            Control::LookupAddress(pattern) => {
                let found = tree
                    .components()
                    .into_iter()
                    .find(|a| matches_wildcard(pattern, *a));
                Some(Control::LookupAddressResponse {
                    address: found.unwrap_or(pattern),
                    valid: found.is_some(),
                })
            }
            Control::LookupServiceAddress { code, output } => {
                let found = tree.components().into_iter().find(|a| {
                    tree.component(*a).is_some_and(|c| {
                        let list = if output { &c.outputs } else { &c.inputs };
                        list.contains(&code.0)
                    })
                });
                Some(Control::LookupServiceAddressResponse {
                    address: found.unwrap_or(Address::new(0, 0, 0, 0)),
                    found: found.is_some(),
                })
            }
            Control::ReadyCheck => Some(Control::ReportReady),
            // Answers are what a node manager sends, not what it takes.
            Control::ReportAddress(_)
            | Control::AddressVerified(_)
            | Control::ComponentAddressList(_)
            | Control::LookupAddressResponse { .. }
            | Control::LookupServiceAddressResponse { .. }
            | Control::ReportReady => {
                self.stats.bad_packet += 1;
                None
            }
        };
        if let Some(r) = reply {
            if self.outbox.len() < self.config.max_outbox {
                self.outbox.push_back(Datagram {
                    to: peer,
                    bytes: r.encode().to_vec(),
                    via: Via::ComponentControl,
                });
            } else {
                self.stats.outbox_full += 1;
            }
        }
    }

    /// A raw JAUS packet on OpenJAUS's component data socket (port 24629) from `peer`:
    /// a component of this node in another process (checked in, or any id this node
    /// does not host), which is registered at `peer` and routed like a built-in
    /// component; messages for it go back raw through [`Via::ComponentData`].
    pub fn handle_component_data(&mut self, now: Instant, peer: SocketAddr, datagram: &[u8]) {
        self.advance(now);
        self.stats.received += 1;
        let (header, body) = match Framing::Raw.packet(datagram) {
            Ok(p) => p,
            Err(e) => {
                self.stats.bad_packet += 1;
                tracing::debug!(%peer, "component datagram dropped: {e}");
                return;
            }
        };
        let src = header.source;
        let mine = src.subsystem == self.config.subsystem && src.node == self.config.node;
        if !mine || !self.accept_external(now, src, peer, Via::ComponentData) {
            self.stats.bad_packet += 1;
            return;
        }
        let Some((header, body)) = self.reassembler.message(now, &header, body) else {
            return;
        };
        self.route(header, body, Origin::Local);
        self.pump();
    }

    /// The next datagram to send.
    pub fn poll_transmit(&mut self) -> Option<Datagram> {
        let d = self.outbox.pop_front()?;
        self.stats.sent += 1;
        Some(d)
    }

    /// When [`handle_timeout`](Self::handle_timeout) must next be called.
    pub fn poll_timeout(&self) -> Option<Instant> {
        let t = [self.manager.poll_timeout(), self.locals.next_timeout()]
            .into_iter()
            .flatten()
            .min();
        let ext = self
            .external
            .values()
            .map(|(_, last, _)| *last + self.config.external_timeout)
            .min();
        [self.reassembler.next_timeout(), ext]
            .into_iter()
            .flatten()
            .fold(t, |acc, x| Some(acc.map_or(x, |a: Instant| a.min(x))))
    }

    fn advance(&mut self, now: Instant) {
        if now > self.now {
            self.now = now;
        }
    }

    /// Moves everything the components want to send, and delivers local messages,
    /// until nothing is left.
    fn pump(&mut self) {
        for _ in 0..MAX_LOCAL_ROUNDS {
            let mut out = std::mem::take(&mut self.transmits);
            loop {
                let buf = self.buffer();
                match Endpoint::poll_transmit_with(&mut self.manager, buf) {
                    Ok(t) => out.push(t),
                    Err(buf) => {
                        self.recycle(buf);
                        break;
                    }
                }
            }
            self.locals.drain_transmits_with(&mut out, &mut self.pool);
            for t in out.drain(..) {
                match t.body {
                    Ok(body) => self.route(t.header, body, Origin::Local),
                    Err(e) => {
                        self.stats.encode_errors += 1;
                        tracing::warn!(message = t.name, code = %t.header.command_code, source = %t.header.source, "not sent: {e}");
                    }
                }
            }
            self.transmits = out;
            let Some((h, body)) = self.local_queue.pop_front() else {
                if self.manager_gone() {
                    continue;
                }
                return;
            };
            self.deliver(&h, &body);
            self.recycle(body);
        }
        tracing::warn!("routing loop limit reached; the rest waits for the next event");
    }

    /// Tells local components about components that disappeared; true if any.
    fn manager_gone(&mut self) -> bool {
        let gone = self.manager.behaviour_mut().0.take_gone();
        for g in &gone {
            self.manager.forget(*g);
            self.locals.forget(*g);
        }
        !gone.is_empty()
    }

    fn is_here(&self, d: Address) -> bool {
        (d.subsystem == self.config.subsystem || d.subsystem == 255)
            && (d.node == self.config.node || d.node == 255)
    }

    /// Routes a message whose body the node owns (a component's, a reassembled one).
    fn route(&mut self, header: Header, body: Vec<u8>, origin: Origin) {
        if self.route_common(&header, &body, origin) && self.admitted(&header, &body, origin) {
            self.enqueue(header, body);
        } else {
            self.recycle(body);
        }
    }

    /// Routes a message read from a datagram: delivered from the datagram's bytes when
    /// nothing waits before it, copied into a pooled buffer only when it must wait.
    fn route_borrowed(&mut self, header: Header, body: &[u8], origin: Origin) {
        if self.route_common(&header, body, origin) && self.admitted(&header, body, origin) {
            if self.local_queue.is_empty() {
                self.deliver(&header, body);
            } else {
                let mut b = self.buffer();
                b.extend_from_slice(body);
                self.enqueue(header, b);
            }
        }
    }

    /// The node's policy on a message for a component here: messages from outside the
    /// node (other nodes, other subsystems, external components) are checked; a refused
    /// one is counted and its answers (Confirm Component Control, NAK) are sent.
    fn admitted(&mut self, header: &Header, body: &[u8], origin: Origin) -> bool {
        let Some(policy) = self.policy.as_mut() else {
            return true;
        };
        if origin == Origin::Local && !self.external.contains_key(&header.source) {
            return true;
        }
        match policy.check(self.now, header, body) {
            Verdict::Pass => true,
            Verdict::Refuse(answers) => {
                self.stats.policy_refused += 1;
                for (h, b) in answers {
                    // From the component the message was for: not checked again.
                    if self.route_common(&h, &b, Origin::Local) {
                        self.enqueue(h, b);
                    }
                }
                false
            }
        }
    }

    /// Sends a message on to the network when it leaves this node; true when it is for
    /// a component here.
    fn route_common(&mut self, header: &Header, body: &[u8], origin: Origin) -> bool {
        let d = header.destination;
        // One line per message at trace level; the fields are evaluated only when it is
        // enabled (`jaus -vvv`, `RUST_LOG=jaus::net=trace`).
        tracing::trace!(
            name = crate::MessageInfo::of(header.command_code).map_or("(not in this set)", |i| i.name),
            code = %header.command_code,
            source = %header.source,
            destination = %d,
            size = body.len(),
            from = origin.name(),
            "route"
        );
        let here = self.is_here(d);
        let (ss, node) = (self.config.subsystem, self.config.node);
        let Some(comm) = self.config.communicator else {
            let only_here = d.subsystem == ss && d.node == node;
            let from_local = origin == Origin::Local;
            if from_local && !only_here {
                self.send_network(header, body, (d.subsystem, d.node));
            }
            if !here && !from_local {
                self.stats.not_for_us += 1;
            }
            return here;
        };
        // Through the communicator (Figure 5-1).
        let own_subsystem = d.subsystem == ss || d.subsystem == 255;
        let other_subsystem = d.subsystem != ss;
        let other_nodes = own_subsystem && d.node != node;
        let comm_here = comm.subsystem == ss && comm.node == node;
        match origin {
            Origin::Local => {
                if other_nodes {
                    self.send_network(header, body, (d.subsystem, d.node));
                }
                if other_subsystem {
                    if comm_here {
                        self.send_gateway(comm, header, body);
                    } else if !(other_nodes && d.subsystem == 255) {
                        // (A broadcast to every subsystem reached the communicator's
                        // node with the other nodes.)
                        self.send_network(header, body, (ss, comm.node));
                    }
                }
            }
            Origin::Network => {
                if other_subsystem && comm_here && header.source.subsystem == ss {
                    self.send_gateway(comm, header, body);
                } else if !here {
                    self.stats.not_for_us += 1;
                }
            }
            Origin::Link => {
                if other_nodes {
                    self.send_network(header, body, (d.subsystem, d.node));
                }
                if !own_subsystem {
                    // Nothing passes between two other subsystems through this one.
                    self.stats.not_for_us += 1;
                }
            }
        }
        here
    }

    /// Queues a message for the components here (bounded; a drop is counted).
    fn enqueue(&mut self, header: Header, body: Vec<u8>) {
        if self.local_queue.len() >= self.config.max_outbox {
            self.stats.outbox_full += 1;
            self.recycle(body);
        } else {
            self.local_queue.push_back((header, body));
        }
    }

    fn deliver(&mut self, header: &Header, body: &[u8]) {
        let d = header.destination;
        let mut any = false;
        let now = self.now;
        if d.matches(&self.manager.address()) && header.source != self.manager.address() {
            self.manager.handle(now, header, body);
            any = true;
        }
        any |= self.locals.deliver(now, header, body);
        if self.external.is_empty() {
            if any {
                self.stats.delivered_local += 1;
            } else if d.component != 255 && d.instance != 255 {
                self.stats.no_such_component += 1;
            }
            return;
        }
        let targets: Vec<(SocketAddr, Via)> = self
            .external
            .iter()
            .filter(|(a, _)| d.matches(a) && header.source != **a)
            .map(|(_, (p, _, via))| (*p, *via))
            .collect();
        if !targets.is_empty() {
            any = true;
            match split(header, body) {
                Ok(packets) => {
                    for (to, via) in targets {
                        // OpenJAUS components take raw packets on their data socket.
                        let framing = match via {
                            Via::Network => self.config.framing,
                            _ => Framing::Raw,
                        };
                        for p in &packets {
                            if self.outbox.len() >= self.config.max_outbox {
                                self.stats.outbox_full += 1;
                                break;
                            }
                            self.outbox.push_back(Datagram {
                                to,
                                bytes: framing.encode(p),
                                via,
                            });
                        }
                    }
                }
                Err(_) => self.stats.encode_errors += 1,
            }
        }
        if any {
            self.stats.delivered_local += 1;
        } else if d.component != 255 && d.instance != 255 {
            self.stats.no_such_component += 1;
        }
    }

    /// Sends a message on the UDP interface toward node `hop` (subsystem, node): the
    /// destination's, or the communicator's node; 255 in either is a broadcast.
    fn send_network(&mut self, header: &Header, body: &[u8], hop: (u8, u8)) {
        let broadcast = hop.0 == 255 || hop.1 == 255;
        // The hot path: one packet to a node whose socket is known, framed into a pooled
        // buffer.
        if body.len() <= MAX_PACKET_BODY && !broadcast {
            if let Some(&to) = self.peers.get(&hop) {
                if self.outbox.len() >= self.config.max_outbox {
                    self.stats.outbox_full += 1;
                    return;
                }
                let mut bytes = self.buffer();
                match self.config.framing.write_packet(&mut bytes, header, body) {
                    Ok(()) => self.outbox.push_back(Datagram {
                        to,
                        bytes,
                        via: Via::Network,
                    }),
                    Err(e) => {
                        self.stats.encode_errors += 1;
                        tracing::warn!(code = %header.command_code, "not sent: {e}");
                        self.recycle(bytes);
                    }
                }
                return;
            }
        }
        let packets = match split(header, body) {
            Ok(p) => p,
            Err(e) => {
                self.stats.encode_errors += 1;
                tracing::warn!(code = %header.command_code, "not sent: {e}");
                return;
            }
        };
        let targets: Vec<SocketAddr> = if broadcast {
            let mut t: Vec<SocketAddr> = self.config.peers.clone();
            if let Some(group) = self.config.multicast {
                // The group reaches every node that listens; the configured peers may
                // be beyond it.
                t.insert(0, group);
                return self.queue(&t, &packets);
            }
            for p in self.peers.values() {
                if !t.contains(p) {
                    t.push(*p);
                }
            }
            t.sort();
            t
        } else if let Some(p) = self.peers.get(&hop) {
            vec![*p]
        } else {
            self.stats.flooded += 1;
            self.config.peers.clone()
        };
        self.queue(&targets, &packets);
    }

    /// Queues every packet for every target (bounded by `max_outbox`, drops counted).
    fn queue(&mut self, targets: &[SocketAddr], packets: &[Vec<u8>]) {
        for &to in targets {
            for p in packets {
                if self.outbox.len() >= self.config.max_outbox {
                    self.stats.outbox_full += 1;
                    return;
                }
                self.outbox.push_back(Datagram {
                    to,
                    bytes: self.config.framing.encode(p),
                    via: Via::Network,
                });
            }
        }
    }

    /// Clock of the node.
    pub fn now(&self) -> Instant {
        self.now
    }
}

impl Participant for Node {
    fn handle_datagram(&mut self, now: Instant, peer: SocketAddr, datagram: &[u8]) {
        Node::handle_datagram(self, now, peer, datagram);
    }

    fn handle_timeout(&mut self, now: Instant) {
        Node::handle_timeout(self, now);
    }

    fn poll_transmit(&mut self) -> Option<Datagram> {
        Node::poll_transmit(self)
    }

    fn recycle(&mut self, bytes: Vec<u8>) {
        Node::recycle(self, bytes);
    }

    fn poll_timeout(&self) -> Option<Instant> {
        Node::poll_timeout(self)
    }

    fn wall_clock(&mut self, now: Instant, utc: std::time::Duration) {
        self.manager.wall_clock(now, utc);
        self.locals.wall_clock(now, utc);
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}
