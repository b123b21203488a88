//! `jaus ros2`: a ROS 2 robot on the JAUS network (crate `jaus-ros2`, docs/ros2.md). The
//! robot's `cmd_vel`, `odom` and `fix` topics, over DDS without a ROS install, become a
//! node of RA 3.3 components (Primitive Driver, Local Pose, Velocity State and Global
//! Pose Sensors) on UDP; with `sensors: {range: true, visual: true}` in the file, its
//! `scan` and camera also become a Range Sensor and a Visual Sensor. Each watchdog event (control lost, ROS silent, ...) is printed
//! as a JSON line on stdout; the bridge's counters at the end.
//!
//! With `--vehicle SUBSYSTEM` (or `vehicle: {subsystem: S}` in the file) the other
//! direction: a JAUS vehicle in ROS 2 ([`jaus_ros2::vehicle`]): its reports published as
//! `odom`, `fix` and `jaus/status`, driven by `cmd_vel` and `goal_pose`.

use std::io::Write;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use jaus::net::{udp, NodeConfig};
use jaus_ros2::{robot_node, vehicle_node, Ros2Config, VehicleEvent, WatchdogEvent};

/// `jaus ros2`.
#[derive(Debug, Clone, clap::Args)]
pub struct Ros2Args {
    /// The bridge's settings (YAML: domain_id, node_name, namespace, topics, frames,
    /// odom_axes, qos_commands, qos_sensors, effort, watchdog_ms, command_timeout_ms,
    /// vehicle, sensors, camera; docs/ros2.md); default: the defaults there.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// The DDS domain id (overrides the file's).
    #[arg(long)]
    pub domain: Option<u16>,
    /// The JAUS subsystem of the robot's node (with --vehicle: the bridge's own).
    #[arg(long, default_value_t = 1)]
    pub subsystem: u8,
    /// The JAUS node id.
    #[arg(long, default_value_t = 1)]
    pub node: u8,
    /// The node's UDP socket.
    #[arg(long, default_value = "127.0.0.1:3794")]
    pub bind: SocketAddr,
    /// Other JAUS nodes to talk to (repeatable).
    #[arg(long)]
    pub peer: Vec<SocketAddr>,
    /// Stop after this many seconds (default: until interrupted).
    #[arg(long)]
    pub seconds: Option<f64>,
    /// Vehicle mode: present the JAUS vehicle of this subsystem in ROS 2 (found through
    /// --peer in the system tree by its component ids): publishes odom
    /// (nav_msgs/Odometry, from Report Local Pose and Velocity State), fix
    /// (sensor_msgs/NavSatFix, Report Global Pose) and jaus/status (std_msgs/String);
    /// cmd_vel (geometry_msgs/Twist) drives its Primitive Driver under control (Set Wrench
    /// Effort, effort.max_linear m/s and max_angular rad/s are 100 %, clamped; no cmd_vel
    /// for vehicle.cmd_vel_timeout_ms, 500 ms, sends zero efforts); goal_pose
    /// (geometry_msgs/PoseStamped in the odom frame) becomes a waypoint of its Local (else
    /// Global) Waypoint Driver. --subsystem/--node are then the bridge's own (another
    /// subsystem than the vehicle's).
    #[arg(long, value_name = "SUBSYSTEM")]
    pub vehicle: Option<u8>,
    /// Vehicle mode: rate of the pose and velocity service connections and of odom and
    /// fix, Hz (overrides the file's vehicle.rate_hz; default 10).
    #[arg(long, value_name = "HZ")]
    pub rate: Option<f64>,
}

/// The bridge's settings: the file's, with the command line's overrides.
pub fn config(args: &Ros2Args) -> Result<Ros2Config, String> {
    let mut c = match &args.config {
        Some(p) => {
            let text = std::fs::read_to_string(p).map_err(|e| format!("{}: {e}", p.display()))?;
            serde_yaml::from_str::<Ros2Config>(&text)
                .map_err(|e| format!("{}: {e}", p.display()))?
        }
        None => Ros2Config::default(),
    };
    if let Some(d) = args.domain {
        c.domain_id = d;
    }
    if let Some(v) = args.vehicle {
        c.vehicle.subsystem = Some(v);
    }
    if let Some(r) = args.rate {
        c.vehicle.rate_hz = r;
    }
    Ok(c)
}

/// A watchdog event as a JSON line (`t`: seconds since the bridge started).
fn event_json(t0: Instant, e: &WatchdogEvent) -> serde_json::Value {
    let secs = |at: &Instant| at.saturating_duration_since(t0).as_secs_f64();
    match e {
        WatchdogEvent::JausStop {
            at,
            controller,
            reason,
        } => serde_json::json!({
            "t": secs(at), "event": "jaus_stop", "reason": reason,
            "controller": controller.map(|a| a.to_string()),
        }),
        WatchdogEvent::RosSilent { at } => {
            serde_json::json!({"t": secs(at), "event": "ros_silent"})
        }
        WatchdogEvent::RosResumed { at } => {
            serde_json::json!({"t": secs(at), "event": "ros_resumed"})
        }
    }
}

