//! Companion components: components of this node that its owner drives beside it rather
//! than the node driving them inside (the RA 3.3 ↔ AS-4 gateway of `jaus-as4`, which is
//! at once an RA 3.3 component of the node and the AS-4 side of its socket). The node
//! and the owner exchange typed values, as quinn-proto's endpoint and connection do:
//! messages routed to a companion leave the node as [`NodeEvent`]s
//! ([`Node::poll_event`]); what a companion sends enters it through
//! [`Node::handle_companion`], routed at once like any local component's message. No
//! downcast, no wake-up: the owner drains the events after each call into the node.
//!
//! The event queue is bounded ([`NodeConfig::max_outbox`](super::NodeConfig::max_outbox),
//! as the local queue); a message that finds it full is dropped and counted
//! ([`NetStats::companion_queue_full`](super::NetStats::companion_queue_full)).

use std::collections::VecDeque;
use std::time::Instant;

use super::route::Origin;
use super::{NetError, Node, PeerAddr};
use crate::component::Outgoing;
use crate::wire::Header;
use crate::Address;

/// What the node hands to its owner for a companion component.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum NodeEvent {
    /// A message routed to companion `to` (its header's destination may be a broadcast
    /// that covers it).
    Deliver {
        /// The companion the message is for.
        to: Address,
        /// The message's header.
        header: Header,
        /// Its body (hand it back with [`Node::recycle`] once read, to reuse it).
        body: Vec<u8>,
    },
    /// How a command companion `to` sent ended ([`NodeConfig::reliable`](super::NodeConfig::reliable)):
    /// hand it to the companion ([`Endpoint::settled`](crate::component::Endpoint::settled)).
    Settled {
        /// The companion that sent the command.
        to: Address,
        /// The outcome.
        settled: crate::component::Settled,
    },
    /// Component `gone` left the system (its node manager stopped answering, or it
    /// timed out): every companion forgets it, as local components do.
    Forget(Address),
}

/// The companions of a node and the events waiting for their owner.
#[derive(Debug, Default)]
pub(super) struct Companions {
    at: Vec<Address>,
    events: VecDeque<NodeEvent>,
}

impl Companions {
    pub(super) fn contains(&self, a: Address) -> bool {
        self.at.contains(&a)
    }

    pub(super) fn is_empty(&self) -> bool {
        self.at.is_empty()
    }

    pub(super) fn pending(&self) -> bool {
        !self.events.is_empty()
    }
}

impl<A: PeerAddr> Node<A> {
    /// Adds a companion component at `a` (see the module's documentation): the node lists it
    /// in its system tree and routes messages for it to [`poll_event`](Self::poll_event);
    /// the owner feeds what it sends to [`handle_companion`](Self::handle_companion).
    /// The address follows the rule of [`add`](Self::add).
    pub fn add_companion(&mut self, a: Address) -> Result<(), NetError> {
        let taken = self.locals.contains(a) || self.companions.contains(a);
        NetError::check_join(a, self.config.subsystem, self.config.node, taken)?;
        self.manager.add_local(a);
        self.companions.at.push(a);
        Ok(())
    }

    /// The next event for the companions (`None`: none waiting). Drain them after
    /// every call into the node.
    pub fn poll_event(&mut self) -> Option<NodeEvent> {
        self.companions.events.pop_front()
    }

    /// A message companion `out.header.source` sends: routed (to local components,
    /// other companions, the network) before this returns. A message from an address
    /// that is not a companion of this node is dropped (logged).
    pub fn handle_companion(&mut self, now: Instant, out: Outgoing) {
        self.advance(now);
        let from = out.header.source;
        if !self.companions.contains(from) {
            tracing::warn!(source = %from, message = out.name, "not sent: the source is not a companion of this node");
            return;
        }
        match out.body {
            Ok(body) => self.route(out.header, body, Origin::Local),
            Err(e) => {
                self.stats.encode_errors += 1;
                tracing::warn!(message = out.name, code = %out.header.command_code, source = %from, "not sent: {e}");
            }
        }
        self.pump();
    }

