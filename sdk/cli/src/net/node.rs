//! `jaus node`: a node from a YAML file, its system tree printed when it changes.

use std::io::Write;
use std::net::SocketAddr;
use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use jaus::net::{udp, Framing, Node, NodeConfig, SystemTree};

use super::links_file::{links_at, LinkFile, QuicLinkFile};

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
/// host:                  # what the node hosts (see below)
///   - vehicle                                # the demo's whole simulated vehicle
///   - arm                                    # the ten manipulator components, one arm
///   - global_pose_sensor                     # a stock component at instance 1
///   - { component: world_model, instance: 2 }
///   - { component: global_waypoint_driver, output: 1.1.33.1, pose: 1.1.38.1 }
///   - component: communicator                # the gateway to other subsystems
///     links:
///       - { id: 1, udp: { bind: "0.0.0.0:4001", peer: "192.168.1.20:4001" } }
///       - id: 2                                # or authenticated and encrypted:
///         quic: { bind: "0.0.0.0:4002", peer: "192.168.1.20:4002",
///                 cert: keys/vehicle.crt, key: keys/vehicle.key, peer_cert: keys/station.crt }
/// io: { spin_us: 50, batch: 32 }  # optional: how the socket is read (udp::IoOptions)
/// policy:               # optional: who may command (see `PolicyFile`); default open
///   default: query
///   rules: [{ from: 200.*.*.*, may: command, max_authority: 100 }]
/// communicator: 1.2.35.1 # optional: the subsystem's communicator on another node
/// ```
///
/// A `host:` entry is `vehicle`, `arm` (the Primitive Manipulator, the three joint sensors
/// and the six manipulator drivers of `jaus_sim::arm_demo::arm_components` over one
/// simulated 6-axis arm) or a stock component by its name in the definitions (`stock:`
/// of a component in `jaus-spec/defs`, `jaus_sim::host::Stock::names()`: for example
/// `primitive_driver`, `global_pose_sensor`, `global_waypoint_driver`, `world_model`,
/// `range_sensor`, `joint_position_sensor`, `communicator`; an unknown name's error
/// lists them all), by name or as a map with `component`,
/// `instance` (1), `output` and `pose` (drivers: where the efforts go and which pose
/// sensor they follow; default: this node's 43.1 or 33.1, and 38.1 or 41.1; manipulator
/// drivers: 49.1) and `authority` (0). Those that need hardware share one simulated
/// vehicle, the manipulator components one simulated arm, in an empty world (no
/// obstacles; the vehicle at the origin of the default frame: `jaus_sim::host::HostConfig`).
///
/// `communicator` (Part 1 §5.2.1, id 35) is the subsystem's gateway to the other
/// subsystems, over real data links: its `links:` (at least one) are each
/// `{ id, udp: { bind, peer, mtu, silence_ms, keepalive_ms, assume_up, poll_ms } }`,
/// a UDP socket bound to `bind` exchanging one datagram per JAUS packet with the far
/// communicator's link socket `peer` (an IP radio modem, a tether; `mtu` 4096 bytes,
/// down after `silence_ms` 3000 of silence, a keep-alive after `keepalive_ms` 1000
/// without sending (0: none), up before anything is heard unless `assume_up: false`,
/// read every `poll_ms` 10: `jaus::net::udp::link::UdpLinkConfig`), or
/// `{ id, quic: { bind, peer, cert, key, peer_cert, mtu, silence_ms, keepalive_ms } }`,
/// a QUIC connection between `bind` and the far end's `peer`, authenticated both ways
/// by pinned certificates and encrypted (`jaus_quic::QuicLink`: this node presents
/// `cert` and `key`, made by `jaus keygen`, and accepts only `peer_cert`, the far end's
/// certificate; paths relative to the node file's directory; `mtu` 4096, down after
/// `silence_ms` 3000 of silence, a QUIC keep-alive after `keepalive_ms` 1000, or a
/// third of `silence_ms` if that is less). A node hosting
/// one sends every message for another subsystem through it and takes those from
/// other subsystems only from it (`NodeConfig::communicator`); the other nodes of the
/// subsystem name it with `communicator:`. At most one per node.
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
    /// What to host.
    #[serde(default)]
    pub host: Vec<HostItem>,
    /// Heartbeat period, ms.
    #[serde(default)]
    pub heartbeat_ms: Option<u64>,
    /// Node timeout, ms.
    #[serde(default)]
    pub node_timeout_ms: Option<u64>,
    /// Multicast discovery (off without it).
    #[serde(default)]
    pub multicast: Option<MulticastFile>,
    /// Serve OpenJAUS component processes over their local interface
    /// (`openjaus_components: {}` for OpenJAUS's ports 24627 and 24629 on 127.0.0.1).
    #[serde(default)]
    pub openjaus_components: Option<OjComponentsFile>,
    /// How the node reads its socket (`udp::IoOptions`; defaults when absent).
    #[serde(default)]
    pub io: Option<IoFile>,
    /// The subsystem's Communicator when another node hosts it
    /// (`subsystem.node.component.instance`): messages for other subsystems go to that
    /// node (`NodeConfig::communicator`). A node hosting one needs none.
    #[serde(default)]
    pub communicator: Option<String>,
    /// The node's access policy (`jaus::net::Policy`; open without it).
    #[serde(default)]
    pub policy: Option<super::PolicyFile>,
}

