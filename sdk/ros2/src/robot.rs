//! The JAUS side: the SDK's stock Primitive Driver, Local Pose, Velocity State and
//! Global Pose Sensors, and the Range and Visual Sensors ([`crate::sensors`]), over
//! hardware traits implemented on the ROS 2 topics, hosted on one JAUS node.

use std::time::{Duration, Instant};

use jaus::component::{Config, CoreState, Endpoint, Refused, StopReason};
use jaus::components::primitive_driver::{self as pd, PrimitiveDriver};
use jaus::components::{
    global_pose_sensor, local_pose_sensor, range_sensor, velocity_state_sensor, visual_sensor,
};
use jaus::messages::{
    QueryDiscreteDevices, QueryWrenchEffort, ReportDiscreteDevices, ReportWrenchEffort,
    SetDiscreteDevices, SetWrenchEffort,
};
use jaus::net::{Node, NodeConfig};
use jaus::stock::drivers::{PrimitiveConfig, StockPrimitiveDriver};
use jaus::stock::environment::camera::{StockVisualSensor, VisualConfig};
use jaus::stock::environment::range::{RangeConfig, StockRangeSensor};
use jaus::stock::hardware::{
    Actuators, GlobalPose, GlobalPoseSource, LocalPose, LocalPoseSource, VelocitySource,
    VelocityState, Wrench,
};
use jaus::stock::sensors::{StockGlobalPoseSensor, StockLocalPoseSensor, StockVelocityStateSensor};
use jaus::Address;

use crate::bridge::Ros2Link;
use crate::config::{EffortMapping, Ros2Config};
use crate::convert::twist_of;
use crate::error::Ros2Error;
use crate::sensors::{RosCamera, ScanSource};
use crate::state::{lock, OdomSample, Tap, WatchdogEvent};

/// A fix older than this is no fix (a GPS publishes at 1..20 Hz).
const FIX_MAX_AGE: Duration = Duration::from_secs(2);

/// The component ids and instance of the components a ROS 2 robot node hosts.
pub mod ids {
    use jaus::components::*;

    /// Primitive Driver (33).
    pub const PRIMITIVE_DRIVER: u8 = primitive_driver::ID;
    /// Global Pose Sensor (38).
    pub const GLOBAL_POSE_SENSOR: u8 = global_pose_sensor::ID;
    /// Local Pose Sensor (41).
    pub const LOCAL_POSE_SENSOR: u8 = local_pose_sensor::ID;
    /// Velocity State Sensor (42).
    pub const VELOCITY_STATE_SENSOR: u8 = velocity_state_sensor::ID;
    /// Visual Sensor (37), with `sensors.visual`.
    pub const VISUAL_SENSOR: u8 = visual_sensor::ID;
    /// Range Sensor (50), with `sensors.range`.
    pub const RANGE_SENSOR: u8 = range_sensor::ID;
    /// The instance of each.
    pub const INSTANCE: u8 = 1;
}

/// The Primitive Driver's actuators: `cmd_vel`.
#[derive(Debug)]
pub struct CmdVelActuators {
    tap: Tap,
    mapping: EffortMapping,
}

impl Actuators for CmdVelActuators {
    fn apply(&mut self, _now: Instant, effort: &Wrench) {
        self.tap.command(twist_of(effort, &self.mapping));
    }
}

/// Local pose and velocity from `odom`; none while the ROS side is silent.
#[derive(Debug)]
pub struct OdomSource {
    tap: Tap,
}

impl OdomSource {
    fn fresh(&self) -> Option<OdomSample> {
        let s = lock(&self.tap.shared);
        if s.silent {
            None
        } else {
            s.odom
        }
    }
}

impl LocalPoseSource for OdomSource {
    fn local_pose(&mut self, _now: Instant) -> Option<LocalPose> {
        self.fresh().map(|o| o.pose)
    }
}

impl VelocitySource for OdomSource {
    fn velocity(&mut self, _now: Instant) -> Option<VelocityState> {
        self.fresh().map(|o| o.velocity)
    }
}

