//! `jaus conform` as a process over UDP: against `jaus node` hosting every stock
//! component (all required checks of a representative six pass: every stock component
//! is tested by the same engine in memory, `tests/memory.rs`, where the virtual clock
//! makes the timed checks free; over UDP each component costs ~6 s of real waits) and against a node in this process hosting a
//! component that takes commands from anyone (exactly its controller-only checks
//! fail, exit status 1). The JSON and JUnit files it writes parse.
//!
//! The binary belongs to the `jaus-cli` package, so `CARGO_BIN_EXE_jaus` is not
//! available here: it is built once with `cargo build -p jaus-cli --bin jaus` (a quick
//! no-op when up to date) and found next to this test's executable. `JAUS_BIN`
//! overrides the path.

mod broken;

use std::io::Read;
use std::net::{SocketAddr, UdpSocket};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};
use std::time::{Duration, Instant};

use jaus::net::{Node, NodeConfig};
use jaus_node::host::{Host, Stock};
use serde_json::Value;

/// The two runs one at a time: each is a tester and a node spinning on their sockets,
/// with 1 s answer timeouts; side by side on a loaded 2-core CI machine, one run once
/// heard nothing from its target for its whole length.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn jaus_bin() -> &'static Path {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| {
        if let Some(p) = std::env::var_os("JAUS_BIN") {
            return PathBuf::from(p);
        }
        let exe = std::env::current_exe().expect("test executable path");
        let deps = exe.parent().expect("deps directory");
        let profile = if deps.file_name().is_some_and(|n| n == "deps") {
            deps.parent().expect("profile directory")
        } else {
            deps
        };
        let bin = profile.join(format!("jaus{}", std::env::consts::EXE_SUFFIX));
        let mut cmd = Command::new(env!("CARGO"));
        cmd.args(["build", "--quiet", "-p", "jaus-cli", "--bin", "jaus"])
            .arg("--manifest-path")
            .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../Cargo.toml"))
            .arg("--target-dir")
            .arg(profile.parent().expect("target directory"));
        if profile.file_name().is_some_and(|n| n == "release") {
            cmd.arg("--release");
        }
        assert!(
            cmd.status().expect("run cargo build").success(),
            "cargo build -p jaus-cli failed"
        );
        bin
    })
}

