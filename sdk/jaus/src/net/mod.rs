//! The network layer: framing and multi-packet messages ([`framing`]), the node
//! manager and its system tree ([`manager`]), a sans-IO node that routes between its
//! components and the network ([`node`]), the seam to any datagram carrier
//! ([`Transport`]) with the one loop that drives a node over it ([`shell`]), and the
//! carriers: UDP for JUDP ([`udp`]), TCP for JTCP ([`tcp`]), serial lines for JSerial
//! (`serial`, on Linux), the two stream framings sans-IO in [`stream`], and
//! [`PeerUrl`] naming a peer on any of them (docs/wire.md §9.6). The `jaus-sim` crate
//! runs nodes on a simulated lossy network with a virtual clock.
//!
//! Two hosts drive components on a carrier, both [`Participant`]s: a [`Node`]
//! (its own node manager, routing for the node) and [`Attached`] (components in a
//! process of their own, joined to a node through its socket).
//!
//! [`as5669a`] is the transport of the SAE AS-4 JAUS Service Sets (JUDP version 2),
//! served beside RA 3.3 on the same socket by wrapping a host in an
//! [`as5669a::As4Mux`].

pub mod as5669a;
pub mod attached;
pub mod framing;
pub mod manager;
pub mod node;
pub mod oj;
mod peer_url;
pub mod policy;
pub mod reliable;
#[cfg(target_os = "linux")]
pub mod serial;
pub mod shell;
pub mod stream;
pub mod tcp;
mod transport;
pub mod udp;

use std::net::SocketAddr;
use std::time::Instant;

pub use attached::{Attached, AttachedConfig, AttachedStats};
pub use framing::{Framing, Reassembler, ReassemblyLimits};
pub use manager::{ManagerConfig, SystemTree};
pub use node::{Node, NodeConfig, NodeEvent};
pub use peer_url::{PeerUrl, DEFAULT_BAUD};
pub use policy::{Permission, Policy, Rule};
pub use transport::{Datagram, NetStats, PeerAddr, Transport, Via};

use crate::Address;

/// Something that lives on a datagram carrier, sans-IO: fed datagrams and timeouts, it
/// hands back datagrams to send and the next instant it wants to be woken. The shells
/// ([`shell::run`] over any [`Transport`], a simulated network) drive any of them the
/// same way. `A` is the carrier's peer address (a UDP socket address by default).
pub trait Participant<A: PeerAddr = SocketAddr>: std::fmt::Debug + Send + 'static {
    /// A datagram arrived from `peer`.
    fn handle_datagram(&mut self, now: Instant, peer: A, datagram: &[u8]);
    /// A datagram arrived from `peer` on socket `via` of the host. The default takes
    /// the carrier's ([`Via::Network`]) and drops the others: only a [`Node`] serves
    /// OpenJAUS's component sockets.
    fn handle_via(&mut self, now: Instant, via: Via, peer: A, datagram: &[u8]) {
        if via == Via::Network {
            self.handle_datagram(now, peer, datagram);
        }
    }
    /// Time passed.
    fn handle_timeout(&mut self, now: Instant);
    /// The next datagram to send.
    fn poll_transmit(&mut self) -> Option<Datagram<A>>;
    /// The bytes of a datagram from [`poll_transmit`](Self::poll_transmit), handed
    /// back once sent so that the host can reuse the buffer (the default drops it).
    fn recycle(&mut self, bytes: Vec<u8>) {
        drop(bytes);
    }
    /// When [`handle_timeout`](Self::handle_timeout) must next be called.
    fn poll_timeout(&self) -> Option<Instant>;
    /// The wall clock from the shell: UTC (since 1970-01-01) at `now`, for components
    /// whose clock nobody set (see `jaus::component::Component::wall_clock`). Ignored
    /// by default.
    fn wall_clock(&mut self, now: Instant, utc: std::time::Duration) {
        let _ = (now, utc);
    }
    /// For downcasting to the concrete host.
    fn as_any(&self) -> &dyn std::any::Any;
    /// For downcasting to the concrete host.
    fn as_any_mut(&mut self) -> &mut dyn std::any::Any;
}

/// Why a component could not be added to a host.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum NetError {
    /// Its address is on another subsystem or node, or uses an id no component may
    /// have (0, 255, or 1: the node manager's).
    #[error("component {component} cannot join node {subsystem}.{node}: it is on another subsystem or node, or its id is reserved (0, 255, or 1 for the node manager)")]
    NotOnThisNode {
        /// The component's address.
        component: Address,
        /// The node's subsystem.
        subsystem: u8,
        /// The node's id.
        node: u8,
    },
    /// A component with that address is already there.
    #[error("component {0} is already on this node")]
    Duplicate(Address),
}

impl NetError {
    /// Whether a component at `a` may join the node `subsystem.node` whose components
    /// already include it (`taken`) or not: the rule both hosts, [`Node`] and
    /// [`Attached`], apply.
    pub(crate) fn check_join(
        a: Address,
        subsystem: u8,
        node: u8,
        taken: bool,
    ) -> Result<(), NetError> {
        if a.subsystem != subsystem || a.node != node || !a.is_valid() || a.component == 1 {
            return Err(NetError::NotOnThisNode {
                component: a,
                subsystem,
                node,
            });
        }
        if taken {
            return Err(NetError::Duplicate(a));
        }
        Ok(())
    }
}
