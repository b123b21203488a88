//! The system tree as the client shows it: as text when it changed, and as JSON
//! (`jaus discover --json`, Python's `Client.tree()`).

use std::time::{Duration, Instant};

use jaus::net::SystemTree;

/// Shows a system tree at most once per `every`, and only when it changed.
#[derive(Debug)]
pub struct TreePrinter {
    every: Duration,
    shown_version: Option<u64>,
    shown_text: String,
    last: Option<Instant>,
}

impl TreePrinter {
    /// At most once per `every`.
    pub fn new(every: Duration) -> Self {
        Self {
            every,
            shown_version: None,
            shown_text: String::new(),
            last: None,
        }
    }

    /// The text to print now, if any: the tree is rendered only when its version moved
    /// and `every` has passed since the last print, and printed only if the text
    /// differs.
    pub fn poll(&mut self, now: Instant, version: u64, tree: &SystemTree) -> Option<String> {
        if self.shown_version == Some(version)
            || self
                .last
                .is_some_and(|t| now.saturating_duration_since(t) < self.every)
        {
            return None;
        }
        self.shown_version = Some(version);
        let text = tree.render();
        if text == self.shown_text {
            return None;
        }
        self.last = Some(now);
        self.shown_text.clone_from(&text);
        Some(text)
    }
}

/// The system tree as JSON (`jaus discover --json`): subsystems, their nodes, and the
/// components of each with their identification and service types (null until
/// answered).
pub fn tree_json(tree: &SystemTree) -> serde_json::Value {
    let subsystems: Vec<serde_json::Value> = tree
        .subsystems
        .iter()
        .map(|(ss, s)| {
            let nodes: Vec<serde_json::Value> = s
                .nodes
                .iter()
                .map(|(n, node)| {
                    let components: Vec<serde_json::Value> = node
                        .components
                        .iter()
                        .map(|((c, i), info)| {
                            serde_json::json!({
                                "address": jaus::Address::new(*ss, *n, *c, *i).to_string(),
                                "name": info.name,
                                "services": info.services,
                            })
                        })
                        .collect();
                    serde_json::json!({ "id": n, "name": node.name, "components": components })
                })
                .collect();
            serde_json::json!({ "id": ss, "name": s.name, "nodes": nodes })
        })
        .collect();
    serde_json::json!({ "subsystems": subsystems })
}
