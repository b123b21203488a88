//! Vehicle mode against a real DDS on the other side, no ROS install: the SDK's
//! simulated vehicle (the demo's vehicle node, `jaus node`'s `host: [vehicle]`) runs on
//! a UDP socket, the bridge in vehicle mode on another one finds it in the system tree,
//! and `ros2_vehicle.py` (the `cyclonedds` Python package) plays the ROS 2 side: it
//! sees `rt/odom`, `rt/fix` and `rt/jaus/status`, drives with `rt/cmd_vel` and sees the
//! vehicle move, goes silent and sees the bridge's watchdog stop it, then sends a
//! `rt/goal_pose` and sees the vehicle reach it through the Local Waypoint Driver.
//!
//! Needs `JAUS_ROS2_PYTHON` as `tests/cyclone.rs` does (skips with a message without
//! it, fails instead with `JAUS_REQUIRE_ROS2=1`).

mod support;

use std::io::{BufRead, BufReader, Write};
use std::net::UdpSocket;
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::messages::RequestComponentControl;
use jaus::net::{udp, Framing, Node, NodeConfig};
use jaus::{Address, Header, JausMessage, Packet};
use jaus_ros2::{vehicle_node, Ros2Config, VehicleEvent, VehicleLink};
use jaus_sim::demo::{vehicle_at, Options};
use serde_json::Value;

/// The Python ROS 2 side: its stdin and the JSON lines it printed.
struct RosSide {
    child: Child,
    stdin: ChildStdin,
    lines: Arc<Mutex<Vec<Value>>>,
}

impl RosSide {
    fn start(py: &str, domain: u16) -> RosSide {
        let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/ros2_vehicle.py");
        let mut child = Command::new(py)
            .arg(script)
            .args(["--domain", &domain.to_string(), "--duration", "90"])
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .expect("start ros2_vehicle.py");
        let stdin = child.stdin.take().unwrap();
        let out = child.stdout.take().unwrap();
        let lines = Arc::new(Mutex::new(Vec::new()));
        let sink = lines.clone();
        std::thread::spawn(move || {
            for line in BufReader::new(out).lines().map_while(Result::ok) {
                if let Ok(v) = serde_json::from_str::<Value>(&line) {
                    sink.lock().unwrap().push(v);
                }
            }
        });
        RosSide {
            child,
            stdin,
            lines,
        }
    }

    fn say(&mut self, word: &str) {
        writeln!(self.stdin, "{word}").unwrap();
        self.stdin.flush().unwrap();
    }

    fn lines(&self) -> Vec<Value> {
        self.lines.lock().unwrap().clone()
    }

    /// The odometry it received since line `from`: (t_ns, x, y, vx).
    fn odoms_since(&self, from: usize) -> Vec<(i64, f64, f64, f64)> {
        self.lines()[from.min(self.lines().len())..]
            .iter()
            .filter(|l| l["odom"].is_u64())
            .map(|l| {
                let f = |k: &str| l[k].as_f64().unwrap_or(f64::NAN);
                (l["t_ns"].as_i64().unwrap_or(0), f("x"), f("y"), f("vx"))
            })
            .collect()
    }
}

impl Drop for RosSide {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The bridge's node, driven in slices on the test's thread.
struct Bridge {
    node: Node,
    link: VehicleLink,
    socket: UdpSocket,
    stop: AtomicBool,
}

impl Bridge {
    fn run(&mut self, d: Duration) {
        let link = &mut self.link;
        udp::run_on(
            &mut self.node,
            &self.socket,
            &self.stop,
            Some(Instant::now() + d),
            |n| link.step(n),
        )
        .unwrap();
    }

