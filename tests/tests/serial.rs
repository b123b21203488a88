//! Two nodes over JSerial (`jaus::net::serial`) on pseudo-terminals: `socat` makes two
//! pty pairs, a relay in this test carries the bytes between them and damages them
//! (drops bytes, injects garbage); the nodes still find each other, and their decoders
//! count the resynchronisations and the bytes skipped. Skipped when `socat` is absent,
//! unless `JAUS_REQUIRE_SOCAT=1` (CI, which installs it).

#![cfg(target_os = "linux")]

use std::fs::File;
use std::io::{Read, Write};
use std::os::unix::fs::OpenOptionsExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{mpsc, Arc};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use jaus::net::serial::{SerialConfig, SerialLine, SerialStats, SerialTransport};
use jaus::net::stream::{JSerialDecoder, JSerialStats};
use jaus::net::{shell, Node, NodeConfig};

/// `socat`'s path, or `None` (and the test skips) when it is not installed and not
/// required.
fn socat() -> Option<PathBuf> {
    let found = std::env::var_os("PATH").and_then(|p| {
        std::env::split_paths(&p)
            .map(|d| d.join("socat"))
            .find(|f| f.is_file())
    });
    if found.is_none() {
        assert!(
            std::env::var("JAUS_REQUIRE_SOCAT").as_deref() != Ok("1"),
            "JAUS_REQUIRE_SOCAT=1 but socat is not on PATH (Debian: apt-get install socat)"
        );
        eprintln!("skipped: socat is not installed (Debian: apt-get install socat)");
    }
    found
}

struct Socat(Child);

