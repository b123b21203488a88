//! The one I/O loop: a [`Participant`] (a node, attached components) driven over a
//! [`Transport`] with the real clock. It waits for datagrams until the participant's
//! next timeout, feeds them in, runs the timeout, lets the caller look, and sends what
//! the participant queued, several datagrams per call to the transport (handing the
//! buffers back for reuse).

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use super::{Participant, Transport, Via};

/// Which way a datagram went, for a tap.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Received from the peer.
    Received,
    /// Sent to the peer (after the carrier accepted it).
    Sent,
}

/// Runs `node` over `transport` until `stop` is set (checked at least every 100 ms) or
/// `until` passes. `on_tick` runs after every event with the node, for a caller that
/// watches it (printing, sending); `tap` sees every datagram that crosses the carrier's
/// own socket ([`Via::Network`]), e.g. to write a capture.
pub fn run<T, P>(
    node: &mut P,
    transport: &mut T,
    stop: &AtomicBool,
    until: Option<Instant>,
    mut on_tick: impl FnMut(&mut P),
    mut tap: impl FnMut(Direction, T::Addr, &[u8]),
) -> std::io::Result<()>
where
    T: Transport,
    P: Participant<T::Addr> + ?Sized,
{
    tracing::info!(bind = %transport.describe(), "up");
    give_wall_clock(node);
    let mut outgoing = Vec::with_capacity(SEND_BATCH);
    loop {
        if stopping(stop, until) {
            return Ok(());
        }
        let wait = next_wait(node, Instant::now());
        transport.recv(wait, |via, peer, datagram| {
            if via == Via::Network {
                tap(Direction::Received, peer, datagram);
            }
            node.handle_via(Instant::now(), via, peer, datagram);
        })?;
        node.handle_timeout(Instant::now());
        on_tick(node);
        loop {
            while outgoing.len() < SEND_BATCH {
                match node.poll_transmit() {
                    Some(d) => outgoing.push(d),
                    None => break,
                }
            }
            if outgoing.is_empty() {
                break;
            }
            transport.send_all(&outgoing, |i, sent| {
                let d = &outgoing[i];
                match sent {
                    Ok(()) if d.via == Via::Network => tap(Direction::Sent, d.to, &d.bytes),
                    Ok(()) => {}
                    Err(e) => tracing::debug!(to = %d.to, "send failed: {e}"),
                }
            });
            for d in outgoing.drain(..) {
                node.recycle(d.bytes);
            }
        }
    }
}

/// Most datagrams handed to the transport at once ([`Transport::send_all`]): what a
/// node queued while it handled one batch of received datagrams and its timeouts
/// usually fits.
const SEND_BATCH: usize = 32;

/// The system's clock for the components whose clock nobody set (the shell reads the
/// clocks; the sans-IO core does not).
fn give_wall_clock<A: super::PeerAddr, P: Participant<A> + ?Sized>(node: &mut P) {
    let utc = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap_or_default();
    node.wall_clock(Instant::now(), utc);
}

/// Whether the loop must end: `stop` set or `until` passed.
fn stopping(stop: &AtomicBool, until: Option<Instant>) -> bool {
    stop.load(Ordering::Relaxed) || until.is_some_and(|u| Instant::now() >= u)
}

/// How long the loop may wait for a datagram: until the node's next timeout, within
/// 100 µs to 100 ms (so that `stop` is seen at least every 100 ms).
fn next_wait<A: super::PeerAddr, P: Participant<A> + ?Sized>(node: &P, now: Instant) -> Duration {
    node.poll_timeout()
        .map_or(Duration::from_millis(100), |t| {
            t.saturating_duration_since(now)
        })
        .clamp(Duration::from_micros(100), Duration::from_millis(100))
}
