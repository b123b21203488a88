//! TCP, the carrier of JTCP ([`stream::jtcp`](super::stream::jtcp)): a
//! [`Transport`] with peers named by socket address, so that a [`Node`](super::Node),
//! an [`As4Mux`](super::as5669a::As4Mux) or any other participant runs on it as on UDP.
//!
//! * **Listening**: connections accepted on [`TcpConfig::listen`] are the peers' to
//!   use; the node knows each by its remote address and its replies go back over it.
//! * **Dialing**: every [`TcpConfig::peers`] address is dialed at start and kept
//!   connected; any other destination the node sends to (and no accepted connection
//!   names) is dialed when first sent to and kept too. A connection that fails or ends
//!   is dialed again after a backoff doubling from [`TcpConfig::backoff_min`] to
//!   [`TcpConfig::backoff_max`] (back to the minimum once a connection carried a
//!   frame). Connecting runs on a short-lived thread per attempt, bounded by
//!   [`TcpConfig::connect_timeout`]; the loop itself never blocks on the network.
//! * **One version per connection**: JTCP sends the version byte once, so a
//!   connection carries RA 3.3 (version 1) or AS5669A (version 2), whichever went or
//!   came first. A datagram of the other version to a dialed peer gets a second
//!   connection; to an accepted connection it is dropped and counted
//!   ([`TcpStats::wrong_version`]). OPC ("JAUS01.0") datagrams have no JTCP form.
//! * **Bounded**: at most [`TcpConfig::max_connections`] connections and dial entries
//!   (more are refused), each with a send queue of [`TcpConfig::max_queue`] datagrams
//!   and [`TcpConfig::max_queue_bytes`]; a datagram over either bound is dropped and
//!   counted ([`TcpStats::queue_full`]).
//! * **A dead peer is noticed**: end of stream, a read or write error, a stream that
//!   does not parse, or a send queue that made no progress for [`TcpConfig::stall`]
//!   close the connection (and a dialed one is dialed again); on Linux the kernel's
//!   keep-alive probes ([`TcpConfig::keepalive`]) end a connection whose peer vanished
//!   silently.

use std::collections::{HashSet, VecDeque};
use std::io::ErrorKind;
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use super::stream::{Version, DEFAULT_MAX_FRAME};
use super::{Datagram, Transport, Via};

mod conn;
mod wait;

use conn::{Closed, Conn, Origin};

/// Settings of a [`TcpTransport`].
///
/// ```
/// let c = jaus::net::tcp::TcpConfig::default();
/// assert_eq!((c.max_connections, c.max_queue), (64, 256));
/// assert_eq!(c.backoff_max, std::time::Duration::from_secs(5));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TcpConfig {
    /// The listening address (`None`: dial only).
    pub listen: Option<SocketAddr>,
    /// Peers dialed at start and kept connected.
    pub peers: Vec<SocketAddr>,
    /// The first redial waits this long. Default 100 ms.
    pub backoff_min: Duration,
    /// Redials wait at most this long. Default 5 s.
    pub backoff_max: Duration,
    /// One connection attempt gives up after this. Default 3 s.
    pub connect_timeout: Duration,
    /// Most connections and most dialed addresses, each. Default 64.
    pub max_connections: usize,
    /// Most datagrams waiting per connection. Default 256.
    pub max_queue: usize,
    /// Most bytes waiting per connection. Default 1 MiB.
    pub max_queue_bytes: usize,
    /// A connection whose waiting data made no progress for this long is closed.
    /// Default 10 s.
    pub stall: Duration,
    /// TCP keep-alive: probes after this much idle time (Linux; `None`: off).
    /// Default 10 s.
    pub keepalive: Option<Duration>,
    /// Largest frame taken. Default [`DEFAULT_MAX_FRAME`].
    pub max_frame: usize,
}

impl Default for TcpConfig {
    fn default() -> Self {
        Self {
            listen: None,
            peers: Vec::new(),
            backoff_min: Duration::from_millis(100),
            backoff_max: Duration::from_secs(5),
            connect_timeout: Duration::from_secs(3),
            max_connections: 64,
            max_queue: 256,
            max_queue_bytes: 1 << 20,
            stall: Duration::from_secs(10),
            keepalive: Some(Duration::from_secs(10)),
            max_frame: DEFAULT_MAX_FRAME,
        }
    }
}

