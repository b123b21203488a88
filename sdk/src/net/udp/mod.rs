//! The I/O shell: one blocking UDP socket driving a sans-IO [`Participant`]
//! (a [`Node`](super::Node), [`Attached`](super::Attached) components) with the real clock.
//!
//! `link` (with the `stock` feature) is the Communicator's data link over UDP
//! (`link::UdpLink`), the hardware a node hosting a
//! `jaus::stock::communicator::CommunicatorEndpoint` uses to reach other subsystems
//! through an IP radio or any other socket.

use std::io::ErrorKind;
use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use super::Participant;

#[cfg(feature = "stock")]
pub mod link;
pub mod shutdown;
mod socket;

pub use shutdown::{join_within, ShutdownError, SHUTDOWN_BOUND};
pub use socket::MAX_BATCH;
use socket::{Receiver, MAX_DATAGRAM};

/// How the I/O shell waits for and reads datagrams.
///
/// The defaults are measured (docs/performance.md, "Routing"): on loopback, a spin of
/// 50 µs takes a node from about 16,000 to about 43,000 routed query/report pairs per
/// second with one request in flight, and p99 latency from about 100 µs to 50 µs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IoOptions {
    /// After a datagram, keep reading without blocking for this long before sleeping in
    /// the kernel: the next datagram of an exchange is taken without a wake-up. It costs
    /// at most `spin` of CPU per datagram when traffic is sparse (at 1,000 datagrams/s
    /// and 50 µs, 5 % of a core); zero always blocks. Default 50 µs.
    pub spin: Duration,
    /// Datagrams read per system call where the OS offers it (`recvmmsg` on Linux), at
    /// most [`MAX_BATCH`]; 1 reads one at a time. Default 32.
    pub batch: usize,
}

impl Default for IoOptions {
    fn default() -> Self {
        Self {
            spin: Duration::from_micros(50),
            batch: 32,
        }
    }
}

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
    run_tapped(
        node,
        socket,
        &IoOptions::default(),
        stop,
        until,
        on_tick,
        |_, _, _| {},
    )
}

/// Which way a datagram went, for a [`run_tapped`] observer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Received from the peer.
    Received,
    /// Sent to the peer (after the socket accepted it).
    Sent,
}

/// [`run_on`] with `io` options, showing `tap` every datagram received and sent
/// (direction, peer, datagram), e.g. to write a capture.
pub fn run_tapped<P: Participant>(
    node: &mut P,
    socket: &UdpSocket,
    io: &IoOptions,
    stop: &AtomicBool,
    until: Option<Instant>,
    mut on_tick: impl FnMut(&mut P),
    mut tap: impl FnMut(Direction, SocketAddr, &[u8]),
) -> std::io::Result<()> {
    tracing::info!(bind = ?socket.local_addr().ok(), "up");
    give_wall_clock(node);
    let mut receiver = Receiver::new(io);
    loop {
        if stopping(stop, until) {
            return Ok(());
        }
        let now = Instant::now();
        let wait = next_wait(node, now);
        match receiver.recv(socket, now, wait) {
            Ok(n) => {
                for i in 0..n {
                    let (peer, datagram) = receiver.datagram(i);
                    tap(Direction::Received, peer, datagram);
                    node.handle_datagram(Instant::now(), peer, datagram);
                }
            }
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
            node.recycle(d.bytes);
        }
    }
}

/// The system's clock for the components whose clock nobody set (the shell reads the
/// clocks; the sans-IO core does not).
fn give_wall_clock<P: Participant + ?Sized>(node: &mut P) {
    let utc = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap_or_default();
    node.wall_clock(Instant::now(), utc);
}

/// Whether the I/O loop must end: `stop` set or `until` passed.
fn stopping(stop: &AtomicBool, until: Option<Instant>) -> bool {
    stop.load(Ordering::Relaxed) || until.is_some_and(|u| Instant::now() >= u)
}

