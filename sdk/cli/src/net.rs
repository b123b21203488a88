//! The network commands of the `jaus` CLI: `node`, `discover`, the operator's session
//! (`send`, `query`, `watch`) and the demo's operator over UDP.
//!
//! # The CLI's place in a system
//!
//! The CLI is a real component (a System Commander at `--me`), never a second voice for
//! a node manager it is not:
//!
//! * when `--me` is on the node it talks to (e.g. `--me 20.1.40.1` with the peer being
//!   node 20.1), it **joins that node** as one of its components through the node's
//!   socket ([`jaus::net::Attached`]): no node manager of its own, heartbeats to the
//!   node's manager, identification and services answered by its runtime;
//! * otherwise it runs a **node of its own** (`--me`'s subsystem and node, its own node
//!   manager) beside the peers.
//!
//! `--mode auto` (the default) decides by asking the peers for the identification of
//! `--me`'s node before anything else: a node that answers as that node is joined.
//!
//! # Sockets
//!
//! JUDP peers such as OpenJAUS send every reply to **port 3794 of the sender's IP
//! address**. The default bind is therefore `auto`: port 3794 on a loopback address of
//! its own (127.0.0.2, .3, ...) when the peers are on loopback, else `0.0.0.0:3794`.

use std::collections::VecDeque;
use std::io::{BufRead, Write};
use std::net::{IpAddr, Ipv4Addr, SocketAddr, UdpSocket};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use jaus::codec::Encode;
use jaus::component::{Component, Config, Refused};
use jaus::components::system_commander::{self, Ctx, SystemCommander};
use jaus::json::JsonPacket;
use jaus::messages::{Message, ReleaseComponentControl};
use jaus::net::framing::{Reassembler, ReassemblyLimits};
use jaus::net::{
    udp, Attached, AttachedConfig, Datagram, Framing, Node, NodeConfig, Participant, SystemTree,
};
use jaus::wire::{AckNak, DataFlag, MessageClass, HEADER_LEN};
use jaus::{Address, CommandCode, Header, JausMessage};

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

/// How the CLI takes its place (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Mode {
    /// Join the peer that answers as `--me`'s node; else run a node of its own.
    #[default]
    Auto,
    /// Join the peer's node as one of its components.
    Join,
    /// Run a node of its own.
    Node,
}

impl std::str::FromStr for Mode {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "auto" => Ok(Mode::Auto),
            "join" => Ok(Mode::Join),
            "node" => Ok(Mode::Node),
            other => Err(format!("unknown mode `{other}` (auto, join or node)")),
        }
    }
}

/// Options of the network commands that act as a component (`discover`, `send`,
/// `query`, `watch`).
#[derive(Debug, Clone)]
pub struct Client {
    /// This tool's address (a System Commander).
    pub me: Address,
    /// Local socket (`None`: chosen as the module docs say).
    pub bind: Option<SocketAddr>,
    /// Peers.
    pub peers: Vec<SocketAddr>,
    /// Framing.
    pub framing: Framing,
    /// How long to wait for answers.
    pub wait: Duration,
    /// How to take a place in the system.
    pub mode: Mode,
}

/// The CLI's own component: a System Commander whose runtime answers the discovery
/// queries of node managers, and which opens and ends the service connections it is
/// asked for.
#[derive(Debug, Default)]
pub struct Commander {
    /// Service connections to open: (provider, report, rate, presence vector).
    pub open: Vec<(Address, CommandCode, f64, u32)>,
    /// Service connections to end.
    pub close: Vec<(Address, CommandCode)>,
}

impl SystemCommander for Commander {
    fn on_other_message(
        &mut self,
        _ctx: &mut Ctx<'_>,
        _msg: &Message,
    ) -> Result<Option<Message>, Refused> {
        // Everything addressed to the CLI is printed by the session's tap.
        Ok(None)
    }

    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        for (p, r, hz, pv) in self.open.drain(..) {
            ctx.create_service_connection(p, r, hz, pv);
        }
        for (p, r) in self.close.drain(..) {
            ctx.terminate_service_connection(p, r);
        }
    }
}

type Tool = Component<system_commander::Dispatch<Commander>>;

