//! The Primitive Driver (Part 1 §5.3): wrench efforts and discrete devices applied to
//! the [`Actuators`](crate::stock::hardware::Actuators), braking when not refreshed.

use std::time::{Duration, Instant};

use crate::codec::Encode;
use crate::component::{CoreState, Refused, StopReason};
use crate::components::primitive_driver as pd;
use crate::messages::*;
use crate::stock::hardware::{Actuators, Wrench};
use crate::stock::motion::{wrench_message, wrench_of};

/// Settings of the Primitive Driver.
#[derive(Debug, Clone)]
pub struct PrimitiveConfig {
    /// A wrench not refreshed within this time is replaced by brakes (watchdog).
    pub command_timeout: Duration,
    /// The platform's specifications (dimensions, centre of gravity, turning radius,
    /// top speeds), answered to Query Platform Specifications with the fields the query
    /// asks for; `None` refuses the query (the platform did not say).
    pub specifications: Option<ReportPlatformSpecifications>,
}

impl Default for PrimitiveConfig {
    fn default() -> Self {
        Self {
            command_timeout: Duration::from_millis(300),
            specifications: None,
        }
    }
}

/// The Primitive Driver: applies wrench efforts to [`Actuators`] while Ready; brakes on
/// leaving Ready and when commands stop arriving.
#[derive(Debug)]
pub struct StockPrimitiveDriver<A> {
    actuators: A,
    config: PrimitiveConfig,
    commanded: Option<(Instant, SetWrenchEffort)>,
    applied: Wrench,
    devices: ReportDiscreteDevices,
    watchdog_trips: u64,
}

impl<A: Actuators> StockPrimitiveDriver<A> {
    /// Over `actuators`.
    pub fn new(actuators: A, config: PrimitiveConfig) -> Self {
        Self {
            actuators,
            config,
            commanded: None,
            applied: Wrench::ZERO,
            devices: ReportDiscreteDevices::default(),
            watchdog_trips: 0,
        }
    }

    /// The effort applied last.
    pub fn applied(&self) -> Wrench {
        self.applied
    }

    /// Times the command watchdog braked.
    pub fn watchdog_trips(&self) -> u64 {
        self.watchdog_trips
    }

    fn apply(&mut self, now: Instant, w: Wrench) {
        self.applied = w;
        self.actuators.apply(now, &w);
    }
}

impl<A: Actuators> pd::PrimitiveDriver for StockPrimitiveDriver<A> {
    fn on_set_wrench_effort(
        &mut self,
        ctx: &mut pd::Ctx<'_>,
        msg: &SetWrenchEffort,
    ) -> Result<(), Refused> {
        let w = wrench_of(msg);
        if !w.is_valid() {
            return Err(Refused::Invalid(
                "wrench effort outside -100..100 % (0..100 % resistive) or not finite".into(),
            ));
        }
        self.commanded = Some((ctx.now(), msg.clone()));
        if ctx.state() == CoreState::Ready {
            self.apply(ctx.now(), w);
        }
        Ok(())
    }

    fn on_set_discrete_devices(
        &mut self,
        _ctx: &mut pd::Ctx<'_>,
        msg: &SetDiscreteDevices,
    ) -> Result<(), Refused> {
        let d = &mut self.devices;
        d.propulsion = msg.propulsion.or(d.propulsion);
        d.parking_brake_and_horn = msg.parking_brake_and_horn.or(d.parking_brake_and_horn);
        d.gear = msg.gear.or(d.gear);
        d.transfer_case = msg.transfer_case.or(d.transfer_case);
        Ok(())
    }

    fn on_query_wrench_effort(
        &mut self,
        _ctx: &mut pd::Ctx<'_>,
        _q: &QueryWrenchEffort,
    ) -> Result<ReportWrenchEffort, Refused> {
        let m = wrench_message(&self.applied);
        Ok(ReportWrenchEffort {
            propulsive_linear_effort_x: m.propulsive_linear_effort_x,
            propulsive_rotational_effort_z: m.propulsive_rotational_effort_z,
            resistive_linear_effort_x: m.resistive_linear_effort_x,
            ..Default::default()
        })
    }

    fn on_query_discrete_devices(
        &mut self,
        _ctx: &mut pd::Ctx<'_>,
        _q: &QueryDiscreteDevices,
    ) -> Result<ReportDiscreteDevices, Refused> {
        Ok(self.devices.clone())
    }

    fn on_query_platform_specifications(
        &mut self,
        _ctx: &mut pd::Ctx<'_>,
        q: &QueryPlatformSpecifications,
    ) -> Result<ReportPlatformSpecifications, Refused> {
        let mut r = self.config.specifications.clone().ok_or_else(|| {
            Refused::Invalid("this platform's specifications are not configured".into())
        })?;
        r.keep_present(u64::from(q.presence_vector));
        Ok(r)
    }

    fn stop(&mut self, ctx: &mut pd::Ctx<'_>, _reason: StopReason) {
        self.commanded = None;
        self.apply(ctx.now(), Wrench::brake());
    }

    fn state_changed(&mut self, ctx: &mut pd::Ctx<'_>, _from: CoreState, to: CoreState) {
        if to != CoreState::Ready {
            self.commanded = None;
            self.apply(ctx.now(), Wrench::brake());
        }
    }

    fn tick(&mut self, ctx: &mut pd::Ctx<'_>) {
        let now = ctx.now();
        if let Some((t, _)) = &self.commanded {
            if now.saturating_duration_since(*t) > self.config.command_timeout {
                self.commanded = None;
                self.watchdog_trips += 1;
                tracing::info!(address = %ctx.address(), "primitive driver: wrench not refreshed; braking");
                self.apply(now, Wrench::brake());
            }
        }
    }
}
