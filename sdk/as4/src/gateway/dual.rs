//! [`DualNode`]: an RA 3.3 node and a [`Gateway`] side by side on one socket, run like
//! any [`Participant`] (the UDP shell of `jaus node`, the simulated network of the
//! tests).
//!
//! The node and the gateway are peers that exchange typed values, as quinn-proto's
//! endpoint and connection do: the gateway is a companion component of the node
//! ([`Node::add_companion`]), so what the node routes to its RA 3.3 address comes out as
//! [`NodeEvent`]s, and what the gateway sends goes into the node with
//! [`Node::handle_companion`]. AS5669A datagrams go to an [`As4Side`] that hands the
//! gateway (and any other endpoint, e.g. a proxy) their messages. After every input the
//! dual node passes values between them until nothing moves, so an RA 3.3 driver's
//! report becomes the AS-4 client's answer in the same call that received it.

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::component::Endpoint;
use jaus::net::as5669a::{As4Config, As4Endpoint, As4Side};
use jaus::net::{Datagram, NetError, Node, NodeEvent, Participant, PeerAddr, Via};

use super::{Gateway, GatewayConfig};
use crate::ra33::Ra33Side;
use crate::service::Service;

/// Most rounds of passing values between node and gateway in one call (each round
/// drains both; two that answered each other forever could not stall the loop).
const MAX_ROUNDS: usize = 64;

/// An RA 3.3 [`Node`] and a [`Gateway`] on one socket: AS5669A datagrams go to the
/// gateway (and the other AS-4 endpoints added), the rest to the node. On every turn
/// the gateway looks for the presented components in the node's system tree when it
/// changed ([`Gateway::refresh`]), so that services appear as RA 3.3 components are
/// discovered.
#[derive(Debug)]
pub struct DualNode<A: PeerAddr = SocketAddr> {
    node: Node<A>,
    gateway: Gateway<A>,
    as4: As4Side<A>,
    /// The tree version the gateway last looked at.
    tree_seen: Option<u64>,
}

impl<A: PeerAddr> DualNode<A> {
    /// `node` with a gateway set up by `config` beside it (at `config.ra33`, a
    /// component address of the node).
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
        node.add_companion(config.ra33)?;
        // Set-point streams go once, even on a node that makes commands arrive.
        for code in crate::ra33::STREAMED {
            node.send_once(config.ra33, *code);
        }
        let mut dual = Self {
            gateway: Gateway::new(config),
            node,
            as4: As4Side::new(transport),
            tree_seen: None,
        };
        let now = dual.node.now();
        dual.settle(now);
        Ok(dual)
    }

    /// With another AS-4 endpoint on the same socket (an
    /// [`As4Proxy`](crate::proxy::As4Proxy): this node is also an AS-4 client of a
    /// vehicle), served the messages for its own id ([`As4Side`]'s routing).
    pub fn with_endpoint(mut self, endpoint: impl As4Endpoint<A>) -> Self {
        self.as4.add_endpoint(endpoint);
        self
    }

    /// With an AS-4 service of the gateway's component that no RA 3.3 component stands
    /// behind, hosted natively ([`Gateway::add_service`]: the demo vehicle's
    /// [Illumination](crate::ugv::IlluminationService) over its simulated lights).
    pub fn with_service(mut self, service: Box<dyn Service<Ra33Side>>) -> Self {
        self.gateway.add_service(service);
        self
    }

    /// The RA 3.3 node.
    pub fn node(&self) -> &Node<A> {
        &self.node
    }

    /// The RA 3.3 node, mutable. A message sent through it reaches the gateway at the
    /// next call into the dual node.
    pub fn node_mut(&mut self) -> &mut Node<A> {
        &mut self.node
    }

    /// The gateway.
    pub fn gateway(&self) -> &Gateway<A> {
        &self.gateway
    }

    /// The AS5669A side of the socket (its stack and counters).
    pub fn as4(&self) -> &As4Side<A> {
        &self.as4
    }

    /// The node, the gateway gone with the dual node (the node still lists its address
    /// until its node manager forgets it).
    pub fn into_node(self) -> Node<A> {
        self.node
    }

    /// Passes values between the node and the gateway until neither has anything for
    /// the other: the node's events to the gateway, the gateway's RA 3.3 messages to
    /// the node, its AS-4 messages to the stack, and the tree when it changed.
    fn settle(&mut self, now: Instant) {
        for _ in 0..MAX_ROUNDS {
            let mut moved = false;
            while let Some(event) = self.node.poll_event() {
                moved = true;
                match event {
                    NodeEvent::Deliver { header, body, .. } => {
                        Endpoint::handle(&mut self.gateway, now, &header, &body);
                        self.node.recycle(body);
                    }
                    NodeEvent::Settled { settled, .. } => {
                        Endpoint::settled(&mut self.gateway, now, settled);
                    }
                    NodeEvent::Forget(gone) => Endpoint::forget(&mut self.gateway, gone),
                }
            }
            let version = self.node.tree_version();
            if self.tree_seen != Some(version) {
                self.tree_seen = Some(version);
                self.gateway.refresh(now, self.node.tree());
                moved = true;
            }
            if Endpoint::poll_timeout(&self.gateway).is_some_and(|t| t <= now) {
                Endpoint::handle_timeout(&mut self.gateway, now);
            }
            while let Some(out) = Endpoint::poll_transmit(&mut self.gateway) {
                moved = true;
                self.node.handle_companion(now, out);
            }
            if As4Endpoint::poll_timeout(&self.gateway).is_some_and(|t| t <= now) {
                self.as4.handle_timeout(now, Some(&mut self.gateway));
            }
            if !moved {
                return;
            }
        }
        tracing::warn!(
            "node and gateway still exchanging after {MAX_ROUNDS} rounds; the rest waits for the next event"
        );
    }
}

impl<A: PeerAddr> Participant<A> for DualNode<A> {
    fn handle_datagram(&mut self, now: Instant, peer: A, datagram: &[u8]) {
        if As4Side::<A>::is_as4(datagram) {
            self.as4
                .handle_datagram(now, peer, datagram, Some(&mut self.gateway));
        } else {
            self.node.handle_datagram(now, peer, datagram);
        }
        self.settle(now);
    }

    fn handle_via(&mut self, now: Instant, via: Via, peer: A, datagram: &[u8]) {
        if via == Via::Network && As4Side::<A>::is_as4(datagram) {
            self.as4
                .handle_datagram(now, peer, datagram, Some(&mut self.gateway));
        } else {
            self.node.handle_via(now, via, peer, datagram);
        }
        self.settle(now);
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.node.handle_timeout(now);
        self.as4.handle_timeout(now, Some(&mut self.gateway));
        self.settle(now);
    }

    fn poll_transmit(&mut self) -> Option<Datagram<A>> {
        self.node
            .poll_transmit()
            .or_else(|| self.as4.poll_transmit())
    }

    fn recycle(&mut self, bytes: Vec<u8>) {
        self.node.recycle(bytes);
    }

    fn poll_timeout(&self) -> Option<Instant> {
        [
            self.node.poll_timeout(),
            Endpoint::poll_timeout(&self.gateway),
            self.as4.poll_timeout(Some(&self.gateway)),
        ]
        .into_iter()
        .flatten()
        .min()
    }

    fn wall_clock(&mut self, now: Instant, utc: Duration) {
        self.node.wall_clock(now, utc);
        As4Endpoint::wall_clock(&mut self.gateway, now, utc);
        self.as4.wall_clock(now, utc);
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }

    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}
