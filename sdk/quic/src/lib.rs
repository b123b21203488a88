//! # jaus-quic — authenticated, encrypted Communicator data links over QUIC
//!
//! A JAUS subsystem's Communicator reaches other subsystems over data links
//! ([`jaus::stock::communicator::DataLink`]). The SDK's
//! [`UdpLink`](jaus::net::udp::link::UdpLink) sends each JAUS packet as a plain UDP
//! datagram: anyone on the path reads it, and anyone who can send to the link's socket
//! from the far end's address is believed. This crate's [`QuicLink`] carries the same
//! frames inside one QUIC connection (TLS 1.3) whose two ends authenticate each other by
//! pinned certificates, with no certificate authority:
//!
//! * [`keys`]: a node's identity, a self-signed ECDSA P-256 certificate and its key, as
//!   two PEM files (`jaus keygen NAME`), and certificate fingerprints;
//! * [`pin`]: the rustls verifiers that accept only the far end's certificate, and the
//!   TLS configurations of the two ends;
//! * [`link`]: [`QuicLink`] itself: datagrams for the packets that fit, a stream per
//!   larger packet, roles agreed from the certificates, reconnection, bounded queues to
//!   a thread of its own, counters.
//!
//! ```
//! use std::time::{Duration, Instant};
//! use jaus::stock::communicator::DataLink;
//! use jaus_quic::keys::Identity;
//! use jaus_quic::link::{QuicLink, QuicLinkConfig};
//!
//! let (a, b) = (Identity::generate("a").unwrap(), Identity::generate("b").unwrap());
//! let port = |p| std::net::SocketAddr::from(([127, 0, 0, 1], p));
//! // Two free ports (the OS's choice, then released).
//! let free = || std::net::UdpSocket::bind(port(0)).unwrap().local_addr().unwrap().port();
//! let (pa, pb) = (free(), free());
//! let mut la = QuicLink::bind(QuicLinkConfig::new(1, port(pa), port(pb), a.clone(), b.cert.clone())).unwrap();
//! let mut lb = QuicLink::bind(QuicLinkConfig::new(1, port(pb), port(pa), b, a.cert)).unwrap();
//! let end = Instant::now() + Duration::from_secs(10);
//! while !(la.is_up(Instant::now()) && lb.is_up(Instant::now())) && Instant::now() < end {
//!     std::thread::sleep(Duration::from_millis(5));
//! }
//! la.send(Instant::now(), &[7u8; 16]).unwrap();
//! let mut buf = Vec::new();
//! while !lb.recv(Instant::now(), &mut buf) && Instant::now() < end {
//!     std::thread::sleep(Duration::from_millis(1));
//! }
//! assert_eq!(buf, [7u8; 16]);
//! ```

#![warn(missing_docs)]

pub mod keys;
pub mod link;
pub mod pin;

mod driver;
mod settings;

pub use keys::{fingerprint, Identity};
pub use link::{QuicLink, QuicLinkConfig, QuicLinkError, QuicLinkStats, Role};

#[cfg(test)]
mod tests;