/// Global pose from `fix` (attitude from `odom`); none without a fix in the last 2 s.
#[derive(Debug)]
pub struct FixSource {
    tap: Tap,
}

impl GlobalPoseSource for FixSource {
    fn global_pose(&mut self, now: Instant) -> Option<GlobalPose> {
        let s = lock(&self.tap.shared);
        let (mut g, at) = s.fix?;
        if now.saturating_duration_since(at) > FIX_MAX_AGE {
            return None;
        }
        if let Some(o) = s.odom.filter(|_| !s.silent) {
            g.attitude = o.pose.attitude;
        }
        Some(g)
    }
}

/// The stock Primitive Driver over [`CmdVelActuators`], which also reports each stop
/// (control lost, Standby, Emergency, ...) as a [`WatchdogEvent::JausStop`].
#[derive(Debug)]
pub struct RosPrimitiveDriver {
    inner: StockPrimitiveDriver<CmdVelActuators>,
    tap: Tap,
}

impl RosPrimitiveDriver {
    /// The stock driver, for its counters ([`StockPrimitiveDriver::watchdog_trips`]).
    pub fn stock(&self) -> &StockPrimitiveDriver<CmdVelActuators> {
        &self.inner
    }
}

impl PrimitiveDriver for RosPrimitiveDriver {
    fn stop(&mut self, ctx: &mut pd::Ctx<'_>, reason: StopReason) {
        let controller = match reason {
            StopReason::ControlLost { controller } => Some(controller),
            _ => None,
        };
        let reason_text = match reason {
            StopReason::Emergency => "emergency",
            StopReason::Standby => "standby",
            StopReason::Shutdown => "shutdown",
            StopReason::Failure => "failure",
            StopReason::ControlLost { .. } => "control lost",
        };
        tracing::info!(address = %ctx.address(), "jaus-ros2: {reason}: zero twist");
        lock(&self.tap.shared).event(WatchdogEvent::JausStop {
            at: ctx.now(),
            controller,
            reason: reason_text,
        });
        self.inner.stop(ctx, reason);
    }

    fn on_set_wrench_effort(
        &mut self,
        ctx: &mut pd::Ctx<'_>,
        msg: &SetWrenchEffort,
    ) -> Result<(), Refused> {
        self.inner.on_set_wrench_effort(ctx, msg)
    }

    fn on_set_discrete_devices(
        &mut self,
        ctx: &mut pd::Ctx<'_>,
        msg: &SetDiscreteDevices,
    ) -> Result<(), Refused> {
        self.inner.on_set_discrete_devices(ctx, msg)
    }

    fn on_query_wrench_effort(
        &mut self,
        ctx: &mut pd::Ctx<'_>,
        q: &QueryWrenchEffort,
    ) -> Result<ReportWrenchEffort, Refused> {
        self.inner.on_query_wrench_effort(ctx, q)
    }

    fn on_query_discrete_devices(
        &mut self,
        ctx: &mut pd::Ctx<'_>,
        q: &QueryDiscreteDevices,
    ) -> Result<ReportDiscreteDevices, Refused> {
        self.inner.on_query_discrete_devices(ctx, q)
    }

    fn state_changed(&mut self, ctx: &mut pd::Ctx<'_>, from: CoreState, to: CoreState) {
        self.inner.state_changed(ctx, from, to);
    }

    fn tick(&mut self, ctx: &mut pd::Ctx<'_>) {
        let trips = self.inner.watchdog_trips();
        self.inner.tick(ctx);
        if self.inner.watchdog_trips() > trips {
            lock(&self.tap.shared).event(WatchdogEvent::JausStop {
                at: ctx.now(),
                controller: None,
                reason: "command timeout",
            });
        }
    }
}

/// The component ids and names a ROS 2 robot of `config` hosts ([`robot_components`]),
/// instance [`ids::INSTANCE`] each.
pub fn robot_parts(config: &Ros2Config) -> Vec<(u8, &'static str)> {
    let mut parts = vec![
        (ids::PRIMITIVE_DRIVER, "Primitive Driver"),
        (ids::GLOBAL_POSE_SENSOR, "Global Pose Sensor"),
        (ids::LOCAL_POSE_SENSOR, "Local Pose Sensor"),
        (ids::VELOCITY_STATE_SENSOR, "Velocity State Sensor"),
    ];
    if config.sensors.range {
        parts.push((ids::RANGE_SENSOR, "Range Sensor"));
    }
    if config.sensors.visual {
        parts.push((ids::VISUAL_SENSOR, "Visual Sensor"));
    }
    parts
}

