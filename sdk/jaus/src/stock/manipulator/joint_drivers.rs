//! The joint-space drivers: Joint Positions Driver (54, Part 1 §5.4.6), Joint
//! Velocities Driver (56, §5.4.8) and Joint Move Driver (58, §5.4.10).

use std::time::Instant;

use super::driver::{check_joints, slew, Goal, RateSmoother, StockArmDriver};
use super::link::ArmLink;
use super::profile::{JointMove, JointSet, SynchronisedMove};
use crate::component::{Refused, StopReason};
use crate::components::parts::ManipulatorDriver;
use crate::components::{
    manipulator_joint_move_driver as jmd, manipulator_joint_positions_driver as jpd,
    manipulator_joint_velocities_driver as jvd,
};
use crate::messages::*;

/// Joint positions the reference moves to on a synchronised rest-to-rest, jerk-limited
/// profile ([`SynchronisedMove`]): each joint within a fraction
/// ([`speed_fraction`](super::link::ArmDriverConfig::speed_fraction)) of its rate and its
/// acceleration limit ([`acceleration_time`](super::link::ArmDriverConfig::acceleration_time)),
/// smoothed over [`jerk_time`](super::link::ArmDriverConfig::jerk_time), all arriving
/// together, decelerating into the target; then the target is held. A new target starts
/// from the reference where it is (from rest).
#[derive(Debug, Default)]
pub struct JointTarget {
    target: Option<Vec<f64>>,
    plan: Option<(Instant, SynchronisedMove)>,
    reference: Option<Vec<f64>>,
    arrived: bool,
}

impl JointTarget {
    /// Sets a new target (the profile starts on the next control period from the
    /// reference, or from where the arm is).
    pub fn set(&mut self, target: Vec<f64>) {
        self.target = Some(target);
        self.plan = None;
        self.arrived = false;
    }

    /// The target, if any.
    pub fn target(&self) -> Option<&[f64]> {
        self.target.as_deref()
    }

    /// Whether the reference has reached the target.
    pub fn arrived(&self) -> bool {
        self.arrived
    }
}

impl Goal for JointTarget {
    fn reference(
        &mut self,
        link: &ArmLink,
        now: Instant,
        q: &[f64],
        q_ref: &mut [f64],
        qd_ref: &mut [f64],
    ) -> bool {
        let (Some(target), Some(chain)) = (&self.target, link.chain()) else {
            return false;
        };
        if target.len() != q.len() || chain.dof() != q.len() {
            return false;
        }
        if self.arrived {
            q_ref.copy_from_slice(target);
            qd_ref.iter_mut().for_each(|v| *v = 0.0);
            return true;
        }
        if self.plan.is_none() {
            let start = match &self.reference {
                Some(r) if r.len() == q.len() => r.clone(),
                _ => q.to_vec(),
            };
            let fraction = link.config.speed_fraction;
            let ramp = link.config.acceleration_time.as_secs_f64();
            let limits = |j: usize| {
                let rate = chain.joints[j].max_rate;
                (rate * fraction, rate / ramp)
            };
            let smoothing = link.config.jerk_time.as_secs_f64();
            match SynchronisedMove::plan(&start, target, limits, smoothing) {
                Ok(plan) => self.plan = Some((now, plan)),
                Err(e) => {
                    // Only bad settings get here (the target is within the limits).
                    tracing::warn!("joint target: no profile ({e}); holding");
                    q_ref.copy_from_slice(&start);
                    qd_ref.iter_mut().for_each(|v| *v = 0.0);
                    self.reference = Some(start);
                    return true;
                }
            }
        }
        let Some((t0, plan)) = &self.plan else {
            return false;
        };
        let t = now.saturating_duration_since(*t0).as_secs_f64();
        plan.sample(t, q_ref, qd_ref);
        if t >= plan.duration() {
            self.plan = None;
            self.arrived = true;
        }
        self.reference = Some(q_ref.to_vec());
        true
    }

    fn clear(&mut self) {
        *self = JointTarget::default();
    }
}

/// The Joint Positions Driver.
pub type StockJointPositionsDriver = StockArmDriver<JointTarget>;

impl jpd::ManipulatorJointPositionsDriver for StockJointPositionsDriver {
    fn manipulator_driver(&mut self) -> Option<&mut dyn ManipulatorDriver<jpd::Interface>> {
        Some(self)
    }

    fn stop(&mut self, ctx: &mut jpd::Ctx<'_>, reason: StopReason) {
        self.stop_for(ctx, reason);
    }

