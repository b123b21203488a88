//! The thread of a [`QuicLink`](crate::link::QuicLink): a single-threaded tokio runtime
//! running quinn's endpoint, the connecting or accepting task, and the loop that moves
//! frames between the node's queues and the current connection.

use std::net::SocketAddr;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

use bytes::Bytes;
use quinn::crypto::rustls::{QuicClientConfig, QuicServerConfig};
use quinn::{Connection, ConnectionError, Endpoint, EndpointConfig, TransportConfig};
use tokio::sync::{mpsc, oneshot, Semaphore};

use crate::settings::{QuicLinkConfig, QuicLinkError, QuicLinkStats, Role, MAX_MTU};

/// The server name the connecting end asks for (certificates are pinned, not matched to
/// names).
const SERVER_NAME: &str = "jaus-link";

/// Streams (frames too large for a datagram) in flight on the way out at once; more
/// wait, and the outgoing queue fills behind them.
const STREAM_SENDS: usize = 32;

/// Streams the far end may have open towards this end at once.
const STREAMS_IN: u32 = 64;

/// Handshakes the accepting end runs at once; more incoming connections are refused.
const HANDSHAKES: usize = 8;

/// Bytes of datagrams buffered each way inside quinn.
const DATAGRAM_BUFFER: usize = 1 << 20;

/// Bytes the far end may have in flight on all its streams at once (each stream may
/// have its frame, at most the MTU): with [`DATAGRAM_BUFFER`] and the incoming queue,
/// what bounds the memory a far end can make this end hold.
const STREAM_BUFFER: u32 = 4 << 20;

/// How long a stopping link lets quinn send its closing packets.
const CLOSE_WAIT: Duration = Duration::from_millis(100);

/// What the accepting end writes on the first stream it opens on a connection, once
/// it has taken the connecting end's certificate. In TLS 1.3 the client's handshake
/// completes before the server has checked the client's certificate; the connecting end
/// counts the link up only when this has come.
const ACCEPTED: &[u8] = b"jaus-link accepted";

/// Application close codes.
const CLOSE_STOPPED: u32 = 0;
const CLOSE_REPLACED: u32 = 1;

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

/// A link's configuration turned into quinn's.
pub(crate) struct Setup {
    pub(crate) id: u8,
    pub(crate) role: Role,
    peer: SocketAddr,
    mtu: usize,
    /// The first and longest wait before reconnecting, and the silence.
    reconnect: (Duration, Duration, Duration),
    client: Option<quinn::ClientConfig>,
    server: Option<quinn::ServerConfig>,
}

impl Setup {
    /// Checks `c` and builds the QUIC and TLS configurations of its role, the
    /// certificates refused by this end counted in `refused`.
    pub(crate) fn new(c: &QuicLinkConfig, refused: Arc<AtomicU64>) -> Result<Self, QuicLinkError> {
        let id = c.id;
        if !(jaus::wire::HEADER_LEN..=MAX_MTU).contains(&c.mtu) {
            return Err(QuicLinkError::Mtu { id, mtu: c.mtu });
        }
        let timing = |what: String| QuicLinkError::Timing { id, what };
        if c.keepalive.is_zero() || c.keepalive >= c.silence {
            return Err(timing(format!(
                "keepalive {:?} must be above zero and below silence {:?}",
                c.keepalive, c.silence
            )));
        }
        if c.reconnect_min.is_zero() || c.reconnect_max < c.reconnect_min {
            return Err(timing(format!(
                "reconnect backoff {:?} to {:?}: the first must be above zero and not above the second",
                c.reconnect_min, c.reconnect_max
            )));
        }
        let idle = quinn::IdleTimeout::try_from(c.silence)
            .map_err(|_| timing(format!("silence {:?} is too long", c.silence)))?;
        let role = c.role().ok_or(QuicLinkError::SameCertificate { id })?;
        let tls = |e: &dyn std::fmt::Display| QuicLinkError::Tls {
            id,
            reason: e.to_string(),
        };
        let rustls_error = |e: rustls::Error| match e {
            rustls::Error::InconsistentKeys(_) => QuicLinkError::Tls {
                id,
                reason: "the private key is not the certificate's".into(),
            },
            e => tls(&e),
        };
        let mut transport = TransportConfig::default();
        transport
            .max_idle_timeout(Some(idle))
            .keep_alive_interval(Some(c.keepalive))
            .max_concurrent_bidi_streams(0u32.into())
            .max_concurrent_uni_streams(STREAMS_IN.into())
            // A frame's worth, and one byte more: a longer one shows as too long
            // rather than waiting for credit that never comes.
            .stream_receive_window((c.mtu as u32 + 1).into())
            .receive_window(STREAM_BUFFER.into())
            .datagram_receive_buffer_size(Some(DATAGRAM_BUFFER))
            .datagram_send_buffer_size(DATAGRAM_BUFFER);
        let transport = Arc::new(transport);
        let (mut client, mut server) = (None, None);
        match role {
            Role::Connect => {
                let t = crate::pin::client_config(&c.identity, &c.peer_cert, refused)
                    .map_err(rustls_error)?;
                let q = QuicClientConfig::try_from(t).map_err(|e| tls(&e))?;
                let mut cc = quinn::ClientConfig::new(Arc::new(q));
                cc.transport_config(transport);
                client = Some(cc);
            }
            Role::Accept => {
                let t = crate::pin::server_config(&c.identity, &c.peer_cert, refused)
                    .map_err(rustls_error)?;
                let q = QuicServerConfig::try_from(t).map_err(|e| tls(&e))?;
                let mut sc = quinn::ServerConfig::with_crypto(Arc::new(q));
                sc.transport_config(transport).max_incoming(HANDSHAKES * 2);
                server = Some(sc);
            }
        }
        Ok(Self {
            id,
            role,
            peer: c.peer,
            mtu: c.mtu,
            reconnect: (c.reconnect_min, c.reconnect_max, c.silence),
            client,
            server,
        })
    }
}

