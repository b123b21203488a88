//! The IOP judge against a ROS 2 robot presented through `jaus node` (issue 50): the
//! Python robot of `sdk/ros2/tests/ros2_robot.py` (Cyclone DDS, the `cyclonedds`
//! package; publishes `rt/odom`, integrates `rt/cmd_vel`) on a DDS domain of its own,
//! the `jaus` binary's `node` with a node file holding `ros2:` (same domain), `host:
//! [local_waypoint_driver]` and `as4: { component: 1 }`, and `jaus conform --as4
//! --allow-motion` against it: every check passes, and the robot drove the judge's
//! waypoints (its odometry moved, `cmd_vel` carried motion).
//!
//! Needs `JAUS_ROS2_PYTHON`: a Python with `cyclonedds` (`python3 -m venv /tmp/ros2venv
//! && /tmp/ros2venv/bin/pip install cyclonedds`, then
//! `JAUS_ROS2_PYTHON=/tmp/ros2venv/bin/python`). Without it the test says so on stderr
//! and passes, unless `JAUS_REQUIRE_ROS2=1`. Run with `--nocapture` for the timings.

#[path = "../../ros2/tests/support/mod.rs"]
mod support;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use serde_json::Value;

const JAUS: &str = env!("CARGO_BIN_EXE_jaus");

/// The processes of the run and its directory: every child killed and reaped, the
/// directory removed, on every path (a failed assertion included).
struct Run {
    dir: PathBuf,
    children: Vec<(&'static str, Child)>,
}

impl Run {
    fn child(&mut self, name: &str) -> &mut Child {
        &mut self
            .children
            .iter_mut()
            .find(|(n, _)| *n == name)
            .expect("started")
            .1
    }

