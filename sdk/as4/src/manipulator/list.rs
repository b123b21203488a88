//! The Joint Position List Driver over the RA 3.3 Joint Move Driver (58): the
//! component's list of Set Joint Positions elements, from the element Manipulator
//! Execute List names (or the head), becomes one RA 3.3 Set Joint Motion of as many
//! poses, each joint moving on its own trapezoid and every pose reached at the time the
//! gateway plans for it.
//!
//! Each element must be a Set Joint Positions for the arm's chain (one value per joint,
//! of its joint's kind, within its range): `isListValid` checks the whole list, and a
//! list that is not valid is refused (logged with the element and why). The time of
//! each pose is what the slowest joint needs from the pose before at [`SPEED_FRACTION`]
//! of its rate and an acceleration of its rate per [`RAMP`] (the limits Report
//! Manipulator Specifications gives; the RA 3.3 driver caps them by its own), with
//! [`MARGIN`] more. The element being driven to (Query Manipulator Active Element,
//! Query Commanded Joint Positions) is the first whose time has not passed; once the
//! last one's has, with [`MARGIN`], the list is done and no target exists.
//!
//! The list is the component's one List Manager's (the Mobility list drivers' too): a
//! list of waypoints is theirs, one of joint positions this driver's, one of
//! end-effector poses the End-Effector Pose List Driver's ([`super::pose_list`]; what
//! the two share is in `listing.rs`). Query Commanded Joint Positions is this
//! driver's while it drives a list, the Joint Position Driver's otherwise. A command
//! event of Execute List runs until the list is done.

use std::time::Instant;

use jaus::messages as ra;
use jaus::stock::manipulator::kinematics::Chain;
use jaus::{Address, JausMessage};

use super::listing::{self, list_driver, start_of, ListDriving, Listing};
use super::{ra33_positions, Arm, ServiceIds};
use crate::core::lists::Lists;
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::manipulator_joint_position_list_driver as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{
    JointPosition, ManipulatorExecuteList, QueryCommandedJointPositions,
    ReportCommandedJointPositions, SetJointPositions,
};
use crate::ra33::Ra33Side;
use crate::service::{Cx, ServiceId};
use crate::{ComponentState, Message};

/// Fraction of each joint's rate a list moves it at.
pub const SPEED_FRACTION: f64 = 0.5;
/// Time a joint takes to reach its full rate.
pub const RAMP: f64 = 0.5;
/// Time added to each pose's, and after the last before the list is done.
pub const MARGIN: f64 = 0.5;

