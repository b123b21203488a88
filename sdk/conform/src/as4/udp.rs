//! The [`As4Session`] over UDP: the judge's AS5669A stack on a socket, talking to one
//! vehicle's socket (the IOP rules: the vehicle answers from the address and port the
//! request went to).

use std::net::{SocketAddr, UdpSocket};
use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Message;

use super::session::{Arrival, As4Session, JudgeStack};
use crate::capture::{wall_now, Tap};

/// Largest datagram read (AS5669A datagrams stay within 4096 bytes; room to spare).
const MAX_DATAGRAM: usize = 65_536;

/// The judge on a UDP socket.
#[derive(Debug)]
pub struct UdpAs4Session {
    socket: UdpSocket,
    peer: SocketAddr,
    local: SocketAddr,
    judge: JudgeStack,
    tap: Tap,
    heard: bool,
    buf: Vec<u8>,
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
            buf: vec![0; MAX_DATAGRAM],
        })
    }

    /// The socket's local address.
    pub fn local_addr(&self) -> SocketAddr {
        self.local
    }

    /// Sends what the stack queued (messages, acknowledgements).
    fn flush(&mut self) {
        while let Some(d) = self.judge.poll_transmit() {
            match self.socket.send_to(&d.bytes, d.to) {
                Ok(_) => self.tap.push(wall_now(), self.local, d.to, &d.bytes),
                Err(e) => tracing::debug!(to = %d.to, "send failed: {e}"),
            }
        }
    }
}

impl As4Session for UdpAs4Session {
    fn now(&self) -> Instant {
        Instant::now()
    }

    fn send(&mut self, message: As4Message) {
        self.judge.send(self.peer, message);
        self.flush();
    }

    fn recv(&mut self, deadline: Instant) -> Option<Arrival> {
        loop {
            if let Some(a) = self.judge.pop() {
                return Some(a);
            }
            let now = Instant::now();
            if now >= deadline {
                return None;
            }
            let until = self
                .judge
                .poll_timeout()
                .map_or(deadline, |t| t.min(deadline));
            let wait = until
                .saturating_duration_since(now)
                .max(Duration::from_millis(1));
            if let Err(e) = self.socket.set_read_timeout(Some(wait)) {
                tracing::warn!("jaus conform --as4: socket: {e}");
                return None;
            }
            match self.socket.recv_from(&mut self.buf) {
                Ok((n, from)) => {
                    let now = Instant::now();
                    self.heard |= from == self.peer;
                    self.tap.push(wall_now(), from, self.local, &self.buf[..n]);
                    self.judge.receive(now, from, &self.buf[..n]);
                    // Acknowledgements the vehicle asked for.
                    self.flush();
                }
                Err(e)
                    if matches!(
                        e.kind(),
                        std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut
                    ) =>
                {
                    self.judge.handle_timeout(Instant::now());
                }
                Err(e) => {
                    // An ICMP error reported on the socket (some systems do): wait a
                    // little rather than spin, and keep listening.
                    tracing::debug!("jaus conform --as4: receive: {e}");
                    std::thread::sleep(Duration::from_millis(5).min(wait));
                }
            }
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