/// What a [`TcpTransport`] counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TcpStats {
    /// Connections accepted.
    pub accepted: u64,
    /// Connections dialed successfully.
    pub connected: u64,
    /// Dial attempts that failed.
    pub connect_failures: u64,
    /// Connections closed (the peer gone, an error, a bad stream, a stall).
    pub closed: u64,
    /// Of those: the peer's stream did not parse.
    pub bad_stream: u64,
    /// Of those: the peer stopped reading.
    pub stalled: u64,
    /// Connections or dials refused: over [`TcpConfig::max_connections`].
    pub refused: u64,
    /// Datagrams received.
    pub datagrams_received: u64,
    /// Bytes received.
    pub bytes_received: u64,
    /// Datagrams written whole.
    pub datagrams_sent: u64,
    /// Dropped: the connection's queue was full.
    pub queue_full: u64,
    /// Dropped: no connection to the destination (a redial waits its backoff, or an
    /// accepted connection is gone).
    pub no_connection: u64,
    /// Dropped: the connection to the destination carries the other version.
    pub wrong_version: u64,
    /// Dropped: not JUDP version 1 or 2, or malformed.
    pub not_carried: u64,
}

/// Where a dialed address stands.
#[derive(Debug)]
enum DialState {
    /// The next attempt is due then.
    Waiting(Instant),
    /// An attempt is under way on its thread.
    Connecting(mpsc::Receiver<std::io::Result<TcpStream>>),
    /// Connected (a connection with this dial's index is live).
    Up,
}

/// An address this transport keeps connected.
#[derive(Debug)]
struct Dial {
    addr: SocketAddr,
    /// The version its connection carries (`None`: not known yet).
    version: Option<Version>,
    state: DialState,
    backoff: Duration,
    /// Datagrams to send once connected (while the first attempt runs).
    pending: VecDeque<Vec<u8>>,
}

/// JTCP over TCP as a [`Transport`] (see the [module documentation](self)).
#[derive(Debug)]
pub struct TcpTransport {
    config: TcpConfig,
    listener: Option<TcpListener>,
    conns: Vec<(Conn, Option<usize>)>,
    dials: Vec<Dial>,
    /// Remote addresses of accepted connections (never dialed), the latest
    /// [`INBOUND_MEMORY`].
    inbound: HashSet<SocketAddr>,
    inbound_order: VecDeque<SocketAddr>,
    stats: TcpStats,
    buf: Vec<u8>,
}

/// How many remote addresses of accepted connections are remembered.
const INBOUND_MEMORY: usize = 1024;

/// Bytes read from one connection per wake-up before the others get their turn.
const READ_BUDGET: usize = 256 * 1024;

impl TcpTransport {
    /// Binds the listening socket (if any) and starts dialing the peers.
    pub fn new(config: TcpConfig) -> std::io::Result<Self> {
        let listener = match config.listen {
            Some(a) => {
                let l = TcpListener::bind(a)
                    .map_err(|e| std::io::Error::new(e.kind(), format!("tcp listen {a}: {e}")))?;
                l.set_nonblocking(true)?;
                Some(l)
            }
            None => None,
        };
        let now = Instant::now();
        let mut me = Self {
            dials: Vec::new(),
            conns: Vec::new(),
            listener,
            inbound: HashSet::new(),
            inbound_order: VecDeque::new(),
            stats: TcpStats::default(),
            buf: vec![0; 64 * 1024],
            config,
        };
        for p in me.config.peers.clone() {
            me.add_dial(p, None, now);
        }
        me.progress_dials(now);
        Ok(me)
    }

    /// The listening socket's address (the port the OS chose for port 0).
    pub fn local_addr(&self) -> Option<SocketAddr> {
        self.listener.as_ref().and_then(|l| l.local_addr().ok())
    }

    /// The counters.
    pub fn stats(&self) -> TcpStats {
        self.stats
    }

    /// The settings.
    pub fn config(&self) -> &TcpConfig {
        &self.config
    }

    /// The peers connected now, each with how it came (`true`: dialed).
    pub fn connected(&self) -> Vec<(SocketAddr, bool)> {
        self.conns
            .iter()
            .map(|(c, _)| (c.key, c.origin == Origin::Dialed))
            .collect()
    }

