//! The Communicator's authenticated, encrypted QUIC data link (issue 28 item 3;
//! `jaus_quic::QuicLink`), as `jaus node` hosts it from a node file's
//! `links: [{ id, quic: { bind, peer, cert, key, peer_cert } }]`:
//!
//! * two `jaus node` processes (keys made by `jaus keygen`) whose JAUS sockets have no
//!   peers, joined only by the QUIC link: `jaus query` of the vehicle's Global Pose
//!   Sensor through the station's node is answered across it, and `jaus watch` opens a
//!   service connection across it and receives its periodic reports; the vehicle's
//!   node took everything from its communicator and nothing on its JAUS socket;
//! * in-process nodes as `communicator_udp.rs` runs them: a node at the vehicle's link
//!   address with a key of its own (pinning the station's certificate correctly) never
//!   gets the link up: the station's link counts the refused handshake, the station's
//!   queries go unanswered and no frame crosses either way; the real vehicle in its
//!   place gets the link up at once and the queries answered;
//! * the node-file entry's errors (file, line, column, entry and field, the key file
//!   named) and the example node files `examples/nodes/quic-*.yaml`.

mod common;

use std::io::Read;
use std::net::{SocketAddr, UdpSocket};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use common::{free_port, jaus_bin};
use jaus::codec::Encode;
use jaus::component::local::Probe;
use jaus::messages::*;
use jaus::net::Node;
use jaus::stock::communicator::CommunicatorEndpoint;
use jaus::wire::Header;
use jaus::Address;
use jaus_node::NodeFile;
use jaus_quic::{QuicLink, QuicLinkStats};

const C1: Address = Address::new(1, 1, 35, 1);
const C2: Address = Address::new(2, 1, 35, 1);
const PROBE: Address = Address::new(1, 1, 200, 1);
const GPS: Address = Address::new(2, 1, 38, 1);

/// A communicator whose links are all QUIC links.
type Gateway = CommunicatorEndpoint<QuicLink>;

fn temp_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("jaus-comm-quic-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("keys")).unwrap();
    dir
}

/// Writes `yaml` to `dir/name.yaml`, loads it as `jaus node` does.
fn load(dir: &Path, name: &str, yaml: &str) -> Result<(NodeFile, PathBuf), String> {
    let path = dir.join(format!("{name}.yaml"));
    std::fs::write(&path, yaml).unwrap();
    NodeFile::load(&path).map(|f| (f, path))
}

/// The node file of subsystem `ss`: its JAUS socket `bind`, no peers, a communicator
/// whose QUIC link 1 binds `link`, talks to `far`, presents `keys/ME.crt` and accepts
/// only `keys/FAR.crt`, and `more` host entries.
fn node_file(
    ss: u8,
    bind: SocketAddr,
    (link, far): (u16, u16),
    (me, far_name): (&str, &str),
    more: &str,
) -> String {
    format!(
        "subsystem: {ss}\nnode: 1\nsubsystem_name: subsystem {ss}\nbind: {bind}\nhost:\n{more}  - component: communicator\n    links:\n      - id: 1\n        quic:\n          bind: \"127.0.0.1:{link}\"\n          peer: \"127.0.0.1:{far}\"\n          cert: keys/{me}.crt\n          key: keys/{me}.key\n          peer_cert: keys/{far_name}.crt\n          silence_ms: 1000\n"
    )
}

/// A `jaus` process, killed if the test ends before it did.
struct Proc(Child);

impl Drop for Proc {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

impl Proc {
    fn start(args: &[&str], config: Option<&Path>) -> Proc {
        let mut c = Command::new(jaus_bin());
        c.args(args);
        if let Some(p) = config {
            c.arg("--config").arg(p);
        }
        Proc(
            c.stdout(Stdio::piped())
                .stderr(Stdio::piped())
                .spawn()
                .unwrap(),
        )
    }

