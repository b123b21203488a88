//! How the CLI takes its place in a system (joins `--me`'s node or runs a node of its
//! own), its own component, and its socket.

use std::net::SocketAddr;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::{Component, Config, Refused};
use jaus::components::system_commander::{self, Ctx, SystemCommander};
use jaus::messages::Message;
use jaus::net::framing::ReassemblyLimits;
use jaus::net::{
    Attached, AttachedConfig, Datagram, Framing, Node, NodeConfig, Participant, SystemTree,
};
use jaus::stock::commander::{ControlEvent, ControlKeeper};
use jaus::{Address, CommandCode, Header, JausMessage};

use super::port::Port;

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
    /// Peers (on a serial line, [`SERIAL_FAR_END`](super::port::SERIAL_FAR_END)).
    pub peers: Vec<SocketAddr>,
    /// What carries the datagrams (UDP unless `--peer` said `tcp://` or `serial://`).
    pub carrier: super::port::Carrier,
    /// Framing.
    pub framing: Framing,
    /// How long to wait for answers.
    pub wait: Duration,
    /// How to take a place in the system.
    pub mode: Mode,
    /// The name the tool gives itself in others' system trees (its identification, and
    /// its node's and subsystem's when it runs a node of its own). The CLI's is
    /// `jaus CLI`.
    pub name: String,
    /// Confirm every command of a session by its effect (`jaus send --confirm`,
    /// [`confirm`](super::confirm)): acknowledged, confirmed by read-back, refused or
    /// not confirmed, printed per command.
    pub confirm: bool,
}

/// The CLI's own component: a System Commander whose runtime answers the discovery
/// queries of node managers, and which opens and ends the service connections it is
/// asked for, and takes and keeps the control it is asked to keep.
#[derive(Debug, Default)]
pub struct Commander {
    /// Service connections to open: (provider, report, rate, presence vector).
    pub open: Vec<(Address, CommandCode, f64, u32)>,
    /// Service connections to end.
    pub close: Vec<(Address, CommandCode)>,
    /// Control to take and keep from the next tick: (target, authority; `None`: the
    /// component's own).
    pub keep: Vec<(Address, Option<u8>)>,
    /// Control kept to give back at the next tick.
    pub release: Vec<Address>,
    /// Control taken and kept: asked for again when lost (`jaus::stock::commander`).
    /// Nothing is kept unless `keep` asks.
    pub keeper: ControlKeeper,
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
            if let Err(e) = ctx.create_service_connection(p, r, hz, pv) {
                tracing::warn!(provider = %p, report = %r, "service connection not requested: {e}");
            }
        }
        for (p, r) in self.close.drain(..) {
            ctx.terminate_service_connection(p, r);
        }
        // Releases first: a release and a new request of one target in one tick keep
        // the new request.
        for target in self.release.drain(..) {
            self.keeper.release(ctx, target);
        }
        for (target, authority) in self.keep.drain(..) {
            match authority {
                Some(a) => self.keeper.keep_with(target, a),
                None => self.keeper.keep(target),
            }
        }
        for e in self.keeper.tick(ctx) {
            if let ControlEvent::Lost(a) = e {
                tracing::info!(component = %a, "control lost; asking again");
            }
        }
    }
}

pub type Tool = Component<system_commander::Dispatch<Commander>>;

/// The CLI on the network: a node of its own or components attached to the peer's node.
#[derive(Debug)]
pub enum Link {
    /// A node of its own (its own node manager, its own system tree).
    Node(Box<Node>),
    /// Components of the peer's node (joined through the node's socket).
    Attached(Box<Attached>),
}

impl Link {
    /// The node or the attached components, as the I/O loop drives them.
    pub fn host(&mut self) -> &mut dyn Participant {
        match self {
            Link::Node(n) => n.as_mut(),
            Link::Attached(a) => a.as_mut(),
        }
    }

    /// This tool's component (`--me`).
    pub fn tool(&mut self, me: Address) -> Option<&mut Tool> {
        match self {
            Link::Node(n) => n.get_mut::<Tool>(me),
            Link::Attached(a) => a.get_mut::<Tool>(me),
        }
    }

    /// Sends a packet from a component of this link.
    pub fn send(&mut self, now: Instant, header: Header, body: Vec<u8>) {
        match self {
            Link::Node(n) => n.send(now, header, body),
            Link::Attached(a) => a.send(now, header, body),
        }
    }

    /// What the system tree says of `to`: `Some(true)` listed, `Some(false)` its node is
    /// known and does not list it (with the components it lists), `None` its node is not
    /// known (or the CLI joined a node and keeps no tree).
    pub fn lists(&self, to: Address) -> Option<(bool, Vec<Address>)> {
        let Link::Node(n) = self else {
            return None;
        };
        let tree = n.tree();
        if !tree.has_node(to.subsystem, to.node) {
            return None;
        }
        let on_node: Vec<Address> = tree
            .components()
            .into_iter()
            .filter(|a| a.subsystem == to.subsystem && a.node == to.node)
            .collect();
        Some((on_node.contains(&to), on_node))
    }