/// The link's ends of the queues, and its stop signal.
pub(crate) struct Queues {
    pub(crate) outgoing: mpsc::Receiver<Bytes>,
    pub(crate) incoming: mpsc::Sender<(Carrier, Bytes)>,
    pub(crate) stop: oneshot::Receiver<()>,
}

/// Starts the link's thread on `socket`; returns it and the socket's local address once
/// quinn's endpoint runs on it.
pub(crate) fn start(
    setup: Setup,
    socket: std::net::UdpSocket,
    queues: Queues,
    shared: Arc<Shared>,
) -> Result<(JoinHandle<()>, SocketAddr), QuicLinkError> {
    let id = setup.id;
    let bind = socket.local_addr().ok();
    let (ready_tx, ready_rx) = std::sync::mpsc::sync_channel(1);
    let thread = std::thread::Builder::new()
        .name(format!("jaus-quic-link-{id}"))
        .spawn(move || {
            let rt = match tokio::runtime::Builder::new_current_thread()
                .enable_io()
                .enable_time()
                .build()
            {
                Ok(rt) => rt,
                Err(e) => {
                    let _ = ready_tx.send(Err(e));
                    return;
                }
            };
            rt.block_on(async move {
                let endpoint = match Endpoint::new(
                    EndpointConfig::default(),
                    setup.server.clone(),
                    socket,
                    Arc::new(quinn::TokioRuntime),
                ) {
                    Ok(e) => e,
                    Err(e) => {
                        let _ = ready_tx.send(Err(e));
                        return;
                    }
                };
                let _ = ready_tx.send(endpoint.local_addr());
                let Queues {
                    outgoing,
                    incoming,
                    stop,
                } = queues;
                tokio::select! {
                    _ = stop => {}
                    () = run(setup, endpoint.clone(), outgoing, incoming, shared.clone()) => {}
                }
                shared.up.store(false, Ordering::Release);
                // Tell the far end at once rather than let it time out.
                endpoint.close(CLOSE_STOPPED.into(), b"link stopped");
                let _ = tokio::time::timeout(CLOSE_WAIT, endpoint.wait_idle()).await;
            });
        })
        .map_err(|e| QuicLinkError::Thread {
            id,
            reason: e.to_string(),
        })?;
    let socket_error = |source| QuicLinkError::Socket {
        id,
        bind: bind.unwrap_or_else(|| SocketAddr::from(([0, 0, 0, 0], 0))),
        source,
    };
    match ready_rx.recv() {
        Ok(Ok(local)) => Ok((thread, local)),
        Ok(Err(e)) => {
            let _ = thread.join();
            Err(socket_error(e))
        }
        Err(_) => Err(QuicLinkError::Thread {
            id,
            reason: "it ended before its endpoint ran".into(),
        }),
    }
}

