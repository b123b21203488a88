//! The CLI's port on its carrier: a UDP socket (JUDP), or JTCP or JSerial through their
//! `jaus::net::Transport`s, read and written one datagram at a time the way the
//! session reads a socket.

use std::collections::VecDeque;
use std::net::{IpAddr, Ipv4Addr, SocketAddr, SocketAddrV4, UdpSocket};
use std::path::PathBuf;
use std::time::Duration;

use jaus::net::{Datagram, PeerUrl, Transport, Via};

/// What carries the CLI's datagrams, from the `--peer` URLs.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub enum Carrier {
    /// JUDP over UDP (`HOST:PORT`).
    #[default]
    Udp,
    /// JTCP over TCP (`tcp://HOST:PORT`): the peers are dialed.
    Tcp,
    /// JSerial on a tty (`serial:///dev/…?baud=N`).
    Serial {
        /// The tty.
        path: PathBuf,
        /// Its speed.
        baud: u32,
    },
}

/// The address the CLI gives the far end of a serial line, which has none of its
/// own: every datagram from the line comes from it, every datagram to it goes down the
/// line.
pub const SERIAL_FAR_END: SocketAddr = SocketAddr::V4(SocketAddrV4::new(Ipv4Addr::UNSPECIFIED, 0));

/// The carrier and the peers' addresses of `--peer` URLs: all of one transport, at
/// most one serial line (its far end is [`SERIAL_FAR_END`]).
pub fn carrier_of(urls: &[PeerUrl]) -> Result<(Carrier, Vec<SocketAddr>), String> {
    let Some(first) = urls.first() else {
        return Ok((Carrier::Udp, Vec::new()));
    };
    if let Some(other) = urls.iter().find(|u| u.scheme() != first.scheme()) {
        return Err(format!(
            "--peer {first} and --peer {other}: one session speaks one transport (udp, tcp or serial)"
        ));
    }
    match first {
        PeerUrl::Udp(_) | PeerUrl::Tcp(_) => {
            let peers = urls.iter().filter_map(PeerUrl::socket_addr).collect();
            let carrier = if matches!(first, PeerUrl::Tcp(_)) {
                Carrier::Tcp
            } else {
                Carrier::Udp
            };
            Ok((carrier, peers))
        }
        PeerUrl::Serial { path, baud } => {
            if urls.len() > 1 {
                return Err(format!(
                    "--peer {first}: one serial line per session (a line has one far end)"
                ));
            }
            Ok((
                Carrier::Serial {
                    path: path.clone(),
                    baud: *baud,
                },
                vec![SERIAL_FAR_END],
            ))
        }
    }
}

/// Most datagrams a stream port keeps between two reads of the session (more are
/// dropped and counted).
const INBOX: usize = 1024;

/// A transport read one datagram at a time.
#[derive(Debug)]
pub struct Inbox<T: Transport<Addr = SocketAddr>> {
    transport: T,
    queue: VecDeque<(SocketAddr, Vec<u8>)>,
    dropped: u64,
}

impl<T: Transport<Addr = SocketAddr>> Inbox<T> {
    fn new(transport: T) -> Self {
        Self {
            transport,
            queue: VecDeque::new(),
            dropped: 0,
        }
    }

    fn recv(&mut self, wait: Duration) -> std::io::Result<Option<(SocketAddr, Vec<u8>)>> {
        if self.queue.is_empty() {
            let (queue, dropped) = (&mut self.queue, &mut self.dropped);
            self.transport.recv(wait, |_, from, d| {
                if queue.len() < INBOX {
                    queue.push_back((from, d.to_vec()));
                } else {
                    *dropped += 1;
                }
            })?;
        }
        Ok(self.queue.pop_front())
    }
}

/// The CLI's port.
#[derive(Debug)]
pub enum Port {
    /// A UDP socket.
    Udp(UdpSocket),
    /// JTCP.
    Tcp(Box<Inbox<jaus::net::tcp::TcpTransport>>),
    /// JSerial.
    #[cfg(target_os = "linux")]
    Serial(Box<Inbox<jaus::net::serial::SerialTransport<SocketAddr>>>),
}