/// `io:` of a node file: how the node waits for and reads datagrams.
#[derive(Debug, Clone, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IoFile {
    /// After a datagram, keep reading without blocking for this many microseconds
    /// (0: always block). Default 50.
    #[serde(default)]
    pub spin_us: Option<u64>,
    /// Datagrams read per system call where the OS offers it, 1 to 64. Default 32.
    #[serde(default)]
    pub batch: Option<usize>,
}

impl IoFile {
    /// The options, defaults filled in.
    pub fn options(&self) -> udp::IoOptions {
        let d = udp::IoOptions::default();
        udp::IoOptions {
            spin: self.spin_us.map_or(d.spin, Duration::from_micros),
            batch: self.batch.unwrap_or(d.batch),
        }
    }
}

/// `openjaus_components:` of a node file: the two sockets of OpenJAUS's local component
/// interface (docs/wire.md §8.5).
#[derive(Debug, Clone, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OjComponentsFile {
    /// The control socket (check-in, lookups). Default 127.0.0.1:24627.
    #[serde(default)]
    pub control: Option<SocketAddr>,
    /// The data socket (raw JAUS packets). Default 127.0.0.1:24629.
    #[serde(default)]
    pub data: Option<SocketAddr>,
}

impl OjComponentsFile {
    /// The control and data sockets, defaults filled in.
    pub fn sockets(&self) -> (SocketAddr, SocketAddr) {
        let local = |port| SocketAddr::from(([127, 0, 0, 1], port));
        (
            self.control
                .unwrap_or_else(|| local(jaus::net::oj::CONTROL_PORT)),
            self.data.unwrap_or_else(|| local(jaus::net::oj::DATA_PORT)),
        )
    }
}

/// `multicast:` of a node file: broadcasts go to `group` on the node's port, and the
/// node listens to it (docs/wire.md §9.5).
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MulticastFile {
    /// The group: 224.1.0.1 is OpenJAUS's subsystem-level group, 225.1.0.1 its node-level
    /// one.
    pub group: std::net::Ipv4Addr,
    /// Time to live of what the node sends to the group. Default 32 (OpenJAUS's
    /// subsystem level).
    #[serde(default)]
    pub ttl: Option<u32>,
    /// Whether the node's own multicasts come back to this host (other nodes on the
    /// same host then hear them). Default false, as OpenJAUS.
    #[serde(default)]
    pub loopback: Option<bool>,
    /// The local interface address to join on. Default 0.0.0.0 (the system's choice).
    /// What the node sends to the group leaves by the route to 224.0.0.0/4.
    #[serde(default)]
    pub interface: Option<std::net::Ipv4Addr>,
}

