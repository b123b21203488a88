//! UDP, the carrier of JUDP: a socket (or a node's sockets, with OpenJAUS's component
//! interface) as a [`Transport`], and the calls that run a sans-IO [`Participant`]
//! (a [`Node`](super::Node), [`Attached`](super::Attached) components) on it through
//! the one loop, [`shell::run`].
//!
//! `link` is the Communicator's data link over UDP
//! (`link::UdpLink`), the hardware a node hosting a
//! `jaus::stock::communicator::CommunicatorEndpoint` uses to reach other subsystems
//! through an IP radio or any other socket.

use std::io::ErrorKind;
use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{mpsc, Arc};
use std::time::{Duration, Instant};

use super::{shell, Datagram, Participant, Transport, Via};

pub use super::shell::Direction;

pub mod link;
pub mod shutdown;
mod socket;

pub use shutdown::{join_within, ShutdownError, SHUTDOWN_BOUND};
pub use socket::MAX_BATCH;
use socket::{Receiver, Sender, MAX_DATAGRAM};

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

/// [`run_on`] with `io` options, showing `tap` every datagram received and sent
/// (direction, peer, datagram), e.g. to write a capture.
pub fn run_tapped<P: Participant>(
    node: &mut P,
    socket: &UdpSocket,
    io: &IoOptions,
    stop: &AtomicBool,
    until: Option<Instant>,
    on_tick: impl FnMut(&mut P),
    tap: impl FnMut(Direction, SocketAddr, &[u8]),
) -> std::io::Result<()> {
    let mut transport = UdpTransport::new(socket, io);
    shell::run(node, &mut transport, stop, until, on_tick, tap)
}

/// One UDP socket as a [`Transport`]: batched, spinning reads ([`IoOptions`]); every
/// datagram is the carrier's ([`Via::Network`]).
#[derive(Debug)]
pub struct UdpTransport<'a> {
    socket: &'a UdpSocket,
    receiver: Receiver,
    sender: Sender,
}

impl<'a> UdpTransport<'a> {
    /// The transport over `socket`, reading as `io` says.
    pub fn new(socket: &'a UdpSocket, io: &IoOptions) -> Self {
        Self {
            socket,
            receiver: Receiver::new(io),
            sender: Sender::default(),
        }
    }
}

impl Transport for UdpTransport<'_> {
    type Addr = SocketAddr;

    fn recv<F: FnMut(Via, SocketAddr, &[u8])>(
        &mut self,
        wait: Duration,
        mut on: F,
    ) -> std::io::Result<()> {
        match self.receiver.recv(self.socket, Instant::now(), wait) {
            Ok(n) => {
                for i in 0..n {
                    let (peer, datagram) = self.receiver.datagram(i);
                    on(Via::Network, peer, datagram);
                }
                Ok(())
            }
            // A previous send to a closed port (ICMP unreachable on some systems).
            Err(e) if e.kind() == ErrorKind::ConnectionReset => Ok(()),
            Err(e) => Err(e),
        }
    }

    fn send(&mut self, d: &Datagram) -> std::io::Result<()> {
        self.socket.send_to(&d.bytes, d.to).map(drop)
    }

    fn send_all(&mut self, ds: &[Datagram], done: impl FnMut(usize, std::io::Result<()>)) {
        self.sender.send_all(self.socket, ds, done);
    }

    fn describe(&self) -> String {
        local(self.socket)
    }
}

/// A socket's local address, for logs.
fn local(socket: &UdpSocket) -> String {
    socket
        .local_addr()
        .map_or_else(|e| format!("(unknown: {e})"), |a| a.to_string())
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
pub fn run_node<P: Participant>(
    node: &mut P,
    sockets: NodeSockets<'_>,
    io: &IoOptions,
    stop: &AtomicBool,
    until: Option<Instant>,
    on_tick: impl FnMut(&mut P),
    tap: impl FnMut(Direction, SocketAddr, &[u8]),
) -> std::io::Result<()> {
    if sockets.component_control.is_none() && sockets.component_data.is_none() {
        return run_tapped(node, sockets.network, io, stop, until, on_tick, tap);
    }
    let mut transport = Sockets::start(sockets)?;
    let result = shell::run(node, &mut transport, stop, until, on_tick, tap);
    let ended = transport.finish();
    result?;
    ended
}

/// Several sockets as one [`Transport`]: a receiving thread per socket feeds a bounded
/// queue (a full queue drops and counts); sends go out on the datagram's socket.
struct Sockets<'a> {
    sockets: NodeSockets<'a>,
    rx: mpsc::Receiver<(Via, SocketAddr, Vec<u8>)>,
    threads: Vec<std::thread::JoinHandle<std::io::Result<()>>>,
    dropped: Arc<AtomicU64>,
    done: Arc<AtomicBool>,
}

