//! The bridge's settings ([`Ros2Config`]): serde with a default for every field, so a
//! node file's `ros2:` section needs only what differs.
//!
//! ```
//! let c: jaus_ros2::Ros2Config = serde_json::from_str(
//!     r#"{"domain_id": 7, "effort": {"max_linear": 0.8}}"#,
//! ).unwrap();
//! assert_eq!(c.domain_id, 7);
//! assert_eq!(c.effort.max_angular, 1.0);
//! assert_eq!(c.topics.odom, "odom");
//! c.validate().unwrap();
//! ```

use std::time::Duration;

use serde::{Deserialize, Serialize};

use crate::error::Ros2Error;

/// Everything the bridge needs to know about the ROS 2 side.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Ros2Config {
    /// DDS domain (`ROS_DOMAIN_ID`), 0..=232.
    pub domain_id: u16,
    /// The ROS 2 node's name (`ros2 node list` shows `<namespace>/<node_name>`).
    pub node_name: String,
    /// The node's namespace; relative topic names are resolved in it.
    pub namespace: String,
    /// Topic names.
    pub topics: Topics,
    /// Frame ids the bridge expects on `odom`.
    pub frames: Frames,
    /// How the odometry frame's axes lie.
    pub odom_axes: OdomAxes,
    /// QoS of the topics the bridge publishes (`cmd_vel`).
    pub qos_commands: Qos,
    /// QoS of the topics the bridge reads (`odom`, `fix`).
    pub qos_sensors: Qos,
    /// JAUS wrench effort → `cmd_vel` scaling.
    pub effort: EffortMapping,
    /// No `odom` for this long (ms): the ROS side is silent; the bridge publishes a zero
    /// twist, holds every further command at zero and stops reporting local pose and
    /// velocity until `odom` comes back.
    pub watchdog_ms: u64,
    /// The Primitive Driver's command timeout (ms): a wrench effort not refreshed within
    /// it is replaced by brakes (a zero twist).
    pub command_timeout_ms: u64,
    /// The other direction: a JAUS vehicle in ROS 2 (`jaus ros2 --vehicle`,
    /// [`crate::vehicle`]).
    pub vehicle: VehicleConfig,
    /// Which of the robot's sensors (lidar, camera) are JAUS components, and their
    /// bounds.
    pub sensors: Sensors,
    /// The camera as the Visual Sensor presents it.
    pub camera: CameraConfig,
}

impl Default for Ros2Config {
    fn default() -> Self {
        Ros2Config {
            domain_id: 0,
            node_name: "jaus_bridge".into(),
            namespace: "/".into(),
            topics: Topics::default(),
            frames: Frames::default(),
            odom_axes: OdomAxes::default(),
            qos_commands: Qos {
                reliability: Reliability::Reliable,
                depth: 10,
            },
            qos_sensors: Qos {
                reliability: Reliability::BestEffort,
                depth: 10,
            },
            effort: EffortMapping::default(),
            watchdog_ms: 500,
            command_timeout_ms: 300,
            vehicle: VehicleConfig::default(),
            sensors: Sensors::default(),
            camera: CameraConfig::default(),
        }
    }
}

impl Ros2Config {
    /// The ROS-silence watchdog time.
    pub fn watchdog(&self) -> Duration {
        Duration::from_millis(self.watchdog_ms)
    }

    /// The Primitive Driver's command timeout.
    pub fn command_timeout(&self) -> Duration {
        Duration::from_millis(self.command_timeout_ms)
    }

