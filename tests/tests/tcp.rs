//! Two nodes over JTCP on loopback (`jaus::net::tcp`): they discover each other through
//! the node managers' queries and reports; one is killed and started again on the same
//! port, the other notices, dials again with backoff, and the traffic resumes both ways.

mod common;

use std::net::SocketAddr;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{mpsc, Arc};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use jaus::net::tcp::{TcpConfig, TcpStats, TcpTransport};
use jaus::net::{shell, Node, NodeConfig};

/// A node `1.n` with a heartbeat every 200 ms, sending to `peers`.
fn node(n: u8, peers: Vec<SocketAddr>) -> Node {
    let mut c = NodeConfig {
        subsystem: 1,
        node: n,
        peers,
        ..NodeConfig::default()
    };
    c.manager.heartbeat = Duration::from_millis(200);
    c.manager.node_name = format!("node {n}");
    Node::new(c, Instant::now())
}

/// A node running on its own thread until `stop`; it says on the channel when its
/// tree first has node 1.`sees`, and returns its transport's counters.
struct Running {
    stop: Arc<AtomicBool>,
    seen: mpsc::Receiver<()>,
    thread: JoinHandle<TcpStats>,
}

impl Running {
    fn start(n: u8, sees: u8, config: TcpConfig) -> Self {
        let stop = Arc::new(AtomicBool::new(false));
        let (tx, seen) = mpsc::channel();
        // The node sends to the peers its transport dials.
        let peers = config.peers.clone();
        let mut transport = TcpTransport::new(config).expect("tcp transport");
        let s = stop.clone();
        let thread = std::thread::spawn(move || {
            let mut node = node(n, peers);
            let mut told = false;
            shell::run(
                &mut node,
                &mut transport,
                &s,
                Some(Instant::now() + Duration::from_secs(60)),
                |node| {
                    if !told && node.tree().has_node(1, sees) {
                        told = true;
                        let _ = tx.send(());
                    }
                },
                |_, _, _| {},
            )
            .expect("the shell runs");
            transport.stats()
        });
        Self { stop, seen, thread }
    }

    fn sees_within(&self, limit: Duration) -> bool {
        self.seen.recv_timeout(limit).is_ok()
    }

    fn kill(self) -> TcpStats {
        self.stop.store(true, Ordering::Relaxed);
        self.thread.join().expect("node thread")
    }
}

fn listen(port: u16) -> TcpConfig {
    TcpConfig {
        listen: Some(SocketAddr::from(([127, 0, 0, 1], port))),
        ..TcpConfig::default()
    }
}

#[test]
fn two_nodes_over_tcp_find_each_other_and_recover_when_one_restarts() {
    let port = common::free_port();
    let limit = Duration::from_secs(15);
    // Node 1.1 listens; node 1.2 dials it (and listens nowhere).
    let a = Running::start(1, 2, listen(port));
    let b_config = TcpConfig {
        peers: vec![SocketAddr::from(([127, 0, 0, 1], port))],
        backoff_min: Duration::from_millis(50),
        backoff_max: Duration::from_millis(400),
        ..TcpConfig::default()
    };
    let b = Running::start(2, 1, b_config);
    assert!(b.sees_within(limit), "1.2 never learned 1.1 over tcp");
    assert!(a.sees_within(limit), "1.1 never learned 1.2 over tcp");

    // Killed: its listener and connection close.
    let a_stats = a.kill();
    assert_eq!(a_stats.accepted, 1, "{a_stats:?}");
    assert!(
        a_stats.datagrams_received > 0 && a_stats.datagrams_sent > 0,
        "{a_stats:?}"
    );
    std::thread::sleep(Duration::from_millis(600));

    // Started again on the same port, with an empty tree: it learns 1.2 only if 1.2
    // dialed again and its traffic flows once more.
    let a2 = Running::start(1, 2, listen(port));
    assert!(
        a2.sees_within(limit),
        "1.2 did not reconnect to the restarted 1.1"
    );
    std::thread::sleep(Duration::from_millis(300));
    let a2_stats = a2.kill();
    let b_stats = b.kill();
    assert_eq!(a2_stats.accepted, 1, "{a2_stats:?}");
    assert!(a2_stats.datagrams_sent > 0, "{a2_stats:?}");
    assert!(
        b_stats.connected >= 2,
        "dialed once per life of 1.1: {b_stats:?}"
    );
    assert!(
        b_stats.closed >= 1,
        "the dead peer was noticed: {b_stats:?}"
    );
    assert!(
        b_stats.connect_failures >= 1,
        "1.1 was down for 600 ms: at least one redial failed: {b_stats:?}"
    );
    assert_eq!(b_stats.bad_stream, 0, "{b_stats:?}");
}

