//! Two `jaus node` processes on 127.0.0.1 discover each other over real UDP sockets, and
//! `jaus query` gets a report from a component on one of them.

mod common;

use std::io::{BufRead, BufReader};
use std::net::UdpSocket;
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use common::jaus_bin;

/// A free UDP port on 127.0.0.1 (bound then released; good enough for a test).
fn free_port() -> u16 {
    UdpSocket::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

struct Running(Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Starts `jaus node` with `yaml`; its stdout lines arrive on the receiver.
fn node(dir: &std::path::Path, name: &str, yaml: &str) -> (Running, mpsc::Receiver<String>) {
    let cfg = dir.join(format!("{name}.yaml"));
    std::fs::write(&cfg, yaml).unwrap();
    let mut child = Command::new(jaus_bin())
        .args(["node", "--config"])
        .arg(&cfg)
        .args(["--seconds", "30"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("start jaus node");
    let out = child.stdout.take().unwrap();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(out).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    (Running(child), rx)
}

/// Reads lines until one contains every needle (lines of one tree print are joined).
fn wait_for(rx: &mpsc::Receiver<String>, needles: &[&str], limit: Duration) -> Result<(), String> {
    let end = Instant::now() + limit;
    let mut tree = String::new();
    while Instant::now() < end {
        match rx.recv_timeout(Duration::from_millis(100)) {
            Ok(line) => {
                if line.starts_with("--- system tree") {
                    tree.clear();
                }
                tree.push_str(&line);
                tree.push('\n');
                if needles.iter().all(|n| tree.contains(n)) {
                    return Ok(());
                }
            }
            Err(mpsc::RecvTimeoutError::Timeout) => {}
            Err(mpsc::RecvTimeoutError::Disconnected) => break,
        }
    }
    Err(format!("not seen {needles:?}; last tree:\n{tree}"))
}

#[test]
fn two_node_processes_discover_each_other_and_answer_a_query() {
    let dir = std::env::temp_dir().join(format!("jaus-udp-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (pa, pb, pc) = (free_port(), free_port(), free_port());
    let (_a, rx_a) = node(
        &dir,
        "vehicle",
        &format!("subsystem: 1\nnode: 1\nnode_name: vehicle\nbind: 127.0.0.1:{pa}\npeers: [127.0.0.1:{pb}]\nhost: [vehicle]\n"),
    );
    let (_b, rx_b) = node(
        &dir,
        "console",
        &format!("subsystem: 1\nnode: 2\nnode_name: console\nbind: 127.0.0.1:{pb}\npeers: [127.0.0.1:{pa}]\n"),
    );
    wait_for(
        &rx_b,
        &[
            "node 1 'vehicle'",
            "1.1.38.1 'GlobalPoseSensor' services [0, 38]",
            "1.1.45.1 'GlobalWaypointDriver'",
        ],
        Duration::from_secs(10),
    )
    .unwrap();
    wait_for(
        &rx_a,
        &["node 2 'console'", "1.2.1.1 'NodeManager'"],
        Duration::from_secs(10),
    )
    .unwrap();

    let out = Command::new(jaus_bin())
        .args([
            "query", "--to", "1.1.38.1", "--me", "1.3.40.1", "--wait", "1",
        ])
        .arg("--bind")
        .arg(format!("127.0.0.1:{pc}"))
        .arg("--peer")
        .arg(format!("127.0.0.1:{pa}"))
        .arg(r#"{"message":"QueryGlobalPose","fields":{"presence_vector":3}}"#)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let report: serde_json::Value = text
        .lines()
        .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
        .find(|v| v["message"]["message"] == "ReportGlobalPose")
        .unwrap_or_else(|| panic!("no report in:\n{text}"));
    assert_eq!(report["source"], "1.1.38.1");
    let lat = report["message"]["fields"]["latitude"].as_f64().unwrap();
    assert!((lat - 29.6436).abs() < 1e-4, "{lat}");
    let _ = std::fs::remove_dir_all(dir);
}
