//! The sensors: Velocity State, Local Pose and Global Pose Sensors, answering from the
//! latest report of the RA 3.3 sensor behind them (which the gateway keeps polling).

use jaus::codec::Encode;
use jaus::messages as ra;
use jaus::{Address, JausMessage};

use super::{time_stamp, ServiceIds};
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::transport::event::Receive;
use crate::messages::services::{global_pose_sensor, local_pose_sensor, velocity_state_sensor};
use crate::messages::{
    QueryGlobalPose, QueryLocalPose, QueryVelocityState, ReportGlobalPose, ReportLocalPose,
    ReportVelocityState, SetLocalPose,
};
use crate::ra33::{Frame, Ra33Side};

machined!(
    VelocityState,
    velocity_state_sensor,
    ServiceIds::VELOCITY_STATE_SENSOR,
    events
);
machined!(
    LocalPose,
    local_pose_sensor,
    ServiceIds::LOCAL_POSE_SENSOR,
    access_control
);
machined!(
    GlobalPose,
    global_pose_sensor,
    ServiceIds::GLOBAL_POSE_SENSOR,
    access_control
);

/// The Velocity State Sensor over an RA 3.3 Velocity State Sensor.
pub type VelocityStateSensor = OnMachines<VelocityState>;

/// The Velocity State Sensor's data: the RA 3.3 sensor it answers from.
#[derive(Debug)]
pub struct VelocityState {
    sensor: Address,
}

impl VelocityStateSensor {
    /// The service over the RA 3.3 sensor at `sensor`; `side` starts polling it.
    pub fn new(side: &mut Ra33Side, now: std::time::Instant, sensor: Address) -> Self {
        side.keep_polling(
            now,
            sensor,
            ra::QueryVelocityState {
                presence_vector: 0x01FF,
            },
        );
        OnMachines::from_impl(VelocityState { sensor })
    }
}

/// The AS-4 report of an RA 3.3 one: the same fields in the same units.
pub fn velocity_state(r: &ra::ReportVelocityState) -> ReportVelocityState {
    ReportVelocityState {
        velocity_x: r.velocity_x,
        velocity_y: r.velocity_y,
        velocity_z: r.velocity_z,
        velocity_rms: r.velocity_rms,
        roll_rate: r.roll_rate,
        pitch_rate: r.pitch_rate,
        yaw_rate: r.yaw_rate,
        rate_rms: r.rate_rms,
        time_stamp: r.time_stamp.as_ref().map(time_stamp),
    }
}

impl velocity_state_sensor::VelocityStateSensor for On<'_, VelocityState> {
    fn send_report_velocity_state(&mut self, msg: &QueryVelocityState, transport: &Receive) {
        let mut report = match self
            .env
            .latest(self.svc.sensor, ra::ReportVelocityState::CODE)
        {
            Some((_, ra::Message::ReportVelocityState(r))) => velocity_state(r),
            _ => ReportVelocityState::default(),
        };
        report.keep_present(u64::from(msg.presence_vector));
        self.reply(transport, report);
    }
}

/// The Local Pose Sensor over an RA 3.3 Local Pose Sensor (or, for a subsystem without
/// one, over its Global Pose Sensor: [`super::derived`]), in the AS-4 local frame that
/// Set Local Pose places ([`Ra33Side::frame`]).
pub type LocalPoseSensor = OnMachines<LocalPose>;

/// The Local Pose Sensor's data: the RA 3.3 sensor it answers from.
#[derive(Debug)]
pub struct LocalPose {
    /// The RA 3.3 Local Pose Sensor; `None`: the pose comes from the global one.
    sensor: Option<Address>,
}

impl LocalPoseSensor {
    /// The service over the RA 3.3 sensor at `sensor`; `side` starts polling it.
    pub fn new(side: &mut Ra33Side, now: std::time::Instant, sensor: Address) -> Self {
        side.keep_polling(
            now,
            sensor,
            ra::QueryLocalPose {
                presence_vector: 0x01FF,
            },
        );
        OnMachines::from_impl(LocalPose {
            sensor: Some(sensor),
        })
    }

    /// The service over the RA 3.3 Global Pose Sensor at `sensor`, in the local frame
    /// placed at its first global position ([`super::derived::local_pose`]); `side`
    /// starts polling it.
    pub fn over_global(side: &mut Ra33Side, now: std::time::Instant, sensor: Address) -> Self {
        side.keep_polling(
            now,
            sensor,
            ra::QueryGlobalPose {
                presence_vector: 0x01FF,
            },
        );
        OnMachines::from_impl(LocalPose { sensor: None })
    }
}

