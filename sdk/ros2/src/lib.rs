//! A ROS 2 robot on a JAUS network, with no ROS install.
//!
//! The crate joins a DDS domain as a ROS 2 node (through `ros2-client` on RustDDS, pure
//! Rust) and hosts the SDK's stock JAUS components over the robot's ROS 2 topics:
//!
//! | ROS 2 | JAUS |
//! | --- | --- |
//! | `cmd_vel` (`geometry_msgs/Twist`), published | Primitive Driver (33): Set Wrench Effort |
//! | `odom` (`nav_msgs/Odometry`), read | Local Pose Sensor (41), Velocity State Sensor (42) |
//! | `fix` (`sensor_msgs/NavSatFix`), read | Global Pose Sensor (38) |
//! | `scan` (`sensor_msgs/LaserScan`), read (`sensors.range`) | Range Sensor (50): Query Relative Object Position |
//! | `image_raw` (`sensor_msgs/Image`) or `image_raw/compressed` (PNG), read (`sensors.visual`) | Visual Sensor (37): Query Image |
//!
//! A watchdog publishes a zero twist and records a [`WatchdogEvent`] when the JAUS side
//! stops the robot (its controller released control or vanished, Standby, Emergency,
//! a command not refreshed) and when `odom` has been silent longer than
//! [`Ros2Config::watchdog_ms`]. Units and frames: [`convert`]; the whole mapping, the
//! configuration and the measured latency: `docs/ros2.md`.
//!
//! The other direction is [`vehicle`] mode ([`vehicle_node`]): a JAUS vehicle on the
//! network (the SDK's or OpenJAUS 3.3's) published as `odom`, `fix` and `jaus/status`,
//! driven by `cmd_vel` (Set Wrench Effort under control, with a watchdog) and
//! `goal_pose` (a waypoint of its Local or Global Waypoint Driver).
//!
//! ```no_run
//! use std::time::Instant;
//! use jaus::net::NodeConfig;
//!
//! let config = jaus_ros2::Ros2Config::default();
//! let node_config = NodeConfig { subsystem: 5, node: 1, ..NodeConfig::default() };
//! let (mut node, link) = jaus_ros2::robot_node(&config, node_config, Instant::now())?;
//! // Run `node` with jaus::net::udp::run_on(&mut node, &socket, &stop, None, |_| {});
//! // `link.stats()` and `link.events()` tell what the ROS 2 side did.
//! # let _ = (&mut node, link);
//! # Ok::<(), jaus_ros2::Ros2Error>(())
//! ```

pub mod bridge;
pub mod config;
pub mod convert;
mod error;
pub mod msg;
pub mod robot;
pub mod sensors;
mod state;
pub mod vehicle;

pub use bridge::{dds_topic_name, BridgeStats, OdomSample, Ros2Link, WatchdogEvent};
pub use config::{
    CameraConfig, EffortMapping, Frames, OdomAxes, Qos, Reliability, Ros2Config, Sensors, Topics,
    VehicleConfig,
};
pub use error::Ros2Error;
pub use robot::{ids, robot_components, robot_node, robot_parts};
pub use sensors::SensorError;
pub use vehicle::{vehicle_node, VehicleEvent, VehicleLink, VehicleStats};
