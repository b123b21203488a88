//! An operator station (`jaus::stock::commander::Station`, what `jaus ocu` runs) on a
//! node of its own over UDP, in a thread of the test: commands go in through a channel,
//! the station's view comes out every 50 ms (as the console publishes it).

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use jaus::component::{Component, Config};
use jaus::components::system_commander;
use jaus::net::{udp, Node, NodeConfig, SystemTree};
use jaus::stock::commander::{Command, Station, SystemView, TreeInput};
use jaus::Address;

type Hosted = Component<system_commander::Dispatch<Station>>;

/// The station's input from a node's system tree (as the console builds it).
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

/// A station on node `me.subsystem.me.node` (System Commander `me`), running until
/// dropped.
#[derive(Debug)]
pub struct StationNode {
    /// The station's address.
    pub me: Address,
    commands: mpsc::Sender<Command>,
    view: Arc<Mutex<(Instant, SystemView)>>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
}

impl StationNode {
    /// Starts the station's node on a free loopback port, talking to `peers`.
    pub fn start(me: Address, authority: u8, peers: Vec<SocketAddr>) -> StationNode {
        let t0 = Instant::now();
        let mut config = NodeConfig {
            subsystem: me.subsystem,
            node: me.node,
            peers,
            ..NodeConfig::default()
        };
        config.manager.node_name = "test station".into();
        let mut node = Node::new(config, t0);
        node.add(system_commander::component(
            me,
            Station::default(),
            Config {
                authority,
                ..Config::default()
            },
            t0,
        ))
        .expect("station component");
        let socket = UdpSocket::bind("127.0.0.1:0").expect("station socket");
        let (commands, rx) = mpsc::channel::<Command>();
        let view = Arc::new(Mutex::new((t0, SystemView::default())));
        let stop = Arc::new(AtomicBool::new(false));
        let (v, s) = (view.clone(), stop.clone());
        let thread = std::thread::spawn(move || {
            let mut version = u64::MAX;
            let mut next = t0;
            let r = udp::run_on(&mut node, &socket, &s, None, |n: &mut Node| {
                let tree = (n.tree_version() != version).then(|| tree_input(n.tree()));
                version = n.tree_version();
                let Some(c) = n.get_mut::<Hosted>(me) else {
                    return;
                };
                let station = &mut c.behaviour_mut().0;
                if let Some(t) = tree {
                    station.set_tree(t);
                }
                for cmd in rx.try_iter() {
                    // A refused command is among the view's notices.
                    let _ = station.submit(cmd);
                }
                let now = Instant::now();
                if now >= next {
                    next = now + Duration::from_millis(50);
                    let snapshot = station.view(now, Duration::ZERO, false);
                    *v.lock().unwrap() = (now, snapshot);
                }
            });
            r.expect("station node");
        });
        StationNode {
            me,
            commands,
            view,
            stop,
            thread: Some(thread),
        }
    }

    /// Queues an operator's command.
    pub fn submit(&self, cmd: Command) {
        self.commands.send(cmd).expect("station thread");
    }

    /// The latest view and when it was taken.
    pub fn view(&self) -> (Instant, SystemView) {
        self.view.lock().unwrap().clone()
    }

    /// Waits up to `within` for a view `ok` accepts; the view, or the last one seen.
    pub fn wait_for(
        &self,
        within: Duration,
        mut ok: impl FnMut(&SystemView) -> bool,
    ) -> Result<SystemView, SystemView> {
        let until = Instant::now() + within;
        loop {
            let (_, v) = self.view();
            if ok(&v) {
                return Ok(v);
            }
            if Instant::now() >= until {
                return Err(v);
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }
}

impl Drop for StationNode {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// The component `address` in `view`, if the tree lists it.
pub fn component(
    view: &SystemView,
    address: Address,
) -> Option<&jaus::stock::commander::view::ComponentView> {
    let text = address.to_string();
    view.subsystems
        .iter()
        .flat_map(|s| &s.nodes)
        .flat_map(|n| &n.components)
        .find(|c| c.address == text)
}

/// The components of node `subsystem.node` in `view`.
pub fn components_of(view: &SystemView, subsystem: u8, node: u8) -> usize {
    view.subsystems
        .iter()
        .filter(|s| s.id == subsystem)
        .flat_map(|s| &s.nodes)
        .filter(|n| n.id == node)
        .map(|n| n.components.len())
        .sum()
}
