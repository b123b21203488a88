//! The End-Effector Pose List Driver over the RA 3.3 End-Effector Pose Driver (55): the
//! component's list of Set End Effector Pose elements, from the element Manipulator
//! Execute List names (or the head), driven one by one. Each element's pose (of the
//! tool point, in the vehicle frame, as the End-Effector Pose Driver takes it) goes to
//! the RA 3.3 driver as its Set End Effector Pose; the element is reached when the
//! measured pose (the RA 3.3 Joint Position Sensor's joints through the chain, as the
//! End-Effector Pose Sensor reports it) is within [`POSITION_TOLERANCE`] and
//! [`ORIENTATION_TOLERANCE`] of it, and the next element's pose is sent. Once the last
//! is reached the list is done: no element is active, the RA 3.3 driver holds the last
//! pose, and a command event of Execute List ends `Successful`.
//!
//! Each element must be a Set End Effector Pose of finite values and a unit quaternion,
//! reachable within the joint limits of the arm's chain (inverse kinematics from the
//! measured joints, each element from the solution of the one before: the RA 3.3
//! driver's own check where it knows no more): `isListValid` checks the whole list, and
//! a list that is not valid is refused (logged with the element's UID and why).
//!
//! The element being driven to is Query Manipulator Active Element's answer and, while
//! a list is driven, Query Commanded End Effector Pose's (the End-Effector Pose
//! Driver's otherwise). The list ends without being done when the component leaves
//! Ready or control ends (the RA 3.3 driver goes to standby, holding the arm where it
//! is), or when the arm is given another command (the End-Effector Pose Driver's
//! included: it commands the same RA 3.3 driver).

use jaus::stock::manipulator::kinematics::IkSolver;
use jaus::stock::manipulator::pose_drivers::pose_of;
use jaus::stock::nalgebra::Isometry3;
use jaus::{Address, JausMessage};

use super::drivers::{commanded_pose, ra33_pose};
use super::listing::{self, list_driver, start_of, ListDriving, Listing};
use super::sensors::chain_and_joints;
use super::{Arm, ServiceIds};
use crate::core::lists::Lists;
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::manipulator_end_effector_pose_list_driver as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{ManipulatorExecuteList, QueryCommandedEndEffectorPose, SetEndEffectorPose};
use crate::ra33::Ra33Side;
use crate::service::{Cx, ServiceId};
use crate::{ComponentState, Message};

/// How far from an element's position the tool point counts as there, m.
pub const POSITION_TOLERANCE: f64 = 1e-3;
/// How far from an element's orientation the tool counts as there, rad (0.57°).
pub const ORIENTATION_TOLERANCE: f64 = 0.01;

const ID: ServiceId = ServiceIds::END_EFFECTOR_POSE_LIST_DRIVER;

machined!(
    PoseList,
    manipulator_end_effector_pose_list_driver,
    ID,
    list_manager {
        fn claims(&self, lists: &Lists, message: &Message) -> bool {
            // The End-Effector Pose Driver answers for the commanded pose when no list
            // is being driven; the Joint Position List Driver for a list of joints.
            self.list
                .claims(lists, message, QueryCommandedEndEffectorPose::CODE)
        }
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            self.advance(cx.env);
        }
        fn state_changed(
            &mut self,
            _cx: &mut Cx<'_, Ra33Side>,
            from: ComponentState,
            to: ComponentState,
        ) {
            // Leaving Ready stops the arm (the RA 3.3 driver goes to standby): the run
            // ends.
            if from == ComponentState::Ready && to != ComponentState::Ready {
                self.list.stop();
            }
        }
        fn in_progress(&self, code: jaus::CommandCode) -> bool {
            self.list.in_progress(code)
        }
    }
);
list_driver!(PoseList);

/// The End-Effector Pose List Driver over an RA 3.3 End-Effector Pose Driver.
pub type EndEffectorPoseListDriver = OnMachines<PoseList>;

/// One element of a list of poses: the AS-4 pose, and as a pose of the tool point in
/// the vehicle frame.
#[derive(Debug, Clone)]
pub(super) struct PoseStep {
    pose: SetEndEffectorPose,
    at: Isometry3<f64>,
}

/// The End-Effector Pose List Driver's data: the list driven over the RA 3.3
/// End-Effector Pose Driver.
#[derive(Debug)]
pub struct PoseList {
    list: Listing<PoseStep>,
}

impl EndEffectorPoseListDriver {
    /// The service over the RA 3.3 End-Effector Pose Driver at `driver`.
    pub fn new(driver: Address, arm: Arm) -> Self {
        OnMachines::from_impl(PoseList {
            list: Listing::new(ID, SetEndEffectorPose::CODE, driver, arm),
        })
    }
}