    /// Waits up to `limit` for child `name` to exit: its status, or `None` (still
    /// running).
    fn wait(&mut self, name: &str, limit: Duration) -> Option<std::process::ExitStatus> {
        let end = Instant::now() + limit;
        loop {
            if let Ok(Some(s)) = self.child(name).try_wait() {
                return Some(s);
            }
            if Instant::now() >= end {
                return None;
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    fn read(&self, file: &str) -> String {
        std::fs::read_to_string(self.dir.join(file)).unwrap_or_default()
    }
}

impl Drop for Run {
    fn drop(&mut self) {
        for (_, c) in &mut self.children {
            let _ = c.kill();
            let _ = c.wait();
        }
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// Lines a child printed on stdout, parsed as JSON where they are.
fn collect(out: std::process::ChildStdout) -> Arc<Mutex<Vec<Value>>> {
    let lines = Arc::new(Mutex::new(Vec::new()));
    let sink = lines.clone();
    std::thread::spawn(move || {
        for line in BufReader::new(out).lines().map_while(Result::ok) {
            if let Ok(v) = serde_json::from_str::<Value>(&line) {
                sink.lock().unwrap().push(v);
            }
        }
    });
    lines
}

fn file(dir: &Path, name: &str) -> std::fs::File {
    std::fs::File::create(dir.join(name)).unwrap()
}

#[test]
fn the_iop_judge_passes_against_a_ros2_robot_through_jaus_node() {
    let Some(py) = support::python("the_iop_judge_passes_against_a_ros2_robot_through_jaus_node")
    else {
        return;
    };
    let started = Instant::now();
    // A domain of its own (the jaus-ros2 tests use 100..=229), a free port.
    let domain = 40 + (std::process::id() % 60) as u16;
    let port = std::net::UdpSocket::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let dir = std::env::temp_dir().join(format!("jaus-ros2-iop-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut run = Run {
        dir: dir.clone(),
        children: Vec::new(),
    };

    // The ROS 2 robot. Its stdin stays open (EOF ends it) as long as `run` holds it.
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/../ros2/tests/ros2_robot.py");
    let mut robot = Command::new(&py)
        .arg(script)
        .args(["--domain", &domain.to_string(), "--duration", "180"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(file(&dir, "robot.err"))
        .spawn()
        .expect("start ros2_robot.py");
    let robot_lines = collect(robot.stdout.take().unwrap());
    run.children.push(("robot", robot));
    let lines = || robot_lines.lock().unwrap().clone();
    let t = Instant::now();
    while !lines().iter().any(|l| l["ready"] == true) && t.elapsed() < Duration::from_secs(30) {
        assert!(
            run.wait("robot", Duration::ZERO).is_none(),
            "ros2_robot.py ended: {}",
            run.read("robot.err")
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(
        lines().iter().any(|l| l["ready"] == true),
        "ros2_robot.py not ready within 30 s: {}",
        run.read("robot.err")
    );
    let robot_ready = started.elapsed();

    // `jaus node`: the robot through `ros2:`, a Local Waypoint Driver over it, AS-4.
    let node_file = dir.join("robot.yaml");
    std::fs::write(
        &node_file,
        format!(
            "subsystem: 1\nnode: 1\nsubsystem_name: ros2 robot\nbind: 127.0.0.1:{port}\n\
             host: [local_waypoint_driver]\nas4: {{ component: 1 }}\nros2: {{ domain_id: {domain} }}\n"
        ),
    )
    .unwrap();
    let node = Command::new(JAUS)
        .args(["-v", "node", "--config"])
        .arg(&node_file)
        .args(["--seconds", "240"])
        .stdin(Stdio::null())
        .stdout(file(&dir, "node.out"))
        .stderr(file(&dir, "node.err"))
        .spawn()
        .expect("start jaus node");
    run.children.push(("node", node));
    let t = Instant::now();
    while !run.read("node.out").contains("--- system tree") && t.elapsed() < Duration::from_secs(40)
    {
        if let Some(s) = run.wait("node", Duration::ZERO) {
            panic!(
                "jaus node ended ({s}):\n{}\n{}",
                run.read("node.out"),
                run.read("node.err")
            );
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    let out = run.read("node.out");
    assert!(
        out.contains("--- system tree"),
        "jaus node not running within 40 s:\n{out}\n{}",
        run.read("node.err")
    );
    // The robot's pose through JAUS and AS-4 (the gateway's report of the Local Pose
    // Sensor, fed by `odom`): what the judge reads first. The node starts before the
    // first `odom` reaches it; its sensors refuse until then.
    let t = Instant::now();
    let pose_flows = || {
        let out = Command::new(JAUS)
            .args(["as4-query", "--peer"])
            .arg(format!("127.0.0.1:{port}"))
            .args(["--to", "1.1.1", "--bind", "127.0.0.1:0", "--wait", "1"])
            .arg(r#"{"message":"QueryLocalPose","fields":{"presence_vector":259}}"#)
            .output()
            .expect("jaus as4-query");
        String::from_utf8_lossy(&out.stdout)
            .lines()
            .any(|l| serde_json::from_str::<Value>(l).is_ok_and(|v| v["fields"]["x"].is_number()))
    };
    while !pose_flows() {
        assert!(
            t.elapsed() < Duration::from_secs(30),
            "no local pose through AS-4 within 30 s:\n{}\n{}",
            run.read("node.out"),
            run.read("node.err")
        );
        std::thread::sleep(Duration::from_millis(200));
    }
    let node_ready = started.elapsed();

    // The judge.
    let json = dir.join("conform.json");
    let conform = Command::new(JAUS)
        .args(["conform", "--as4", "--allow-motion", "--peer"])
        .arg(format!("127.0.0.1:{port}"))
        .args(["--bind", "127.0.0.1:0", "--json"])
        .arg(&json)
        .stdin(Stdio::null())
        .stdout(file(&dir, "conform.out"))
        .stderr(file(&dir, "conform.err"))
        .spawn()
        .expect("start jaus conform");
    run.children.push(("conform", conform));
    let judged_from = Instant::now();
    let status = run.wait("conform", Duration::from_secs(180));
    let judged = judged_from.elapsed();
    let report = format!(
        "{}\n{}\n--- node:\n{}\n{}",
        run.read("conform.out"),
        run.read("conform.err"),
        run.read("node.out"),
        run.read("node.err")
    );
    let status =
        status.unwrap_or_else(|| panic!("jaus conform still running after 180 s:\n{report}"));
    assert!(status.success(), "jaus conform: {status}\n{report}");

    let result: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap())
        .unwrap_or_else(|e| panic!("{}: {e}", json.display()));
    let outcomes: Vec<&Value> = result["components"]
        .as_array()
        .into_iter()
        .flatten()
        .flat_map(|c| c["outcomes"].as_array().into_iter().flatten())
        .collect();
    assert_eq!(outcomes.len(), 20, "{report}");
    let bad: Vec<String> = outcomes
        .iter()
        .filter(|o| o["verdict"] != "pass")
        .map(|o| format!("{} {}: {}", o["id"], o["verdict"], o["detail"]))
        .collect();
    assert!(
        bad.is_empty(),
        "checks that did not pass:\n{}",
        bad.join("\n")
    );
    let required = outcomes.iter().filter(|o| o["level"] == "required").count();
    let waypoints = outcomes
        .iter()
        .find(|o| o["id"] == "as4.waypoints.active_element")
        .expect("the waypoint check");
    println!(
        "judge: {} checks pass ({required} required); waypoints: {}",
        outcomes.len(),
        waypoints["detail"]
    );

    // The robot drove: its odometry moved and cmd_vel carried motion.
    let odom: Vec<(f64, f64)> = lines()
        .iter()
        .filter(|l| l["odom"].is_u64())
        .filter_map(|l| Some((l["x"].as_f64()?, l["y"].as_f64()?)))
        .collect();
    let (x0, y0) = odom.first().copied().expect("no odom from the robot");
    let farthest = odom
        .iter()
        .map(|(x, y)| (x - x0).hypot(y - y0))
        .fold(0.0, f64::max);
    let moving = lines()
        .iter()
        .filter_map(|l| l["cmd"].as_array().cloned())
        .filter(|c| {
            c.first()
                .and_then(Value::as_f64)
                .is_some_and(|v| v.abs() > 0.05)
        })
        .count();
    println!(
        "robot: {} odom, {moving} moving cmd_vel, at most {farthest:.2} m from its start",
        odom.len()
    );
    assert!(
        moving > 10,
        "the robot was never driven: {moving} moving cmd_vel"
    );
    assert!(farthest > 1.0, "the robot did not move: {farthest:.2} m");

    // The node stops on Ctrl-C and prints its counters, the bridge's among them.
    let pid = run.child("node").id().to_string();
    let _ = Command::new("kill").args(["-INT", &pid]).status();
    let ended = run.wait("node", Duration::from_secs(15));
    let out = run.read("node.out");
    assert!(ended.is_some(), "jaus node did not stop on SIGINT:\n{out}");
    let stats = out
        .lines()
        .find(|l| l.starts_with("ros2 stats:"))
        .unwrap_or_else(|| panic!("no `ros2 stats:` line:\n{out}"));
    println!("{stats}");
    println!(
        "timing: robot ready {:.1} s, jaus node up {:.1} s, judge {:.1} s, total {:.1} s",
        robot_ready.as_secs_f64(),
        (node_ready - robot_ready).as_secs_f64(),
        judged.as_secs_f64(),
        started.elapsed().as_secs_f64()
    );
}