    /// Checks the values a DDS participant or the mapping cannot use.
    pub fn validate(&self) -> Result<(), Ros2Error> {
        let bad = |what: String| Err(Ros2Error::Config(what));
        if self.domain_id > 232 {
            return bad(format!("domain_id {} above 232", self.domain_id));
        }
        for (name, m) in [
            ("max_linear", self.effort.max_linear),
            ("max_angular", self.effort.max_angular),
        ] {
            if !(m.is_finite() && m >= 0.0) {
                return bad(format!("effort.{name} {m} is not a finite speed ≥ 0"));
            }
        }
        for (name, q) in [
            ("qos_commands", self.qos_commands),
            ("qos_sensors", self.qos_sensors),
        ] {
            if q.depth == 0 || q.depth > 10_000 {
                return bad(format!("{name}.depth {} not in 1..=10000", q.depth));
            }
        }
        if self.watchdog_ms == 0 || self.command_timeout_ms == 0 {
            return bad("watchdog_ms and command_timeout_ms must be above 0".into());
        }
        let v = &self.vehicle;
        if !(v.rate_hz.is_finite() && v.rate_hz > 0.0 && v.rate_hz <= 100.0) {
            return bad(format!("vehicle.rate_hz {} not in (0, 100]", v.rate_hz));
        }
        if !(v.waypoint_speed.is_finite() && v.waypoint_speed > 0.0) {
            return bad(format!(
                "vehicle.waypoint_speed {} is not a speed > 0",
                v.waypoint_speed
            ));
        }
        if v.cmd_vel_timeout_ms == 0 {
            return bad("vehicle.cmd_vel_timeout_ms must be above 0".into());
        }
        if v.subsystem.is_some()
            && (self.effort.max_linear == 0.0 || self.effort.max_angular == 0.0)
        {
            return bad("vehicle mode: effort.max_linear and max_angular must be above 0".into());
        }
        for (name, t) in [
            ("cmd_vel", &self.topics.cmd_vel),
            ("odom", &self.topics.odom),
            ("fix", &self.topics.fix),
            ("status", &self.topics.status),
            ("goal_pose", &self.topics.goal_pose),
            ("scan", &self.topics.scan),
            ("image", &self.topics.image),
            ("compressed_image", &self.topics.compressed_image),
        ] {
            if t.is_empty() || t.contains("//") || t.ends_with('/') {
                return bad(format!("topics.{name} {t:?} is not a ROS 2 topic name"));
            }
        }
        let (sn, cam) = (&self.sensors, &self.camera);
        if sn.max_age_ms == 0 {
            return bad("sensors.max_age_ms must be above 0".into());
        }
        if !(1024..=MAX_IMAGE_BYTES).contains(&sn.max_image_bytes) {
            return bad(format!(
                "sensors.max_image_bytes {} not in 1024..={MAX_IMAGE_BYTES}",
                sn.max_image_bytes
            ));
        }
        for (name, v) in [("width", cam.width), ("height", cam.height)] {
            if !(1..=MAX_IMAGE_SIDE).contains(&u32::from(v)) {
                return bad(format!("camera.{name} {v} not in 1..={MAX_IMAGE_SIDE}"));
            }
        }
        if cam.frame_rate == 0 || cam.frame_rate > 255 {
            return bad(format!(
                "camera.frame_rate {} not in 1..=255",
                cam.frame_rate
            ));
        }
        if !(cam.horizontal_fov_deg.is_finite()
            && cam.horizontal_fov_deg > 0.0
            && cam.horizontal_fov_deg <= 180.0)
        {
            return bad(format!(
                "camera.horizontal_fov_deg {} not in (0, 180]",
                cam.horizontal_fov_deg
            ));
        }
        Ok(())
    }
}

/// Topic names, relative to the node's namespace unless they start with `/`; on DDS
/// each becomes `rt/<namespace>/<name>`.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Topics {
    /// `geometry_msgs/Twist` the bridge publishes.
    pub cmd_vel: String,
    /// `nav_msgs/Odometry` the bridge reads.
    pub odom: String,
    /// `sensor_msgs/NavSatFix` the bridge reads.
    pub fix: String,
    /// Vehicle mode: `std_msgs/String` the bridge publishes (the JAUS components' state
    /// and controller).
    pub status: String,
    /// Vehicle mode: `geometry_msgs/PoseStamped` the bridge reads (a goal for the
    /// vehicle's waypoint driver).
    pub goal_pose: String,
    /// `sensor_msgs/LaserScan` the bridge reads (the Range Sensor's sweeps, with
    /// [`Sensors::range`]).
    pub scan: String,
    /// `sensor_msgs/Image` the bridge reads (the Visual Sensor's frames, with
    /// [`Sensors::visual`] and not [`Sensors::compressed`]).
    pub image: String,
    /// `sensor_msgs/CompressedImage` the bridge reads instead of
    /// [`image`](Self::image) with [`Sensors::compressed`] (PNG only).
    pub compressed_image: String,
}