#[test]
fn datagrams_to_an_unreachable_peer_are_dropped_and_counted_without_blocking() {
    // A port nothing listens on: connecting fails at once on loopback.
    let port = common::free_port();
    let to = SocketAddr::from(([127, 0, 0, 1], port));
    let mut t = TcpTransport::new(TcpConfig {
        peers: vec![to],
        backoff_min: Duration::from_millis(20),
        ..TcpConfig::default()
    })
    .unwrap();
    use jaus::net::{Datagram, Transport, Via};
    let d = Datagram {
        to,
        bytes: jaus::net::Framing::Judp.encode(&[0u8; 16]),
        via: Via::Network,
    };
    let end = Instant::now() + Duration::from_secs(5);
    while t.stats().connect_failures < 2 && Instant::now() < end {
        let _ = t.send(&d);
        t.recv(Duration::from_millis(10), |_, _, _| {}).unwrap();
    }
    let s = t.stats();
    assert!(s.connect_failures >= 2, "{s:?}");
    assert!(s.no_connection >= 1, "{s:?}");
    assert_eq!(s.connected, 0);
    // OPC has no JTCP form.
    let opc = Datagram {
        bytes: jaus::net::Framing::Opc.encode(&[0u8; 16]),
        ..d
    };
    let e = t.send(&opc).unwrap_err();
    assert!(e.to_string().contains(&to.to_string()), "{e}");
    assert_eq!(t.stats().not_carried, 1);
}

/// A `jaus node` process, killed when dropped.
struct Child(std::process::Child);

