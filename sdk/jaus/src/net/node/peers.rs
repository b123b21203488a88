//! The nodes a node has heard from, by (subsystem, node), and where a message toward
//! one of them goes: that node's address when it is known, the configured peers (and
//! every node learned, or the multicast group) for a broadcast, the configured peers
//! (a flood) otherwise.

use std::collections::HashMap;

use super::super::PeerAddr;

/// Where the other nodes are.
#[derive(Debug)]
pub(crate) struct Peers<A> {
    located: HashMap<(u8, u8), A>,
    configured: Vec<A>,
    multicast: Option<A>,
}

/// The carrier addresses a message toward a node goes to.
#[derive(Debug, PartialEq, Eq)]
pub(crate) enum Targets<A> {
    /// The node's address, learned from its traffic.
    One(A),
    /// A broadcast: the multicast group (if any) first, then the configured peers and,
    /// without a group, every node learned; each once, in a stable order.
    Broadcast(Vec<A>),
    /// The node is not located yet: the configured peers.
    Flood(Vec<A>),
}

impl<A: PeerAddr> Peers<A> {
    pub(crate) fn new(configured: Vec<A>, multicast: Option<A>) -> Self {
        Self {
            located: HashMap::new(),
            configured,
            multicast,
        }
    }

    /// `node` (subsystem, node) was heard at `at`.
    pub(crate) fn learn(&mut self, node: (u8, u8), at: A) {
        self.located.insert(node, at);
    }

    /// Where `node` was last heard.
    pub(crate) fn get(&self, node: (u8, u8)) -> Option<A> {
        self.located.get(&node).copied()
    }

    /// Every node located so far.
    pub(crate) fn located(&self) -> &HashMap<(u8, u8), A> {
        &self.located
    }

    /// Where a message toward `hop` goes (255 in either part: a broadcast).
    pub(crate) fn targets(&self, hop: (u8, u8)) -> Targets<A> {
        if hop.0 == 255 || hop.1 == 255 {
            let mut t = self.configured.clone();
            if let Some(group) = self.multicast {
                // The group reaches every node that listens; the configured peers may
                // be beyond it.
                t.insert(0, group);
                return Targets::Broadcast(t);
            }
            for p in self.located.values() {
                if !t.contains(p) {
                    t.push(*p);
                }
            }
            t.sort();
            return Targets::Broadcast(t);
        }
        match self.located.get(&hop) {
            Some(p) => Targets::One(*p),
            None => Targets::Flood(self.configured.clone()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn broadcasts_reach_every_peer_once_and_unknown_nodes_are_flooded() {
        let mut p = Peers::new(vec![9u8, 3], None);
        p.learn((1, 2), 3);
        p.learn((1, 4), 5);
        assert_eq!(p.targets((1, 2)), Targets::One(3));
        assert_eq!(p.targets((1, 7)), Targets::Flood(vec![9, 3]));
        assert_eq!(p.targets((255, 255)), Targets::Broadcast(vec![3, 5, 9]));
        let g = Peers::new(vec![9u8], Some(200));
        assert_eq!(g.targets((1, 255)), Targets::Broadcast(vec![200, 9]));
    }
}