impl LocalPose {
    fn current(&self, side: &Ra33Side) -> Option<ra::ReportLocalPose> {
        let Some(sensor) = self.sensor else {
            return super::derived::local_pose(side);
        };
        match side.latest(sensor, ra::ReportLocalPose::CODE) {
            Some((_, ra::Message::ReportLocalPose(r))) => Some(r.clone()),
            _ => None,
        }
    }
}

/// The AS-4 report of an RA 3.3 one, its position and yaw moved into the AS-4 frame.
pub fn local_pose(r: &ra::ReportLocalPose, frame: &Frame) -> ReportLocalPose {
    let (x, y) = match (r.x, r.y) {
        (Some(x), Some(y)) => {
            let (ax, ay) = frame.to_as4(x, y);
            (Some(ax), Some(ay))
        }
        _ => (None, None),
    };
    ReportLocalPose {
        x,
        y,
        z: r.z,
        position_rms: r.position_rms,
        roll: r.roll,
        pitch: r.pitch,
        yaw: r.yaw.map(|y| frame.yaw_to_as4(y)),
        attitude_rms: r.attitude_rms,
        time_stamp: r.time_stamp.as_ref().map(time_stamp),
    }
}

impl local_pose_sensor::LocalPoseSensor for On<'_, LocalPose> {
    fn send_report_local_pose(&mut self, msg: &QueryLocalPose, transport: &Receive) {
        let mut report = self
            .svc
            .current(self.env)
            .map(|r| local_pose(&r, &self.env.frame))
            .unwrap_or_default();
        report.keep_present(u64::from(msg.presence_vector));
        self.reply(transport, report);
    }

    fn update_local_pose(&mut self, msg: &SetLocalPose) {
        let Some(now) = self.svc.current(self.env) else {
            let why = if self.svc.sensor.is_some() {
                "no pose from the RA 3.3 local pose sensor yet"
            } else {
                "no global position from the RA 3.3 global pose sensor yet"
            };
            return self.refuse(why);
        };
        let (Some(x), Some(y), Some(yaw)) = (now.x, now.y, now.yaw) else {
            return self.refuse("the RA 3.3 local pose sensor reports no position or yaw");
        };
        // Fields left out keep their current AS-4 value.
        let here = local_pose(&now, &self.env.frame);
        let ax = msg.x.or(here.x).unwrap_or(0.0);
        let ay = msg.y.or(here.y).unwrap_or(0.0);
        let ayaw = msg.yaw.or(here.yaw).unwrap_or(0.0);
        self.env.frame = Frame::placing(x, y, yaw, ax, ay, ayaw);
        tracing::info!(x = ax, y = ay, yaw = ayaw, "AS-4 local pose set");
    }
}

/// The Global Pose Sensor over an RA 3.3 Global Pose Sensor (Set Global Pose is not
/// offered: an RA 3.3 pose sensor cannot be set).
pub type GlobalPoseSensor = OnMachines<GlobalPose>;

/// The Global Pose Sensor's data: the RA 3.3 sensor it answers from.
#[derive(Debug)]
pub struct GlobalPose {
    sensor: Address,
}

impl GlobalPoseSensor {
    /// The service over the RA 3.3 sensor at `sensor`; `side` starts polling it.
    pub fn new(side: &mut Ra33Side, now: std::time::Instant, sensor: Address) -> Self {
        side.keep_polling(
            now,
            sensor,
            ra::QueryGlobalPose {
                presence_vector: 0x01FF,
            },
        );
        OnMachines::from_impl(GlobalPose { sensor })
    }
}

/// The AS-4 report of an RA 3.3 one (RA 3.3's elevation is AS-4's altitude).
pub fn global_pose(r: &ra::ReportGlobalPose) -> ReportGlobalPose {
    ReportGlobalPose {
        latitude: r.latitude,
        longitude: r.longitude,
        altitude: r.elevation,
        position_rms: r.position_rms,
        roll: r.roll,
        pitch: r.pitch,
        yaw: r.yaw,
        attitude_rms: r.attitude_rms,
        time_stamp: r.time_stamp.as_ref().map(time_stamp),
    }
}

impl global_pose_sensor::GlobalPoseSensor for On<'_, GlobalPose> {
    fn send_report_global_pose(&mut self, msg: &QueryGlobalPose, transport: &Receive) {
        let mut report = match self.env.latest(self.svc.sensor, ra::ReportGlobalPose::CODE) {
            Some((_, ra::Message::ReportGlobalPose(r))) => global_pose(r),
            _ => ReportGlobalPose::default(),
        };
        report.keep_present(u64::from(msg.presence_vector));
        self.reply(transport, report);
    }
}