    fn on_set_joint_positions(
        &mut self,
        _ctx: &mut jpd::Ctx<'_>,
        m: &SetJointPositions,
    ) -> Result<(), Refused> {
        let chain = self.link.arm()?;
        let dof = chain.dof();
        check_joints(
            &m.joint_position,
            dof,
            "joint_position",
            |j| (chain.joints[j].min, chain.joints[j].max),
            "rad|m",
        )?;
        self.goal.set(m.joint_position.clone());
        Ok(())
    }
}

/// Joint velocities held while the command is fresh; the position reference integrates
/// them, its rates changing within each joint's acceleration limit, smoothed over the
/// drivers' jerk time (it slows to a stop when the command goes stale).
#[derive(Debug, Default)]
pub struct JointRates {
    command: Option<(Instant, Vec<f64>)>,
    reference: Option<Vec<f64>>,
    rates: Vec<f64>,
    smoother: RateSmoother,
    smoothed: Vec<f64>,
    last: Option<Instant>,
}

impl JointRates {
    /// Sets the commanded velocities at `now`.
    pub fn set(&mut self, now: Instant, rates: Vec<f64>) {
        self.command = Some((now, rates));
    }

    /// The commanded velocities, if any.
    pub fn command(&self) -> Option<&[f64]> {
        self.command.as_ref().map(|c| c.1.as_slice())
    }
}

impl Goal for JointRates {
    fn reference(
        &mut self,
        link: &ArmLink,
        now: Instant,
        q: &[f64],
        q_ref: &mut [f64],
        qd_ref: &mut [f64],
    ) -> bool {
        let Some(chain) = link.chain() else {
            return false;
        };
        let n = q.len();
        if chain.dof() != n {
            *self = JointRates::default();
            return false;
        }
        let fresh = matches!(&self.command, Some((t, v))
            if v.len() == n
                && now.saturating_duration_since(*t) <= link.config.command_timeout);
        if !fresh && self.command.take().is_some() {
            tracing::info!("joint velocity command not refreshed; stopping");
        }
        if self.command.is_none() && !self.rates.iter().any(|v| *v != 0.0) && self.smoother.still()
        {
            *self = JointRates::default();
            return false;
        }
        let dt = self.last.map_or(0.0, |t| {
            now.saturating_duration_since(t).as_secs_f64().min(0.1)
        });
        self.last = Some(now);
        if self.rates.len() != n {
            self.rates = vec![0.0; n];
        }
        let desired = self
            .command
            .as_ref()
            .map_or_else(|| vec![0.0; n], |c| c.1.clone());
        let ramp = link.config.acceleration_time.as_secs_f64();
        slew(&mut self.rates, &desired, dt, |j| {
            chain.joints[j].max_rate / ramp
        });
        self.smoothed.resize(n, 0.0);
        self.smoother
            .smooth(now, &self.rates, link.config.jerk_time, &mut self.smoothed);
        let r = self.reference.get_or_insert_with(|| q.to_vec());
        if r.len() != n {
            *r = q.to_vec();
        }
        for (r, v) in r.iter_mut().zip(&self.smoothed) {
            *r += v * dt;
        }
        q_ref.copy_from_slice(r);
        qd_ref.copy_from_slice(&self.smoothed);
        true
    }

    fn clear(&mut self) {
        *self = JointRates::default();
    }
}

/// The Joint Velocities Driver. Its interface has no joint positions, so it integrates
/// the measured velocities: joint limits are the Primitive Manipulator's and the arm's.
pub type StockJointVelocitiesDriver = StockArmDriver<JointRates>;

impl jvd::ManipulatorJointVelocitiesDriver for StockJointVelocitiesDriver {
    fn manipulator_driver(&mut self) -> Option<&mut dyn ManipulatorDriver<jvd::Interface>> {
        Some(self)
    }

    fn stop(&mut self, ctx: &mut jvd::Ctx<'_>, reason: StopReason) {
        self.stop_for(ctx, reason);
    }

    fn on_set_joint_velocities(
        &mut self,
        ctx: &mut jvd::Ctx<'_>,
        m: &SetJointVelocities,
    ) -> Result<(), Refused> {
        let chain = self.link.arm()?;
        let dof = chain.dof();
        check_joints(
            &m.joint_velocity,
            dof,
            "joint_velocity",
            |j| (-chain.joints[j].max_rate, chain.joints[j].max_rate),
            "rad/s|m/s",
        )?;
        self.goal.set(ctx.now(), m.joint_velocity.clone());
        Ok(())
    }
}

