//! The network commands of the `jaus` CLI: `node`, `discover`, `send`, `query`, and the
//! operator-only demo.

use std::io::Write;
use std::net::SocketAddr;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::{Component, Config, Refused};
use jaus::components::system_commander::{self, Ctx, SystemCommander};
use jaus::messages::Message;
use jaus::net::{udp, Framing, Node, NodeConfig};
use jaus::{Address, Header};

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
        if !f.host.is_empty() && (f.subsystem, f.node) != (1, 1) {
            return Err(format!(
                "{}: the built-in vehicle uses the demo addresses: subsystem 1, node 1",
                path.display()
            ));
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

/// `jaus node --config FILE`: runs a node until interrupted (or for `duration`),
/// printing the system tree whenever it changes.
pub fn node(config: &Path, duration: Option<Duration>, out: &mut impl Write) -> Result<(), String> {
    let file = NodeFile::load(config)?;
    let t0 = Instant::now();
    let mut node = Node::new(file.node_config(), t0);
    if file.host.iter().any(|h| h == "vehicle") {
        let (parts, _vehicle) = jaus_sim::demo::vehicle(t0, &jaus_sim::demo::Options::default());
        for p in parts {
            node.add_boxed(p)?;
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
    let stop = AtomicBool::new(false);
    let mut last = String::new();
    udp::run(&mut node, file.bind, &stop, duration.map(|d| t0 + d), |n| {
        let now = n.tree().render();
        if now != last {
            let _ = writeln!(
                out,
                "--- system tree at {:.1} s\n{now}",
                t0.elapsed().as_secs_f64()
            );
            let _ = out.flush();
            last = now;
        }
    })
    .map_err(|e| format!("{}: {e}", file.bind))
}

/// Options of the one-shot commands (`discover`, `send`, `query`).
#[derive(Debug, Clone)]
pub struct Client {
    /// This node's address (its components use it).
    pub me: Address,
    /// Local socket.
    pub bind: SocketAddr,
    /// Peers.
    pub peers: Vec<SocketAddr>,
    /// Framing.
    pub framing: Framing,
    /// How long to listen.
    pub wait: Duration,
}

/// The CLI's own component: a System Commander that records what it receives. Being a
/// real component, it answers the core queries (identification, services, status) other
/// node managers send it during discovery.
#[derive(Debug, Default)]
pub struct Recorder {
    received: Vec<(Address, Message)>,
}

/// Most messages the CLI keeps.
const RECORD_LIMIT: usize = 100_000;

impl SystemCommander for Recorder {
    fn on_other_message(
        &mut self,
        ctx: &mut Ctx<'_>,
        msg: &Message,
    ) -> Result<Option<Message>, Refused> {
        if self.received.len() < RECORD_LIMIT {
            self.received
                .push((ctx.source().unwrap_or_default(), msg.clone()));
        }
        Ok(None)
    }
}

type Tool = Component<system_commander::Dispatch<Recorder>>;

impl Client {
    fn node(&self, t0: Instant) -> Result<Node, String> {
        let mut c = NodeConfig {
            subsystem: self.me.subsystem,
            node: self.me.node,
            framing: self.framing,
            peers: self.peers.clone(),
            ..NodeConfig::default()
        };
        c.manager.node_name = "jaus CLI".into();
        let mut node = Node::new(c, t0);
        if self.me.component != 1 {
            let cfg = Config {
                heartbeat: None,
                ..Config::default()
            };
            node.add(system_commander::component(
                self.me,
                Recorder::default(),
                cfg,
                t0,
            ))?;
        }
        Ok(node)
    }
}

/// `jaus discover`: listens, then prints the system tree.
pub fn discover(c: &Client, out: &mut impl Write) -> Result<(), String> {
    let t0 = Instant::now();
    let mut node = c.node(t0)?;
    let stop = AtomicBool::new(false);
    udp::run(&mut node, c.bind, &stop, Some(t0 + c.wait), |_| {})
        .map_err(|e| format!("{}: {e}", c.bind))?;
    let _ = write!(out, "{}", node.tree().render());
    Ok(())
}

/// `jaus send` / `jaus query`: sends `json` (a message as `jaus decode` prints it:
/// `{"message": NAME, "fields": {...}}`) to `to`, then prints every message received
/// within the wait as a JSON line.
pub fn send(c: &Client, to: Address, json: &str, out: &mut impl Write) -> Result<usize, String> {
    let msg: Message = serde_json::from_str(json).map_err(|e| format!("bad message JSON: {e}"))?;
    let body = msg.to_bytes().map_err(|e| format!("{}: {e}", msg.name()))?;
    let t0 = Instant::now();
    let mut node = c.node(t0)?;
    let stop = AtomicBool::new(false);
    let mut sent = false;
    let me = c.me;
    udp::run(&mut node, c.bind, &stop, Some(t0 + c.wait), |n| {
        // Once the destination's node is located (or at once for a broadcast), send.
        if !sent
            && (n.peers().contains_key(&(to.subsystem, to.node))
                || to.subsystem == 255
                || to.node == 255
                || t0.elapsed() > Duration::from_millis(300))
        {
            sent = true;
            let now = Instant::now();
            n.send(now, Header::new(msg.code(), to, me), body.clone());
        }
    })
    .map_err(|e| format!("{}: {e}", c.bind))?;
    let tool = node.get::<Tool>(me).ok_or("no local component")?;
    let asked_heartbeat = matches!(msg, Message::QueryHeartbeatPulse(_));
    let mut n = 0;
    for (source, m) in &tool.behaviour().0.received {
        // Heartbeats broadcast by the other nodes are not an answer (unless asked for).
        if matches!(m, Message::ReportHeartbeatPulse(_)) && !asked_heartbeat {
            continue;
        }
        let line = serde_json::json!({
            "source": source.to_string(),
            "message": m,
        });
        let _ = writeln!(out, "{line}");
        n += 1;
    }
    Ok(n)
}

/// `jaus demo --ocu-only`: the demo's operator on its own node (1.2), driving a vehicle
/// hosted by `jaus node` (`host: [vehicle]`) over UDP. Prints progress and the times
/// the two phases finished.
pub fn demo_operator(
    bind: SocketAddr,
    peers: Vec<SocketAddr>,
    framing: Framing,
    timeout: Duration,
    out: &mut impl Write,
) -> Result<(), String> {
    let t0 = Instant::now();
    let mut c = NodeConfig {
        subsystem: 1,
        node: 2,
        framing,
        peers,
        ..NodeConfig::default()
    };
    c.manager.node_name = "operator".into();
    let mut node = Node::new(c, t0);
    let opts = jaus_sim::demo::Options::default();
    node.add(jaus_sim::demo::operator(t0, &opts))?;
    let stop = AtomicBool::new(false);
    let mut last = "";
    let mut done = None;
    udp::run(&mut node, bind, &stop, Some(t0 + timeout), |n| {
        if done.is_some() {
            return;
        }
        if let Some(o) = n.get::<jaus_sim::demo::Ocu>(jaus_sim::demo::addr::OCU) {
            let (phase, wp, path, mission) = jaus_sim::demo::progress(o);
            if phase != last {
                let _ = writeln!(out, "t = {:6.1} s  {phase}", t0.elapsed().as_secs_f64());
                let _ = out.flush();
                last = phase;
            }
            if phase == "done" {
                done = Some((wp, path, mission));
                stop.store(true, std::sync::atomic::Ordering::Relaxed);
            }
        }
    })
    .map_err(|e| format!("{bind}: {e}"))?;
    match done {
        Some((wp, path, mission)) => {
            let s = |t: Option<Instant>| t.map_or("—".into(), |t| format!("{:.1} s", (t - t0).as_secs_f64()));
            let _ = writeln!(
                out,
                "waypoints: Standby at {}; path segments: Standby at {}; spooled mission finished at {}",
                s(wp),
                s(path),
                s(mission)
            );
            Ok(())
        }
        None => Err(format!("the mission did not finish within {timeout:?} (is `jaus node` with host: [vehicle] running and reachable?)")),
    }
}