/// One `host:` entry as written.
#[derive(Debug, Clone, serde::Deserialize)]
#[serde(untagged)]
pub enum HostItem {
    /// `vehicle` or a stock component's name.
    Name(String),
    /// A stock component with settings.
    Component {
        /// Its name.
        component: String,
        /// Its instance.
        #[serde(default)]
        instance: Option<u8>,
        /// Where a driver's efforts go (`ss.node.component.instance`).
        #[serde(default)]
        output: Option<String>,
        /// A driver's pose sensor.
        #[serde(default)]
        pose: Option<String>,
        /// Its authority.
        #[serde(default)]
        authority: Option<u8>,
        /// The Communicator's data links (checked field by field when loaded).
        #[serde(default)]
        links: Option<serde_yaml::Value>,
    },
}

/// What a node hosts, checked.
#[derive(Debug, Clone, PartialEq)]
pub enum Hosted {
    /// The demo's simulated vehicle (every component of `jaus_sim::demo::vehicle_at`).
    Vehicle,
    /// The arm demo's ten manipulator components over one simulated arm
    /// (`jaus_sim::arm_demo::arm_components`).
    Arm,
    /// One stock component.
    Stock(jaus_sim::host::Entry),
}

impl NodeFile {
    /// Reads and checks a configuration file.
    pub fn load(path: &Path) -> Result<NodeFile, String> {
        let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
        let f: NodeFile =
            serde_yaml::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let index = jaus_spec::location::LocationIndex::build(&text);
        let at = |key: &str| {
            let p = index.find(key);
            format!("{}:{}:{}", path.display(), p.line, p.column)
        };
        for (what, v) in [("subsystem", f.subsystem), ("node", f.node)] {
            if v == 0 || v == 255 {
                return Err(format!("{}: {what} {v} is not in 1..=254", at(what)));
            }
        }
        if let Some(io) = &f.io {
            if io.spin_us.is_some_and(|s| s > 10_000) {
                return Err(format!(
                    "{}: spin_us {} is over 10000 (10 ms of busy waiting per datagram)",
                    at("io.spin_us"),
                    io.spin_us.unwrap_or_default()
                ));
            }
            if let Some(b) = io.batch.filter(|b| !(1..=udp::MAX_BATCH).contains(b)) {
                return Err(format!(
                    "{}: batch {b} is not in 1..={}",
                    at("io.batch"),
                    udp::MAX_BATCH
                ));
            }
        }
        let hosted = f.hosted_at(&at)?;
        f.communicator_at(&hosted, &at)?;
        f.check_quic_links(path, &at)?;
        if let Some(p) = &f.policy {
            p.policy(&at)?;
        }
        Ok(f)
    }

    /// The subsystem's Communicator: the one hosted here, else `communicator:`, checked
    /// (`at` gives the file:line:column of a YAML path).
    fn communicator_at(
        &self,
        hosted: &[Hosted],
        at: &dyn Fn(&str) -> String,
    ) -> Result<Option<jaus::Address>, String> {
        let entries = hosted.iter().filter_map(|h| match h {
            Hosted::Stock(e) => Some(e),
            Hosted::Vehicle | Hosted::Arm => None,
        });
        let here = jaus_sim::host::Host::communicator_of(self.subsystem, self.node, entries);
        let Some(text) = &self.communicator else {
            return Ok(here);
        };
        let a: jaus::Address = text.parse().map_err(|_| {
            format!(
                "{}: communicator: `{text}` is not an address subsystem.node.component.instance",
                at("communicator")
            )
        })?;
        if a.subsystem != self.subsystem || a.node == 0 || a.node == 255 {
            return Err(format!(
                "{}: communicator: {a} is not a component of this subsystem ({}): a node reaches other subsystems only through its own subsystem's communicator",
                at("communicator"),
                self.subsystem
            ));
        }
        match here {
            Some(h) if h != a => Err(format!(
                "{}: communicator: {a}, but this node hosts the communicator {h}",
                at("communicator")
            )),
            None if a.node == self.node => Err(format!(
                "{}: communicator: {a} is on this node but not hosted here (add `communicator` with its `links:` to `host:`)",
                at("communicator")
            )),
            _ => Ok(Some(a)),
        }
    }

