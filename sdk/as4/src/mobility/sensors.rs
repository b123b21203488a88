//! The sensors: Velocity State, Local Pose and Global Pose Sensors, answering from the
//! latest report of the RA 3.3 sensor behind them (which the gateway keeps polling).

use jaus::codec::Encode;
use jaus::messages as ra;
use jaus::{Address, CommandCode, JausMessage};

use super::{is, time_stamp, ServiceIds};
use crate::messages::{
    QueryGlobalPose, QueryLocalPose, QueryVelocityState, ReportGlobalPose, ReportLocalPose,
    ReportVelocityState, SetLocalPose,
};
use crate::ra33::{Frame, Ra33Side};
use crate::service::{Cx, Handled, Request, Service, ServiceId};
use crate::Message;

/// The Velocity State Sensor over an RA 3.3 Velocity State Sensor.
#[derive(Debug)]
pub struct VelocityStateSensor {
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
        Self { sensor }
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

impl Service<Ra33Side> for VelocityStateSensor {
    fn id(&self) -> ServiceId {
        ServiceIds::VELOCITY_STATE_SENSOR
    }

    fn receives(&self, code: CommandCode) -> bool {
        code == QueryVelocityState::CODE
    }

    fn handle(&mut self, cx: &mut Cx<'_, Ra33Side>, request: &Request<'_>) -> Handled {
        let Message::QueryVelocityState(q) = request.message else {
            return Handled::NotMine;
        };
        let mut report = match cx.env.latest(self.sensor, ra::ReportVelocityState::CODE) {
            Some((_, ra::Message::ReportVelocityState(r))) => velocity_state(r),
            _ => ReportVelocityState::default(),
        };
        report.keep_present(u64::from(q.presence_vector));
        Handled::Reply(report.into())
    }
}

/// The Local Pose Sensor over an RA 3.3 Local Pose Sensor (or, for a subsystem without
/// one, over its Global Pose Sensor: [`super::derived`]), in the AS-4 local frame that
/// Set Local Pose places ([`Ra33Side::frame`]).
#[derive(Debug)]
pub struct LocalPoseSensor {
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
        Self {
            sensor: Some(sensor),
        }
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
        Self { sensor: None }
    }

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

impl Service<Ra33Side> for LocalPoseSensor {
    fn id(&self) -> ServiceId {
        ServiceIds::LOCAL_POSE_SENSOR
    }

    fn receives(&self, code: CommandCode) -> bool {
        is(code, &[QueryLocalPose::CODE, SetLocalPose::CODE])
    }

    fn needs_ready(&self, code: CommandCode) -> bool {
        // Setting the pose is the controller's in any state, not a motion command.
        code != SetLocalPose::CODE
    }

    fn handle(&mut self, cx: &mut Cx<'_, Ra33Side>, request: &Request<'_>) -> Handled {
        match request.message {
            Message::QueryLocalPose(q) => {
                let mut report = self
                    .current(cx.env)
                    .map(|r| local_pose(&r, &cx.env.frame))
                    .unwrap_or_default();
                report.keep_present(u64::from(q.presence_vector));
                Handled::Reply(report.into())
            }
            Message::SetLocalPose(s) => {
                let Some(now) = self.current(cx.env) else {
                    return Handled::Refused(if self.sensor.is_some() {
                        "no pose from the RA 3.3 local pose sensor yet".into()
                    } else {
                        "no global position from the RA 3.3 global pose sensor yet".into()
                    });
                };
                let (Some(x), Some(y), Some(yaw)) = (now.x, now.y, now.yaw) else {
                    return Handled::Refused(
                        "the RA 3.3 local pose sensor reports no position or yaw".into(),
                    );
                };
                // Fields left out keep their current AS-4 value.
                let here = local_pose(&now, &cx.env.frame);
                let ax = s.x.or(here.x).unwrap_or(0.0);
                let ay = s.y.or(here.y).unwrap_or(0.0);
                let ayaw = s.yaw.or(here.yaw).unwrap_or(0.0);
                cx.env.frame = Frame::placing(x, y, yaw, ax, ay, ayaw);
                tracing::info!(x = ax, y = ay, yaw = ayaw, "AS-4 local pose set");
                Handled::Done
            }
            _ => Handled::NotMine,
        }
    }
}

/// The Global Pose Sensor over an RA 3.3 Global Pose Sensor (Set Global Pose is not
/// offered: an RA 3.3 pose sensor cannot be set).
#[derive(Debug)]
pub struct GlobalPoseSensor {
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
        Self { sensor }
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

impl Service<Ra33Side> for GlobalPoseSensor {
    fn id(&self) -> ServiceId {
        ServiceIds::GLOBAL_POSE_SENSOR
    }

    fn receives(&self, code: CommandCode) -> bool {
        code == QueryGlobalPose::CODE
    }

    fn handle(&mut self, cx: &mut Cx<'_, Ra33Side>, request: &Request<'_>) -> Handled {
        let Message::QueryGlobalPose(q) = request.message else {
            return Handled::NotMine;
        };
        let mut report = match cx.env.latest(self.sensor, ra::ReportGlobalPose::CODE) {
            Some((_, ra::Message::ReportGlobalPose(r))) => global_pose(r),
            _ => ReportGlobalPose::default(),
        };
        report.keep_present(u64::from(q.presence_vector));
        Handled::Reply(report.into())
    }
}
