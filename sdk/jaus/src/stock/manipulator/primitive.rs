//! The Primitive Manipulator (Part 1 §5.4.2): joint efforts applied open loop to the
//! [`JointActuators`], the arm's specifications reported from its [`Chain`]; while no
//! controller commands the arm, an optional [`HoldingController`] holds it still (without
//! one, no effort).

use std::time::{Duration, Instant};

use super::hardware::JointActuators;
use super::hold::HoldingController;
use super::kinematics::Chain;
use crate::component::{CoreState, InitError, Refused, StopReason};
use crate::components::primitive_manipulator as pm;
use crate::messages::*;

/// One step of Set Joint Efforts' scaled integer (200 % over 65,535 steps).
const ZERO_STEP: f64 = 200.0 / 65_535.0;

/// Settings of the Primitive Manipulator.
#[derive(Debug, Clone)]
pub struct PrimitiveManipulatorConfig {
    /// A command not refreshed within this time ends (watchdog): the holding controller
    /// takes the arm, or without one every effort is zero.
    pub command_timeout: Duration,
}

/// The default: efforts stale after 300 ms.
///
/// ```
/// use std::time::Duration;
/// let c = jaus::stock::manipulator::PrimitiveManipulatorConfig::default();
/// assert_eq!(c.command_timeout, Duration::from_millis(300));
/// ```
impl Default for PrimitiveManipulatorConfig {
    fn default() -> Self {
        Self {
            command_timeout: Duration::from_millis(300),
        }
    }
}

/// The Primitive Manipulator: applies Set Joint Efforts to [`JointActuators`] while
/// Ready.
///
/// Without a holding controller ([`new`](Self::new) alone) every effort is zero whenever
/// no fresh command is applied: before the first one, when commands stop arriving, when
/// control is released, outside Ready.
///
/// With one ([`with_hold`](Self::with_hold)), the arm is never left without effort by a
/// hand-over: while Standby or Ready and not commanded (at start, between drivers, after
/// the controlling driver let go or its commands stopped arriving) the holding controller
/// holds the joints where they are, gravity compensated, starting from the efforts applied
/// until then. Emergency wins: on emergency, failure and shutdown, and after a controller
/// commanded zero effort on every joint (what a driver sends on its own emergency or when
/// its feedback goes stale), every effort is zero and stays zero, through releases of
/// control and cleared emergencies, until a controller commands an effort again.
#[derive(Debug)]
pub struct StockPrimitiveManipulator<A> {
    actuators: A,
    chain: Chain,
    config: PrimitiveManipulatorConfig,
    commanded: Option<Instant>,
    applied: Vec<f64>,
    watchdog_trips: u64,
    hold: Option<HoldingController>,
    limp: bool,
    holding: bool,
    /// Whether the efforts applied now are a controller's command (which held the arm).
    from_command: bool,
    scratch: Vec<f64>,
}

impl<A: JointActuators> StockPrimitiveManipulator<A> {
    /// Over `actuators`, for the arm `chain` (what Report Manipulator Specifications
    /// describes).
    pub fn new(actuators: A, chain: Chain, config: PrimitiveManipulatorConfig) -> Self {
        let n = chain.dof();
        Self {
            actuators,
            chain,
            config,
            commanded: None,
            applied: vec![0.0; n],
            watchdog_trips: 0,
            hold: None,
            limp: false,
            holding: false,
            from_command: false,
            scratch: Vec::new(),
        }
    }

    /// With `hold` holding the arm whenever no controller commands it.
    pub fn with_hold(mut self, hold: HoldingController) -> Self {
        self.hold = Some(hold);
        self
    }

    /// The efforts applied last, percent.
    pub fn applied(&self) -> &[f64] {
        &self.applied
    }

    /// Times the command watchdog ended a command that was not refreshed.
    pub fn watchdog_trips(&self) -> u64 {
        self.watchdog_trips
    }

    /// The arm.
    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    /// Whether the holding controller is holding the arm.
    pub fn holding(&self) -> bool {
        self.holding
    }

    /// The joint positions the holding controller holds (while holding).
    pub fn hold_target(&self) -> Option<&[f64]> {
        self.hold
            .as_ref()
            .filter(|_| self.holding)
            .and_then(HoldingController::target)
    }

    fn zero(&mut self, now: Instant) {
        self.commanded = None;
        self.from_command = false;
        self.stop_holding();
        self.applied.iter_mut().for_each(|e| *e = 0.0);
        self.actuators.apply_efforts(now, &self.applied);
    }

    /// Emergency wins: zero effort, latched until a controller commands an effort.
    fn go_limp(&mut self, now: Instant) {
        self.limp = true;
        self.zero(now);
    }

    fn stop_holding(&mut self) {
        self.holding = false;
        if let Some(h) = &mut self.hold {
            h.release();
        }
    }

    /// Nobody commands the arm any more: hold it, or without a holding controller (or
    /// after zero effort was commanded) no effort.
    fn let_go(&mut self, state: CoreState, now: Instant) {
        self.commanded = None;
        if self.limp || self.hold.is_none() {
            self.zero(now);
        } else {
            self.hold_step(state, now);
        }
    }

