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
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use bytes::Bytes;
use jaus::stock::communicator::{DataLink, LinkError};
use tokio::sync::{mpsc, oneshot};

use crate::driver::{Carrier, Shared};
use crate::keys::fingerprint;
pub use crate::settings::{QuicLinkConfig, QuicLinkError, QuicLinkStats, Role, MAX_MTU};

/// How long dropping a link waits for its thread to stop.
pub const STOP_BOUND: Duration = Duration::from_secs(2);

/// After [`LinkError::Busy`], the outgoing queue is offered frames again this much
/// later.
const BUSY_RETRY: Duration = Duration::from_millis(1);

impl QuicLinkConfig {
    /// Checks the settings and builds the QUIC and TLS configurations, without binding
    /// anything (what [`QuicLink::bind`] does first; a node file's loader calls it to
    /// report a bad key before starting).
    pub fn check(&self) -> Result<Role, QuicLinkError> {
        crate::driver::Setup::new(self, Arc::new(AtomicU64::new(0))).map(|s| s.role)
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