/// The CLI on the network: a node of its own or components attached to the peer's node.
#[derive(Debug)]
enum Link {
    Node(Box<Node>),
    Attached(Box<Attached>),
}

impl Link {
    fn host(&mut self) -> &mut dyn Participant {
        match self {
            Link::Node(n) => n.as_mut(),
            Link::Attached(a) => a.as_mut(),
        }
    }

    fn tool(&mut self, me: Address) -> Option<&mut Tool> {
        match self {
            Link::Node(n) => n.get_mut::<Tool>(me),
            Link::Attached(a) => a.get_mut::<Tool>(me),
        }
    }

    fn send(&mut self, now: Instant, header: Header, body: Vec<u8>) {
        match self {
            Link::Node(n) => n.send(now, header, body),
            Link::Attached(a) => a.send(now, header, body),
        }
    }

    /// Whether messages to `to` can go now (its node located, or attached).
    fn reaches(&self, to: Address) -> bool {
        match self {
            Link::Node(n) => {
                to.subsystem == 255
                    || to.node == 255
                    || n.peers().contains_key(&(to.subsystem, to.node))
            }
            Link::Attached(_) => true,
        }
    }
}

/// One line of output: a packet received (or sent, for the record) with its time.
#[derive(Debug, serde::Serialize)]
struct Line<'a> {
    /// Seconds since the session started.
    t: f64,
    /// UTC, seconds since 1970-01-01.
    utc: f64,
    #[serde(flatten)]
    packet: &'a JsonPacket,
}

/// An acknowledgement line (ACK/NAK carry no body).
#[derive(Debug, serde::Serialize)]
struct AckLine<'a> {
    t: f64,
    utc: f64,
    header: &'a Header,
    /// The message acknowledged.
    acknowledges: &'a str,
}

/// A packet addressed to the CLI that did not decode.
#[derive(Debug, serde::Serialize)]
struct RawLine<'a> {
    t: f64,
    utc: f64,
    header: &'a Header,
    error: String,
    body: String,
}

/// What the tap saw of one datagram.
enum Tapped {
    Packet(Box<JsonPacket>),
    Ack(Header),
    Raw(Header, Vec<u8>, String),
}

/// Reads what arrives for the CLI, before the hosts do, so that every message is
/// printed with its real header (flags, service-connection sequence numbers) and ACK/NAK
/// replies are seen.
struct Tap {
    me: Address,
    framing: Framing,
    reassembler: Reassembler,
}

impl Tap {
    /// A datagram for a component of this tool's node that is not this tool: another
    /// node with the same subsystem and node id is on the network.
    fn foreign_twin(&self, datagram: &[u8]) -> Option<Address> {
        let packet = self.framing.decode(datagram).ok()?;
        let h = Header::parse(packet).ok()?;
        let d = h.destination;
        (d.subsystem == self.me.subsystem
            && d.node == self.me.node
            && d.component != 255
            && d.instance != 255
            && d.component != 1
            && d != self.me)
            .then_some(d)
    }

    fn see(&mut self, now: Instant, datagram: &[u8]) -> Option<Tapped> {
        let packet = self.framing.decode(datagram).ok()?;
        let header = Header::parse(packet).ok()?;
        if packet.len() - HEADER_LEN != usize::from(header.data_size)
            || !header.destination.matches(&self.me)
            || header.source == self.me
        {
            return None;
        }
        if matches!(header.ack_nak, AckNak::Ack | AckNak::Nak) {
            return Some(Tapped::Ack(header));
        }
        let body = &packet[HEADER_LEN..];
        let (header, body) = if header.data_flag == DataFlag::Single {
            (header, body.to_vec())
        } else {
            self.reassembler.push(now, &header, body)?
        };
        Some(match Message::decode(header.command_code, &body) {
            Ok(message) => Tapped::Packet(Box::new(JsonPacket { header, message })),
            Err(e) => Tapped::Raw(header, body, e.to_string()),
        })
    }
}