/// How long the I/O loop may wait for a datagram: until the node's next timeout, within
/// 100 µs to 100 ms (so that `stop` is seen at least every 100 ms).
fn next_wait<P: Participant + ?Sized>(node: &P, now: Instant) -> Duration {
    node.poll_timeout()
        .map_or(Duration::from_millis(100), |t| {
            t.saturating_duration_since(now)
        })
        .clamp(Duration::from_micros(100), Duration::from_millis(100))
}

/// The sockets of a [`Node`](super::Node): its JAUS socket, and when it serves
/// OpenJAUS component processes, the two sockets of their local interface
/// ([`oj`](super::oj): control on port 24627, data on 24629 of the loopback address).
#[derive(Debug, Clone, Copy)]
pub struct NodeSockets<'a> {
    /// The node's JAUS socket.
    pub network: &'a UdpSocket,
    /// OpenJAUS's component control socket.
    pub component_control: Option<&'a UdpSocket>,
    /// OpenJAUS's component data socket.
    pub component_data: Option<&'a UdpSocket>,
}

/// Runs `node` on its sockets until `stop` is set or `until` passes, like
/// [`run_tapped`] (`tap` sees what crosses the JAUS socket). With only the JAUS socket
/// everything happens on the caller's thread as in [`run_tapped`]; with OpenJAUS's
/// component sockets too, one thread per socket receives (one datagram per read, `io`
/// unused) into a bounded queue and the caller's thread does the rest.
pub fn run_node(
    node: &mut super::Node,
    sockets: NodeSockets<'_>,
    io: &IoOptions,
    stop: &AtomicBool,
    until: Option<Instant>,
    mut on_tick: impl FnMut(&mut super::Node),
    mut tap: impl FnMut(Direction, SocketAddr, &[u8]),
) -> std::io::Result<()> {
    use super::Via;
    use std::sync::mpsc;
    if sockets.component_control.is_none() && sockets.component_data.is_none() {
        return run_tapped(node, sockets.network, io, stop, until, on_tick, tap);
    }
    tracing::info!(bind = ?sockets.network.local_addr().ok(), "up, with OpenJAUS component sockets");
    give_wall_clock(node);
    let (tx, rx) = mpsc::sync_channel::<(Via, SocketAddr, Vec<u8>)>(1024);
    let receivers = [
        (Via::Network, Some(sockets.network)),
        (Via::ComponentControl, sockets.component_control),
        (Via::ComponentData, sockets.component_data),
    ];
    let dropped = std::sync::Arc::new(std::sync::atomic::AtomicU64::new(0));
    let done = std::sync::Arc::new(AtomicBool::new(false));
    // Owned threads (not scoped ones): one that does not stop is reported and left
    // behind instead of holding the node's shutdown forever.
    let mut threads = Vec::new();
    let mut spawned = Ok(());
    for (via, socket) in receivers {
        let Some(socket) = socket else { continue };
        let started = socket.try_clone().and_then(|socket| {
            let (tx, dropped, done) = (tx.clone(), dropped.clone(), done.clone());
            std::thread::Builder::new()
                .name(format!("jaus-rx-{}", via_name(via)))
                .spawn(move || receive(&socket, via, &tx, &dropped, &done))
        });
        match started {
            Ok(h) => threads.push(h),
            Err(e) => {
                spawned = Err(e);
                break;
            }
        }
    }
    drop(tx);
    let result = spawned.and_then(|()| loop {
        if stopping(stop, until) {
            return Ok(());
        }
        let now = Instant::now();
        let wait = next_wait(&*node, now);
        match rx.recv_timeout(wait) {
            Ok((via, peer, bytes)) => match via {
                Via::Network => {
                    tap(Direction::Received, peer, &bytes);
                    node.handle_datagram(Instant::now(), peer, &bytes);
                }
                Via::ComponentControl => {
                    node.handle_component_control(Instant::now(), peer, &bytes)
                }
                Via::ComponentData => node.handle_component_data(Instant::now(), peer, &bytes),
            },
            Err(mpsc::RecvTimeoutError::Timeout) => {}
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                return Err(std::io::Error::other("a socket's receiver stopped"))
            }
        }
        node.handle_timeout(Instant::now());
        on_tick(node);
        while let Some(d) = node.poll_transmit() {
            let socket = match d.via {
                Via::Network => Some(sockets.network),
                Via::ComponentControl => sockets.component_control,
                Via::ComponentData => sockets.component_data,
            };
            let Some(socket) = socket else { continue };
            match socket.send_to(&d.bytes, d.to) {
                Ok(_) if d.via == Via::Network => tap(Direction::Sent, d.to, &d.bytes),
                Ok(_) => {}
                Err(e) => tracing::debug!(to = %d.to, "send failed: {e}"),
            }
            node.recycle(d.bytes);
        }
    });
    // Let the receivers end; each is waited for within the bound.
    done.store(true, Ordering::Relaxed);
    let mut ended = Ok(());
    for h in threads {
        match join_within(h, SHUTDOWN_BOUND) {
            Ok(Ok(())) => {}
            Ok(Err(e)) => tracing::warn!("a receiver ended with an error: {e}"),
            Err(e) => ended = Err(std::io::Error::from(e)),
        }
    }
    result?;
    ended?;
    let lost = dropped.load(Ordering::Relaxed);
    if lost > 0 {
        tracing::warn!("{lost} datagrams dropped: the receive queue was full");
    }
    Ok(())
}