impl Port {
    /// Opens the port of `carrier`: UDP binds as [`bind_socket`]
    /// says; TCP dials `peers` (and listens on `bind` if given); serial opens the line.
    pub fn open(
        carrier: &Carrier,
        bind: Option<SocketAddr>,
        peers: &[SocketAddr],
    ) -> Result<Port, String> {
        match carrier {
            Carrier::Udp => bind_socket(bind, peers).map(Port::Udp),
            Carrier::Tcp => jaus::net::tcp::TcpTransport::new(jaus::net::tcp::TcpConfig {
                listen: bind,
                peers: peers.to_vec(),
                ..jaus::net::tcp::TcpConfig::default()
            })
            .map(|t| Port::Tcp(Box::new(Inbox::new(t))))
            .map_err(|e| e.to_string()),
            #[cfg(target_os = "linux")]
            Carrier::Serial { path, baud } => jaus::net::serial::SerialTransport::open(
                jaus::net::serial::SerialConfig::new(path, *baud),
                SERIAL_FAR_END,
            )
            .map(|t| Port::Serial(Box::new(Inbox::new(t))))
            .map_err(|e| e.to_string()),
            #[cfg(not(target_os = "linux"))]
            Carrier::Serial { path, .. } => Err(format!(
                "serial://{}: serial lines are supported on Linux only",
                path.display()
            )),
        }
    }

    /// The local address (UDP's socket, TCP's listening socket if any).
    pub fn local_addr(&self) -> Option<SocketAddr> {
        match self {
            Port::Udp(s) => s.local_addr().ok(),
            Port::Tcp(t) => t.transport.local_addr(),
            #[cfg(target_os = "linux")]
            Port::Serial(_) => None,
        }
    }

    /// What the port is, for messages.
    pub fn describe(&self) -> String {
        match self {
            Port::Udp(s) => s.local_addr().map_or("udp".into(), |a| format!("udp {a}")),
            Port::Tcp(t) => t.transport.describe(),
            #[cfg(target_os = "linux")]
            Port::Serial(t) => t.transport.describe(),
        }
    }

    /// Sends one datagram to `to`.
    pub fn send_to(&mut self, bytes: &[u8], to: SocketAddr) -> std::io::Result<()> {
        let d = |bytes: &[u8]| Datagram {
            to,
            bytes: bytes.to_vec(),
            via: Via::Network,
        };
        match self {
            Port::Udp(s) => s.send_to(bytes, to).map(drop),
            Port::Tcp(t) => t.transport.send(&d(bytes)),
            #[cfg(target_os = "linux")]
            Port::Serial(t) => t.transport.send(&d(bytes)),
        }
    }

    /// Waits at most `wait` for one datagram: its length (copied into `buf`, cut to
    /// it) and sender; `None` when the wait ended with none.
    pub fn recv_from(
        &mut self,
        buf: &mut [u8],
        wait: Duration,
    ) -> std::io::Result<Option<(usize, SocketAddr)>> {
        let got = match self {
            Port::Udp(s) => {
                s.set_read_timeout(Some(wait.max(Duration::from_micros(100))))?;
                return match s.recv_from(buf) {
                    Ok((n, from)) => Ok(Some((n, from))),
                    Err(e)
                        if matches!(
                            e.kind(),
                            std::io::ErrorKind::WouldBlock
                                | std::io::ErrorKind::TimedOut
                                | std::io::ErrorKind::ConnectionReset
                                | std::io::ErrorKind::Interrupted
                        ) =>
                    {
                        Ok(None)
                    }
                    Err(e) => Err(e),
                };
            }
            Port::Tcp(t) => t.recv(wait)?,
            #[cfg(target_os = "linux")]
            Port::Serial(t) => t.recv(wait)?,
        };
        Ok(got.map(|(from, d)| {
            let n = d.len().min(buf.len());
            buf[..n].copy_from_slice(&d[..n]);
            (n, from)
        }))
    }
}

