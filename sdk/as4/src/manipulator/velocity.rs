//! The velocity services: the Joint Velocity Driver and the End-Effector Velocity State
//! Driver, passing the controlling client's rates on to the RA 3.3 Joint Velocities
//! Driver (56) and End-Effector Velocity State Driver (57), and the End-Effector
//! Velocity State Sensor, the velocity of the tool point from the measured joints and
//! their rates (RA 3.3 has no such sensor).
//!
//! The rates are set-points, streamed ([`crate::ra33::STREAMED`]): the RA 3.3 drivers
//! stop the arm when a command is not refreshed (the stock ones after 500 ms), so a
//! client keeps sending its rates while it wants motion, as it does its efforts to the
//! Primitive Driver. Rates of zero stop the arm; so does leaving Ready (the drivers go
//! to standby) and the client's control ending (RA 3.3 control given back).

use jaus::messages as ra;
use jaus::stock::manipulator::kinematics::{Chain, JointKind};
use jaus::stock::nalgebra::{DVector, Dyn, OMatrix, U6};
use jaus::{Address, JausMessage};

use super::drivers::{deliver, flush};
use super::sensors::chain_and_joints;
use super::{joint_velocities, within, Arm, ServiceIds};
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::transport::event::Receive;
use crate::messages::services::{
    manipulator_end_effector_velocity_state_driver as ee_driver,
    manipulator_end_effector_velocity_state_sensor as ee_sensor,
    manipulator_joint_velocity_driver as joint_driver,
};
use crate::messages::{
    JointVelocity, ReportCommandedEndEffectorVelocityState, ReportCommandedJointVelocity,
    ReportEndEffectorVelocityState, SetEndEffectorVelocityState, SetJointVelocity,
};
use crate::ra33::Ra33Side;
use crate::service::Cx;
use crate::ComponentState;

/// RA 3.3's `coordinate_system` of Set End Effector Velocity State for the vehicle
/// frame (the frame AS-4's end-effector pose and velocity are given in here).
pub const VEHICLE_FRAME: u8 = 1;

/// The joint rates of an AS-4 joint velocity command for the RA 3.3 driver: one per
/// joint of `chain`, each of its joint's kind, finite and within its joint's speed
/// limit, or why not (naming the joint, base joint 1).
pub fn ra33_rates(chain: &Chain, rates: &[JointVelocity]) -> Result<Vec<f64>, String> {
    if rates.len() != chain.dof() {
        return Err(format!(
            "{} joint velocities for a manipulator of {} joints",
            rates.len(),
            chain.dof()
        ));
    }
    rates
        .iter()
        .zip(&chain.joints)
        .enumerate()
        .map(|(i, (v, j))| {
            let value = match (v, j.kind) {
                (JointVelocity::RadiansPerSecond(r), JointKind::Revolute) => r.value,
                (JointVelocity::MetresPerSecond(m), JointKind::Prismatic) => m.value,
                (JointVelocity::RadiansPerSecond(_), JointKind::Prismatic) => {
                    return Err(format!(
                        "joint {}: an angular rate (rad/s) for a prismatic joint (m/s)",
                        i + 1
                    ))
                }
                (JointVelocity::MetresPerSecond(_), JointKind::Revolute) => {
                    return Err(format!(
                        "joint {}: a linear rate (m/s) for a revolute joint (rad/s)",
                        i + 1
                    ))
                }
            };
            if !value.is_finite() || value.abs() > j.max_rate {
                return Err(format!(
                    "joint {}: rate {value} beyond its limit {}",
                    i + 1,
                    j.max_rate
                ));
            }
            Ok(value)
        })
        .collect()
}

machined!(
    JointRates,
    manipulator_joint_velocity_driver,
    ServiceIds::JOINT_VELOCITY_DRIVER,
    management {
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            self.follow_driver(cx);
        }
        fn state_changed(
            &mut self,
            _cx: &mut Cx<'_, Ra33Side>,
            from: ComponentState,
            to: ComponentState,
        ) {
            self.follow_state(from, to);
        }
    }
);
machined!(
    ToolRates,
    manipulator_end_effector_velocity_state_driver,
    ServiceIds::END_EFFECTOR_VELOCITY_STATE_DRIVER,
    management {
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            self.follow_driver(cx);
        }
        fn state_changed(
            &mut self,
            _cx: &mut Cx<'_, Ra33Side>,
            from: ComponentState,
            to: ComponentState,
        ) {
            self.follow_state(from, to);
        }
    }
);
machined!(
    ToolVelocity,
    manipulator_end_effector_velocity_state_sensor,
    ServiceIds::END_EFFECTOR_VELOCITY_STATE_SENSOR,
    access_control
);

