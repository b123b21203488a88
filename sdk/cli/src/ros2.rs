//! `jaus ros2`: a ROS 2 robot on the JAUS network (crate `jaus-ros2`, docs/ros2.md). The
//! robot's `cmd_vel`, `odom` and `fix` topics, over DDS without a ROS install, become a
//! node of RA 3.3 components (Primitive Driver, Local Pose, Velocity State and Global
//! Pose Sensors) on UDP. Each watchdog event (control lost, ROS silent, ...) is printed
//! as a JSON line on stdout; the bridge's counters at the end.

use std::io::Write;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::time::{Duration, Instant};

use jaus::net::{udp, NodeConfig};
use jaus_ros2::{robot_node, Ros2Config, WatchdogEvent};

/// `jaus ros2`.
#[derive(Debug, Clone, clap::Args)]
pub struct Ros2Args {
    /// The bridge's settings (YAML: domain_id, node_name, namespace, topics, frames,
    /// odom_axes, qos_commands, qos_sensors, effort, watchdog_ms, command_timeout_ms;
    /// docs/ros2.md); default: the defaults there.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// The DDS domain id (overrides the file's).
    #[arg(long)]
    pub domain: Option<u16>,
    /// The JAUS subsystem of the robot's node.
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

/// Runs the bridge until `--seconds` pass or `stop` is set.
pub fn run(args: &Ros2Args, stop: &AtomicBool, out: &mut impl Write) -> Result<(), String> {
    let config = config(args)?;
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
            }
        })
    )
    .map_err(|e| format!("stdout: {e}"))?;
    link.stop();
    Ok(())
}
