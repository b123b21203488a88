//! The pan-tilt services (AS6057A v2.0) over the pan/tilt mount of a camera of the RA 3.3
//! Visual Sensor (Part 1 §5.5, id 37): the Pan Tilt Specification Service, the Pan Tilt
//! Joint Position Sensor and the Pan Tilt Joint Position Driver.
//!
//! RA 3.3 gives a camera's orientation as the direction cosines of its axes (Report
//! Camera Pose) and commands it in percent of each axis's range (Set Camera Pose); it has
//! no message giving that range. The mount's limits are therefore the gateway's
//! configuration ([`PanTiltMount`], `GatewayConfig::pan_tilt`): without them no pan-tilt
//! service is offered. Joint 1 is the pan (about the platform's z axis, down: positive
//! turns the lens to the right), joint 2 the tilt (positive raises the lens), both in
//! radians, as the RA 3.3 Visual Sensor's frame has them:
//!
//! * pan = atan2(z·y, z·x) and tilt = atan2(−z·z, √(z·x² + z·y²)) of the lens axis z
//!   (Report Camera Pose's `z_camera_axis_direction_cosine_*`, polled);
//! * Set Pan Tilt Joint Positions → Set Camera Pose in position mode, Y angular (pan) =
//!   pan / pan limit × 100 %, X angular (tilt) = tilt / tilt limit × 100 %.
//!
//! Set Camera Pose is an RA 3.3 command: the Visual Sensor takes it only from the
//! component controlling it. The gateway asks for RA 3.3 control of the Visual Sensor
//! when the AS-4 client first commands the mount (not before: Still Image and Digital
//! Video only query it), sends the command once control is granted, and gives control
//! back when the AS-4 client's control ends, as for the other drivers.
//!
//! Not offered: the joint velocity driver and sensor and the motion profile service. The
//! RA 3.3 camera's rate mode would carry rates, but the stock Visual Sensor refuses it
//! (its mount takes positions and reaches them at once), and RA 3.3 reports no speed or
//! acceleration limits a client could read or set.

use jaus::messages as ra;
use jaus::{Address, JausMessage};

use super::ServiceIds;
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::transport::event::Receive;
use crate::messages::services::{
    pan_tilt_joint_position_driver as position_driver,
    pan_tilt_joint_position_sensor as position_sensor,
    pan_tilt_specification_service as specification,
};
use crate::messages::{
    QueryPanTiltSpecifications, ReportCommandedPanTiltJointPositions, ReportPanTiltJointPositions,
    ReportPanTiltSpecifications, SetPanTiltJointPositions,
};
use crate::ra33::{Ra33Control, Ra33Side};
use crate::service::{Cx, Service};

/// The largest angle the AS-4 joint position fields carry, rad (8π).
const ANGLE_MAX: f64 = 8.0 * std::f64::consts::PI;

/// The largest speed the AS-4 speed fields carry, rad/s (10π): what Report Pan Tilt
/// Specifications gives as a joint's speed limit, RA 3.3 giving none.
pub const SPEED_MAX: f64 = 10.0 * std::f64::consts::PI;

/// How far beyond a limit a commanded angle may be and still be taken (the fields'
/// rounding), rad.
const LIMIT_SLACK: f64 = 1e-6;

/// Report Camera Pose's presence bits asked for: the origin (1-3) and the direction
/// cosines of the X (4-6) and Z (7-9) axes.
const POSE_FIELDS: u16 = 0b11_1111_1110;

/// A camera's pan/tilt mount, as the gateway is told it (RA 3.3 does not say it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PanTiltMount {
    /// The camera of the RA 3.3 Visual Sensor on the mount (from 1).
    pub camera_id: u8,
    /// The mount pans ±this far, rad (the RA 3.3 pan axis's 100 %).
    pub pan_limit: f64,
    /// The mount tilts ±this far, rad (the RA 3.3 tilt axis's 100 %).
    pub tilt_limit: f64,
}

impl PanTiltMount {
    /// Camera `camera_id` panning ±`pan_limit` and tilting ±`tilt_limit` (rad).
    pub fn new(camera_id: u8, pan_limit: f64, tilt_limit: f64) -> Self {
        Self {
            camera_id,
            pan_limit,
            tilt_limit,
        }
    }

