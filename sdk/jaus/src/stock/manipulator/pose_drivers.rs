//! The end-effector drivers: End-Effector Pose Driver (55, Part 1 §5.4.7), End-Effector
//! Velocity State Driver (57, §5.4.9) and End-Effector Discrete Pose Driver (59,
//! §5.4.11). Poses are in the vehicle frame; each is turned into joint positions by
//! inverse kinematics and then driven like a joint target. The pose driver's poses are
//! of its tool point (Set Tool Point); the other two have no tool point in their
//! interface, so theirs are of the end-effector frame.

use std::time::Instant;

use nalgebra::{Dyn, Isometry3, Matrix6, OMatrix, Quaternion, Translation3, UnitQuaternion, U6};
use nalgebra::{Vector3, Vector6};

use super::driver::{slew, Goal, RateSmoother, StockArmDriver};
use super::joint_drivers::JointTarget;
use super::kinematics::{Chain, IkSolver};
use super::link::ArmLink;
use super::profile::PosePath;
use crate::component::{Refused, StopReason};
use crate::components::parts::ManipulatorDriver;
use crate::components::{
    manipulator_end_effector_discrete_pose_driver as dpd,
    manipulator_end_effector_pose_driver as epd,
    manipulator_end_effector_velocity_state_driver as evd,
};
use crate::messages::*;

/// The pose of position `x, y, z` (m) and quaternion `d` (scalar), `a, b, c`; refused
/// unless finite and the quaternion has a usable length.
pub fn pose_of(
    x: f64,
    y: f64,
    z: f64,
    d: f64,
    a: f64,
    b: f64,
    c: f64,
) -> Result<Isometry3<f64>, Refused> {
    if ![x, y, z, d, a, b, c].iter().all(|v| v.is_finite()) {
        return Err(Refused::Invalid(
            "pose has a value that is not a finite number".into(),
        ));
    }
    let q = Quaternion::new(d, a, b, c);
    if q.norm() < 0.5 {
        return Err(Refused::Invalid(format!(
            "pose quaternion (d {d}, a {a}, b {b}, c {c}) has length {:.3}, not 1",
            q.norm()
        )));
    }
    Ok(Isometry3::from_parts(
        Translation3::new(x, y, z),
        UnitQuaternion::from_quaternion(q),
    ))
}

fn solve(
    solver: &mut IkSolver,
    chain: &Chain,
    target: &Isometry3<f64>,
    seed: &[f64],
    what: &str,
) -> Result<Vec<f64>, Refused> {
    let mut out = vec![0.0; chain.dof()];
    solver.solve(chain, target, seed, &mut out).map_err(|e| {
        let p = target.translation.vector;
        Refused::Invalid(format!(
            "{what} at ({:.4}, {:.4}, {:.4}) m: {e}",
            p.x, p.y, p.z
        ))
    })?;
    Ok(out)
}

/// An end-effector pose, reached through its joint solution.
#[derive(Debug, Default)]
pub struct PoseTarget {
    joints: JointTarget,
    pose: Option<Isometry3<f64>>,
    solver: Option<IkSolver>,
}

impl PoseTarget {
    /// The pose commanded last (tool point in the vehicle frame).
    pub fn pose(&self) -> Option<Isometry3<f64>> {
        self.pose
    }

    /// The joint solution being driven to.
    pub fn joints(&self) -> Option<&[f64]> {
        self.joints.target()
    }
}

impl Goal for PoseTarget {
    fn reference(
        &mut self,
        link: &ArmLink,
        now: Instant,
        q: &[f64],
        q_ref: &mut [f64],
        qd_ref: &mut [f64],
    ) -> bool {
        self.joints.reference(link, now, q, q_ref, qd_ref)
    }

    fn clear(&mut self) {
        self.joints.clear();
        self.pose = None;
    }
}

/// The End-Effector Pose Driver.
pub type StockEndEffectorPoseDriver = StockArmDriver<PoseTarget>;

impl epd::ManipulatorEndEffectorPoseDriver for StockEndEffectorPoseDriver {
    fn manipulator_driver(&mut self) -> Option<&mut dyn ManipulatorDriver<epd::Interface>> {
        Some(self)
    }

    fn stop(&mut self, ctx: &mut epd::Ctx<'_>, reason: StopReason) {
        self.stop_for(ctx, reason);
    }

    fn on_set_tool_point(
        &mut self,
        _ctx: &mut epd::Ctx<'_>,
        m: &SetToolPoint,
    ) -> Result<(), Refused> {
        let t = Vector3::new(m.x, m.y, m.z);
        if !t.iter().all(|v| v.is_finite()) {
            return Err(Refused::Invalid("tool point is not finite".into()));
        }
        self.link.set_tool(t);
        Ok(())
    }

