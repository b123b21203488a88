//! The Manipulator services (AS6057A, `urn:jaus:jss:manipulator` v2.0) over RA 3.3
//! manipulator components: what a gateway (the `gateway` module) presents of an RA 3.3
//! arm, be it the stock components of this SDK over the simulated 6-axis arm or a
//! vendor's.
//!
//! Each runs its generated machines (`defs/manipulator_services.yaml`,
//! [`crate::machined`]) as a [`Service`] over the gateway's RA 3.3
//! side, as the Mobility services do. The arm's kinematic chain is the RA 3.3 Primitive
//! Manipulator's Report Manipulator Specifications, read into the SDK's
//! [`Chain`] (the model the stock RA 3.3 drivers solve with), with the tool point of the
//! RA 3.3 End-Effector Pose Driver; the AS-4 reports are written from it.
//!
//! | AS-4 service | RA 3.3 component | messages |
//! |---|---|---|
//! | Joint Position Sensor | Joint Position Sensor | Query/Report Joint Positions (each joint tagged revolute, rad, or prismatic, m, by the chain) |
//! | Joint Velocity Sensor | Joint Velocity Sensor | Query Joint Velocity / Report Joint Velocity (rad/s or m/s) |
//! | Specification Service | Primitive Manipulator | Query/Report Manipulator Specifications (the chain: base frame, each joint's link, offset, range and speed limit) |
//! | End-Effector Pose Sensor | Joint Position Sensor + the chain | Query/Report End Effector Pose (forward kinematics of the measured joints, with the tool point) |
//! | Joint Position Driver | Joint Positions Driver | Set Joint Positions (checked against the chain: count, joint kinds) → RA 3.3 Set Joint Positions; Query/Report Commanded Joint Positions |
//! | End-Effector Pose Driver | End-Effector Pose Driver | Set End Effector Pose → RA 3.3 Set End Effector Pose (the same position and quaternion, in the vehicle frame); Query/Report Commanded End Effector Pose |
//! | Joint Force/Torque Sensor | Joint Force/Torque Sensor | Query/Report Joint Force Torques (each joint's torque, N·m, or force, N, tagged by the chain) |
//! | Joint Velocity Driver | Joint Velocities Driver | Set Joint Velocity (checked against the chain: count, joint kinds, each joint's speed limit) → RA 3.3 Set Joint Velocities, streamed; Query/Report Commanded Joint Velocity |
//! | End-Effector Velocity State Driver | End-Effector Velocity State Driver | Set End Effector Velocity State → RA 3.3 Set End Effector Velocity State (the same six rates, vehicle frame), streamed; Query/Report Commanded End Effector Velocity State |
//! | End-Effector Velocity State Sensor | Joint Position + Joint Velocity Sensors + the chain | Query/Report End Effector Velocity State (the Jacobian of the measured joints times their rates, at the tool point) |
//! | Tool Offset Service | End-Effector Pose Driver | Set Tool Offset → RA 3.3 Set Tool Point; Query/Report Tool Offset from Report Tool Point ([`tool`]) |
//! | Pan Tilt Specification Service | Visual Sensor + the configured mount ([`PanTiltMount`]) | Query/Report Pan Tilt Specifications (the mount's limits; its origin from Report Camera Pose) ([`pan_tilt`]) |
//! | Pan Tilt Joint Position Sensor | Visual Sensor | Query/Report Pan Tilt Joint Positions from Report Camera Pose's lens axis ([`pan_tilt`]) |
//! | Pan Tilt Joint Position Driver | Visual Sensor | Set Pan Tilt Joint Positions (checked against the mount's limits) → RA 3.3 Set Camera Pose, position mode, percent of the limits; Query/Report Commanded Pan Tilt Joint Positions ([`pan_tilt`]) |
//! | Joint Position List Driver | Joint Move Driver | the component's list of Set Joint Positions, from Manipulator Execute List's element → one RA 3.3 Set Joint Motion, each pose at a planned time; Query Manipulator Active Element, Query/Report Commanded Joint Positions ([`list`]) |
//! | End-Effector Pose List Driver | End-Effector Pose Driver + Joint Position Sensor + the chain | the component's list of Set End Effector Pose (each checked within reach), from Manipulator Execute List's element → one RA 3.3 Set End Effector Pose at a time, the next once the measured pose is within 1 mm and 0.01 rad; Query Manipulator Active Element, Query/Report Commanded End Effector Pose ([`pose_list`]) |
//!
//! The five drivers are one [`Group`](crate::ra33::Group): the one an AS-4 client
//! commands is resumed and the others put in standby, as two RA 3.3 drivers of one arm
//! must not both hold the Primitive Manipulator. Leaving Ready (the JSIDL's exit action
//! `stopMotion`) puts them in standby, which holds the arm where it is. The velocity
//! drivers' rates are set-points a client streams ([`velocity`]).
//!
//! Not offered (their machines are generated, `defs/manipulator_services.yaml`, for a
//! vendor to serve): the Joint Motion Profile (RA 3.3 keeps no acceleration limits a
//! client could read or set), the Actuator Force/Torque Driver and Primitive
//! Manipulator (the stock Primitive Manipulator takes efforts only from the RA 3.3
//! drivers, which hold it, and RA 3.3 has no force/torque command), the Primitive End
//! Effector (no RA 3.3 component, no simulated gripper), the Primitive Pan Tilt, the
//! pan-tilt velocity services and the Pan Tilt Motion Profile Service (the stock Visual
//! Sensor's mount takes positions only; RA 3.3 gives no speed limits, [`pan_tilt`]).