    /// The RA 3.3 Set Camera Pose (position mode) turning the mount to `pan` and `tilt`
    /// (rad), or why not (naming the message, the field and the limit): a value not
    /// finite or beyond the mount's limits.
    pub fn command(&self, pan: f64, tilt: f64) -> Result<ra::SetCameraPose, String> {
        let percent = |field: &str, joint: &str, v: f64, limit: f64| {
            if !v.is_finite() {
                return Err(format!(
                    "Set Pan Tilt Joint Positions: {field} ({joint}) is not finite"
                ));
            }
            if v.abs() > limit + LIMIT_SLACK {
                return Err(format!(
                    "Set Pan Tilt Joint Positions: {field} ({joint}) {v:.4} rad ({:.2}°) beyond the mount's limits ±{limit:.4} rad (±{:.2}°)",
                    v.to_degrees(),
                    limit.to_degrees()
                ));
            }
            // A fixed axis (limit 0) is left as it is.
            Ok((limit > 0.0).then(|| (v / limit * 100.0).clamp(-100.0, 100.0)))
        };
        let y_angular = percent("joint1_position", "pan", pan, self.pan_limit)?;
        let x_angular = percent("joint2_position", "tilt", tilt, self.tilt_limit)?;
        Ok(ra::SetCameraPose {
            camera_id: self.camera_id,
            mode: ra::CameraPoseMode::default(),
            x_linear_position_or_rate: None,
            y_linear_position_or_rate: None,
            z_linear_position_or_rate: None,
            x_angular_position_or_rate: x_angular,
            y_angular_position_or_rate: y_angular,
            z_angular_position_or_rate: None,
        })
    }

    /// The RA 3.3 query polled for the mount's camera's pose.
    pub fn query(&self) -> ra::QueryCameraPose {
        ra::QueryCameraPose {
            presence_vector: POSE_FIELDS,
            camera_id: self.camera_id,
        }
    }
}

/// The pan and tilt (rad) of a camera whose lens axis has direction cosines `z` in the
/// platform frame (x forward, y right, z down).
pub fn pan_tilt_of(z: [f64; 3]) -> (f64, f64) {
    let [x, y, z] = z;
    (y.atan2(x), (-z).atan2(x.hypot(y)))
}

/// The mount behind a pan-tilt service: the RA 3.3 Visual Sensor and what the gateway
/// was told of the mount.
#[derive(Debug, Clone, Copy)]
pub struct Mount {
    sensor: Address,
    spec: PanTiltMount,
}

impl Mount {
    /// The latest Report Camera Pose of the mount's camera, or why there is none.
    fn pose<'e>(&self, env: &'e Ra33Side) -> Result<&'e ra::ReportCameraPose, String> {
        match env.latest(self.sensor, ra::ReportCameraPose::CODE) {
            Some((_, ra::Message::ReportCameraPose(p))) if p.camera_id == self.spec.camera_id => {
                Ok(p)
            }
            Some((_, ra::Message::ReportCameraPose(p))) => Err(format!(
                "Report Camera Pose from the RA 3.3 visual sensor {} is of camera {}, not camera {}",
                self.sensor, p.camera_id, self.spec.camera_id
            )),
            _ => Err(format!(
                "no Report Camera Pose of camera {} from the RA 3.3 visual sensor {} yet",
                self.spec.camera_id, self.sensor
            )),
        }
    }

    /// The measured pan and tilt (rad), or why there are none.
    pub fn measured(&self, env: &Ra33Side) -> Result<(f64, f64), String> {
        let p = self.pose(env)?;
        match (
            p.z_camera_axis_direction_cosine_x,
            p.z_camera_axis_direction_cosine_y,
            p.z_camera_axis_direction_cosine_z,
        ) {
            (Some(x), Some(y), Some(z)) if [x, y, z].iter().all(|v| v.is_finite()) => {
                Ok(pan_tilt_of([x, y, z]))
            }
            _ => Err(format!(
                "Report Camera Pose of camera {} from the RA 3.3 visual sensor {} lacks z_camera_axis_direction_cosine_x/y/z",
                self.spec.camera_id, self.sensor
            )),
        }
    }
}

/// The pan-tilt services over camera `mount` of the RA 3.3 Visual Sensor at `sensor`
/// (just found); `env` starts polling the camera's pose.
pub fn services(
    env: &mut Ra33Side,
    now: std::time::Instant,
    sensor: Address,
    mount: PanTiltMount,
) -> Vec<Box<dyn Service<Ra33Side>>> {
    env.keep_polling(now, sensor, mount.query());
    let m = Mount {
        sensor,
        spec: mount,
    };
    vec![
        Box::new(PanTiltSpecificationService::new(m)),
        Box::new(PanTiltJointPositionSensor::new(m)),
        Box::new(PanTiltJointPositionDriver::new(m)),
    ]
}

