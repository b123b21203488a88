//! The bridge against a real DDS on the other side, no ROS install: `ros2_robot.py`
//! (the `cyclonedds` Python package, which bundles Cyclone DDS) plays a ROS 2 robot
//! publishing `rt/odom` and `rt/fix` and integrating the `rt/cmd_vel` it receives. A
//! JAUS client on the bridge's node takes control of the Primitive Driver, drives
//! forward, sees the Local Pose, Velocity State and Global Pose move, releases control
//! and sees the zero twist stop the robot; then the ROS side goes silent and the
//! watchdog holds the robot. The bridge's latency (odom published → Report Local Pose
//! reflecting it) is printed with `--nocapture`. A second test gives the robot a lidar
//! and a camera (`rt/scan`, `rt/image_raw`, `rt/image_raw/compressed`) and reads them
//! through the Range Sensor and the Visual Sensor.
//!
//! Needs `JAUS_ROS2_PYTHON`: a Python with `cyclonedds`
//! (`python3 -m venv /tmp/ros2venv && /tmp/ros2venv/bin/pip install cyclonedds`, then
//! `JAUS_ROS2_PYTHON=/tmp/ros2venv/bin/python`). Without it the test says so on stderr
//! and passes, unless `JAUS_REQUIRE_ROS2=1`.

mod support;

use std::io::{BufRead, BufReader, Write};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use jaus::component::local::Probe;
use jaus::messages::*;
use jaus::net::{Node, NodeConfig};
use jaus::stock::hardware::Wrench;
use jaus::stock::motion::wrench_message;
use jaus::{Address, Header, JausMessage};
use jaus_ros2::{ids, robot_node, Ros2Config, WatchdogEvent};
use serde_json::Value;

fn wall_ns() -> i128 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map(|d| d.as_nanos() as i128)
        .unwrap_or(0)
}

/// The Python robot: its stdin (pause/resume) and the JSON lines it printed.
struct Robot {
    child: Child,
    stdin: ChildStdin,
    lines: Arc<Mutex<Vec<Value>>>,
}

