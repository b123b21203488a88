//! The [`Session`] over UDP: the tester's node (its own node manager, the four voices)
//! on a socket, driven by the SDK's one I/O loop ([`jaus::net::shell::run`] over
//! [`UdpTransport`]) until a voice has mail or the deadline passes.

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use jaus::net::udp::{IoOptions, UdpTransport};
use jaus::net::{shell, Datagram, Framing, Node, NodeConfig, Transport, Via};
use jaus::{Address, Header};

use crate::capture::{wall_now, Tap};
use crate::session::{dropped, pop, tester_node, Inbox, Incoming, Session, Voices};

/// A transport whose waits end by `until`: the shell waits until the node's next timer,
/// which may be later than the session's deadline (a watch polling every few
/// milliseconds needs its waits to end on time).
struct Until<T> {
    inner: T,
    until: Instant,
}

impl<T: Transport> Transport for Until<T> {
    type Addr = T::Addr;

    fn recv<F: FnMut(Via, Self::Addr, &[u8])>(
        &mut self,
        wait: Duration,
        on: F,
    ) -> std::io::Result<()> {
        let left = self.until.saturating_duration_since(Instant::now());
        self.inner
            .recv(wait.min(left.max(Duration::from_micros(100))), on)
    }

    fn send(&mut self, d: &Datagram<Self::Addr>) -> std::io::Result<()> {
        self.inner.send(d)
    }

    fn send_all(
        &mut self,
        ds: &[Datagram<Self::Addr>],
        done: impl FnMut(usize, std::io::Result<()>),
    ) {
        self.inner.send_all(ds, done);
    }

    fn describe(&self) -> String {
        self.inner.describe()
    }
}

/// The tester on a UDP socket.
#[derive(Debug)]
pub struct UdpSession {
    socket: UdpSocket,
    node: Node,
    inbox: Inbox,
    peers: Vec<SocketAddr>,
    framing: Framing,
    io: IoOptions,
    heard: bool,
    tap: Tap,
    local: SocketAddr,
}

impl UdpSession {
    /// The tester's node at `voices`' subsystem and node on `socket`, talking to
    /// `peers` (the target's node, and any other node to discover).
    pub fn new(
        socket: UdpSocket,
        peers: Vec<SocketAddr>,
        framing: Framing,
        voices: &Voices,
    ) -> Result<Self, String> {
        let inbox = Inbox::default();
        let mut config = NodeConfig {
            subsystem: voices.controller.subsystem,
            node: voices.controller.node,
            framing,
            peers: peers.clone(),
            ..NodeConfig::default()
        };
        config.manager.node_name = "jaus conform".into();
        config.manager.subsystem_name = "jaus conform".into();
        let node = tester_node(config, voices, &inbox, Instant::now())?;
        let local = socket
            .local_addr()
            .map_err(|e| format!("tester socket: {e}"))?;
        Ok(UdpSession {
            socket,
            node,
            inbox,
            peers,
            framing,
            io: IoOptions::default(),
            heard: false,
            tap: Tap::default(),
            local,
        })
    }

    fn keep(&mut self, sent: bool, peer: SocketAddr, bytes: &[u8]) {
        let (from, to) = if sent {
            (self.local, peer)
        } else {
            (peer, self.local)
        };
        self.tap.push(wall_now(), from, to, bytes);
    }

    /// Runs the node for `wait` (its node manager discovers the system), then the
    /// components the system tree lists.
    pub fn discover(&mut self, wait: Duration) -> Vec<Address> {
        self.drive(Instant::now() + wait, false);
        if let Ok(mut q) = self.inbox.lock() {
            q.clear();
        }
        self.node.tree().components()
    }

    /// Whether any datagram came from a peer.
    pub fn heard(&self) -> bool {
        self.heard
    }

    /// The socket's local address.
    pub fn local_addr(&self) -> Option<SocketAddr> {
        self.socket.local_addr().ok()
    }

    fn drive(&mut self, deadline: Instant, stop_on_mail: bool) {
        let stop = AtomicBool::new(false);
        let inbox = self.inbox.clone();
        let peers = self.peers.clone();
        let mut heard = false;
        let (tap, local) = (&mut self.tap, self.local);
        let mut transport = Until {
            inner: UdpTransport::new(&self.socket, &self.io),
            until: deadline,
        };
        let r = shell::run(
            &mut self.node,
            &mut transport,
            &stop,
            Some(deadline),
            |_| {
                if stop_on_mail && inbox.lock().is_ok_and(|q| !q.is_empty()) {
                    stop.store(true, Ordering::Relaxed);
                }
            },
            |dir, peer, bytes| {
                let received = dir == shell::Direction::Received;
                if received && peers.contains(&peer) {
                    heard = true;
                }
                let (from, to) = if received {
                    (peer, local)
                } else {
                    (local, peer)
                };
                tap.push(wall_now(), from, to, bytes);
            },
        );
        self.heard |= heard;
        if let Err(e) = r {
            tracing::warn!("jaus conform: socket error: {e}");
        }
    }

    /// The socket of `to`'s node: the one the tester's node located, else the first
    /// peer.
    fn socket_of(&self, to: Address) -> Option<SocketAddr> {
        self.node
            .peers()
            .get(&(to.subsystem, to.node))
            .copied()
            .or(self.peers.first().copied())
    }
}

impl Session for UdpSession {
    fn now(&self) -> Instant {
        Instant::now()
    }
    fn utc(&self) -> Duration {
        wall_now()
    }
    fn send(&mut self, header: Header, body: Vec<u8>) {
        self.node.send(Instant::now(), header, body);
        while let Some(d) = self.node.poll_transmit() {
            match self.socket.send_to(&d.bytes, d.to) {
                Ok(_) => self.keep(true, d.to, &d.bytes),
                Err(e) => tracing::debug!(to = %d.to, "send failed: {e}"),
            }
            self.node.recycle(d.bytes);
        }
    }
    fn send_raw(&mut self, to: Address, packet: Vec<u8>) {
        if let Some(peer) = self.socket_of(to) {
            let bytes = self.framing.encode(&packet);
            match self.socket.send_to(&bytes, peer) {
                Ok(_) => self.keep(true, peer, &bytes),
                Err(e) => tracing::debug!(to = %peer, "send failed: {e}"),
            }
        }
    }
    fn tap(&mut self) -> &mut Tap {
        &mut self.tap
    }
    fn dropped(&self) -> u64 {
        dropped(&self.inbox)
    }
    fn recv(&mut self, deadline: Instant) -> Option<Incoming> {
        if let Some(p) = pop(&self.inbox) {
            return Some(p);
        }
        if Instant::now() < deadline {
            self.drive(deadline, true);
        }
        pop(&self.inbox)
    }
}