impl Drop for Socat {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// A pty pair whose ends are the links `a` and `b`.
fn pty_pair(socat: &Path, a: &Path, b: &Path) -> Socat {
    let child = Command::new(socat)
        .arg("-d")
        .arg(format!("pty,raw,echo=0,link={}", a.display()))
        .arg(format!("pty,raw,echo=0,link={}", b.display()))
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .expect("start socat");
    let end = Instant::now() + Duration::from_secs(5);
    while !(a.exists() && b.exists()) {
        assert!(
            Instant::now() < end,
            "socat made no ptys at {}",
            a.display()
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    Socat(child)
}

fn open(p: &Path) -> File {
    std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .custom_flags(0o4000) // O_NONBLOCK
        .open(p)
        .expect("open a pty")
}

/// What the relay did to the bytes.
#[derive(Debug, Default)]
struct Damage {
    dropped: AtomicU64,
    injected: AtomicU64,
    carried: AtomicU64,
}

/// Carries bytes both ways between `x` and `y` until `stop`, dropping a byte from every
/// 7th read and putting 1-12 bytes of garbage before every 5th.
fn relay(x: PathBuf, y: PathBuf, stop: Arc<AtomicBool>, damage: Arc<Damage>) -> JoinHandle<()> {
    std::thread::spawn(move || {
        let mut ends = [open(&x), open(&y)];
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let mut reads = 0u64;
        let mut buf = [0u8; 1024];
        while !stop.load(Ordering::Relaxed) {
            let mut idle = true;
            for from in 0..2 {
                let n = match ends[from].read(&mut buf) {
                    Ok(n) if n > 0 => n,
                    _ => continue,
                };
                idle = false;
                reads += 1;
                let mut out = Vec::with_capacity(n + 16);
                if reads.is_multiple_of(5) {
                    let k = 1 + (next() % 12) as usize;
                    out.extend((0..k).map(|_| next() as u8));
                    damage.injected.fetch_add(k as u64, Ordering::Relaxed);
                }
                let mut bytes = buf[..n].to_vec();
                if reads.is_multiple_of(7) {
                    bytes.remove((next() as usize) % n);
                    damage.dropped.fetch_add(1, Ordering::Relaxed);
                }
                out.extend_from_slice(&bytes);
                damage.carried.fetch_add(n as u64, Ordering::Relaxed);
                let _ = ends[1 - from].write_all(&out);
            }
            if idle {
                std::thread::sleep(Duration::from_millis(1));
            }
        }
    })
}

/// Node 1.`n` on the pty at `path`; says on the channel when its tree has 1.`sees`;
/// returns its counters when stopped.
fn run_node(
    n: u8,
    sees: u8,
    path: &Path,
    stop: Arc<AtomicBool>,
) -> (mpsc::Receiver<()>, JoinHandle<(SerialStats, JSerialStats)>) {
    let mut transport =
        SerialTransport::open(SerialConfig::new(path, 115_200), SerialLine(0)).expect("open");
    let (tx, rx) = mpsc::channel();
    let thread = std::thread::spawn(move || {
        let mut c = NodeConfig {
            subsystem: 1,
            node: n,
            ..NodeConfig::default()
        }
        .with_peers(vec![SerialLine(0)], None);
        c.manager.heartbeat = Duration::from_millis(100);
        let mut node = Node::new(c, Instant::now());
        let mut told = false;
        shell::run(
            &mut node,
            &mut transport,
            &stop,
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
        (transport.stats(), transport.line_stats())
    });
    (rx, thread)
}

#[test]
fn two_nodes_over_a_damaged_serial_line_find_each_other_and_count_the_damage() {
    let Some(socat) = socat() else { return };
    let dir = std::env::temp_dir().join(format!("jaus-serial-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let (a, ra, rb, b) = (dir.join("a"), dir.join("ra"), dir.join("rb"), dir.join("b"));
    let _p1 = pty_pair(&socat, &a, &ra);
    let _p2 = pty_pair(&socat, &rb, &b);
    let stop = Arc::new(AtomicBool::new(false));
    let damage = Arc::new(Damage::default());
    let relay = relay(ra, rb, stop.clone(), damage.clone());
    let (seen_a, node_a) = run_node(1, 2, &a, stop.clone());
    let (seen_b, node_b) = run_node(2, 1, &b, stop.clone());
    let limit = Duration::from_secs(20);
    let found = seen_a.recv_timeout(limit).is_ok() && seen_b.recv_timeout(limit).is_ok();
    // More traffic through the damage.
    std::thread::sleep(Duration::from_millis(1500));
    stop.store(true, Ordering::Relaxed);
    let (sa, la) = node_a.join().unwrap();
    let (sb, lb) = node_b.join().unwrap();
    relay.join().unwrap();
    let d = (
        damage.dropped.load(Ordering::Relaxed),
        damage.injected.load(Ordering::Relaxed),
        damage.carried.load(Ordering::Relaxed),
    );
    let report =
        format!("relay (dropped, injected, carried) {d:?}\nA {sa:?}\n  {la:?}\nB {sb:?}\n  {lb:?}");
    eprintln!("{report}");
    assert!(
        found,
        "the nodes did not find each other over the line\n{report}"
    );
    assert!(d.0 > 0 && d.1 > 0, "the relay damaged nothing\n{report}");
    assert!(la.frames > 0 && lb.frames > 0, "{report}");
    assert!(
        la.resyncs + lb.resyncs > 0,
        "no resynchronisation counted\n{report}"
    );
    assert!(la.bytes_skipped + lb.bytes_skipped > 0, "{report}");
    let refused = |s: &JSerialStats| {
        s.bad_checksum
            + s.bad_header_checksum
            + s.malformed
            + s.bad_length
            + s.bad_version
            + s.abandoned
    };
    assert!(
        refused(&la) + refused(&lb) > 0,
        "a dropped byte must cost a packet somewhere\n{report}"
    );
    // Every datagram queued went down the line.
    assert_eq!(
        sa.queue_full + sb.queue_full + sa.not_carried + sb.not_carried,
        0,
        "{report}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_missing_line_is_an_error_naming_it() {
    let e = SerialTransport::open(
        SerialConfig::new("/dev/no-such-jaus-tty", 57_600),
        SerialLine(0),
    )
    .unwrap_err();
    assert!(e.to_string().contains("/dev/no-such-jaus-tty"), "{e}");
    let e =
        SerialTransport::open(SerialConfig::new("/dev/null", 57_600), SerialLine(0)).unwrap_err();
    assert!(e.to_string().contains("not a terminal"), "{e}");
}

/// The fuzz seeds were written by an encoder of their own (a few lines of Python
/// following the JAUS Tool Set's layout, not this crate's): the decoder reads them.
#[test]
fn packets_encoded_independently_decode() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/corpus/jserial");
    for (name, expected) in [("v1_packets", 2), ("v2_packets", 2), ("garbage_between", 2)] {
        let bytes = std::fs::read(root.join(name)).unwrap();
        let mut d = JSerialDecoder::default();
        let mut n = 0;
        d.decode(&bytes[4..], |_| n += 1);
        assert_eq!(n, expected, "{name}: {:?}", d.stats());
    }
}

#[path = "common/mod.rs"]
#[allow(dead_code)]
mod common;

#[test]
fn jaus_query_over_a_serial_line_gets_its_reply_from_jaus_node() {
    let Some(socat) = socat() else { return };
    let dir = std::env::temp_dir().join(format!("jaus-serial-cli-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let (a, b) = (dir.join("a"), dir.join("b"));
    let _pair = pty_pair(&socat, &a, &b);
    let cfg = dir.join("vehicle.yaml");
    std::fs::write(
        &cfg,
        format!(
            "subsystem: 20\nnode: 1\ntransport: serial\nserial: serial://{}?baud=115200\nhost: [global_pose_sensor]\n",
            a.display()
        ),
    )
    .unwrap();
    let mut node = Command::new(common::jaus_bin())
        .args(["node", "--seconds", "30", "--config"])
        .arg(&cfg)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut lines = std::io::BufRead::lines(std::io::BufReader::new(node.stdout.take().unwrap()));
    let first: Vec<String> = lines.by_ref().take(3).map_while(Result::ok).collect();
    assert!(
        first.iter().any(|l| l.starts_with("transport: JSerial")),
        "{first:?}"
    );
    let out = Command::new(common::jaus_bin())
        .args([
            "query",
            "--me",
            "21.1.40.1",
            "--to",
            "20.1.38.1",
            "--wait",
            "10",
        ])
        .args(["--peer", &format!("serial://{}?baud=115200", b.display())])
        .arg(r#"{"message":"QueryHeartbeatPulse"}"#)
        .output()
        .unwrap();
    let _ = node.kill();
    let _ = node.wait();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}\n{stdout}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("ReportHeartbeatPulse"), "{stdout}");
    let _ = std::fs::remove_dir_all(&dir);
}