/// The Joint Velocity Driver over an RA 3.3 Joint Velocities Driver.
pub type JointVelocityDriver = OnMachines<JointRates>;

/// A velocity driver's data: the RA 3.3 driver, the arm, the last command `C`, and the
/// RA 3.3 command not sent yet.
#[derive(Debug)]
pub struct Rates<C> {
    driver: Address,
    arm: Arm,
    commanded: Option<C>,
    pending: Option<ra::Message>,
}

/// The Joint Velocity Driver's data.
pub type JointRates = Rates<SetJointVelocity>;
/// The End-Effector Velocity State Driver's data.
pub type ToolRates = Rates<SetEndEffectorVelocityState>;

impl<C> Rates<C> {
    fn over(driver: Address, arm: Arm) -> Self {
        Rates {
            driver,
            arm,
            commanded: None,
            pending: None,
        }
    }

    /// The arm stopped for this driver (the component left Ready, or another driver
    /// took the arm: the RA 3.3 driver is in standby): no rate stands commanded.
    fn stopped(&mut self) {
        self.commanded = None;
        self.pending = None;
    }

    /// Its tick: the command not sent yet goes out; a driver no longer active stopped.
    fn follow_driver(&mut self, cx: &mut Cx<'_, Ra33Side>) {
        flush(cx.env, self.driver, &mut self.pending);
        if !cx.env.is_active(self.driver) {
            self.stopped();
        }
    }

    /// Leaving Ready stops the arm for this driver.
    fn follow_state(&mut self, from: ComponentState, to: ComponentState) {
        if from == ComponentState::Ready && to != ComponentState::Ready {
            self.stopped();
        }
    }
}

impl JointVelocityDriver {
    /// The service over the RA 3.3 Joint Velocities Driver at `driver`.
    pub fn new(driver: Address, arm: Arm) -> Self {
        OnMachines::from_impl(Rates::over(driver, arm))
    }
}

impl joint_driver::ManipulatorJointVelocityDriver for On<'_, JointRates> {
    fn motion_profile_exists(&self) -> bool {
        self.svc.arm.chain(self.env).is_some()
    }

    fn send_report_commanded_joint_velocity(&mut self, transport: &Receive) {
        let joint_velocities = match &self.svc.commanded {
            Some(c) => c.joint_velocities.clone(),
            None => {
                let chain = self.svc.arm.chain(self.env);
                let n = chain.as_ref().map_or(0, Chain::dof);
                joint_velocities(chain.as_ref(), &vec![0.0; n])
            }
        };
        self.reply(transport, ReportCommandedJointVelocity { joint_velocities });
    }

    fn set_joint_velocity(&mut self, msg: &SetJointVelocity) {
        let Some(chain) = self.svc.arm.chain(self.env) else {
            return self.refuse("the manipulator's specifications are not known yet");
        };
        let v = match ra33_rates(&chain, &msg.joint_velocities) {
            Ok(v) => v,
            Err(why) => return self.refuse(why),
        };
        self.svc.commanded = Some(msg.clone());
        let command = ra::SetJointVelocities { joint_velocity: v }.into();
        deliver(self.env, self.svc.driver, command, &mut self.svc.pending);
    }
}

/// The End-Effector Velocity State Driver over an RA 3.3 End-Effector Velocity State
/// Driver: the same six rates, in the vehicle frame ([`VEHICLE_FRAME`]).
pub type EndEffectorVelocityStateDriver = OnMachines<ToolRates>;

impl EndEffectorVelocityStateDriver {
    /// The service over the RA 3.3 End-Effector Velocity State Driver at `driver`.
    pub fn new(driver: Address, arm: Arm) -> Self {
        OnMachines::from_impl(Rates::over(driver, arm))
    }
}

