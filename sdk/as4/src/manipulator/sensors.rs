//! The sensors and the specification service: Joint Position, Joint Velocity and Joint
//! Force/Torque Sensors, the Specification Service and the End-Effector Pose Sensor,
//! answering from the latest reports of the RA 3.3 components behind them (which the
//! gateway keeps polling) and the arm's chain ([`Arm::chain`]).

use jaus::messages as ra;
use jaus::{Address, JausMessage};

use super::{end_effector_pose, force_torques, joint_positions, joint_velocities, specifications};
use super::{Arm, ServiceIds};
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::transport::event::Receive;
use crate::messages::services::{
    manipulator_end_effector_pose_sensor as pose_sensor,
    manipulator_joint_force_torque_sensor as force_torque_sensor,
    manipulator_joint_position_sensor as position_sensor,
    manipulator_joint_velocity_sensor as velocity_sensor,
    manipulator_specification_service as specification,
};
use crate::messages::{
    QueryManipulatorSpecifications, ReportEndEffectorPose, ReportJointForceTorques,
    ReportJointPositions, ReportJointVelocity,
};
use crate::ra33::Ra33Side;
use jaus::stock::manipulator::kinematics::Chain;

machined!(
    JointPositions,
    manipulator_joint_position_sensor,
    ServiceIds::JOINT_POSITION_SENSOR,
    events
);
machined!(
    JointVelocities,
    manipulator_joint_velocity_sensor,
    ServiceIds::JOINT_VELOCITY_SENSOR,
    events
);
machined!(
    Specification,
    manipulator_specification_service,
    ServiceIds::SPECIFICATION,
    events
);
machined!(
    EndEffectorPose,
    manipulator_end_effector_pose_sensor,
    ServiceIds::END_EFFECTOR_POSE_SENSOR,
    access_control
);

/// The latest joint values the RA 3.3 Joint Position Sensor at `sensor` reported.
pub(super) fn measured(env: &Ra33Side, sensor: Address) -> Option<&[f64]> {
    match env.latest(sensor, ra::ReportJointPositions::CODE) {
        Some((_, ra::Message::ReportJointPositions(r))) => Some(&r.joint_position),
        _ => None,
    }
}

/// The Joint Position Sensor over an RA 3.3 Joint Position Sensor.
pub type JointPositionSensor = OnMachines<JointPositions>;

/// The Joint Position Sensor's data: the RA 3.3 sensor and the arm.
#[derive(Debug)]
pub struct JointPositions {
    sensor: Address,
    arm: Arm,
}

impl JointPositionSensor {
    /// The service over the RA 3.3 sensor at `sensor`; `side` starts polling it.
    pub fn new(side: &mut Ra33Side, now: std::time::Instant, sensor: Address, arm: Arm) -> Self {
        side.keep_polling(now, sensor, ra::QueryJointPositions {});
        OnMachines::from_impl(JointPositions { sensor, arm })
    }
}

impl position_sensor::ManipulatorJointPositionSensor for On<'_, JointPositions> {
    fn send_report_joint_positions(&mut self, transport: &Receive) {
        let chain = self.svc.arm.chain(self.env);
        let q = measured(self.env, self.svc.sensor).unwrap_or_default();
        let report = ReportJointPositions {
            joint_positions: joint_positions(chain.as_ref(), q),
        };
        self.reply(transport, report);
    }
}

/// The Joint Velocity Sensor over an RA 3.3 Joint Velocity Sensor.
pub type JointVelocitySensor = OnMachines<JointVelocities>;

/// The Joint Velocity Sensor's data: the RA 3.3 sensor and the arm.
#[derive(Debug)]
pub struct JointVelocities {
    sensor: Address,
    arm: Arm,
}

impl JointVelocitySensor {
    /// The service over the RA 3.3 sensor at `sensor`; `side` starts polling it.
    pub fn new(side: &mut Ra33Side, now: std::time::Instant, sensor: Address, arm: Arm) -> Self {
        side.keep_polling(now, sensor, ra::QueryJointVelocities {});
        OnMachines::from_impl(JointVelocities { sensor, arm })
    }
}

impl velocity_sensor::ManipulatorJointVelocitySensor for On<'_, JointVelocities> {
    fn send_report_joint_velocity(&mut self, transport: &Receive) {
        let chain = self.svc.arm.chain(self.env);
        let v = match self
            .env
            .latest(self.svc.sensor, ra::ReportJointVelocities::CODE)
        {
            Some((_, ra::Message::ReportJointVelocities(r))) => r.joint_velocity.as_slice(),
            _ => &[],
        };
        let report = ReportJointVelocity {
            joint_velocities: joint_velocities(chain.as_ref(), v),
        };
        self.reply(transport, report);
    }
}

/// The Specification Service over the RA 3.3 Primitive Manipulator's specifications.
pub type SpecificationService = OnMachines<Specification>;

