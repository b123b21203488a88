//! One socket, both generations. [`As4Mux`] wraps a host of the RA 3.3 side (a
//! [`Node`](crate::net::Node), or any [`Participant`]) and looks at the first byte of
//! every datagram on the carrier: version 2 goes to the AS5669A side, everything else
//! (version 1, "JAUS01.0") to the host, untouched. The AS5669A side is the sans-IO
//! [`As4Stack`] (parsing, acknowledgements, reassembly, splitting, sequence numbers,
//! packing several messages per datagram) and an [`As4Endpoint`] the host supplies,
//! which sees whole messages and answers with whole messages; its replies are framed as
//! AS5669A and leave from the same socket for the sender.
//!
//! Without a mux nothing changes: a node counts a version-2 datagram as a framing error,
//! as before.

use std::net::SocketAddr;
use std::time::Instant;

use super::datagram::Generation;
use super::header::As4Id;
pub use super::message::As4Message;
pub use super::stack::{As4Config, As4Stack, As4Stats};
use crate::net::{Datagram, Participant, PeerAddr, Via};

/// A message for a peer, from an [`As4Endpoint`]'s timer.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct As4Send<A> {
    /// The peer.
    pub to: A,
    /// The message.
    pub message: As4Message,
}

/// The AS-4 side of a host, sans-IO: it is handed whole messages with the peer they
/// came from and answers with whole messages, which go back to that peer.
pub trait As4Endpoint<A: PeerAddr = SocketAddr>: std::fmt::Debug + Send + 'static {
    /// `messages` (whole, in order) came from `from` at `now`; the answers go to `from`.
    fn handle(&mut self, now: Instant, from: A, messages: Vec<As4Message>) -> Vec<As4Message>;
    /// Time passed ([`poll_timeout`](Self::poll_timeout) is due); messages to send.
    fn handle_timeout(&mut self, now: Instant) -> Vec<As4Send<A>> {
        let _ = now;
        Vec::new()
    }
    /// When [`handle_timeout`](Self::handle_timeout) must next be called (default
    /// never).
    fn poll_timeout(&self) -> Option<Instant> {
        None
    }
    /// The wall clock: UTC (since 1970-01-01) is `utc` at `now` (default: ignored).
    fn wall_clock(&mut self, now: Instant, utc: std::time::Duration) {
        let _ = (now, utc);
    }
    /// Whether messages for `destination` are this endpoint's: an [`As4Mux`] with
    /// several endpoints hands each one the messages it serves (default: every
    /// message, for a mux with one endpoint).
    fn serves(&self, destination: As4Id) -> bool {
        let _ = destination;
        true
    }
}

/// The AS-4 side of a socket: the [`As4Stack`] and the endpoints that answer AS5669A
/// peers, sans-IO. [`As4Mux`] puts one beside any RA 3.3 host; a host that owns an
/// endpoint of its own (the RA 3.3 ↔ AS-4 gateway of `jaus-as4`, which is also a
/// component of its node) passes it to each call as `first`, so that nothing has to
/// find it inside anything.
///
/// **Several endpoints on one socket.** A node may answer AS-4 clients (a gateway
/// presenting its RA 3.3 components) and be an AS-4 client of other vehicles (a proxy
/// presenting them as RA 3.3 components) at once. Each endpoint (`first`, then those
/// added with [`add_endpoint`](Self::add_endpoint)) gets the received messages whose
/// destination it [serves](As4Endpoint::serves), in order (a broadcast destination may
/// be served by several); their answers go back to the sender. A message no endpoint
/// serves is dropped and counted ([`unrouted`](Self::unrouted)). Every endpoint's timer
/// is run.
#[derive(Debug)]
pub struct As4Side<A: PeerAddr = SocketAddr> {
    stack: As4Stack<A>,
    endpoints: Vec<Box<dyn As4Endpoint<A>>>,
    unrouted: u64,
}

impl<A: PeerAddr> As4Side<A> {
    /// A stack set up by `config`, no endpoint yet.
    pub fn new(config: As4Config) -> Self {
        Self {
            stack: As4Stack::new(config),
            endpoints: Vec::new(),
            unrouted: 0,
        }
    }

    /// Adds an endpoint after those already there.
    pub fn add_endpoint(&mut self, endpoint: impl As4Endpoint<A>) {
        self.endpoints.push(Box::new(endpoint));
    }

    /// Endpoint `i` of those added, in order (`None` past the end).
    pub fn endpoint_at(&self, i: usize) -> Option<&dyn As4Endpoint<A>> {
        self.endpoints.get(i).map(|e| e.as_ref())
    }

    /// Messages received that no endpoint serves (dropped).
    pub fn unrouted(&self) -> u64 {
        self.unrouted
    }

    /// The AS5669A stack.
    pub fn stack(&self) -> &As4Stack<A> {
        &self.stack
    }

    /// The AS5669A stack, mutable (e.g. to send a message of one's own).
    pub fn stack_mut(&mut self) -> &mut As4Stack<A> {
        &mut self.stack
    }

