//! The closed-loop manipulator driver all six drivers of Part 1 §5.4.6–§5.4.11 are:
//! an [`ArmLink`] and a [`Goal`] that turns the command into a joint reference every
//! control period. While nothing is commanded (or a velocity command went stale) the
//! driver holds the arm where it is; on leaving Ready, on emergency and when control is
//! lost it sets every effort to zero and gives the Primitive Manipulator back.

use std::time::Instant;

use super::link::{ArmDriverConfig, ArmLink};
use crate::component::{Context, CoreState, EmittedBy, InitError, Interface, Refused};
use crate::components::parts::ManipulatorDriver;
use crate::messages::{
    QueryManipulatorSpecifications, ReportJointEfforts, ReportJointPositions,
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

    /// Stops: forget the command, every effort to zero.
    pub fn halt<I: Interface>(&mut self, ctx: &mut Context<'_, I>)
    where
        SetJointEfforts: EmittedBy<I>,
    {
        self.goal.clear();
        self.hold = None;
        self.link.stop(ctx);
    }

    /// On leaving Ready: stop and give the Primitive Manipulator back.
    pub fn leave_ready<I: Interface>(&mut self, ctx: &mut Context<'_, I>)
    where
        SetJointEfforts: EmittedBy<I>,
    {
        self.halt(ctx);
        self.link.release_output(ctx);
    }
}

/// Moves a joint reference toward a target at a limited rate per joint (the position
/// drivers' reference, so the servo is never asked for a step).
#[derive(Debug, Clone, Default)]
pub struct Ramp {
    reference: Option<Vec<f64>>,
    last: Option<Instant>,
}

impl Ramp {
    /// Restarts from the current positions on the next step.
    pub fn reset(&mut self) {
        self.reference = None;
        self.last = None;
    }

    /// Steps the reference from where it is (or from `q` on the first step) toward
    /// `target`, each joint at no more than `rates[j]`; fills `q_ref`, `qd_ref`.
    pub fn step(
        &mut self,
        now: Instant,
        q: &[f64],
        target: &[f64],
        rates: impl Fn(usize) -> f64,
        q_ref: &mut [f64],
        qd_ref: &mut [f64],
    ) {
        let dt = self.last.map_or(0.0, |t| {
            now.saturating_duration_since(t).as_secs_f64().min(0.1)
        });
        self.last = Some(now);
        let r = self.reference.get_or_insert_with(|| q.to_vec());
        if r.len() != target.len() {
            *r = q.to_vec();
        }
        for j in 0..target.len() {
            let max = rates(j) * dt;
            let step = (target[j] - r[j]).clamp(-max, max);
            r[j] += step;
            q_ref[j] = r[j];
            qd_ref[j] = if dt > 0.0 && (target[j] - r[j]).abs() > 0.0 {
                step / dt
            } else {
                0.0
            };
        }
    }

    /// Whether the reference has reached `target`.
    pub fn arrived(&self, target: &[f64]) -> bool {
        self.reference.as_deref() == Some(target)
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
        _ctx: &mut Context<'_, I>,
        _r: &ReportJointEfforts,
    ) -> Result<(), Refused> {
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
            self.leave_ready(ctx);
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