    fn add_dial(
        &mut self,
        addr: SocketAddr,
        version: Option<Version>,
        now: Instant,
    ) -> Option<usize> {
        if self.dials.len() >= self.config.max_connections {
            self.stats.refused += 1;
            return None;
        }
        self.dials.push(Dial {
            addr,
            version,
            state: DialState::Waiting(now),
            backoff: self.config.backoff_min,
            pending: VecDeque::new(),
        });
        Some(self.dials.len() - 1)
    }

    /// Starts the attempts that are due, and takes the results of those that ended.
    fn progress_dials(&mut self, now: Instant) {
        for i in 0..self.dials.len() {
            match &self.dials[i].state {
                DialState::Waiting(at) if *at <= now => {
                    if self.conns.len() >= self.config.max_connections {
                        // No room now: try again after a backoff, not at every wake-up.
                        self.stats.refused += 1;
                        let d = &mut self.dials[i];
                        d.state = DialState::Waiting(now + d.backoff);
                        continue;
                    }
                    let (tx, rx) = mpsc::channel();
                    let (addr, timeout) = (self.dials[i].addr, self.config.connect_timeout);
                    let spawned = std::thread::Builder::new()
                        .name(format!("jaus-tcp-dial-{addr}"))
                        .spawn(move || {
                            let _ = tx.send(TcpStream::connect_timeout(&addr, timeout));
                        });
                    match spawned {
                        Ok(_) => self.dials[i].state = DialState::Connecting(rx),
                        Err(e) => self.dial_failed(i, now, &e),
                    }
                }
                DialState::Connecting(rx) => match rx.try_recv() {
                    Ok(Ok(stream)) => self.dial_succeeded(i, stream, now),
                    Ok(Err(e)) => self.dial_failed(i, now, &e),
                    Err(mpsc::TryRecvError::Empty) => {}
                    Err(mpsc::TryRecvError::Disconnected) => {
                        self.dial_failed(i, now, &std::io::Error::other("dial thread ended"))
                    }
                },
                _ => {}
            }
        }
    }

    fn dial_failed(&mut self, i: usize, now: Instant, e: &std::io::Error) {
        self.stats.connect_failures += 1;
        let d = &mut self.dials[i];
        tracing::debug!(peer = %d.addr, "tcp connect failed: {e}; again in {:?}", d.backoff);
        d.state = DialState::Waiting(now + d.backoff);
        d.backoff = (d.backoff * 2).min(self.config.backoff_max);
        let lost = d.pending.len() as u64;
        d.pending.clear();
        self.stats.no_connection += lost;
    }

    fn dial_succeeded(&mut self, i: usize, stream: TcpStream, now: Instant) {
        let addr = self.dials[i].addr;
        self.set_keepalive(&stream);
        match Conn::new(stream, addr, Origin::Dialed, self.config.max_frame, now) {
            Ok(mut c) => {
                tracing::info!(peer = %addr, "tcp connected");
                self.stats.connected += 1;
                let pending = std::mem::take(&mut self.dials[i].pending);
                for d in pending {
                    if c.enqueue(&d, now).is_err() {
                        self.stats.wrong_version += 1;
                    }
                }
                self.dials[i].state = DialState::Up;
                self.conns.push((c, Some(i)));
            }
            Err(e) => self.dial_failed(i, now, &e),
        }
    }

    #[cfg(target_os = "linux")]
    fn set_keepalive(&self, stream: &TcpStream) {
        use nix::sys::socket::{setsockopt, sockopt};
        if let Some(idle) = self.config.keepalive {
            let idle = u32::try_from(idle.as_secs().max(1)).unwrap_or(u32::MAX);
            let set = setsockopt(stream, sockopt::KeepAlive, &true)
                .and_then(|()| setsockopt(stream, sockopt::TcpKeepIdle, &idle))
                .and_then(|()| {
                    setsockopt(stream, sockopt::TcpKeepInterval, &idle.div_ceil(3).max(1))
                })
                .and_then(|()| setsockopt(stream, sockopt::TcpKeepCount, &3));
            if let Err(e) = set {
                tracing::debug!("tcp keep-alive not set: {e}");
            }
        }
    }

    #[cfg(not(target_os = "linux"))]
    fn set_keepalive(&self, _stream: &TcpStream) {}