use jaus::messages as ra;
use jaus::stock::manipulator::kinematics::{Chain, JointKind};
use jaus::{Address, JausMessage};

use crate::core::generated_id;
use crate::messages::{
    FirstJoint, FirstPrismaticJoint, FirstRevoluteJoint, ForceNewtons, ForceTorque, JointPosition,
    JointPositionMetres, JointPositionRadians, JointSpecification, JointVelocity,
    JointVelocityMetresPerSecond, JointVelocityRadiansPerSecond, ManipulatorCoordinateSystem,
    PrismaticJointSpecification, ReportEndEffectorPose, ReportManipulatorSpecifications,
    RevoluteJointSpecification, TorqueNewtonMetres,
};
use crate::ra33::{Ra33Side, Targets};
use crate::service::{Service, ServiceId};

pub mod drivers;
pub mod list;
mod listing;
pub mod pan_tilt;
pub mod pose_list;
pub mod sensors;
pub mod tool;
pub mod velocity;

pub use drivers::{EndEffectorPoseDriver, JointPositionDriver};
pub use list::JointPositionListDriver;
pub use pan_tilt::{
    PanTiltJointPositionDriver, PanTiltJointPositionSensor, PanTiltMount,
    PanTiltSpecificationService,
};
pub use pose_list::EndEffectorPoseListDriver;
pub use sensors::{
    EndEffectorPoseSensor, JointForceTorqueSensor, JointPositionSensor, JointVelocitySensor,
    SpecificationService,
};
pub use tool::ToolOffsetService;
pub use velocity::{
    EndEffectorVelocityStateDriver, EndEffectorVelocityStateSensor, JointVelocityDriver,
};

/// The URIs and versions of the Manipulator services, as
/// `defs/manipulator_services.yaml` gives them.
#[derive(Debug)]
pub struct ServiceIds;