impl Robot {
    fn start(py: &str, domain: u16, extra: &[&str]) -> Robot {
        let script = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/ros2_robot.py");
        let mut child = Command::new(py)
            .arg(script)
            .args(["--domain", &domain.to_string(), "--duration", "90"])
            .args(extra)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .expect("start ros2_robot.py");
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
        Robot {
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

    /// The twists it received since line `from`.
    fn cmds_since(&self, from: usize) -> Vec<Vec<f64>> {
        self.lines()[from..]
            .iter()
            .filter_map(|l| l["cmd"].as_array())
            .map(|a| a.iter().map(|v| v.as_f64().unwrap()).collect())
            .collect()
    }
}

impl Drop for Robot {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A JAUS client component on the bridge's own node, driving it in process.
struct Client {
    node: Node,
    me: Address,
}

impl Client {
    fn to(&self, id: u8) -> Address {
        Address::new(self.me.subsystem, self.me.node, id, ids::INSTANCE)
    }

    fn send<M: JausMessage>(&mut self, id: u8, m: &M) {
        let h = Header::new(M::CODE, self.to(id), self.me);
        self.node.send(Instant::now(), h, m.to_bytes().unwrap());
        self.pump();
    }

    fn pump(&mut self) {
        self.node.handle_timeout(Instant::now());
        while let Some(d) = self.node.poll_transmit() {
            self.node.recycle(d.bytes);
        }
    }

    /// Runs the node for `d`, calling `each` every `period`.
    fn run(&mut self, d: Duration, period: Duration, mut each: impl FnMut(&mut Client)) {
        let end = Instant::now() + d;
        while Instant::now() < end {
            each(self);
            self.pump();
            std::thread::sleep(period);
        }
    }

    /// Takes what the client received, with the wall time it was taken at.
    fn take(&mut self) -> Vec<Message> {
        let p: &mut Probe = self.node.get_mut(self.me).unwrap();
        let out = p.messages().cloned().collect();
        p.clear();
        out
    }
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    let i = ((sorted.len() as f64 - 1.0) * p).round() as usize;
    sorted[i.min(sorted.len() - 1)]
}

#[test]
fn a_jaus_client_drives_a_cyclone_dds_ros2_robot() {
    let Some(py) = support::python("a_jaus_client_drives_a_cyclone_dds_ros2_robot") else {
        return;
    };
    // A domain of its own, so that parallel runs do not meet.
    let domain = 100 + (std::process::id() % 100) as u16;
    let mut robot = Robot::start(&py, domain, &[]);
    let t = Instant::now();
    while !robot.lines().iter().any(|l| l["ready"] == true) && t.elapsed() < Duration::from_secs(20)
    {
        std::thread::sleep(Duration::from_millis(20));
    }
    std::thread::sleep(Duration::from_millis(300));
    let config = Ros2Config {
        domain_id: domain,
        ..Ros2Config::default()
    };
    let node_config = NodeConfig {
        subsystem: 9,
        node: 1,
        ..NodeConfig::default()
    };
    let (mut node, link) = robot_node(&config, node_config, Instant::now()).unwrap();
    assert_eq!(link.dds_topics(), ["rt/cmd_vel", "rt/odom", "rt/fix"]);
    let me = Address::new(9, 1, 200, 1);
    node.add(Probe::new(me)).unwrap();
    let mut c = Client { node, me };

    // Discovery: odometry arrives.
    let t = Instant::now();
    while link.odom().is_none() && t.elapsed() < Duration::from_secs(20) {
        c.run(Duration::from_millis(50), Duration::from_millis(5), |_| {});
    }
    assert!(
        link.odom().is_some(),
        "no odom over DDS: {:?}",
        link.stats()
    );
    println!("discovery: odom after {:?}", t.elapsed());
    // The Python side sees the bridge in the ROS 2 graph (`ros_discovery_info`, what
    // `ros2 node list` reads). Only its name and a writer are checked: with RustDDS
    // 0.13 the last update of the node's reader/writer lists may not reach Cyclone
    // (docs/ros2.md, "Not mapped yet").
    let t = Instant::now();
    let seen = |r: &Robot| {
        r.lines().iter().any(|l| {
            l["ros_node"] == "jaus_bridge"
                && l["namespace"] == "/"
                && l["writers"].as_u64() >= Some(1)
        })
    };
    while !seen(&robot) && t.elapsed() < Duration::from_secs(10) {
        c.run(Duration::from_millis(50), Duration::from_millis(5), |_| {});
    }
    let nodes: Vec<_> = robot
        .lines()
        .into_iter()
        .filter(|l| l["ros_node"].is_string())
        .collect();
    assert!(seen(&robot), "not in the ROS 2 graph: {nodes:?}");
    println!("ROS 2 graph, as Cyclone saw it: {nodes:?}");

    // Control and Resume.
    let pd = ids::PRIMITIVE_DRIVER;
    c.send(pd, &RequestComponentControl { authority_code: 10 });
    c.run(Duration::from_millis(100), Duration::from_millis(5), |_| {});
    c.send(pd, &Resume {});
    c.run(Duration::from_millis(100), Duration::from_millis(5), |_| {});
    let confirmed = c
        .take()
        .iter()
        .any(|m| matches!(m, Message::ConfirmComponentControl(_)));
    assert!(confirmed, "control not confirmed");

    // Forward at 50 % (0.5 m/s with the default mapping), refreshed every 100 ms; Local
    // Pose queried every 0.5 ms. The robot's odometry frame is ENU and it starts facing
    // east (+x), so JAUS sees it move along y (east).
    let forward = {
        let mut w = Wrench::ZERO;
        w.linear.x = 50.0;
        wrench_message(&w)
    };
    let mut reports: Vec<(i128, f64, f64)> = Vec::new();
    let mut velocities = Vec::new();
    let mut globals = Vec::new();
    // DDS leg: each odom's header.stamp (its publication) → the bridge taking it.
    let mut dds_ms = Vec::new();
    let mut last_stamp = None;
    let mut last_effort = Instant::now() - Duration::from_secs(1);
    let drive_from = robot.lines().len();
    c.run(Duration::from_secs(3), Duration::from_micros(500), |c| {
        if last_effort.elapsed() >= Duration::from_millis(100) {
            c.send(pd, &forward);
            c.send(
                ids::VELOCITY_STATE_SENSOR,
                &QueryVelocityState {
                    presence_vector: 0x47,
                },
            );
            c.send(
                ids::GLOBAL_POSE_SENSOR,
                &QueryGlobalPose {
                    presence_vector: 0x4f,
                },
            );
            last_effort = Instant::now();
        }
        c.send(
            ids::LOCAL_POSE_SENSOR,
            &QueryLocalPose {
                presence_vector: 0x47,
            },
        );
        let now = wall_ns();
        if let Some(o) = link.odom().filter(|o| Some(o.stamp) != last_stamp) {
            last_stamp = Some(o.stamp);
            let taken = now - o.received.elapsed().as_nanos() as i128;
            dds_ms.push((taken - i128::from(o.stamp.as_nanos())) as f64 / 1e6);
        }
        for m in c.take() {
            match m {
                Message::ReportLocalPose(r) => {
                    reports.push((now, r.x.unwrap_or(f64::NAN), r.y.unwrap_or(f64::NAN)))
                }
                Message::ReportVelocityState(v) => velocities.push(v),
                Message::ReportGlobalPose(g) => globals.push(g),
                _ => {}
            }
        }
    });
    let (_, x0, y0) = reports.first().copied().expect("no Report Local Pose");
    let (_, x1, y1) = reports.last().copied().unwrap();
    println!(
        "local pose: ({x0:.3}, {y0:.3}) → ({x1:.3}, {y1:.3}) in {} reports",
        reports.len()
    );
    assert!(y1 - y0 > 0.8, "the robot did not move east: {y0} → {y1}");
    assert!((x1 - x0).abs() < 0.05, "the robot moved north: {x0} → {x1}");
    let cmds = robot.cmds_since(drive_from);
    assert!(
        cmds.iter()
            .any(|t| (t[0] - 0.5).abs() < 1e-3 && t[5] == 0.0),
        "robot never got 0.5 m/s: {cmds:?}"
    );
    let moving = velocities
        .iter()
        .filter_map(|v| v.velocity_x)
        .fold(0.0, f64::max);
    assert!((moving - 0.5).abs() < 0.01, "velocity state: {moving}");
    let g = globals.last().expect("no Report Global Pose");
    assert!((g.latitude.unwrap() - 29.65).abs() < 1e-3, "{g:?}");
    assert!(
        g.longitude.unwrap() > -82.32,
        "fix did not move east: {g:?}"
    );

    // Latency: each odom publication, to the first Report Local Pose carrying its y
    // (JAUS y = ROS x east). Quantised by the 0.5 ms query period.
    let odoms: Vec<(i128, f64)> = robot
        .lines()
        .iter()
        .filter(|l| l["odom"].is_u64())
        .map(|l| {
            (
                l["t_ns"].as_i64().unwrap() as i128,
                l["x"].as_f64().unwrap(),
            )
        })
        .collect();
    let mut lat_ms = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for &(t_report, _, y) in &reports {
        if let Some((i, &(t_pub, _))) = odoms
            .iter()
            .enumerate()
            .find(|(_, (_, x))| (x - y).abs() < 1e-4)
        {
            // Moving samples only (a stationary pose matches many).
            if i > 0 && (odoms[i - 1].1 - odoms[i].1).abs() > 1e-3 && seen.insert(i) {
                lat_ms.push((t_report - t_pub) as f64 / 1e6);
            }
        }
    }
    lat_ms.sort_by(|a, b| a.total_cmp(b));
    assert!(
        lat_ms.len() >= 20,
        "too few matched samples: {}",
        lat_ms.len()
    );
    println!(
        "latency odom published → Report Local Pose: n={} p50={:.2} ms p99={:.2} ms max={:.2} ms",
        lat_ms.len(),
        percentile(&lat_ms, 0.5),
        percentile(&lat_ms, 0.99),
        lat_ms[lat_ms.len() - 1]
    );
    dds_ms.sort_by(|a, b| a.total_cmp(b));
    println!(
        "of which DDS (Cyclone → RustDDS, odom published → taken by the bridge): n={} \
         p50={:.2} ms p99={:.2} ms",
        dds_ms.len(),
        percentile(&dds_ms, 0.5),
        percentile(&dds_ms, 0.99)
    );

    // Release control: the driver stops, the watchdog publishes a zero twist, the robot
    // stops.
    let release_from = robot.lines().len();
    let _ = link.events();
    c.send(pd, &ReleaseComponentControl {});
    c.run(Duration::from_millis(300), Duration::from_millis(5), |_| {});
    let events = link.events();
    assert!(
        events.iter().any(|e| matches!(
            e,
            WatchdogEvent::JausStop { controller: Some(a), .. } if *a == me
        )),
        "{events:?}"
    );
    let after = robot.cmds_since(release_from);
    assert!(
        after.last().is_some_and(|t| t.iter().all(|v| *v == 0.0)),
        "no zero twist after release: {after:?}"
    );
    assert!(link.last_published().unwrap().is_zero());
    let stopped_at = link.odom().unwrap().pose.position.y;
    c.run(Duration::from_millis(500), Duration::from_millis(5), |_| {});
    let still = link.odom().unwrap().pose.position.y;
    assert!(
        (still - stopped_at).abs() < 0.01,
        "still moving: {stopped_at} → {still}"
    );

    // ROS side silent: control again, drive, pause odom: the watchdog zeroes cmd_vel and
    // holds further commands; odom back: commands pass again.
    c.send(pd, &RequestComponentControl { authority_code: 10 });
    c.send(pd, &Resume {});
    let mut last_effort = Instant::now() - Duration::from_secs(1);
    let mut drive = |c: &mut Client| {
        if last_effort.elapsed() >= Duration::from_millis(100) {
            c.send(pd, &forward);
            last_effort = Instant::now();
        }
    };
    c.run(
        Duration::from_millis(300),
        Duration::from_millis(5),
        &mut drive,
    );
    assert!(!link.last_published().unwrap().is_zero());
    let held_before = link.stats().held;
    robot.say("pause");
    c.run(
        Duration::from_millis(1200),
        Duration::from_millis(5),
        &mut drive,
    );
    assert!(link.ros_silent());
    assert!(link.stats().held > held_before, "{:?}", link.stats());
    assert!(link.last_published().unwrap().is_zero());
    let events = link.events();
    assert!(
        events
            .iter()
            .any(|e| matches!(e, WatchdogEvent::RosSilent { .. })),
        "{events:?}"
    );
    c.send(
        ids::LOCAL_POSE_SENSOR,
        &QueryLocalPose {
            presence_vector: 0x47,
        },
    );
    c.run(Duration::from_millis(50), Duration::from_millis(5), |_| {});
    assert!(
        !c.take()
            .iter()
            .any(|m| matches!(m, Message::ReportLocalPose(_))),
        "a stale local pose was reported"
    );
    robot.say("resume");
    c.run(
        Duration::from_millis(600),
        Duration::from_millis(5),
        &mut drive,
    );
    assert!(!link.ros_silent());
    assert!(link
        .events()
        .iter()
        .any(|e| matches!(e, WatchdogEvent::RosResumed { .. })));
    assert!(!link.last_published().unwrap().is_zero());
    println!("bridge stats: {:?}", link.stats());

    // Dropping the link publishes a last zero twist.
    let end_from = robot.lines().len();
    drop(link);
    std::thread::sleep(Duration::from_millis(300));
    let last = robot.cmds_since(end_from);
    assert!(
        last.last().is_some_and(|t| t.iter().all(|v| *v == 0.0)),
        "{last:?}"
    );
}

/// The camera's pixel (x, y), as `ros2_robot.py` draws it.
fn pattern(x: u32, y: u32) -> [u8; 3] {
    [(x * 30) as u8, (y * 40) as u8, (200 - x * 10) as u8]
}

fn decode_png(data: &[u8]) -> (u32, u32, Vec<u8>) {
    let mut d = png::Decoder::new(data).read_info().expect("a PNG");
    let mut buf = vec![0; d.output_buffer_size()];
    let info = d.next_frame(&mut buf).expect("PNG pixels");
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// Asks the Visual Sensor of `c` for an image until one comes (5 s at most).
fn query_image(c: &mut Client) -> ReportImage {
    let t = Instant::now();
    while t.elapsed() < Duration::from_secs(5) {
        c.send(ids::VISUAL_SENSOR, &QueryImage {});
        c.run(Duration::from_millis(50), Duration::from_millis(5), |_| {});
        if let Some(r) = c.take().into_iter().find_map(|m| match m {
            Message::ReportImage(r) => Some(r),
            _ => None,
        }) {
            return r;
        }
    }
    panic!("no Report Image");
}

/// Waits (running `c`'s node) until `done` or 20 s.
fn wait_for(c: &mut Client, mut done: impl FnMut() -> bool) -> bool {
    let t = Instant::now();
    while !done() && t.elapsed() < Duration::from_secs(20) {
        c.run(Duration::from_millis(50), Duration::from_millis(5), |_| {});
    }
    done()
}

/// The 8×6 test pattern of the robot's camera in `r` (with `mark` at (7, 5)).
fn check(r: &ReportImage, mark: Option<[u8; 3]>) {
    assert_eq!((r.camera_id, r.video_format), (1, ImageFormat::Png));
    let (w, h, px) = decode_png(&r.data);
    assert_eq!((w, h), (8, 6));
    for y in 0..h {
        for x in 0..w {
            let at = ((y * w + x) * 3) as usize;
            let want = match mark {
                Some(m) if (x, y) == (7, 5) => m,
                _ => pattern(x, y),
            };
            assert_eq!(&px[at..at + 3], &want, "pixel ({x}, {y})");
        }
    }
}

#[test]
fn lidar_and_camera_of_a_cyclone_dds_ros2_robot() {
    let Some(py) = support::python("lidar_and_camera_of_a_cyclone_dds_ros2_robot") else {
        return;
    };
    // Not the other test's domain (100..=199) when both run at once.
    let domain = 200 + (std::process::id() % 30) as u16;
    let mut robot = Robot::start(&py, domain, &["--sensors"]);
    let t = Instant::now();
    while !robot.lines().iter().any(|l| l["ready"] == true) && t.elapsed() < Duration::from_secs(20)
    {
        std::thread::sleep(Duration::from_millis(20));
    }
    let mut config = Ros2Config {
        domain_id: domain,
        ..Ros2Config::default()
    };
    (config.sensors.range, config.sensors.visual) = (true, true);
    (config.camera.width, config.camera.height) = (8, 6);
    let node_config = NodeConfig {
        subsystem: 9,
        node: 1,
        ..NodeConfig::default()
    };
    let (mut node, link) = robot_node(&config, node_config, Instant::now()).unwrap();
    assert_eq!(
        link.sensor_topics(),
        (Some("rt/scan"), Some("rt/image_raw"))
    );
    let me = Address::new(9, 1, 200, 1);
    node.add(Probe::new(me)).unwrap();
    let mut c = Client { node, me };
    assert!(
        wait_for(&mut c, || {
            let s = link.stats();
            s.scans > 0 && s.images > 0
        }),
        "no scan or image over DDS: {:?}",
        link.stats()
    );

    // The Range Sensor: the nearest object, 2.0 m at ROS −30° (to the right), is at
    // JAUS bearing +30°; the 0.05 m return (below range_min) and the NaN are ignored.
    c.send(
        ids::RANGE_SENSOR,
        &QueryRelativeObjectPosition {
            presence_vector: 0x7f,
        },
    );
    c.run(Duration::from_millis(100), Duration::from_millis(5), |_| {});
    let r = c
        .take()
        .into_iter()
        .find_map(|m| match m {
            Message::ReportRelativeObjectPosition(r) => Some(r),
            _ => None,
        })
        .expect("no Report Relative Object Position");
    println!("range sensor: {r:?}");
    let range = r.range.expect("a range");
    let bearing = r.bearing.expect("a bearing");
    assert!((range - 2.0).abs() < 0.01, "range {range}");
    // One beam is 1°: the bearing within half of it.
    assert!(
        (bearing - 30f64.to_radians()).abs() < 0.5f64.to_radians(),
        "bearing {} rad ({}°): positive is to the right",
        bearing,
        bearing.to_degrees()
    );
    assert_eq!(r.confidence, Some(5), "five beams saw the object");

    // The Visual Sensor: rgb8 rows with padding, as PNG.
    check(&query_image(&mut c), None);
    // bgr8: the same colours (and the mark only bgr8 frames have).
    robot.say("encoding bgr8");
    let images = link.stats().images;
    assert!(wait_for(&mut c, || link.stats().images >= images + 3));
    check(&query_image(&mut c), Some([250, 10, 60]));

    // Bad messages: dropped and counted, nothing else changes.
    let before = link.stats();
    robot.say("bad");
    assert!(
        wait_for(&mut c, || {
            let s = link.stats();
            s.scans_refused > before.scans_refused && s.images_refused > before.images_refused
        }),
        "{:?}",
        link.stats()
    );
    c.run(Duration::from_millis(300), Duration::from_millis(5), |_| {});
    check(&query_image(&mut c), Some([250, 10, 60]));
    println!("bridge stats: {:?}", link.stats());
}

/// The camera as `sensor_msgs/CompressedImage` (PNG), with a robot and a domain of its
/// own: a bridge joining a domain where another bridge of the process has been (CI saw
/// it hear nothing in 20 s, 2 runs of 9) is not what this checks.
#[test]
fn compressed_camera_of_a_cyclone_dds_ros2_robot() {
    let Some(py) = support::python("compressed_camera_of_a_cyclone_dds_ros2_robot") else {
        return;
    };
    // Neither of the other tests' domains (100..=199, 200..=229).
    let domain = 20 + (std::process::id() % 60) as u16;
    let robot = Robot::start(&py, domain, &["--sensors"]);
    let t = Instant::now();
    while !robot.lines().iter().any(|l| l["ready"] == true) && t.elapsed() < Duration::from_secs(20)
    {
        std::thread::sleep(Duration::from_millis(20));
    }
    let mut config = Ros2Config {
        domain_id: domain,
        ..Ros2Config::default()
    };
    (config.sensors.range, config.sensors.visual) = (true, true);
    (config.camera.width, config.camera.height) = (8, 6);
    let mut compressed = config.clone();
    compressed.node_name = "jaus_bridge_png".into();
    (compressed.sensors.compressed, compressed.sensors.range) = (true, false);
    let node_config = NodeConfig {
        subsystem: 9,
        node: 2,
        ..NodeConfig::default()
    };
    let (mut node, link2) = robot_node(&compressed, node_config, Instant::now()).unwrap();
    assert_eq!(
        link2.sensor_topics(),
        (None, Some("rt/image_raw/compressed"))
    );
    let me = Address::new(9, 2, 200, 1);
    node.add(Probe::new(me)).unwrap();
    let mut c2 = Client { node, me };
    assert!(
        wait_for(&mut c2, || link2.stats().images > 0),
        "no compressed image over DDS: {:?}",
        link2.stats()
    );
    check(&query_image(&mut c2), None);
    c2.send(
        ids::RANGE_SENSOR,
        &QueryRelativeObjectPosition {
            presence_vector: 0x7f,
        },
    );
    c2.run(Duration::from_millis(100), Duration::from_millis(5), |_| {});
    assert!(
        !c2.take()
            .iter()
            .any(|m| matches!(m, Message::ReportRelativeObjectPosition(_))),
        "sensors.range off: no Range Sensor"
    );
    println!("compressed bridge stats: {:?}", link2.stats());
}
