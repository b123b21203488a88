//! `jaus node`: a node from a YAML file, its system tree printed when it changes.

use std::io::Write;
use std::net::SocketAddr;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use jaus::net::{udp, Framing, Node, NodeConfig, SystemTree};

/// A node configuration file (YAML).
///
/// ```yaml
/// subsystem: 1
/// node: 1
/// subsystem_name: demo vehicle
/// node_name: vehicle computer
/// bind: 127.0.0.1:3794
/// framing: judp          # or opc ("JAUS01.0")
/// peers: [127.0.0.2:3794]
/// host: [vehicle]        # built-in components: vehicle (the demo's simulated vehicle)
/// ```
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeFile {
    /// Subsystem id.
    pub subsystem: u8,
    /// Node id.
    pub node: u8,
    /// Subsystem name.
    #[serde(default)]
    pub subsystem_name: Option<String>,
    /// Node name.
    #[serde(default)]
    pub node_name: Option<String>,
    /// Local address and port.
    pub bind: SocketAddr,
    /// Framing.
    #[serde(default)]
    pub framing: Framing,
    /// Peers sent broadcasts and messages to nodes not yet located.
    #[serde(default)]
    pub peers: Vec<SocketAddr>,
    /// Built-in components to host.
    #[serde(default)]
    pub host: Vec<String>,
    /// Heartbeat period, ms.
    #[serde(default)]
    pub heartbeat_ms: Option<u64>,
    /// Node timeout, ms.
    #[serde(default)]
    pub node_timeout_ms: Option<u64>,
}

impl NodeFile {
    /// Reads and checks a configuration file.
    pub fn load(path: &Path) -> Result<NodeFile, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let f: NodeFile =
            serde_yaml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        for (what, v) in [("subsystem", f.subsystem), ("node", f.node)] {
            if v == 0 || v == 255 {
                return Err(format!("{}: {what} {v} is not in 1..=254", path.display()));
            }
        }
        for h in &f.host {
            if h != "vehicle" {
                return Err(format!(
                    "{}: unknown built-in component `{h}` (known: vehicle)",
                    path.display()
                ));
            }
        }
        Ok(f)
    }

    /// The node configuration.
    pub fn node_config(&self) -> NodeConfig {
        let mut c = NodeConfig {
            subsystem: self.subsystem,
            node: self.node,
            framing: self.framing,
            peers: self.peers.clone(),
            ..NodeConfig::default()
        };
        if let Some(n) = &self.subsystem_name {
            c.manager.subsystem_name = n.clone();
        }
        c.manager.node_name = self
            .node_name
            .clone()
            .unwrap_or_else(|| format!("node {}.{}", self.subsystem, self.node));
        if let Some(ms) = self.heartbeat_ms {
            c.manager.heartbeat = Duration::from_millis(ms.max(10));
        }
        if let Some(ms) = self.node_timeout_ms {
            c.manager.node_timeout = Duration::from_millis(ms.max(100));
        }
        c
    }
}

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

/// `jaus node --config FILE`: runs a node until interrupted (or for `duration`),
/// printing the system tree when it changed, at most once a second.
pub fn node(
    config: &Path,
    duration: Option<Duration>,
    stop: &AtomicBool,
    out: &mut impl Write,
) -> Result<(), String> {
    let file = NodeFile::load(config)?;
    let t0 = Instant::now();
    let mut node = Node::new(file.node_config(), t0);
    if file.host.iter().any(|h| h == "vehicle") {
        let (parts, _vehicle) = jaus_sim::demo::vehicle_at(
            t0,
            &jaus_sim::demo::Options::default(),
            file.subsystem,
            file.node,
        );
        for p in parts {
            node.add_boxed(p).map_err(|e| e.to_string())?;
        }
    }
    let _ = writeln!(
        out,
        "node {} on {} ({:?}), peers {:?}",
        node.address(),
        file.bind,
        file.framing,
        file.peers
    );
    let _ = out.flush();
    let mut printer = TreePrinter::new(Duration::from_secs(1));
    udp::run(&mut node, file.bind, stop, duration.map(|d| t0 + d), |n| {
        let now = Instant::now();
        if let Some(text) = printer.poll(now, n.tree_version(), n.tree()) {
            let _ = writeln!(
                out,
                "--- system tree at {:.1} s\n{text}",
                t0.elapsed().as_secs_f64()
            );
            let _ = out.flush();
        }
    })
    .map_err(|e| format!("{}: {e}", file.bind))
}