impl ServiceIds {
    /// `urn:jaus:jss:manipulator:ManipulatorJointPositionSensor`.
    pub const JOINT_POSITION_SENSOR: ServiceId = generated_id!(manipulator_joint_position_sensor);
    /// `urn:jaus:jss:manipulator:ManipulatorJointVelocitySensor`.
    pub const JOINT_VELOCITY_SENSOR: ServiceId = generated_id!(manipulator_joint_velocity_sensor);
    /// `urn:jaus:jss:manipulator:ManipulatorSpecificationService`.
    pub const SPECIFICATION: ServiceId = generated_id!(manipulator_specification_service);
    /// `urn:jaus:jss:manipulator:ManipulatorEndEffectorPoseSensor`.
    pub const END_EFFECTOR_POSE_SENSOR: ServiceId =
        generated_id!(manipulator_end_effector_pose_sensor);
    /// `urn:jaus:jss:manipulator:ManipulatorJointPositionDriver`.
    pub const JOINT_POSITION_DRIVER: ServiceId = generated_id!(manipulator_joint_position_driver);
    /// `urn:jaus:jss:manipulator:ManipulatorEndEffectorPoseDriver`.
    pub const END_EFFECTOR_POSE_DRIVER: ServiceId =
        generated_id!(manipulator_end_effector_pose_driver);
    /// `urn:jaus:jss:manipulator:ManipulatorJointForceTorqueSensor`.
    pub const JOINT_FORCE_TORQUE_SENSOR: ServiceId =
        generated_id!(manipulator_joint_force_torque_sensor);
    /// `urn:jaus:jss:manipulator:ManipulatorJointVelocityDriver`.
    pub const JOINT_VELOCITY_DRIVER: ServiceId = generated_id!(manipulator_joint_velocity_driver);
    /// `urn:jaus:jss:manipulator:ManipulatorEndEffectorVelocityStateDriver`.
    pub const END_EFFECTOR_VELOCITY_STATE_DRIVER: ServiceId =
        generated_id!(manipulator_end_effector_velocity_state_driver);
    /// `urn:jaus:jss:manipulator:ManipulatorEndEffectorVelocityStateSensor`.
    pub const END_EFFECTOR_VELOCITY_STATE_SENSOR: ServiceId =
        generated_id!(manipulator_end_effector_velocity_state_sensor);
    /// `urn:jaus:jss:manipulator:ManipulatorToolOffsetService`.
    pub const TOOL_OFFSET: ServiceId = generated_id!(manipulator_tool_offset_service);
    /// `urn:jaus:jss:manipulator:ManipulatorJointPositionListDriver`.
    pub const JOINT_POSITION_LIST_DRIVER: ServiceId =
        generated_id!(manipulator_joint_position_list_driver);
    /// `urn:jaus:jss:manipulator:ManipulatorEndEffectorPoseListDriver`.
    pub const END_EFFECTOR_POSE_LIST_DRIVER: ServiceId =
        generated_id!(manipulator_end_effector_pose_list_driver);
    /// `urn:jaus:jss:manipulator:PanTiltSpecificationService`.
    pub const PAN_TILT_SPECIFICATION: ServiceId = generated_id!(pan_tilt_specification_service);
    /// `urn:jaus:jss:manipulator:PanTiltJointPositionSensor`.
    pub const PAN_TILT_JOINT_POSITION_SENSOR: ServiceId =
        generated_id!(pan_tilt_joint_position_sensor);
    /// `urn:jaus:jss:manipulator:PanTiltJointPositionDriver`.
    pub const PAN_TILT_JOINT_POSITION_DRIVER: ServiceId =
        generated_id!(pan_tilt_joint_position_driver);
}

/// The message the elements of each list driver's list hold: the service, the message
/// the gateway's List Manager is to accept.
pub const LIST_ELEMENTS: [(ServiceId, jaus::CommandCode); 2] = [
    (
        ServiceIds::JOINT_POSITION_LIST_DRIVER,
        crate::messages::SetJointPositions::CODE,
    ),
    (
        ServiceIds::END_EFFECTOR_POSE_LIST_DRIVER,
        crate::messages::SetEndEffectorPose::CODE,
    ),
];

