//! The seam between a node and the carrier of its datagrams. A node is sans-IO and
//! generic over its peers' address type ([`PeerAddr`]); a [`Transport`] moves the bytes:
//! UDP sockets ([`udp::UdpTransport`](super::udp::UdpTransport)), a serial bus, a radio
//! modem's packet interface, an in-memory pipe in a test. The routing never sees which.

use std::time::Duration;

use super::Datagram;
use super::Via;

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

    /// What the carrier is bound to, for the shell's first log line.
    fn describe(&self) -> String;
}