    /// Takes the connections waiting on the listening socket.
    fn accept(&mut self, now: Instant) {
        loop {
            let accepted = match &self.listener {
                Some(l) => l.accept(),
                None => return,
            };
            match accepted {
                Ok((stream, remote)) => {
                    if self.conns.len() >= self.config.max_connections {
                        self.stats.refused += 1;
                        tracing::warn!(peer = %remote, "tcp connection refused: {} connections already", self.conns.len());
                        continue;
                    }
                    self.set_keepalive(&stream);
                    match Conn::new(stream, remote, Origin::Accepted, self.config.max_frame, now) {
                        Ok(c) => {
                            tracing::info!(peer = %remote, "tcp accepted");
                            self.stats.accepted += 1;
                            self.remember_inbound(remote);
                            self.conns.push((c, None));
                        }
                        Err(e) => tracing::debug!(peer = %remote, "tcp accept failed: {e}"),
                    }
                }
                Err(e) if e.kind() == ErrorKind::WouldBlock => return,
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => {
                    // E.g. out of file descriptors: try again at the next wake-up.
                    tracing::warn!("tcp accept: {e}");
                    return;
                }
            }
        }
    }

    fn remember_inbound(&mut self, remote: SocketAddr) {
        if self.inbound.insert(remote) {
            self.inbound_order.push_back(remote);
            if self.inbound_order.len() > INBOUND_MEMORY {
                if let Some(old) = self.inbound_order.pop_front() {
                    self.inbound.remove(&old);
                }
            }
        }
    }

    /// Closes connection `i` (`why` logged); a dialed one is dialed again.
    fn close(&mut self, i: usize, why: &Closed, now: Instant) {
        let (c, dial) = self.conns.swap_remove(i);
        self.stats.closed += 1;
        match why {
            Closed::Stream(_) => self.stats.bad_stream += 1,
            Closed::Stalled => self.stats.stalled += 1,
            _ => {}
        }
        let lost = c.queued() as u64;
        self.stats.no_connection += lost;
        tracing::info!(peer = %c.key, dialed = c.origin == Origin::Dialed, "tcp connection ended: {why}");
        if let Some(d) = dial.and_then(|d| self.dials.get_mut(d)) {
            if c.heard {
                d.backoff = self.config.backoff_min;
            }
            d.version = d.version.or(c.version());
            d.state = DialState::Waiting(now + d.backoff);
            d.backoff = (d.backoff * 2).min(self.config.backoff_max);
        }
    }

    /// Reads every connection, handing the datagrams to `on`; writes what waits;
    /// closes the dead. Returns how many datagrams were handed on.
    fn service(&mut self, now: Instant, on: &mut impl FnMut(Via, SocketAddr, &[u8])) -> u64 {
        let mut handed = 0;
        let mut i = 0;
        while i < self.conns.len() {
            let (c, _) = &mut self.conns[i];
            let read = c.read(&mut self.buf, READ_BUDGET, |from, d| {
                handed += 1;
                on(Via::Network, from, d);
            });
            let result = read.and_then(|r| {
                self.stats.bytes_received += r.bytes;
                self.stats.datagrams_received += r.frames;
                let sent = c.flush(now)?;
                self.stats.datagrams_sent += sent;
                if c.stalled(now, self.config.stall) {
                    return Err(Closed::Stalled);
                }
                Ok(())
            });
            match result {
                Ok(()) => i += 1,
                Err(why) => self.close(i, &why, now),
            }
        }
        handed
    }

    /// When a dial wants attention: the next due attempt, or soon while one runs.
    fn next_dial(&self, now: Instant) -> Option<Instant> {
        self.dials
            .iter()
            .filter_map(|d| match &d.state {
                DialState::Waiting(at) => Some(*at),
                DialState::Connecting(_) => Some(now + Duration::from_millis(5)),
                DialState::Up => None,
            })
            .min()
    }

    /// Queues `bytes` on connection `i` within the bounds and writes what it can.
    fn queue_on(&mut self, i: usize, bytes: &[u8], now: Instant) -> std::io::Result<()> {
        let (c, _) = &mut self.conns[i];
        if c.queued() >= self.config.max_queue
            || c.queued_bytes() + bytes.len() > self.config.max_queue_bytes
        {
            self.stats.queue_full += 1;
            return Err(std::io::Error::new(
                ErrorKind::WouldBlock,
                format!("tcp peer {}: send queue full", c.key),
            ));
        }
        if let Err(e) = c.enqueue(bytes, now) {
            self.stats.wrong_version += 1;
            return Err(std::io::Error::new(
                ErrorKind::InvalidInput,
                format!("tcp peer {}: {e}", c.key),
            ));
        }
        match c.flush(now) {
            Ok(n) => {
                self.stats.datagrams_sent += n;
                Ok(())
            }
            Err(why) => {
                let key = c.key;
                self.close(i, &why, now);
                Err(std::io::Error::new(
                    ErrorKind::BrokenPipe,
                    format!("tcp peer {key}: {why}"),
                ))
            }
        }
    }
}