/// The Manipulator services for the RA 3.3 components just found (`new`, a subset of
/// `targets`, the gateway's whole set): a service is offered once the components it
/// needs are known, and polling of what it reads starts.
pub fn services(
    env: &mut Ra33Side,
    now: std::time::Instant,
    targets: &Targets,
    new: &Targets,
) -> Vec<Box<dyn Service<Ra33Side>>> {
    let mut out: Vec<Box<dyn Service<Ra33Side>>> = Vec::new();
    // Every service but the velocity sensor needs the chain: the Primitive Manipulator
    // (and, for poses, the End-Effector Pose Driver's tool point) is polled with the
    // first of them.
    let Some(pm) = targets.primitive_manipulator else {
        return out;
    };
    let arm = Arm {
        manipulator: pm,
        tool_from: targets.end_effector_pose_driver,
        joints_from: targets.joint_position_sensor,
    };
    let pm_new = new.primitive_manipulator.is_some();
    if pm_new {
        env.keep_polling(now, pm, ra::QueryManipulatorSpecifications {});
        out.push(Box::new(SpecificationService::new(arm)));
    }
    if let Some(epd) = new.end_effector_pose_driver {
        env.keep_polling(now, epd, ra::QueryToolPoint {});
    }
    let jps = targets.joint_position_sensor;
    if let (Some(s), true) = (jps, pm_new || new.joint_position_sensor.is_some()) {
        out.push(Box::new(JointPositionSensor::new(env, now, s, arm)));
        out.push(Box::new(EndEffectorPoseSensor::new(arm)));
    }
    if let (Some(s), true) = (
        targets.joint_velocity_sensor,
        pm_new || new.joint_velocity_sensor.is_some(),
    ) {
        out.push(Box::new(JointVelocitySensor::new(env, now, s, arm)));
    }
    // Before the Joint Position Driver: it answers Query Commanded Joint Positions
    // while it drives a list, and leaves it to the other driver otherwise.
    if let (Some(d), Some(_), true) = (
        targets.joint_move_driver,
        jps,
        pm_new || new.joint_move_driver.is_some() || new.joint_position_sensor.is_some(),
    ) {
        out.push(Box::new(JointPositionListDriver::new(d, arm)));
    }
    if let (Some(d), true) = (
        targets.joint_positions_driver,
        pm_new || new.joint_positions_driver.is_some(),
    ) {
        out.push(Box::new(JointPositionDriver::new(d, arm)));
    }
    // Before the End-Effector Pose Driver, as the joint list before the Joint Position
    // Driver (Query Commanded End Effector Pose while it drives a list).
    if let (Some(d), Some(_), true) = (
        targets.end_effector_pose_driver,
        jps,
        pm_new || new.end_effector_pose_driver.is_some() || new.joint_position_sensor.is_some(),
    ) {
        out.push(Box::new(EndEffectorPoseListDriver::new(d, arm)));
    }
    if let (Some(d), true) = (
        targets.end_effector_pose_driver,
        pm_new || new.end_effector_pose_driver.is_some(),
    ) {
        out.push(Box::new(EndEffectorPoseDriver::new(d, arm)));
        out.push(Box::new(ToolOffsetService::new(d)));
    }
    if let (Some(s), true) = (
        targets.joint_force_torque_sensor,
        pm_new || new.joint_force_torque_sensor.is_some(),
    ) {
        out.push(Box::new(JointForceTorqueSensor::new(env, now, s, arm)));
    }
    if let (Some(d), true) = (
        targets.joint_velocities_driver,
        pm_new || new.joint_velocities_driver.is_some(),
    ) {
        out.push(Box::new(JointVelocityDriver::new(d, arm)));
    }
    if let (Some(d), true) = (
        targets.end_effector_velocity_state_driver,
        pm_new || new.end_effector_velocity_state_driver.is_some(),
    ) {
        out.push(Box::new(EndEffectorVelocityStateDriver::new(d, arm)));
    }
    // The tool's velocity needs the joints and their rates, polled by the two sensor
    // services.
    if let (Some(_), Some(v), true) = (
        jps,
        targets.joint_velocity_sensor,
        pm_new || new.joint_position_sensor.is_some() || new.joint_velocity_sensor.is_some(),
    ) {
        out.push(Box::new(EndEffectorVelocityStateSensor::new(arm, v)));
    }
    out
}

/// Where the arm's model and state come from: the RA 3.3 Primitive Manipulator's
/// specifications, the End-Effector Pose Driver's tool point, the Joint Position
/// Sensor's joints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Arm {
    /// The RA 3.3 Primitive Manipulator (answers Query Manipulator Specifications).
    pub manipulator: Address,
    /// The RA 3.3 End-Effector Pose Driver (answers Query Tool Point), if any.
    pub tool_from: Option<Address>,
    /// The RA 3.3 Joint Position Sensor, if any.
    pub joints_from: Option<Address>,
}