impl Default for Topics {
    fn default() -> Self {
        Topics {
            cmd_vel: "cmd_vel".into(),
            odom: "odom".into(),
            fix: "fix".into(),
            status: "jaus/status".into(),
            goal_pose: "goal_pose".into(),
            scan: "scan".into(),
            image: "image_raw".into(),
            compressed_image: "image_raw/compressed".into(),
        }
    }
}

/// Frame ids expected on `odom` (REP-105); an empty one accepts any. An odometry
/// message in other frames is ignored and counted
/// ([`BridgeStats::foreign_frames`](crate::BridgeStats::foreign_frames)).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Frames {
    /// The pose's frame (`header.frame_id`).
    pub odom: String,
    /// The twist's frame (`child_frame_id`).
    pub base: String,
}

impl Default for Frames {
    fn default() -> Self {
        Frames {
            odom: "odom".into(),
            base: "base_link".into(),
        }
    }
}

/// How the axes of the odometry frame lie; the robot's base frame is always REP-103's
/// x forward, y left, z up.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OdomAxes {
    /// x east, y north, z up (REP-103 for world frames; what a GPS-aligned odometry or
    /// `robot_localization` with a magnetometer gives): JAUS x north = ROS y, y east =
    /// ROS x, z down = −ROS z, yaw = π/2 − ROS yaw.
    #[default]
    Enu,
    /// Forward, left, up from where the robot started (plain wheel odometry): JAUS x =
    /// ROS x, y = −ROS y, z = −ROS z, yaw = −ROS yaw. JAUS "north" is then the robot's
    /// initial heading.
    Flu,
}

/// Vehicle mode (a JAUS vehicle in ROS 2, [`crate::vehicle`]): which vehicle, how often
/// its reports become topics, and how `cmd_vel` and `goal_pose` drive it. The topics'
/// names are [`Topics`]'; the velocity → effort scaling is [`Ros2Config::effort`]
/// (`max_linear` m/s is 100 %), the frames [`Ros2Config::frames`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct VehicleConfig {
    /// The JAUS subsystem of the vehicle (its components are found in the system tree
    /// by their component ids). `None` (the default): robot mode, not vehicle mode.
    pub subsystem: Option<u8>,
    /// Rate of the pose and velocity service connections and of `odom`, `fix`, Hz.
    pub rate_hz: f64,
    /// No `cmd_vel` for this long (ms): zero efforts are sent (the vehicle stops).
    pub cmd_vel_timeout_ms: u64,
    /// The authority the bridge asks for control with.
    pub authority: u8,
    /// Travel speed sent with a `goal_pose` waypoint, m/s.
    pub waypoint_speed: f64,
}

impl Default for VehicleConfig {
    fn default() -> Self {
        VehicleConfig {
            subsystem: None,
            rate_hz: 10.0,
            cmd_vel_timeout_ms: 500,
            authority: 10,
            waypoint_speed: 1.0,
        }
    }
}

impl VehicleConfig {
    /// The `cmd_vel` watchdog time.
    pub fn cmd_vel_timeout(&self) -> Duration {
        Duration::from_millis(self.cmd_vel_timeout_ms)
    }

    /// The period of [`rate_hz`](Self::rate_hz).
    pub fn period(&self) -> Duration {
        Duration::from_secs_f64(1.0 / self.rate_hz.clamp(0.01, 1000.0))
    }
}