    fn on_query_tool_point(
        &mut self,
        _ctx: &mut epd::Ctx<'_>,
        _q: &QueryToolPoint,
    ) -> Result<ReportToolPoint, Refused> {
        let t = self.link.tool();
        Ok(ReportToolPoint {
            x: t.x,
            y: t.y,
            z: t.z,
        })
    }

    fn on_set_end_effector_pose(
        &mut self,
        ctx: &mut epd::Ctx<'_>,
        m: &SetEndEffectorPose,
    ) -> Result<(), Refused> {
        let chain = self.link.arm()?.clone();
        let target = pose_of(m.x, m.y, m.z, m.d, m.a, m.b, m.c)?;
        let seed = self
            .link
            .feedback(ctx.now())
            .map(|(q, _)| q.to_vec())
            .unwrap_or_else(|| chain.mid_range());
        let solver = self
            .goal
            .solver
            .get_or_insert_with(|| IkSolver::new(chain.dof()));
        let joints = solve(solver, &chain, &target, &seed, "end-effector pose")?;
        self.goal.joints.set(joints);
        self.goal.pose = Some(target);
        Ok(())
    }
}

/// The frame a velocity state is given in (the message's `coordinate_system`: this SDK
/// reads 1 as the vehicle frame and 2 as the end-effector frame, the two Part 1 names;
/// other values are refused).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VelocityFrame {
    /// The vehicle frame (1).
    Vehicle,
    /// The end-effector frame (2).
    EndEffector,
}

/// An end-effector velocity (linear m/s, angular rad/s) held while fresh; the joint
/// rates come from the damped pseudo-inverse of the Jacobian, scaled down together so
/// no joint exceeds its rate; the tool's velocity changes within the joints' acceleration
/// limits (smoothed over the drivers' jerk time); a joint stops at its limit.
#[derive(Debug, Default)]
pub struct ToolVelocity {
    command: Option<(Instant, VelocityFrame, Vector3<f64>, Vector3<f64>)>,
    reference: Option<Vec<f64>>,
    twist: Vector6<f64>,
    smoother: RateSmoother,
    last: Option<Instant>,
    jacobian: Option<OMatrix<f64, U6, Dyn>>,
}

/// Damping of the pseudo-inverse near singular configurations.
const DAMPING: f64 = 0.02;

impl ToolVelocity {
    /// The velocity commanded last: frame, linear (m/s), angular (rad/s).
    pub fn command(&self) -> Option<(VelocityFrame, Vector3<f64>, Vector3<f64>)> {
        self.command.map(|c| (c.1, c.2, c.3))
    }
}

impl ToolVelocity {
    /// The joint rates that give `twist` (vehicle frame: linear, angular) at the joint
    /// positions `r`, or `None` when the Jacobian cannot be inverted.
    fn rates_for(&mut self, chain: &Chain, twist: &Vector6<f64>, r: &[f64]) -> Option<Vec<f64>> {
        let n = chain.dof();
        let jac = self
            .jacobian
            .get_or_insert_with(|| OMatrix::<f64, U6, Dyn>::zeros(n));
        if jac.ncols() != n {
            *jac = OMatrix::<f64, U6, Dyn>::zeros(n);
        }
        chain.jacobian(r, jac);
        let jjt: Matrix6<f64> = &*jac * jac.transpose() + Matrix6::identity() * DAMPING * DAMPING;
        let w = jjt.cholesky().map(|c| c.solve(twist))?;
        Some((0..n).map(|j| jac.column(j).dot(&w)).collect())
    }
}

