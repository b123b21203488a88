//! This node's configuration, told to node managers that hold it without a
//! subscription here.
//!
//! RA 3.3 has configuration changes reach the subscribers of the configuration event
//! (Create Event, every change, on Report Configuration: the component runtime's event
//! table sends them). A node manager may hold this node's configuration without such a
//! subscription: OpenJAUS subscribes once, when it discovers a subsystem or node
//! (docs/wire.md §8.3), and never again while it keeps hearing its heartbeats. So when
//! this node restarts within OpenJAUS's 5 s timeout, or its one Create Event is lost,
//! OpenJAUS keeps the configuration it had and is told of no change; and an OpenJAUS
//! component drops a controller its node manager's tree does not list (a component
//! that joined this node since). Such a node manager is sent the configuration, at the
//! level it asked for (another subsystem's: the subsystem; another node of this
//! subsystem's: the node), as a plain Report Configuration whenever it differs from
//! what it was last given (an answer to its query, or an earlier report); one that
//! never asked is sent it when it changes, and once after
//! [`ManagerConfig::announce_after`](super::ManagerConfig::announce_after).

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use crate::components::node_manager::Ctx;
use crate::messages::{QueryLevel, ReportConfiguration};
use crate::{Address, JausMessage};

/// A node manager's record, kept this long after its node left the tree and it last
/// asked (it may be back soon, still holding what it was given).
const FORGET_AFTER: Duration = Duration::from_secs(10);

/// What one node manager of another node was given of this node's configuration.
#[derive(Debug)]
struct Peer {
    /// The level it asked for (by default: the subsystem for another subsystem's node
    /// manager, the node for one of this subsystem).
    level: QueryLevel,
    /// When it was first followed (it asked, or its node entered the tree).
    since: Instant,
    /// When it last asked, or its record was made.
    updated: Instant,
    /// This node's configuration when its node entered the tree, for one that never
    /// asked.
    at_since: Option<ReportConfiguration>,
    /// What it was last given (an answer, an Event, a report); `None`: nothing since
    /// this node manager started.
    given: Option<ReportConfiguration>,
}

/// The node managers of the other nodes and what each holds of this node's
/// configuration.
#[derive(Debug, Default)]
pub(super) struct Announcer {
    peers: BTreeMap<Address, Peer>,
}

impl Announcer {
    /// `peer` was answered `report` to its Query Configuration at `level` (its own
    /// query, or the event table's check of its subscription). Only node managers of
    /// other nodes are followed.
    pub(super) fn answered(
        &mut self,
        me: Address,
        peer: Address,
        level: QueryLevel,
        report: &ReportConfiguration,
        now: Instant,
    ) {
        if peer.component != 1 || (peer.subsystem == me.subsystem && peer.node == me.node) {
            return;
        }
        let p = self.peers.entry(peer).or_insert_with(|| Peer {
            level,
            since: now,
            updated: now,
            at_since: None,
            given: None,
        });
        p.level = level;
        p.updated = now;
        p.given = Some(report.clone());
    }

    /// Follows the node managers of `nodes` (the other nodes in the tree) and sends the
    /// configuration to each that does not subscribe to it here and holds another one
    /// (or, never having asked, was first heard `announce_after` ago). `configuration`
    /// gives this node's configuration at a level.
    pub(super) fn run(
        &mut self,
        ctx: &mut Ctx<'_>,
        nodes: &[(u8, u8)],
        configuration: impl Fn(QueryLevel) -> ReportConfiguration,
        announce_after: Duration,
    ) {
        let (me, now) = (ctx.address(), ctx.now());
        let in_tree = |a: &Address| nodes.contains(&(a.subsystem, a.node));
        self.peers
            .retain(|a, p| in_tree(a) || now.saturating_duration_since(p.updated) < FORGET_AFTER);
        for &(ss, n) in nodes {
            // A node manager is instance 1 in OpenJAUS and here; one that asked from
            // another instance is followed at that address.
            if self.peers.keys().any(|a| (a.subsystem, a.node) == (ss, n)) {
                continue;
            }
            let level = if ss == me.subsystem {
                QueryLevel::Node
            } else {
                QueryLevel::Subsystem
            };
            self.peers.insert(
                Address::new(ss, n, 1, 1),
                Peer {
                    level,
                    since: now,
                    updated: now,
                    at_since: Some(configuration(level)),
                    given: None,
                },
            );
        }
        let code = ReportConfiguration::CODE;
        for (&peer, p) in &mut self.peers {
            if !in_tree(&peer) || ctx.has_subscriber(peer, code) {
                continue;
            }
            let current = configuration(p.level);
            let due = match &p.given {
                Some(given) => *given != current,
                None => {
                    now.saturating_duration_since(p.since) >= announce_after
                        || p.at_since.as_ref() != Some(&current)
                }
            };
            if !due {
                continue;
            }
            if p.given.is_none() {
                tracing::info!(node_manager = %peer, "holds this node's configuration without a subscription here (subscribed to an earlier run of this node, or never): configuration sent as a report, and each change after");
            } else {
                tracing::debug!(node_manager = %peer, "configuration changed: sent as a report (no subscription here)");
            }
            p.given = Some(current.clone());
            ctx.send(peer, current);
        }
    }
}
