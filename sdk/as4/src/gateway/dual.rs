//! [`DualNode`]: an RA 3.3 node with a [`Gateway`] on its socket, run like any
//! [`Participant`] (the UDP shell of `jaus node`, the simulated network of the tests).

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::net::as5669a::{As4Config, As4Endpoint, As4Mux};
use jaus::net::{Datagram, NetError, Node, Participant, PeerAddr, Via};
use jaus::Address;

use super::{Gateway, GatewayConfig, InNode};

/// An RA 3.3 [`Node`] hosting a [`Gateway`], with AS5669A datagrams of its socket going
/// to the gateway ([`As4Mux::hosted`]). On every turn it lets the gateway look for the
/// presented components in the node's system tree ([`Gateway::refresh_in`]), so that
/// services appear as RA 3.3 components are discovered.
#[derive(Debug)]
pub struct DualNode<A: PeerAddr = SocketAddr> {
    mux: As4Mux<Node<A>, A>,
    at: Address,
}

impl<A: PeerAddr> DualNode<A> {
    /// `node` with a gateway set up by `config` added to it (at `config.ra33`).
    pub fn new(node: Node<A>, config: GatewayConfig) -> Result<Self, NetError> {
        Self::with_transport(node, config, As4Config::default())
    }

    /// [`new`](Self::new) with the AS5669A side's settings `transport` (e.g. messages
    /// that arrive, [`As4Config::reliable`]).
    pub fn with_transport(
        mut node: Node<A>,
        config: GatewayConfig,
        transport: As4Config,
    ) -> Result<Self, NetError> {
        let at = config.ra33;
        node.add(Gateway::<A>::new(config))?;
        let mut dual = Self {
            mux: As4Mux::hosted(node, InNode(at), transport),
            at,
        };
        let now = dual.mux.inner().now();
        dual.refresh(now);
        Ok(dual)
    }

    /// With another AS-4 endpoint on the same socket (an
    /// [`As4Proxy`](crate::proxy::As4Proxy): this node is also an AS-4 client of a
    /// vehicle), served the messages for its own id ([`As4Mux`]'s routing).
    pub fn with_endpoint(mut self, endpoint: impl As4Endpoint<A>) -> Self {
        self.mux.add_endpoint(endpoint);
        self
    }

    /// The RA 3.3 node.
    pub fn node(&self) -> &Node<A> {
        self.mux.inner()
    }

    /// The RA 3.3 node, mutable.
    pub fn node_mut(&mut self) -> &mut Node<A> {
        self.mux.inner_mut()
    }

    /// The gateway.
    pub fn gateway(&self) -> Option<&Gateway<A>> {
        self.mux.inner().get::<Gateway<A>>(self.at)
    }

    /// The AS5669A side of the socket (its counters).
    pub fn mux(&self) -> &As4Mux<Node<A>, A> {
        &self.mux
    }

    /// The node, the gateway still in it.
    pub fn into_node(self) -> Node<A> {
        self.mux.into_inner()
    }

    fn refresh(&mut self, now: Instant) {
        Gateway::refresh_in(self.mux.inner_mut(), self.at, now);
    }
}

impl<A: PeerAddr> Participant<A> for DualNode<A> {
    fn handle_datagram(&mut self, now: Instant, peer: A, datagram: &[u8]) {
        self.mux.handle_datagram(now, peer, datagram);
        self.refresh(now);
    }

    fn handle_via(&mut self, now: Instant, via: Via, peer: A, datagram: &[u8]) {
        self.mux.handle_via(now, via, peer, datagram);
        self.refresh(now);
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.mux.handle_timeout(now);
        self.refresh(now);
    }

    fn poll_transmit(&mut self) -> Option<Datagram<A>> {
        self.mux.poll_transmit()
    }

    fn recycle(&mut self, bytes: Vec<u8>) {
        self.mux.recycle(bytes);
    }

    fn poll_timeout(&self) -> Option<Instant> {
        self.mux.poll_timeout()
    }

    fn wall_clock(&mut self, now: Instant, utc: Duration) {
        self.mux.wall_clock(now, utc);
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}
