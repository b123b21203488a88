//! A [`QuicLink`](crate::link::QuicLink)'s settings, why one cannot be set up, its role
//! and its counters: what the link and its thread both read.

use std::net::SocketAddr;
use std::time::Duration;

use jaus::wire::HEADER_LEN;
use rustls::pki_types::CertificateDer;

use crate::keys::{fingerprint, Identity};

/// The largest frame a link may be set to carry, bytes (as a UDP datagram over IPv4).
pub const MAX_MTU: usize = 65_507;

/// Settings of a [`QuicLink`](crate::link::QuicLink).
///
/// ```
/// use std::time::Duration;
/// use jaus_quic::keys::Identity;
/// use jaus_quic::link::QuicLinkConfig;
/// let (me, far) = (Identity::generate("me").unwrap(), Identity::generate("far").unwrap());
/// let any = "127.0.0.1:0".parse().unwrap();
/// let c = QuicLinkConfig::new(1, any, any, me, far.cert);
/// assert_eq!((c.mtu, c.silence, c.keepalive), (4096, Duration::from_secs(3), Duration::from_secs(1)));
/// assert_eq!((c.reconnect_min, c.reconnect_max), (Duration::from_millis(100), Duration::from_secs(5)));
/// assert_eq!((c.queue, c.poll), (256, Duration::from_millis(10)));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct QuicLinkConfig {
    /// The link's id (Data Link ID in the communications messages).
    pub id: u8,
    /// The local UDP socket address the link binds (the accepting end's is the one the
    /// far end connects to).
    pub bind: SocketAddr,
    /// The far end's link socket: where the connecting end connects (the accepting end
    /// takes connections from any address).
    pub peer: SocketAddr,
    /// This end's certificate and private key.
    pub identity: Identity,
    /// The far end's certificate, the only one accepted.
    pub peer_cert: CertificateDer<'static>,
    /// The largest frame carried, bytes ([`HEADER_LEN`] to [`MAX_MTU`]). Default 4096:
    /// the largest JAUS packet.
    pub mtu: usize,
    /// The connection is lost after this long without anything from the far end (the
    /// QUIC idle timeout; also the longest a connection attempt waits). Default 3 s.
    pub silence: Duration,
    /// A QUIC keep-alive goes when nothing was sent for this long (less than
    /// `silence`). Default 1 s.
    pub keepalive: Duration,
    /// The connecting end waits this long before its first reconnection attempt, twice
    /// as long after each failed one. Default 100 ms.
    pub reconnect_min: Duration,
    /// The longest wait between reconnection attempts. Default 5 s.
    pub reconnect_max: Duration,
    /// Frames each of the two queues between the node's thread and the link's holds.
    /// Default 256.
    pub queue: usize,
    /// The incoming queue is read again at most this long after it was last read to the
    /// end. Default 10 ms.
    pub poll: Duration,
}

impl QuicLinkConfig {
    /// Link `id` bound to `bind`, its far end at `peer` presenting `peer_cert`, this end
    /// presenting `identity`, the other settings at their defaults.
    pub fn new(
        id: u8,
        bind: SocketAddr,
        peer: SocketAddr,
        identity: Identity,
        peer_cert: CertificateDer<'static>,
    ) -> Self {
        Self {
            id,
            bind,
            peer,
            identity,
            peer_cert,
            mtu: HEADER_LEN + jaus::net::framing::MAX_PACKET_BODY,
            silence: Duration::from_secs(3),
            keepalive: Duration::from_secs(1),
            reconnect_min: Duration::from_millis(100),
            reconnect_max: Duration::from_secs(5),
            queue: 256,
            poll: Duration::from_millis(10),
        }
    }

    /// This end's role: [`Role::Connect`] when its certificate's fingerprint is the
    /// smaller of the two; `None` when both ends have the same certificate.
    pub fn role(&self) -> Option<Role> {
        let (mine, theirs) = (
            fingerprint(&self.identity.cert),
            fingerprint(&self.peer_cert),
        );
        match mine.cmp(&theirs) {
            std::cmp::Ordering::Less => Some(Role::Connect),
            std::cmp::Ordering::Greater => Some(Role::Accept),
            std::cmp::Ordering::Equal => None,
        }
    }
}