impl Drop for Child {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// `jaus node` with `transport: tcp`: its stdout lines on the receiver.
fn jaus_node(dir: &std::path::Path, name: &str, yaml: &str) -> (Child, mpsc::Receiver<String>) {
    use std::io::BufRead;
    let cfg = dir.join(format!("{name}.yaml"));
    std::fs::write(&cfg, yaml).unwrap();
    let log = std::fs::File::create(dir.join(format!("{name}.log"))).unwrap();
    let mut child = std::process::Command::new(common::jaus_bin())
        .args(["node", "--config"])
        .arg(&cfg)
        .args(["--seconds", "30"])
        .stdout(std::process::Stdio::piped())
        .stderr(log)
        .spawn()
        .expect("start jaus node");
    let out = child.stdout.take().unwrap();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in std::io::BufReader::new(out).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    (Child(child), rx)
}

#[test]
fn jaus_node_files_with_transport_tcp_discover_each_other() {
    let dir = std::env::temp_dir().join(format!("jaus-tcp-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (pa, pb) = (common::free_port(), common::free_port());
    let (_a, _rx_a) = jaus_node(
        &dir,
        "vehicle",
        &format!("subsystem: 1\nnode: 1\nnode_name: vehicle\ntransport: tcp\nbind: 127.0.0.1:{pa}\nhost: [global_pose_sensor]\n"),
    );
    let (_b, rx_b) = jaus_node(
        &dir,
        "console",
        &format!("subsystem: 1\nnode: 2\nnode_name: console\ntransport: tcp\nbind: 127.0.0.1:{pb}\npeers: [127.0.0.1:{pa}]\n"),
    );
    let end = Instant::now() + Duration::from_secs(20);
    let mut seen = String::new();
    while Instant::now() < end && !seen.contains("1.1.38.1 'GlobalPoseSensor'") {
        if let Ok(line) = rx_b.recv_timeout(Duration::from_millis(100)) {
            seen.push_str(&line);
            seen.push('\n');
        }
    }
    assert!(
        seen.contains("transport: JTCP"),
        "the console did not say it runs over tcp:\n{seen}"
    );
    assert!(
        seen.contains("1.1.38.1 'GlobalPoseSensor'"),
        "the console never saw the vehicle's component over tcp:\n{seen}"
    );
}

#[test]
fn jaus_query_over_tcp_gets_its_reply() {
    let dir = std::env::temp_dir().join(format!("jaus-tcp-query-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let pa = common::free_port();
    let (_a, rx_a) = jaus_node(
        &dir,
        "vehicle",
        &format!("subsystem: 20\nnode: 1\ntransport: tcp\nbind: 127.0.0.1:{pa}\nhost: [global_pose_sensor]\n"),
    );
    // Listening before the query dials.
    let end = Instant::now() + Duration::from_secs(10);
    while Instant::now() < end {
        if let Ok(l) = rx_a.recv_timeout(Duration::from_millis(100)) {
            if l.starts_with("transport: JTCP") {
                break;
            }
        }
    }
    let out = std::process::Command::new(common::jaus_bin())
        .args([
            "query",
            "--me",
            "21.1.40.1",
            "--to",
            "20.1.38.1",
            "--wait",
            "10",
        ])
        .args(["--peer", &format!("tcp://127.0.0.1:{pa}")])
        .arg(r#"{"message":"QueryHeartbeatPulse"}"#)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}\n{stdout}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("ReportHeartbeatPulse"), "{stdout}");
    // Mixed transports are refused, naming both.
    let out = std::process::Command::new(common::jaus_bin())
        .args([
            "query",
            "--to",
            "20.1.38.1",
            "--peer",
            "tcp://127.0.0.1:1",
            "--peer",
            "127.0.0.1:2",
        ])
        .arg(r#"{"message":"QueryHeartbeatPulse"}"#)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(stderr.contains("one transport"), "{stderr}");
}

/// AS-4 over JTCP (version 2 on the connection): an AS-4 client on a `TcpTransport`
/// asks a `jaus node` with `as4:` and `transport: tcp` for its services.
#[test]
fn an_as4_client_over_tcp_is_answered_by_a_node_with_as4() {
    use jaus::net::as5669a::{As4Client, As4Id, As4Message};
    let dir = std::env::temp_dir().join(format!("jaus-tcp-as4-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let pa = common::free_port();
    let (_a, rx_a) = jaus_node(
        &dir,
        "vehicle",
        &format!("subsystem: 1\nnode: 1\ntransport: tcp\nbind: 127.0.0.1:{pa}\nhost: [global_pose_sensor]\nas4: {{}}\n"),
    );
    let end = Instant::now() + Duration::from_secs(10);
    while Instant::now() < end {
        if let Ok(l) = rx_a.recv_timeout(Duration::from_millis(100)) {
            if l.starts_with("transport: JTCP") {
                break;
            }
        }
    }
    let vehicle = SocketAddr::from(([127, 0, 0, 1], pa));
    let mut t = TcpTransport::new(TcpConfig {
        peers: vec![vehicle],
        ..TcpConfig::default()
    })
    .unwrap();
    let mut client = As4Client::<SocketAddr>::default();
    let q = jaus_as4::Message::from(jaus_as4::QueryServices {
        nodes: vec![jaus_as4::NodeServicesQuery {
            node_id: 255,
            component_ids: vec![255],
        }],
    });
    let body = jaus::codec::Encode::to_bytes(q.body()).unwrap();
    let me = As4Id::new(42, 1, 1);
    let stop = AtomicBool::new(false);
    let mut services = None;
    // The gateway finds the RA 3.3 components first: ask again until it answers.
    for _ in 0..20 {
        client.send(
            vehicle,
            &[As4Message::new(
                q.code().0,
                As4Id::new(1, 1, 1),
                me,
                body.clone(),
            )],
        );
        shell::run(
            &mut client,
            &mut t,
            &stop,
            Some(Instant::now() + Duration::from_millis(500)),
            |_| {},
            |_, _, _| {},
        )
        .unwrap();
        services = client.take().into_iter().find_map(|(_, m)| {
            match jaus_as4::Message::decode(jaus::CommandCode(m.message_id), &m.body) {
                Ok(jaus_as4::Message::ReportServices(r)) => Some(r),
                _ => None,
            }
        });
        if services.is_some() {
            break;
        }
    }
    let s = t.stats();
    let r = services.unwrap_or_else(|| panic!("no Report Services over tcp: {s:?}"));
    assert!(!r.nodes.is_empty(), "{r:?}");
    assert_eq!(
        (s.connected, s.bad_stream, s.wrong_version),
        (1, 0, 0),
        "{s:?}"
    );
}

/// By hand, against the JAUS Tool Set's runtime (its node manager with
/// `EnableTCPInterface="1"` and a component such as its `Management_11` example at
/// 126.1.11): an AS-4 client over JTCP asks `JAUS_JUNIOR_ID` (default 126.1.11) at
/// `JAUS_JUNIOR_TCP` (e.g. 127.0.0.1:3794) for its identification and its status and
/// prints what comes back.
///
/// `JAUS_JUNIOR_TCP=127.0.0.1:3794 cargo test -p jaus-tests --test tcp -- --ignored junior --nocapture`
#[test]
#[ignore = "needs the JAUS Tool Set's node manager listening on JTCP (JAUS_JUNIOR_TCP)"]
fn junior_answers_over_jtcp() {
    use jaus::net::as5669a::{As4Client, As4Id, As4Message};
    let Some(at) = std::env::var("JAUS_JUNIOR_TCP").ok() else {
        panic!("set JAUS_JUNIOR_TCP=HOST:PORT of the JAUS Tool Set's node manager");
    };
    let junior: SocketAddr = at.parse().expect("JAUS_JUNIOR_TCP is HOST:PORT");
    let id = std::env::var("JAUS_JUNIOR_ID").unwrap_or_else(|_| "126.1.11".into());
    let parts: Vec<u32> = id.split('.').map(|p| p.parse().unwrap()).collect();
    let target = As4Id::new(parts[0] as u16, parts[1] as u8, parts[2] as u8);
    let mut t = TcpTransport::new(TcpConfig {
        peers: vec![junior],
        ..TcpConfig::default()
    })
    .unwrap();
    let mut client = As4Client::<SocketAddr>::default();
    let me = As4Id::new(42, 1, 1);
    let stop = AtomicBool::new(false);
    let queries = [
        jaus_as4::Message::from(jaus_as4::QueryIdentification {
            query_type: jaus_as4::IdentificationType::Component,
        }),
        // Management_11 has no Discovery service: its Management answers this.
        jaus_as4::Message::from(jaus_as4::QueryStatus {}),
    ];
    let mut answers = Vec::new();
    for q in &queries {
        let body = jaus::codec::Encode::to_bytes(q.body()).unwrap();
        client.send(junior, &[As4Message::new(q.code().0, target, me, body)]);
        shell::run(
            &mut client,
            &mut t,
            &stop,
            Some(Instant::now() + Duration::from_secs(2)),
            |_| {},
            |dir, peer, bytes| eprintln!("{dir:?} {peer} {}", hex(bytes)),
        )
        .unwrap();
        for (_, m) in client.take() {
            let decoded = jaus_as4::Message::decode(jaus::CommandCode(m.message_id), &m.body);
            eprintln!("from {}: {decoded:?}", m.source);
            answers.push(decoded);
        }
    }
    eprintln!("{:?}", t.stats());
    assert!(
        answers.iter().any(|a| matches!(
            a,
            Ok(jaus_as4::Message::ReportIdentification(_) | jaus_as4::Message::ReportStatus(_))
        )),
        "no Report Identification or Report Status from {target} over JTCP: {:?}",
        t.stats()
    );
}

fn hex(b: &[u8]) -> String {
    b.iter().map(|x| format!("{x:02x}")).collect()
}