/// What the session does with its time.
#[derive(Debug, Clone, Default)]
pub struct Script {
    /// Messages to send, in order, each to its destination.
    pub messages: Vec<(Address, Message)>,
    /// Also take messages from standard input (JSON lines), as they come.
    pub stdin: bool,
    /// Service connections to open: (provider, report, rate Hz, presence vector).
    pub service_connections: Vec<(Address, CommandCode, f64, u32)>,
    /// Print incoming query messages and heartbeats too.
    pub all: bool,
    /// End as soon as every message sent is answered (query → its report, command →
    /// ACK or NAK), or `wait` after the last one was sent when some are not.
    pub until_answered: bool,
    /// Stay this long after the last message (holding control, watching): `None` runs
    /// until interrupted.
    pub hold: Option<Duration>,
    /// Default destination of stdin lines without one.
    pub to: Option<Address>,
}

/// What a session saw.
#[derive(Debug, Default, Clone, PartialEq, Eq)]
pub struct Outcome {
    /// Messages printed.
    pub printed: usize,
    /// Messages sent.
    pub sent: usize,
    /// Sent messages answered (report, ACK or NAK).
    pub answered: usize,
    /// NAKs received.
    pub naks: usize,
    /// Whether anything at all came from a peer.
    pub heard: bool,
    /// Whether the CLI joined the peer's node (else it ran a node of its own).
    pub joined: bool,
    /// Bad input lines.
    pub bad_lines: usize,
    /// Control requests rejected (Reject Component Control received).
    pub rejected: usize,
    /// The socket the session used.
    pub local: Option<SocketAddr>,
    /// Another node answers as this tool's node (`--me`'s subsystem and node): the
    /// session stopped.
    pub conflict: Option<String>,
}

/// A message given to the CLI, in the shape [`jaus::json::parse_message`] reads
/// (`{"message": NAME, "fields": {...}}`, `fields` optional, or a whole line as `jaus
/// decode` prints it); the destination of its header, if it has one, is returned.
pub fn parse_message(json: &str) -> Result<(Option<Address>, Message), String> {
    let (header, message) = jaus::json::parse_message(json).map_err(|e| e.to_string())?;
    Ok((header.destination, message))
}

/// Picks the local socket: the one asked for, or port 3794 on an address of its own
/// (see the module docs).
pub fn bind_socket(bind: Option<SocketAddr>, peers: &[SocketAddr]) -> Result<UdpSocket, String> {
    if let Some(b) = bind {
        return UdpSocket::bind(b).map_err(|e| format!("cannot bind {b}: {e}"));
    }
    let loopback = !peers.is_empty() && peers.iter().all(|p| p.ip().is_loopback());
    if loopback {
        for x in 2..=254u8 {
            let ip = IpAddr::V4(Ipv4Addr::new(127, 0, 0, x));
            if peers.iter().any(|p| p.ip() == ip) {
                continue;
            }
            if let Ok(s) = UdpSocket::bind(SocketAddr::new(ip, 3794)) {
                return Ok(s);
            }
        }
        return Err("no free port 3794 on 127.0.0.2-254: JUDP peers answer port 3794 of the sender's address; give --bind ADDRESS:3794 with an address of this host".into());
    }
    let any = SocketAddr::new(IpAddr::V4(Ipv4Addr::UNSPECIFIED), 3794);
    UdpSocket::bind(any).map_err(|e| {
        format!("cannot bind {any}: {e}. JUDP peers (OpenJAUS) answer port 3794 of the sender's address, so this tool needs port 3794 on an address of its own: give --bind ADDRESS:3794 (or --bind ADDRESS:0 when the peer is a jaus node, which answers any port)")
    })
}

/// Says why nothing came back when nothing did.
pub fn silence_hint(socket: &SocketAddr, peers: &[SocketAddr], wait: Duration) -> String {
    format!(
        "no datagram from {peers:?} within {:.1} s. Is a node running there? JUDP peers (OpenJAUS) send their answers to port 3794 of the sender's IP address: this tool listened on {socket}{}",
        wait.as_secs_f64(),
        if socket.port() == 3794 {
            "".to_string()
        } else {
            "; bind to port 3794 of an address of your own (--bind 127.0.0.2:3794)".to_string()
        }
    )
}

fn unix_now() -> f64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64())
}