/// The Specification Service's data: the arm.
#[derive(Debug)]
pub struct Specification {
    arm: Arm,
}

impl SpecificationService {
    /// The service over `arm` (the gateway polls its specifications).
    pub fn new(arm: Arm) -> Self {
        OnMachines::from_impl(Specification { arm })
    }
}

impl specification::ManipulatorSpecificationService for On<'_, Specification> {
    fn send_report_manipulator_specifications(
        &mut self,
        msg: &QueryManipulatorSpecifications,
        transport: &Receive,
    ) {
        match self.svc.arm.chain(self.env) {
            Some(chain) => {
                let report = specifications(&chain, msg.presence_vector);
                self.reply(transport, report);
            }
            None => self.refuse(format!(
                "no usable Report Manipulator Specifications from the RA 3.3 manipulator {} yet",
                self.svc.arm.manipulator
            )),
        }
    }
}

/// The End-Effector Pose Sensor: the pose of the tool point at the joints the RA 3.3
/// Joint Position Sensor measures (forward kinematics of the chain).
pub type EndEffectorPoseSensor = OnMachines<EndEffectorPose>;

/// The End-Effector Pose Sensor's data: the arm.
#[derive(Debug)]
pub struct EndEffectorPose {
    arm: Arm,
}

impl EndEffectorPoseSensor {
    /// The service over `arm`, whose Joint Position Sensor the Joint Position Sensor
    /// service polls.
    pub fn new(arm: Arm) -> Self {
        OnMachines::from_impl(EndEffectorPose { arm })
    }
}

/// The arm's joint position sensor, kinematic chain and measured joint positions, or why
/// there are none
/// (no sensor behind the gateway, no specifications or no positions yet).
pub(super) fn chain_and_joints<'e>(
    env: &'e Ra33Side,
    arm: &Arm,
) -> Result<(Address, Chain, &'e [f64]), String> {
    let sensor = arm
        .joints_from
        .ok_or("no RA 3.3 joint position sensor behind the gateway")?;
    let chain = arm.chain(env).ok_or_else(|| {
        format!(
            "no usable Report Manipulator Specifications from the RA 3.3 manipulator {} yet",
            arm.manipulator
        )
    })?;
    let q = measured(env, sensor)
        .ok_or_else(|| format!("no joint positions from the RA 3.3 sensor {sensor} yet"))?;
    Ok((sensor, chain, q))
}

/// The measured pose of the tool point, or why there is none.
pub(super) fn measured_pose(env: &Ra33Side, arm: &Arm) -> Result<ReportEndEffectorPose, String> {
    let (sensor, chain, q) = chain_and_joints(env, arm)?;
    if q.len() != chain.dof() {
        return Err(format!(
            "the RA 3.3 sensor {sensor} reports {} joints, the manipulator has {}",
            q.len(),
            chain.dof()
        ));
    }
    Ok(end_effector_pose(&chain, q))
}

impl pose_sensor::ManipulatorEndEffectorPoseSensor for On<'_, EndEffectorPose> {
    fn send_report_end_effector_pose(&mut self, transport: &Receive) {
        match measured_pose(self.env, &self.svc.arm) {
            Ok(report) => self.reply(transport, report),
            Err(why) => self.refuse(why),
        }
    }
}

machined!(
    ForceTorques,
    manipulator_joint_force_torque_sensor,
    ServiceIds::JOINT_FORCE_TORQUE_SENSOR,
    events
);

/// The Joint Force/Torque Sensor over an RA 3.3 Joint Force/Torque Sensor: each joint's
/// torque (revolute, N·m) or force (prismatic, N), tagged by the chain.
pub type JointForceTorqueSensor = OnMachines<ForceTorques>;

/// The Joint Force/Torque Sensor's data: the RA 3.3 sensor and the arm.
#[derive(Debug)]
pub struct ForceTorques {
    sensor: Address,
    arm: Arm,
}

impl JointForceTorqueSensor {
    /// The service over the RA 3.3 sensor at `sensor`; `side` starts polling it.
    pub fn new(side: &mut Ra33Side, now: std::time::Instant, sensor: Address, arm: Arm) -> Self {
        side.keep_polling(now, sensor, ra::QueryJointForceTorques {});
        OnMachines::from_impl(ForceTorques { sensor, arm })
    }
}

impl force_torque_sensor::ManipulatorJointForceTorqueSensor for On<'_, ForceTorques> {
    fn send_report_joint_force_torques(&mut self, transport: &Receive) {
        let chain = self.svc.arm.chain(self.env);
        let values = match self
            .env
            .latest(self.svc.sensor, ra::ReportJointForceTorques::CODE)
        {
            Some((_, ra::Message::ReportJointForceTorques(r))) => r.joint_force_torque.as_slice(),
            _ => &[],
        };
        let report = ReportJointForceTorques {
            actuator_force_torques: force_torques(chain.as_ref(), values),
        };
        self.reply(transport, report);
    }
}