impl Goal for ToolVelocity {
    /// The tool's velocity follows the command with every joint's change of rate within
    /// its acceleration limit, smoothed over the drivers' jerk time (in the tool's space,
    /// so the joints stay coordinated): it speeds up into a command and slows down to a
    /// stop when the command is zero or went stale, rather than stepping.
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
        let n = chain.dof();
        if q.len() != n {
            *self = ToolVelocity::default();
            return false;
        }
        if self
            .command
            .is_some_and(|c| now.saturating_duration_since(c.0) > link.config.command_timeout)
        {
            tracing::info!("end-effector velocity command not refreshed; stopping");
            self.command = None;
        }
        let moving = self.twist.iter().any(|v| *v != 0.0) || !self.smoother.still();
        if self.command.is_none() && !moving {
            *self = ToolVelocity {
                jacobian: self.jacobian.take(),
                ..ToolVelocity::default()
            };
            return false;
        }
        let dt = self.last.map_or(0.0, |t| {
            now.saturating_duration_since(t).as_secs_f64().min(0.1)
        });
        self.last = Some(now);
        let mut r = self
            .reference
            .take()
            .filter(|r| r.len() == n)
            .unwrap_or_else(|| q.to_vec());
        let desired = match self.command {
            Some((_, frame, linear, angular)) => {
                let (linear, angular) = match frame {
                    VelocityFrame::Vehicle => (linear, angular),
                    VelocityFrame::EndEffector => {
                        let rot = chain.tool_pose(&r).rotation;
                        (rot * linear, rot * angular)
                    }
                };
                Vector6::new(
                    linear.x, linear.y, linear.z, angular.x, angular.y, angular.z,
                )
            }
            None => Vector6::zeros(),
        };
        // The change of twist this period, scaled so no joint's rate changes faster than
        // its acceleration limit.
        let change = desired - self.twist;
        let ramp = link.config.acceleration_time.as_secs_f64();
        if let Some(delta) = self.rates_for(chain, &change, &r) {
            let mut step = vec![0.0; n];
            slew(&mut step, &delta, dt, |j| chain.joints[j].max_rate / ramp);
            let scale = delta
                .iter()
                .zip(&step)
                .map(|(d, s)| if d.abs() > 0.0 { s / d } else { 1.0 })
                .fold(1.0, f64::min)
                .max(0.0);
            self.twist += change * scale;
        }
        let mut smoothed = [0.0; 6];
        self.smoother.smooth(
            now,
            self.twist.as_slice(),
            link.config.jerk_time,
            &mut smoothed,
        );
        let mut rates = self
            .rates_for(chain, &Vector6::from(smoothed), &r)
            .unwrap_or_else(|| vec![0.0; n]);
        let over = rates
            .iter()
            .enumerate()
            .map(|(j, v)| v.abs() / chain.joints[j].max_rate)
            .fold(1.0, f64::max);
        for (j, v) in rates.iter_mut().enumerate() {
            *v /= over;
            let next = r[j] + *v * dt;
            let joint = &chain.joints[j];
            if next < joint.min || next > joint.max {
                *v = 0.0;
            }
            r[j] += *v * dt;
            q_ref[j] = r[j];
            qd_ref[j] = *v;
        }
        self.reference = Some(r);
        true
    }

    fn clear(&mut self) {
        *self = ToolVelocity::default();
    }
}

/// The End-Effector Velocity State Driver.
pub type StockEndEffectorVelocityStateDriver = StockArmDriver<ToolVelocity>;

impl evd::ManipulatorEndEffectorVelocityStateDriver for StockEndEffectorVelocityStateDriver {
    fn manipulator_driver(&mut self) -> Option<&mut dyn ManipulatorDriver<evd::Interface>> {
        Some(self)
    }

    fn stop(&mut self, ctx: &mut evd::Ctx<'_>, reason: StopReason) {
        self.stop_for(ctx, reason);
    }

    fn on_set_end_effector_velocity_state(
        &mut self,
        ctx: &mut evd::Ctx<'_>,
        m: &SetEndEffectorVelocityState,
    ) -> Result<(), Refused> {
        self.link.arm()?;
        let frame = match m.coordinate_system {
            1 => VelocityFrame::Vehicle,
            2 => VelocityFrame::EndEffector,
            other => {
                return Err(Refused::Invalid(format!(
                    "coordinate_system = {other}: 1 (vehicle) or 2 (end effector) expected"
                )))
            }
        };
        let linear = Vector3::new(m.x_linear, m.y_linear, m.z_linear);
        let angular = Vector3::new(m.x_angular, m.y_angular, m.z_angular);
        if !linear.iter().chain(angular.iter()).all(|v| v.is_finite()) {
            return Err(Refused::Invalid("velocity state is not finite".into()));
        }
        self.goal.command = Some((ctx.now(), frame, linear, angular));
        Ok(())
    }
}

/// A timed end-effector path: the pose at each instant interpolated (position linearly,
/// orientation by slerp) from the pose where the move started, solved by inverse
/// kinematics from the previous instant's solution.
#[derive(Debug, Default)]
pub struct PathMotion {
    path: Option<(Instant, PosePath)>,
    solver: Option<IkSolver>,
    previous: Option<(Instant, Vec<f64>)>,
    hold: Option<Vec<f64>>,
    finished: bool,
    ik_failures: u64,
}

impl PathMotion {
    /// Whether a path is being executed.
    pub fn moving(&self) -> bool {
        self.path.is_some()
    }

    /// Instants at which the interpolated pose had no joint solution (the reference
    /// then holds).
    pub fn ik_failures(&self) -> u64 {
        self.ik_failures
    }
}