impl Arm {
    /// The arm's chain from the latest reports (`None` before the specifications came,
    /// or when they describe no usable chain: logged once per report by the caller).
    pub fn chain(&self, env: &Ra33Side) -> Option<Chain> {
        let Some((_, ra::Message::ReportManipulatorSpecifications(spec))) =
            env.latest(self.manipulator, ra::ReportManipulatorSpecifications::CODE)
        else {
            return None;
        };
        let mut chain = match Chain::from_specifications(spec) {
            Ok(c) => c,
            Err(e) => {
                tracing::debug!(manipulator = %self.manipulator, "no chain: {e}");
                return None;
            }
        };
        if let Some(Some((_, ra::Message::ReportToolPoint(t)))) = self
            .tool_from
            .map(|epd| env.latest(epd, ra::ReportToolPoint::CODE))
        {
            chain.tool = [t.x, t.y, t.z].into();
        }
        Some(chain)
    }
}

/// Each joint value tagged with its joint's kind (revolute: rad; prismatic: m); a value
/// beyond the chain's joints, or without a chain, is taken as revolute.
pub fn joint_positions(chain: Option<&Chain>, q: &[f64]) -> Vec<JointPosition> {
    q.iter()
        .enumerate()
        .map(|(i, &value)| match kind(chain, i) {
            JointKind::Revolute => JointPosition::Radians(JointPositionRadians { value }),
            JointKind::Prismatic => JointPosition::Metres(JointPositionMetres { value }),
        })
        .collect()
}

/// Each joint rate tagged with its joint's kind, as [`joint_positions`].
pub fn joint_velocities(chain: Option<&Chain>, v: &[f64]) -> Vec<JointVelocity> {
    v.iter()
        .enumerate()
        .map(|(i, &value)| match kind(chain, i) {
            JointKind::Revolute => {
                JointVelocity::RadiansPerSecond(JointVelocityRadiansPerSecond { value })
            }
            JointKind::Prismatic => {
                JointVelocity::MetresPerSecond(JointVelocityMetresPerSecond { value })
            }
        })
        .collect()
}

/// Each joint's torque or force tagged with its joint's kind (revolute: N·m, within
/// ±1000; prismatic: N, within ±500, what the report carries), as [`joint_positions`].
pub fn force_torques(chain: Option<&Chain>, f: &[f64]) -> Vec<ForceTorque> {
    f.iter()
        .enumerate()
        .map(|(i, &value)| match kind(chain, i) {
            JointKind::Revolute => ForceTorque::NewtonMetres(TorqueNewtonMetres {
                value: within(value, -1000.0, 1000.0),
            }),
            JointKind::Prismatic => ForceTorque::Newtons(ForceNewtons {
                value: within(value, -500.0, 500.0),
            }),
        })
        .collect()
}

fn kind(chain: Option<&Chain>, i: usize) -> JointKind {
    chain
        .and_then(|c| c.joints.get(i))
        .map_or(JointKind::Revolute, |j| j.kind)
}

/// The joint values of an AS-4 joint position command for the RA 3.3 driver: one per
/// joint of `chain`, each of its joint's kind, or why not (naming the joint, base joint
/// 1).
pub fn ra33_positions(chain: &Chain, positions: &[JointPosition]) -> Result<Vec<f64>, String> {
    if positions.len() != chain.dof() {
        return Err(format!(
            "{} joint positions for a manipulator of {} joints",
            positions.len(),
            chain.dof()
        ));
    }
    positions
        .iter()
        .zip(&chain.joints)
        .enumerate()
        .map(|(i, (p, j))| match (p, j.kind) {
            (JointPosition::Radians(r), JointKind::Revolute) => Ok(r.value),
            (JointPosition::Metres(m), JointKind::Prismatic) => Ok(m.value),
            (JointPosition::Radians(_), JointKind::Prismatic) => Err(format!(
                "joint {}: an angle (rad) for a prismatic joint (m)",
                i + 1
            )),
            (JointPosition::Metres(_), JointKind::Revolute) => Err(format!(
                "joint {}: a length (m) for a revolute joint (rad)",
                i + 1
            )),
        })
        .collect()
}

/// `v` within a field's limits `[lo, hi]` (a value beyond them is saturated, as a
/// scaled field cannot carry it).
fn within(v: f64, lo: f64, hi: f64) -> f64 {
    v.clamp(lo, hi)
}