machined!(
    Specification,
    pan_tilt_specification_service,
    ServiceIds::PAN_TILT_SPECIFICATION,
    events
);
machined!(
    Positions,
    pan_tilt_joint_position_sensor,
    ServiceIds::PAN_TILT_JOINT_POSITION_SENSOR,
    events
);
machined!(
    Commanded,
    pan_tilt_joint_position_driver,
    ServiceIds::PAN_TILT_JOINT_POSITION_DRIVER,
    management {
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            self.flush(cx.env);
        }
    }
);

/// The Pan Tilt Specification Service over a camera's mount.
pub type PanTiltSpecificationService = OnMachines<Specification>;

/// The Pan Tilt Specification Service's data: the mount.
#[derive(Debug)]
pub struct Specification {
    mount: Mount,
}

impl PanTiltSpecificationService {
    /// The service over `mount` (whose pose the gateway polls).
    pub fn new(mount: Mount) -> Self {
        OnMachines::from_impl(Specification { mount })
    }
}

impl specification::PanTiltSpecificationService for On<'_, Specification> {
    fn send_report_pan_tilt_specifications(
        &mut self,
        msg: &QueryPanTiltSpecifications,
        transport: &Receive,
    ) {
        let m = self.svc.mount;
        let want = |bit: u8| msg.presence_vector & (1 << bit) != 0;
        // The mount's origin is the camera's (Report Camera Pose); its orientation at
        // zero pan and tilt RA 3.3 does not give: the quaternion is left out.
        let origin = m.pose(self.env).ok().map(|p| {
            [p.x_camera_origin, p.y_camera_origin, p.z_camera_origin]
                .map(|v| v.filter(|v| v.is_finite()).map(|v| v.clamp(-30.0, 30.0)))
        });
        let [ox, oy, oz] = origin.unwrap_or([None; 3]);
        let limit = |l: f64| l.clamp(0.0, ANGLE_MAX);
        let report = ReportPanTiltSpecifications {
            origin_x: ox.filter(|_| want(0)),
            origin_y: oy.filter(|_| want(1)),
            origin_z: oz.filter(|_| want(2)),
            quaternion_d: None,
            quaternion_a: None,
            quaternion_b: None,
            quaternion_c: None,
            joint1_min_value: -limit(m.spec.pan_limit),
            joint1_max_value: limit(m.spec.pan_limit),
            joint1_max_speed: SPEED_MAX,
            joint2_min_value: -limit(m.spec.tilt_limit),
            joint2_max_value: limit(m.spec.tilt_limit),
            joint2_max_speed: SPEED_MAX,
        };
        self.reply(transport, report);
    }
}

/// The Pan Tilt Joint Position Sensor over a camera's mount: the angles of the lens
/// axis of the latest RA 3.3 Report Camera Pose.
pub type PanTiltJointPositionSensor = OnMachines<Positions>;

/// The Pan Tilt Joint Position Sensor's data: the mount.
#[derive(Debug)]
pub struct Positions {
    mount: Mount,
}

impl PanTiltJointPositionSensor {
    /// The service over `mount` (whose pose the gateway polls).
    pub fn new(mount: Mount) -> Self {
        OnMachines::from_impl(Positions { mount })
    }
}

impl position_sensor::PanTiltJointPositionSensor for On<'_, Positions> {
    fn send_report_pan_tilt_joint_positions(&mut self, transport: &Receive) {
        match self.svc.mount.measured(self.env) {
            Ok((pan, tilt)) => self.reply(
                transport,
                ReportPanTiltJointPositions {
                    joint1_position: pan.clamp(-ANGLE_MAX, ANGLE_MAX),
                    joint2_position: tilt.clamp(-ANGLE_MAX, ANGLE_MAX),
                },
            ),
            Err(why) => self.refuse(why),
        }
    }
}

/// The Pan Tilt Joint Position Driver over a camera's mount: the controlling client's
/// angles, checked against the mount's limits, as RA 3.3 Set Camera Pose.
pub type PanTiltJointPositionDriver = OnMachines<Commanded>;

