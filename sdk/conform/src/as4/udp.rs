//! The [`As4Session`] over UDP: the judge's AS5669A stack on a socket, talking to one
//! vehicle's socket (the IOP rules: the vehicle answers from the address and port the
//! request went to), run by the SDK's one I/O loop ([`jaus::net::shell::run_until`]).

use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Message;
use jaus::net::shell::{self, Direction};
use jaus::net::udp::{IoOptions, UdpTransport};

use super::session::{Arrival, As4Session, JudgeStack};
use crate::capture::{wall_now, Tap};

/// The judge on a UDP socket.
#[derive(Debug)]
pub struct UdpAs4Session {
    socket: UdpSocket,
    peer: SocketAddr,
    local: SocketAddr,
    judge: JudgeStack,
    tap: Tap,
    heard: bool,
}

impl UdpAs4Session {
    /// The judge on `socket`, talking to the vehicle at `peer`.
    pub fn new(socket: UdpSocket, peer: SocketAddr) -> Result<Self, String> {
        let local = socket
            .local_addr()
            .map_err(|e| format!("judge socket: {e}"))?;
        Ok(UdpAs4Session {
            socket,
            peer,
            local,
            judge: JudgeStack::new(),
            tap: Tap::default(),
            heard: false,
        })
    }

    /// The socket's local address.
    pub fn local_addr(&self) -> SocketAddr {
        self.local
    }

    /// Runs the socket until a message waits or `until` passed (at least one turn:
    /// what was queued is sent). Every datagram is recorded; a datagram from the
    /// vehicle's address marks it heard.
    fn pump(&mut self, until: Instant) {
        let mut transport = UdpTransport::new(&self.socket, &IoOptions::default());
        let (local, peer) = (self.local, self.peer);
        let (tap, heard) = (&mut self.tap, &mut self.heard);
        let r = shell::run_until(
            &mut self.judge,
            &mut transport,
            until,
            |j| j.has_mail(),
            |dir, addr, bytes| match dir {
                Direction::Received => {
                    *heard |= addr == peer;
                    tap.push(wall_now(), addr, local, bytes);
                }
                Direction::Sent => tap.push(wall_now(), local, addr, bytes),
            },
        );
        if let Err(e) = r {
            // An ICMP error reported on the socket (some systems do): wait a little
            // rather than spin, and keep listening.
            tracing::debug!("jaus conform --as4: socket: {e}");
            std::thread::sleep(Duration::from_millis(5));
        }
    }
}

impl As4Session for UdpAs4Session {
    fn now(&self) -> Instant {
        Instant::now()
    }

    fn send(&mut self, message: As4Message) {
        self.judge.send(self.peer, message);
        self.pump(Instant::now());
    }

    fn recv(&mut self, deadline: Instant) -> Option<Arrival> {
        loop {
            if let Some(a) = self.judge.pop() {
                return Some(a);
            }
            if Instant::now() >= deadline {
                return None;
            }
            self.pump(deadline);
        }
    }

    fn dropped(&self) -> u64 {
        self.judge.dropped()
    }

    fn heard(&self) -> bool {
        self.heard
    }

    fn tap(&mut self) -> &mut Tap {
        &mut self.tap
    }
}