impl<'a> Sockets<'a> {
    /// Starts a receiver per socket.
    fn start(sockets: NodeSockets<'a>) -> std::io::Result<Self> {
        let (tx, rx) = mpsc::sync_channel::<(Via, SocketAddr, Vec<u8>)>(1024);
        let mut me = Self {
            sockets,
            rx,
            threads: Vec::new(),
            dropped: Arc::new(AtomicU64::new(0)),
            done: Arc::new(AtomicBool::new(false)),
        };
        let receivers = [
            (Via::Network, Some(sockets.network)),
            (Via::ComponentControl, sockets.component_control),
            (Via::ComponentData, sockets.component_data),
        ];
        // Owned threads (not scoped ones): one that does not stop is reported and left
        // behind instead of holding the node's shutdown forever.
        for (via, socket) in receivers {
            let Some(socket) = socket else { continue };
            let started = socket.try_clone().and_then(|socket| {
                let (tx, dropped, done) = (tx.clone(), me.dropped.clone(), me.done.clone());
                std::thread::Builder::new()
                    .name(format!("jaus-rx-{}", via_name(via)))
                    .spawn(move || receive(&socket, via, &tx, &dropped, &done))
            });
            match started {
                Ok(h) => me.threads.push(h),
                Err(e) => {
                    // The receivers already started end with the error.
                    let _ = me.finish();
                    return Err(e);
                }
            }
        }
        Ok(me)
    }

    /// Lets the receivers end, each waited for within the bound.
    fn finish(&mut self) -> std::io::Result<()> {
        self.done.store(true, Ordering::Relaxed);
        let mut ended = Ok(());
        for h in self.threads.drain(..) {
            match join_within(h, SHUTDOWN_BOUND) {
                Ok(Ok(())) => {}
                Ok(Err(e)) => tracing::warn!("a receiver ended with an error: {e}"),
                Err(e) => ended = Err(std::io::Error::from(e)),
            }
        }
        let lost = self.dropped.swap(0, Ordering::Relaxed);
        if lost > 0 {
            tracing::warn!("{lost} datagrams dropped: the receive queue was full");
        }
        ended
    }
}

impl Transport for Sockets<'_> {
    type Addr = SocketAddr;

    fn recv<F: FnMut(Via, SocketAddr, &[u8])>(
        &mut self,
        wait: Duration,
        mut on: F,
    ) -> std::io::Result<()> {
        match self.rx.recv_timeout(wait) {
            Ok((via, peer, bytes)) => {
                on(via, peer, &bytes);
                Ok(())
            }
            Err(mpsc::RecvTimeoutError::Timeout) => Ok(()),
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                Err(std::io::Error::other("a socket's receiver stopped"))
            }
        }
    }

    fn send(&mut self, d: &Datagram) -> std::io::Result<()> {
        let socket = match d.via {
            Via::Network => Some(self.sockets.network),
            Via::ComponentControl => self.sockets.component_control,
            Via::ComponentData => self.sockets.component_data,
        };
        let socket = socket.ok_or_else(|| {
            std::io::Error::new(
                ErrorKind::NotConnected,
                format!("no {} socket", via_name(d.via)),
            )
        })?;
        socket.send_to(&d.bytes, d.to).map(drop)
    }

    fn describe(&self) -> String {
        format!(
            "{}, with OpenJAUS component sockets",
            local(self.sockets.network)
        )
    }
}

impl Drop for Sockets<'_> {
    fn drop(&mut self) {
        if !self.threads.is_empty() {
            let _ = self.finish();
        }
    }
}

/// The short name of a socket of a node, for thread names and logs.
fn via_name(via: Via) -> &'static str {
    match via {
        Via::Network => "network",
        Via::ComponentControl => "component-control",
        Via::ComponentData => "component-data",
    }
}

/// One socket's receiver thread of [`run_node`]: reads (100 ms timeout) into the
/// bounded queue until `done` is set; a full queue drops and counts.
fn receive(
    socket: &UdpSocket,
    via: Via,
    tx: &mpsc::SyncSender<(Via, SocketAddr, Vec<u8>)>,
    dropped: &AtomicU64,
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
