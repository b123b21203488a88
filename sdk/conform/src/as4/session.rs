//! The AS-4 seam: the judge's client speaks AS5669A (JUDP version 2) through an
//! [`As4Session`], which sends whole messages to the vehicle and hands back whole
//! messages by a deadline. [`MemoryAs4Session`] runs the vehicle (any
//! [`Participant`]: a node with an AS-4 side, or a bare [`As4Endpoint`] in an
//! [`As4Host`]) in the same process on a virtual clock; [`super::udp::UdpAs4Session`]
//! talks to a real one. Both keep the datagrams they exchange in a [`Tap`], for a pcap
//! file, as the RA 3.3 sessions do.

use std::collections::VecDeque;
use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::net::as5669a::{As4Config, As4Endpoint, As4Message, As4Stack, As4Stats};
use jaus::net::{Datagram, Participant};

use crate::capture::{wall_now, Recording, Tap};
use crate::memory::{TARGET, TESTER};
use crate::session::MAX_INBOX;

/// A whole AS-4 message received by the judge.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Arrival {
    /// When it arrived (the session's clock).
    pub at: Instant,
    /// The message.
    pub message: As4Message,
}

/// The network as the AS-4 checks see it.
pub trait As4Session {
    /// The session's clock (virtual for [`MemoryAs4Session`]).
    fn now(&self) -> Instant;
    /// Sends `message` to the vehicle's socket (its destination id may be a broadcast
    /// id: discovery).
    fn send(&mut self, message: As4Message);
    /// The next message for the judge, waiting until `deadline` at most.
    fn recv(&mut self, deadline: Instant) -> Option<Arrival>;
    /// Messages not kept because the judge's inbox was full (a flooding vehicle).
    fn dropped(&self) -> u64;
    /// Whether any datagram came from the vehicle's socket.
    fn heard(&self) -> bool;
    /// The session's recording of the datagrams it exchanges.
    fn tap(&mut self) -> &mut Tap;
    /// Keeps every datagram exchanged from now on (for a pcap file).
    fn record(&mut self) {
        self.tap().start();
    }
    /// The datagrams kept since [`record`](As4Session::record), leaving an empty
    /// recording.
    fn take_recording(&mut self) -> Recording {
        self.tap().take()
    }
}

/// The judge's transport: an [`As4Stack`] (parsing, acknowledgements, reassembly) and
/// a bounded inbox of whole messages.
#[derive(Debug)]
pub struct JudgeStack {
    stack: As4Stack<SocketAddr>,
    inbox: VecDeque<Arrival>,
    dropped: u64,
}

impl Default for JudgeStack {
    fn default() -> Self {
        Self::new()
    }
}

impl JudgeStack {
    /// An empty stack with the default AS5669A settings.
    pub fn new() -> Self {
        JudgeStack {
            stack: As4Stack::new(As4Config::default()),
            inbox: VecDeque::new(),
            dropped: 0,
        }
    }

    /// A datagram from `from`: its whole messages go to the inbox (at most
    /// [`MAX_INBOX`] waiting; more are counted as dropped). A datagram that is not
    /// AS5669A (an RA 3.3 one on the same port) or does not parse is counted by the
    /// stack and otherwise ignored.
    pub fn receive(&mut self, now: Instant, from: SocketAddr, datagram: &[u8]) {
        match self.stack.receive(now, from, datagram) {
            Ok(messages) => {
                for message in messages {
                    if self.inbox.len() < MAX_INBOX {
                        self.inbox.push_back(Arrival { at: now, message });
                    } else {
                        self.dropped += 1;
                    }
                }
            }
            Err(e) => tracing::debug!(%from, "jaus conform --as4: datagram ignored: {e}"),
        }
    }

    /// Queues `message` for `to`.
    pub fn send(&mut self, to: SocketAddr, message: As4Message) {
        self.stack.send(to, std::slice::from_ref(&message));
    }

    /// The next datagram to send.
    pub fn poll_transmit(&mut self) -> Option<Datagram<SocketAddr>> {
        self.stack.poll_transmit()
    }

    /// The oldest message waiting.
    pub fn pop(&mut self) -> Option<Arrival> {
        self.inbox.pop_front()
    }

    /// Whether a message waits.
    pub fn has_mail(&self) -> bool {
        !self.inbox.is_empty()
    }

    /// Messages dropped because the inbox was full.
    pub fn dropped(&self) -> u64 {
        self.dropped
    }

    /// The stack's counters.
    pub fn stats(&self) -> As4Stats {
        self.stack.stats()
    }

    /// Expires incomplete messages.
    pub fn handle_timeout(&mut self, now: Instant) {
        self.stack.handle_timeout(now);
    }

    /// When [`handle_timeout`](Self::handle_timeout) is next due.
    pub fn poll_timeout(&self) -> Option<Instant> {
        self.stack.poll_timeout()
    }
}

/// The judge runs on the SDK's one I/O loop ([`jaus::net::shell`]) like any participant.
impl Participant<SocketAddr> for JudgeStack {
    fn handle_datagram(&mut self, now: Instant, peer: SocketAddr, datagram: &[u8]) {
        self.receive(now, peer, datagram);
    }

    fn handle_timeout(&mut self, now: Instant) {
        JudgeStack::handle_timeout(self, now);
    }

    fn poll_transmit(&mut self) -> Option<Datagram<SocketAddr>> {
        JudgeStack::poll_transmit(self)
    }

