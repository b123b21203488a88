//! The one I/O loop: a [`Participant`] (a node, attached components) driven over a
//! [`Transport`] with the real clock. It waits for datagrams until the participant's
//! next timeout, feeds them in, runs the timeout, lets the caller look, and sends what
//! the participant queued, several datagrams per call to the transport (handing the
//! buffers back for reuse).
//!
//! Two ways in: [`run`] until told to stop (a node, a console), and [`run_until`] until
//! something arrived or a deadline (a tool that asks and waits for the answer). Both
//! take the same turns, so whatever runs on a socket acknowledges, retries and sends in
//! batches alike.

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
        turn(node, transport, wait, &mut tap)?;
        on_tick(node);
        flush(node, transport, &mut outgoing, &mut tap);
    }
}

/// Runs `node` over `transport` until `done` answers true or `until` passes, and says
/// which: the loop of a tool that sends something and waits for what answers it (an
/// AS-4 client, a conformance session). At least one turn is taken, so what the node
/// queued before the call is sent even when `until` has passed. `done` runs after every
/// event with the node, as [`run`]'s `on_tick`; what it queues is sent before the call
/// returns.
pub fn run_until<T, P>(
    node: &mut P,
    transport: &mut T,
    until: Instant,
    mut done: impl FnMut(&mut P) -> bool,
    mut tap: impl FnMut(Direction, T::Addr, &[u8]),
) -> std::io::Result<bool>
where
    T: Transport,
    P: Participant<T::Addr> + ?Sized,
{
    let mut outgoing = Vec::with_capacity(SEND_BATCH);
    flush(node, transport, &mut outgoing, &mut tap);
    loop {
        let now = Instant::now();
        let wait = next_wait(node, now).min(until.saturating_duration_since(now));
        turn(node, transport, wait, &mut tap)?;
        let finished = done(node);
        flush(node, transport, &mut outgoing, &mut tap);
        if finished {
            return Ok(true);
        }
        if Instant::now() >= until {
            return Ok(false);
        }
    }
}

/// One turn of the loop: waits up to `wait` for datagrams and feeds them in, then runs
/// the node's timeouts.
fn turn<T, P>(
    node: &mut P,
    transport: &mut T,
    wait: Duration,
    tap: &mut impl FnMut(Direction, T::Addr, &[u8]),
) -> std::io::Result<()>
where
    T: Transport,
    P: Participant<T::Addr> + ?Sized,
{
    transport.recv(wait, |via, peer, datagram| {
        if via == Via::Network {
            tap(Direction::Received, peer, datagram);
        }
        node.handle_via(Instant::now(), via, peer, datagram);
    })?;
    node.handle_timeout(Instant::now());
    Ok(())
}

/// Sends what the node queued, several datagrams per call to the transport, and hands
/// the buffers back to the node for reuse. A datagram the carrier refuses is logged
/// and dropped (the node's own counters and acknowledgements see to the rest).
fn flush<T, P>(
    node: &mut P,
    transport: &mut T,
    outgoing: &mut Vec<super::Datagram<T::Addr>>,
    tap: &mut impl FnMut(Direction, T::Addr, &[u8]),
) where
    T: Transport,
    P: Participant<T::Addr> + ?Sized,
{
    loop {
        while outgoing.len() < SEND_BATCH {
            match node.poll_transmit() {
                Some(d) => outgoing.push(d),
                None => break,
            }
        }
        if outgoing.is_empty() {
            return;
        }
        transport.send_all(outgoing, |i, sent| {
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

#[cfg(test)]
mod tests {
    use std::net::UdpSocket;

    use super::*;
    use crate::net::as5669a::{As4Client, As4Id, As4Message};
    use crate::net::udp::{IoOptions, UdpTransport};

    /// A peer that sends every datagram back, until told to stop.
    fn echo() -> (
        std::net::SocketAddr,
        std::thread::JoinHandle<usize>,
        UdpSocket,
    ) {
        let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
        let addr = socket.local_addr().unwrap();
        let stopper = UdpSocket::bind("127.0.0.1:0").unwrap();
        let handle = std::thread::spawn(move || {
            let mut buf = [0u8; 65536];
            let mut echoed = 0;
            while let Ok((n, from)) = socket.recv_from(&mut buf) {
                if &buf[..n] == b"stop" {
                    break;
                }
                socket.send_to(&buf[..n], from).unwrap();
                echoed += 1;
            }
            echoed
        });
        (addr, handle, stopper)
    }

    #[test]
    fn run_until_sends_what_was_queued_and_returns_when_done_or_at_the_deadline() {
        let (peer, echoer, stopper) = echo();
        let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
        let mut transport = UdpTransport::new(&socket, &IoOptions::default());
        let mut client: As4Client = As4Client::default();
        let me = As4Id::new(42, 1, 1);
        let mut seen = Vec::new();

        // Queued before the call and sent by its first turn; done once the echo is in.
        client.send(peer, &[As4Message::new(0x2B00, me, me, vec![])]);
        let done = run_until(
            &mut client,
            &mut transport,
            Instant::now() + Duration::from_secs(5),
            |c| !c.take().is_empty(),
            |dir, addr, _| seen.push((dir, addr)),
        )
        .unwrap();
        assert!(done);
        assert_eq!(seen, [(Direction::Sent, peer), (Direction::Received, peer)]);

        // Nothing more comes: false once the deadline passes, not before.
        let t0 = Instant::now();
        let done = run_until(
            &mut client,
            &mut transport,
            t0 + Duration::from_millis(50),
            |c| !c.take().is_empty(),
            |_, _, _| {},
        )
        .unwrap();
        assert!(!done);
        assert!(t0.elapsed() >= Duration::from_millis(50));

        stopper.send_to(b"stop", peer).unwrap();
        assert_eq!(echoer.join().unwrap(), 1);
    }
}