/// The link's main loop: takes the connections the connecting or accepting task
/// establishes, and sends the node's frames on the current one.
async fn run(
    setup: Setup,
    endpoint: Endpoint,
    mut outgoing: mpsc::Receiver<Bytes>,
    incoming: mpsc::Sender<(Carrier, Bytes)>,
    shared: Arc<Shared>,
) {
    let id = setup.id;
    let (conn_tx, mut conn_rx) = mpsc::channel::<Connection>(4);
    match (setup.role, setup.client.clone()) {
        (Role::Connect, Some(client)) => {
            tokio::spawn(connect(
                endpoint.clone(),
                client,
                setup.peer,
                setup.reconnect,
                conn_tx,
                shared.clone(),
                id,
            ));
        }
        _ => {
            tokio::spawn(accept(endpoint.clone(), conn_tx, shared.clone(), id));
        }
    }
    let sends = Arc::new(Semaphore::new(STREAM_SENDS));
    let mut current: Option<Connection> = None;
    let mut ever_up = false;
    loop {
        tokio::select! {
            conn = conn_rx.recv() => {
                let Some(conn) = conn else { return };
                if let Some(old) = current.replace(conn.clone()) {
                    old.close(CLOSE_REPLACED.into(), b"replaced by a newer connection");
                }
                if ever_up {
                    shared.count(|s| s.reconnects += 1);
                }
                ever_up = true;
                shared.up.store(true, Ordering::Release);
                let remote = conn.remote_address();
                tracing::info!(link = id, %remote, "QUIC data link up");
                let (to, mtu) = (incoming.clone(), setup.mtu);
                tokio::spawn(read_datagrams(conn.clone(), to.clone(), shared.clone(), mtu));
                tokio::spawn(read_streams(conn, to, shared.clone(), mtu));
            }
            why = closed(current.as_ref()) => {
                current = None;
                shared.up.store(false, Ordering::Release);
                tracing::info!(link = id, "QUIC data link down: {why}");
            }
            frame = outgoing.recv() => {
                let Some(frame) = frame else { return };
                match &current {
                    Some(conn) => send(conn, frame, &sends, &shared).await,
                    // Taken just before the connection went: lost.
                    None => shared.count(|s| s.send_errors += 1),
                }
            }
        }
    }
}

/// When `conn` closes (never without one).
async fn closed(conn: Option<&Connection>) -> ConnectionError {
    match conn {
        Some(c) => c.closed().await,
        None => std::future::pending().await,
    }
}

/// Sends one frame: as a datagram if it fits, else on a stream of its own (started
/// here, finished by a task of its own; at most [`STREAM_SENDS`] at once).
async fn send(conn: &Connection, frame: Bytes, sends: &Arc<Semaphore>, shared: &Arc<Shared>) {
    let n = frame.len() as u64;
    if conn
        .max_datagram_size()
        .is_some_and(|max| frame.len() <= max)
    {
        match conn.send_datagram_wait(frame.clone()).await {
            Ok(()) => {
                shared.count(|s| {
                    s.datagrams_sent += 1;
                    s.datagram_bytes_sent += n;
                });
                return;
            }
            // The path's limit fell in between: a stream then.
            Err(quinn::SendDatagramError::TooLarge) => {}
            Err(e) => {
                shared.count(|s| s.send_errors += 1);
                tracing::debug!("frame not sent: {e}");
                return;
            }
        }
    }
    let Ok(permit) = sends.clone().acquire_owned().await else {
        return;
    };
    let (conn, shared) = (conn.clone(), shared.clone());
    tokio::spawn(async move {
        let _permit = permit;
        let sent = async {
            let mut stream = conn.open_uni().await.map_err(|e| e.to_string())?;
            stream.write_all(&frame).await.map_err(|e| e.to_string())?;
            stream.finish().map_err(|e| e.to_string())
        };
        match sent.await {
            Ok(()) => shared.count(|s| {
                s.streams_sent += 1;
                s.stream_bytes_sent += n;
            }),
            Err(e) => {
                shared.count(|s| s.send_errors += 1);
                tracing::debug!("frame not sent on its stream: {e}");
            }
        }
    });
}

/// Hands a frame received to the node's queue: dropped and counted when longer than
/// the MTU or when the queue is full.
fn deliver(
    to: &mpsc::Sender<(Carrier, Bytes)>,
    carrier: Carrier,
    frame: Bytes,
    mtu: usize,
    shared: &Shared,
) {
    if frame.len() > mtu {
        shared.count(|s| s.dropped_oversize_received += 1);
        return;
    }
    if let Err(mpsc::error::TrySendError::Full(_)) = to.try_send((carrier, frame)) {
        shared.count(|s| s.dropped_queue_full += 1);
    }
}

/// Reads the datagrams of `conn` until it closes.
async fn read_datagrams(
    conn: Connection,
    to: mpsc::Sender<(Carrier, Bytes)>,
    shared: Arc<Shared>,
    mtu: usize,
) {
    while let Ok(d) = conn.read_datagram().await {
        deliver(&to, Carrier::Datagram, d, mtu, &shared);
    }
}

