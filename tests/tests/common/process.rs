//! `jaus node` processes for the tests that kill and restart them (store_restart,
//! faults_peer_restart, faults_soak): started from a node file, their standard output
//! read on a thread as it comes, killed with SIGKILL.

use std::io::{BufRead, BufReader};
use std::net::{SocketAddr, UdpSocket};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::messages::{QueryHeartbeatPulse, ReportHeartbeatPulse};
use jaus::net::Framing;
use jaus::wire::Header;
use jaus::{Address, JausMessage};

use super::jaus_bin;

/// A running `jaus node --config FILE`; killed (SIGKILL) when dropped.
#[derive(Debug)]
pub struct NodeProcess {
    child: Child,
    lines: mpsc::Receiver<String>,
}

impl NodeProcess {
    /// Starts `jaus node --config config` (its standard error goes to the test's).
    pub fn start(config: &Path) -> NodeProcess {
        let mut child = Command::new(jaus_bin())
            .args(["node", "--config"])
            .arg(config)
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("start jaus node");
        let out = child.stdout.take().expect("stdout");
        let (tx, lines) = mpsc::channel();
        std::thread::spawn(move || {
            for l in BufReader::new(out).lines().map_while(Result::ok) {
                let _ = tx.send(l);
            }
        });
        NodeProcess { child, lines }
    }

    /// Asks the node to stop (SIGINT, as Ctrl-C): it prints its counters (`stats:
    /// ...`) and ends; [`finish`](Self::finish) collects them.
    pub fn interrupt(&self) {
        let ok = Command::new("kill")
            .args(["-INT", &self.child.id().to_string()])
            .status()
            .is_ok_and(|s| s.success());
        assert!(ok, "kill -INT {}", self.child.id());
    }

    /// Waits for the process to end (after [`interrupt`](Self::interrupt)); everything it printed since the last
    /// [`output`](Self::output).
    pub fn finish(mut self) -> String {
        let _ = self.child.wait();
        let mut lines = Vec::new();
        while let Ok(l) = self.lines.recv_timeout(Duration::from_secs(2)) {
            lines.push(l);
        }
        lines.join("\n")
    }

    /// The process id (for /proc/PID/...).
    pub fn pid(&self) -> u32 {
        self.child.id()
    }

    /// SIGKILL, and wait for the process to be gone.
    pub fn kill(mut self) {
        self.child.kill().expect("kill -9");
        self.child.wait().expect("reap");
    }

    /// What it printed since the last call.
    pub fn output(&self) -> String {
        self.lines.try_iter().collect::<Vec<_>>().join("\n")
    }
}

impl Drop for NodeProcess {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A fresh directory for one test's files (removed first if a run left it).
pub fn test_dir(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("jaus-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("test directory");
    dir
}

/// A socket address on 127.0.0.1 with a free port.
pub fn free_addr() -> SocketAddr {
    SocketAddr::from(([127, 0, 0, 1], super::free_port()))
}

/// Writes `dir/name`: a node file for `subsystem.node` bound to `bind`, hosting
/// `host` (a YAML list's items), with `extra` lines after.
pub fn node_file(
    dir: &Path,
    name: &str,
    (subsystem, node): (u8, u8),
    bind: SocketAddr,
    host: &str,
    extra: &str,
) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(
        &path,
        format!("subsystem: {subsystem}\nnode: {node}\nbind: {bind}\nhost: [{host}]\n{extra}"),
    )
    .expect("node file");
    path
}

/// A JUDP datagram carrying `msg` from `src` to `dst`.
pub fn datagram<M: JausMessage + Encode>(src: Address, dst: Address, msg: &M) -> Vec<u8> {
    let body = msg.to_bytes().expect("encode");
    let h = Header::new(M::CODE, dst, src);
    let packet = [
        h.encode_with_size(body.len()).expect("header").as_slice(),
        &body,
    ]
    .concat();
    Framing::Judp.encode(&packet)
}

/// Whether `packet` (a JUDP datagram) is a Report Heartbeat Pulse.
pub fn is_heartbeat_report(datagram: &[u8]) -> bool {
    Framing::Judp.decode(datagram).is_ok_and(|p| {
        p.len() >= 4 && u16::from_le_bytes([p[2], p[3]]) == ReportHeartbeatPulse::CODE.0
    })
}

/// Asks `to` (a component of the node at `node`) for a heartbeat from `me` on `sock`
/// until it answers or `within` passes; the time the answer took.
pub fn ping(
    sock: &UdpSocket,
    node: SocketAddr,
    me: Address,
    to: Address,
    within: Duration,
) -> Option<Duration> {
    let until = Instant::now() + within;
    let mut buf = [0u8; 9000];
    sock.set_read_timeout(Some(Duration::from_millis(100)))
        .ok()?;
    while Instant::now() < until {
        let t = Instant::now();
        sock.send_to(&datagram(me, to, &QueryHeartbeatPulse {}), node)
            .ok()?;
        while let Ok((n, _)) = sock.recv_from(&mut buf) {
            if is_heartbeat_report(&buf[..n]) {
                return Some(t.elapsed());
            }
        }
    }
    None
}