/// Which end of the link opens the connection ([`QuicLinkConfig::role`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Connects to the far end, and reconnects.
    Connect,
    /// Accepts the far end's connection.
    Accept,
}

/// Why a [`QuicLink`](crate::link::QuicLink) could not be set up.
#[derive(Debug, thiserror::Error)]
pub enum QuicLinkError {
    /// The socket could not be bound or used.
    #[error("data link {id}: cannot use {bind}: {source}")]
    Socket {
        /// The link's id.
        id: u8,
        /// The address asked for.
        bind: SocketAddr,
        /// What the OS said.
        source: std::io::Error,
    },
    /// The MTU cannot carry a JAUS header, or is over [`MAX_MTU`].
    #[error("data link {id}: mtu {mtu} is not in {HEADER_LEN}..={MAX_MTU}")]
    Mtu {
        /// The link's id.
        id: u8,
        /// The MTU asked for.
        mtu: usize,
    },
    /// A time setting is out of range.
    #[error("data link {id}: {what}")]
    Timing {
        /// The link's id.
        id: u8,
        /// What is wrong.
        what: String,
    },
    /// Both ends would present the same certificate.
    #[error("data link {id}: the far end's certificate is this end's own (each end needs its own key: jaus keygen)")]
    SameCertificate {
        /// The link's id.
        id: u8,
    },
    /// The key or certificate cannot be used (e.g. the key is not the certificate's).
    #[error("data link {id}: certificate and key: {reason}")]
    Tls {
        /// The link's id.
        id: u8,
        /// What rustls or quinn said.
        reason: String,
    },
    /// The link's thread could not be started.
    #[error("data link {id}: cannot start its thread: {reason}")]
    Thread {
        /// The link's id.
        id: u8,
        /// What went wrong.
        reason: String,
    },
}

/// What a [`QuicLink`](crate::link::QuicLink) counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct QuicLinkStats {
    /// Frames sent as QUIC datagrams.
    pub datagrams_sent: u64,
    /// Bytes of those frames.
    pub datagram_bytes_sent: u64,
    /// Frames sent on streams of their own (larger than a datagram could carry).
    pub streams_sent: u64,
    /// Bytes of those frames.
    pub stream_bytes_sent: u64,
    /// Frames received as datagrams and handed to the node.
    pub datagrams_received: u64,
    /// Bytes of those frames.
    pub datagram_bytes_received: u64,
    /// Frames received on streams and handed to the node.
    pub streams_received: u64,
    /// Bytes of those frames.
    pub stream_bytes_received: u64,
    /// Frames refused for sending: longer than the MTU.
    pub dropped_oversize_sent: u64,
    /// Frames from the far end dropped: longer than the MTU.
    pub dropped_oversize_received: u64,
    /// Frames from the far end dropped: the incoming queue was full (the node did not
    /// read the link in time).
    pub dropped_queue_full: u64,
    /// Sends answered [`LinkError::Busy`](jaus::stock::communicator::LinkError::Busy): the outgoing queue was full.
    pub busy: u64,
    /// Frames lost on the way out: the connection failed or was lost while they
    /// waited or went.
    pub send_errors: u64,
    /// Handshakes completed (connections established).
    pub handshakes_ok: u64,
    /// Handshakes that did not complete: no answer, refused by either end, or broken.
    pub handshakes_failed: u64,
    /// Handshakes this end refused: the far end presented a certificate that is not
    /// the pinned one (wrong key). Counted in `handshakes_failed` too.
    pub handshakes_refused: u64,
    /// Connections established after the first one: the link came back up.
    pub reconnects: u64,
}

impl QuicLinkStats {
    /// Frames sent, datagrams and streams.
    pub fn frames_sent(&self) -> u64 {
        self.datagrams_sent + self.streams_sent
    }

    /// Bytes of the frames sent.
    pub fn bytes_sent(&self) -> u64 {
        self.datagram_bytes_sent + self.stream_bytes_sent
    }

    /// Frames received, datagrams and streams.
    pub fn frames_received(&self) -> u64 {
        self.datagrams_received + self.streams_received
    }

    /// Bytes of the frames received.
    pub fn bytes_received(&self) -> u64 {
        self.datagram_bytes_received + self.stream_bytes_received
    }
}