/// Picks the local socket: the one asked for, or port 3794 on an address of its own
/// (see the crate docs: JUDP peers answer port 3794 of the sender's address).
pub fn bind_socket(bind: Option<SocketAddr>, peers: &[SocketAddr]) -> Result<UdpSocket, String> {
    if let Some(b) = bind {
        return UdpSocket::bind(b).map_err(|e| format!("cannot bind {b}: {e}"));
    }
    let loopback = !peers.is_empty() && peers.iter().all(|p| p.ip().is_loopback());
    if loopback {
        for x in 2..=254u8 {
            let ip = IpAddr::V4(Ipv4Addr::new(127, 0, 0, x));
            if peers.iter().any(|p| p.ip() == ip) {
                continue;
            }
            if let Ok(s) = UdpSocket::bind(SocketAddr::new(ip, 3794)) {
                return Ok(s);
            }
        }
        return Err("no free port 3794 on 127.0.0.2-254: JUDP peers answer port 3794 of the sender's address; give --bind ADDRESS:3794 with an address of this host".into());
    }
    let any = SocketAddr::new(IpAddr::V4(Ipv4Addr::UNSPECIFIED), 3794);
    UdpSocket::bind(any).map_err(|e| {
        format!("cannot bind {any}: {e}. JUDP peers (OpenJAUS) answer port 3794 of the sender's address, so this tool needs port 3794 on an address of its own: give --bind ADDRESS:3794 (or --bind ADDRESS:0 when the peer is a jaus node, which answers any port)")
    })
}

/// Says why nothing came back when nothing did.
pub fn silence_hint(socket: &SocketAddr, peers: &[SocketAddr], wait: Duration) -> String {
    format!(
        "no datagram from {peers:?} within {:.1} s. Is a node running there? JUDP peers (OpenJAUS) send their answers to port 3794 of the sender's IP address: this tool listened on {socket}{}",
        wait.as_secs_f64(),
        if socket.port() == 3794 {
            "".to_string()
        } else {
            "; bind to port 3794 of an address of your own (--bind 127.0.0.2:3794)".to_string()
        }
    )
}

/// The port as a carrier of the SDK's one I/O loop ([`jaus::net::shell`]): what a
/// client runs until it is done (discovery) goes through the same turns as a node.
impl Transport for Port {
    type Addr = SocketAddr;

    fn recv<F: FnMut(Via, SocketAddr, &[u8])>(
        &mut self,
        wait: Duration,
        mut on: F,
    ) -> std::io::Result<()> {
        let mut buf = [0u8; MAX_DATAGRAM];
        if let Some((n, from)) = self.recv_from(&mut buf, wait)? {
            on(Via::Network, from, &buf[..n]);
        }
        Ok(())
    }

    fn send(&mut self, d: &Datagram) -> std::io::Result<()> {
        self.send_to(&d.bytes, d.to)
    }

    fn describe(&self) -> String {
        Port::describe(self)
    }
}

/// Largest datagram the port reads for the shell (a JUDP datagram carries at most
/// 4096 bytes of packet; TCP and serial hand whole datagrams of the same bound).
const MAX_DATAGRAM: usize = 8 + 4096 + 64;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn peers_are_one_transport_and_one_serial_line_at_most() {
        let p = |s: &str| s.parse::<PeerUrl>().unwrap();
        let (c, peers) = carrier_of(&[p("tcp://127.0.0.1:1"), p("tcp://127.0.0.1:2")]).unwrap();
        assert_eq!((c, peers.len()), (Carrier::Tcp, 2));
        let e = carrier_of(&[p("tcp://127.0.0.1:1"), p("127.0.0.1:2")]).unwrap_err();
        assert!(e.contains("one transport"), "{e}");
        let e = carrier_of(&[p("serial:///dev/a"), p("serial:///dev/b")]).unwrap_err();
        assert!(e.contains("one serial line"), "{e}");
        let (c, peers) = carrier_of(&[p("serial:///dev/a?baud=9600")]).unwrap();
        assert_eq!(
            c,
            Carrier::Serial {
                path: "/dev/a".into(),
                baud: 9600
            }
        );
        assert_eq!(peers, [SERIAL_FAR_END]);
    }
}