impl Client {
    /// Asks the peers who speaks for `--me`'s node: the peer whose node manager answers
    /// as that node is joined.
    fn probe(&self, socket: &UdpSocket) -> Option<SocketAddr> {
        // Asked of every node manager (a broadcast, so no node logs a message for a
        // subsystem it is not); the one answering as `--me`'s node is joined. Done as soon
        // as every peer has answered.
        let nm = Address::new(self.me.subsystem, self.me.node, 1, 1);
        let q = jaus::messages::QueryIdentification {
            query_field: jaus::messages::QueryLevel::Node,
        };
        let header = Header::new(
            jaus::messages::QueryIdentification::CODE,
            Address::new(255, 255, 1, 1),
            self.me,
        );
        let body = q.to_bytes().ok()?;
        let packet = jaus::Packet::new(header, body).to_bytes().ok()?;
        let bytes = self.framing.encode(&packet);
        for p in &self.peers {
            let _ = socket.send_to(&bytes, p);
        }
        let deadline = Instant::now() + Duration::from_millis(400);
        let mut answered: Vec<SocketAddr> = Vec::new();
        let mut buf = vec![0u8; 8192];
        while let Some(left) = deadline.checked_duration_since(Instant::now()) {
            if !self.peers.is_empty() && self.peers.iter().all(|p| answered.contains(p)) {
                break;
            }
            let _ = socket.set_read_timeout(Some(left.max(Duration::from_millis(1))));
            let Ok((n, from)) = socket.recv_from(&mut buf) else {
                break;
            };
            let Ok(packet) = self.framing.decode(&buf[..n]) else {
                continue;
            };
            if let Ok(h) = Header::parse(packet) {
                if h.command_code == jaus::messages::ReportIdentification::CODE {
                    if h.source == nm {
                        return Some(from);
                    }
                    answered.push(from);
                }
            }
        }
        None
    }

    fn link(&self, socket: &UdpSocket, t0: Instant) -> Result<Link, String> {
        if !self.me.is_valid() || self.me.component == 1 {
            return Err(format!(
                "--me {}: not a component address (ids 1-254, component not 1: the node manager's)",
                self.me
            ));
        }
        let join = match self.mode {
            Mode::Node => None,
            Mode::Join => Some(
                self.probe(socket)
                    .or(self.peers.first().copied())
                    .ok_or("--mode join needs a --peer: the socket of the node to join")?,
            ),
            Mode::Auto => self.probe(socket),
        };
        let tool = system_commander::component(
            self.me,
            Commander::default(),
            Config {
                identification: Some("jaus CLI".into()),
                ..Config::default()
            },
            t0,
        );
        Ok(match join {
            Some(node_socket) => {
                tracing::info!(me = %self.me, %node_socket, "joining the node as one of its components");
                let mut a = Attached::new(
                    AttachedConfig {
                        subsystem: self.me.subsystem,
                        node: self.me.node,
                        node_socket,
                        framing: self.framing,
                        reassembly: ReassemblyLimits::default(),
                        max_outbox: 8192,
                    },
                    t0,
                );
                a.add(tool).map_err(|e| e.to_string())?;
                Link::Attached(Box::new(a))
            }
            None => {
                let mut c = NodeConfig {
                    subsystem: self.me.subsystem,
                    node: self.me.node,
                    framing: self.framing,
                    peers: self.peers.clone(),
                    ..NodeConfig::default()
                };
                c.manager.node_name = "jaus CLI".into();
                c.manager.subsystem_name = "jaus CLI".into();
                let mut node = Node::new(c, t0);
                node.add(tool).map_err(|e| e.to_string())?;
                Link::Node(Box::new(node))
            }
        })
    }

