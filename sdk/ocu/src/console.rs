//! The console's node: a System Commander whose logic is [`Station`], on a node of its
//! own (its node manager keeps the console in every subsystem's tree: heartbeats,
//! discovery answers), run on one thread by `jaus::net::udp`. Between node events it
//! takes the page's commands, gives the station the system tree when it changed, and
//! publishes what the station knows for the web server ([`Shared`]).

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use jaus::component::{Component, Config};
use jaus::components::system_commander;
use jaus::net::{udp, Node, NodeConfig, SystemTree};
use jaus::stock::commander::{Station, StationConfig, TreeInput};
use jaus::Address;

use crate::log::MessageLog;
use crate::map::{MapError, MapLayers, MapOptions};
use crate::shared::{lock, Published, Shared};

/// The console's System Commander: the station as a component.
type Hosted = Component<system_commander::Dispatch<Station>>;

/// How the console runs.
#[derive(Debug, Clone)]
pub struct ConsoleOptions {
    /// The console's node (subsystem, node id, peers, framing).
    pub node: NodeConfig,
    /// The JAUS socket.
    pub bind: SocketAddr,
    /// The web server's socket (127.0.0.1 unless asked otherwise).
    pub http: SocketAddr,
    /// The key the page must carry ([`crate::guard`]); `None` (the default): a new random
    /// one for this run.
    pub key: Option<String>,
    /// DNS names besides `localhost` the page may be opened under (the Host check
    /// refuses every other name, against DNS rebinding). Default none.
    pub allowed_hosts: Vec<String>,
    /// The System Commander's instance (its address is `subsystem.node.40.instance`).
    pub instance: u8,
    /// The component's default authority.
    pub authority: u8,
    /// The map's origin (default: the first position received).
    pub origin: Option<(f64, f64)>,
    /// The map's optional background (default none).
    pub map: MapOptions,
    /// The station's settings.
    pub station: StationConfig,
    /// How often the view is published to the page when no new pose arrived (a new
    /// pose is published at once, at most every 10 ms).
    pub publish_period: Duration,
}

impl Default for ConsoleOptions {
    fn default() -> Self {
        Self {
            node: NodeConfig {
                subsystem: 200,
                node: 1,
                // The Station's commands (control, Resume, waypoints, missions) are
                // resent until acknowledged, in order, a peer that never acknowledges
                // learnt (jaus::net::reliable); the console sends no set-point stream.
                reliable: Some(jaus::net::reliable::RetryPolicy::cautious()),
                ..NodeConfig::default()
            },
            bind: SocketAddr::from(([127, 0, 0, 1], 0)),
            http: SocketAddr::from(([127, 0, 0, 1], 8700)),
            key: None,
            allowed_hosts: Vec::new(),
            instance: 1,
            authority: 0,
            origin: None,
            map: MapOptions::default(),
            station: StationConfig::default(),
            publish_period: Duration::from_millis(50),
        }
    }
}

/// Why the console could not run.
#[derive(Debug, thiserror::Error)]
pub enum ConsoleError {
    /// The JAUS socket.
    #[error("JAUS socket {addr}: {source}")]
    Udp {
        /// The address.
        addr: SocketAddr,
        /// What went wrong.
        source: std::io::Error,
    },
    /// The web server's socket.
    #[error("web server {addr}: {source}")]
    Http {
        /// The address.
        addr: SocketAddr,
        /// What went wrong.
        source: std::io::Error,
    },
    /// The node refused the console's component.
    #[error("the console's component: {0}")]
    Node(String),
    /// A key given in the options that is too short or not URL- and cookie-safe.
    #[error("the console's key must be at least 16 characters of A-Z, a-z, 0-9, `-` or `_`")]
    Key,
    /// A background layer of the map (the file and what is wrong).
    #[error("{0}")]
    Map(#[from] MapError),
    /// A thread of the console did not end (named).
    #[error("shutdown: {0}")]
    Shutdown(#[from] udp::ShutdownError),
}

/// Where a running console is.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Bound {
    /// The JAUS socket.
    pub udp: SocketAddr,
    /// The web server (open [`url`](Self::url)).
    pub http: SocketAddr,
    /// The System Commander's address.
    pub me: Address,
    /// The run's key (the page gets it from [`url`](Self::url); scripts send it as an
    /// `X-Jaus-Key` header).
    pub key: String,
}

impl Bound {
    /// The address to open: it carries the key, which the server turns into a cookie.
    pub fn url(&self) -> String {
        format!("http://{}/?key={}", self.http, self.key)
    }

