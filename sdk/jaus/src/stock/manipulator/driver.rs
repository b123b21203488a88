//! The closed-loop manipulator driver all six drivers of Part 1 §5.4.6–§5.4.11 are:
//! an [`ArmLink`] and a [`Goal`] that turns the command into a joint reference every
//! control period. While nothing is commanded (or a velocity command went stale) the
//! driver holds the arm where it is. On emergency, failure and shutdown it sets every
//! effort to zero; on Standby it stops commanding without a word and gives the Primitive
//! Manipulator back, whose holding controller keeps the arm where it is until the next
//! driver takes it (a hand-over without a moment of zero effort); when its own controller
//! lets it go it forgets the command and holds the arm where it is.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use super::link::{ArmDriverConfig, ArmLink};
use crate::component::{Context, CoreState, EmittedBy, InitError, Interface, Refused, StopReason};
use crate::components::parts::ManipulatorDriver;
use crate::messages::{
    QueryJointEfforts, QueryManipulatorSpecifications, ReportJointEfforts, ReportJointPositions,
    ReportJointVelocities, ReportManipulatorSpecifications, SetJointEfforts,
};
use crate::JausMessage;

/// What a driver's command asks of the joints, sampled once per control period.
pub trait Goal: std::fmt::Debug + Send + 'static {
    /// Fills the joint reference (positions and velocities, one per joint) for `now`
    /// from the current joint positions `q`, or returns `false` when nothing is
    /// commanded (the driver then holds the arm where it is).
    fn reference(
        &mut self,
        link: &ArmLink,
        now: Instant,
        q: &[f64],
        q_ref: &mut [f64],
        qd_ref: &mut [f64],
    ) -> bool;

    /// Forgets the command (leaving Ready, emergency, lost control).
    fn clear(&mut self);

    /// Whether the command just completed (the mid-level drivers leave their Moving
    /// mode); reading it resets it.
    fn take_finished(&mut self) -> bool {
        false
    }
}

/// A manipulator driver: [`ArmLink`] plus its [`Goal`].
#[derive(Debug)]
pub struct StockArmDriver<G> {
    /// Kinematics, feedback, output and servo.
    pub link: ArmLink,
    /// The command being executed.
    pub goal: G,
    hold: Option<Vec<f64>>,
    q_ref: Vec<f64>,
    qd_ref: Vec<f64>,
}

impl<G: Goal + Default> StockArmDriver<G> {
    /// With `config`.
    pub fn new(config: ArmDriverConfig) -> Self {
        Self {
            link: ArmLink::new(config),
            goal: G::default(),
            hold: None,
            q_ref: Vec::new(),
            qd_ref: Vec::new(),
        }
    }
}

