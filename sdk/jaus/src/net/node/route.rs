//! Routing as a decision: where one message goes is a pure function of the node's
//! place in the system (its subsystem, node and the subsystem's Communicator), the
//! message's addresses and where it came from. The node applies the [`Decision`]
//! (delivers, sends, hands to the gateway, counts); nothing here does I/O or holds
//! state, so every rule of Part 1's Figure 5-1 is tested on values.

use crate::Address;

/// Where a message being routed comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Origin {
    /// A component of this node (built-in or external).
    Local,
    /// Another node, through the node's carrier.
    Network,
    /// Another subsystem, through this node's communicator.
    Link,
}

impl Origin {
    /// For logs.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Origin::Local => "here",
            Origin::Network => "network",
            Origin::Link => "communicator",
        }
    }
}

/// The node's place in the system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Scope {
    /// This node's subsystem.
    pub subsystem: u8,
    /// This node's id.
    pub node: u8,
    /// The subsystem's Communicator, when messages between subsystems go through it.
    pub communicator: Option<Address>,
}

/// What to do with one message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Decision {
    /// For components of this node.
    pub here: bool,
    /// Send it over the carrier toward this (subsystem, node); 255 in either is a
    /// broadcast.
    pub network: Option<(u8, u8)>,
    /// Hand it to the communicator at this address, on this node, to leave the
    /// subsystem.
    pub gateway: Option<Address>,
    /// Count it as not for this node (it arrived, and nothing here or beyond takes it).
    pub not_for_us: bool,
}

impl Scope {
    /// Whether `d` names this node (255 in subsystem or node: every one).
    pub(crate) fn is_here(&self, d: Address) -> bool {
        (d.subsystem == self.subsystem || d.subsystem == 255)
            && (d.node == self.node || d.node == 255)
    }

    /// Where a message from `source` to `destination` goes, arriving from `origin`.
    pub(crate) fn decide(&self, source: Address, destination: Address, origin: Origin) -> Decision {
        let d = destination;
        let here = self.is_here(d);
        let (ss, node) = (self.subsystem, self.node);
        let mut out = Decision {
            here,
            ..Decision::default()
        };
        let Some(comm) = self.communicator else {
            // Every node reaches every other over the carrier.
            let only_here = d.subsystem == ss && d.node == node;
            match origin {
                Origin::Local if !only_here => out.network = Some((d.subsystem, d.node)),
                Origin::Local => {}
                _ => out.not_for_us = !here,
            }
            return out;
        };
        // Through the communicator (Figure 5-1).
        let own_subsystem = d.subsystem == ss || d.subsystem == 255;
        let other_subsystem = d.subsystem != ss;
        let other_nodes = own_subsystem && d.node != node;
        let comm_here = comm.subsystem == ss && comm.node == node;
        match origin {
            Origin::Local => {
                if other_nodes {
                    out.network = Some((d.subsystem, d.node));
                }
                if other_subsystem {
                    if comm_here {
                        out.gateway = Some(comm);
                    } else if !(other_nodes && d.subsystem == 255) {
                        // (A broadcast to every subsystem reached the communicator's
                        // node with the other nodes.)
                        out.network = Some((ss, comm.node));
                    }
                }
            }
            Origin::Network => {
                if other_subsystem && comm_here && source.subsystem == ss {
                    out.gateway = Some(comm);
                } else {
                    out.not_for_us = !here;
                }
            }
            Origin::Link => {
                if other_nodes {
                    out.network = Some((d.subsystem, d.node));
                }
                // Nothing passes between two other subsystems through this one.
                out.not_for_us = !own_subsystem;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn a(ss: u8, n: u8, c: u8) -> Address {
        Address::new(ss, n, c, 1)
    }

    const OPEN: Scope = Scope {
        subsystem: 1,
        node: 1,
        communicator: None,
    };

    fn with_comm(node: u8) -> Scope {
        Scope {
            communicator: Some(a(1, node, 35)),
            ..OPEN
        }
    }

    fn go(here: bool, network: Option<(u8, u8)>, gateway: Option<Address>, nfu: bool) -> Decision {
        Decision {
            here,
            network,
            gateway,
            not_for_us: nfu,
        }
    }

    #[test]
    fn without_a_communicator_every_node_is_reached_over_the_carrier() {
        let me = a(1, 1, 33);
        assert_eq!(
            OPEN.decide(me, a(1, 1, 42), Origin::Local),
            go(true, None, None, false)
        );
        assert_eq!(
            OPEN.decide(me, a(1, 2, 42), Origin::Local),
            go(false, Some((1, 2)), None, false)
        );
        assert_eq!(
            OPEN.decide(me, a(2, 7, 42), Origin::Local),
            go(false, Some((2, 7)), None, false)
        );
        // A broadcast goes out and is delivered here too.
        assert_eq!(
            OPEN.decide(me, a(255, 255, 255), Origin::Local),
            go(true, Some((255, 255)), None, false)
        );
        // From the network: taken or counted, never sent on (no forwarding).
        assert_eq!(
            OPEN.decide(a(1, 2, 1), a(1, 1, 33), Origin::Network),
            go(true, None, None, false)
        );
        assert_eq!(
            OPEN.decide(a(1, 2, 1), a(1, 3, 33), Origin::Network),
            go(false, None, None, true)
        );
    }

    #[test]
    fn with_the_communicator_here_other_subsystems_go_through_its_gateway() {
        let s = with_comm(1);
        let me = a(1, 1, 33);
        assert_eq!(
            s.decide(me, a(2, 1, 33), Origin::Local),
            go(false, None, Some(a(1, 1, 35)), false)
        );
        // Every subsystem: the other nodes here over the carrier, the rest through it.
        assert_eq!(
            s.decide(me, a(255, 255, 1), Origin::Local),
            go(true, Some((255, 255)), Some(a(1, 1, 35)), false)
        );
        // Another node of ours sends to another subsystem: relayed through the gateway.
        assert_eq!(
            s.decide(a(1, 2, 33), a(3, 1, 1), Origin::Network),
            go(false, None, Some(a(1, 1, 35)), false)
        );
        // A foreign source on the carrier is not relayed.
        assert_eq!(
            s.decide(a(4, 1, 1), a(3, 1, 1), Origin::Network),
            go(false, None, None, true)
        );
        // From a data link: to our other nodes over the carrier; never between two others.
        assert_eq!(
            s.decide(a(2, 1, 1), a(1, 3, 33), Origin::Link),
            go(false, Some((1, 3)), None, false)
        );
        assert_eq!(
            s.decide(a(2, 1, 1), a(3, 1, 1), Origin::Link),
            go(false, None, None, true)
        );
        assert_eq!(
            s.decide(a(2, 1, 1), a(1, 1, 33), Origin::Link),
            go(true, None, None, false)
        );
    }

    #[test]
    fn with_the_communicator_on_another_node_other_subsystems_go_to_that_node() {
        let s = with_comm(4);
        let me = a(1, 1, 33);
        assert_eq!(
            s.decide(me, a(2, 1, 33), Origin::Local),
            go(false, Some((1, 4)), None, false)
        );
        // A broadcast to every subsystem reaches the communicator's node with the rest.
        assert_eq!(
            s.decide(me, a(255, 255, 1), Origin::Local),
            go(true, Some((255, 255)), None, false)
        );
        // Our subsystem, every node: over the carrier only.
        assert_eq!(
            s.decide(me, a(1, 255, 1), Origin::Local),
            go(true, Some((1, 255)), None, false)
        );
    }
}
