//! [`UdpLink`]: a Communicator data link ([`DataLink`]) over UDP, for links whose
//! hardware is reached through a socket: an IP radio modem or its serial bridge, a
//! tether, a satellite terminal, a VPN between two vehicles.
//!
//! The wire is as plain as it gets: every frame (one JAUS packet, header and body, as
//! `Framing::Raw` writes it) is one datagram from the link's socket to the far
//! communicator's link socket, and back. Nothing else crosses it but a keep-alive
//! ([`KEEPALIVE`], 4 bytes: shorter than a JAUS header, so never mistaken for a frame)
//! sent when the link has sent nothing for [`UdpLinkConfig::keepalive`].
//!
//! Up and down: the link is up while a datagram came from the far end within
//! [`UdpLinkConfig::silence`], and, with [`UdpLinkConfig::assume_up`], before anything
//! was ever heard (so that the first frames go out at once). The Communicator forwards
//! nothing on a link that is down, its heartbeats included; the keep-alives are what
//! brings two links back up after an outage that silenced both.
//!
//! Bounded: a frame longer than [`UdpLinkConfig::mtu`] is refused on the way out
//! ([`LinkError::TooLarge`]) and dropped on the way in, both counted
//! ([`UdpLinkStats`]); datagrams from any address other than the far end's are dropped
//! and counted. Nothing read from the socket can make it panic.
//!
//! The socket is non-blocking and read by [`DataLink::recv`], which the node calls on
//! every wake-up; [`DataLink::poll_timeout`] asks for a wake-up
//! [`UdpLinkConfig::poll`] after the last time the socket was read to the end, so that
//! the I/O loop (which sleeps on the node's own socket) reads the link within that
//! time.

use std::io::ErrorKind;
use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

use crate::link::{DataLink, LinkError};
use crate::wire::HEADER_LEN;

/// The keep-alive datagram: shorter than a JAUS header, so never a frame.
pub const KEEPALIVE: &[u8] = b"JLKA";

/// The largest UDP payload over IPv4 (65,535 less the IP and UDP headers).
pub const MAX_UDP_PAYLOAD: usize = 65_507;

/// Most datagrams one [`DataLink::recv`] reads and discards (keep-alives, strangers,
/// oversize) before it gives up until the next wake-up.
const MAX_SKIPPED: usize = 256;

/// Settings of a [`UdpLink`].
///
/// ```
/// use std::time::Duration;
/// use jaus::net::udp::link::UdpLinkConfig;
/// let c = UdpLinkConfig::new(1, "127.0.0.1:4001".parse().unwrap(), "127.0.0.1:4002".parse().unwrap());
/// assert_eq!((c.mtu, c.silence, c.assume_up), (4096, Duration::from_secs(3), true));
/// assert_eq!((c.keepalive, c.poll), (Some(Duration::from_secs(1)), Duration::from_millis(10)));
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UdpLinkConfig {
    /// The link's id (Data Link ID in the communications messages).
    pub id: u8,
    /// The local socket address the link binds.
    pub bind: SocketAddr,
    /// The far end: the other communicator's link socket (or the modem bridge in front
    /// of it). Only datagrams from this address are taken.
    pub peer: SocketAddr,
    /// The largest frame carried, bytes ([`HEADER_LEN`] to [`MAX_UDP_PAYLOAD`]).
    /// Default 4096: the largest JAUS packet (16-byte header, 4080-byte body).
    pub mtu: usize,
    /// Up while the far end was heard within this. Default 3 s (three of the far
    /// communicator's heartbeats, or of its link's keep-alives).
    pub silence: Duration,
    /// Up before anything was heard from the far end. Default true.
    pub assume_up: bool,
    /// A keep-alive goes to the far end when nothing was sent for this long (while the
    /// link is powered); `None`: never. Default 1 s.
    pub keepalive: Option<Duration>,
    /// The socket is read again at most this long after it was last read to the end.
    /// Default 10 ms.
    pub poll: Duration,
}

impl UdpLinkConfig {
    /// Link `id` bound to `bind`, its far end at `peer`, the other settings at their
    /// defaults.
    pub fn new(id: u8, bind: SocketAddr, peer: SocketAddr) -> Self {
        Self {
            id,
            bind,
            peer,
            mtu: HEADER_LEN + crate::net::framing::MAX_PACKET_BODY,
            silence: Duration::from_secs(3),
            assume_up: true,
            keepalive: Some(Duration::from_secs(1)),
            poll: Duration::from_millis(10),
        }
    }
}