/// The short name of a socket of a node, for thread names and logs.
fn via_name(via: super::Via) -> &'static str {
    match via {
        super::Via::Network => "network",
        super::Via::ComponentControl => "component-control",
        super::Via::ComponentData => "component-data",
    }
}

/// One socket's receiver thread of [`run_node`]: reads (100 ms timeout) into the
/// bounded queue until `done` is set; a full queue drops and counts.
fn receive(
    socket: &UdpSocket,
    via: super::Via,
    tx: &std::sync::mpsc::SyncSender<(super::Via, SocketAddr, Vec<u8>)>,
    dropped: &std::sync::atomic::AtomicU64,
    done: &AtomicBool,
) -> std::io::Result<()> {
    socket.set_read_timeout(Some(Duration::from_millis(100)))?;
    tracing::debug!(socket = via_name(via), local = ?socket.local_addr().ok(), "receiving");
    let mut buf = vec![0u8; MAX_DATAGRAM];
    while !done.load(Ordering::Relaxed) {
        match socket.recv_from(&mut buf) {
            Ok((n, peer)) => {
                if tx.try_send((via, peer, buf[..n].to_vec())).is_err() {
                    dropped.fetch_add(1, Ordering::Relaxed);
                }
            }
            Err(e)
                if matches!(
                    e.kind(),
                    ErrorKind::WouldBlock | ErrorKind::TimedOut | ErrorKind::ConnectionReset
                ) => {}
            Err(e) => return Err(e),
        }
    }
    tracing::debug!(socket = via_name(via), "receiver stopped");
    Ok(())
}

/// The component side of OpenJAUS's check-in: asks the node manager at `control`
/// (its port 24627) for an address for component id `component` from `socket`, and
/// waits up to `timeout` for the answer. OpenJAUS does not answer an id it refuses or
/// when no instance is free: that is a timeout.
pub fn oj_check_in(
    socket: &UdpSocket,
    control: SocketAddr,
    component: u8,
    data_port: u16,
    timeout: Duration,
) -> std::io::Result<crate::Address> {
    use super::oj::Control;
    socket.send_to(
        &Control::CheckIn {
            component,
            data_port,
        }
        .encode(),
        control,
    )?;
    let deadline = Instant::now() + timeout;
    let mut buf = [0u8; 64];
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() {
            return Err(std::io::Error::new(
                ErrorKind::TimedOut,
                format!("no OpenJAUS check-in answer from {control} for component id {component}"),
            ));
        }
        socket.set_read_timeout(Some(left))?;
        match socket.recv_from(&mut buf) {
            Ok((n, from)) if from == control => {
                if let Ok(Control::ReportAddress(a)) = Control::decode(&buf[..n]) {
                    return Ok(a);
                }
            }
            Ok(_) => {}
            Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => {}
            Err(e) => return Err(e),
        }
    }
}
