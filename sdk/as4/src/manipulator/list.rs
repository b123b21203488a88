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
//! list of waypoints is theirs, one of joint positions this driver's. Query Commanded
//! Joint Positions is this driver's while it drives a list, the Joint Position Driver's
//! otherwise.

use std::time::Instant;

use jaus::messages as ra;
use jaus::stock::manipulator::kinematics::Chain;
use jaus::Address;

use super::drivers::{deliver, flush};
use super::{ra33_positions, Arm, ServiceIds};
use crate::core::lists::Lists;
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::manipulator_joint_position_list_driver as generated;
use crate::messages::services::manipulator_list_driver as parent;
use crate::messages::services::transport::event::Receive;
use crate::messages::{
    JointPosition, ManipulatorExecuteList, ReportCommandedJointPositions,
    ReportManipulatorActiveElement,
};
use crate::ra33::Ra33Side;
use crate::service::Cx;
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
        fn claims(&self, _lists: &Lists, message: &Message) -> bool {
            // The Joint Position Driver answers for the commanded joints when no list
            // is being driven.
            !matches!(message, Message::QueryCommandedJointPositions(_))
                || self.target().is_some()
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
                self.run = None;
                self.pending = None;
            }
        }
    }
);

/// The Joint Position List Driver over an RA 3.3 Joint Move Driver.
pub type JointPositionListDriver = OnMachines<JointList>;

/// A list being driven: the elements' UIDs and joint positions, the time (s from the
/// start) each is reached at, the one being driven to.
#[derive(Debug)]
struct Run {
    uids: Vec<u16>,
    targets: Vec<Vec<JointPosition>>,
    times: Vec<f64>,
    active: usize,
    started: Instant,
}

/// The Joint Position List Driver's data: the RA 3.3 driver, the arm, the list being
/// driven, a command waiting for RA 3.3 control.
#[derive(Debug)]
pub struct JointList {
    driver: Address,
    arm: Arm,
    run: Option<Run>,
    pending: Option<ra::Message>,
}

impl JointPositionListDriver {
    /// The service over the RA 3.3 Joint Move Driver at `driver`.
    pub fn new(driver: Address, arm: Arm) -> Self {
        OnMachines::from_impl(JointList {
            driver,
            arm,
            run: None,
            pending: None,
        })
    }
}

impl JointList {
    /// Sends the command waiting for RA 3.3 control, and follows the run at `now`: the
    /// elements whose time has passed are reached; the list is done [`MARGIN`] after
    /// the last; it ends when another driver took the arm.
    fn advance(&mut self, env: &mut Ra33Side, now: Instant) {
        const ID: crate::service::ServiceId = ServiceIds::JOINT_POSITION_LIST_DRIVER;
        flush(env, self.driver, &mut self.pending);
        if self.run.is_some() && !env.is_active(self.driver) {
            // The RA 3.3 Joint Move Driver is in standby: the list is not driven.
            tracing::info!(service = %ID, "list ended: the arm was given to another driver");
            self.run = None;
        }
        let Some(run) = self.run.as_mut() else {
            return;
        };
        let t = now.saturating_duration_since(run.started).as_secs_f64();
        while run.active < run.times.len() && t > run.times[run.active] {
            tracing::info!(service = %ID, uid = run.uids[run.active], "element reached");
            run.active += 1;
        }
        let end = run.times.last().copied().unwrap_or(0.0) + MARGIN;
        if run.active == run.times.len() && t > end {
            tracing::info!(service = %ID, "list finished");
            self.run = None;
        }
    }

    /// The element being driven to: its UID and joint positions.
    fn target(&self) -> Option<(u16, &[JointPosition])> {
        let run = self.run.as_ref()?;
        let i = run.active.min(run.uids.len().checked_sub(1)?);
        Some((run.uids[i], &run.targets[i]))
    }
}

/// The UID a Manipulator Execute List starts from: the one it names, else the list's
/// head; `None` when the list holds no such element.
fn start_of(lists: &Lists, e: &ManipulatorExecuteList) -> Option<u16> {
    match e.element_uid {
        Some(uid) => lists.get(uid).map(|_| uid),
        None => lists.head(),
    }
}

/// One element of the list: its UID, its AS-4 joint positions, the RA 3.3 joint values.
type Target = (u16, Vec<JointPosition>, Vec<f64>);

