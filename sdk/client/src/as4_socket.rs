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
/// oldest are dropped first and counted, [`dropped`](Self::dropped)).
#[derive(Debug)]
pub struct As4Socket {
    socket: UdpSocket,
    client: As4Client<SocketAddr>,
    pending: VecDeque<As4Message>,
    peer: SocketAddr,
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
        })
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

    /// Runs the socket until a message arrived or `until` passed (at least one turn:
    /// what was queued is sent).
    fn pump(&mut self, until: Instant) -> Result<(), String> {
        let mut transport = UdpTransport::new(&self.socket, &IoOptions::default());
        let pending = &mut self.pending;
        shell::run_until(
            &mut self.client,
            &mut transport,
            until,
            |c| {
                pending.extend(c.take().into_iter().map(|(_, m)| m));
                !pending.is_empty()
            },
            |_, _, _| {},
        )
        .map(drop)
        .map_err(|e| format!("{}: {e}", self.peer))
    }
}