/// Why a [`UdpLink`] could not be set up.
#[derive(Debug, thiserror::Error)]
pub enum UdpLinkError {
    /// The socket could not be bound or configured.
    #[error("data link {id}: cannot use {bind}: {source}")]
    Socket {
        /// The link's id.
        id: u8,
        /// The address asked for.
        bind: SocketAddr,
        /// What the OS said.
        source: std::io::Error,
    },
    /// The MTU cannot carry a JAUS header, or is more than a UDP datagram carries.
    #[error("data link {id}: mtu {mtu} is not in {HEADER_LEN}..={MAX_UDP_PAYLOAD}")]
    Mtu {
        /// The link's id.
        id: u8,
        /// The MTU asked for.
        mtu: usize,
    },
}

/// What a [`UdpLink`] counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct UdpLinkStats {
    /// Frames sent to the far end.
    pub frames_sent: u64,
    /// Bytes of those frames.
    pub bytes_sent: u64,
    /// Frames received from the far end.
    pub frames_received: u64,
    /// Bytes of those frames.
    pub bytes_received: u64,
    /// Keep-alives sent.
    pub keepalives_sent: u64,
    /// Keep-alives received.
    pub keepalives_received: u64,
    /// Frames refused for sending: longer than the MTU.
    pub dropped_oversize_sent: u64,
    /// Datagrams from the far end dropped: longer than the MTU.
    pub dropped_oversize_received: u64,
    /// Datagrams dropped: not from the far end's address.
    pub dropped_stranger: u64,
    /// Sends the socket failed (the frame is lost).
    pub send_errors: u64,
    /// Reads the socket failed (e.g. an ICMP error reported on the socket).
    pub recv_errors: u64,
}

/// A [`DataLink`] over a UDP socket: each frame one datagram to the far communicator's
/// link socket (see the [module documentation](self) for up/down, keep-alives and
/// bounds).
///
/// ```
/// use std::time::Instant;
/// use jaus::net::udp::link::{UdpLink, UdpLinkConfig};
/// use jaus::link::DataLink;
///
/// let any = "127.0.0.1:0".parse().unwrap();
/// let mut a = UdpLink::bind(UdpLinkConfig::new(1, any, any)).unwrap();
/// let mut b = UdpLink::bind(UdpLinkConfig::new(1, any, a.local_addr().unwrap())).unwrap();
/// a.set_peer(b.local_addr().unwrap());
/// let now = Instant::now();
/// a.send(now, &[0u8; 16]).unwrap();
/// let mut buf = Vec::new();
/// let t = Instant::now() + std::time::Duration::from_secs(1);
/// while !b.recv(Instant::now(), &mut buf) && Instant::now() < t {}
/// assert_eq!(buf, [0u8; 16]);
/// ```
#[derive(Debug)]
pub struct UdpLink {
    socket: UdpSocket,
    config: UdpLinkConfig,
    stats: UdpLinkStats,
    /// When a datagram last came from the far end.
    last_heard: Option<Instant>,
    /// When a datagram last left (frame or keep-alive).
    last_sent: Option<Instant>,
    /// When the socket was last read to the end.
    drained_at: Option<Instant>,
    powered: bool,
}

impl UdpLink {
    /// A link with `config`, its socket bound (non-blocking).
    pub fn bind(config: UdpLinkConfig) -> Result<Self, UdpLinkError> {
        let socket = UdpSocket::bind(config.bind).map_err(|source| UdpLinkError::Socket {
            id: config.id,
            bind: config.bind,
            source,
        })?;
        Self::on(socket, config)
    }

    /// A link with `config` on a socket the caller has bound (`config.bind` is then
    /// only a label); the socket is made non-blocking.
    pub fn on(socket: UdpSocket, config: UdpLinkConfig) -> Result<Self, UdpLinkError> {
        if !(HEADER_LEN..=MAX_UDP_PAYLOAD).contains(&config.mtu) {
            return Err(UdpLinkError::Mtu {
                id: config.id,
                mtu: config.mtu,
            });
        }
        socket
            .set_nonblocking(true)
            .map_err(|source| UdpLinkError::Socket {
                id: config.id,
                bind: config.bind,
                source,
            })?;
        Ok(Self {
            socket,
            config,
            stats: UdpLinkStats::default(),
            last_heard: None,
            last_sent: None,
            drained_at: None,
            powered: true,
        })
    }

