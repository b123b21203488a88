//! The system tree: what a node manager knows of the subsystems, nodes and components
//! of the system (docs/wire.md §8.3).

use std::collections::BTreeMap;
use std::time::Instant;

use crate::Address;

/// What is known about one component of the system.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ComponentInfo {
    /// Identification text, once answered.
    pub name: Option<String>,
    /// Service types it reported (component ids; 0 = core), once answered.
    pub services: Option<Vec<u16>>,
    /// Command codes of the messages its services take, from the same report.
    pub inputs: Vec<u16>,
    /// Command codes of the messages its services send, from the same report.
    pub outputs: Vec<u16>,
}

/// What is known about one node.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NodeInfo {
    /// Identification text, once answered.
    pub name: Option<String>,
    /// Components by (component id, instance).
    pub components: BTreeMap<(u8, u8), ComponentInfo>,
    /// Whether a Report Configuration was received.
    pub configured: bool,
    /// When it was last heard from.
    pub last_heard: Instant,
    /// This node manager's subscription to the node's configuration events.
    pub subscription: Subscription,
    /// When its configuration was last asked for (`None`: never).
    pub config_asked: Option<Instant>,
}

/// The state of a node manager's subscription to another node's configuration
/// (Create Event, every change, on Report Configuration of that node).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Subscription {
    /// Not asked yet (or the node is this node).
    #[default]
    None,
    /// Create Event sent at that instant, not answered yet.
    Requested(Instant),
    /// Confirmed with this event id: configuration changes arrive as Events.
    Confirmed(u8),
    /// Refused: the configuration is only re-queried periodically.
    Rejected,
}

/// What is known about one subsystem.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SubsystemInfo {
    /// Identification text, once answered.
    pub name: Option<String>,
    /// Nodes by id.
    pub nodes: BTreeMap<u8, NodeInfo>,
}

/// The system as this node manager sees it.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SystemTree {
    /// Subsystems by id (this node's own subsystem included, with this node).
    pub subsystems: BTreeMap<u8, SubsystemInfo>,
}

impl SystemTree {
    /// Every component address known.
    pub fn components(&self) -> Vec<Address> {
        let mut v = Vec::new();
        for (ss, s) in &self.subsystems {
            for (n, node) in &s.nodes {
                for (c, i) in node.components.keys() {
                    v.push(Address::new(*ss, *n, *c, *i));
                }
            }
        }
        v
    }

    /// What is known about the component at `a`.
    pub fn component(&self, a: Address) -> Option<&ComponentInfo> {
        self.subsystems
            .get(&a.subsystem)?
            .nodes
            .get(&a.node)?
            .components
            .get(&(a.component, a.instance))
    }

    /// Whether node `node` of subsystem `ss` is known.
    pub fn has_node(&self, ss: u8, node: u8) -> bool {
        self.subsystems
            .get(&ss)
            .is_some_and(|s| s.nodes.contains_key(&node))
    }

    /// A readable multi-line view.
    pub fn render(&self) -> String {
        use std::fmt::Write as _;
        let mut out = String::new();
        for (ss, s) in &self.subsystems {
            let _ = writeln!(
                out,
                "subsystem {ss} {}",
                s.name
                    .as_deref()
                    .map(|n| format!("'{n}'"))
                    .unwrap_or_default()
            );
            for (n, node) in &s.nodes {
                let _ = writeln!(
                    out,
                    "  node {n} {}",
                    node.name
                        .as_deref()
                        .map(|n| format!("'{n}'"))
                        .unwrap_or_default()
                );
                for ((c, i), info) in &node.components {
                    let _ = writeln!(
                        out,
                        "    {ss}.{n}.{c}.{i} {}{}",
                        info.name
                            .as_deref()
                            .map(|n| format!("'{n}'"))
                            .unwrap_or_else(|| "(unidentified)".into()),
                        info.services
                            .as_ref()
                            .map(|s| format!(" services {s:?}"))
                            .unwrap_or_default()
                    );
                }
            }
        }
        out
    }
}
