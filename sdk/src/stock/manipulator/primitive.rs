//! The Primitive Manipulator (Part 1 §5.4.2): joint efforts applied open loop to the
//! [`JointActuators`], the arm's specifications reported from its [`Chain`], all efforts
//! to zero when commands stop arriving.

use std::time::{Duration, Instant};

use super::hardware::JointActuators;
use super::kinematics::Chain;
use crate::component::{CoreState, InitError, Refused, StopReason};
use crate::components::primitive_manipulator as pm;
use crate::messages::*;

/// One step of Set Joint Efforts' scaled integer (200 % over 65,535 steps).
const ZERO_STEP: f64 = 200.0 / 65_535.0;

/// Settings of the Primitive Manipulator.
#[derive(Debug, Clone)]
pub struct PrimitiveManipulatorConfig {
    /// Efforts not refreshed within this time are set to zero (watchdog).
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
/// Ready; zero efforts on leaving Ready, on emergency and when commands stop arriving.
#[derive(Debug)]
pub struct StockPrimitiveManipulator<A> {
    actuators: A,
    chain: Chain,
    config: PrimitiveManipulatorConfig,
    commanded: Option<Instant>,
    applied: Vec<f64>,
    watchdog_trips: u64,
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
        }
    }

    /// The efforts applied last, percent.
    pub fn applied(&self) -> &[f64] {
        &self.applied
    }

    /// Times the command watchdog zeroed the efforts.
    pub fn watchdog_trips(&self) -> u64 {
        self.watchdog_trips
    }

    /// The arm.
    pub fn chain(&self) -> &Chain {
        &self.chain
    }

    fn zero(&mut self, now: Instant) {
        self.commanded = None;
        self.applied.iter_mut().for_each(|e| *e = 0.0);
        self.actuators.apply_efforts(now, &self.applied);
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
        self.commanded = Some(ctx.now());
        if ctx.state() == CoreState::Ready {
            for (a, e) in self.applied.iter_mut().zip(&msg.joint_effort) {
                // The wire's scaled u16 over ±100 % has no exact zero (its nearest values
                // are ±0.0015 %): within one step of zero is zero.
                *a = if e.abs() < ZERO_STEP { 0.0 } else { *e };
            }
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

    fn initialize(&mut self, ctx: &mut pm::Ctx<'_>) -> Result<(), InitError> {
        self.zero(ctx.now());
        Ok(())
    }

    fn stop(&mut self, ctx: &mut pm::Ctx<'_>, _reason: StopReason) {
        self.zero(ctx.now());
    }

    fn state_changed(&mut self, ctx: &mut pm::Ctx<'_>, _from: CoreState, to: CoreState) {
        if to != CoreState::Ready {
            self.zero(ctx.now());
        }
    }

    fn tick(&mut self, ctx: &mut pm::Ctx<'_>) {
        let now = ctx.now();
        if let Some(t) = self.commanded {
            if now.saturating_duration_since(t) > self.config.command_timeout {
                self.watchdog_trips += 1;
                tracing::info!(address = %ctx.address(), "primitive manipulator: efforts not refreshed; zero effort");
                self.zero(now);
            }
        }
    }
}