/// The most a configured image may hold ([`Sensors::max_image_bytes`]): 64 MiB.
pub const MAX_IMAGE_BYTES: usize = 64 << 20;
/// The widest and tallest image taken, pixels (larger ones are dropped and counted).
pub const MAX_IMAGE_SIDE: u32 = 4096;
/// The most beams a sweep may have (a larger `LaserScan` is dropped and counted).
pub const MAX_BEAMS: usize = 4096;

/// The robot's sensors as JAUS components (robot mode). Off by default: a JAUS
/// component for a sensor the robot does not have would only refuse its queries.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Sensors {
    /// Host a Range Sensor (50) over [`Topics::scan`] (default `false`).
    pub range: bool,
    /// Host a Visual Sensor (37) over [`Topics::image`] (or
    /// [`Topics::compressed_image`]) (default `false`).
    pub visual: bool,
    /// The camera reads `sensor_msgs/CompressedImage` (format `png`) from
    /// [`Topics::compressed_image`] instead of raw images.
    pub compressed: bool,
    /// A scan or image older than this (ms) is none: the Range Sensor and the Visual
    /// Sensor refuse their queries until a new one arrives.
    pub max_age_ms: u64,
    /// Larger images (raw bytes, or a compressed file and what it decodes to) are
    /// dropped and counted, 1024..=64 MiB.
    pub max_image_bytes: usize,
}

impl Default for Sensors {
    fn default() -> Self {
        Sensors {
            range: false,
            visual: false,
            compressed: false,
            max_age_ms: 1000,
            max_image_bytes: 16 << 20,
        }
    }
}

impl Sensors {
    /// [`max_age_ms`](Self::max_age_ms).
    pub fn max_age(&self) -> Duration {
        Duration::from_millis(self.max_age_ms)
    }
}

/// The camera as the Visual Sensor (37) presents it: one fixed camera (no pan or
/// tilt) at the platform's origin. JAUS gets frames of its camera settings' size (at
/// most `width` × `height`, the default); an image of another size is resampled
/// (nearest pixel), so set these to what the topic publishes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CameraConfig {
    /// Name in Report Camera Pose (15 characters).
    pub name: String,
    /// Largest (and default) image width, pixels, 1..=4096.
    pub width: u16,
    /// Largest (and default) image height, pixels, 1..=4096.
    pub height: u16,
    /// Highest frame rate, frames/s (a faster Query Image gets the last frame again).
    pub frame_rate: u16,
    /// Horizontal field of view, degrees, (0, 180].
    pub horizontal_fov_deg: f64,
}

impl Default for CameraConfig {
    fn default() -> Self {
        CameraConfig {
            name: "ros2 camera".into(),
            width: 640,
            height: 480,
            frame_rate: 30,
            horizontal_fov_deg: 60.0,
        }
    }
}

/// DDS reliability.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Reliability {
    /// Retransmitted until acknowledged (ROS 2's default QoS profile).
    Reliable,
    /// Sent once (the sensor-data profile); a best-effort reader matches writers of
    /// either kind.
    BestEffort,
}

/// A topic's QoS: reliability and the depth of its keep-last history; volatile
/// durability (ROS 2's defaults for both profiles).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Qos {
    /// Reliability.
    pub reliability: Reliability,
    /// Samples kept per writer/reader.
    pub depth: i32,
}

/// How a JAUS wrench effort (percent of the platform's available effort) becomes a
/// velocity command: 100 % propulsive linear x is `max_linear` m/s forward, 100 %
/// propulsive rotational z is `max_angular` rad/s (JAUS z points down, so + turns right,
/// which is a negative ROS `angular.z`). A resistive (braking) effort scales its axis
/// down: 100 % brakes is a zero twist.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EffortMapping {
    /// m/s at 100 % linear effort (x, y and z alike).
    pub max_linear: f64,
    /// rad/s at 100 % rotational effort (about x, y and z alike).
    pub max_angular: f64,
}