    /// Runs until `done` holds (checked every 50 ms) or `limit` passes.
    fn run_until(&mut self, limit: Duration, mut done: impl FnMut(&mut Bridge) -> bool) -> bool {
        let end = Instant::now() + limit;
        while Instant::now() < end {
            if done(self) {
                return true;
            }
            self.run(Duration::from_millis(50));
        }
        done(self)
    }
}

/// The Primitive Driver's component id.
const PD: u8 = jaus::components::primitive_driver::ID;

fn percentile(sorted: &[f64], p: f64) -> f64 {
    let i = ((sorted.len() as f64 - 1.0) * p).round() as usize;
    sorted[i.min(sorted.len() - 1)]
}

#[test]
fn a_jaus_vehicle_is_driven_from_cyclone_dds() {
    let Some(py) = support::python("a_jaus_vehicle_is_driven_from_cyclone_dds") else {
        return;
    };
    let domain = 150 + (std::process::id() % 80) as u16;
    let mut ros = RosSide::start(&py, domain);

    // The JAUS vehicle: the demo's vehicle node (subsystem 1, node 1) on UDP.
    let t0 = Instant::now();
    let opts = Options {
        local_waypoint_driver: true,
        position_noise: 0.0,
        ..Options::default()
    };
    let (parts, sim) = vehicle_at(t0, &opts, 1, 1);
    let mut vnode = Node::new(
        NodeConfig {
            subsystem: 1,
            node: 1,
            ..NodeConfig::default()
        },
        t0,
    );
    for p in parts {
        vnode.add_boxed(p).unwrap();
    }
    let vsocket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let vaddr = vsocket.local_addr().unwrap();
    let vstop = Arc::new(AtomicBool::new(false));
    let vstop2 = vstop.clone();
    let vehicle = std::thread::spawn(move || {
        udp::run_on(&mut vnode, &vsocket, &vstop2, None, |_| {}).unwrap();
    });

    // The bridge, vehicle mode, subsystem 30.
    let mut config = Ros2Config {
        domain_id: domain,
        ..Ros2Config::default()
    };
    config.vehicle.subsystem = Some(1);
    let node_config = NodeConfig {
        subsystem: 30,
        node: 1,
        peers: vec![vaddr],
        ..NodeConfig::default()
    };
    let (node, link) = vehicle_node(&config, node_config, Instant::now()).unwrap();
    let mut b = Bridge {
        node,
        link,
        socket: UdpSocket::bind("127.0.0.1:0").unwrap(),
        stop: AtomicBool::new(false),
    };

    // (a) odometry, a fix and the status arrive over DDS.
    let t = Instant::now();
    let seen = b.run_until(Duration::from_secs(30), |_| {
        let l = ros.lines();
        l.iter().any(|l| l["odom"].is_u64())
            && l.iter().any(|l| l["fix"].is_u64())
            && l.iter().any(|l| {
                l["status"]
                    .as_str()
                    .is_some_and(|s| s.contains("PD 1.1.33.1"))
            })
    });
    assert!(
        seen,
        "no odom/fix/status over DDS: stats {:?}, status {}, lines {:?}",
        b.link.stats(),
        b.link.status_text(),
        ros.lines().iter().rev().take(5).collect::<Vec<_>>()
    );
    println!("discovery: odom, fix and status after {:?}", t.elapsed());
    let lines = ros.lines();
    let first = lines.iter().find(|l| l["odom"].is_u64()).unwrap();
    assert_eq!(
        (first["frame"].as_str(), first["child"].as_str()),
        (Some("odom"), Some("base_link"))
    );
    let fix = lines.iter().find(|l| l["fix"].is_u64()).unwrap();
    assert!(
        (fix["lat"].as_f64().unwrap() - 29.6436).abs() < 1e-3,
        "{fix}"
    );
    assert!(
        (fix["lon"].as_f64().unwrap() + 82.3549).abs() < 1e-3,
        "{fix}"
    );

    // (b) cmd_vel drives: 0.5 m/s forward with the default mapping (1 m/s = 100 %) is
    // 50 % effort; the simulated vehicle does 2 m/s at 100 %.
    let from = ros.lines().len();
    ros.say("drive 0.5 0.0");
    let moved = b.run_until(Duration::from_secs(8), |_| {
        let o = ros.odoms_since(from);
        o.len() > 2 && {
            let (a, z) = (o[0], o[o.len() - 1]);
            (z.1 - a.1).hypot(z.2 - a.2) > 1.0 && z.3 > 0.5
        }
    });
    let odoms = ros.odoms_since(from);
    assert!(
        moved,
        "the vehicle did not move: stats {:?}, events {:?}, effort {:?}, odom {:?}",
        b.link.stats(),
        b.link.events(),
        sim.lock().effort(),
        odoms.last()
    );
    let effort = sim.lock().effort();
    assert!((effort.linear.x - 50.0).abs() < 0.01, "{effort:?}");
    assert_eq!(effort.rotational.z, 0.0);
    assert_eq!(b.link.held().len(), 1, "{:?}", b.link.held());
    assert!(
        b.link.status_text().contains("this bridge"),
        "{}",
        b.link.status_text()
    );
    let (a, z) = (odoms[0], odoms[odoms.len() - 1]);
    println!(
        "drove: odom ({:.2}, {:.2}) → ({:.2}, {:.2}), vx {:.2} m/s, {} odom in {:.2} s ({:.1} Hz)",
        a.1,
        a.2,
        z.1,
        z.2,
        z.3,
        odoms.len(),
        (z.0 - a.0) as f64 / 1e9,
        (odoms.len() - 1) as f64 / ((z.0 - a.0) as f64 / 1e9)
    );
    // The simulated vehicle starts facing JAUS north (yaw 0): ENU +y.
    assert!(z.2 - a.2 > 1.0 && (z.1 - a.1).abs() < 0.2, "{a:?} → {z:?}");

    // (c) silence: the bridge's watchdog sends zero efforts; the vehicle stops.
    let _ = b.link.events();
    ros.say("silent");
    let silent_at = Instant::now();
    let stopped = b.run_until(Duration::from_secs(3), |b| {
        b.link.stats().watchdog_stops >= 1 && sim.lock().effort().linear.x == 0.0
    });
    let stop_after = silent_at.elapsed();
    assert!(
        stopped,
        "no watchdog stop: {:?} {:?}",
        b.link.stats(),
        sim.lock().effort()
    );
    assert!(
        b.link
            .events()
            .iter()
            .any(|e| matches!(e, VehicleEvent::CmdVelSilent { .. })),
        "no CmdVelSilent event"
    );
    let effort = sim.lock().effort();
    assert_eq!(
        effort.resistive_linear.x, 0.0,
        "zero efforts, not the driver's own brakes: {effort:?}"
    );
    b.run(Duration::from_millis(1500));
    let tail_from = ros.lines().len();
    b.run(Duration::from_millis(600));
    let tail = ros.odoms_since(tail_from);
    assert!(tail.len() >= 2, "odom stopped flowing");
    let (a, z) = (tail[0], tail[tail.len() - 1]);
    assert!(
        (z.1 - a.1).hypot(z.2 - a.2) < 0.02 && z.3.abs() < 0.02,
        "still moving: {a:?} → {z:?}"
    );
    println!(
        "watchdog: zero efforts at the vehicle {stop_after:?} after the ROS side went \
         silent (its last cmd_vel 0-100 ms before that; timeout 500 ms)"
    );

    // cmd_vel taken → Set Wrench Effort queued.
    let mut lat: Vec<f64> = b
        .link
        .latencies()
        .iter()
        .map(|d| d.as_secs_f64() * 1e3)
        .collect();
    lat.sort_by(|a, b| a.total_cmp(b));
    assert!(!lat.is_empty());
    println!(
        "latency cmd_vel taken from DDS → Set Wrench Effort queued: n={} p50={:.2} ms p99={:.2} ms max={:.2} ms",
        lat.len(),
        percentile(&lat, 0.5),
        percentile(&lat, 0.99),
        lat[lat.len() - 1]
    );

    // goal_pose: 3 m east of where the vehicle stands, through the Local Waypoint Driver.
    let here = ros.odoms_since(0).last().copied().unwrap();
    let goal = (here.1 + 3.0, here.2);
    ros.say(&format!("goal {} {}", goal.0, goal.1));
    let from = ros.lines().len();
    let reached = b.run_until(Duration::from_secs(25), |_| {
        ros.odoms_since(from)
            .last()
            .is_some_and(|o| (o.1 - goal.0).hypot(o.2 - goal.1) < 1.0)
    });
    let events = b.link.events();
    assert!(
        reached,
        "goal {goal:?} not reached from {here:?}: last {:?}, events {events:?}, stats {:?}, status {}",
        ros.odoms_since(from).last(),
        b.link.stats(),
        b.link.status_text()
    );
    assert!(events
        .iter()
        .any(|e| matches!(e, VehicleEvent::GoalSent { driver, .. } if driver.component == jaus::components::local_waypoint_driver::ID)));
    println!("goal reached");

    // Losing control: drive again, then another controller with a higher authority
    // (31.1.40.1, authority 50 > the bridge's 10) takes the Primitive Driver. The bridge
    // says so and sends nothing more while cmd_vel goes on (its requests are refused).
    ros.say("drive 0.3 0.0");
    let driving = b.run_until(Duration::from_secs(5), |b| {
        b.link.held().iter().any(|a| a.component == PD) && sim.lock().effort().linear.x > 20.0
    });
    assert!(
        driving,
        "not driving again: {:?} {:?}",
        b.link.held(),
        b.link.events()
    );
    let _ = b.link.events();
    let rival = UdpSocket::bind("127.0.0.1:0").unwrap();
    let request = |authority_code: u8| {
        let h = Header::new(
            RequestComponentControl::CODE,
            Address::new(1, 1, PD, 1),
            Address::new(31, 1, 40, 1),
        );
        let body = RequestComponentControl { authority_code }
            .to_bytes()
            .unwrap();
        Framing::Judp.encode(&Packet::new(h, body).to_bytes().unwrap())
    };
    rival.send_to(&request(50), vaddr).unwrap();
    let lost = b.run_until(Duration::from_secs(3), |b| {
        b.link
            .events()
            .iter()
            .any(|e| matches!(e, VehicleEvent::ControlLost { component, .. } if component.component == PD))
    });
    assert!(lost, "no ControlLost: {:?}", b.link.held());
    let sent = b.link.stats().wrench_sent;
    b.run(Duration::from_millis(800));
    assert_eq!(
        b.link.stats().wrench_sent,
        sent,
        "commands sent without control"
    );
    assert!(b.link.stats().cmd_vel > 0 && b.link.held().is_empty());
    // The bridge asks who holds control when it loses it; the answer is one round trip.
    let named = b.run_until(Duration::from_secs(3), |b| {
        b.link.status_text().contains("controller 31.1.40.1")
    });
    assert!(named, "{}", b.link.status_text());
    ros.say("silent");
    println!("bridge stats: {:?}", b.link.stats());

    vstop.store(true, Ordering::Relaxed);
    vehicle.join().unwrap();
}
