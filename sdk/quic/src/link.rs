//! [`QuicLink`]: a Communicator data link ([`DataLink`]) over QUIC, authenticated and
//! encrypted, for links that cross a network nobody vouches for (a shared radio net, a
//! VPN-less internet path between a vehicle and its station).
//!
//! The wire: one QUIC connection (TLS 1.3, ALPN `jaus-link/1`) between the two
//! communicators' link sockets. Each end pins the other's certificate
//! ([`crate::pin`]); a far end presenting any other certificate never gets a
//! connection, and the refusal is counted ([`QuicLinkStats::handshakes_refused`]).
//! Every frame (one JAUS packet, header and body, as `Framing::Raw` writes it) goes as
//! one QUIC datagram (RFC 9221: unreliable and unordered, like the UDP JAUS expects);
//! a frame larger than the connection's current datagram limit
//! (`quinn::Connection::max_datagram_size`, about 1,150 to 1,400 bytes, while JAUS
//! packets reach 4,096) goes alone on a unidirectional stream of its own (reliable,
//! and independent of the other frames: no head-of-line blocking), counted apart.
//!
//! Roles, without a setting: the end whose certificate's fingerprint
//! ([`crate::keys::fingerprint`]) is the smaller connects to [`QuicLinkConfig::peer`]
//! and reconnects after a loss (backoff from [`QuicLinkConfig::reconnect_min`],
//! doubling to [`QuicLinkConfig::reconnect_max`]); the other accepts on
//! [`QuicLinkConfig::bind`] from any address, the certificate being what
//! authenticates, and takes a newer authenticated connection in place of the current
//! one (the far end restarted). Both ends compare the same two certificates, so they
//! agree.
//!
//! Up and down: the link is up while its QUIC connection is established and it is
//! powered. QUIC keep-alives go every [`QuicLinkConfig::keepalive`]; the connection is
//! lost after [`QuicLinkConfig::silence`] without anything from the far end (the QUIC
//! idle timeout), or at once when the far end closes it.
//!
//! Threads and bounds: the [`DataLink`] methods are called from the node's thread and
//! never block. quinn runs on a single-threaded tokio runtime on one thread owned by
//! the link (`jaus-quic-link-ID`), joined within 2 s when the link is dropped. Frames
//! cross between the two through two bounded queues of [`QuicLinkConfig::queue`]
//! frames: a full outgoing queue makes [`DataLink::send`] answer
//! [`LinkError::Busy`] (the Communicator keeps the frame and offers it again at
//! [`DataLink::ready_at`]), a full incoming queue drops the frame received, counted.
//! A frame longer than [`QuicLinkConfig::mtu`] is refused on the way out and dropped on
//! the way in, counted. Nothing received can make it panic.
//!
//! Nothing wakes the node's thread when a frame arrives: [`DataLink::poll_timeout`]
//! asks for a wake-up [`QuicLinkConfig::poll`] after the incoming queue was last read
//! to the end, while the link is up or frames wait, as
//! [`UdpLink`](jaus::net::udp::link::UdpLink) does for its socket.

use std::net::SocketAddr;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use bytes::Bytes;
use jaus::stock::communicator::{DataLink, LinkError};
use jaus::wire::HEADER_LEN;
use rustls::pki_types::CertificateDer;
use tokio::sync::{mpsc, oneshot};

use crate::keys::{fingerprint, Identity};

/// The largest frame a link may be set to carry, bytes (as a UDP datagram over IPv4).
pub const MAX_MTU: usize = 65_507;

/// How long dropping a link waits for its thread to stop.
pub const STOP_BOUND: Duration = Duration::from_secs(2);

/// After [`LinkError::Busy`], the outgoing queue is offered frames again this much
/// later.
const BUSY_RETRY: Duration = Duration::from_millis(1);

/// Settings of a [`QuicLink`].
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

    /// Checks the settings and builds the QUIC and TLS configurations, without binding
    /// anything (what [`QuicLink::bind`] does first; a node file's loader calls it to
    /// report a bad key before starting).
    pub fn check(&self) -> Result<Role, QuicLinkError> {
        crate::driver::Setup::new(self, Arc::new(AtomicU64::new(0))).map(|s| s.role)
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

/// Why a [`QuicLink`] could not be set up.
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

/// What a [`QuicLink`] counted.
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
    /// Sends answered [`LinkError::Busy`]: the outgoing queue was full.
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

/// How a frame crossed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Carrier {
    Datagram,
    Stream,
}

/// What the node's thread and the link's thread share.
#[derive(Debug, Default)]
pub(crate) struct Shared {
    /// A connection is established.
    pub(crate) up: AtomicBool,
    /// The counters (all but the refusals).
    pub(crate) stats: Mutex<QuicLinkStats>,
    /// Certificates refused by this end's verifier.
    pub(crate) refused: Arc<AtomicU64>,
}

impl Shared {
    /// Updates the counters.
    pub(crate) fn count(&self, f: impl FnOnce(&mut QuicLinkStats)) {
        f(&mut self.stats.lock().unwrap_or_else(|e| e.into_inner()));
    }
}