impl Default for EffortMapping {
    fn default() -> Self {
        EffortMapping {
            max_linear: 1.0,
            max_angular: 1.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_validate_and_round_trip_through_yaml() {
        let c = Ros2Config::default();
        c.validate().unwrap();
        let y = serde_yaml::to_string(&c).unwrap();
        assert!(y.contains("reliability: best_effort"), "{y}");
        assert_eq!(serde_yaml::from_str::<Ros2Config>(&y).unwrap(), c);
        let partial: Ros2Config =
            serde_yaml::from_str("odom_axes: flu\nqos_sensors: {reliability: reliable, depth: 5}")
                .unwrap();
        assert_eq!(partial.odom_axes, OdomAxes::Flu);
        assert_eq!(partial.qos_sensors.depth, 5);
        assert_eq!(partial.watchdog(), Duration::from_millis(500));
    }

    #[test]
    fn bad_values_are_refused() {
        let mut c = Ros2Config {
            domain_id: 300,
            ..Ros2Config::default()
        };
        assert!(c.validate().is_err());
        c.domain_id = 0;
        c.effort.max_linear = f64::NAN;
        assert!(c.validate().is_err());
        c.effort.max_linear = 1.0;
        c.topics.odom = "a//b".into();
        assert!(c.validate().is_err());
        assert!(serde_yaml::from_str::<Ros2Config>("domian_id: 3").is_err());
    }

    #[test]
    fn vehicle_settings_parse_and_are_checked() {
        let c: Ros2Config =
            serde_yaml::from_str("vehicle: {subsystem: 1, rate_hz: 20}\ntopics: {status: st}")
                .unwrap();
        assert_eq!((c.vehicle.subsystem, c.vehicle.rate_hz), (Some(1), 20.0));
        assert_eq!(c.vehicle.cmd_vel_timeout(), Duration::from_millis(500));
        assert_eq!(
            (c.topics.status.as_str(), c.topics.goal_pose.as_str()),
            ("st", "goal_pose")
        );
        c.validate().unwrap();
        let mut bad = c.clone();
        bad.vehicle.rate_hz = 0.0;
        assert!(bad.validate().is_err());
        let mut bad = c.clone();
        bad.effort.max_linear = 0.0;
        assert!(bad.validate().is_err());
        bad.vehicle.subsystem = None;
        bad.validate().unwrap();
        let mut bad = c;
        bad.vehicle.cmd_vel_timeout_ms = 0;
        assert!(bad.validate().is_err());
    }

    #[test]
    fn sensor_settings_parse_and_are_checked() {
        let c = Ros2Config::default();
        assert_eq!(
            (c.topics.scan.as_str(), c.topics.image.as_str()),
            ("scan", "image_raw")
        );
        assert!(!c.sensors.range && !c.sensors.visual && !c.sensors.compressed);
        let c: Ros2Config = serde_yaml::from_str(
            "sensors: {visual: true, max_age_ms: 250}\ncamera: {width: 8, height: 6}\ntopics: {scan: front/scan}",
        )
        .unwrap();
        assert!(!c.sensors.range && c.sensors.visual);
        assert_eq!(c.sensors.max_age(), Duration::from_millis(250));
        assert_eq!(
            (c.camera.width, c.camera.height, c.camera.frame_rate),
            (8, 6, 30)
        );
        c.validate().unwrap();
        assert!(serde_yaml::from_str::<Ros2Config>("sensors: {lidar: true}").is_err());
        assert!(serde_yaml::from_str::<Ros2Config>("camera: {fov: 3}").is_err());
        for bad in [
            "camera: {width: 0}",
            "camera: {height: 5000}",
            "camera: {frame_rate: 0}",
            "camera: {horizontal_fov_deg: .nan}",
            "camera: {horizontal_fov_deg: 190}",
            "sensors: {max_age_ms: 0}",
            "sensors: {max_image_bytes: 100}",
            "topics: {image: a//b}",
        ] {
            let c: Ros2Config = serde_yaml::from_str(bad).unwrap();
            let e = c.validate().unwrap_err().to_string();
            let key = bad.split(['{', ':']).nth(2).unwrap_or_default().trim();
            assert!(e.contains(key), "{bad}: {e}");
        }
    }
}