/// An angle in (−π, π].
fn wrapped(a: f64) -> f64 {
    let w = a.rem_euclid(std::f64::consts::TAU);
    if w > std::f64::consts::PI {
        w - std::f64::consts::TAU
    } else {
        w
    }
}

/// The AS-4 specifications of `chain`: the base frame (when `presence_vector` bit 0
/// asks), the first joint, each further joint with its link; each joint's range and
/// speed limit. Joint names (bit 1) are not sent: RA 3.3 has none.
pub fn specifications(chain: &Chain, presence_vector: u8) -> ReportManipulatorSpecifications {
    use std::f64::consts::PI;
    let pi8 = 8.0 * PI;
    let speed = |v: f64| Some(within(v, 0.0, 10.0 * PI));
    let first = &chain.joints[0];
    let first_joint = match first.kind {
        JointKind::Revolute => FirstJoint::Revolute(FirstRevoluteJoint {
            joint1_offset: within(first.offset, -10.0, 10.0),
            joint1_min_value: Some(within(first.min, -pi8, pi8)),
            joint1_max_value: Some(within(first.max, -pi8, pi8)),
            joint1_max_speed: speed(first.max_rate),
            ..Default::default()
        }),
        JointKind::Prismatic => FirstJoint::Prismatic(FirstPrismaticJoint {
            joint1_angle: wrapped(first.offset),
            joint1_min_value: within(first.min, -10.0, 10.0),
            joint1_max_value: within(first.max, -10.0, 10.0),
            joint1_max_speed: Some(within(first.max_rate, -5.0, 5.0)),
            ..Default::default()
        }),
    };
    let joints = chain.joints[1..]
        .iter()
        .map(|j| match j.kind {
            JointKind::Revolute => JointSpecification::Revolute(RevoluteJointSpecification {
                link_length: within(j.link_length, -10.0, 10.0),
                twist_angle: wrapped(j.twist),
                joint_offset: within(j.offset, -10.0, 10.0),
                min_value: Some(within(j.min, -pi8, pi8)),
                max_value: Some(within(j.max, -pi8, pi8)),
                max_speed: speed(j.max_rate),
                ..Default::default()
            }),
            JointKind::Prismatic => JointSpecification::Prismatic(PrismaticJointSpecification {
                link_length: within(j.link_length, -10.0, 10.0),
                twist_angle: wrapped(j.twist),
                joint_angle: wrapped(j.offset),
                min_value: within(j.min, -10.0, 10.0),
                max_value: within(j.max, -10.0, 10.0),
                max_speed: Some(within(j.max_rate, -5.0, 5.0)),
                ..Default::default()
            }),
        })
        .collect();
    let coordinate_system = (presence_vector & 1 != 0).then(|| {
        let p = chain.base.translation.vector;
        let q = chain.base.rotation;
        ManipulatorCoordinateSystem {
            origin_x: within(p.x, -30.0, 30.0),
            origin_y: within(p.y, -30.0, 30.0),
            origin_z: within(p.z, -30.0, 30.0),
            quaternion_d: q.w,
            quaternion_a: q.i,
            quaternion_b: q.j,
            quaternion_c: q.k,
        }
    });
    ReportManipulatorSpecifications {
        coordinate_system,
        first_joint,
        joints,
        joint_names: None,
    }
}

/// The pose of the tool point at joint values `q` (vehicle frame; the quaternion with
/// d ≥ 0), as AS-4 reports it.
pub fn end_effector_pose(chain: &Chain, q: &[f64]) -> ReportEndEffectorPose {
    let t = chain.tool_pose(q);
    let p = t.translation.vector;
    let r = t.rotation;
    let s = if r.w < 0.0 { -1.0 } else { 1.0 };
    ReportEndEffectorPose {
        tool_point_x: within(p.x, -30.0, 30.0),
        tool_point_y: within(p.y, -30.0, 30.0),
        tool_point_z: within(p.z, -30.0, 30.0),
        quaternion_d: s * r.w,
        quaternion_a: s * r.i,
        quaternion_b: s * r.j,
        quaternion_c: s * r.k,
    }
}