    /// Runs one session: takes its place, sends `script`'s messages in order (each
    /// after the previous one was answered, or after a short pause when the receiver
    /// does not acknowledge), opens its service connections, prints every message
    /// addressed to it as a timestamped JSON line as it arrives, and at the end ends
    /// its service connections and gives back the control it took.
    pub fn session(
        &self,
        script: &Script,
        stop: &AtomicBool,
        out: &mut impl Write,
        err: &mut impl Write,
    ) -> Result<Outcome, String> {
        let socket = bind_socket(self.bind, &self.peers)?;
        let local = socket.local_addr().map_err(|e| e.to_string())?;
        let t0 = Instant::now();
        let mut link = self.link(&socket, t0)?;
        let mut outcome = Outcome {
            joined: matches!(link, Link::Attached(_)),
            local: Some(local),
            ..Outcome::default()
        };
        // Commands wait until the system knows this tool (a node manager asked for its
        // identification or services): OpenJAUS rejects a controller it cannot find in its
        // system tree. Queries go at once.
        let mut known = false;
        let known_by = Duration::from_millis(2500);
        let mut requested: Vec<Address> = Vec::new();
        let me = self.me;
        let lines = script.stdin.then(stdin_reader);
        let mut queue: VecDeque<(Address, Message)> = script.messages.iter().cloned().collect();
        let mut stdin_open = lines.is_some();
        // The message waiting for its answer: (code answering it, destination, deadline).
        let mut pending: Option<(Option<CommandCode>, Address, CommandCode, Instant)> = None;
        let mut last_sent: Option<Instant> = None;
        let mut controlled: Vec<Address> = Vec::new();
        let mut opened = false;
        let mut tap = Tap {
            me,
            framing: self.framing,
            reassembler: Reassembler::new(ReassemblyLimits::default()),
        };
        let mut done = false;
        let step = Duration::from_millis(500);
        let mut buf = vec![0u8; 8 + 4096 + 64];
        let _ = socket.set_nonblocking(false);
        loop {
            let now = Instant::now();
            if stop.load(Ordering::Relaxed) {
                break;
            }
            // Input lines.
            if let Some(rx) = &lines {
                loop {
                    match rx.try_recv() {
                        Ok(line) => {
                            if line.trim().is_empty() {
                                continue;
                            }
                            match parse_message(&line) {
                                Ok((to, m)) => match to.or(script.to) {
                                    Some(to) => queue.push_back((to, m)),
                                    None => {
                                        outcome.bad_lines += 1;
                                        let _ = writeln!(err, "error: {}: no destination (--to, or a header with a destination)", m.name());
                                    }
                                },
                                Err(e) => {
                                    outcome.bad_lines += 1;
                                    let _ = writeln!(err, "error: {e}");
                                }
                            }
                        }
                        Err(mpsc::TryRecvError::Empty) => break,
                        Err(mpsc::TryRecvError::Disconnected) => {
                            stdin_open = false;
                            break;
                        }
                    }
                }
            }
            // The next message, once the previous one is answered or timed out.
            if pending.is_some_and(|p| now >= p.3) {
                pending = None;
            }
            if pending.is_none() {
                if let Some((to, next)) = queue.front() {
                    let waited = now.saturating_duration_since(t0);
                    let ready = (link.reaches(*to) || waited > Duration::from_millis(300))
                        && (known
                            || next.code().class() != MessageClass::Command
                            || waited > known_by);
                    if ready {
                        let (to, msg) = queue.pop_front().expect("front checked");
                        let body = msg.to_bytes().map_err(|e| format!("{}: {e}", msg.name()))?;
                        let code = msg.code();
                        let mut header = Header::new(code, to, me);
                        let class = code.class();
                        if class == MessageClass::Command {
                            header.ack_nak = AckNak::Request;
                        }
                        if matches!(msg, Message::RequestComponentControl(_)) {
                            requested.push(to);
                        }
                        if matches!(msg, Message::ReleaseComponentControl(_)) {
                            controlled.retain(|a| *a != to);
                            requested.retain(|a| *a != to);
                        }
                        let answer = match class {
                            MessageClass::Query => jaus::MessageInfo::of(code)
                                .and_then(|i| i.report)
                                .and_then(|r| jaus::messages::MESSAGES.iter().find(|m| m.name == r))
                                .map(|m| m.code)
                                .or(code.complement()),
                            _ => None,
                        };
                        let wait = if class == MessageClass::Query {
                            self.wait
                        } else {
                            step
                        };
                        pending = Some((answer, to, code, now + wait));
                        link.send(now, header, body);
                        outcome.sent += 1;
                        last_sent = Some(now);
                    }
                }
            }
            if !opened && !script.service_connections.is_empty() {
                opened = true;
                if let Some(t) = link.tool(me) {
                    t.behaviour_mut()
                        .0
                        .open
                        .extend(script.service_connections.iter().copied());
                }
            }
            // Done?
            let idle = queue.is_empty() && pending.is_none() && !stdin_open;
            if idle && !done {
                let since = last_sent.unwrap_or(t0);
                let all_answered = outcome.answered >= outcome.sent;
                let finished = match script.hold {
                    Some(h) => now.saturating_duration_since(since) >= h,
                    None => false,
                } || (script.until_answered
                    && (all_answered || now.saturating_duration_since(since) >= self.wait));
                if finished {
                    done = true;
                }
            }
            if done {
                break;
            }
            // The network.
            let host = link.host();
            let wake = host
                .poll_timeout()
                .map_or(Duration::from_millis(50), |t| {
                    t.saturating_duration_since(Instant::now())
                })
                .clamp(Duration::from_micros(100), Duration::from_millis(50));
            let _ = socket.set_read_timeout(Some(wake));
            match socket.recv_from(&mut buf) {
                Ok((n, from)) => {
                    let now = Instant::now();
                    if self.peers.contains(&from) || matches!(link, Link::Attached(_)) {
                        outcome.heard = true;
                    }
                    if !outcome.joined {
                        if let Some(other) = tap.foreign_twin(&buf[..n]) {
                            let text = format!("another node answers as {}.{} (a message for {other} arrived from {from}); this tool's --me {me} is on that node: use --mode join to join it, or a --me on a node of its own", me.subsystem, me.node);
                            let _ = writeln!(err, "error: {text}");
                            outcome.conflict = Some(text);
                            break;
                        }
                    }
                    if let Some(seen) = tap.see(now, &buf[..n]) {
                        let (t, utc) = ((now - t0).as_secs_f64(), unix_now());
                        match seen {
                            Tapped::Ack(h) => {
                                let name =
                                    jaus::MessageInfo::of(h.command_code).map_or("?", |i| i.name);
                                if let Some(p) =
                                    pending.filter(|p| p.1 == h.source && p.2 == h.command_code)
                                {
                                    let _ = p;
                                    pending = None;
                                }
                                outcome.answered += 1;
                                if h.ack_nak == AckNak::Nak {
                                    outcome.naks += 1;
                                    let _ = writeln!(err, "NAK from {} for {name}: refused (the receiver's log names the reason)", h.source);
                                }
                                let line = AckLine {
                                    t,
                                    utc,
                                    header: &h,
                                    acknowledges: name,
                                };
                                let _ = writeln!(
                                    out,
                                    "{}",
                                    serde_json::to_string(&line).unwrap_or_default()
                                );
                                outcome.printed += 1;
                            }
                            Tapped::Packet(p) => {
                                let code = p.header.command_code;
                                let from_addr = p.header.source;
                                match &p.message {
                                    Message::QueryIdentification(_) | Message::QueryServices(_) => {
                                        known = true;
                                    }
                                    Message::ConfirmComponentControl(c)
                                        if c.response_code
                                            == jaus::messages::ControlResponse::ControlAccepted
                                            && requested.contains(&from_addr)
                                            && !controlled.contains(&from_addr) =>
                                    {
                                        controlled.push(from_addr);
                                    }
                                    Message::RejectComponentControl(_) => {
                                        if requested.contains(&from_addr)
                                            || controlled.contains(&from_addr)
                                        {
                                            outcome.rejected += 1;
                                            let _ = writeln!(err, "control of {from_addr} rejected (or taken by a component of higher authority)");
                                        }
                                        controlled.retain(|a| *a != from_addr);
                                        requested.retain(|a| *a != from_addr);
                                    }
                                    _ => {}
                                }
                                let answer = pending.is_some_and(|q| {
                                    q.0 == Some(code) && q.1.matches(&p.header.source)
                                });
                                if answer {
                                    pending = None;
                                    outcome.answered += 1;
                                }
                                let noise = !answer
                                    && (code.class() == MessageClass::Query
                                        || matches!(p.message, Message::ReportHeartbeatPulse(_)));
                                if script.all || !noise {
                                    let line = Line { t, utc, packet: &p };
                                    let _ = writeln!(
                                        out,
                                        "{}",
                                        serde_json::to_string(&line).unwrap_or_default()
                                    );
                                    outcome.printed += 1;
                                }
                            }
                            Tapped::Raw(h, body, e) => {
                                let line = RawLine {
                                    t,
                                    utc,
                                    header: &h,
                                    error: e,
                                    body: jaus::hex::encode(&body),
                                };
                                let _ = writeln!(
                                    out,
                                    "{}",
                                    serde_json::to_string(&line).unwrap_or_default()
                                );
                                outcome.printed += 1;
                            }
                        }
                        let _ = out.flush();
                    }
                    link.host().handle_datagram(now, from, &buf[..n]);
                }
                Err(e)
                    if matches!(
                        e.kind(),
                        std::io::ErrorKind::WouldBlock
                            | std::io::ErrorKind::TimedOut
                            | std::io::ErrorKind::ConnectionReset
                    ) => {}
                Err(e) => return Err(format!("{local}: {e}")),
            }
            let host = link.host();
            host.handle_timeout(Instant::now());
            flush(host, &socket);
        }
        // End cleanly: service connections ended, control given back.
        let now = Instant::now();
        if let Some(t) = link.tool(me) {
            let sc: Vec<(Address, CommandCode)> = script
                .service_connections
                .iter()
                .map(|s| (s.0, s.1))
                .collect();
            t.behaviour_mut().0.close.extend(sc);
        }
        for to in controlled {
            if let Ok(body) = (ReleaseComponentControl {}).to_bytes() {
                link.send(
                    now,
                    Header::new(ReleaseComponentControl::CODE, to, me),
                    body,
                );
            }
        }
        let host = link.host();
        host.handle_timeout(now + Duration::from_millis(60));
        flush(host, &socket);
        Ok(outcome)
    }