    fn poll_timeout(&self) -> Option<Instant> {
        JudgeStack::poll_timeout(self)
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}

/// A bare [`As4Endpoint`] on a carrier of its own: an [`As4Stack`] in front of it,
/// so that it can be the vehicle of a [`MemoryAs4Session`] (or a participant of a
/// simulated network) without an RA 3.3 node.
#[derive(Debug)]
pub struct As4Host<E> {
    stack: As4Stack<SocketAddr>,
    endpoint: E,
}

impl<E: As4Endpoint<SocketAddr>> As4Host<E> {
    /// `endpoint` behind a stack with the default settings.
    pub fn new(endpoint: E) -> Self {
        As4Host {
            stack: As4Stack::new(As4Config::default()),
            endpoint,
        }
    }

    /// The endpoint.
    pub fn endpoint(&self) -> &E {
        &self.endpoint
    }

    /// The endpoint, mutable.
    pub fn endpoint_mut(&mut self) -> &mut E {
        &mut self.endpoint
    }
}

impl<E: As4Endpoint<SocketAddr>> Participant<SocketAddr> for As4Host<E> {
    fn handle_datagram(&mut self, now: Instant, peer: SocketAddr, datagram: &[u8]) {
        match self.stack.receive(now, peer, datagram) {
            Ok(messages) if !messages.is_empty() => {
                let replies = self.endpoint.handle(now, peer, messages);
                self.stack.send(peer, &replies);
            }
            Ok(_) => {}
            Err(e) => tracing::debug!(%peer, "AS5669A datagram dropped: {e}"),
        }
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.stack.handle_timeout(now);
        if self.endpoint.poll_timeout().is_some_and(|t| t <= now) {
            for s in self.endpoint.handle_timeout(now) {
                self.stack.send(s.to, std::slice::from_ref(&s.message));
            }
        }
    }

    fn poll_transmit(&mut self) -> Option<Datagram<SocketAddr>> {
        self.stack.poll_transmit()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        [self.stack.poll_timeout(), self.endpoint.poll_timeout()]
            .into_iter()
            .flatten()
            .min()
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}

/// Most datagrams handed over in one pump (two sides answering each other forever
/// cannot hang the session).
const MAX_PUMP: usize = 100_000;

/// The vehicle and the judge in one process on a virtual clock: the vehicle at
/// [`TARGET`], the judge at [`TESTER`]; datagrams cross between them at once and
/// without loss (every byte through both AS5669A stacks).
#[derive(Debug)]
pub struct MemoryAs4Session {
    now: Instant,
    t0: Instant,
    wall0: Duration,
    target: Box<dyn Participant<SocketAddr>>,
    judge: JudgeStack,
    tap: Tap,
    heard: bool,
}

impl MemoryAs4Session {
    /// A session with `target` (a node with an AS-4 side, or an [`As4Host`]) at `t0`;
    /// the vehicle first runs alone for a virtual second (to start up).
    pub fn new(target: impl Participant<SocketAddr>, t0: Instant) -> Self {
        let mut s = MemoryAs4Session {
            now: t0,
            t0,
            wall0: wall_now(),
            target: Box::new(target),
            judge: JudgeStack::new(),
            tap: Tap::default(),
            heard: false,
        };
        s.run_until(t0 + Duration::from_secs(1), false);
        while s.judge.pop().is_some() {}
        s
    }

    /// The vehicle (downcast with `as_any_mut` to look at it after a run).
    pub fn target(&mut self) -> &mut dyn Participant<SocketAddr> {
        self.target.as_mut()
    }

    fn keep(&mut self, from: SocketAddr, to: SocketAddr, bytes: &[u8]) {
        let time = self.wall0 + self.now.saturating_duration_since(self.t0);
        self.tap.push(time, from, to, bytes);
    }

    fn pump(&mut self) {
        for _ in 0..MAX_PUMP {
            let mut moved = false;
            while let Some(d) = self.judge.poll_transmit() {
                moved = true;
                if d.to == TARGET {
                    self.keep(TESTER, TARGET, &d.bytes);
                    self.target.handle_datagram(self.now, TESTER, &d.bytes);
                }
            }
            while let Some(d) = self.target.poll_transmit() {
                moved = true;
                if d.to == TESTER && d.via == jaus::net::Via::Network {
                    self.heard = true;
                    self.keep(TARGET, TESTER, &d.bytes);
                    self.judge.receive(self.now, TARGET, &d.bytes);
                }
                self.target.recycle(d.bytes);
            }
            if !moved {
                return;
            }
        }
    }

    /// Runs both sides until `deadline`, or until the judge has mail when
    /// `stop_on_mail`.
    fn run_until(&mut self, deadline: Instant, stop_on_mail: bool) {
        for _ in 0..MAX_PUMP {
            self.pump();
            if (stop_on_mail && self.judge.has_mail()) || self.now >= deadline {
                return;
            }
            let next = [self.target.poll_timeout(), self.judge.poll_timeout()]
                .into_iter()
                .flatten()
                .min()
                .unwrap_or(deadline);
            // Virtual time moves by at least a microsecond, so a timer that stays due
            // cannot stall the loop.
            self.now = next.max(self.now + Duration::from_micros(1)).min(deadline);
            self.target.handle_timeout(self.now);
            self.judge.handle_timeout(self.now);
        }
    }
}

impl As4Session for MemoryAs4Session {
    fn now(&self) -> Instant {
        self.now
    }
    fn send(&mut self, message: As4Message) {
        self.judge.send(TARGET, message);
        self.pump();
    }
    fn recv(&mut self, deadline: Instant) -> Option<Arrival> {
        if let Some(a) = self.judge.pop() {
            return Some(a);
        }
        self.run_until(deadline, true);
        self.judge.pop()
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
