//! Soak of a `jaus node` process hosting the demo vehicle under a mixed load (issue 35):
//!
//! * an operator station (`jaus::stock::commander::Station`, what `jaus ocu` runs) on
//!   node 1.2 with its service connections (pose and velocity at 10 Hz), status,
//!   controller and world-model queries, taking and releasing control of the waypoint
//!   driver every 2 s;
//! * a rival operator (1.4.40.1) asking for the same driver with a lower authority
//!   every second (granted while the station lets it go, taken back after);
//! * a prober (1.5.40.1) querying a heartbeat every 10 ms from a rotating component
//!   (the request latency), a pose and a status every 100 ms, and opening and ending
//!   a 20 Hz service connection on the velocity every 3 s;
//! * a garbage datagram every 10 ms;
//! * a peer node (1.3, a `jaus node` hosting a world model) killed with
//!   SIGKILL and started again every 5 s.
//!
//! Every second: the node's RSS (`VmRSS` of /proc/PID/status), its CPU (utime + stime
//! of /proc/PID/stat over the second), the heartbeat latency (median and maximum) and
//! how many were answered. Written to `target/soak/soak.csv` and plotted in
//! `target/soak/soak.svg`. Checked: the node answered every second, no latency above
//! 250 ms, RSS within 16 MiB of its value after the warm-up (5 s), and the vehicle,
//! never commanded to move, did not.
//!
//! 20 s in the suite; `JAUS_SOAK_SECS=600 cargo test --release -p jaus-tests --test
//! faults_soak -- --nocapture` for the ten-minute run (docs/faults.md).

mod common;

use std::fmt::Write as _;
use std::net::{SocketAddr, UdpSocket};
use std::path::PathBuf;
use std::time::{Duration, Instant};

use common::process::{datagram, free_addr, node_file, test_dir, NodeProcess};
use common::station::{component, StationNode};
use jaus::messages::*;
use jaus::net::Framing;
use jaus::stock::commander::Command;
use jaus::wire::PacketRef;
use jaus::{Address, JausMessage};
use jaus_cli::series::{time_series_svg, Series};
use jaus_sim::demo::addr;

const STATION: Address = Address::new(1, 2, 40, 1);
const RIVAL: Address = Address::new(1, 4, 40, 1);
const PROBER: Address = Address::new(1, 5, 40, 1);
/// Largest heartbeat latency accepted.
const MAX_LATENCY: Duration = Duration::from_millis(250);
/// Largest RSS growth after the warm-up.
const MAX_GROWTH_KIB: u64 = 16 * 1024;
const WARM_UP: usize = 5;

/// One second of the soak.
#[derive(Debug, Clone, Copy, Default)]
struct Sample {
    t: f64,
    rss_kib: u64,
    cpu_percent: f64,
    latency_median_ms: f64,
    latency_max_ms: f64,
    asked: u32,
    answered: u32,
}

/// VmRSS of `pid`, KiB.
fn rss_kib(pid: u32) -> Option<u64> {
    let s = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    s.lines()
        .find(|l| l.starts_with("VmRSS:"))?
        .split_whitespace()
        .nth(1)?
        .parse()
        .ok()
}

/// utime + stime of `pid`, clock ticks (fields 14 and 15 of /proc/PID/stat).
fn cpu_ticks(pid: u32) -> Option<u64> {
    let s = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // After the command name, which may hold spaces, in parentheses.
    let rest = &s[s.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    Some(f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?)
}

/// Clock ticks per second (`getconf CLK_TCK`; 100, Linux's, if that fails).
fn clock_ticks() -> f64 {
    std::process::Command::new("getconf")
        .arg("CLK_TCK")
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .and_then(|s| s.trim().parse().ok())
        .unwrap_or(100.0)
}

struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> u64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        self.0 >> 16
    }
}

/// The source and message of a JUDP datagram, if it holds one whole message.
fn message(bytes: &[u8]) -> Option<(Address, Message)> {
    let p = Framing::Judp.decode(bytes).ok()?;
    let p = PacketRef::parse(p).ok()?;
    let m = Message::decode(p.header.command_code, p.body).ok()?;
    Some((p.header.source, m))
}

fn out_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../target"))
        .join("soak")
}

/// The load and the probes, for `seconds`; one sample a second.
struct Load {
    node: SocketAddr,
    prober: UdpSocket,
    noise: UdpSocket,
    rng: Lcg,
    tick: u64,
}

impl Load {
    fn send<M: JausMessage + jaus::codec::Encode>(&self, from: Address, to: Address, m: &M) {
        let sock = if from == PROBER {
            &self.prober
        } else {
            &self.noise
        };
        let _ = sock.send_to(&datagram(from, to, m), self.node);
    }

