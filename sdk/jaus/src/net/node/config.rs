//! A node's settings (its counters, [`NetStats`](crate::net::NetStats), are beside the
//! transport).

use std::net::SocketAddr;

use super::super::framing::{Framing, ReassemblyLimits};
use super::super::manager::ManagerConfig;
use super::super::PeerAddr;
use crate::component::Config;
use crate::Address;

/// Settings of a node.
#[derive(Debug, Clone)]
pub struct NodeConfig<A: PeerAddr = SocketAddr> {
    /// Subsystem id (1-254). Default 1.
    pub subsystem: u8,
    /// Node id (1-254). Default 1.
    pub node: u8,
    /// Node manager settings (names, heartbeat, node timeout; defaults there).
    pub manager: ManagerConfig,
    /// Framing of the node's datagrams. Default JUDP.
    pub framing: Framing,
    /// Peers always sent broadcasts and messages to nodes not yet located. Default
    /// none.
    pub peers: Vec<A>,
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
    pub multicast: Option<A>,
    /// The subsystem's Communicator (Part 1 §5.2.1 and Figure 5-1: the single point of
    /// entry into the subsystem), on this node or another node of the subsystem.
    /// When set, every message for another subsystem goes through it: on this node it
    /// is handed, packet by packet, to the communicator's endpoint
    /// ([`Endpoint::gateway_send`](crate::component::Endpoint::gateway_send), e.g. `jaus::stock::communicator::CommunicatorEndpoint`)
    /// instead of to a UDP peer, and the packets it receives from its data links are
    /// routed as if received (to the components here and the other nodes of the
    /// subsystem); on another node, such messages are sent to that node. Datagrams on
    /// the UDP interface from other subsystems are then dropped (counted in
    /// [`NetStats::not_via_communicator`](crate::net::NetStats::not_via_communicator))
    /// unless a node relays them from its communicator. Default `None`: other
    /// subsystems are reached over UDP like nodes.
    pub communicator: Option<Address>,
    /// Who may command the components here, take control of them and with what
    /// authority ([`Policy`](crate::net::policy::Policy)), checked before a message from
    /// outside the node reaches a component. Default `None`: open, as RA 3.3 is.
    pub policy: Option<crate::net::policy::Policy>,
    /// Commands that arrive ([`reliable`](crate::net::reliable)): when set, a command
    /// (a message of the Command class) that a component here sends to one component
    /// of another node asks for an acknowledgement and is resent with backoff until it
    /// is acknowledged or refused, or the policy's attempts run out; each ends as a
    /// [`Delivery`](crate::net::reliable::Delivery) ([`Node::poll_delivery`](super::Node::poll_delivery)),
    /// also handed to the component that sent it
    /// ([`Endpoint::settled`](crate::component::Endpoint::settled): the stock Mission
    /// Spooler and the AS-4 gateway act on it). Set-point streams a component declares
    /// with [`Node::send_once`](super::Node::send_once) go once.
    /// A peer that never acknowledges (OpenJAUS 3.3's components) is learnt and then
    /// sent to once. Messages asking for an acknowledgement themselves (`jaus send`,
    /// the Python client) are tracked the same way. Meant for nodes that send
    /// commands (an operator, a spooler), not for streams of set-points, where a newer
    /// value replaces a lost one. Default `None`: sent once. Whatever this says, a
    /// retransmitted message that arrives is carried out once and its answer repeated.
    pub reliable: Option<crate::net::reliable::RetryPolicy>,
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
/// assert!(n.reliable.is_none());
/// ```
impl Default for NodeConfig<SocketAddr> {
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
            reliable: None,
        }
    }
}

impl<A: PeerAddr> NodeConfig<A> {
    /// The same settings on another carrier: `peers` and `multicast` are addresses of
    /// that carrier ([`PeerAddr`]); everything else is kept.
    ///
    /// ```
    /// // A node on a serial bus whose drops have one-byte addresses.
    /// let c = jaus::net::NodeConfig::default().with_peers(vec![2u8, 3], None);
    /// assert_eq!((c.subsystem, c.peers.len()), (1, 2));
    /// ```
    pub fn with_peers<B: PeerAddr>(self, peers: Vec<B>, multicast: Option<B>) -> NodeConfig<B> {
        NodeConfig {
            subsystem: self.subsystem,
            node: self.node,
            manager: self.manager,
            framing: self.framing,
            peers,
            reassembly: self.reassembly,
            max_outbox: self.max_outbox,
            component: self.component,
            max_external: self.max_external,
            external_timeout: self.external_timeout,
            multicast,
            communicator: self.communicator,
            policy: self.policy,
            reliable: self.reliable,
        }
    }
}