    /// The subsystem's Communicator (checked by [`NodeFile::load`]): the one this
    /// node hosts, else `communicator:`.
    pub fn communicator(&self) -> Option<jaus::Address> {
        let hosted = self.hosted();
        self.communicator_at(&hosted, &|k| k.to_string())
            .ok()
            .flatten()
    }

    /// The `host:` entries, checked (`at` gives the file:line:column of a YAML path).
    fn hosted_at(&self, at: &dyn Fn(&str) -> String) -> Result<Vec<Hosted>, String> {
        let known = || {
            let mut k = vec!["vehicle", "arm"];
            k.extend(jaus_sim::host::Stock::names());
            k.join(", ")
        };
        let mut out = Vec::new();
        for (i, h) in self.host.iter().enumerate() {
            let (name, key) = match h {
                HostItem::Name(n) => (n, format!("host[{i}]")),
                HostItem::Component { component, .. } => {
                    (component, format!("host[{i}].component"))
                }
            };
            if name == "vehicle" {
                out.push(Hosted::Vehicle);
                continue;
            }
            if name == "arm" {
                out.push(Hosted::Arm);
                continue;
            }
            let Some(stock) = jaus_sim::host::Stock::by_name(name) else {
                return Err(format!(
                    "{}: unknown component `{name}` (known: {})",
                    at(&key),
                    known()
                ));
            };
            let mut e = jaus_sim::host::Host::entry(stock);
            let is_communicator = stock.id() == jaus::components::communicator::ID;
            let mut has_links = false;
            if let HostItem::Component {
                instance,
                output,
                pose,
                authority,
                links,
                ..
            } = h
            {
                if let Some(n) = instance {
                    if *n == 0 || *n == 255 {
                        return Err(format!(
                            "{}: instance {n} is not in 1..=254",
                            at(&format!("host[{i}].instance"))
                        ));
                    }
                    e.instance = *n;
                }
                let addr =
                    |v: &Option<String>, key: &str| -> Result<Option<jaus::Address>, String> {
                        v.as_deref()
                            .map(|s| {
                                s.parse().map_err(|_| {
                                    format!(
                                    "{}: `{s}` is not an address subsystem.node.component.instance",
                                    at(&format!("host[{i}].{key}"))
                                )
                                })
                            })
                            .transpose()
                    };
                e.output = addr(output, "output")?;
                e.pose = addr(pose, "pose")?;
                e.authority = authority.unwrap_or(0);
                match links {
                    Some(v) if is_communicator => {
                        let all = links_at(v, i, at)?;
                        has_links = !all.is_empty();
                        // The UDP links are built by the host; the others by build_node.
                        e.links = all.into_iter().filter_map(LinkFile::into_udp).collect();
                    }
                    Some(_) => {
                        return Err(format!(
                            "{}: host[{i}].links: `links` is for the communicator, not `{name}`",
                            at(&format!("host[{i}].links"))
                        ))
                    }
                    None => {}
                }
            }
            if is_communicator && !has_links {
                return Err(format!(
                    "{}: host[{i}]: `communicator` needs its data links: `{{ component: communicator, links: [{{ id: 1, udp: {{ bind: IP:PORT, peer: IP:PORT }} }}] }}`",
                    at(&format!("host[{i}]"))
                ));
            }
            if is_communicator
                && out
                    .iter()
                    .any(|o| matches!(o, Hosted::Stock(p) if p.stock == stock))
            {
                return Err(format!(
                    "{}: host[{i}]: a second `communicator`: a node hosts at most one (the subsystem's gateway)",
                    at(&key)
                ));
            }
            let clash = out.iter().any(|o| match o {
                Hosted::Stock(p) => p.stock == e.stock && p.instance == e.instance,
                Hosted::Vehicle | Hosted::Arm => false,
            });
            if clash {
                return Err(format!(
                    "{}: `{name}` instance {} is hosted twice",
                    at(&key),
                    e.instance
                ));
            }
            out.push(Hosted::Stock(e));
        }
        Ok(out)
    }

    /// The `host:` entries (checked by [`NodeFile::load`]).
    pub fn hosted(&self) -> Vec<Hosted> {
        self.hosted_at(&|k| k.to_string()).unwrap_or_default()
    }

