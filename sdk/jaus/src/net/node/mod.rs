//! A node, sans-IO: its node manager and local components, routing between them and
//! one datagram carrier (UDP, a simulated network, a serial bus: anything whose
//! addresses are a [`PeerAddr`]). Inputs are `(now, peer, datagram)` and timeouts;
//! outputs are datagrams for peers and the next wake-up time; a shell
//! ([`shell::run`](super::shell::run) over a [`Transport`](super::Transport), or
//! `jaus-sim`'s network) does the I/O.
//!
//! Components in other processes join through the same carrier: a datagram whose source
//! is this node's subsystem and node (and not a built-in id) registers an external
//! component at the datagram's address; it is routed like a built-in component and
//! removed after [`NodeConfig::external_timeout`] of silence.
//!
//! The node is cut by job: `route` decides where a message goes (a value), `peers`
//! knows where the other nodes are, `external` keeps the components of other
//! processes, `companions` exchanges typed events with components its owner drives
//! beside it (the AS-4 gateway), `gateway` is the node's side of the subsystem's
//! Communicator,
//! `oj_server` serves OpenJAUS's component sockets, `queue` holds the buffer pool
//! and the outbox; this file applies the decisions.

mod acks;
mod companions;
mod config;
mod external;
mod gateway;
mod oj_server;
mod peers;
mod queue;
mod route;

use std::collections::{HashMap, VecDeque};
use std::net::SocketAddr;
use std::time::Instant;

pub use super::transport::NetStats;
pub use super::transport::{Datagram, Via};
pub use acks::{AckKey, MAX_STREAMS};
pub use companions::NodeEvent;
pub use config::NodeConfig;

use super::framing::{split, DatagramError, Reassembler, ReassemblyStats, MAX_PACKET_BODY};
use super::manager::{StockNodeManager, SystemTree};
use super::policy::{PolicyState, Verdict};
use super::reliable::{Receiver, Sender};
use super::{NetError, Participant, PeerAddr};
use crate::component::{Component, Endpoint, Endpoints, Outgoing};
use crate::components::node_manager;
use crate::wire::{DataFlag, Header};
use crate::Address;
use companions::Companions;
use external::{Externals, Heard};
use peers::{Peers, Targets};
use queue::{Outbox, Pool};
use route::{Origin, Scope};

/// The node manager component of a node, with the few things the node asks of its
/// stock behaviour (the system tree, the components here) in one place.
struct Manager(Component<node_manager::Dispatch<StockNodeManager>>);

impl Manager {
    fn stock(&self) -> &StockNodeManager {
        &self.0.behaviour().0
    }
    fn stock_mut(&mut self) -> &mut StockNodeManager {
        &mut self.0.behaviour_mut().0
    }
    fn address(&self) -> Address {
        self.0.address()
    }
    fn tree(&self) -> &SystemTree {
        self.stock().tree()
    }
    fn add_local(&mut self, a: Address) {
        self.stock_mut().add_local(a);
    }
    fn remove_local(&mut self, a: Address) {
        self.stock_mut().remove_local(a);
    }
}