    /// Whether `to` is asked for acknowledgements: false once this tool's node learnt
    /// that it never gives one (always true when joined to a node).
    pub fn acknowledges(&self, to: Address) -> bool {
        match self {
            Link::Node(n) => n.acknowledges(to),
            Link::Attached(_) => true,
        }
    }

    /// Whether messages to `to` can go now (its node located, or attached).
    pub fn reaches(&self, to: Address) -> bool {
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

/// The CLI's address when `--me` is not given: S.1.40.1 with S in 200–253 from the
/// process id. Each session is a subsystem of its own because OpenJAUS keeps one IP
/// address per subsystem: two sessions as two nodes of one subsystem, on two sockets,
/// would split its traffic between them (seen in the OpenJAUS trial).
pub fn default_me() -> Address {
    Address::new(200 + (std::process::id() % 54) as u8, 1, 40, 1)
}
impl Client {
    /// Asks the peers who speaks for `--me`'s node: the peer whose node manager answers
    /// as that node is joined.
    fn probe(&self, port: &mut Port) -> Option<SocketAddr> {
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
            let _ = port.send_to(&bytes, *p);
        }
        let deadline = Instant::now() + Duration::from_millis(400);
        let mut answered: Vec<SocketAddr> = Vec::new();
        let mut buf = vec![0u8; 8192];
        while let Some(left) = deadline.checked_duration_since(Instant::now()) {
            if !self.peers.is_empty() && self.peers.iter().all(|p| answered.contains(p)) {
                break;
            }
            let Ok(Some((n, from))) = port.recv_from(&mut buf, left.max(Duration::from_millis(1)))
            else {
                break;
            };
            if let Ok((h, _)) = self.framing.packet(&buf[..n]) {
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

    /// Takes this client's place on `port` (see the module docs): the peer's node
    /// joined, or a node of its own, with this tool's component in it.
    pub fn link(&self, port: &mut Port, t0: Instant) -> Result<Link, String> {
        if !self.me.is_valid() || self.me.component == 1 {
            return Err(format!(
                "--me {}: not a component address (ids 1-254, component not 1: the node manager's)",
                self.me
            ));
        }
        let join = match self.mode {
            Mode::Node => None,
            Mode::Join => Some(
                self.probe(port)
                    .or(self.peers.first().copied())
                    .ok_or("--mode join needs a --peer: the socket of the node to join")?,
            ),
            Mode::Auto => self.probe(port),
        };
        let tool = system_commander::component(
            self.me,
            Commander::default(),
            Config {
                identification: Some(self.name.clone()),
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
                    // The tool's commands arrive: resent until acknowledged, in order,
                    // a component that never acknowledges learnt (docs/wire.md §1.7).
                    reliable: Some(jaus::net::reliable::RetryPolicy::cautious()),
                    ..NodeConfig::default()
                };
                c.manager.node_name = self.name.clone();
                c.manager.subsystem_name = self.name.clone();
                let mut node = Node::new(c, t0);
                node.add(tool).map_err(|e| e.to_string())?;
                Link::Node(Box::new(node))
            }
        })
    }

    /// `jaus discover`: a node of its own listens for `wait`, then the system tree.
    pub fn discover(&self, stop: &AtomicBool) -> Result<(SystemTree, bool), String> {
        let mut port = Port::open(&self.carrier, self.bind, &self.peers)?;
        let t0 = Instant::now();
        let client = Client {
            mode: Mode::Node,
            ..self.clone()
        };
        let Link::Node(mut node) = client.link(&mut port, t0)? else {
            return Err("discover runs a node of its own".into());
        };
        let mut heard = false;
        let peers = self.peers.clone();
        jaus::net::shell::run(
            node.as_mut(),
            &mut port,
            stop,
            Some(t0 + self.wait),
            |_| {},
            |dir, from, _| {
                heard |= dir == jaus::net::shell::Direction::Received && peers.contains(&from)
            },
        )
        .map_err(|e| format!("{}: {e}", port.describe()))?;
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
/// Sends every datagram `host` has queued on `port`.
pub fn flush(host: &mut dyn Participant, port: &mut Port) {
    flush_seen(host, port, |_| {});
}

/// [`flush`], showing `seen` each datagram as it goes (to see when a command held by
/// the node leaves).
pub fn flush_seen(host: &mut dyn Participant, port: &mut Port, mut seen: impl FnMut(&[u8])) {
    while let Some(Datagram { to, bytes, .. }) = host.poll_transmit() {
        seen(&bytes);
        if let Err(e) = port.send_to(&bytes, to) {
            tracing::debug!(%to, "send failed: {e}");
        }
    }
}