/// The Pan Tilt Joint Position Driver's data: the mount, the last command taken and
/// the RA 3.3 command waiting for control of the Visual Sensor.
#[derive(Debug)]
pub struct Commanded {
    mount: Mount,
    commanded: Option<SetPanTiltJointPositions>,
    pending: Option<ra::SetCameraPose>,
}

impl PanTiltJointPositionDriver {
    /// The service over `mount`.
    pub fn new(mount: Mount) -> Self {
        OnMachines::from_impl(Commanded {
            mount,
            commanded: None,
            pending: None,
        })
    }
}

impl Commanded {
    /// Sends the waiting command once RA 3.3 control of the Visual Sensor is held, then
    /// asks for the camera's pose; drops it when the AS-4 client's control has ended.
    fn flush(&mut self, env: &mut Ra33Side) {
        if !env.controlled() {
            self.pending = None;
            return;
        }
        let sensor = self.mount.sensor;
        if env.control_of(sensor) != Ra33Control::Granted {
            return;
        }
        if let Some(c) = self.pending.take() {
            env.send(sensor, c);
            env.send(sensor, self.mount.spec.query());
        }
    }
}

impl position_driver::PanTiltJointPositionDriver for On<'_, Commanded> {
    fn pan_tilt_motion_profile_exists(&self) -> bool {
        // The joints are the configured mount's.
        true
    }

    fn send_report_commanded_pan_tilt_joint_positions(&mut self, transport: &Receive) {
        // Before any command, what the mount holds.
        let (pan, tilt) = match &self.svc.commanded {
            Some(c) => (c.joint1_position, c.joint2_position),
            None => match self.svc.mount.measured(self.env) {
                Ok(m) => m,
                Err(why) => return self.refuse(why),
            },
        };
        self.reply(
            transport,
            ReportCommandedPanTiltJointPositions {
                joint1_position: pan.clamp(-ANGLE_MAX, ANGLE_MAX),
                joint2_position: tilt.clamp(-ANGLE_MAX, ANGLE_MAX),
            },
        );
    }

    fn set_pan_tilt_joint_positions(&mut self, msg: &SetPanTiltJointPositions) {
        let command = match self
            .svc
            .mount
            .spec
            .command(msg.joint1_position, msg.joint2_position)
        {
            Ok(c) => c,
            Err(why) => return self.refuse(why),
        };
        self.svc.commanded = Some(msg.clone());
        self.svc.pending = Some(command);
        self.env.ensure_control(self.svc.mount.sensor);
        self.svc.flush(self.env);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_come_back_from_the_lens_axis() {
        for (pan, tilt) in [(0.0, 0.0), (0.5, -0.2), (-1.5, 0.5), (1.57, -0.52)] {
            let (sp, cp) = f64::sin_cos(pan);
            let (st, ct) = f64::sin_cos(tilt);
            // The stock Visual Sensor's lens axis (`CameraSettings::axes`).
            let (p, t) = pan_tilt_of([ct * cp, ct * sp, -st]);
            assert!((p - pan).abs() < 1e-12 && (t - tilt).abs() < 1e-12);
        }
    }

    #[test]
    fn commands_are_percent_of_the_limits_and_checked() {
        let m = PanTiltMount::new(1, std::f64::consts::FRAC_PI_2, 30f64.to_radians());
        let c = m
            .command(30f64.to_radians(), -10f64.to_radians())
            .expect("within the limits");
        let pan = c.y_angular_position_or_rate.expect("pan");
        let tilt = c.x_angular_position_or_rate.expect("tilt");
        assert!((pan - 100.0 / 3.0).abs() < 1e-9, "{pan}");
        assert!((tilt + 100.0 / 3.0).abs() < 1e-9, "{tilt}");
        assert_eq!(c.mode, ra::CameraPoseMode::default());
        let e = m.command(0.0, 40f64.to_radians()).unwrap_err();
        assert!(e.contains("joint2_position (tilt)"), "{e}");
        let e = m.command(f64::NAN, 0.0).unwrap_err();
        assert!(e.contains("joint1_position (pan) is not finite"), "{e}");
        // A fixed axis: only zero, and left out of the command.
        let fixed = PanTiltMount::new(1, 1.0, 0.0);
        assert!(fixed.command(0.5, 0.1).is_err());
        let c = fixed.command(0.5, 0.0).expect("tilt zero");
        assert_eq!(c.x_angular_position_or_rate, None);
    }
}
