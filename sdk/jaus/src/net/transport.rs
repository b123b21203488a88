//! The seam between a node and the carrier of its datagrams. A node is sans-IO and
//! generic over its peers' address type ([`PeerAddr`]); a [`Transport`] moves the bytes:
//! UDP sockets ([`udp::UdpTransport`](super::udp::UdpTransport)), a serial bus, a radio
//! modem's packet interface, an in-memory pipe in a test. The routing never sees which.
//! What crosses the seam: [`Datagram`]s, each with the socket ([`Via`]) it uses; what a
//! node counts of them and of their routing: [`NetStats`].

use std::net::SocketAddr;
use std::time::Duration;

/// The address of a peer on a carrier: a UDP socket address, a drop on a serial bus, a
/// radio id. Anything small, comparable, hashable and printable is one.
pub trait PeerAddr:
    Copy + Eq + Ord + std::hash::Hash + std::fmt::Debug + std::fmt::Display + Send + Sync + 'static
{
}

impl<T> PeerAddr for T where
    T: Copy
        + Eq
        + Ord
        + std::hash::Hash
        + std::fmt::Debug
        + std::fmt::Display
        + Send
        + Sync
        + 'static
{
}

/// A datagram carrier for a node, driven by [`shell::run`](super::shell::run).
///
/// A carrier with one socket hands every datagram with [`Via::Network`]; a host that
/// also serves OpenJAUS's component sockets says which socket each came in on.
pub trait Transport {
    /// How the carrier names a peer.
    type Addr: PeerAddr;

    /// Waits at most `wait` for datagrams and hands each one to `on` (the socket it came
    /// in on, its sender, its bytes); returns after handing at least one, or when
    /// `wait` passed with none. An error ends the shell.
    fn recv<F: FnMut(Via, Self::Addr, &[u8])>(
        &mut self,
        wait: Duration,
        on: F,
    ) -> std::io::Result<()>;

    /// Sends one datagram, through socket `d.via` when the carrier has several. An
    /// error is logged by the shell and the datagram is dropped.
    fn send(&mut self, d: &Datagram<Self::Addr>) -> std::io::Result<()>;

    /// Sends `ds` in order and tells `done` the outcome of each (its index in `ds`),
    /// in as few system calls as the carrier can (`sendmmsg` for UDP on Linux). The
    /// default sends them one by one with [`send`](Self::send).
    fn send_all(
        &mut self,
        ds: &[Datagram<Self::Addr>],
        mut done: impl FnMut(usize, std::io::Result<()>),
    ) {
        for (i, d) in ds.iter().enumerate() {
            done(i, self.send(d));
        }
    }

    /// What the carrier is bound to, for the shell's first log line.
    fn describe(&self) -> String;
}

/// A datagram to send.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Datagram<A = SocketAddr> {
    /// The peer.
    pub to: A,
    /// Framed bytes.
    pub bytes: Vec<u8>,
    /// The socket it leaves from ([`Via::Network`] on a carrier that has only one).
    pub via: Via,
}

/// Which socket of a node a datagram leaves from: the network interface, or one of the
/// two sockets of OpenJAUS's local component interface ([`oj`](crate::net::oj)), which a
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
    /// ([`NodeConfig::communicator`](super::NodeConfig::communicator)).
    pub to_communicator: u64,
    /// Packets this node's communicator received from its data links.
    pub from_communicator: u64,
    /// Dropped: a datagram from another subsystem that did not come through the
    /// subsystem's communicator.
    pub not_via_communicator: u64,
    /// Messages refused by the node's policy ([`NodeConfig::policy`](super::NodeConfig::policy); per rule in
    /// [`Node::policy`](super::Node::policy)).
    pub policy_refused: u64,
    /// Dropped: a message for a companion component found its owner's event queue
    /// full ([`Node::poll_event`](super::Node::poll_event) not drained).
    pub companion_queue_full: u64,
}