/// Whether the tool at `here` is at `target`: within [`POSITION_TOLERANCE`] and
/// [`ORIENTATION_TOLERANCE`].
fn close(here: &Isometry3<f64>, target: &Isometry3<f64>) -> bool {
    let position = (target.translation.vector - here.translation.vector).norm();
    let angle = (target.rotation * here.rotation.inverse()).angle();
    position <= POSITION_TOLERANCE && angle <= ORIENTATION_TOLERANCE
}

impl PoseList {
    /// Sends the command waiting for RA 3.3 control, and follows the run: the active
    /// element is reached when the measured pose is close to it ([`close`]), and the
    /// next one's pose is sent; the list is done when the last is reached.
    fn advance(&mut self, env: &mut Ra33Side) {
        let arm = self.list.arm;
        let Some(run) = self.list.follow(env) else {
            return;
        };
        let here = match chain_and_joints(env, &arm) {
            Ok((_, chain, q)) if q.len() == chain.dof() => chain.tool_pose(q),
            _ => return,
        };
        let before = run.active;
        while run
            .targets
            .get(run.active)
            .is_some_and(|s| close(&here, &s.at))
        {
            run.reach(ID);
        }
        if run.all_reached() {
            self.list.finish();
        } else if run.active != before {
            let command = ra33_pose(&run.targets[run.active].pose);
            self.list.command(env, command);
        }
    }
}

impl ListDriving for PoseList {
    type Target = PoseStep;
    const ID: ServiceId = ID;

    fn listing(&self) -> &Listing<PoseStep> {
        &self.list
    }

    /// Each element a Set End Effector Pose of finite values and a unit quaternion,
    /// within reach ([`IkSolver`] within the chain's joint limits, from the measured
    /// joints or the middle of their ranges, then each from the one before).
    fn check(
        &self,
        env: &Ra33Side,
        lists: &Lists,
        start: u16,
    ) -> Result<Vec<(u16, PoseStep)>, String> {
        let arm = &self.list.arm;
        let (chain, mut seed) = match chain_and_joints(env, arm) {
            Ok((_, chain, q)) if q.len() == chain.dof() => {
                let q = q.to_vec();
                (chain, q)
            }
            _ => {
                let chain = arm
                    .chain(env)
                    .ok_or("the manipulator's specifications are not known yet")?;
                let mid = chain.mid_range();
                (chain, mid)
            }
        };
        let mut solver = IkSolver::new(chain.dof());
        let mut q = vec![0.0; chain.dof()];
        listing::elements(
            lists,
            start,
            SetEndEffectorPose::CODE,
            "Set End Effector Pose",
            |m| {
                let Message::SetEndEffectorPose(m) = m else {
                    return Err("not a Set End Effector Pose".into());
                };
                let at = pose_of(
                    m.tool_point_x,
                    m.tool_point_y,
                    m.tool_point_z,
                    m.quaternion_d,
                    m.quaternion_a,
                    m.quaternion_b,
                    m.quaternion_c,
                )
                .map_err(|e| e.to_string())?;
                solver.solve(&chain, &at, &seed, &mut q).map_err(|e| {
                    let p = at.translation.vector;
                    format!("pose at ({:.4}, {:.4}, {:.4}) m: {e}", p.x, p.y, p.z)
                })?;
                seed.copy_from_slice(&q);
                Ok(PoseStep {
                    pose: m.clone(),
                    at,
                })
            },
        )
    }
}

impl generated::ManipulatorEndEffectorPoseListDriver for On<'_, PoseList> {
    fn send_report_commanded_end_effector_pose(&mut self, transport: &Receive) {
        let list = &self.svc.list;
        let commanded = list.target().map(|(_, s)| &s.pose);
        match commanded_pose(self.env, &list.arm, commanded) {
            Ok(report) => self.reply(transport, report),
            Err(why) => self.refuse(why),
        }
    }

    fn execute_target_list(&mut self, msg: &ManipulatorExecuteList) {
        let Some(start) = start_of(self.lists, msg) else {
            return self.refuse("Manipulator Execute List: no such element");
        };
        let list = match self.svc.check(self.env, self.lists, start) {
            Ok(l) => l,
            Err(why) => return self.refuse(format!("Manipulator Execute List: {why}")),
        };
        let Some((uid, first)) = list.first() else {
            return self.refuse("Manipulator Execute List: no elements from there");
        };
        tracing::info!(service = %ID, first = uid, elements = list.len(), "list executed");
        let command = ra33_pose(&first.pose);
        self.svc.list.start(self.env, self.now, list, command);
    }
}