    /// The data links of the communicator this node hosts (none if it hosts none).
    pub fn communicator_links(&self) -> Vec<LinkFile> {
        self.communicator_link_files()
            .map(|(_, links)| links)
            .unwrap_or_default()
    }

    /// The `links:` of the communicator this node hosts, and the index of its `host:`
    /// entry (checked by [`NodeFile::load`]).
    fn communicator_link_files(&self) -> Option<(usize, Vec<LinkFile>)> {
        use jaus_sim::host::Stock;
        self.host.iter().enumerate().find_map(|(i, h)| match h {
            HostItem::Component {
                component,
                links: Some(v),
                ..
            } if Stock::by_name(component).map(Stock::id)
                == Some(jaus::components::communicator::ID) =>
            {
                Some((i, links_at(v, i, &|k| k.to_string()).unwrap_or_default()))
            }
            _ => None,
        })
    }

    /// The QUIC links' key files (relative to the directory of the node file `path`)
    /// read and their configurations checked, before anything is bound (`at` gives the
    /// file:line:column of a YAML path).
    fn check_quic_links(&self, path: &Path, at: &dyn Fn(&str) -> String) -> Result<(), String> {
        let Some((i, links)) = self.communicator_link_files() else {
            return Ok(());
        };
        let dir = path.parent().unwrap_or_else(|| Path::new("."));
        for (j, link) in links.iter().enumerate() {
            let LinkFile::Quic(q) = link else { continue };
            let here = format!("host[{i}].links[{j}].quic");
            let c = q.config(dir).map_err(|(field, e)| {
                let f = format!("{here}.{field}");
                format!("{}: {f}: {e}", at(&f))
            })?;
            c.check()
                .map_err(|e| format!("{}: {here}: {e}", at(&here)))?;
        }
        Ok(())
    }

    /// The communicator of entry `e` over its links, UDP ones built by the host as for
    /// any stock component, QUIC ones (key files relative to the directory of the node
    /// file `path`) here.
    fn build_communicator(
        &self,
        host: &mut jaus_sim::host::Host,
        e: &jaus_sim::host::Entry,
        path: &Path,
    ) -> Result<Box<dyn jaus::component::Endpoint>, String> {
        use jaus::stock::communicator::DataLink;
        let links = self.communicator_links();
        let dir = path.parent().unwrap_or_else(|| Path::new("."));
        let quic = |q: &QuicLinkFile| -> Result<jaus_quic::QuicLink, String> {
            let c = q
                .config(dir)
                .map_err(|(_, e)| format!("communicator: data link {}: {e}", q.id))?;
            jaus_quic::QuicLink::bind(c).map_err(|e| format!("communicator: {e}"))
        };
        let built = if links.iter().all(|l| matches!(l, LinkFile::Udp(_))) {
            // A communicator over UDP links only: `CommunicatorEndpoint<UdpLink>`.
            host.build(e)
        } else if links.iter().all(|l| matches!(l, LinkFile::Quic(_))) {
            // Over QUIC links only: `CommunicatorEndpoint<QuicLink>`.
            let mut made = Vec::new();
            for l in &links {
                if let LinkFile::Quic(q) = l {
                    made.push(quic(q)?);
                }
            }
            host.build_communicator(e, made)
        } else {
            // A mix: `CommunicatorEndpoint<Box<dyn DataLink>>`.
            let mut made: Vec<Box<dyn DataLink>> = Vec::new();
            for l in &links {
                made.push(match l {
                    LinkFile::Udp(c) => Box::new(
                        jaus::net::udp::link::UdpLink::bind(c.clone())
                            .map_err(|e| format!("communicator: {e}"))?,
                    ),
                    LinkFile::Quic(q) => Box::new(quic(q)?),
                });
            }
            host.build_communicator(e, made)
        };
        built.map_err(|e| e.to_string())
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
        if let Some(m) = &self.multicast {
            c.multicast = Some(SocketAddr::from((m.group, self.bind.port())));
        }
        c.communicator = self.communicator();
        // Checked by `load`.
        c.policy = self
            .policy
            .as_ref()
            .and_then(|p| p.policy(&|k| k.to_string()).ok());
        c
    }