/// The components of a ROS 2 robot at `subsystem`.`node`, over `link`: Primitive
/// Driver (33), Global Pose Sensor (38), Local Pose Sensor (41), Velocity State Sensor
/// (42), and with `sensors.range` a Range Sensor (50) over `scan`, with `sensors.visual`
/// a Visual Sensor (37) over the camera ([`robot_parts`]); instance 1 each, with the
/// component settings `component`.
pub fn robot_components(
    link: &Ros2Link,
    config: &Ros2Config,
    subsystem: u8,
    node: u8,
    component: &Config,
    t0: Instant,
) -> Vec<Box<dyn Endpoint>> {
    let at = |id: u8| Address::new(subsystem, node, id, ids::INSTANCE);
    let driver = RosPrimitiveDriver {
        inner: StockPrimitiveDriver::new(
            CmdVelActuators {
                tap: link.tap(),
                mapping: config.effort,
            },
            PrimitiveConfig {
                command_timeout: config.command_timeout(),
                ..PrimitiveConfig::default()
            },
        ),
        tap: link.tap(),
    };
    let mut parts: Vec<Box<dyn Endpoint>> = vec![
        Box::new(pd::component(
            at(ids::PRIMITIVE_DRIVER),
            driver,
            component.clone(),
            t0,
        )),
        Box::new(global_pose_sensor::component(
            at(ids::GLOBAL_POSE_SENSOR),
            StockGlobalPoseSensor(FixSource { tap: link.tap() }),
            component.clone(),
            t0,
        )),
        Box::new(local_pose_sensor::component(
            at(ids::LOCAL_POSE_SENSOR),
            StockLocalPoseSensor(OdomSource { tap: link.tap() }),
            component.clone(),
            t0,
        )),
        Box::new(velocity_state_sensor::component(
            at(ids::VELOCITY_STATE_SENSOR),
            StockVelocityStateSensor(OdomSource { tap: link.tap() }),
            component.clone(),
            t0,
        )),
    ];
    let (scan_topic, camera_topic) = link.sensor_topics();
    if scan_topic.is_some() {
        parts.push(Box::new(range_sensor::component(
            at(ids::RANGE_SENSOR),
            StockRangeSensor::new(
                ScanSource::new(link.tap(), &config.sensors),
                RangeConfig::default(),
            ),
            component.clone(),
            t0,
        )));
    }
    if let Some(topic) = camera_topic {
        let camera = RosCamera::new(link.tap(), config, topic.to_string());
        parts.push(Box::new(visual_sensor::component(
            at(ids::VISUAL_SENSOR),
            StockVisualSensor::new(camera, VisualConfig::default()),
            component.clone(),
            t0,
        )));
    }
    parts
}

/// A JAUS node hosting a ROS 2 robot: starts the ROS 2 side of `config` (a ROS 2 node
/// on DDS domain `config.domain_id`) and hosts [`robot_components`] on a node of
/// `node_config`. Run the node with the SDK's transports
/// (`jaus::net::udp::run_on`); keep the [`Ros2Link`] as long as the node runs
/// (dropping it publishes a zero twist and leaves the ROS graph).
pub fn robot_node(
    config: &Ros2Config,
    node_config: NodeConfig,
    t0: Instant,
) -> Result<(Node, Ros2Link), Ros2Error> {
    let link = Ros2Link::start(config)?;
    let (ss, n) = (node_config.subsystem, node_config.node);
    let component = node_config.component.clone();
    let mut node = Node::new(node_config, t0);
    for c in robot_components(&link, config, ss, n, &component, t0) {
        node.add_boxed(c)
            .map_err(|e| Ros2Error::Jaus(e.to_string()))?;
    }
    Ok((node, link))
}