    /// One period of the holding controller (in Standby and Ready only).
    fn hold_step(&mut self, state: CoreState, now: Instant) {
        if !matches!(state, CoreState::Standby | CoreState::Ready) || self.limp {
            return;
        }
        let Some(hold) = &mut self.hold else {
            return;
        };
        let mut out = std::mem::take(&mut self.scratch);
        let applied = self.from_command.then_some(self.applied.as_slice());
        if hold.efforts(&self.chain, now, applied, &mut out) {
            if !self.holding {
                tracing::debug!("primitive manipulator: nobody commands the arm; holding it");
            }
            self.holding = true;
            self.from_command = false;
            self.applied.copy_from_slice(&out);
            self.actuators.apply_efforts(now, &self.applied);
        } else {
            // No usable joint reading: nothing to hold against.
            self.holding = false;
            self.from_command = false;
            hold.release();
            self.applied.iter_mut().for_each(|e| *e = 0.0);
            self.actuators.apply_efforts(now, &self.applied);
        }
        self.scratch = out;
    }
}

impl<A: JointActuators> pm::PrimitiveManipulator for StockPrimitiveManipulator<A> {
    fn on_set_joint_efforts(
        &mut self,
        ctx: &mut pm::Ctx<'_>,
        msg: &SetJointEfforts,
    ) -> Result<(), Refused> {
        let n = self.chain.dof();
        if msg.joint_effort.len() != n {
            return Err(Refused::Invalid(format!(
                "Set Joint Efforts lists {} joints; this arm has {n}",
                msg.joint_effort.len()
            )));
        }
        if let Some((j, e)) = msg
            .joint_effort
            .iter()
            .enumerate()
            .find(|(_, e)| !(e.is_finite() && (-100.0..=100.0).contains(*e)))
        {
            return Err(Refused::Invalid(format!(
                "joint_effort[{j}] = {e} is not in -100..=100 %"
            )));
        }
        if ctx.state() == CoreState::Ready {
            self.commanded = Some(ctx.now());
            self.stop_holding();
            for (a, e) in self.applied.iter_mut().zip(&msg.joint_effort) {
                // The wire's scaled u16 over ±100 % has no exact zero (its nearest values
                // are ±0.0015 %): within one step of zero is zero.
                *a = if e.abs() < ZERO_STEP { 0.0 } else { *e };
            }
            // Zero effort on every joint is an order (a driver's emergency or watchdog):
            // it stands until an effort is commanded again.
            self.limp = self.applied.iter().all(|e| *e == 0.0);
            self.from_command = !self.limp;
            self.actuators.apply_efforts(ctx.now(), &self.applied);
        }
        Ok(())
    }

    fn on_query_manipulator_specifications(
        &mut self,
        _ctx: &mut pm::Ctx<'_>,
        _q: &QueryManipulatorSpecifications,
    ) -> Result<ReportManipulatorSpecifications, Refused> {
        Ok(self.chain.to_specifications())
    }

    fn on_query_joint_efforts(
        &mut self,
        _ctx: &mut pm::Ctx<'_>,
        _q: &QueryJointEfforts,
    ) -> Result<ReportJointEfforts, Refused> {
        Ok(ReportJointEfforts {
            joint_effort: self.applied.clone(),
        })
    }

    /// Starts without effort; the holding controller (if any) takes the arm on the first
    /// tick.
    fn initialize(&mut self, ctx: &mut pm::Ctx<'_>) -> Result<(), InitError> {
        self.limp = false;
        self.zero(ctx.now());
        Ok(())
    }

    /// Emergency, failure and shutdown: zero effort (latched). Standby and a controller
    /// that let go: the holding controller takes the arm (zero effort without one).
    fn stop(&mut self, ctx: &mut pm::Ctx<'_>, reason: StopReason) {
        match reason {
            StopReason::Emergency | StopReason::Failure | StopReason::Shutdown => {
                self.go_limp(ctx.now());
            }
            StopReason::Standby | StopReason::ControlLost { .. } => {
                self.let_go(ctx.state(), ctx.now());
            }
        }
    }

    fn state_changed(&mut self, ctx: &mut pm::Ctx<'_>, _from: CoreState, to: CoreState) {
        match to {
            CoreState::Ready => {}
            CoreState::Standby => self.let_go(to, ctx.now()),
            _ => self.go_limp(ctx.now()),
        }
    }

    fn tick(&mut self, ctx: &mut pm::Ctx<'_>) {
        let now = ctx.now();
        if let Some(t) = self.commanded {
            if now.saturating_duration_since(t) <= self.config.command_timeout {
                return;
            }
            self.watchdog_trips += 1;
            tracing::info!(address = %ctx.address(), "primitive manipulator: efforts not refreshed; the command ends");
            self.let_go(ctx.state(), now);
            return;
        }
        self.hold_step(ctx.state(), now);
    }
}