/// A planned joint move and when it started.
#[derive(Debug, Default)]
pub struct JointMotion {
    plan: Option<(Instant, JointMove)>,
    finished: bool,
    last_target: Option<Vec<f64>>,
}

impl JointMotion {
    /// Whether a move is being executed.
    pub fn moving(&self) -> bool {
        self.plan.is_some()
    }

    /// The joint positions the last move ends at (held afterwards).
    pub fn final_positions(&self) -> Option<&[f64]> {
        self.last_target.as_deref()
    }
}

impl Goal for JointMotion {
    fn reference(
        &mut self,
        _link: &ArmLink,
        now: Instant,
        q: &[f64],
        q_ref: &mut [f64],
        qd_ref: &mut [f64],
    ) -> bool {
        if let Some((start, plan)) = &self.plan {
            let t = now.saturating_duration_since(*start).as_secs_f64();
            plan.sample(t, q_ref, qd_ref);
            if t >= plan.duration() {
                self.plan = None;
                self.finished = true;
            }
            return true;
        }
        match &self.last_target {
            Some(target) if target.len() == q.len() => {
                q_ref.copy_from_slice(target);
                qd_ref.iter_mut().for_each(|v| *v = 0.0);
                true
            }
            _ => false,
        }
    }

    fn clear(&mut self) {
        *self = JointMotion::default();
    }

    fn take_finished(&mut self) -> bool {
        std::mem::take(&mut self.finished)
    }
}

/// The Joint Move Driver: each joint set of Set Joint Motion reached at its time, on
/// trapezoidal profiles within the given velocity, acceleration and deceleration (capped
/// by the joint's rate and acceleration limits), smoothed over the drivers' jerk time so
/// each joint decelerates gently into the last set.
pub type StockJointMoveDriver = StockArmDriver<JointMotion>;

impl jmd::ManipulatorJointMoveDriver for StockJointMoveDriver {
    fn manipulator_driver(&mut self) -> Option<&mut dyn ManipulatorDriver<jmd::Interface>> {
        Some(self)
    }

    fn stop(&mut self, ctx: &mut jmd::Ctx<'_>, reason: StopReason) {
        self.stop_for(ctx, reason);
    }

    fn on_set_joint_motion(
        &mut self,
        ctx: &mut jmd::Ctx<'_>,
        m: &SetJointMotion,
    ) -> Result<(), Refused> {
        let chain = self.link.arm()?;
        let dof = chain.dof();
        if m.poses.is_empty() {
            return Err(Refused::Invalid("Set Joint Motion has no poses".into()));
        }
        let mut sets = Vec::with_capacity(m.poses.len());
        for (i, pose) in m.poses.iter().enumerate() {
            let positions: Vec<f64> = pose.joints.iter().map(|j| j.position).collect();
            check_joints(
                &positions,
                dof,
                "poses[].joints[].position",
                |j| (chain.joints[j].min, chain.joints[j].max),
                "rad|m",
            )
            .map_err(|e| Refused::Invalid(format!("pose {i}: {e}")))?;
            sets.push(JointSet {
                time: pose.pose_time,
                joints: pose
                    .joints
                    .iter()
                    .enumerate()
                    .map(|(j, l)| {
                        // The joint's own rate and acceleration limits cap the move's.
                        let rate = chain.joints[j].max_rate;
                        let accel = rate / self.link.config.acceleration_time.as_secs_f64();
                        let v = l.max_velocity.abs().min(rate);
                        let a = l.max_acceleration.abs().min(accel);
                        let d = l.max_deceleration.abs().min(accel);
                        (l.position, v, a, d)
                    })
                    .collect(),
            });
        }
        let start = self.link.start_positions(ctx.now())?;
        let plan = JointMove::plan(&start, &sets)
            .map_err(|e| Refused::Invalid(e.to_string()))?
            .smoothed(self.link.config.jerk_time.as_secs_f64());
        if ctx.mode() == jmd::Mode::Idle {
            ctx.transition(jmd::Transition::Start)
                .map_err(|e| Refused::Invalid(e.to_string()))?;
        }
        self.goal.last_target = sets.last().map(|s| s.joints.iter().map(|j| j.0).collect());
        self.goal.plan = Some((ctx.now(), plan));
        Ok(())
    }

    fn tick(&mut self, ctx: &mut jmd::Ctx<'_>) {
        self.run(ctx);
        if self.goal.take_finished() && ctx.mode() == jmd::Mode::Moving {
            let _ = ctx.transition(jmd::Transition::Finish);
        }
    }
}
