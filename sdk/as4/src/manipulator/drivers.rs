//! The drivers: the Joint Position Driver and the End-Effector Pose Driver, passing the
//! controlling client's commands on to the RA 3.3 drivers the gateway controls.
//!
//! A command that arrives before RA 3.3 control of the driver is granted waits (the
//! latest one only) and leaves when it is; the driver is resumed first
//! ([`Ra33Side::activate`]). Before any command, Query Commanded ... reports what the
//! arm holds: the measured joints, the measured pose.

use jaus::messages as ra;
use jaus::stock::manipulator::pose_drivers::pose_of;
use jaus::Address;

use super::sensors::{measured, measured_pose};
use super::{joint_positions, ra33_positions, Arm, ServiceIds};
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::transport::event::Receive;
use crate::messages::services::{
    manipulator_end_effector_pose_driver as pose_driver,
    manipulator_joint_position_driver as position_driver,
};
use crate::messages::{
    ReportCommandedEndEffectorPose, ReportCommandedJointPositions, SetEndEffectorPose,
    SetJointPositions,
};
use crate::ra33::{Ra33Control, Ra33Side};
use crate::service::Cx;

/// Sends `command` to `driver` now if the gateway holds it, else keeps it in `pending`
/// for [`flush`]; either way `driver` becomes its group's active driver.
pub(super) fn deliver(
    env: &mut Ra33Side,
    driver: Address,
    command: ra::Message,
    pending: &mut Option<ra::Message>,
) {
    env.activate(driver);
    if env.control_of(driver) == Ra33Control::Granted {
        env.send(driver, command);
        *pending = None;
    } else {
        *pending = Some(command);
    }
}

/// Sends the command kept in `pending` once RA 3.3 control of `driver` is granted.
pub(super) fn flush(env: &mut Ra33Side, driver: Address, pending: &mut Option<ra::Message>) {
    if env.control_of(driver) == Ra33Control::Granted {
        if let Some(c) = pending.take() {
            env.send(driver, c);
        }
    }
}

machined!(
    JointPositions,
    manipulator_joint_position_driver,
    ServiceIds::JOINT_POSITION_DRIVER,
    management {
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            flush(cx.env, self.driver, &mut self.pending);
        }
    }
);
machined!(
    EndEffectorPose,
    manipulator_end_effector_pose_driver,
    ServiceIds::END_EFFECTOR_POSE_DRIVER,
    management {
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            flush(cx.env, self.driver, &mut self.pending);
        }
    }
);

/// The Joint Position Driver over an RA 3.3 Joint Positions Driver.
pub type JointPositionDriver = OnMachines<JointPositions>;

/// The Joint Position Driver's data: the RA 3.3 driver, the arm, the last command.
#[derive(Debug)]
pub struct JointPositions {
    driver: Address,
    arm: Arm,
    commanded: Option<SetJointPositions>,
    pending: Option<ra::Message>,
}

impl JointPositionDriver {
    /// The service over the RA 3.3 Joint Positions Driver at `driver`.
    pub fn new(driver: Address, arm: Arm) -> Self {
        OnMachines::from_impl(JointPositions {
            driver,
            arm,
            commanded: None,
            pending: None,
        })
    }
}

impl position_driver::ManipulatorJointPositionDriver for On<'_, JointPositions> {
    fn motion_profile_exists(&self) -> bool {
        self.svc.arm.chain(self.env).is_some()
    }

    fn send_report_commanded_joint_positions(&mut self, transport: &Receive) {
        let joint_positions = match &self.svc.commanded {
            Some(c) => c.joint_positions.clone(),
            None => {
                let chain = self.svc.arm.chain(self.env);
                let q = self
                    .svc
                    .arm
                    .joints_from
                    .and_then(|s| measured(self.env, s))
                    .unwrap_or_default();
                joint_positions(chain.as_ref(), q)
            }
        };
        self.reply(transport, ReportCommandedJointPositions { joint_positions });
    }

    fn set_joint_positions(&mut self, msg: &SetJointPositions) {
        let Some(chain) = self.svc.arm.chain(self.env) else {
            return self.refuse("the manipulator's specifications are not known yet");
        };
        let q = match ra33_positions(&chain, &msg.joint_positions) {
            Ok(q) => q,
            Err(why) => return self.refuse(why),
        };
        if !chain.within_limits(&q) {
            return self.refuse(format!(
                "joint positions {q:?} beyond the manipulator's limits"
            ));
        }
        self.svc.commanded = Some(msg.clone());
        let command = ra::SetJointPositions { joint_position: q }.into();
        deliver(self.env, self.svc.driver, command, &mut self.svc.pending);
    }
}