    /// SIGINT, then its exit status and standard output (within 10 s).
    fn stop(mut self) -> (ExitStatus, String) {
        let ok = Command::new("kill")
            .args(["-INT", &self.0.id().to_string()])
            .status()
            .unwrap();
        assert!(ok.success());
        let end = Instant::now() + Duration::from_secs(10);
        let status = loop {
            if let Some(s) = self.0.try_wait().unwrap() {
                break s;
            }
            assert!(Instant::now() < end, "still running 10 s after SIGINT");
            std::thread::sleep(Duration::from_millis(20));
        };
        let mut out = String::new();
        if let Some(mut o) = self.0.stdout.take() {
            o.read_to_string(&mut out).unwrap();
        }
        (status, out)
    }
}

/// Runs `jaus ARGS` to the end: success, standard output, standard error.
fn jaus(args: &[&str]) -> (bool, String, String) {
    let o = Command::new(jaus_bin()).args(args).output().unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// `key value` of a node's `stats:` line.
fn stat(out: &str, key: &str) -> u64 {
    let line = out
        .lines()
        .find(|l| l.starts_with("stats: "))
        .unwrap_or_else(|| panic!("no stats line: {out}"));
    let words: Vec<&str> = line.split_whitespace().collect();
    let i = words.iter().position(|w| *w == key).unwrap();
    words[i + 1].parse().unwrap()
}

#[test]
fn two_jaus_node_processes_joined_only_by_a_quic_link() {
    // (Timed from when the binary is built.)
    jaus_bin();
    let started = Instant::now();
    let dir = temp_dir("e2e");
    let keys = dir.join("keys");
    let keys_arg = keys.to_str().unwrap();
    for name in ["station", "vehicle"] {
        let (ok, out, err) = jaus(&["keygen", name, "--dir", keys_arg]);
        assert!(ok, "{err}");
        assert!(out.contains(&format!("{name}.crt")) && out.contains("fingerprint (SHA-256): "));
    }
    // Never over existing keys.
    let (ok, _, err) = jaus(&["keygen", "vehicle", "--dir", keys_arg]);
    assert!(!ok && err.contains("already exists"), "{err}");

    let (s1, s2) = (free_port(), free_port());
    let (l1, l2) = (free_port(), free_port());
    let station: SocketAddr = format!("127.0.0.1:{s1}").parse().unwrap();
    let vehicle: SocketAddr = format!("127.0.0.1:{s2}").parse().unwrap();
    let (_, p1) = load(
        &dir,
        "station",
        &node_file(1, station, (l1, l2), ("station", "vehicle"), ""),
    )
    .unwrap();
    let (_, p2) = load(
        &dir,
        "vehicle",
        &node_file(
            2,
            vehicle,
            (l2, l1),
            ("vehicle", "station"),
            "  - global_pose_sensor\n",
        ),
    )
    .unwrap();
    let n2 = Proc::start(&["node", "--seconds", "60"], Some(&p2));
    let n1 = Proc::start(&["node", "--seconds", "60"], Some(&p1));

    // A query of the vehicle's Global Pose Sensor through the station's node: answered
    // across the link (asked again until the link is up).
    let tool = |cmd: &str| {
        vec![
            cmd.to_string(),
            "--me".into(),
            "1.1.40.1".into(),
            "--bind".into(),
            format!("127.0.0.1:{}", free_port()),
            "--peer".into(),
            station.to_string(),
            "--to".into(),
            GPS.to_string(),
        ]
    };
    let end = Instant::now() + Duration::from_secs(15);
    let answer = loop {
        let mut args = tool("query");
        args.extend(["--wait".into(), "2".into()]);
        args.push(r#"{"message":"QueryGlobalPose","fields":{"presence_vector":3}}"#.into());
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let (ok, out, err) = jaus(&args);
        if ok {
            break out;
        }
        assert!(Instant::now() < end, "no answer across the link: {err}");
    };
    assert!(
        answer
            .lines()
            .any(|l| l.contains(r#""message":"ReportGlobalPose""#)
                && l.contains(r#""source":[2,1,38,1]"#)),
        "{answer}"
    );

    // A service connection across the link: confirmed, and its reports keep coming.
    let mut args = tool("watch");
    args.extend(["--sc".into(), "ReportGlobalPose@5:0x3".into()]);
    args.extend(["--seconds".into(), "2".into()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let (ok, out, err) = jaus(&args);
    assert!(ok, "{err}\n{out}");
    assert!(
        out.lines()
            .any(|l| l.contains(r#""message":"ConfirmServiceConnection""#)
                && l.contains(r#""response_code":"Successful""#)),
        "{out}"
    );
    let reports = out
        .lines()
        .filter(|l| {
            l.contains(r#""message":"ReportGlobalPose""#)
                && l.contains(r#""service_connection":true"#)
        })
        .count();
    assert!(
        reports >= 5,
        "{reports} periodic reports in 2 s at 5 Hz:\n{out}"
    );

    let (st1, out1) = n1.stop();
    let (st2, out2) = n2.stop();
    assert!(st1.success() && st2.success(), "{out1}\n{out2}");
    for (out, link) in [
        (
            &out1,
            format!("link 1 quic 127.0.0.1:{l1} -> 127.0.0.1:{l2}"),
        ),
        (
            &out2,
            format!("link 1 quic 127.0.0.1:{l2} -> 127.0.0.1:{l1}"),
        ),
    ] {
        assert!(out.contains(&link), "{out}");
    }
    // The vehicle's JAUS socket carried nothing: everything between the subsystems
    // went through the communicators and their QUIC link.
    assert_eq!(
        (stat(&out2, "received"), stat(&out2, "sent")),
        (0, 0),
        "{out2}"
    );
    assert!(stat(&out2, "from_communicator") >= 3, "{out2}");
    assert!(stat(&out1, "from_communicator") >= 6, "{out1}");
    let elapsed = started.elapsed();
    eprintln!("test ran {elapsed:?}");
    assert!(elapsed < Duration::from_secs(30), "{elapsed:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// What subsystem 1's probe asks and hears, and what its link shows, shared between
/// its node's thread (which works it after every event of the I/O loop) and the test.
#[derive(Debug, Default)]
struct Asker {
    /// Keep asking (one query at a time, a new one 300 ms after an unanswered one).
    asking: bool,
    asked_at: Option<Instant>,
    answered: usize,
    unanswered: usize,
    /// The station's link was ever up.
    ever_up: bool,
    link: QuicLinkStats,
}

impl Asker {
    fn tick(&mut self, n: &mut Node) {
        let now = Instant::now();
        if let Some(p) = n.get_mut::<Probe>(PROBE) {
            let answered = p
                .messages()
                .any(|m| matches!(m, Message::ReportGlobalPose(_)));
            p.clear();
            if answered && self.asked_at.take().is_some() {
                self.answered += 1;
            }
        }
        if self
            .asked_at
            .is_some_and(|t| now - t > Duration::from_millis(300))
        {
            self.unanswered += 1;
            self.asked_at = None;
        }
        if self.asked_at.is_none() && self.asking {
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
        if let Some(link) = n.get::<Gateway>(C1).and_then(|g| g.communicator().link(1)) {
            self.ever_up |= link.is_connected();
            self.link = link.stats();
        }
    }
}

/// Runs `node` on `socket` with the real I/O loop until `stop`; gives the node back.
fn run(
    mut node: Node,
    socket: UdpSocket,
    stop: Arc<AtomicBool>,
    asker: Option<Arc<Mutex<Asker>>>,
) -> JoinHandle<Node> {
    std::thread::spawn(move || {
        let until = Some(Instant::now() + Duration::from_secs(30));
        jaus::net::udp::run_on(&mut node, &socket, &stop, until, |n| {
            if let Some(a) = &asker {
                a.lock().unwrap().tick(n);
            }
        })
        .unwrap();
        node
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

fn link_of(node: &Node, at: Address) -> &QuicLink {
    node.get::<Gateway>(at)
        .expect("the communicator over a QUIC link")
        .communicator()
        .link(1)
        .expect("link 1")
}

#[test]
fn a_node_with_the_wrong_key_never_gets_a_frame_through() {
    let started = Instant::now();
    let dir = temp_dir("impostor");
    let keys = dir.join("keys");
    let station = jaus_quic::keys::generate("station", &keys).unwrap();
    let vehicle = jaus_quic::keys::generate("vehicle", &keys).unwrap();
    // The impostor has a key of its own and pins the station's certificate. It takes
    // the vehicle's part (its fingerprint on the same side of the station's): else the
    // two ends would both wait, or both call, and never meet, which would prove nothing.
    let vehicle_connects = vehicle.fingerprint < station.fingerprint;
    let impostor = (0..)
        .map(|k| jaus_quic::keys::generate(&format!("impostor-{k}"), &keys).unwrap())
        .find(|x| (x.fingerprint < station.fingerprint) == vehicle_connects)
        .unwrap();
    let impostor_name = impostor
        .cert
        .file_stem()
        .unwrap()
        .to_str()
        .unwrap()
        .to_string();

    let (l1, l2) = (free_port(), free_port());
    let socket = || UdpSocket::bind("127.0.0.1:0").unwrap();
    let (s1, s2) = (socket(), socket());
    let (f1, p1) = load(
        &dir,
        "station",
        &node_file(
            1,
            s1.local_addr().unwrap(),
            (l1, l2),
            ("station", "vehicle"),
            "",
        ),
    )
    .unwrap();
    let (fx, px) = load(
        &dir,
        "impostor",
        &node_file(
            2,
            s2.local_addr().unwrap(),
            (l2, l1),
            (&impostor_name, "station"),
            "  - global_pose_sensor\n",
        ),
    )
    .unwrap();
    let t0 = Instant::now();
    let mut n1 = f1.build_node(&p1, t0).unwrap();
    n1.add(Probe::new(PROBE)).unwrap();
    let nx = fx.build_node(&px, t0).unwrap();
    let asker = Arc::new(Mutex::new(Asker {
        asking: true,
        ..Asker::default()
    }));
    let stop1 = Arc::new(AtomicBool::new(false));
    let stopx = Arc::new(AtomicBool::new(false));
    let h1 = run(n1, s1, stop1.clone(), Some(asker.clone()));
    let hx = run(nx, s2, stopx.clone(), None);

    // The station refuses the impostor's certificate (counted), and for a second more
    // nothing crosses: the link never comes up, every query goes unanswered.
    wait(&asker, Duration::from_secs(10), "refused", |a| {
        a.link.handshakes_refused >= 1
    });
    let refused_at = Instant::now();
    wait(
        &asker,
        Duration::from_secs(5),
        "3 queries unanswered",
        |a| a.unanswered >= 3 && refused_at.elapsed() >= Duration::from_secs(1),
    );
    {
        let a = asker.lock().unwrap();
        assert_eq!(a.answered, 0, "{a:?}");
        assert!(!a.ever_up, "{a:?}");
        assert_eq!(a.link.handshakes_ok, 0, "{a:?}");
        assert_eq!(a.link.frames_received() + a.link.frames_sent(), 0, "{a:?}");
    }
    stopx.store(true, Ordering::Relaxed);
    let nx = hx.join().unwrap();
    let x = link_of(&nx, C2);
    let xs = x.stats();
    assert!(!x.is_connected(), "{xs:?}");
    assert_eq!(xs.frames_received() + xs.frames_sent(), 0, "{xs:?}");
    let st = nx.stats();
    assert_eq!((st.from_communicator, st.received), (0, 0), "{st:?}");
    drop(nx); // its link's socket freed for the real vehicle

    // The real vehicle in its place: up, and the queries are answered across the link.
    let s2 = socket();
    let (f2, p2) = load(
        &dir,
        "vehicle",
        &node_file(
            2,
            s2.local_addr().unwrap(),
            (l2, l1),
            ("vehicle", "station"),
            "  - global_pose_sensor\n",
        ),
    )
    .unwrap();
    let n2 = f2.build_node(&p2, Instant::now()).unwrap();
    let stop2 = Arc::new(AtomicBool::new(false));
    let h2 = run(n2, s2, stop2.clone(), None);
    wait(&asker, Duration::from_secs(10), "answered 3 times", |a| {
        a.answered >= 3
    });
    stop1.store(true, Ordering::Relaxed);
    stop2.store(true, Ordering::Relaxed);
    let (n1, n2) = (h1.join().unwrap(), h2.join().unwrap());
    let (a, b) = (link_of(&n1, C1).stats(), link_of(&n2, C2).stats());
    assert_eq!((a.handshakes_ok, b.handshakes_ok), (1, 1), "{a:?} {b:?}");
    assert_eq!(b.handshakes_refused, 0, "{b:?}");
    assert!(
        a.frames_received() >= 3 && b.frames_received() >= 3,
        "{a:?} {b:?}"
    );
    // What the communicator handed its link is what the link sent.
    let ls = n1
        .get::<Gateway>(C1)
        .unwrap()
        .communicator()
        .link_stats(1)
        .unwrap();
    assert_eq!(ls.frames_received, a.frames_received(), "{ls:?} {a:?}");
    let elapsed = started.elapsed();
    eprintln!("test ran {elapsed:?}");
    assert!(elapsed < Duration::from_secs(30), "{elapsed:?}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A bad `quic` link entry is refused with the file, line and column, the entry and
/// the field; a key file that cannot be read is named.
#[test]
fn a_bad_quic_link_entry_names_the_file_the_entry_and_the_field() {
    let dir = temp_dir("errors");
    let keys = dir.join("keys");
    jaus_quic::keys::generate("a", &keys).unwrap();
    jaus_quic::keys::generate("b", &keys).unwrap();
    let head = "subsystem: 1\nnode: 1\nbind: 127.0.0.1:1\nhost:\n  - component: communicator\n    links:\n";
    let link = |quic: &str| format!("{head}      - id: 1\n        quic: {{ {quic} }}\n");
    let good = "bind: \"127.0.0.1:8\", peer: \"127.0.0.1:9\", cert: keys/a.crt, key: keys/a.key, peer_cert: keys/b.crt";
    assert!(load(&dir, "good", &link(good)).is_ok());
    let missing = keys.join("nope.crt");
    let cases: Vec<(String, String)> = vec![
        (
            link("bind: \"127.0.0.1:8\", peer: \"127.0.0.1:9\", cert: keys/a.crt, key: keys/a.key"),
            "bad.yaml:8:9: host[0].links[0].quic: `peer_cert` missing".into(),
        ),
        (
            link(&format!("{good}, speed: 9600")),
            "host[0].links[0].quic: unknown field `speed` (known: bind, peer, cert, key, peer_cert, mtu, silence_ms, keepalive_ms)".into(),
        ),
        (
            link(&good.replace("keys/b.crt", "keys/nope.crt")),
            format!(
                "bad.yaml:8:94: host[0].links[0].quic.peer_cert: {}: No such file",
                missing.display()
            ),
        ),
        (
            link(&good.replace("cert: keys/a.crt", "cert: keys/a.key")),
            "host[0].links[0].quic.cert:".into(),
        ),
        (
            link(&good.replace("key: keys/a.key", "key: keys/b.key")),
            "bad.yaml:8:9: host[0].links[0].quic: data link 1: certificate and key: the private key is not the certificate's".into(),
        ),
        (
            link(&good.replace("keys/b.crt", "keys/a.crt")),
            "host[0].links[0].quic: data link 1: the far end's certificate is this end's own".into(),
        ),
        (
            link(&format!("{good}, mtu: 8")),
            "host[0].links[0].quic.mtu: 8 is not an integer in 16..=65507".into(),
        ),
        (
            link(&format!("{good}, silence_ms: 500, keepalive_ms: 500")),
            "host[0].links[0].quic: data link 1: keepalive 500ms must be above zero and below silence 500ms".into(),
        ),
        (
            format!("{head}      - {{ id: 1, udp: {{ bind: \"127.0.0.1:8\", peer: \"127.0.0.1:9\" }}, quic: {{ {good} }} }}\n"),
            "host[0].links[0]: `udp` and `quic`: a data link is one or the other".into(),
        ),
        (
            format!("{head}      - {{ id: 1 }}\n"),
            "host[0].links[0]: `udp` or `quic` missing".into(),
        ),
    ];
    for (yaml, expected) in &cases {
        let err = load(&dir, "bad", yaml)
            .err()
            .unwrap_or_else(|| panic!("accepted: {yaml}"));
        assert!(
            err.contains(expected.as_str()),
            "{yaml}\n{err}\nexpected: {expected}"
        );
        assert!(err.contains("bad.yaml:"), "{err}");
    }
    // A socket that cannot be bound at start names the file and the entry.
    let taken = UdpSocket::bind("127.0.0.1:0").unwrap();
    let at = taken.local_addr().unwrap();
    let (f, p) = load(
        &dir,
        "busy",
        &link(&good.replace("127.0.0.1:8", &at.to_string())),
    )
    .unwrap();
    let err = f.build_node(&p, Instant::now()).err().unwrap();
    assert!(
        err.contains("busy.yaml: host[0]: communicator: data link 1: cannot use 127.0.0.1:"),
        "{err}"
    );
    // A communicator may mix the two kinds: then its links are boxed.
    let (f, p) = load(
        &dir,
        "mixed",
        &format!(
            "{head}      - {{ id: 1, quic: {{ {} }} }}\n      - {{ id: 2, udp: {{ bind: \"127.0.0.1:0\", peer: \"127.0.0.1:9\" }} }}\n",
            good.replace("127.0.0.1:8", "127.0.0.1:0")
        ),
    )
    .unwrap();
    let kinds: Vec<&str> = f.communicator_links().iter().map(|l| l.kind()).collect();
    assert_eq!(kinds, ["quic", "udp"]);
    let node = f.build_node(&p, Instant::now()).unwrap();
    let gw = node
        .get::<CommunicatorEndpoint<Box<dyn jaus::stock::communicator::DataLink>>>(Address::new(
            1, 1, 35, 1,
        ))
        .expect("a communicator over boxed links");
    assert_eq!(gw.communicator().link_ids().collect::<Vec<_>>(), [1, 2]);
    std::fs::remove_dir_all(&dir).ok();
}

/// The example node files (examples/nodes/quic-*.yaml) load once their keys are made
/// as their comments say, each hosting a communicator whose QUIC link is the other's
/// far end, each pinning the other's certificate.
#[test]
fn the_example_node_files_are_a_quic_pair() {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/nodes");
    let dir = temp_dir("examples");
    for name in ["quic-vehicle.yaml", "quic-station.yaml"] {
        std::fs::copy(examples.join(name), dir.join(name)).unwrap();
    }
    let keys = dir.join("keys");
    jaus_quic::keys::generate("vehicle", &keys).unwrap();
    jaus_quic::keys::generate("station", &keys).unwrap();
    let vehicle = NodeFile::load(&dir.join("quic-vehicle.yaml")).unwrap();
    let station = NodeFile::load(&dir.join("quic-station.yaml")).unwrap();
    assert_eq!(vehicle.node_config().communicator, Some(C2));
    assert_eq!(station.node_config().communicator, Some(C1));
    assert!(vehicle.peers.is_empty() && station.peers.is_empty());
    let link = |f: &NodeFile| {
        let links = f.communicator_links();
        assert_eq!(links.len(), 1);
        match &links[0] {
            jaus_node::LinkFile::Quic(q) => q.clone(),
            other => panic!("not a QUIC link: {other:?}"),
        }
    };
    let (v, s) = (link(&vehicle), link(&station));
    assert_eq!((v.peer, s.peer), (s.bind, v.bind));
    assert_eq!(v.id, s.id);
    assert_eq!((v.cert.clone(), s.cert.clone()), (s.peer_cert, v.peer_cert));
    std::fs::remove_dir_all(&dir).ok();
}