    /// Everything but the heartbeat probe, once every 10 ms.
    fn background(&mut self) {
        self.tick += 1;
        let n = (self.rng.next() % 300) as usize;
        let junk: Vec<u8> = (0..n).map(|_| self.rng.next() as u8).collect();
        let _ = self.noise.send_to(&junk, self.node);
        if self.tick.is_multiple_of(100) {
            let authority_code = 150;
            self.send(
                RIVAL,
                addr::GWD,
                &RequestComponentControl { authority_code },
            );
        }
        if self.tick.is_multiple_of(10) {
            let q = QueryGlobalPose {
                presence_vector: 0x43,
            };
            self.send(PROBER, addr::GPS, &q);
            self.send(PROBER, addr::PD, &QueryComponentStatus {});
        }
        let sc = ReportVelocityState::CODE.0;
        match self.tick % 300 {
            0 => self.send(
                PROBER,
                addr::VSS,
                &CreateServiceConnection {
                    service_connection_command_code: sc,
                    presence_vector: 0x43,
                    requested_periodic_update_rate: 20.0,
                },
            ),
            150 => self.send(
                PROBER,
                addr::VSS,
                &TerminateServiceConnection {
                    service_connection_command_code: sc,
                    instance_id: 0,
                },
            ),
            _ => {}
        }
    }

    /// One heartbeat query to a rotating component; its latency if answered in time.
    fn probe(&mut self) -> Option<Duration> {
        const TARGETS: [Address; 4] = [addr::GPS, addr::VSS, addr::PD, addr::GWD];
        let to = TARGETS[(self.tick % 4) as usize];
        let t = Instant::now();
        self.send(PROBER, to, &QueryHeartbeatPulse {});
        let mut buf = [0u8; 9000];
        while t.elapsed() < MAX_LATENCY * 2 {
            let Ok((n, _)) = self.prober.recv_from(&mut buf) else {
                continue;
            };
            if let Some((from, Message::ReportHeartbeatPulse(_))) = message(&buf[..n]) {
                if from == to {
                    return Some(t.elapsed());
                }
            }
        }
        None
    }
}

fn write_results(samples: &[Sample], stats: &str) -> PathBuf {
    let dir = out_dir();
    std::fs::create_dir_all(&dir).unwrap();
    let mut csv =
        String::from("t_s,rss_kib,cpu_percent,latency_median_ms,latency_max_ms,asked,answered\n");
    for s in samples {
        let _ = writeln!(
            csv,
            "{:.0},{},{:.1},{:.3},{:.3},{},{}",
            s.t,
            s.rss_kib,
            s.cpu_percent,
            s.latency_median_ms,
            s.latency_max_ms,
            s.asked,
            s.answered
        );
    }
    let _ = writeln!(csv, "# {stats}");
    std::fs::write(dir.join("soak.csv"), csv).unwrap();
    let series = |name: &str, unit: &str, f: fn(&Sample) -> f64| Series {
        name: name.into(),
        unit: unit.into(),
        points: samples.iter().map(|s| (s.t, f(s))).collect(),
    };
    let svg = time_series_svg(
        &format!(
            "jaus node (host: [vehicle]) under mixed load, {} s",
            samples.len()
        ),
        &[
            series("RSS", "MiB", |s| s.rss_kib as f64 / 1024.0),
            series("CPU", "% of a core", |s| s.cpu_percent),
            series("heartbeat latency, max", "ms", |s| s.latency_max_ms),
            series("heartbeat latency, median", "ms", |s| s.latency_median_ms),
        ],
    )
    .unwrap();
    std::fs::write(dir.join("soak.svg"), svg).unwrap();
    dir
}