machined!(
    JointList,
    manipulator_joint_position_list_driver,
    ServiceIds::JOINT_POSITION_LIST_DRIVER,
    list_manager {
        fn claims(&self, lists: &Lists, message: &Message) -> bool {
            // The Joint Position Driver answers for the commanded joints when no list
            // is being driven; the End-Effector Pose List Driver for a list of poses.
            self.list
                .claims(lists, message, QueryCommandedJointPositions::CODE)
        }
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            let now = cx.now;
            self.advance(cx.env, now);
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
list_driver!(JointList);

/// The Joint Position List Driver over an RA 3.3 Joint Move Driver.
pub type JointPositionListDriver = OnMachines<JointList>;

/// One element of a list of joint positions: its AS-4 joint positions, the RA 3.3 joint
/// values, the time (s from the start) it is reached at.
#[derive(Debug, Clone)]
pub(super) struct JointStep {
    positions: Vec<JointPosition>,
    q: Vec<f64>,
    at: f64,
}

/// The Joint Position List Driver's data: the list driven over the RA 3.3 Joint Move
/// Driver.
#[derive(Debug)]
pub struct JointList {
    list: Listing<JointStep>,
}

impl JointPositionListDriver {
    /// The service over the RA 3.3 Joint Move Driver at `driver`.
    pub fn new(driver: Address, arm: Arm) -> Self {
        OnMachines::from_impl(JointList {
            list: Listing::new(ID, SetJointPositions::CODE, driver, arm),
        })
    }
}

const ID: ServiceId = ServiceIds::JOINT_POSITION_LIST_DRIVER;

impl JointList {
    /// Sends the command waiting for RA 3.3 control, and follows the run at `now`: the
    /// elements whose time has passed are reached; the list is done [`MARGIN`] after
    /// the last; it ends when another driver took the arm.
    fn advance(&mut self, env: &mut Ra33Side, now: Instant) {
        let Some(run) = self.list.follow(env) else {
            return;
        };
        let t = now.saturating_duration_since(run.started).as_secs_f64();
        while run.targets.get(run.active).is_some_and(|s| t > s.at) {
            run.reach(ID);
        }
        let end = run.targets.last().map_or(0.0, |s| s.at) + MARGIN;
        if run.all_reached() && t > end {
            self.list.finish();
        }
    }
}

impl ListDriving for JointList {
    type Target = JointStep;
    const ID: ServiceId = ID;

    fn listing(&self) -> &Listing<JointStep> {
        &self.list
    }

    /// Each element a Set Joint Positions for the arm's chain: one value per joint, of
    /// its joint's kind, within its range; 255 at most (what Set Joint Motion carries).
    fn check(
        &self,
        env: &Ra33Side,
        lists: &Lists,
        start: u16,
    ) -> Result<Vec<(u16, JointStep)>, String> {
        let chain = self
            .list
            .arm
            .chain(env)
            .ok_or("the manipulator's specifications are not known yet")?;
        let out = listing::elements(
            lists,
            start,
            SetJointPositions::CODE,
            "Set Joint Positions",
            |m| {
                let Message::SetJointPositions(m) = m else {
                    return Err("not a Set Joint Positions".into());
                };
                let q = ra33_positions(&chain, &m.joint_positions)?;
                if !chain.within_limits(&q) {
                    return Err(format!(
                        "joint positions {q:?} beyond the manipulator's limits"
                    ));
                }
                Ok(JointStep {
                    positions: m.joint_positions.clone(),
                    q,
                    at: 0.0,
                })
            },
        )?;
        if out.len() > usize::from(u8::MAX) {
            return Err(format!(
                "{} elements: Set Joint Motion carries 255 poses at most",
                out.len()
            ));
        }
        Ok(out)
    }
}

/// Seconds joint `j` of `chain` needs from `from` to `to`, rest to rest, at
/// [`SPEED_FRACTION`] of its rate and its rate per [`RAMP`] of acceleration.
fn segment_time(chain: &Chain, j: usize, from: f64, to: f64) -> f64 {
    let rate = chain.joints[j].max_rate;
    let (v, a) = (SPEED_FRACTION * rate, rate / RAMP);
    let d = (to - from).abs();
    if d <= v * v / a {
        2.0 * (d / a).sqrt()
    } else {
        d / v + v / a
    }
}

/// RA 3.3 Set Joint Motion through `steps` from `start`: each pose at the time the
/// slowest joint needs ([`segment_time`]) plus [`MARGIN`] (written into the step), the
/// joints' limits those of [`segment_time`].
fn joint_motion(
    chain: &Chain,
    start: &[f64],
    steps: &mut [(u16, JointStep)],
) -> ra::SetJointMotion {
    let mut out = Vec::with_capacity(steps.len());
    let (mut t, mut from) = (0.0, start.to_vec());
    for (_, step) in steps.iter_mut() {
        let q = &step.q;
        let need = (0..chain.dof())
            .map(|j| segment_time(chain, j, from[j], q[j]))
            .fold(0.0, f64::max);
        t += need + MARGIN;
        step.at = t;
        out.push(ra::JointMotionPose {
            pose_time: t,
            joints: q
                .iter()
                .zip(&chain.joints)
                .map(|(&position, joint)| ra::JointMotionLimits {
                    position,
                    max_velocity: SPEED_FRACTION * joint.max_rate,
                    max_acceleration: joint.max_rate / RAMP,
                    max_deceleration: joint.max_rate / RAMP,
                })
                .collect(),
        });
        from.clone_from(q);
    }
    ra::SetJointMotion {
        num_joints: u8::try_from(chain.dof()).unwrap_or(u8::MAX),
        num_poses: u8::try_from(out.len()).unwrap_or(u8::MAX),
        poses: out,
    }
}

impl generated::ManipulatorJointPositionListDriver for On<'_, JointList> {
    fn target_exists(&self) -> bool {
        self.svc.list.target().is_some()
    }

    fn send_report_commanded_joint_positions(&mut self, transport: &Receive) {
        let joint_positions = self
            .svc
            .list
            .target()
            .map(|(_, s)| s.positions.clone())
            .unwrap_or_default();
        self.reply(transport, ReportCommandedJointPositions { joint_positions });
    }

    fn execute_target_list(&mut self, msg: &ManipulatorExecuteList) {
        let Some(chain) = self.svc.list.arm.chain(self.env) else {
            return self.refuse("the manipulator's specifications are not known yet");
        };
        let Some(start) = start_of(self.lists, msg) else {
            return self.refuse("Manipulator Execute List: no such element");
        };
        let mut list = match self.svc.check(self.env, self.lists, start) {
            Ok(l) => l,
            Err(why) => return self.refuse(format!("Manipulator Execute List: {why}")),
        };
        let Some(q0) = self
            .svc
            .list
            .arm
            .joints_from
            .and_then(|s| super::sensors::measured(self.env, s))
            .filter(|q| q.len() == chain.dof())
            .map(<[f64]>::to_vec)
        else {
            return self.refuse("no joint positions from the RA 3.3 joint position sensor yet");
        };
        let motion = joint_motion(&chain, &q0, &mut list);
        tracing::info!(
            service = %ID,
            elements = list.len(),
            seconds = list.last().map_or(0.0, |s| s.1.at),
            "list executed"
        );
        self.svc.list.start(self.env, self.now, list, motion.into());
    }
}
