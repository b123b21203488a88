//! The Global and Local Vector Drivers (Part 1 §5.3): a heading and speed loop over the
//! pose received by service connection, with a command watchdog.

use std::time::Instant;

use super::finite;
use crate::component::{Context, CoreState, EmittedBy, InitError, Interface, Refused, StopReason};
use crate::components::{global_vector_driver as gvd, local_vector_driver as lvd};
use crate::messages::*;
use crate::stock::motion::{DriverConfig, Motion};
use crate::JausMessage;

/// A global or local vector command: speed (m/s) and heading (rad).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Vector {
    speed: f64,
    heading: f64,
}

/// The Global or Local Vector Driver: holds a heading and a speed.
#[derive(Debug)]
pub struct StockVectorDriver<M> {
    /// Feedback and output.
    pub motion: Motion,
    commanded: Option<(Instant, Vector, M)>,
}

impl<M: Clone> StockVectorDriver<M> {
    /// With `config` (its `pose_sensor` must be the Global Pose Sensor for the global
    /// driver, the Local Pose Sensor for the local one).
    pub fn new(config: DriverConfig) -> Self {
        Self {
            motion: Motion::new(config),
            commanded: None,
        }
    }

    fn set(&mut self, now: Instant, v: Vector, m: M) -> Result<(), Refused> {
        finite(v.speed, "speed")?;
        finite(v.heading, "heading")?;
        Refused::check_range("speed", v.speed, 0.0, self.motion.config.max_speed, "m/s")?;
        self.commanded = Some((now, v, m));
        Ok(())
    }

    fn run<I: Interface>(&mut self, ctx: &mut Context<'_, I>)
    where
        SetWrenchEffort: EmittedBy<I>,
    {
        if ctx.state() != CoreState::Ready {
            return;
        }
        self.motion.hold_output(ctx);
        let now = ctx.now();
        let fresh = |t: Instant| {
            self.motion
                .config
                .command_timeout
                .is_none_or(|limit| now.saturating_duration_since(t) <= limit)
        };
        match self.commanded {
            Some((t, v, _)) if fresh(t) => self.motion.drive(ctx, v.speed, v.heading),
            _ => self.motion.stop(ctx),
        }
    }

    fn leave_ready<I: Interface>(&mut self, ctx: &mut Context<'_, I>)
    where
        SetWrenchEffort: EmittedBy<I>,
    {
        self.commanded = None;
        self.motion.stop(ctx);
        self.motion.release_output(ctx);
    }
}

/// The Global Vector Driver.
pub type StockGlobalVectorDriver = StockVectorDriver<SetGlobalVector>;
/// The Local Vector Driver.
pub type StockLocalVectorDriver = StockVectorDriver<SetLocalVector>;

impl gvd::GlobalVectorDriver for StockGlobalVectorDriver {
    fn initialize(&mut self, ctx: &mut gvd::Ctx<'_>) -> Result<(), InitError> {
        self.motion.subscribe(ctx, ReportGlobalPose::CODE);
        Ok(())
    }
    fn on_set_global_vector(
        &mut self,
        ctx: &mut gvd::Ctx<'_>,
        m: &SetGlobalVector,
    ) -> Result<(), Refused> {
        let v = Vector {
            speed: m.speed.unwrap_or(0.0),
            heading: m
                .heading
                .unwrap_or_else(|| self.motion.pose(ctx.now()).map_or(0.0, |p| p.1)),
        };
        self.set(ctx.now(), v, m.clone())
    }
    fn on_query_global_vector(
        &mut self,
        _ctx: &mut gvd::Ctx<'_>,
        _q: &QueryGlobalVector,
    ) -> Result<ReportGlobalVector, Refused> {
        let m = self
            .commanded
            .as_ref()
            .map(|c| c.2.clone())
            .unwrap_or_default();
        Ok(ReportGlobalVector {
            speed: m.speed,
            altitude: m.altitude,
            heading: m.heading,
            roll: m.roll,
            pitch: m.pitch,
        })
    }
    fn on_report_global_pose(
        &mut self,
        ctx: &mut gvd::Ctx<'_>,
        r: &ReportGlobalPose,
    ) -> Result<(), Refused> {
        self.motion.on_global_pose(ctx.now(), r);
        Ok(())
    }
    fn on_report_velocity_state(
        &mut self,
        ctx: &mut gvd::Ctx<'_>,
        r: &ReportVelocityState,
    ) -> Result<(), Refused> {
        self.motion.on_velocity(ctx.now(), r);
        Ok(())
    }
    fn stop(&mut self, ctx: &mut gvd::Ctx<'_>, _reason: StopReason) {
        self.commanded = None;
        self.motion.stop(ctx);
    }
    fn state_changed(&mut self, ctx: &mut gvd::Ctx<'_>, _from: CoreState, to: CoreState) {
        if to != CoreState::Ready {
            self.leave_ready(ctx);
        }
    }
    fn tick(&mut self, ctx: &mut gvd::Ctx<'_>) {
        self.run(ctx);
    }
}

impl lvd::LocalVectorDriver for StockLocalVectorDriver {
    fn initialize(&mut self, ctx: &mut lvd::Ctx<'_>) -> Result<(), InitError> {
        self.motion.subscribe(ctx, ReportLocalPose::CODE);
        Ok(())
    }
    fn on_set_local_vector(
        &mut self,
        ctx: &mut lvd::Ctx<'_>,
        m: &SetLocalVector,
    ) -> Result<(), Refused> {
        self.set(
            ctx.now(),
            Vector {
                speed: m.speed,
                heading: m.heading,
            },
            m.clone(),
        )
    }
    fn on_query_local_vector(
        &mut self,
        _ctx: &mut lvd::Ctx<'_>,
        _q: &QueryLocalVector,
    ) -> Result<ReportLocalVector, Refused> {
        let (speed, heading) = self
            .commanded
            .as_ref()
            .map_or((0.0, 0.0), |c| (c.1.speed, c.1.heading));
        Ok(ReportLocalVector { speed, heading })
    }
    fn on_report_local_pose(
        &mut self,
        ctx: &mut lvd::Ctx<'_>,
        r: &ReportLocalPose,
    ) -> Result<(), Refused> {
        self.motion.on_local_pose(ctx.now(), r);
        Ok(())
    }
    fn on_report_velocity_state(
        &mut self,
        ctx: &mut lvd::Ctx<'_>,
        r: &ReportVelocityState,
    ) -> Result<(), Refused> {
        self.motion.on_velocity(ctx.now(), r);
        Ok(())
    }
    fn stop(&mut self, ctx: &mut lvd::Ctx<'_>, _reason: StopReason) {
        self.commanded = None;
        self.motion.stop(ctx);
    }
    fn state_changed(&mut self, ctx: &mut lvd::Ctx<'_>, _from: CoreState, to: CoreState) {
        if to != CoreState::Ready {
            self.leave_ready(ctx);
        }
    }
    fn tick(&mut self, ctx: &mut lvd::Ctx<'_>) {
        self.run(ctx);
    }
}