impl Transport for TcpTransport {
    type Addr = SocketAddr;

    fn recv<F: FnMut(Via, SocketAddr, &[u8])>(
        &mut self,
        wait: Duration,
        mut on: F,
    ) -> std::io::Result<()> {
        let deadline = Instant::now() + wait;
        loop {
            let now = Instant::now();
            self.accept(now);
            self.progress_dials(now);
            if self.service(now, &mut on) > 0 || now >= deadline {
                return Ok(());
            }
            let until = self.next_dial(now).map_or(deadline, |d| d.min(deadline));
            let listener = self.listener.as_ref();
            let conns: Vec<(&TcpStream, bool)> = self
                .conns
                .iter()
                .map(|(c, _)| (&c.stream, c.wants_write()))
                .collect();
            wait::ready(listener, &conns, until.saturating_duration_since(now))?;
        }
    }

    fn send(&mut self, d: &Datagram<SocketAddr>) -> std::io::Result<()> {
        let now = Instant::now();
        let not_carried = |stats: &mut TcpStats, why: String| {
            stats.not_carried += 1;
            std::io::Error::new(ErrorKind::InvalidInput, format!("tcp peer {}: {why}", d.to))
        };
        let Some(version) = d.bytes.first().copied().and_then(Version::from_byte) else {
            return Err(not_carried(
                &mut self.stats,
                "only JUDP versions 1 and 2 have a JTCP form".into(),
            ));
        };
        let fits = |v: Option<Version>| v.is_none_or(|v| v == version);
        if let Some(i) = self
            .conns
            .iter()
            .position(|(c, _)| c.key == d.to && fits(c.version()))
        {
            return self.queue_on(i, &d.bytes, now);
        }
        if let Some(i) = self
            .dials
            .iter()
            .position(|x| x.addr == d.to && fits(x.version) && !matches!(x.state, DialState::Up))
        {
            let dial = &mut self.dials[i];
            let first_attempt = dial.backoff == self.config.backoff_min
                || matches!(dial.state, DialState::Connecting(_));
            if !first_attempt {
                self.stats.no_connection += 1;
                return Err(std::io::Error::new(
                    ErrorKind::NotConnected,
                    format!("tcp peer {}: not connected (dialing again)", d.to),
                ));
            }
            if dial.pending.len() >= self.config.max_queue {
                self.stats.queue_full += 1;
                return Err(std::io::Error::new(
                    ErrorKind::WouldBlock,
                    format!("tcp peer {}: send queue full while connecting", d.to),
                ));
            }
            dial.version = Some(version);
            dial.pending.push_back(d.bytes.clone());
            return Ok(());
        }
        if self.inbound.contains(&d.to) {
            let live = self.conns.iter().any(|(c, _)| c.key == d.to);
            if live {
                self.stats.wrong_version += 1;
            } else {
                self.stats.no_connection += 1;
            }
            return Err(std::io::Error::new(
                ErrorKind::NotConnected,
                format!(
                    "tcp peer {}: {}",
                    d.to,
                    if live {
                        "its connection carries the other JUDP version"
                    } else {
                        "its connection ended (it dialed this node; it must dial again)"
                    }
                ),
            ));
        }
        let Some(i) = self.add_dial(d.to, Some(version), now) else {
            return Err(std::io::Error::new(
                ErrorKind::OutOfMemory,
                format!("tcp peer {}: too many peers", d.to),
            ));
        };
        self.dials[i].pending.push_back(d.bytes.clone());
        self.progress_dials(now);
        Ok(())
    }

    fn describe(&self) -> String {
        let listen = self
            .local_addr()
            .map_or("no listening socket".to_string(), |a| format!("tcp {a}"));
        if self.config.peers.is_empty() {
            listen
        } else {
            format!("{listen}, dialing {:?}", self.config.peers)
        }
    }
}