impl Goal for PathMotion {
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
        let Some((start, path)) = &self.path else {
            return match &self.hold {
                Some(h) if h.len() == q.len() => {
                    q_ref.copy_from_slice(h);
                    qd_ref.iter_mut().for_each(|v| *v = 0.0);
                    true
                }
                _ => false,
            };
        };
        let t = now.saturating_duration_since(*start).as_secs_f64();
        let pose = path.sample(t);
        let done = t >= path.duration();
        let solver = self
            .solver
            .get_or_insert_with(|| IkSolver::new(chain.dof()));
        let seed = self.previous.as_ref().map_or(q, |p| p.1.as_slice());
        let mut out = vec![0.0; chain.dof()];
        match solver.solve(chain, &pose, seed, &mut out) {
            Ok(_) => {
                let dt = self
                    .previous
                    .as_ref()
                    .map_or(0.0, |p| now.saturating_duration_since(p.0).as_secs_f64());
                for j in 0..out.len() {
                    q_ref[j] = out[j];
                    qd_ref[j] = match &self.previous {
                        Some((_, p)) if dt > 0.0 && !done => (out[j] - p[j]) / dt,
                        _ => 0.0,
                    };
                }
                self.previous = Some((now, out));
            }
            Err(_) => {
                self.ik_failures += 1;
                let hold = self.previous.as_ref().map_or(q, |p| p.1.as_slice());
                q_ref.copy_from_slice(hold);
                qd_ref.iter_mut().for_each(|v| *v = 0.0);
            }
        }
        if done {
            self.hold = Some(q_ref.to_vec());
            self.path = None;
            self.previous = None;
            self.finished = true;
        }
        true
    }

    fn clear(&mut self) {
        self.path = None;
        self.previous = None;
        self.hold = None;
        self.finished = false;
    }

    fn take_finished(&mut self) -> bool {
        std::mem::take(&mut self.finished)
    }
}

/// The End-Effector Discrete Pose Driver.
pub type StockEndEffectorDiscretePoseDriver = StockArmDriver<PathMotion>;

impl dpd::ManipulatorEndEffectorDiscretePoseDriver for StockEndEffectorDiscretePoseDriver {
    fn manipulator_driver(&mut self) -> Option<&mut dyn ManipulatorDriver<dpd::Interface>> {
        Some(self)
    }

    fn stop(&mut self, ctx: &mut dpd::Ctx<'_>, reason: StopReason) {
        self.stop_for(ctx, reason);
    }

    fn on_set_end_effector_path_motion(
        &mut self,
        ctx: &mut dpd::Ctx<'_>,
        m: &SetEndEffectorPathMotion,
    ) -> Result<(), Refused> {
        let chain = self.link.arm()?.clone();
        if m.poses.is_empty() {
            return Err(Refused::Invalid(
                "Set End Effector Path Motion has no poses".into(),
            ));
        }
        let q0 = self.link.start_positions(ctx.now())?;
        let mut targets = Vec::with_capacity(m.poses.len());
        for (i, p) in m.poses.iter().enumerate() {
            let pose = pose_of(p.x, p.y, p.z, p.d, p.a, p.b, p.c)
                .map_err(|e| Refused::Invalid(format!("pose {i}: {e}")))?;
            targets.push((p.pose_time, pose));
        }
        let path = PosePath::new(chain.tool_pose(&q0), targets)
            .map_err(|e| Refused::Invalid(e.to_string()))?;
        // Every pose must be reachable, and each within the joints' rates of the previous
        // one over its time.
        let solver = self
            .goal
            .solver
            .get_or_insert_with(|| IkSolver::new(chain.dof()));
        let (mut seed, mut t0) = (q0, 0.0);
        for (i, (t, pose)) in path.targets().iter().enumerate() {
            let q = solve(solver, &chain, pose, &seed, &format!("pose {i}"))?;
            for (j, joint) in chain.joints.iter().enumerate() {
                let rate = (q[j] - seed[j]).abs() / (t - t0);
                if rate > joint.max_rate {
                    return Err(Refused::Invalid(format!(
                        "pose {i}: joint {j} would move at {rate:.3}/s, above its limit {:.3}/s",
                        joint.max_rate
                    )));
                }
            }
            (seed, t0) = (q, *t);
        }
        if ctx.mode() == dpd::Mode::Idle {
            ctx.transition(dpd::Transition::Start)
                .map_err(|e| Refused::Invalid(e.to_string()))?;
        }
        self.goal.previous = None;
        self.goal.hold = None;
        self.goal.path = Some((ctx.now(), path));
        Ok(())
    }

    fn tick(&mut self, ctx: &mut dpd::Ctx<'_>) {
        self.run(ctx);
        if self.goal.take_finished() && ctx.mode() == dpd::Mode::Moving {
            let _ = ctx.transition(dpd::Transition::Finish);
        }
    }
}