    /// `jaus discover`: a node of its own listens for `wait`, then the system tree.
    pub fn discover(&self, stop: &AtomicBool) -> Result<(SystemTree, bool), String> {
        let socket = bind_socket(self.bind, &self.peers)?;
        let t0 = Instant::now();
        let client = Client {
            mode: Mode::Node,
            ..self.clone()
        };
        let Link::Node(mut node) = client.link(&socket, t0)? else {
            return Err("discover runs a node of its own".into());
        };
        let mut heard = false;
        let peers = self.peers.clone();
        let end = t0 + self.wait;
        let mut buf = vec![0u8; 8 + 4096 + 64];
        while Instant::now() < end && !stop.load(Ordering::Relaxed) {
            let _ = socket.set_read_timeout(Some(Duration::from_millis(20)));
            if let Ok((n, from)) = socket.recv_from(&mut buf) {
                heard |= peers.contains(&from);
                node.handle_datagram(Instant::now(), from, &buf[..n]);
            }
            node.handle_timeout(Instant::now());
            flush(node.as_mut(), &socket);
        }
        Ok((node.tree().clone(), heard))
    }

    /// The socket this client would use, for messages.
    pub fn describe_bind(&self) -> String {
        self.bind
            .map_or("auto (port 3794 on an address of its own)".into(), |b| {
                b.to_string()
            })
    }
}

fn flush(host: &mut dyn Participant, socket: &UdpSocket) {
    while let Some(Datagram { to, bytes }) = host.poll_transmit() {
        if let Err(e) = socket.send_to(&bytes, to) {
            tracing::debug!(%to, "send failed: {e}");
        }
    }
}

/// Standard input, line by line, on a thread of its own.
fn stdin_reader() -> mpsc::Receiver<String> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in std::io::stdin().lock().lines() {
            let Ok(line) = line else { break };
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    rx
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
    node.add(jaus_sim::demo::operator(t0, &opts))
        .map_err(|e| e.to_string())?;
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
                stop.store(true, Ordering::Relaxed);
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

/// The CLI's address when `--me` is not given: S.1.40.1 with S in 200–253 from the
/// process id. Each session is a subsystem of its own because OpenJAUS keeps one IP
/// address per subsystem: two sessions as two nodes of one subsystem, on two sockets,
/// would split its traffic between them (seen in the OpenJAUS trial).
pub fn default_me() -> Address {
    Address::new(200 + (std::process::id() % 54) as u8, 1, 40, 1)
}