/// Reads each stream the far end opens (one frame each, at most the MTU) until `conn`
/// closes.
async fn read_streams(
    conn: Connection,
    to: mpsc::Sender<(Carrier, Bytes)>,
    shared: Arc<Shared>,
    mtu: usize,
) {
    while let Ok(mut stream) = conn.accept_uni().await {
        let (to, shared) = (to.clone(), shared.clone());
        tokio::spawn(async move {
            match stream.read_to_end(mtu).await {
                Ok(frame) => deliver(&to, Carrier::Stream, frame.into(), mtu, &shared),
                Err(quinn::ReadToEndError::TooLong) => {
                    let _ = stream.stop(0u32.into());
                    shared.count(|s| s.dropped_oversize_received += 1);
                }
                Err(e) => tracing::debug!("stream not read: {e}"),
            }
        });
    }
}

/// The connecting end: connects to `peer`, waits for the far end's [`ACCEPTED`] (at most
/// `reconnect.2`, the silence), hands the connection over, waits for its loss, and
/// connects again, waiting `reconnect.0` after a loss and doubling the wait after each
/// failed attempt up to `reconnect.1`.
async fn connect(
    endpoint: Endpoint,
    client: quinn::ClientConfig,
    peer: SocketAddr,
    reconnect: (Duration, Duration, Duration),
    to: mpsc::Sender<Connection>,
    shared: Arc<Shared>,
    id: u8,
) {
    let (first, longest, silence) = reconnect;
    let mut wait = first;
    loop {
        let attempt = match endpoint.connect_with(client.clone(), peer, SERVER_NAME) {
            Ok(connecting) => connecting.await.map_err(|e| e.to_string()),
            Err(e) => Err(e.to_string()),
        };
        let attempt = match attempt {
            Ok(conn) => accepted(&conn, silence)
                .await
                .map(|()| conn)
                .map_err(|e| format!("not accepted: {e}")),
            Err(e) => Err(e),
        };
        match attempt {
            Ok(conn) => {
                shared.count(|s| s.handshakes_ok += 1);
                wait = first;
                if to.send(conn.clone()).await.is_err() {
                    return;
                }
                conn.closed().await;
            }
            Err(e) => {
                shared.count(|s| s.handshakes_failed += 1);
                tracing::debug!(link = id, %peer, "QUIC connection failed: {e}; again in {wait:?}");
                tokio::time::sleep(wait).await;
                wait = (wait * 2).min(longest);
                continue;
            }
        }
        tokio::time::sleep(wait).await;
    }
}

/// The accepting end: runs the handshake of every incoming connection (at most
/// [`HANDSHAKES`] at once) and hands over those that complete (the far end presented
/// the pinned certificate).
async fn accept(endpoint: Endpoint, to: mpsc::Sender<Connection>, shared: Arc<Shared>, id: u8) {
    let handshakes = Arc::new(Semaphore::new(HANDSHAKES));
    while let Some(incoming) = endpoint.accept().await {
        let Ok(permit) = handshakes.clone().try_acquire_owned() else {
            incoming.refuse();
            shared.count(|s| s.handshakes_failed += 1);
            continue;
        };
        let remote = incoming.remote_address();
        let (to, shared) = (to.clone(), shared.clone());
        tokio::spawn(async move {
            let _permit = permit;
            let handshake = match incoming.accept() {
                Ok(connecting) => connecting.await,
                Err(e) => Err(e),
            };
            let handshake = match handshake {
                Ok(conn) => accept_with(&conn)
                    .await
                    .map(|()| conn)
                    .map_err(|e| e.to_string()),
                Err(e) => Err(e.to_string()),
            };
            match handshake {
                Ok(conn) => {
                    shared.count(|s| s.handshakes_ok += 1);
                    let _ = to.send(conn).await;
                }
                Err(e) => {
                    shared.count(|s| s.handshakes_failed += 1);
                    tracing::debug!(link = id, %remote, "QUIC handshake failed: {e}");
                }
            }
        });
    }
}

/// The accepting end's [`ACCEPTED`], on the first stream it opens on `conn`.
async fn accept_with(conn: &Connection) -> Result<(), quinn::WriteError> {
    let mut stream = conn.open_uni().await?;
    stream.write_all(ACCEPTED).await?;
    Ok(stream.finish()?)
}

/// Waits (at most `limit`) for the far end's [`ACCEPTED`] on the first stream it opens
/// on `conn`.
async fn accepted(conn: &Connection, limit: Duration) -> Result<(), String> {
    let read = async {
        let mut stream = conn.accept_uni().await.map_err(|e| e.to_string())?;
        let got = stream
            .read_to_end(ACCEPTED.len())
            .await
            .map_err(|e| e.to_string())?;
        if got == ACCEPTED {
            Ok(())
        } else {
            Err("a first stream that is not the acceptance".to_string())
        }
    };
    match tokio::time::timeout(limit, read).await {
        Ok(r) => r,
        Err(_) => Err(format!("nothing within {limit:?}")),
    }
}