/// A node: node manager, local components, one datagram carrier whose peers have
/// addresses of type `A` (a UDP socket address by default).
pub struct Node<A: PeerAddr = SocketAddr> {
    config: NodeConfig<A>,
    scope: Scope,
    now: Instant,
    manager: Manager,
    locals: Endpoints,
    /// Components its owner drives beside it ([`NodeEvent`]).
    companions: Companions,
    external: Externals<A>,
    peers: Peers<A>,
    reassembler: Reassembler,
    outbox: Outbox<A>,
    local_queue: VecDeque<(Header, Vec<u8>)>,
    pool: Pool,
    /// What the components want to send, collected before routing (kept for its
    /// capacity).
    transmits: Vec<Outgoing>,
    stats: NetStats,
    policy: Option<PolicyState>,
    /// Commands waiting for their acknowledgement ([`NodeConfig::reliable`]).
    sender: Sender<AckKey, Address, acks::Kept>,
    /// Messages that asked for one, to carry out their retransmissions once.
    receiver: Receiver<acks::SeenKey, Header>,
    /// The sequence number of the last command tracked.
    ack_sequence: u16,
    /// The component (local or companion) that sent each tracked command, to hand it
    /// the outcome; as many as the sender tracks at most.
    ack_sources: HashMap<AckKey, Address>,
    /// Outcomes for [`poll_delivery`](Self::poll_delivery) (bounded, oldest dropped and
    /// counted).
    outcomes: VecDeque<super::reliable::Delivery<AckKey>>,
    outcomes_dropped: u64,
    /// (component, command code) pairs sent once, never tracked: set-point streams
    /// ([`send_once`](Self::send_once)).
    streams: Vec<(Address, crate::CommandCode)>,
}

impl<A: PeerAddr> std::fmt::Debug for Node<A> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Node")
            .field("address", &self.manager.address())
            .field("locals", &self.locals.len())
            .field("peers", self.peers.located())
            .field("stats", &self.stats)
            .finish()
    }
}

/// Most local deliveries in one run of the routing loop (two local components that
/// answer each other forever cannot starve the node).
const MAX_LOCAL_ROUNDS: usize = 100_000;

impl<A: PeerAddr> Node<A> {
    /// A node starting at `now` with its node manager at `subsystem.node.1.1`.
    pub fn new(config: NodeConfig<A>, now: Instant) -> Self {
        let me = Address::new(config.subsystem, config.node, 1, 1);
        let stock = StockNodeManager::new(me, config.manager.clone());
        let manager = Manager(node_manager::component(
            me,
            stock,
            config.component.clone(),
            now,
        ));
        let policy = config.policy.clone().map(PolicyState::new);
        let retry = config.reliable.unwrap_or_default();
        Self {
            sender: Sender::new(retry),
            receiver: Receiver::new(&retry),
            ack_sequence: super::reliable::random_start(),
            ack_sources: HashMap::new(),
            outcomes: VecDeque::new(),
            outcomes_dropped: 0,
            streams: Vec::new(),
            reassembler: Reassembler::new(config.reassembly),
            scope: Scope {
                subsystem: config.subsystem,
                node: config.node,
                communicator: config.communicator,
            },
            now,
            manager,
            locals: Endpoints::default(),
            companions: Companions::default(),
            external: Externals::new(config.max_external, config.external_timeout),
            peers: Peers::new(config.peers.clone(), config.multicast),
            outbox: Outbox::new(config.max_outbox),
            local_queue: VecDeque::new(),
            pool: Pool::default(),
            transmits: Vec::new(),
            stats: NetStats::default(),
            policy,
            config,
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
        let taken = self.locals.contains(a);
        NetError::check_join(a, self.config.subsystem, self.config.node, taken)?;
        self.manager.add_local(a);
        self.locals.push(endpoint);
        Ok(a)
    }

    /// The system tree.
    pub fn tree(&self) -> &SystemTree {
        self.manager.tree()
    }

    /// Moves whenever the system tree may have changed (see
    /// [`StockNodeManager::tree_version`](super::manager::StockNodeManager::tree_version)).
    pub fn tree_version(&self) -> u64 {
        self.manager.stock().tree_version()
    }

    /// The runtime counters of the node manager and of every local component.
    pub fn component_stats(&self) -> impl Iterator<Item = (Address, crate::component::Stats)> + '_ {
        std::iter::once((self.manager.address(), self.manager.0.stats())).chain(self.locals.stats())
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
    pub fn peers(&self) -> &HashMap<(u8, u8), A> {
        self.peers.located()
    }

    /// The local component at `a`, as a `T`.
    pub fn get<T: 'static>(&self, a: Address) -> Option<&T> {
        self.locals.get(a)
    }

