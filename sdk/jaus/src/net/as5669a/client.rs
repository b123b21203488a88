//! [`As4Client`]: an AS-4 client as a [`Participant`]: whole messages queued to send,
//! whole messages received kept in a bounded inbox. For tools and tests that talk
//! AS-4 over any carrier the SDK runs participants on (a UDP socket, the simulated
//! network).

use std::collections::VecDeque;
use std::net::SocketAddr;
use std::time::Instant;

use super::message::As4Message;
use super::stack::{As4Config, As4Stack};
use crate::net::{Datagram, Participant, PeerAddr};

/// Default bound of the inbox (older messages are dropped first, and counted).
pub const DEFAULT_INBOX: usize = 4096;

/// An AS-4 client over an [`As4Stack`]: [`send`](Self::send) queues whole messages for
/// a peer; what arrives waits in the inbox ([`take`](Self::take)), at most
/// [`DEFAULT_INBOX`] messages unless set otherwise, the oldest dropped first and counted
/// ([`dropped`](Self::dropped)).
#[derive(Debug)]
pub struct As4Client<A: PeerAddr = SocketAddr> {
    stack: As4Stack<A>,
    inbox: VecDeque<(A, As4Message)>,
    max_inbox: usize,
    dropped: u64,
}

impl<A: PeerAddr> Default for As4Client<A> {
    fn default() -> Self {
        Self::new(As4Config::default())
    }
}

impl<A: PeerAddr> As4Client<A> {
    /// A client with the transport settings `config`.
    pub fn new(config: As4Config) -> Self {
        Self {
            stack: As4Stack::new(config),
            inbox: VecDeque::new(),
            max_inbox: DEFAULT_INBOX,
            dropped: 0,
        }
    }

    /// Keeps at most `max` received messages.
    pub fn with_inbox(mut self, max: usize) -> Self {
        self.max_inbox = max.max(1);
        self
    }

    /// Queues `messages` for `to`, at the last time the client was given.
    pub fn send(&mut self, to: A, messages: &[As4Message]) {
        self.stack.send(to, messages);
    }

    /// Queues `messages` for `to` at `now` (a command's resend timer starts then).
    pub fn send_at(&mut self, now: Instant, to: A, messages: &[As4Message]) {
        self.stack.send_at(now, to, messages);
    }

    /// Every message received so far, with the peer it came from, oldest first.
    pub fn take(&mut self) -> Vec<(A, As4Message)> {
        self.inbox.drain(..).collect()
    }

    /// Messages dropped because the inbox was full.
    pub fn dropped(&self) -> u64 {
        self.dropped
    }

    /// The transport (its counters).
    pub fn stack(&self) -> &As4Stack<A> {
        &self.stack
    }
}

impl<A: PeerAddr> Participant<A> for As4Client<A> {
    fn handle_datagram(&mut self, now: Instant, peer: A, datagram: &[u8]) {
        if let Ok(ms) = self.stack.receive(now, peer, datagram) {
            for m in ms {
                if self.inbox.len() >= self.max_inbox {
                    self.inbox.pop_front();
                    self.dropped += 1;
                }
                self.inbox.push_back((peer, m));
            }
        }
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.stack.handle_timeout(now);
    }

    fn poll_transmit(&mut self) -> Option<Datagram<A>> {
        self.stack.poll_transmit()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        self.stack.poll_timeout()
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}