impl<G: Goal> StockArmDriver<G> {
    /// One control period: keep the output, then servo toward the goal (or hold).
    pub fn run<I: Interface>(&mut self, ctx: &mut Context<'_, I>)
    where
        SetJointEfforts: EmittedBy<I>,
        QueryManipulatorSpecifications: EmittedBy<I>,
        QueryJointEfforts: EmittedBy<I>,
    {
        // The arm is learnt in every state, so commands are accepted as soon as the
        // driver is Ready.
        self.link.request_specifications(ctx);
        if ctx.state() != CoreState::Ready {
            return;
        }
        self.link.hold_output(ctx);
        if !self.link.ready_to_drive(ctx) {
            self.hold = None;
            return;
        }
        let now = ctx.now();
        let Some((q, _)) = self.link.feedback(now) else {
            return;
        };
        let q = q.to_vec();
        self.q_ref.resize(q.len(), 0.0);
        self.qd_ref.resize(q.len(), 0.0);
        if self
            .goal
            .reference(&self.link, now, &q, &mut self.q_ref, &mut self.qd_ref)
        {
            self.hold = None;
        } else {
            let hold = self.hold.get_or_insert_with(|| q.clone());
            self.q_ref.copy_from_slice(hold);
            self.qd_ref.iter_mut().for_each(|v| *v = 0.0);
        }
        let (q_ref, qd_ref) = (
            std::mem::take(&mut self.q_ref),
            std::mem::take(&mut self.qd_ref),
        );
        self.link.servo_to(ctx, &q_ref, &qd_ref);
        (self.q_ref, self.qd_ref) = (q_ref, qd_ref);
    }

    /// Stops: forget the command, every effort to zero (emergency, failure, shutdown,
    /// stale feedback).
    pub fn halt<I: Interface>(&mut self, ctx: &mut Context<'_, I>)
    where
        SetJointEfforts: EmittedBy<I>,
    {
        self.goal.clear();
        self.hold = None;
        self.link.stop(ctx);
    }

    /// Hands the arm back: forget the command, stop commanding and give the Primitive
    /// Manipulator back, whose holding controller keeps the arm where it is.
    pub fn let_go<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        self.goal.clear();
        self.hold = None;
        self.link.let_go();
        self.link.release_output(ctx);
    }

    /// What the runtime's stop asks: emergency, failure and shutdown set every effort to
    /// zero; Standby hands the arm back ([`let_go`](Self::let_go)); when the driver's
    /// own controller lets it go the command is forgotten and the driver holds the arm
    /// where it is.
    pub fn stop_for<I: Interface>(&mut self, ctx: &mut Context<'_, I>, reason: StopReason)
    where
        SetJointEfforts: EmittedBy<I>,
    {
        match reason {
            StopReason::Emergency | StopReason::Failure | StopReason::Shutdown => self.halt(ctx),
            StopReason::Standby => self.let_go(ctx),
            StopReason::ControlLost { .. } => {
                self.goal.clear();
                self.hold = None;
            }
        }
    }

    /// On leaving Ready: to Standby, hand the arm back; otherwise (emergency, failure,
    /// shutdown) every effort to zero, then give the Primitive Manipulator back.
    pub fn leave_ready<I: Interface>(&mut self, ctx: &mut Context<'_, I>, to: CoreState)
    where
        SetJointEfforts: EmittedBy<I>,
    {
        if to == CoreState::Standby {
            self.let_go(ctx);
        } else {
            self.halt(ctx);
            self.link.release_output(ctx);
        }
    }
}

/// Moves the joint rates `rates` toward `desired` over `dt` seconds with each joint's
/// change within `limit(j)` (its acceleration, per second), all joints' changes scaled
/// by the same factor (so a tool velocity keeps its direction while it changes).
pub fn slew(rates: &mut [f64], desired: &[f64], dt: f64, limit: impl Fn(usize) -> f64) {
    if dt.is_nan() || dt <= 0.0 {
        return;
    }
    let scale = rates
        .iter()
        .zip(desired)
        .enumerate()
        .map(|(j, (r, d))| {
            let most = limit(j) * dt;
            if most > 0.0 && most.is_finite() {
                (d - r).abs() / most
            } else {
                0.0
            }
        })
        .fold(1.0, f64::max);
    for (r, d) in rates.iter_mut().zip(desired) {
        *r += (d - *r) / scale;
    }
}

/// Joint rates averaged over a sliding time window (the velocity drivers' jerk limit):
/// rates that ramp from one value to another come out with a change that builds up and
/// dies away over the window, within the same speed and acceleration. Time before the
/// first rates counts as at rest.
#[derive(Debug, Clone, Default)]
pub struct RateSmoother {
    history: VecDeque<(Instant, Vec<f64>)>,
}

impl RateSmoother {
    /// Forgets the history (at rest).
    pub fn reset(&mut self) {
        self.history.clear();
    }

    /// Whether every rate in the window is zero.
    pub fn still(&self) -> bool {
        self.history
            .iter()
            .all(|(_, v)| v.iter().all(|r| *r == 0.0))
    }

    /// Takes `rates` (in force since the previous call) at `now` and writes their
    /// average over the last `window` into `out`; without a window, `rates` themselves.
    pub fn smooth(&mut self, now: Instant, rates: &[f64], window: Duration, out: &mut [f64]) {
        let w = window.as_secs_f64();
        if w <= 0.0 {
            out.copy_from_slice(rates);
            self.history.clear();
            return;
        }
        if self
            .history
            .back()
            .is_some_and(|(_, v)| v.len() != rates.len())
        {
            self.history.clear();
        }
        self.history.push_back((now, rates.to_vec()));
        // Keep one entry from before the window: it marks where the next one starts.
        while self
            .history
            .get(1)
            .is_some_and(|(t, _)| now.saturating_duration_since(*t) >= window)
        {
            self.history.pop_front();
        }
        out.iter_mut().for_each(|v| *v = 0.0);
        let from = now.checked_sub(window);
        let mut previous: Option<Instant> = None;
        for (t, v) in &self.history {
            // Rates `v` were in force from the previous entry's time to `t`.
            let start = match (previous, from) {
                (Some(p), Some(f)) => p.max(f),
                (Some(p), None) => p,
                (None, _) => *t,
            };
            let span = t.saturating_duration_since(start).as_secs_f64();
            for (o, r) in out.iter_mut().zip(v) {
                *o += r * span / w;
            }
            previous = Some(*t);
        }
    }
}

/// The part the six drivers share (`ManipulatorDriver` of `manipulator.yaml`): the
/// specifications and joint feedback into the link, feedback subscribed to as the
/// driver's interface takes it, every effort to zero on leaving Ready, one control
/// period per tick.
impl<G: Goal, I: Interface> ManipulatorDriver<I> for StockArmDriver<G>
where
    SetJointEfforts: EmittedBy<I>,
    QueryManipulatorSpecifications: EmittedBy<I>,
    QueryJointEfforts: EmittedBy<I>,
{
    fn on_report_manipulator_specifications(
        &mut self,
        ctx: &mut Context<'_, I>,
        r: &ReportManipulatorSpecifications,
    ) -> Result<(), Refused> {
        self.link.on_specifications(ctx, r);
        Ok(())
    }

    fn on_report_joint_efforts(
        &mut self,
        ctx: &mut Context<'_, I>,
        r: &ReportJointEfforts,
    ) -> Result<(), Refused> {
        self.link.on_efforts(ctx.source(), r);
        Ok(())
    }

    fn on_report_joint_positions(
        &mut self,
        ctx: &mut Context<'_, I>,
        r: &ReportJointPositions,
    ) -> Result<(), Refused> {
        self.link.on_positions(ctx.now(), r);
        Ok(())
    }

    fn on_report_joint_velocities(
        &mut self,
        ctx: &mut Context<'_, I>,
        r: &ReportJointVelocities,
    ) -> Result<(), Refused> {
        self.link.on_velocities(ctx.now(), r);
        Ok(())
    }

    /// Subscribes to the joint feedback the driver's interface takes.
    fn initialize(&mut self, ctx: &mut Context<'_, I>) -> Result<(), InitError> {
        let takes = |code| I::ACCEPTS.contains(&code);
        let (positions, velocities) = (
            takes(ReportJointPositions::CODE),
            takes(ReportJointVelocities::CODE),
        );
        self.link.subscribe(ctx, positions, velocities);
        Ok(())
    }

    fn state_changed(&mut self, ctx: &mut Context<'_, I>, _from: CoreState, to: CoreState) {
        if to != CoreState::Ready {
            self.leave_ready(ctx, to);
        }
    }

    fn tick(&mut self, ctx: &mut Context<'_, I>) {
        self.run(ctx);
    }
}

/// A joint list of a command checked against the arm: the right count, finite values
/// within each joint's limits (`limit(j)` gives them).
pub(super) fn check_joints(
    values: &[f64],
    dof: usize,
    field: &'static str,
    limit: impl Fn(usize) -> (f64, f64),
    unit: &'static str,
) -> Result<(), Refused> {
    if values.len() != dof {
        return Err(Refused::Invalid(format!(
            "`{field}` lists {} joints; this arm has {dof}",
            values.len()
        )));
    }
    for (j, &v) in values.iter().enumerate() {
        let (min, max) = limit(j);
        if !(v.is_finite() && v >= min && v <= max) {
            return Err(Refused::Invalid(format!(
                "`{field}[{j}]` = {v} {unit} is outside joint {j}'s limits [{min}, {max}] {unit}"
            )));
        }
    }
    Ok(())
}