/// The End-Effector Pose Driver over an RA 3.3 End-Effector Pose Driver.
pub type EndEffectorPoseDriver = OnMachines<EndEffectorPose>;

/// The End-Effector Pose Driver's data: the RA 3.3 driver, the arm, the last command.
#[derive(Debug)]
pub struct EndEffectorPose {
    driver: Address,
    arm: Arm,
    commanded: Option<SetEndEffectorPose>,
    pending: Option<ra::Message>,
}

impl EndEffectorPoseDriver {
    /// The service over the RA 3.3 End-Effector Pose Driver at `driver`.
    pub fn new(driver: Address, arm: Arm) -> Self {
        OnMachines::from_impl(EndEffectorPose {
            driver,
            arm,
            commanded: None,
            pending: None,
        })
    }
}

impl pose_driver::ManipulatorEndEffectorPoseDriver for On<'_, EndEffectorPose> {
    fn motion_profile_exists(&self) -> bool {
        self.svc.arm.chain(self.env).is_some()
    }

    fn send_report_commanded_end_effector_pose(&mut self, transport: &Receive) {
        match commanded_pose(self.env, &self.svc.arm, self.svc.commanded.as_ref()) {
            Ok(report) => self.reply(transport, report),
            Err(why) => self.refuse(why),
        }
    }

    fn set_end_effector_pose(&mut self, msg: &SetEndEffectorPose) {
        if let Err(e) = pose_of(
            msg.tool_point_x,
            msg.tool_point_y,
            msg.tool_point_z,
            msg.quaternion_d,
            msg.quaternion_a,
            msg.quaternion_b,
            msg.quaternion_c,
        ) {
            return self.refuse(e.to_string());
        }
        self.svc.commanded = Some(msg.clone());
        let command = ra33_pose(msg);
        deliver(self.env, self.svc.driver, command, &mut self.svc.pending);
    }
}

/// The RA 3.3 Set End Effector Pose of an AS-4 one: the same position and quaternion,
/// in the vehicle frame.
pub(super) fn ra33_pose(msg: &SetEndEffectorPose) -> ra::Message {
    ra::SetEndEffectorPose {
        x: msg.tool_point_x,
        y: msg.tool_point_y,
        z: msg.tool_point_z,
        d: msg.quaternion_d,
        a: msg.quaternion_a,
        b: msg.quaternion_b,
        c: msg.quaternion_c,
    }
    .into()
}

/// Report Commanded End Effector Pose: the pose `commanded`, else the measured one (or
/// why there is none).
pub(super) fn commanded_pose(
    env: &Ra33Side,
    arm: &Arm,
    commanded: Option<&SetEndEffectorPose>,
) -> Result<ReportCommandedEndEffectorPose, String> {
    Ok(match commanded {
        Some(c) => ReportCommandedEndEffectorPose {
            tool_point_x: c.tool_point_x,
            tool_point_y: c.tool_point_y,
            tool_point_z: c.tool_point_z,
            quaternion_d: c.quaternion_d,
            quaternion_a: c.quaternion_a,
            quaternion_b: c.quaternion_b,
            quaternion_c: c.quaternion_c,
        },
        None => {
            let p = measured_pose(env, arm)?;
            ReportCommandedEndEffectorPose {
                tool_point_x: p.tool_point_x,
                tool_point_y: p.tool_point_y,
                tool_point_z: p.tool_point_z,
                quaternion_d: p.quaternion_d,
                quaternion_a: p.quaternion_a,
                quaternion_b: p.quaternion_b,
                quaternion_c: p.quaternion_c,
            }
        }
    })
}