fn free_port() -> u16 {
    UdpSocket::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("jaus-conform-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A child process killed when dropped.
struct Running(Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Runs `jaus conform` with `args`, killed after `limit`; its output and the JSON and
/// JUnit files it wrote (`Null`/empty when it wrote none).
fn conform(dir: &Path, args: &[&str], limit: Duration) -> (Output, Value, String) {
    let (json, junit, html, pcap) = (
        dir.join("run.json"),
        dir.join("run.xml"),
        dir.join("run.html"),
        dir.join("run.pcapng"),
    );
    let mut child = Command::new(jaus_bin())
        .arg("conform")
        .args(args)
        .arg("--json")
        .arg(&json)
        .arg("--junit")
        .arg(&junit)
        .arg("--html")
        .arg(&html)
        .arg("--pcap")
        .arg(&pcap)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start jaus conform");
    // Drain both pipes on threads so that a full pipe cannot block the child.
    let mut so = child.stdout.take().unwrap();
    let mut se = child.stderr.take().unwrap();
    let t_out = std::thread::spawn(move || {
        let mut v = Vec::new();
        let _ = so.read_to_end(&mut v);
        v
    });
    let t_err = std::thread::spawn(move || {
        let mut v = Vec::new();
        let _ = se.read_to_end(&mut v);
        v
    });
    let end = Instant::now() + limit;
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if Instant::now() > end {
            let _ = child.kill();
            panic!("jaus conform did not finish within {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let out = Output {
        status,
        stdout: t_out.join().unwrap(),
        stderr: t_err.join().unwrap(),
    };
    let json = std::fs::read_to_string(&json)
        .ok()
        .map(|t| serde_json::from_str(&t).expect("--json writes JSON"))
        .unwrap_or(Value::Null);
    let junit = std::fs::read_to_string(&junit).unwrap_or_default();
    if !junit.is_empty() {
        assert!(junit.starts_with("<?xml") && junit.trim_end().ends_with("</testsuites>"));
        assert_eq!(
            junit.matches("<testcase ").count(),
            junit.matches("</testcase>").count()
        );
        let html = std::fs::read_to_string(&html).expect("--html writes a page");
        assert!(html.starts_with("<!DOCTYPE html>") && html.trim_end().ends_with("</html>"));
    }
    (out, json, junit)
}

/// The UDP datagrams of a pcapng file of raw IPv4 packets: (source, destination,
/// payload).
fn read_pcapng(path: &Path) -> Vec<(SocketAddr, SocketAddr, Vec<u8>)> {
    use pcap_file::pcapng::{Block, PcapNgReader};
    let file = std::fs::File::open(path).expect("--pcap writes a file");
    let mut r = PcapNgReader::new(file).expect("a pcapng file");
    let mut v = Vec::new();
    while let Some(block) = r.next_block() {
        if let Block::EnhancedPacket(p) = block.expect("a pcapng block") {
            let d = &p.data;
            assert_eq!((d[0], d[9]), (0x45, 17), "IPv4 carrying UDP");
            let ip = |o: usize| std::net::Ipv4Addr::new(d[o], d[o + 1], d[o + 2], d[o + 3]);
            let port = |o: usize| u16::from_be_bytes([d[o], d[o + 1]]);
            v.push((
                SocketAddr::from((ip(12), port(20))),
                SocketAddr::from((ip(16), port(22))),
                d[28..].to_vec(),
            ));
        }
    }
    v
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

#[test]
fn jaus_node_hosting_every_stock_component_conforms() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let dir = scratch("stock");
    let (port, link_a, link_b) = (free_port(), free_port(), free_port());
    // Every stock component; the Communicator with a data link to nowhere.
    let names: Vec<&str> = Stock::all()
        .filter(|s| s.id() != 35)
        .map(|s| s.name())
        .collect();
    let mut yaml = format!("subsystem: 1\nnode: 1\nbind: 127.0.0.1:{port}\nhost:\n");
    for n in &names {
        yaml.push_str(&format!("  - {n}\n"));
    }
    yaml.push_str(&format!(
        "  - component: communicator\n    links:\n      - {{ id: 1, udp: {{ bind: \"127.0.0.1:{link_a}\", peer: \"127.0.0.1:{link_b}\" }} }}\n"
    ));
    let cfg = dir.join("node.yaml");
    std::fs::write(&cfg, yaml).unwrap();
    let log = std::fs::File::create(dir.join("node.log")).unwrap();
    let _node = Running(
        Command::new(jaus_bin())
            .args(["node", "--config"])
            .arg(&cfg)
            .args(["--seconds", "300"])
            .stdout(Stdio::null())
            .stderr(log)
            .spawn()
            .expect("start jaus node"),
    );
    std::thread::sleep(Duration::from_millis(500));
    let peer = format!("127.0.0.1:{port}");
    // One of each kind of check: a driver with read-backs and the two documented
    // advisory failures, a sensor with events, a waypoint driver, the mission spooler,
    // the world model, an arm driver and the Communicator with its data link.
    let chosen = [
        "primitive_driver",
        "global_pose_sensor",
        "global_waypoint_driver",
        "mission_spooler",
        "world_model",
        "joint_positions_driver",
        "communicator",
    ];
    let targets: Vec<String> = chosen
        .iter()
        .map(|n| {
            let s = Stock::by_name(n).unwrap_or_else(|| panic!("no stock component {n}"));
            format!("1.1.{}.1", s.id())
        })
        .collect();
    let mut args = vec![
        "--peer",
        &peer,
        "--bind",
        "127.0.0.1:0",
        // On subsystem 1: a node hosting a Communicator reaches other subsystems
        // only through its data link.
        "--me",
        "1.9.40.1",
        "--wait",
        "2",
        "--settle-ms",
        "60",
    ];
    for t in &targets {
        args.extend(["--target", t.as_str()]);
    }
    let (out, json, junit) = conform(&dir, &args, Duration::from_secs(240));
    let stdout = text(&out.stdout);
    println!("{stdout}");
    assert!(out.status.success(), "{stdout}\n{}", text(&out.stderr));
    assert!(stdout.contains("CONFORMS"), "{stdout}");
    let components = json["components"].as_array().expect("components");
    let tested: Vec<&str> = components
        .iter()
        .map(|c| c["address"].as_str().unwrap())
        .collect();
    assert_eq!(tested, targets, "{stdout}");
    let mut total = 0;
    for c in components {
        let n = c["outcomes"].as_array().expect("outcomes").len();
        assert!(n >= 20, "{}: {n} checks", c["address"]);
        total += n;
        // The summary prints each component's count of checks.
        let line = format!("{} ", c["address"].as_str().unwrap());
        assert!(stdout
            .lines()
            .any(|l| l.starts_with(&line) && l.contains(&format!("{n} checks"))));
    }
    assert!(total > 7 * 25, "{total} checks");
    // No advisory check fails either: the last documented deviation (Query Platform
    // Operational Data, unanswered by the stock Primitive Driver) is gone since its
    // hardware gives the simulated vehicle's odometer (docs/conformance.md).
    let advisory_failures: Vec<String> = components
        .iter()
        .flat_map(|c| {
            c["outcomes"]
                .as_array()
                .unwrap()
                .iter()
                .filter(|o| o["verdict"] == "fail")
                .map(move |o| {
                    format!(
                        "{} {}",
                        c["address"].as_str().unwrap(),
                        o["id"].as_str().unwrap()
                    )
                })
        })
        .collect();
    assert!(
        advisory_failures.is_empty(),
        "advisory failures: {advisory_failures:?}"
    );
    assert_eq!(junit.matches("<testcase ").count(), total);
    assert_eq!(junit.matches("<failure ").count(), 0);
}

#[test]
fn a_component_taking_commands_from_anyone_fails_over_udp() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    // The binary first: building it can take longer than the target below runs (one
    // CI run built it for over two minutes and found the target gone).
    jaus_bin();
    let dir = scratch("broken");
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let peer: SocketAddr = socket.local_addr().unwrap();
    let t0 = Instant::now();
    let mut host = Host::new(3, 1, t0);
    let mut node = Node::new(
        NodeConfig {
            subsystem: 3,
            ..NodeConfig::default()
        },
        t0,
    );
    let gvd = Stock::by_id(34).unwrap();
    let built = host.build(&Host::entry(gvd)).unwrap();
    node.add_boxed(Box::new(broken::AnyoneCommands::new(built)))
        .unwrap();
    let stop = Arc::new(AtomicBool::new(false));
    let s = stop.clone();
    let runner = std::thread::spawn(move || {
        let _ = jaus::net::udp::run_on(
            &mut node,
            &socket,
            &s,
            Some(Instant::now() + Duration::from_secs(120)),
            |_| {},
        );
    });
    let p = peer.to_string();
    let (out, json, junit) = conform(
        &dir,
        &[
            "--peer",
            &p,
            "--bind",
            "127.0.0.1:0",
            "--target",
            "3.1.34.1",
            "--settle-ms",
            "60",
        ],
        Duration::from_secs(60),
    );
    stop.store(true, Ordering::Relaxed);
    let _ = runner.join();
    let stdout = text(&out.stdout);
    println!("{stdout}");
    // The pcap holds the exchange: the tester's queries to the target's socket and
    // the target's answers from it, each a JUDP datagram.
    let datagrams = read_pcapng(&dir.join("run.pcapng"));
    assert!(
        stdout.contains(&format!("pcap: {} datagrams", datagrams.len())),
        "{stdout}"
    );
    let code = |d: &[u8]| u16::from_le_bytes([d[7], d[8]]);
    assert!(datagrams.iter().all(|(_, _, d)| d.len() >= 21 && d[0] == 1));
    let to_target = datagrams.iter().filter(|(_, to, _)| *to == peer);
    let from_target = datagrams.iter().filter(|(from, _, _)| *from == peer);
    assert!(to_target.clone().any(|(_, _, d)| code(d) == 0x2B00));
    assert!(from_target.clone().any(|(_, _, d)| code(d) == 0x4B00));
    assert!(from_target.count() > 50 && to_target.count() > 50);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{stdout}\n{}",
        text(&out.stderr)
    );
    let outcomes = json["components"][0]["outcomes"]
        .as_array()
        .expect("outcomes");
    let failed: Vec<&str> = outcomes
        .iter()
        .filter(|o| o["verdict"] == "fail" && o["level"] == "required")
        .map(|o| o["id"].as_str().unwrap())
        .collect();
    let citing: Vec<&str> = outcomes
        .iter()
        .filter(|o| o["rule"]["id"] == "controller-only")
        .map(|o| o["id"].as_str().unwrap())
        .collect();
    assert_eq!(failed, citing, "{stdout}");
    assert_eq!(junit.matches("<failure ").count(), citing.len());
}