    /// The node this file describes, its `host:` entries built and added, starting at
    /// `t0` (`path`: the file, for the errors).
    pub fn build_node(&self, path: &Path, t0: Instant) -> Result<Node, String> {
        let mut node = Node::new(self.node_config(), t0);
        let hosted = self.hosted();
        let mut host = jaus_sim::host::Host::new(self.subsystem, self.node, t0);
        if hosted.iter().any(
            |h| matches!(h, Hosted::Stock(e) if e.stock.id() == jaus::components::reflexive_driver::ID),
        ) {
            host.expect_reflexive_driver();
        }
        // One `Hosted` per `host:` entry, in order.
        for (i, h) in hosted.into_iter().enumerate() {
            let parts = match h {
                Hosted::Vehicle => {
                    jaus_sim::demo::vehicle_at(
                        t0,
                        &jaus_sim::demo::Options::default(),
                        self.subsystem,
                        self.node,
                    )
                    .0
                }
                Hosted::Arm => jaus_sim::arm_demo::arm_components(
                    &jaus_sim::SimArm::new(jaus_sim::ArmParams::six_axis()),
                    self.subsystem,
                    self.node,
                    t0,
                ),
                Hosted::Stock(e) if e.stock.id() == jaus::components::communicator::ID => {
                    vec![self
                        .build_communicator(&mut host, &e, path)
                        .map_err(|e| format!("{}: host[{i}]: {e}", path.display()))?]
                }
                Hosted::Stock(e) => vec![host
                    .build(&e)
                    .map_err(|e| format!("{}: host[{i}]: {e}", path.display()))?],
            };
            for p in parts {
                node.add_boxed(p)
                    .map_err(|e| format!("{}: host[{i}]: {e}", path.display()))?;
            }
        }
        Ok(node)
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

/// `jaus node --config FILE [--capture PCAPNG]`: runs a node until interrupted (or for
/// `duration`), printing the system tree when it changed, at most once a second; with
/// `capture`, every datagram it receives and sends is written to that pcapng file.
pub fn node(
    config: &Path,
    duration: Option<Duration>,
    capture: Option<&Path>,
    stop: &AtomicBool,
    out: &mut impl Write,
) -> Result<(), String> {
    let file = NodeFile::load(config)?;
    let t0 = Instant::now();
    let mut node = file.build_node(config, t0)?;
    let _ = writeln!(
        out,
        "node {} on {} ({:?}), peers {:?}",
        node.address(),
        file.bind,
        file.framing,
        file.peers
    );
    let _ = match node.policy() {
        Some(p) if !p.policy().is_open() => writeln!(out, "access policy: {}", p.policy().describe()),
        _ => writeln!(
            out,
            "access: open (no `policy:`): any sender that reaches this node may command its components and take control of them"
        ),
    };
    if let Some(c) = file.communicator() {
        let links: Vec<String> = file
            .communicator_links()
            .iter()
            .map(|l| format!("link {} {} {} -> {}", l.id(), l.kind(), l.bind(), l.peer()))
            .collect();
        let _ = writeln!(
            out,
            "other subsystems through the communicator {c}{}{}",
            if links.is_empty() { "" } else { ": " },
            links.join(", ")
        );
    }
    let _ = out.flush();
    let mut printer = TreePrinter::new(Duration::from_secs(1));
    let socket = std::net::UdpSocket::bind(file.bind).map_err(|e| format!("{}: {e}", file.bind))?;
    let local = socket
        .local_addr()
        .map_err(|e| format!("{}: {e}", file.bind))?;
    if let Some(m) = &file.multicast {
        let at =
            |e: std::io::Error| format!("{}: multicast group {}: {e}", config.display(), m.group);
        if !m.group.is_multicast() {
            return Err(at(std::io::Error::other("not a multicast address")));
        }
        let interface = m.interface.unwrap_or(std::net::Ipv4Addr::UNSPECIFIED);
        socket.join_multicast_v4(&m.group, &interface).map_err(at)?;
        socket
            .set_multicast_ttl_v4(m.ttl.unwrap_or(32))
            .map_err(at)?;
        socket
            .set_multicast_loop_v4(m.loopback.unwrap_or(false))
            .map_err(at)?;
        let _ = writeln!(
            out,
            "multicast discovery: group {}:{} (ttl {}, interface {interface})",
            m.group,
            local.port(),
            m.ttl.unwrap_or(32)
        );
    }
    let mut writer = match capture {
        Some(p) => Some(
            crate::capture::CaptureWriter::create(p)
                .map_err(|e| format!("{}: {e}", p.display()))?,
        ),
        None => None,
    };
    let mut capture_error = None;
    let mut last_flush = Instant::now();
    let oj = match &file.openjaus_components {
        Some(o) => {
            let (control, data) = o.sockets();
            let bind = |a: SocketAddr| {
                std::net::UdpSocket::bind(a).map_err(|e| {
                    format!("{}: OpenJAUS component socket {a}: {e}", config.display())
                })
            };
            let pair = (bind(control)?, bind(data)?);
            let _ = writeln!(
                out,
                "OpenJAUS component interface: control {control}, data {data}"
            );
            Some(pair)
        }
        None => None,
    };
    let sockets = udp::NodeSockets {
        network: &socket,
        component_control: oj.as_ref().map(|p| &p.0),
        component_data: oj.as_ref().map(|p| &p.1),
    };
    let io = file.io.clone().unwrap_or_default().options();
    let result = udp::run_node(
        &mut node,
        sockets,
        &io,
        stop,
        duration.map(|d| t0 + d),
        |n| {
            let now = Instant::now();
            if let Some(text) = printer.poll(now, n.tree_version(), n.tree()) {
                let _ = writeln!(
                    out,
                    "--- system tree at {:.1} s\n{text}",
                    t0.elapsed().as_secs_f64()
                );
                let _ = out.flush();
            }
        },
        |direction, peer, datagram| {
            let Some(w) = writer.as_mut() else {
                return;
            };
            let time = std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .unwrap_or_default();
            let (src, dst) = match direction {
                udp::Direction::Received => (peer, local),
                udp::Direction::Sent => (local, peer),
            };
            let mut written = w.write(time, src, dst, datagram);
            if written.is_ok() && last_flush.elapsed() >= Duration::from_secs(1) {
                last_flush = Instant::now();
                written = w.flush();
            }
            if let Err(e) = written {
                // Stop capturing; the node keeps running.
                capture_error.get_or_insert(e.to_string());
                writer = None;
            }
        },
    )
    .map_err(|e| format!("{}: {e}", file.bind));
    // What the node counted, for whoever watched it run (one line, `key value` pairs).
    let st = node.stats();
    let (reassembly, buffered) = node.reassembly();
    let (mut missed, mut refused) = (0, 0);
    for (_, c) in node.component_stats() {
        missed += c.reports_missed;
        refused += c.not_controller + c.wrong_state + c.invalid;
    }
    let _ = writeln!(
        out,
        "stats: received {} sent {} delivered_local {} bad_framing {} bad_packet {} from_self {} not_for_us {} no_such_component {} outbox_full {} flooded {} reassembly_timed_out {} reassembly_over_limit {} reassembly_buffered {buffered} reports_missed {missed} commands_refused {refused} to_communicator {} from_communicator {} not_via_communicator {} policy_refused {}",
        st.received,
        st.sent,
        st.delivered_local,
        st.bad_framing,
        st.bad_packet,
        st.from_self,
        st.not_for_us,
        st.no_such_component,
        st.outbox_full,
        st.flooded,
        reassembly.timed_out,
        reassembly.over_limit,
        st.to_communicator,
        st.from_communicator,
        st.not_via_communicator,
        st.policy_refused,
    );
    let _ = out.flush();
    if let (Some(w), Some(p)) = (writer.as_mut(), capture) {
        w.flush().map_err(|e| format!("{}: {e}", p.display()))?;
    }
    if let (Some(e), Some(p)) = (capture_error, capture) {
        return Err(format!("{}: capture stopped: {e}", p.display()));
    }
    result
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