    /// The settings.
    pub fn config(&self) -> &UdpLinkConfig {
        &self.config
    }

    /// The local address the socket is bound to (the port the OS chose for port 0).
    pub fn local_addr(&self) -> std::io::Result<SocketAddr> {
        self.socket.local_addr()
    }

    /// The far end's address.
    pub fn peer(&self) -> SocketAddr {
        self.config.peer
    }

    /// Sends to, and takes datagrams only from, `peer` from now on.
    pub fn set_peer(&mut self, peer: SocketAddr) {
        self.config.peer = peer;
    }

    /// The counters.
    pub fn stats(&self) -> UdpLinkStats {
        self.stats
    }

    /// When a datagram last came from the far end.
    pub fn last_heard(&self) -> Option<Instant> {
        self.last_heard
    }

    /// Sends a keep-alive at `now` if the link is powered and has sent nothing for the
    /// keep-alive period.
    fn keep_alive(&mut self, now: Instant) {
        let Some(period) = self.config.keepalive else {
            return;
        };
        if !self.powered
            || self
                .last_sent
                .is_some_and(|t| now.saturating_duration_since(t) < period)
        {
            return;
        }
        match self.socket.send_to(KEEPALIVE, self.config.peer) {
            Ok(_) => self.stats.keepalives_sent += 1,
            // Full: the frames waiting say the same.
            Err(e) if e.kind() == ErrorKind::WouldBlock => {}
            Err(e) => {
                self.stats.send_errors += 1;
                tracing::debug!(link = self.config.id, peer = %self.config.peer, "keep-alive not sent: {e}");
            }
        }
        // Tried: the next one is a period away even if this one failed.
        self.last_sent = Some(now);
    }
}

impl DataLink for UdpLink {
    fn id(&self) -> u8 {
        self.config.id
    }

    fn send(&mut self, now: Instant, frame: &[u8]) -> Result<(), LinkError> {
        if !self.powered {
            return Err(LinkError::Down);
        }
        if frame.len() > self.config.mtu {
            self.stats.dropped_oversize_sent += 1;
            return Err(LinkError::TooLarge {
                len: frame.len(),
                max: self.config.mtu,
            });
        }
        match self.socket.send_to(frame, self.config.peer) {
            Ok(n) if n == frame.len() => {
                self.stats.frames_sent += 1;
                self.stats.bytes_sent += n as u64;
                self.last_sent = Some(now);
                Ok(())
            }
            Ok(n) => {
                // A datagram leaves whole or not at all; should a platform say otherwise,
                // the frame is lost.
                self.stats.send_errors += 1;
                tracing::debug!(
                    link = self.config.id,
                    sent = n,
                    len = frame.len(),
                    "frame cut short"
                );
                Err(LinkError::Down)
            }
            Err(e) if e.kind() == ErrorKind::WouldBlock => Err(LinkError::Busy),
            Err(e) => {
                self.stats.send_errors += 1;
                tracing::debug!(link = self.config.id, peer = %self.config.peer, "frame not sent: {e}");
                Err(LinkError::Down)
            }
        }
    }

    fn recv(&mut self, now: Instant, buf: &mut Vec<u8>) -> bool {
        self.keep_alive(now);
        let mtu = self.config.mtu;
        for _ in 0..MAX_SKIPPED {
            buf.clear();
            // One byte more than the MTU: a longer datagram shows as MTU + 1 (the
            // kernel cuts it) or as an error (Windows), never as a frame.
            buf.resize(mtu + 1, 0);
            match self.socket.recv_from(buf) {
                Ok((n, from)) => {
                    if from != self.config.peer {
                        self.stats.dropped_stranger += 1;
                        continue;
                    }
                    self.last_heard = Some(now);
                    let Some(bytes) = buf.get(..n) else {
                        self.stats.recv_errors += 1;
                        continue;
                    };
                    if bytes == KEEPALIVE {
                        self.stats.keepalives_received += 1;
                        continue;
                    }
                    if n > mtu {
                        self.stats.dropped_oversize_received += 1;
                        tracing::debug!(
                            link = self.config.id,
                            mtu,
                            "datagram over the MTU dropped"
                        );
                        continue;
                    }
                    buf.truncate(n);
                    self.stats.frames_received += 1;
                    self.stats.bytes_received += n as u64;
                    return true;
                }
                Err(e) if e.kind() == ErrorKind::WouldBlock => break,
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => {
                    // ICMP errors of earlier sends (connection refused or reset), a
                    // datagram over the buffer on Windows: counted, and read on.
                    self.stats.recv_errors += 1;
                    tracing::debug!(link = self.config.id, "read failed: {e}");
                }
            }
        }
        buf.clear();
        self.drained_at = Some(now);
        false
    }