/// A [`DataLink`] over QUIC between two communicators that pin each other's
/// certificate (see the [module documentation](self) for the wire, roles, threads and
/// bounds).
#[derive(Debug)]
pub struct QuicLink {
    id: u8,
    mtu: usize,
    poll: Duration,
    role: Role,
    local: SocketAddr,
    shared: Arc<Shared>,
    outgoing: mpsc::Sender<Bytes>,
    incoming: mpsc::Receiver<(Carrier, Bytes)>,
    stop: Option<oneshot::Sender<()>>,
    thread: Option<JoinHandle<()>>,
    powered: bool,
    /// When the incoming queue was last read to the end.
    drained_at: Option<Instant>,
    /// When a send last found the outgoing queue full.
    busy_at: Option<Instant>,
}

impl QuicLink {
    /// A link with `config`: its socket bound, its thread started (connecting or
    /// accepting at once).
    pub fn bind(config: QuicLinkConfig) -> Result<Self, QuicLinkError> {
        let shared = Arc::new(Shared::default());
        let setup = crate::driver::Setup::new(&config, shared.refused.clone())?;
        let role = setup.role;
        let socket =
            std::net::UdpSocket::bind(config.bind).map_err(|source| QuicLinkError::Socket {
                id: config.id,
                bind: config.bind,
                source,
            })?;
        let (outgoing, out_rx) = mpsc::channel(config.queue.max(1));
        let (in_tx, incoming) = mpsc::channel(config.queue.max(1));
        let (stop, stop_rx) = oneshot::channel();
        let (thread, local) = crate::driver::start(
            setup,
            socket,
            crate::driver::Queues {
                outgoing: out_rx,
                incoming: in_tx,
                stop: stop_rx,
            },
            shared.clone(),
        )?;
        tracing::info!(
            link = config.id,
            %local,
            peer = %config.peer,
            ?role,
            me = %fingerprint(&config.identity.cert),
            pinned = %fingerprint(&config.peer_cert),
            "QUIC data link started"
        );
        Ok(Self {
            id: config.id,
            mtu: config.mtu,
            poll: config.poll,
            role,
            local,
            shared,
            outgoing,
            incoming,
            stop: Some(stop),
            thread: Some(thread),
            powered: true,
            drained_at: None,
            busy_at: None,
        })
    }

    /// The local address the socket is bound to (the port the OS chose for port 0).
    pub fn local_addr(&self) -> SocketAddr {
        self.local
    }

    /// Whether this end connects or accepts.
    pub fn role(&self) -> Role {
        self.role
    }

    /// Whether the QUIC connection is established now (whatever the power state).
    pub fn is_connected(&self) -> bool {
        self.shared.up.load(Ordering::Acquire)
    }

    /// The counters.
    pub fn stats(&self) -> QuicLinkStats {
        let mut s = *self.shared.stats.lock().unwrap_or_else(|e| e.into_inner());
        s.handshakes_refused = self.shared.refused.load(Ordering::Relaxed);
        s
    }
}

impl Drop for QuicLink {
    fn drop(&mut self) {
        if let Some(stop) = self.stop.take() {
            let _ = stop.send(());
        }
        if let Some(thread) = self.thread.take() {
            // A stuck thread is named in the log and left behind.
            let _ = jaus::net::udp::join_within(thread, STOP_BOUND);
        }
    }
}

impl DataLink for QuicLink {
    fn id(&self) -> u8 {
        self.id
    }

    fn send(&mut self, now: Instant, frame: &[u8]) -> Result<(), LinkError> {
        if !self.powered || !self.is_connected() {
            return Err(LinkError::Down);
        }
        if frame.len() > self.mtu {
            self.shared.count(|s| s.dropped_oversize_sent += 1);
            return Err(LinkError::TooLarge {
                len: frame.len(),
                max: self.mtu,
            });
        }
        match self.outgoing.try_send(Bytes::copy_from_slice(frame)) {
            Ok(()) => Ok(()),
            Err(mpsc::error::TrySendError::Full(_)) => {
                self.shared.count(|s| s.busy += 1);
                self.busy_at = Some(now);
                Err(LinkError::Busy)
            }
            Err(mpsc::error::TrySendError::Closed(_)) => {
                // The link's thread is gone (it never panics; a runtime that failed).
                self.shared.count(|s| s.send_errors += 1);
                Err(LinkError::Down)
            }
        }
    }

    fn recv(&mut self, now: Instant, buf: &mut Vec<u8>) -> bool {
        buf.clear();
        match self.incoming.try_recv() {
            Ok((carrier, frame)) => {
                buf.extend_from_slice(&frame);
                let n = frame.len() as u64;
                self.shared.count(|s| match carrier {
                    Carrier::Datagram => {
                        s.datagrams_received += 1;
                        s.datagram_bytes_received += n;
                    }
                    Carrier::Stream => {
                        s.streams_received += 1;
                        s.stream_bytes_received += n;
                    }
                });
                true
            }
            Err(_) => {
                self.drained_at = Some(now);
                false
            }
        }
    }

    fn is_up(&self, _now: Instant) -> bool {
        self.powered && self.is_connected()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        if self.is_connected() || !self.incoming.is_empty() {
            self.drained_at.map(|t| t + self.poll)
        } else {
            None
        }
    }

    fn ready_at(&self) -> Option<Instant> {
        self.busy_at.map(|t| t + BUSY_RETRY)
    }

    fn set_powered(&mut self, _now: Instant, on: bool) {
        // The connection stays (and its keep-alives): powered down, the link takes and
        // reports nothing, and the far end's communicator sees the silence.
        self.powered = on;
    }
}
