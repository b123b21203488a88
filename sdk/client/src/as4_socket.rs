//! An AS-4 client on a UDP socket, run by the SDK's one I/O loop
//! ([`jaus::net::shell::run_until`]): what the peer asks to be acknowledged is
//! acknowledged, commands sent reliably are resent on the transport's timer, large
//! messages are split and reassembled, as a node does. The AS-4 link
//! ([`crate::as4_link`]) and `jaus as4-drive` talk through it.

use std::collections::VecDeque;
use std::net::{SocketAddr, UdpSocket};
use std::time::Instant;

use jaus::net::as5669a::{As4Client, As4Config, As4Message};
use jaus::net::shell;
use jaus::net::udp::{IoOptions, UdpTransport};

/// One socket talking AS-4 to the node at `peer`; messages received wait in order
/// until [`next`](Self::next) takes them (at most `As4Client`'s inbox bound; the
/// oldest are dropped first and counted, [`dropped`](Self::dropped)). Only the peer's
/// messages count: a datagram from any other address (a stranger on the network
/// claiming a component's id) is acknowledged by the transport if it asks, then
/// dropped and counted ([`strangers`](Self::strangers)).
#[derive(Debug)]
pub struct As4Socket {
    socket: UdpSocket,
    client: As4Client<SocketAddr>,
    pending: VecDeque<As4Message>,
    peer: SocketAddr,
    strangers: u64,
}

impl As4Socket {
    /// A socket bound to `bind` talking to `peer` with the transport settings `config`.
    pub fn bind(bind: SocketAddr, peer: SocketAddr, config: As4Config) -> Result<Self, String> {
        let socket = UdpSocket::bind(bind).map_err(|e| format!("{bind}: {e}"))?;
        Ok(Self {
            socket,
            client: As4Client::new(config),
            pending: VecDeque::new(),
            peer,
            strangers: 0,
        })
    }

    /// The socket's local address.
    pub fn local_addr(&self) -> Result<SocketAddr, String> {
        self.socket.local_addr().map_err(|e| e.to_string())
    }

    /// The node talked to.
    pub fn peer(&self) -> SocketAddr {
        self.peer
    }

    /// Sends `messages` to the peer now (one turn of the loop).
    pub fn send(&mut self, messages: &[As4Message]) -> Result<(), String> {
        self.client.send_at(Instant::now(), self.peer, messages);
        self.pump(Instant::now())
    }

    /// The oldest message received and not taken yet, waiting for one until `until`.
    pub fn next(&mut self, until: Instant) -> Result<Option<As4Message>, String> {
        loop {
            if let Some(m) = self.pending.pop_front() {
                return Ok(Some(m));
            }
            if Instant::now() >= until {
                return Ok(None);
            }
            self.pump(until)?;
        }
    }

    /// Messages dropped because the client's inbox was full.
    pub fn dropped(&self) -> u64 {
        self.client.dropped()
    }

    /// Messages dropped because they came from another address than the peer's.
    pub fn strangers(&self) -> u64 {
        self.strangers
    }

    /// Runs the socket until a message arrived or `until` passed (at least one turn:
    /// what was queued is sent).
    fn pump(&mut self, until: Instant) -> Result<(), String> {
        let mut transport = UdpTransport::new(&self.socket, &IoOptions::default());
        let (pending, strangers, peer) = (&mut self.pending, &mut self.strangers, self.peer);
        shell::run_until(
            &mut self.client,
            &mut transport,
            until,
            |c| {
                for (from, m) in c.take() {
                    if from == peer {
                        pending.push_back(m);
                    } else {
                        *strangers += 1;
                        tracing::debug!(%from, %peer, "AS-4 message from another address than the peer's dropped");
                    }
                }
                !pending.is_empty()
            },
            |_, _, _| {},
        )
        .map(drop)
        .map_err(|e| format!("{}: {e}", self.peer))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use jaus::net::as5669a::{As4Id, As4Stack};
    use std::time::Duration;

    /// The datagram carrying `m` from a stack of its own.
    fn datagram(m: As4Message, to: SocketAddr) -> Vec<u8> {
        let mut stack: As4Stack<SocketAddr> = As4Stack::new(As4Config::default());
        stack.send(to, &[m]);
        stack.poll_transmit().expect("one datagram").bytes
    }

    #[test]
    fn only_the_peers_messages_are_taken_and_a_strangers_are_counted() {
        let peer = UdpSocket::bind("127.0.0.1:0").unwrap();
        let stranger = UdpSocket::bind("127.0.0.1:0").unwrap();
        let mut s = As4Socket::bind(
            "127.0.0.1:0".parse().unwrap(),
            peer.local_addr().unwrap(),
            As4Config::default(),
        )
        .unwrap();
        let me = s.local_addr().unwrap();
        let vehicle = As4Id::new(1, 1, 1);
        let forged = As4Message::new(0x4002, As4Id::new(42, 1, 1), vehicle, vec![1, 0, 0, 0, 0]);
        let real = As4Message::new(0x4002, As4Id::new(42, 1, 1), vehicle, vec![2, 0, 0, 0, 0]);
        stranger.send_to(&datagram(forged, me), me).unwrap();
        peer.send_to(&datagram(real.clone(), me), me).unwrap();
        let got = s.next(Instant::now() + Duration::from_secs(2)).unwrap();
        assert_eq!(got.map(|m| m.body), Some(real.body));
        assert_eq!(s.strangers(), 1);
        assert!(s
            .next(Instant::now() + Duration::from_millis(50))
            .unwrap()
            .is_none());
    }
}
