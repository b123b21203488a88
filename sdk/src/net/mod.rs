//! The network layer: UDP framing and multi-packet messages ([`framing`]), the node
//! manager and its system tree ([`manager`]), a sans-IO node that routes between its
//! components and the network ([`node`]) and a thin blocking UDP shell ([`udp`]). The
//! `jaus-sim` crate runs nodes on a simulated lossy network with a virtual clock.

pub mod framing;
pub mod manager;
pub mod node;
pub mod udp;

pub use framing::{Framing, Reassembler, ReassemblyLimits};
pub use manager::{ManagerConfig, SystemTree};
pub use node::{Datagram, NetStats, Node, NodeConfig};