/// The elements of the list from `start`, or why one is not a joint position of the
/// arm.
fn elements(lists: &Lists, start: u16, chain: &Chain) -> Result<Vec<Target>, String> {
    let mut out = Vec::new();
    for el in lists.iter_from(start) {
        let Some(Ok(Message::SetJointPositions(m))) = el.message() else {
            return Err(format!("element {} is not a Set Joint Positions", el.uid));
        };
        let q = ra33_positions(chain, &m.joint_positions)
            .map_err(|why| format!("element {}: {why}", el.uid))?;
        if !chain.within_limits(&q) {
            return Err(format!(
                "element {}: joint positions {q:?} beyond the manipulator's limits",
                el.uid
            ));
        }
        out.push((el.uid, m.joint_positions, q));
    }
    if out.len() > usize::from(u8::MAX) {
        return Err(format!(
            "{} elements: Set Joint Motion carries 255 poses at most",
            out.len()
        ));
    }
    Ok(out)
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

/// RA 3.3 Set Joint Motion through `poses` from `start`: each pose at the time the
/// slowest joint needs ([`segment_time`]) plus [`MARGIN`], the joints' limits those of
/// [`segment_time`]; the poses' times (s from the start).
fn joint_motion(
    chain: &Chain,
    start: &[f64],
    poses: &[Vec<f64>],
) -> (ra::SetJointMotion, Vec<f64>) {
    let mut times = Vec::with_capacity(poses.len());
    let mut out = Vec::with_capacity(poses.len());
    let (mut t, mut from) = (0.0, start.to_vec());
    for q in poses {
        let need = (0..chain.dof())
            .map(|j| segment_time(chain, j, from[j], q[j]))
            .fold(0.0, f64::max);
        t += need + MARGIN;
        times.push(t);
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
    let motion = ra::SetJointMotion {
        num_joints: u8::try_from(chain.dof()).unwrap_or(u8::MAX),
        num_poses: u8::try_from(out.len()).unwrap_or(u8::MAX),
        poses: out,
    };
    (motion, times)
}

impl parent::ManipulatorListDriver for On<'_, JointList> {
    fn element_exists(&self, msg: &ManipulatorExecuteList) -> bool {
        start_of(self.lists, msg).is_some()
    }

    fn is_list_valid(&self) -> bool {
        let (Some(chain), Some(head)) = (self.svc.arm.chain(self.env), self.lists.head()) else {
            return false;
        };
        match elements(self.lists, head, &chain) {
            Ok(_) => true,
            Err(why) => {
                tracing::info!(service = %ServiceIds::JOINT_POSITION_LIST_DRIVER, "list not valid: {why}");
                false
            }
        }
    }

    fn send_report_manipulator_active_element(&mut self, transport: &Receive) {
        let element_uid = self.svc.target().map_or(0, |(uid, _)| uid);
        self.reply(transport, ReportManipulatorActiveElement { element_uid });
    }
}

impl generated::ManipulatorJointPositionListDriver for On<'_, JointList> {
    fn target_exists(&self) -> bool {
        self.svc.target().is_some()
    }

    fn send_report_commanded_joint_positions(&mut self, transport: &Receive) {
        let joint_positions = self
            .svc
            .target()
            .map(|(_, q)| q.to_vec())
            .unwrap_or_default();
        self.reply(transport, ReportCommandedJointPositions { joint_positions });
    }

    fn execute_target_list(&mut self, msg: &ManipulatorExecuteList) {
        let Some(chain) = self.svc.arm.chain(self.env) else {
            return self.refuse("the manipulator's specifications are not known yet");
        };
        let Some(start) = start_of(self.lists, msg) else {
            return self.refuse("Manipulator Execute List: no such element");
        };
        let list = match elements(self.lists, start, &chain) {
            Ok(l) => l,
            Err(why) => return self.refuse(format!("Manipulator Execute List: {why}")),
        };
        let Some(q0) = self
            .svc
            .arm
            .joints_from
            .and_then(|s| super::sensors::measured(self.env, s))
            .filter(|q| q.len() == chain.dof())
            .map(<[f64]>::to_vec)
        else {
            return self.refuse("no joint positions from the RA 3.3 joint position sensor yet");
        };
        let poses: Vec<Vec<f64>> = list.iter().map(|e| e.2.clone()).collect();
        let (motion, times) = joint_motion(&chain, &q0, &poses);
        tracing::info!(
            service = %ServiceIds::JOINT_POSITION_LIST_DRIVER,
            elements = list.len(),
            seconds = times.last().copied().unwrap_or(0.0),
            "list executed"
        );
        self.svc.run = Some(Run {
            uids: list.iter().map(|e| e.0).collect(),
            targets: list.into_iter().map(|e| e.1).collect(),
            times,
            active: 0,
            started: self.now,
        });
        deliver(
            self.env,
            self.svc.driver,
            motion.into(),
            &mut self.svc.pending,
        );
    }
}