    /// Queues the message for each companion its destination covers; true if any.
    pub(super) fn deliver_companions(&mut self, header: &Header, body: &[u8]) -> bool {
        let d = header.destination;
        let mut any = false;
        for i in 0..self.companions.at.len() {
            let to = self.companions.at[i];
            if !d.matches(&to) || header.source == to {
                continue;
            }
            any = true;
            if self.companions.events.len() >= self.config.max_outbox {
                self.stats.companion_queue_full += 1;
                continue;
            }
            let mut copy = self.pool.take();
            copy.extend_from_slice(body);
            self.companions.events.push_back(NodeEvent::Deliver {
                to,
                header: *header,
                body: copy,
            });
        }
        any
    }

    /// Hands companion `to` the outcome of a command it sent (bounded as the other
    /// events).
    pub(super) fn settled_companion(&mut self, to: Address, settled: crate::component::Settled) {
        if self.companions.events.len() >= self.config.max_outbox {
            self.stats.companion_queue_full += 1;
            return;
        }
        self.companions
            .events
            .push_back(NodeEvent::Settled { to, settled });
    }

    /// Tells the companions that `gone` left (one event, whatever their number).
    pub(super) fn forget_companions(&mut self, gone: Address) {
        if self.companions.is_empty() {
            return;
        }
        if self.companions.events.len() >= self.config.max_outbox {
            self.stats.companion_queue_full += 1;
            return;
        }
        self.companions.events.push_back(NodeEvent::Forget(gone));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::codec::Encode;
    use crate::messages::{QueryIdentification, ReportIdentification};
    use crate::net::NodeConfig;
    use crate::JausMessage;

    const COMPANION: Address = Address::new(1, 1, 60, 1);

    fn node() -> (Node<std::net::SocketAddr>, Instant) {
        let t0 = Instant::now();
        let config = NodeConfig {
            subsystem: 1,
            node: 1,
            ..NodeConfig::default()
        };
        (Node::new(config, t0), t0)
    }

    #[test]
    fn a_companion_is_listed_and_hears_what_is_routed_to_it() {
        let (mut n, t0) = node();
        n.add_companion(COMPANION).unwrap();
        n.handle_timeout(t0);
        assert!(n.tree().component(COMPANION).is_some());
        assert!(matches!(
            n.add_companion(COMPANION),
            Err(NetError::Duplicate(_))
        ));
        // The companion asks the node manager who it is; the answer comes back as an
        // event before handle_companion returns.
        let q = QueryIdentification {
            query_field: crate::messages::dynamic_configuration::QueryLevel::Node,
        };
        n.handle_companion(
            t0,
            Outgoing {
                header: Header::new(QueryIdentification::CODE, n.address(), COMPANION),
                name: "QueryIdentification",
                body: q.to_bytes(),
            },
        );
        // (The node manager may also ask the new component who it is.)
        let mut answered = false;
        while let Some(event) = n.poll_event() {
            let NodeEvent::Deliver { to, header, body } = event else {
                continue;
            };
            assert_eq!(to, COMPANION);
            answered |=
                header.command_code == ReportIdentification::CODE && header.source == n.address();
            n.recycle(body);
        }
        assert!(answered, "no answer for the companion");
        assert_eq!(n.poll_event(), None);
    }

    #[test]
    fn only_a_companion_sends_through_it() {
        let (mut n, t0) = node();
        n.add_companion(COMPANION).unwrap();
        let stranger = Address::new(1, 1, 61, 1);
        n.handle_companion(
            t0,
            Outgoing {
                header: Header::new(QueryIdentification::CODE, n.address(), stranger),
                name: "QueryIdentification",
                body: QueryIdentification::default().to_bytes(),
            },
        );
        assert_eq!(n.poll_event(), None);
        assert_eq!(n.stats().delivered_local, 0);
    }
}
