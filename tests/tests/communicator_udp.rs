//! The Communicator as `jaus node` hosts it (issue 14 item 3): two nodes of two
//! subsystems, built from node files whose only connection is the communicators' UDP
//! data link (`jaus::net::udp::link::UdpLink`), run by the real UDP I/O loop on
//! loopback threads. Their JAUS sockets have no peers and carry nothing: a query from
//! subsystem 1 to subsystem 2's Global Pose Sensor is answered across the link, twenty
//! times in a row (the round trips are printed; that the link asks to be read every
//! 10 ms is checked by `UdpLink`'s own tests, not by timing here); when subsystem 2 stops, the link goes
//! down by silence (Loss Of Command, the query dropped and counted); when it runs
//! again, the link comes back up and the query is answered. Also: the node-file
//! entry's errors (file, line, column, entry and field) and the example node files.

mod common;

use std::net::{SocketAddr, UdpSocket};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::local::Probe;
use jaus::messages::*;
use jaus::net::udp::link::{UdpLink, UdpLinkStats};
use jaus::net::{NetStats, Node};
use jaus::stock::communicator::{CommunicatorEndpoint, LinkStats};
use jaus::wire::Header;
use jaus::Address;
use jaus_node::NodeFile;

const C1: Address = Address::new(1, 1, 35, 1);
const C2: Address = Address::new(2, 1, 35, 1);
const PROBE: Address = Address::new(1, 1, 200, 1);
const GPS: Address = Address::new(2, 1, 38, 1);

