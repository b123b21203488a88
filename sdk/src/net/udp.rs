//! The I/O shell: one blocking UDP socket driving a sans-IO [`Participant`]
//! (a [`Node`](super::Node), [`Attached`](super::Attached) components) with the real clock.

use std::io::ErrorKind;
use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use super::Participant;

/// Largest datagram read (JUDP or OPC framing plus a full 4096-byte packet).
const MAX_DATAGRAM: usize = 8 + 4096 + 64;

/// Runs `node` (a [`Node`](super::Node), [`Attached`](super::Attached) components, ...)
/// on a socket bound to `bind` until `stop` is set (checked at least every 100 ms) or
/// `until` passes. `on_tick` runs after every event with the node, for a caller that
/// watches it (printing, sending).
pub fn run<P: Participant>(
    node: &mut P,
    bind: SocketAddr,
    stop: &AtomicBool,
    until: Option<Instant>,
    on_tick: impl FnMut(&mut P),
) -> std::io::Result<()> {
    let socket = UdpSocket::bind(bind)?;
    run_on(node, &socket, stop, until, on_tick)
}

/// [`run`] on a socket the caller has bound.
pub fn run_on<P: Participant>(
    node: &mut P,
    socket: &UdpSocket,
    stop: &AtomicBool,
    until: Option<Instant>,
    on_tick: impl FnMut(&mut P),
) -> std::io::Result<()> {
    run_tapped(node, socket, stop, until, on_tick, |_, _, _| {})
}

/// Which way a datagram went, for a [`run_tapped`] observer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Received from the peer.
    Received,
    /// Sent to the peer (after the socket accepted it).
    Sent,
}

/// [`run_on`], showing `tap` every datagram received and sent (direction, peer,
/// datagram), e.g. to write a capture.
pub fn run_tapped<P: Participant>(
    node: &mut P,
    socket: &UdpSocket,
    stop: &AtomicBool,
    until: Option<Instant>,
    mut on_tick: impl FnMut(&mut P),
    mut tap: impl FnMut(Direction, SocketAddr, &[u8]),
) -> std::io::Result<()> {
    tracing::info!(bind = ?socket.local_addr().ok(), "up");
    let mut buf = vec![0u8; MAX_DATAGRAM];
    loop {
        if stop.load(Ordering::Relaxed) || until.is_some_and(|u| Instant::now() >= u) {
            return Ok(());
        }
        let now = Instant::now();
        let wait = node
            .poll_timeout()
            .map_or(Duration::from_millis(100), |t| {
                t.saturating_duration_since(now)
            })
            .clamp(Duration::from_micros(100), Duration::from_millis(100));
        socket.set_read_timeout(Some(wait))?;
        match socket.recv_from(&mut buf) {
            Ok((n, peer)) => {
                tap(Direction::Received, peer, &buf[..n]);
                node.handle_datagram(Instant::now(), peer, &buf[..n]);
            }
            Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => {}
            // A previous send to a closed port (ICMP unreachable on some systems).
            Err(e) if e.kind() == ErrorKind::ConnectionReset => {}
            Err(e) => return Err(e),
        }
        node.handle_timeout(Instant::now());
        on_tick(node);
        while let Some(d) = node.poll_transmit() {
            match socket.send_to(&d.bytes, d.to) {
                Ok(_) => tap(Direction::Sent, d.to, &d.bytes),
                Err(e) => tracing::debug!(to = %d.to, "send failed: {e}"),
            }
        }
    }
}