    /// The local component at `a`, as a mutable `T`.
    pub fn get_mut<T: 'static>(&mut self, a: Address) -> Option<&mut T> {
        self.locals.get_mut(a)
    }

    /// External components of this node and where they are.
    pub fn external(&self) -> impl Iterator<Item = (Address, A)> + '_ {
        self.external.iter()
    }

    /// Clock of the node.
    pub fn now(&self) -> Instant {
        self.now
    }

    /// Queues a message from a local address (as if that component sent it).
    pub fn send(&mut self, now: Instant, header: Header, body: Vec<u8>) {
        self.advance(now);
        self.route(header, body, Origin::Local);
        self.pump();
    }

    /// A datagram arrived from `peer`.
    pub fn handle_datagram(&mut self, now: Instant, peer: A, datagram: &[u8]) {
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
                && self.peers.get((self.config.subsystem, comm.node)) == Some(peer);
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
            self.peers.learn((src.subsystem, src.node), peer);
        }
        if !self.incoming(&header, body) {
            self.pump();
            return;
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

    /// A datagram arrived on socket `via` of the node (the carrier, or one of
    /// OpenJAUS's component sockets): the one entry point of a shell.
    pub fn handle_via(&mut self, now: Instant, via: Via, peer: A, datagram: &[u8]) {
        match via {
            Via::Network => self.handle_datagram(now, peer, datagram),
            Via::ComponentControl => self.handle_component_control(now, peer, datagram),
            Via::ComponentData => self.handle_component_data(now, peer, datagram),
        }
    }

    /// Hands back the bytes of a datagram taken with [`poll_transmit`](Self::poll_transmit)
    /// once it is sent, for reuse: a shell that does so routes without allocating.
    pub fn recycle(&mut self, bytes: Vec<u8>) {
        self.pool.give(bytes);
    }

    /// A datagram with this node's subsystem and node as its source: an external
    /// component (another process using this node's carrier) unless the id belongs to
    /// the node manager or a built-in component, or the table is full.
    fn accept_external(&mut self, now: Instant, src: Address, peer: A, via: Via) -> bool {
        if !src.is_valid()
            || src.component == 255
            || src.instance == 255
            || src == self.manager.address()
            || self.locals.contains(src)
            || self.companions.contains(src)
        {
            return false;
        }
        match self.external.heard(now, src, peer, via) {
            Heard::Known => true,
            Heard::Joined => {
                tracing::info!(component = %src, %peer, "external component joined");
                self.manager.add_local(src);
                true
            }
            Heard::Full => {
                self.stats.external_refused += 1;
                false
            }
        }
    }

    /// Time passed.
    pub fn handle_timeout(&mut self, now: Instant) {
        self.advance(now);
        self.reassembler.expire(self.now);
        for a in self.external.expire(self.now) {
            self.stats.external_timed_out += 1;
            self.manager.remove_local(a);
            tracing::info!(component = %a, "external component timed out");
        }
        if self.manager.0.poll_timeout().is_some_and(|t| t <= self.now) {
            self.manager.0.handle_timeout(self.now);
        }
        self.locals.run_due(self.now);
        self.drain_communicator();
        self.resend_due(self.now);
        self.pump();
    }

    /// The next datagram to send.
    pub fn poll_transmit(&mut self) -> Option<Datagram<A>> {
        let d = self.outbox.pop()?;
        self.stats.sent += 1;
        Some(d)
    }

    /// When [`handle_timeout`](Self::handle_timeout) must next be called.
    pub fn poll_timeout(&self) -> Option<Instant> {
        [
            self.manager.0.poll_timeout(),
            self.locals.next_timeout(),
            self.reassembler.next_timeout(),
            self.external.next_timeout(),
            self.sender.next_timeout(),
            // Events wait for the owner: it drains them after every call.
            self.companions.pending().then_some(self.now),
        ]
        .into_iter()
        .flatten()
        .min()
    }

    fn advance(&mut self, now: Instant) {
        if now > self.now {
            self.now = now;
        }
    }

    /// Moves everything the components want to send, and delivers local messages,
    /// until nothing is left.
    fn pump(&mut self) {
        self.settle_outcomes();
        for _ in 0..MAX_LOCAL_ROUNDS {
            let mut out = std::mem::take(&mut self.transmits);
            loop {
                let buf = self.pool.take();
                match Endpoint::poll_transmit_with(&mut self.manager.0, buf) {
                    Ok(t) => out.push(t),
                    Err(buf) => {
                        self.pool.give(buf);
                        break;
                    }
                }
            }
            self.locals
                .drain_transmits_with(&mut out, self.pool.buffers());
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
            self.pool.give(body);
        }
        tracing::warn!("routing loop limit reached; the rest waits for the next event");
    }

    /// Tells local components about components that disappeared; true if any.
    fn manager_gone(&mut self) -> bool {
        let gone = self.manager.stock_mut().take_gone();
        for g in &gone {
            self.manager.0.forget(*g);
            self.locals.forget(*g);
            self.forget_companions(*g);
        }
        !gone.is_empty()
    }

    /// Routes a message whose body the node owns (a component's, a reassembled one).
    fn route(&mut self, header: Header, body: Vec<u8>, origin: Origin) {
        if self.route_common(&header, &body, origin) && self.admitted(&header, &body, origin) {
            self.enqueue(header, body);
        } else {
            self.pool.give(body);
        }
    }

    /// Routes a message read from a datagram: delivered from the datagram's bytes when
    /// nothing waits before it, copied into a pooled buffer only when it must wait.
    fn route_borrowed(&mut self, header: Header, body: &[u8], origin: Origin) {
        if self.route_common(&header, body, origin) && self.admitted(&header, body, origin) {
            if self.local_queue.is_empty() {
                self.deliver(&header, body);
            } else {
                let mut b = self.pool.take();
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
        if origin == Origin::Local && !self.external.contains(&header.source) {
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

    /// Applies the routing [`Decision`](route::Decision) for a message: sends it on
    /// when it leaves this node; true when it is for a component here.
    fn route_common(&mut self, header: &Header, body: &[u8], origin: Origin) -> bool {
        // One line per message at trace level; the fields are evaluated only when it is
        // enabled (`jaus -vvv`, `RUST_LOG=jaus::net=trace`).
        tracing::trace!(
            name = crate::MessageInfo::of(header.command_code).map_or("(not in this set)", |i| i.name),
            code = %header.command_code,
            source = %header.source,
            destination = %header.destination,
            size = body.len(),
            from = origin.name(),
            "route"
        );
        if origin == Origin::Local {
            self.answer_given(header);
        }
        let decision = self.scope.decide(header.source, header.destination, origin);
        if let Some(hop) = decision.network {
            if let Some(header) = self.outgoing(header, body, origin) {
                self.send_network(&header, body, hop);
            }
        }
        if let Some(comm) = decision.gateway {
            self.send_gateway(comm, header, body);
        }
        if decision.not_for_us {
            self.stats.not_for_us += 1;
        }
        decision.here
    }

    /// Queues a message for the components here (bounded; a drop is counted).
    fn enqueue(&mut self, header: Header, body: Vec<u8>) {
        if self.local_queue.len() >= self.config.max_outbox {
            self.stats.outbox_full += 1;
            self.pool.give(body);
        } else {
            self.local_queue.push_back((header, body));
        }
    }

    fn deliver(&mut self, header: &Header, body: &[u8]) {
        let d = header.destination;
        let now = self.now;
        let mut any = false;
        if d.matches(&self.manager.address()) && header.source != self.manager.address() {
            self.manager.0.handle(now, header, body);
            any = true;
        }
        any |= self.locals.deliver(now, header, body);
        if !self.companions.is_empty() {
            any |= self.deliver_companions(header, body);
        }
        if !self.external.is_empty() {
            let targets = self.external.targets(d, header.source);
            if !targets.is_empty() {
                any = true;
                self.send_external(header, body, &targets);
            }
        }
        if any {
            self.stats.delivered_local += 1;
        } else if d.component != 255 && d.instance != 255 {
            self.stats.no_such_component += 1;
        }
    }

    /// Sends a message to external components (OpenJAUS's take raw packets on their
    /// data socket).
    fn send_external(&mut self, header: &Header, body: &[u8], targets: &[(A, Via)]) {
        let packets = match split(header, body) {
            Ok(p) => p,
            Err(_) => {
                self.stats.encode_errors += 1;
                return;
            }
        };
        for &(to, via) in targets {
            let framing = match via {
                Via::Network => self.config.framing,
                _ => super::Framing::Raw,
            };
            for p in &packets {
                let d = Datagram {
                    to,
                    bytes: framing.encode(p),
                    via,
                };
                if self.outbox.push(d).is_err() {
                    self.stats.outbox_full += 1;
                    break;
                }
            }
        }
    }

    /// Sends a message over the carrier toward node `hop` (subsystem, node): the
    /// destination's, or the communicator's node; 255 in either is a broadcast.
    fn send_network(&mut self, header: &Header, body: &[u8], hop: (u8, u8)) {
        let targets = self.peers.targets(hop);
        // The hot path: one packet to a node whose address is known, framed into a
        // pooled buffer.
        if let (Targets::One(to), true) = (&targets, body.len() <= MAX_PACKET_BODY) {
            if !self.outbox.has_room() {
                self.stats.outbox_full += 1;
                return;
            }
            let mut bytes = self.pool.take();
            match self.config.framing.write_packet(&mut bytes, header, body) {
                Ok(()) => {
                    let d = Datagram {
                        to: *to,
                        bytes,
                        via: Via::Network,
                    };
                    // Room was checked above.
                    let _ = self.outbox.push(d);
                }
                Err(e) => {
                    self.stats.encode_errors += 1;
                    tracing::warn!(code = %header.command_code, "not sent: {e}");
                    self.pool.give(bytes);
                }
            }
            return;
        }
        let packets = match split(header, body) {
            Ok(p) => p,
            Err(e) => {
                self.stats.encode_errors += 1;
                tracing::warn!(code = %header.command_code, "not sent: {e}");
                return;
            }
        };
        let to = match targets {
            Targets::One(p) => vec![p],
            Targets::Broadcast(t) => t,
            Targets::Flood(t) => {
                self.stats.flooded += 1;
                t
            }
        };
        'all: for to in to {
            for p in &packets {
                let d = Datagram {
                    to,
                    bytes: self.config.framing.encode(p),
                    via: Via::Network,
                };
                if self.outbox.push(d).is_err() {
                    self.stats.outbox_full += 1;
                    break 'all;
                }
            }
        }
    }
}

impl<A: PeerAddr> Participant<A> for Node<A> {
    fn handle_datagram(&mut self, now: Instant, peer: A, datagram: &[u8]) {
        Node::handle_datagram(self, now, peer, datagram);
    }

    fn handle_via(&mut self, now: Instant, via: Via, peer: A, datagram: &[u8]) {
        Node::handle_via(self, now, via, peer, datagram);
    }

    fn handle_timeout(&mut self, now: Instant) {
        Node::handle_timeout(self, now);
    }

    fn poll_transmit(&mut self) -> Option<Datagram<A>> {
        Node::poll_transmit(self)
    }

    fn recycle(&mut self, bytes: Vec<u8>) {
        Node::recycle(self, bytes);
    }

    fn poll_timeout(&self) -> Option<Instant> {
        Node::poll_timeout(self)
    }

    fn wall_clock(&mut self, now: Instant, utc: std::time::Duration) {
        self.manager.0.wall_clock(now, utc);
        self.locals.wall_clock(now, utc);
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}