    /// Whether `datagram` is for the AS5669A side.
    pub fn is_as4(datagram: &[u8]) -> bool {
        Generation::of(datagram) == Generation::As5669a
    }

    /// An AS5669A datagram arrived from `from`: its whole messages go to the endpoints
    /// that serve them (`first`, then the added ones); their answers are queued for
    /// `from`.
    pub fn handle_datagram(
        &mut self,
        now: Instant,
        from: A,
        datagram: &[u8],
        first: Option<&mut dyn As4Endpoint<A>>,
    ) {
        let messages = match self.stack.receive(now, from, datagram) {
            Ok(m) => m,
            Err(e) => {
                tracing::debug!(%from, "AS5669A datagram dropped: {e}");
                return;
            }
        };
        if messages.is_empty() {
            return;
        }
        let mut routed = vec![false; messages.len()];
        let mut replies = Vec::new();
        let owned = self.endpoints.iter_mut().map(|e| e.as_mut());
        for endpoint in first.into_iter().chain(owned) {
            let batch: Vec<As4Message> = messages
                .iter()
                .zip(routed.iter_mut())
                .filter(|(m, _)| endpoint.serves(m.destination))
                .map(|(m, r)| {
                    *r = true;
                    m.clone()
                })
                .collect();
            if !batch.is_empty() {
                replies.extend(endpoint.handle(now, from, batch));
            }
        }
        let lost = routed.iter().filter(|r| !**r).count() as u64;
        if lost > 0 {
            self.unrouted += lost;
            tracing::debug!(%from, lost, "AS5669A messages dropped: no AS-4 endpoint serves their destination");
        }
        self.stack.send(from, &replies);
    }

    /// Time passed: the stack's timers (retransmissions, reassembly) and every due
    /// endpoint's (`first` included); what they send is queued.
    pub fn handle_timeout(&mut self, now: Instant, first: Option<&mut dyn As4Endpoint<A>>) {
        self.stack.handle_timeout(now);
        let owned = self.endpoints.iter_mut().map(|e| e.as_mut());
        for e in first.into_iter().chain(owned) {
            if e.poll_timeout().is_some_and(|t| t <= now) {
                for s in e.handle_timeout(now) {
                    self.stack.send(s.to, std::slice::from_ref(&s.message));
                }
            }
        }
    }

    /// The next datagram to send.
    pub fn poll_transmit(&mut self) -> Option<Datagram<A>> {
        self.stack.poll_transmit()
    }

    /// When [`handle_timeout`](Self::handle_timeout) must next be called.
    pub fn poll_timeout(&self, first: Option<&dyn As4Endpoint<A>>) -> Option<Instant> {
        let owned = self.endpoints.iter().map(|e| e.as_ref());
        first
            .into_iter()
            .chain(owned)
            .filter_map(|e| e.poll_timeout())
            .chain(self.stack.poll_timeout())
            .min()
    }

    /// The wall clock, for the added endpoints (a host passes it to its own).
    pub fn wall_clock(&mut self, now: Instant, utc: std::time::Duration) {
        for e in &mut self.endpoints {
            e.wall_clock(now, utc);
        }
    }
}

/// A host of RA 3.3 (`P`, e.g. a [`Node`](crate::net::Node)) and an [`As4Side`] on one
/// carrier: version-2 datagrams go to the AS-4 side, all others to the host. Run it
/// like the host ([`shell::run`](crate::net::shell::run),
/// [`udp::run_on`](crate::net::udp::run_on)); [`inner`](Self::inner) reaches the host.
#[derive(Debug)]
pub struct As4Mux<P, A: PeerAddr = SocketAddr> {
    inner: P,
    side: As4Side<A>,
}

impl<P: Participant<A> + 'static, A: PeerAddr> As4Mux<P, A> {
    /// `inner` on the carrier, with `endpoint` answering AS5669A peers.
    pub fn new(inner: P, endpoint: impl As4Endpoint<A>, config: As4Config) -> Self {
        let mut side = As4Side::new(config);
        side.add_endpoint(endpoint);
        Self { inner, side }
    }

    /// With another endpoint after those already there (see [`As4Side`] for how
    /// messages are shared out).
    pub fn with_endpoint(mut self, endpoint: impl As4Endpoint<A>) -> Self {
        self.side.add_endpoint(endpoint);
        self
    }

    /// Adds an endpoint (as [`with_endpoint`](Self::with_endpoint)).
    pub fn add_endpoint(&mut self, endpoint: impl As4Endpoint<A>) {
        self.side.add_endpoint(endpoint);
    }

    /// Messages received that no endpoint serves (dropped).
    pub fn unrouted(&self) -> u64 {
        self.side.unrouted()
    }

    /// The RA 3.3 host.
    pub fn inner(&self) -> &P {
        &self.inner
    }

    /// The RA 3.3 host, mutable.
    pub fn inner_mut(&mut self) -> &mut P {
        &mut self.inner
    }

    /// The RA 3.3 host, the mux taken apart.
    pub fn into_inner(self) -> P {
        self.inner
    }

    /// The AS-4 side (stack, endpoints, counters).
    pub fn side(&self) -> &As4Side<A> {
        &self.side
    }

    /// The AS5669A side.
    pub fn stack(&self) -> &As4Stack<A> {
        self.side.stack()
    }

    /// The AS5669A side, mutable (e.g. to send a message of one's own).
    pub fn stack_mut(&mut self) -> &mut As4Stack<A> {
        self.side.stack_mut()
    }

    /// The first endpoint, for a caller that knows its type.
    pub fn endpoint(&self) -> Option<&dyn As4Endpoint<A>> {
        self.side.endpoint_at(0)
    }

    /// Endpoint `i` in the order they were added (`None` past the end).
    pub fn endpoint_at(&self, i: usize) -> Option<&dyn As4Endpoint<A>> {
        self.side.endpoint_at(i)
    }

    /// Whether `datagram` is for the AS5669A side.
    pub fn is_as4(datagram: &[u8]) -> bool {
        As4Side::<A>::is_as4(datagram)
    }
}