    /// Whether the web server answers beyond this machine.
    pub fn is_public(&self) -> bool {
        !self.http.ip().is_loopback()
    }
}

/// Runs the console until `stop` is set: binds both sockets, calls `ready` with where
/// they are, serves the page on a thread of its own and runs the node on this one.
pub fn run(
    options: &ConsoleOptions,
    stop: &AtomicBool,
    ready: impl FnOnce(Bound),
) -> Result<(), ConsoleError> {
    let map = Arc::new(MapLayers::load(&options.map)?);
    let socket = UdpSocket::bind(options.bind).map_err(|source| ConsoleError::Udp {
        addr: options.bind,
        source,
    })?;
    let udp_local = socket.local_addr().map_err(|source| ConsoleError::Udp {
        addr: options.bind,
        source,
    })?;
    let listener =
        std::net::TcpListener::bind(options.http).map_err(|source| ConsoleError::Http {
            addr: options.http,
            source,
        })?;
    let http_local = listener.local_addr().map_err(|source| ConsoleError::Http {
        addr: options.http,
        source,
    })?;
    let t0 = Instant::now();
    let mut node = Node::new(options.node.clone(), t0);
    let me = Address::new(
        options.node.subsystem,
        options.node.node,
        40,
        options.instance,
    );
    let mut station = Station::new(options.station);
    if let Some((lat, lon)) = options.origin {
        station.set_origin(lat, lon);
    }
    node.add(system_commander::component(
        me,
        station,
        Config {
            authority: options.authority,
            ..Config::default()
        },
        t0,
    ))
    .map_err(|e| ConsoleError::Node(e.to_string()))?;
    let shared = Shared::new(MessageLog::new(me, options.node.framing));
    let server_shared = shared.clone();
    let server_stop = Arc::new(AtomicBool::new(false));
    let server_stop2 = server_stop.clone();
    let key = match &options.key {
        Some(k) if crate::guard::key_is_sound(k) => k.clone(),
        Some(_) => return Err(ConsoleError::Key),
        None => crate::guard::new_key().map_err(|source| ConsoleError::Http {
            addr: http_local,
            source,
        })?,
    };
    let guard = Arc::new(crate::guard::Guard::new(
        key.clone(),
        http_local.port(),
        options.allowed_hosts.clone(),
    ));
    let server = std::thread::Builder::new()
        .name("ocu-http".into())
        .spawn(move || crate::server::serve(listener, server_shared, guard, map, &server_stop2))
        .map_err(|source| ConsoleError::Http {
            addr: http_local,
            source,
        })?;
    let bound = Bound {
        udp: udp_local,
        http: http_local,
        me,
        key,
    };
    if bound.is_public() {
        tracing::warn!(http = %http_local, "the console answers beyond this machine: only the key keeps others out, and plain HTTP carries it unencrypted");
    }
    ready(bound);
    let mut publisher = Publisher {
        me,
        shared: shared.clone(),
        tree_version: u64::MAX,
        next_publish: t0,
        next_trails: t0,
        last_publish: t0,
        poses: 0,
        period: options.publish_period,
    };
    let io = udp::IoOptions {
        spin: Duration::ZERO,
        ..udp::IoOptions::default()
    };
    let log_shared = shared.clone();
    let result = udp::run_tapped(
        &mut node,
        &socket,
        &io,
        stop,
        None,
        |n| publisher.step(n),
        |dir, _peer, datagram| {
            lock(&log_shared.log).see(Instant::now(), dir == udp::Direction::Received, datagram);
        },
    );
    server_stop.store(true, Ordering::Relaxed);
    let ended = udp::join_within(server, udp::SHUTDOWN_BOUND);
    result.map_err(|source| ConsoleError::Udp {
        addr: udp_local,
        source,
    })?;
    Ok(ended?)
}

/// The node thread's work between events.
struct Publisher {
    me: Address,
    shared: Arc<Shared>,
    tree_version: u64,
    next_publish: Instant,
    next_trails: Instant,
    last_publish: Instant,
    poses: u64,
    period: Duration,
}

impl Publisher {
    fn step(&mut self, node: &mut Node) {
        let now = Instant::now();
        let version = node.tree_version();
        let tree = (version != self.tree_version).then(|| tree_input(node.tree()));
        self.tree_version = version;
        let inbox: Vec<String> = lock(&self.shared.inbox).drain(..).collect();
        let Some(console) = node.get_mut::<Hosted>(self.me) else {
            return;
        };
        let station = &mut console.behaviour_mut().0;
        if let Some(t) = tree {
            station.set_tree(t);
        }
        for text in inbox {
            match crate::protocol::parse(&text, station.frame()) {
                Ok(cmd) => {
                    // A refused command is a notice already.
                    let _ = station.submit(cmd);
                }
                Err(e) => station.report_error(format!("page: {e}")),
            }
        }
        let dropped = self.shared.dropped.swap(0, Ordering::Relaxed);
        if dropped > 0 {
            station.report_error(format!(
                "{dropped} page message(s) dropped: the console is busy"
            ));
        }
        // Every period, and as soon as a new pose arrived (at most every 10 ms).
        let new_pose =
            station.poses() != self.poses && now >= self.last_publish + Duration::from_millis(10);
        if now >= self.next_publish || new_pose {
            self.poses = station.poses();
            self.last_publish = now;
            self.next_publish = now + self.period;
            let wall = unix_now();
            let view = station.view(now, wall, false);
            let json = serde_json::to_string(&view).unwrap_or_else(|_| "{}".into());
            let log_seq = lock(&self.shared.log).seq();
            let unix_ms = wall.as_secs_f64() * 1e3;
            self.shared.view.send_replace(Arc::new(Published {
                view: json,
                log_seq,
                unix_ms,
            }));
        }
        if now >= self.next_trails || self.shared.trails_wanted.swap(false, Ordering::Relaxed) {
            self.next_trails = now + Duration::from_secs(1);
            let view = station.view(now, unix_now(), true);
            let json = serde_json::to_string(&view).unwrap_or_else(|_| "{}".into());
            *lock(&self.shared.trails) = Arc::new(json);
        }
    }
}

/// The wall clock, since the Unix epoch (the shell's; the station reads none).
fn unix_now() -> Duration {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap_or_default()
}

/// The station's input from the node's system tree.
pub fn tree_input(tree: &SystemTree) -> TreeInput {
    let mut t = TreeInput::default();
    for (ss, s) in &tree.subsystems {
        t.subsystems.insert(*ss, s.name.clone());
        for (n, node) in &s.nodes {
            t.nodes.insert((*ss, *n), node.name.clone());
            for ((c, i), info) in &node.components {
                t.components
                    .insert(Address::new(*ss, *n, *c, *i), info.name.clone());
            }
        }
    }
    t
}