    fn is_up(&self, now: Instant) -> bool {
        self.powered
            && match self.last_heard {
                Some(t) => now.saturating_duration_since(t) < self.config.silence,
                None => self.config.assume_up,
            }
    }

    fn poll_timeout(&self) -> Option<Instant> {
        self.drained_at.map(|t| t + self.config.poll)
    }

    fn set_powered(&mut self, _now: Instant, on: bool) {
        if on && !self.powered {
            // Powered up: say so to the far end at the next wake-up.
            self.last_sent = None;
        }
        self.powered = on;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two links on loopback, each the other's far end, with `tweak` applied to both
    /// configurations.
    fn pair(tweak: impl Fn(&mut UdpLinkConfig)) -> (UdpLink, UdpLink) {
        let any: SocketAddr = "127.0.0.1:0".parse().unwrap();
        let mut ca = UdpLinkConfig::new(1, any, any);
        tweak(&mut ca);
        let mut a = UdpLink::bind(ca).unwrap();
        let mut cb = UdpLinkConfig::new(1, any, a.local_addr().unwrap());
        tweak(&mut cb);
        let b = UdpLink::bind(cb).unwrap();
        a.set_peer(b.local_addr().unwrap());
        (a, b)
    }

    /// Reads `link` until a frame comes or `limit` passes.
    fn recv_within(link: &mut UdpLink, limit: Duration) -> Option<Vec<u8>> {
        let end = Instant::now() + limit;
        let mut buf = Vec::new();
        while Instant::now() < end {
            if link.recv(Instant::now(), &mut buf) {
                return Some(buf);
            }
            std::thread::sleep(Duration::from_millis(1));
        }
        None
    }

    /// Reads `link` to the end for `d` (keep-alives and drops are counted on the way).
    fn drain_for(link: &mut UdpLink, d: Duration) -> Vec<Vec<u8>> {
        let end = Instant::now() + d;
        let mut got = Vec::new();
        let mut buf = Vec::new();
        while Instant::now() < end {
            while link.recv(Instant::now(), &mut buf) {
                got.push(buf.clone());
            }
            std::thread::sleep(Duration::from_millis(1));
        }
        got
    }

    fn frame(len: usize, tag: u8) -> Vec<u8> {
        (0..len).map(|i| (i as u8).wrapping_add(tag)).collect()
    }

    #[test]
    fn frames_cross_both_ways_one_datagram_each() {
        let (mut a, mut b) = pair(|_| {});
        let now = Instant::now();
        for i in 0..5u8 {
            a.send(now, &frame(16 + usize::from(i) * 100, i)).unwrap();
        }
        b.send(now, &frame(4096, 9)).unwrap();
        for i in 0..5u8 {
            let got = recv_within(&mut b, Duration::from_secs(2)).expect("a frame");
            assert_eq!(got, frame(16 + usize::from(i) * 100, i));
        }
        assert_eq!(
            recv_within(&mut a, Duration::from_secs(2)).as_deref(),
            Some(&frame(4096, 9)[..]),
            "a full-size packet fits the default MTU"
        );
        let (sa, sb) = (a.stats(), b.stats());
        assert_eq!((sa.frames_sent, sb.frames_received), (5, 5));
        assert_eq!(sa.bytes_sent, sb.bytes_received);
        assert_eq!((sb.frames_sent, sa.frames_received), (1, 1));
        assert_eq!(sa.dropped_stranger + sb.dropped_stranger, 0);
    }

    #[test]
    fn oversize_frames_are_refused_and_dropped_and_counted() {
        let (mut a, mut b) = pair(|c| c.mtu = 100);
        let now = Instant::now();
        // Out: refused with the sizes, counted, nothing sent.
        assert_eq!(
            a.send(now, &frame(101, 0)),
            Err(LinkError::TooLarge { len: 101, max: 100 })
        );
        assert_eq!(a.stats().dropped_oversize_sent, 1);
        assert_eq!(a.stats().frames_sent, 0);
        // In: a far end that sends more than the MTU (a raw socket standing in for a
        // link with a larger MTU) is dropped and counted; the next frame still comes.
        let raw = UdpSocket::bind("127.0.0.1:0").unwrap();
        b.set_peer(raw.local_addr().unwrap());
        let to = b.local_addr().unwrap();
        raw.send_to(&frame(1000, 1), to).unwrap();
        raw.send_to(&frame(101, 2), to).unwrap();
        raw.send_to(&frame(100, 3), to).unwrap();
        assert_eq!(
            recv_within(&mut b, Duration::from_secs(2)),
            Some(frame(100, 3))
        );
        assert_eq!(b.stats().dropped_oversize_received, 2);
        assert_eq!(b.stats().frames_received, 1);
        // Heard, though: the far end is alive.
        assert!(b.last_heard().is_some());
        // Strangers are dropped and counted.
        let stranger = UdpSocket::bind("127.0.0.1:0").unwrap();
        stranger.send_to(&frame(20, 4), to).unwrap();
        raw.send_to(&frame(20, 5), to).unwrap();
        assert_eq!(
            recv_within(&mut b, Duration::from_secs(2)),
            Some(frame(20, 5))
        );
        assert_eq!(b.stats().dropped_stranger, 1);
        // A bad MTU is refused at set-up.
        let any: SocketAddr = "127.0.0.1:0".parse().unwrap();
        let mut c = UdpLinkConfig::new(3, any, any);
        c.mtu = 15;
        let e = UdpLink::bind(c).unwrap_err();
        assert_eq!(e.to_string(), "data link 3: mtu 15 is not in 16..=65507");
    }

    #[test]
    fn up_until_the_far_end_is_silent_and_kept_up_by_keepalives() {
        let (mut a, mut b) = pair(|c| c.keepalive = Some(Duration::from_millis(20)));
        let t0 = Instant::now();
        // Nothing heard yet: up (assumed).
        assert!(a.is_up(t0));
        let mut quiet = a.config().clone();
        quiet.assume_up = false;
        quiet.bind = "127.0.0.1:0".parse().unwrap();
        let never = UdpLink::bind(quiet).unwrap();
        assert!(!never.is_up(t0), "not assumed up: down until heard");

        // Only keep-alives flow: both ends hear each other, no frame comes out.
        let got = drain_for(&mut a, Duration::from_millis(100));
        assert!(got.is_empty());
        assert!(drain_for(&mut b, Duration::from_millis(100)).is_empty());
        assert!(drain_for(&mut a, Duration::from_millis(10)).is_empty());
        assert!(a.stats().keepalives_sent >= 2, "{:?}", a.stats());
        assert!(b.stats().keepalives_received >= 2, "{:?}", b.stats());
        assert!(a.stats().keepalives_received >= 1, "{:?}", a.stats());
        let heard = b.last_heard().expect("heard the far end");
        assert!(b.is_up(heard + Duration::from_millis(2999)));
        // Silent for the silence timeout: down.
        assert!(!b.is_up(heard + Duration::from_secs(3)));

        // Powered off: down, nothing sent, no keep-alives.
        let now = Instant::now();
        a.set_powered(now, false);
        assert!(!a.is_up(now));
        assert_eq!(a.send(now, &frame(20, 0)), Err(LinkError::Down));
        let sent = a.stats().keepalives_sent;
        drain_for(&mut a, Duration::from_millis(60));
        assert_eq!(a.stats().keepalives_sent, sent);
        // On again: a keep-alive at once.
        a.set_powered(Instant::now(), true);
        drain_for(&mut a, Duration::from_millis(2));
        assert_eq!(a.stats().keepalives_sent, sent + 1);
    }

    #[test]
    fn the_socket_is_read_again_a_poll_period_after_it_was_drained() {
        let (mut a, _b) = pair(|c| c.poll = Duration::from_millis(7));
        assert_eq!(a.poll_timeout(), None, "read at the first wake-up");
        let now = Instant::now();
        let mut buf = vec![1, 2, 3];
        assert!(!a.recv(now, &mut buf));
        assert!(buf.is_empty());
        assert_eq!(a.poll_timeout(), Some(now + Duration::from_millis(7)));
    }
}