type Gateway = CommunicatorEndpoint<UdpLink>;

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("jaus-comm-udp-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes `yaml` to `dir/name.yaml`, loads it as `jaus node` does.
fn load(dir: &Path, name: &str, yaml: &str) -> Result<(NodeFile, PathBuf), String> {
    let path = dir.join(format!("{name}.yaml"));
    std::fs::write(&path, yaml).unwrap();
    NodeFile::load(&path).map(|f| (f, path))
}

/// The node file of subsystem `ss`: its JAUS socket `bind`, no peers, a communicator
/// whose link 1 binds `link` and talks to `far`, and `more` host entries.
fn node_file(ss: u8, bind: SocketAddr, link: u16, far: u16, more: &str) -> String {
    format!(
        "subsystem: {ss}\nnode: 1\nsubsystem_name: subsystem {ss}\nbind: {bind}\nhost:\n{more}  - component: communicator\n    links:\n      - id: 1\n        udp: {{ bind: \"127.0.0.1:{link}\", peer: \"127.0.0.1:{far}\", silence_ms: 500, keepalive_ms: 100 }}\n"
    )
}

/// What subsystem 1's probe asks and hears, shared between its node's thread (which
/// works it after every event of the I/O loop) and the test.
#[derive(Debug, Default)]
struct Asker {
    /// Queries still to send, one at a time.
    want: usize,
    asked_at: Option<Instant>,
    /// Round trips of the queries answered.
    rtts: Vec<Duration>,
    /// Queries not answered within 300 ms.
    unanswered: usize,
    /// Snapshots of node 1 after the last event.
    state: Option<DataLinkState>,
    comm: LinkStats,
    link: UdpLinkStats,
    sees_subsystem_2: bool,
}

impl Asker {
    fn tick(&mut self, n: &mut Node) {
        let now = Instant::now();
        if let Some(p) = n.get_mut::<Probe>(PROBE) {
            let answered = p
                .messages()
                .any(|m| matches!(m, Message::ReportGlobalPose(_)));
            p.clear();
            if answered {
                if let Some(t) = self.asked_at.take() {
                    self.rtts.push(now - t);
                }
            }
        }
        if self
            .asked_at
            .is_some_and(|t| now - t > Duration::from_millis(300))
        {
            self.unanswered += 1;
            self.asked_at = None;
        }
        if self.asked_at.is_none() && self.want > 0 {
            self.want -= 1;
            let q = Message::from(QueryGlobalPose {
                presence_vector: 0x3,
            });
            n.send(
                now,
                Header::new(q.code(), GPS, PROBE),
                q.to_bytes().unwrap(),
            );
            self.asked_at = Some(now);
        }
        if let Some(g) = n.get::<Gateway>(C1) {
            let c = g.communicator();
            self.state = c.link_state(1, now);
            self.comm = c.link_stats(1).unwrap_or_default();
            self.link = c.link(1).map(UdpLink::stats).unwrap_or_default();
        }
        self.sees_subsystem_2 = n.tree().has_node(2, 1);
    }
}

/// Runs `node` on `socket` with the real I/O loop until `stop`; gives both back.
fn run(
    mut node: Node,
    socket: UdpSocket,
    stop: Arc<AtomicBool>,
    asker: Option<Arc<Mutex<Asker>>>,
) -> JoinHandle<(Node, UdpSocket)> {
    std::thread::spawn(move || {
        let until = Some(Instant::now() + Duration::from_secs(30));
        jaus::net::udp::run_on(&mut node, &socket, &stop, until, |n| {
            if let Some(a) = &asker {
                a.lock().unwrap().tick(n);
            }
        })
        .unwrap();
        (node, socket)
    })
}

/// Waits up to `limit` for `done` to hold of the asker.
fn wait(asker: &Mutex<Asker>, limit: Duration, what: &str, done: impl Fn(&Asker) -> bool) {
    let end = Instant::now() + limit;
    while Instant::now() < end {
        if done(&asker.lock().unwrap()) {
            return;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    panic!("not {what} within {limit:?}: {:?}", asker.lock().unwrap());
}

fn gateway(node: &Node, at: Address) -> &Gateway {
    node.get::<Gateway>(at).expect("the communicator")
}

#[test]
fn two_subsystems_joined_only_by_the_communicators_udp_link() {
    let started = Instant::now();
    let dir = temp_dir("e2e");
    let (s1, s2) = (
        UdpSocket::bind("127.0.0.1:0").unwrap(),
        UdpSocket::bind("127.0.0.1:0").unwrap(),
    );
    let (l1, l2) = (common::free_port(), common::free_port());
    let (f1, p1) = load(
        &dir,
        "station",
        &node_file(1, s1.local_addr().unwrap(), l1, l2, ""),
    )
    .unwrap();
    let (f2, p2) = load(
        &dir,
        "vehicle",
        &node_file(
            2,
            s2.local_addr().unwrap(),
            l2,
            l1,
            "  - global_pose_sensor\n",
        ),
    )
    .unwrap();
    // The node file makes the hosted communicator the node's gateway.
    assert_eq!(f1.node_config().communicator, Some(C1));
    assert_eq!(f2.node_config().communicator, Some(C2));
    assert!(f1.peers.is_empty() && f2.peers.is_empty());
    let t0 = Instant::now();
    let mut n1 = f1.build_node(&p1, t0).unwrap();
    n1.add(Probe::new(PROBE)).unwrap();
    let n2 = f2.build_node(&p2, t0).unwrap();

    let asker = Arc::new(Mutex::new(Asker::default()));
    let (stop1, stop2) = (
        Arc::new(AtomicBool::new(false)),
        Arc::new(AtomicBool::new(false)),
    );
    let h1 = run(n1, s1, stop1.clone(), Some(asker.clone()));
    let h2 = run(n2, s2, stop2.clone(), None);

    // Subsystem 2 is discovered across the link (the communicators' heartbeats), and
    // twenty queries in a row are answered across it, promptly: the link's socket is
    // read within its poll period (10 ms), not at the I/O loop's 100 ms fallback.
    wait(&asker, Duration::from_secs(5), "seeing subsystem 2", |a| {
        a.sees_subsystem_2
    });
    asker.lock().unwrap().want = 20;
    wait(&asker, Duration::from_secs(5), "answered 20 times", |a| {
        a.rtts.len() == 20
    });
    let (mut rtts, unanswered, state) = {
        let a = asker.lock().unwrap();
        (a.rtts.clone(), a.unanswered, a.state)
    };
    rtts.sort();
    let median = rtts[rtts.len() / 2];
    eprintln!(
        "round trips across the UDP link: median {median:?}, max {:?}",
        rtts[rtts.len() - 1]
    );
    assert_eq!(unanswered, 0);
    assert_eq!(state, Some(DataLinkState::On));

    // Subsystem 2 stops: its link falls silent, subsystem 1's link is down after its
    // silence (500 ms): Loss Of Command, and a query is dropped, counted.
    stop2.store(true, Ordering::Relaxed);
    let (n2, s2) = h2.join().unwrap();
    let paused = Instant::now();
    wait(&asker, Duration::from_secs(3), "in Loss Of Command", |a| {
        a.state == Some(DataLinkState::LossOfCommand)
    });
    let silent_for = paused.elapsed();
    assert!(silent_for >= Duration::from_millis(350), "{silent_for:?}");
    let dropped = asker.lock().unwrap().comm.dropped_link_down;
    asker.lock().unwrap().want = 1;
    wait(&asker, Duration::from_secs(2), "unanswered", |a| {
        a.unanswered == 1
    });
    let now_dropped = asker.lock().unwrap().comm.dropped_link_down;
    assert!(now_dropped > dropped, "{dropped} -> {now_dropped}");

    // It runs again: keep-alives bring the link up, the query is answered.
    let stop2 = Arc::new(AtomicBool::new(false));
    let h2 = run(n2, s2, stop2.clone(), None);
    wait(&asker, Duration::from_secs(3), "On again", |a| {
        a.state == Some(DataLinkState::On)
    });
    asker.lock().unwrap().want = 1;
    wait(&asker, Duration::from_secs(3), "answered again", |a| {
        a.rtts.len() == 21
    });

    stop1.store(true, Ordering::Relaxed);
    stop2.store(true, Ordering::Relaxed);
    let (n1, _) = h1.join().unwrap();
    let (n2, _) = h2.join().unwrap();

    // Nothing crossed the JAUS sockets: every message between the subsystems went
    // through the communicators, and their links carried it.
    for (n, name) in [(&n1, "subsystem 1"), (&n2, "subsystem 2")] {
        let st: NetStats = n.stats();
        assert_eq!((st.received, st.sent), (0, 0), "{name}: {st:?}");
        assert!(
            st.to_communicator >= 21 && st.from_communicator >= 21,
            "{name}: {st:?}"
        );
        assert_eq!(st.bad_packet, 0, "{name}: {st:?}");
    }
    for (n, c) in [(&n1, C1), (&n2, C2)] {
        let comm = gateway(n, c).communicator();
        let (ls, us) = (comm.link_stats(1).unwrap(), comm.link(1).unwrap().stats());
        // What the communicator handed its link left as datagrams, and everything the
        // link received from the far end reached the communicator.
        assert_eq!(
            (ls.frames_sent, ls.bytes_sent),
            (us.frames_sent, us.bytes_sent),
            "{c}"
        );
        assert_eq!(
            (ls.frames_received, ls.bytes_received),
            (us.frames_received, us.bytes_received),
            "{c}"
        );
        assert!(
            us.frames_sent >= 21 && us.frames_received >= 21,
            "{c}: {us:?}"
        );
        assert!(
            us.keepalives_sent > 0 && us.keepalives_received > 0,
            "{c}: {us:?}"
        );
        assert_eq!(
            us.dropped_oversize_received + us.dropped_stranger + us.send_errors,
            0,
            "{c}: {us:?}"
        );
        assert_eq!(
            ls.dropped_too_large + ls.dropped_queue_full,
            0,
            "{c}: {ls:?}"
        );
    }
    // Subsystem 1's node delivered what came over the link: the node and the
    // communicator counted the same packets.
    let st1 = n1.stats();
    let ls1 = gateway(&n1, C1).communicator().link_stats(1).unwrap();
    assert_eq!(st1.from_communicator, ls1.frames_received);
    let elapsed = started.elapsed();
    eprintln!("test ran {elapsed:?}");
    assert!(elapsed < Duration::from_secs(10), "{elapsed:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A bad `communicator` entry is refused with the file, line and column, the entry and
/// the field.
#[test]
fn a_bad_communicator_entry_names_the_file_the_entry_and_the_field() {
    let dir = temp_dir("errors");
    let head = "subsystem: 1\nnode: 1\nbind: 127.0.0.1:1\nhost:\n  - global_pose_sensor\n";
    let cases: &[(&str, &str)] = &[
        (
            "  - communicator\n",
            "bad.yaml:6:5: host[1]: `communicator` needs its data links",
        ),
        (
            "  - { component: communicator, links: [] }\n",
            "bad.yaml:6:7: host[1]: `communicator` needs its data links",
        ),
        (
            "  - { component: communicator, links: { id: 1 } }\n",
            "host[1].links: a list of data links",
        ),
        (
            "  - component: communicator\n    links:\n      - { id: 1, udp: { bind: \"127.0.0.1\", peer: \"127.0.0.1:9\" } }\n",
            "bad.yaml:8:25: host[1].links[0].udp.bind: 127.0.0.1 is not a socket address IP:PORT",
        ),
        (
            "  - component: communicator\n    links:\n      - { id: 1, udp: { bind: \"127.0.0.1:8\" } }\n",
            "host[1].links[0].udp: `peer` missing",
        ),
        (
            "  - component: communicator\n    links:\n      - { id: 1, udp: { bind: \"127.0.0.1:8\", peer: \"127.0.0.1:9\", mtu: 8 } }\n",
            "host[1].links[0].udp.mtu: 8 is not an integer in 16..=65507",
        ),
        (
            "  - component: communicator\n    links:\n      - { id: 1, udp: { bind: \"127.0.0.1:8\", peer: \"127.0.0.1:9\", speed: 9600 } }\n",
            "host[1].links[0].udp: unknown field `speed` (known: bind, peer, mtu, silence_ms, keepalive_ms, assume_up, poll_ms)",
        ),
        (
            "  - component: communicator\n    links:\n      - { id: 1, udp: { bind: \"127.0.0.1:8\", peer: \"127.0.0.1:9\" } }\n      - { id: 1, udp: { bind: \"127.0.0.1:10\", peer: \"127.0.0.1:11\" } }\n",
            "bad.yaml:9:11: host[1].links[1].id: data link id 1 is used twice",
        ),
        (
            "  - { component: world_model, links: [] }\n",
            "host[1].links: `links` is for the communicator, not `world_model`",
        ),
        (
            "  - { component: communicator, links: [{ id: 1, udp: { bind: \"127.0.0.1:8\", peer: \"127.0.0.1:9\" } }] }\n  - { component: communicator, instance: 2, links: [{ id: 1, udp: { bind: \"127.0.0.1:10\", peer: \"127.0.0.1:11\" } }] }\n",
            "bad.yaml:7:7: host[2]: a second `communicator`: a node hosts at most one",
        ),
        (
            "communicator: 1.1.35.1\n",
            "communicator: 1.1.35.1 is on this node but not hosted here",
        ),
        (
            "communicator: 2.1.35.1\n",
            "communicator: 2.1.35.1 is not a component of this subsystem (1)",
        ),
    ];
    for (tail, expected) in cases {
        let err = load(&dir, "bad", &format!("{head}{tail}"))
            .err()
            .unwrap_or_else(|| panic!("accepted: {tail}"));
        assert!(
            err.contains(expected),
            "{tail}\n{err}\nexpected: {expected}"
        );
        assert!(err.contains("bad.yaml:"), "{err}");
    }
    // A node of the subsystem without the communicator names the one on another node.
    let (f, _) = load(
        &dir,
        "other",
        "subsystem: 1\nnode: 2\nbind: 127.0.0.1:1\ncommunicator: 1.1.35.1\nhost: [global_pose_sensor]\n",
    )
    .unwrap();
    assert_eq!(f.node_config().communicator, Some(C1));
    // A socket that cannot be bound at start names the file and the entry.
    let taken = UdpSocket::bind("127.0.0.1:0").unwrap();
    let at = taken.local_addr().unwrap();
    let (f, p) = load(
        &dir,
        "busy",
        &format!("{head}  - component: communicator\n    links:\n      - {{ id: 7, udp: {{ bind: \"{at}\", peer: \"127.0.0.1:9\" }} }}\n"),
    )
    .unwrap();
    let err = f.build_node(&p, Instant::now()).err().unwrap();
    assert!(
        err.contains("busy.yaml: host[1]: communicator: data link 7: cannot use 127.0.0.1:"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The example node files (examples/nodes/communicator-*.yaml) load, each hosting a
/// communicator whose link is the other's far end.
#[test]
fn the_example_node_files_are_a_communicator_pair() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/nodes");
    let vehicle = NodeFile::load(&dir.join("communicator-vehicle.yaml")).unwrap();
    let station = NodeFile::load(&dir.join("communicator-station.yaml")).unwrap();
    assert_eq!(vehicle.node_config().communicator, Some(C2));
    assert_eq!(station.node_config().communicator, Some(C1));
    assert!(vehicle.peers.is_empty() && station.peers.is_empty());
    let link = |f: &NodeFile| {
        let links = f.communicator_links();
        assert_eq!(links.len(), 1);
        links[0].clone()
    };
    let (v, s) = (link(&vehicle), link(&station));
    assert_eq!((v.kind(), s.kind()), ("udp", "udp"));
    assert_eq!((v.peer(), s.peer()), (s.bind(), v.bind()));
    assert_eq!(v.id(), s.id());
}