#[test]
fn a_vehicle_node_holds_under_mixed_load_with_a_restarting_peer() {
    let seconds: u64 = std::env::var("JAUS_SOAK_SECS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20);
    let dir = test_dir("soak");
    let at = free_addr();
    let cfg = node_file(&dir, "vehicle.yaml", (1, 1), at, "vehicle", "");
    let vehicle = NodeProcess::start(&cfg);
    let pid = vehicle.pid();
    let peer_cfg = node_file(
        &dir,
        "peer.yaml",
        (1, 3),
        free_addr(),
        "world_model",
        &format!("peers: [{at}]\n"),
    );
    let mut peer = Some(NodeProcess::start(&peer_cfg));
    let station = StationNode::start(STATION, 200, vec![at]);
    let ready = station.wait_for(Duration::from_secs(20), |v| {
        component(v, addr::GWD).is_some()
    });
    assert!(ready.is_ok(), "the vehicle was not discovered");
    let mut load = Load {
        node: at,
        prober: UdpSocket::bind("127.0.0.1:0").unwrap(),
        noise: UdpSocket::bind("127.0.0.1:0").unwrap(),
        rng: Lcg(35),
        tick: 0,
    };
    load.prober
        .set_read_timeout(Some(Duration::from_millis(5)))
        .unwrap();
    load.noise.set_nonblocking(true).unwrap();

    let ticks = clock_ticks();
    let start = Instant::now();
    let mut samples: Vec<Sample> = Vec::new();
    let mut second: Vec<Duration> = Vec::new();
    let mut asked = 0;
    let mut last_cpu = (Instant::now(), cpu_ticks(pid).unwrap_or(0));
    let (mut restarts, mut controls) = (0, 0);
    let mut sink = [0u8; 9000];
    while start.elapsed() < Duration::from_secs(seconds) {
        let elapsed = start.elapsed();
        load.background();
        while load.noise.recv_from(&mut sink).is_ok() {}
        asked += 1;
        if let Some(l) = load.probe() {
            second.push(l);
        }
        // Control changes: the station takes and lets go of the waypoint driver.
        if elapsed.as_secs() / 2 > controls {
            controls = elapsed.as_secs() / 2;
            station.submit(if controls % 2 == 1 {
                Command::TakeControl {
                    target: addr::GWD,
                    authority: 200,
                }
            } else {
                Command::ReleaseControl { target: addr::GWD }
            });
        }
        // The peer restarts.
        if elapsed.as_secs() / 5 > restarts {
            restarts = elapsed.as_secs() / 5;
            if let Some(p) = peer.take() {
                p.kill();
            }
            peer = Some(NodeProcess::start(&peer_cfg));
        }
        if elapsed.as_secs() as usize > samples.len() {
            let now = Instant::now();
            let cpu = cpu_ticks(pid).unwrap_or(last_cpu.1);
            let dt = (now - last_cpu.0).as_secs_f64();
            let cpu_percent = (cpu - last_cpu.1) as f64 / ticks / dt * 100.0;
            last_cpu = (now, cpu);
            second.sort();
            let ms = |d: Option<&Duration>| d.map_or(f64::NAN, |d| d.as_secs_f64() * 1e3);
            samples.push(Sample {
                t: elapsed.as_secs_f64(),
                rss_kib: rss_kib(pid).unwrap_or(0),
                cpu_percent,
                latency_median_ms: ms(second.get(second.len() / 2)),
                latency_max_ms: ms(second.last()),
                asked,
                answered: second.len() as u32,
            });
            second.clear();
            asked = 0;
        }
        std::thread::sleep(Duration::from_millis(8));
    }
    let (_, view) = station.view();
    drop(station);
    drop(peer);
    vehicle.interrupt();
    let out = vehicle.finish();
    let stats = out
        .lines()
        .find(|l| l.starts_with("stats:"))
        .unwrap_or("")
        .to_string();
    let results = write_results(&samples, &stats);

    let answered: u32 = samples.iter().map(|s| s.answered).sum();
    let total: u32 = samples.iter().map(|s| s.asked).sum();
    let warm = samples.get(WARM_UP).map_or(0, |s| s.rss_kib);
    let max_rss = samples.iter().map(|s| s.rss_kib).max().unwrap_or(0);
    let worst = samples.iter().map(|s| s.latency_max_ms).fold(0.0, f64::max);
    let mut medians: Vec<f64> = samples.iter().map(|s| s.latency_median_ms).collect();
    medians.sort_by(f64::total_cmp);
    let cpu: f64 = samples.iter().skip(1).map(|s| s.cpu_percent).sum::<f64>()
        / samples.len().saturating_sub(1).max(1) as f64;
    println!(
        "soak {seconds} s: {answered} of {total} heartbeat queries answered; latency median of the per-second medians {:.2} ms, worst {worst:.2} ms; RSS {warm} KiB after {WARM_UP} s, at most {max_rss} KiB; CPU {cpu:.1} % of a core on average; {restarts} peer restarts, {controls} control changes\n{stats}\nresults: {}",
        medians.get(medians.len() / 2).copied().unwrap_or(f64::NAN),
        results.display()
    );
    // The node answered throughout, in time.
    for s in &samples {
        assert!(s.answered > 0, "no answer in second {}: {samples:#?}", s.t);
    }
    assert!(
        answered as f64 >= 0.98 * total as f64,
        "{answered} of {total} answered"
    );
    assert!(
        worst < MAX_LATENCY.as_secs_f64() * 1e3,
        "a heartbeat took {worst} ms"
    );
    // Memory: flat after the warm-up.
    assert!(
        max_rss.saturating_sub(warm) < MAX_GROWTH_KIB,
        "RSS grew from {warm} to {max_rss} KiB"
    );
    // Nobody commanded a move: the vehicle stayed where it started.
    let pose = view
        .subsystems
        .iter()
        .find(|s| s.id == 1)
        .and_then(|s| s.pose);
    let pose = pose.expect("the station followed the vehicle's pose");
    assert!(pose.x.hypot(pose.y) < 0.5, "the vehicle moved: {pose:?}");
    assert!(pose.age_s < 1.0, "the pose stopped coming: {pose:?}");
    // It counted the garbage it refused, and ran to the end (it prints its counters
    // when it stops).
    let count = |key: &str| -> u64 {
        let mut it = stats.split_whitespace();
        it.by_ref().find(|w| *w == key);
        it.next().and_then(|v| v.parse().ok()).unwrap_or(0)
    };
    assert!(count("bad_framing") + count("bad_packet") > 0, "{out}");
    let _ = std::fs::remove_dir_all(&dir);
}