/// A vehicle-mode event as a JSON line (`t`: seconds since the bridge started).
fn vehicle_event_json(t0: Instant, e: &VehicleEvent) -> serde_json::Value {
    let secs = |at: &Instant| at.saturating_duration_since(t0).as_secs_f64();
    match e {
        VehicleEvent::ControlGained { at, component } => serde_json::json!({
            "t": secs(at), "event": "control_gained", "component": component.to_string(),
        }),
        VehicleEvent::ControlLost { at, component } => serde_json::json!({
            "t": secs(at), "event": "control_lost", "component": component.to_string(),
        }),
        VehicleEvent::CmdVelSilent { at } => {
            serde_json::json!({"t": secs(at), "event": "cmd_vel_silent"})
        }
        VehicleEvent::GoalSent { at, driver } => serde_json::json!({
            "t": secs(at), "event": "goal_sent", "driver": driver.to_string(),
        }),
        VehicleEvent::GoalRefused { at, reason } => serde_json::json!({
            "t": secs(at), "event": "goal_refused", "reason": reason,
        }),
    }
}

/// Vehicle mode (`--vehicle`): the bridge's node with its JAUS client, until `--seconds`
/// pass or `stop` is set.
fn run_vehicle(
    args: &Ros2Args,
    config: &Ros2Config,
    stop: &AtomicBool,
    out: &mut impl Write,
) -> Result<(), String> {
    let t0 = Instant::now();
    let node_config = NodeConfig {
        subsystem: args.subsystem,
        node: args.node,
        peers: args.peer.clone(),
        ..NodeConfig::default()
    };
    let (mut node, mut link) = vehicle_node(config, node_config, t0).map_err(|e| e.to_string())?;
    let until = args
        .seconds
        .map(|s| t0 + Duration::from_secs_f64(s.max(0.0)));
    let socket = std::net::UdpSocket::bind(args.bind).map_err(|e| format!("{}: {e}", args.bind))?;
    let mut write_error = None;
    udp::run_on(&mut node, &socket, stop, until, |n| {
        link.step(n);
        for e in link.events() {
            if let Err(err) = writeln!(out, "{}", vehicle_event_json(t0, &e)) {
                write_error.get_or_insert(err);
            }
        }
    })
    .map_err(|e| format!("{}: {e}", args.bind))?;
    if let Some(e) = write_error {
        return Err(format!("stdout: {e}"));
    }
    let s = link.stats();
    writeln!(
        out,
        "{}",
        serde_json::json!({
            "stats": {
                "local_pose": s.local_pose, "velocity": s.velocity, "global_pose": s.global_pose,
                "odom": s.odom, "fix": s.fix, "status": s.status,
                "refused_reports": s.refused_reports, "cmd_vel": s.cmd_vel, "goals": s.goals,
                "refused_ros": s.refused_ros, "wrench_sent": s.wrench_sent,
                "watchdog_stops": s.watchdog_stops, "not_in_control": s.not_in_control,
                "publish_errors": s.publish_errors, "events_dropped": s.events_dropped,
            },
            "status": link.status_text(),
        })
    )
    .map_err(|e| format!("stdout: {e}"))?;
    link.stop();
    Ok(())
}

/// Runs the bridge until `--seconds` pass or `stop` is set.
pub fn run(args: &Ros2Args, stop: &AtomicBool, out: &mut impl Write) -> Result<(), String> {
    let config = config(args)?;
    if config.vehicle.subsystem.is_some() {
        return run_vehicle(args, &config, stop, out);
    }
    let t0 = Instant::now();
    let node_config = NodeConfig {
        subsystem: args.subsystem,
        node: args.node,
        peers: args.peer.clone(),
        ..NodeConfig::default()
    };
    let (mut node, link) = robot_node(&config, node_config, t0).map_err(|e| e.to_string())?;
    let until = args
        .seconds
        .map(|s| t0 + Duration::from_secs_f64(s.max(0.0)));
    let socket = std::net::UdpSocket::bind(args.bind).map_err(|e| format!("{}: {e}", args.bind))?;
    let mut write_error = None;
    udp::run_on(&mut node, &socket, stop, until, |_| {
        for e in link.events() {
            if let Err(err) = writeln!(out, "{}", event_json(t0, &e)) {
                write_error.get_or_insert(err);
            }
        }
    })
    .map_err(|e| format!("{}: {e}", args.bind))?;
    if let Some(e) = write_error {
        return Err(format!("stdout: {e}"));
    }
    let s = link.stats();
    writeln!(
        out,
        "{}",
        serde_json::json!({
            "stats": {
                "odom": s.odom, "fix": s.fix, "refused": s.refused,
                "foreign_frames": s.foreign_frames, "published": s.published,
                "published_zero": s.published_zero, "publish_errors": s.publish_errors,
                "superseded": s.superseded, "held": s.held, "events_dropped": s.events_dropped,
                "scans": s.scans, "scans_refused": s.scans_refused,
                "images": s.images, "images_refused": s.images_refused,
            }
        })
    )
    .map_err(|e| format!("stdout: {e}"))?;
    link.stop();
    Ok(())
}