impl<P: Participant<A> + 'static, A: PeerAddr> Participant<A> for As4Mux<P, A> {
    fn handle_datagram(&mut self, now: Instant, peer: A, datagram: &[u8]) {
        if Self::is_as4(datagram) {
            self.side.handle_datagram(now, peer, datagram, None);
        } else {
            self.inner.handle_datagram(now, peer, datagram);
        }
    }

    fn handle_via(&mut self, now: Instant, via: Via, peer: A, datagram: &[u8]) {
        if via == Via::Network && Self::is_as4(datagram) {
            self.side.handle_datagram(now, peer, datagram, None);
        } else {
            self.inner.handle_via(now, via, peer, datagram);
        }
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.inner.handle_timeout(now);
        self.side.handle_timeout(now, None);
    }

    fn poll_transmit(&mut self) -> Option<Datagram<A>> {
        self.inner
            .poll_transmit()
            .or_else(|| self.side.poll_transmit())
    }

    fn recycle(&mut self, bytes: Vec<u8>) {
        self.inner.recycle(bytes);
    }

    fn poll_timeout(&self) -> Option<Instant> {
        [self.inner.poll_timeout(), self.side.poll_timeout(None)]
            .into_iter()
            .flatten()
            .min()
    }

    fn wall_clock(&mut self, now: Instant, utc: std::time::Duration) {
        self.inner.wall_clock(now, utc);
        self.side.wall_clock(now, utc);
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::net::as5669a::header::Broadcast;
    use crate::net::as5669a::parse_datagram;

    /// The properties byte of every message of the datagrams `stack` queued.
    fn broadcast_fields(stack: &mut As4Stack<SocketAddr>) -> Vec<(As4Id, Broadcast)> {
        std::iter::from_fn(|| stack.poll_transmit())
            .flat_map(|d| parse_datagram(&d.bytes).expect("the stack writes datagrams it reads"))
            .map(|p| (p.header.destination, p.header.broadcast))
            .collect()
    }

    #[test]
    fn a_message_to_a_wildcard_id_goes_out_as_a_global_broadcast() {
        let peer: SocketAddr = "127.0.0.1:3794".parse().unwrap();
        let me = As4Id::new(42, 1, 1);
        let wildcards = [
            As4Id::new(0xFFFF, 0xFF, 0xFF),
            As4Id::new(0xFFFF, 1, 1),
            As4Id::new(7, 0xFF, 1),
            As4Id::new(7, 1, 0xFF),
        ];
        let unicast = As4Id::new(7, 1, 1);
        let mut stack = As4Stack::new(As4Config::default());
        let mut messages: Vec<As4Message> = wildcards
            .iter()
            .map(|to| As4Message::new(0x2B00, *to, me, vec![2]))
            .collect();
        messages.push(As4Message::new(0x2B00, unicast, me, vec![2]));
        // A large message to every component: each of its packets is marked.
        messages.push(As4Message::new(0x4002, wildcards[0], me, vec![0xAB; 9000]));
        stack.send(peer, &messages);
        let got = broadcast_fields(&mut stack);
        assert_eq!(got.len(), 5 + 3, "{got:?}");
        for (to, broadcast) in &got {
            let want = if *to == unicast {
                Broadcast::None
            } else {
                Broadcast::Global
            };
            assert_eq!(*broadcast, want, "to {to}");
        }
        // On the wire: bits 3-2 of the properties byte (the byte after the data size).
        let mut stack = As4Stack::new(As4Config::default());
        stack.send(peer, &messages[..1]);
        let d = stack.poll_transmit().unwrap();
        assert_eq!((d.bytes[4] >> 2) & 3, 2);
        stack.send(peer, &messages[4..5]);
        let d = stack.poll_transmit().unwrap();
        assert_eq!((d.bytes[4] >> 2) & 3, 0);
        // A reply to a broadcast goes back to its sender alone.
        let reply = messages[0].reply(0x4B00, vec![]);
        assert_eq!((reply.destination, reply.broadcast), (me, Broadcast::None));
    }
}