impl ee_driver::ManipulatorEndEffectorVelocityStateDriver for On<'_, ToolRates> {
    fn motion_profile_exists(&self) -> bool {
        self.svc.arm.chain(self.env).is_some()
    }

    fn send_report_commanded_end_effector_velocity_state(&mut self, transport: &Receive) {
        let c = self.svc.commanded.clone().unwrap_or_default();
        self.reply(
            transport,
            ReportCommandedEndEffectorVelocityState {
                angular_velocity_x: c.angular_velocity_x,
                angular_velocity_y: c.angular_velocity_y,
                angular_velocity_z: c.angular_velocity_z,
                linear_velocity_x: c.linear_velocity_x,
                linear_velocity_y: c.linear_velocity_y,
                linear_velocity_z: c.linear_velocity_z,
            },
        );
    }

    fn set_end_effector_velocity_state(&mut self, msg: &SetEndEffectorVelocityState) {
        let all = [
            msg.angular_velocity_x,
            msg.angular_velocity_y,
            msg.angular_velocity_z,
            msg.linear_velocity_x,
            msg.linear_velocity_y,
            msg.linear_velocity_z,
        ];
        if !all.iter().all(|v| v.is_finite()) {
            return self.refuse("end-effector velocity state is not finite");
        }
        self.svc.commanded = Some(msg.clone());
        let command = ra::SetEndEffectorVelocityState {
            coordinate_system: VEHICLE_FRAME,
            x_angular: msg.angular_velocity_x,
            y_angular: msg.angular_velocity_y,
            z_angular: msg.angular_velocity_z,
            x_linear: msg.linear_velocity_x,
            y_linear: msg.linear_velocity_y,
            z_linear: msg.linear_velocity_z,
        }
        .into();
        deliver(self.env, self.svc.driver, command, &mut self.svc.pending);
    }
}

/// The End-Effector Velocity State Sensor: the velocity of the tool point (vehicle
/// frame) at the joints and rates the RA 3.3 Joint Position and Joint Velocity Sensors
/// measure, through the chain's Jacobian.
pub type EndEffectorVelocityStateSensor = OnMachines<ToolVelocity>;

/// The End-Effector Velocity State Sensor's data: the arm and the RA 3.3 Joint
/// Velocity Sensor.
#[derive(Debug)]
pub struct ToolVelocity {
    arm: Arm,
    rates_from: Address,
}

impl EndEffectorVelocityStateSensor {
    /// The service over `arm` and the RA 3.3 Joint Velocity Sensor at `rates_from` (the
    /// Joint Position and Joint Velocity Sensor services poll both).
    pub fn new(arm: Arm, rates_from: Address) -> Self {
        OnMachines::from_impl(ToolVelocity { arm, rates_from })
    }
}

/// The measured velocity of the tool point, or why there is none.
pub fn measured_tool_velocity(
    env: &Ra33Side,
    arm: &Arm,
    rates_from: Address,
) -> Result<ReportEndEffectorVelocityState, String> {
    let (_, chain, q) = chain_and_joints(env, arm)?;
    let qd = match env.latest(rates_from, ra::ReportJointVelocities::CODE) {
        Some((_, ra::Message::ReportJointVelocities(r))) => r.joint_velocity.as_slice(),
        _ => {
            return Err(format!(
                "no joint velocities from the RA 3.3 sensor {rates_from} yet"
            ))
        }
    };
    let n = chain.dof();
    if q.len() != n || qd.len() != n {
        return Err(format!(
            "the RA 3.3 sensors report {} joint positions and {} rates, the manipulator has {n} joints",
            q.len(),
            qd.len()
        ));
    }
    Ok(tool_velocity(&chain, q, qd))
}

/// The velocity of the tool point of `chain` at joints `q` moving at `qd` (vehicle
/// frame; linear from the Jacobian's first three rows, angular from its last three),
/// saturated at what the report carries.
pub fn tool_velocity(chain: &Chain, q: &[f64], qd: &[f64]) -> ReportEndEffectorVelocityState {
    let mut jac = OMatrix::<f64, U6, Dyn>::zeros(chain.dof());
    chain.jacobian(q, &mut jac);
    let twist = jac * DVector::from_column_slice(qd);
    let angular = |v: f64| within(v, -20.0 * std::f64::consts::PI, 20.0 * std::f64::consts::PI);
    let linear = |v: f64| within(v, -10.0, 10.0);
    ReportEndEffectorVelocityState {
        angular_velocity_x: angular(twist[3]),
        angular_velocity_y: angular(twist[4]),
        angular_velocity_z: angular(twist[5]),
        linear_velocity_x: linear(twist[0]),
        linear_velocity_y: linear(twist[1]),
        linear_velocity_z: linear(twist[2]),
    }
}

impl ee_sensor::ManipulatorEndEffectorVelocityStateSensor for On<'_, ToolVelocity> {
    fn send_report_end_effector_velocity_state(&mut self, transport: &Receive) {
        match measured_tool_velocity(self.env, &self.svc.arm, self.svc.rates_from) {
            Ok(report) => self.reply(transport, report),
            Err(why) => self.refuse(why),
        }
    }
}
