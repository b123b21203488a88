//! The Reflexive Driver (Part 1 §5.3): effort limits and obstacle slow-down between a
//! controller and the Primitive Driver.

use std::time::{Duration, Instant};

use crate::component::{CoreState, Refused, StopReason};
use crate::components::reflexive_driver as rd;
use crate::messages::*;
use crate::stock::hardware::Wrench;
use crate::stock::motion::{wrench_message, wrench_of, DriverConfig, Motion};
use crate::Address;

/// Distance to the nearest obstacle ahead of the platform.
pub trait ObstacleSource: Send + 'static {
    /// Free distance ahead, m (`None`: nothing seen).
    fn obstacle_distance(&mut self, now: Instant) -> Option<f64>;
}

/// No obstacle sensor.
impl ObstacleSource for () {
    fn obstacle_distance(&mut self, _now: Instant) -> Option<f64> {
        None
    }
}

/// Settings of the Reflexive Driver.
#[derive(Debug, Clone)]
pub struct ReflexiveConfig {
    /// Where the filtered wrench goes (the Primitive Driver).
    pub output: Address,
    /// Largest forward/backward effort passed on, %.
    pub max_linear_effort: f64,
    /// Largest rotational effort passed on, %.
    pub max_rotational_effort: f64,
    /// Below this free distance forward effort is scaled down, m.
    pub slow_distance: f64,
    /// At or below this free distance forward effort is cut and brakes applied, m.
    pub stop_distance: f64,
    /// A wrench not refreshed within this time is replaced by brakes.
    pub command_timeout: Duration,
}

impl Default for ReflexiveConfig {
    fn default() -> Self {
        Self {
            output: Address::new(1, 1, 33, 1),
            max_linear_effort: 100.0,
            max_rotational_effort: 100.0,
            slow_distance: 3.0,
            stop_distance: 0.8,
            command_timeout: Duration::from_millis(500),
        }
    }
}

/// The Reflexive Driver: passes the commanded wrench on, limited in effort and cut down
/// as an obstacle ahead gets near.
#[derive(Debug)]
pub struct StockReflexiveDriver<O> {
    obstacles: O,
    config: ReflexiveConfig,
    motion: Motion,
    commanded: Option<(Instant, Wrench)>,
    modified: Wrench,
    interventions: u64,
}

impl<O: ObstacleSource> StockReflexiveDriver<O> {
    /// Over `obstacles`.
    pub fn new(obstacles: O, config: ReflexiveConfig) -> Self {
        let motion = Motion::new(DriverConfig {
            output: config.output,
            ..DriverConfig::default()
        });
        Self {
            obstacles,
            config,
            motion,
            commanded: None,
            modified: Wrench::ZERO,
            interventions: 0,
        }
    }

    /// The wrench sent on last.
    pub fn modified(&self) -> Wrench {
        self.modified
    }

    /// How many commands were changed for safety.
    pub fn interventions(&self) -> u64 {
        self.interventions
    }

    fn filter(&mut self, now: Instant, w: Wrench) -> Wrench {
        let c = &self.config;
        let mut out = w;
        out.linear.x = w.linear.x.clamp(-c.max_linear_effort, c.max_linear_effort);
        out.rotational.z = w
            .rotational
            .z
            .clamp(-c.max_rotational_effort, c.max_rotational_effort);
        if let Some(d) = self.obstacles.obstacle_distance(now) {
            if out.linear.x > 0.0 && d < c.slow_distance {
                let k =
                    ((d - c.stop_distance) / (c.slow_distance - c.stop_distance)).clamp(0.0, 1.0);
                out.linear.x *= k;
                if k == 0.0 {
                    out.resistive_linear.x = 100.0;
                }
            }
        }
        if out != w {
            self.interventions += 1;
        }
        out
    }
}

impl<O: ObstacleSource> rd::ReflexiveDriver for StockReflexiveDriver<O> {
    fn on_set_wrench_effort(
        &mut self,
        ctx: &mut rd::Ctx<'_>,
        msg: &SetWrenchEffort,
    ) -> Result<(), Refused> {
        let w = wrench_of(msg);
        if !w.is_valid() {
            return Err(Refused::Invalid(
                "wrench effort out of range or not finite".into(),
            ));
        }
        let now = ctx.now();
        self.commanded = Some((now, w));
        if ctx.state() == CoreState::Ready {
            let m = self.filter(now, w);
            self.send_output(ctx, m);
        }
        Ok(())
    }

    fn on_query_wrench_effort(
        &mut self,
        _ctx: &mut rd::Ctx<'_>,
        _q: &QueryWrenchEffort,
    ) -> Result<ReportWrenchEffort, Refused> {
        let m = wrench_message(&self.modified);
        Ok(ReportWrenchEffort {
            propulsive_linear_effort_x: m.propulsive_linear_effort_x,
            propulsive_rotational_effort_z: m.propulsive_rotational_effort_z,
            resistive_linear_effort_x: m.resistive_linear_effort_x,
            ..Default::default()
        })
    }

    fn stop(&mut self, ctx: &mut rd::Ctx<'_>, _reason: StopReason) {
        self.commanded = None;
        self.modified = Wrench::brake();
        if ctx.has_control_of(self.config.output) {
            ctx.send(self.config.output, wrench_message(&self.modified));
        }
    }

    fn state_changed(&mut self, ctx: &mut rd::Ctx<'_>, _from: CoreState, to: CoreState) {
        if to != CoreState::Ready {
            rd::ReflexiveDriver::stop(self, ctx, StopReason::Standby);
        }
    }

    fn tick(&mut self, ctx: &mut rd::Ctx<'_>) {
        if ctx.state() != CoreState::Ready {
            return;
        }
        self.motion.hold_output(ctx);
        let now = ctx.now();
        match self.commanded {
            Some((t, _)) if now.saturating_duration_since(t) > self.config.command_timeout => {
                self.commanded = None;
                self.send_output(ctx, Wrench::brake());
            }
            // Re-evaluate the obstacle between commands (and send what could not be sent
            // before the output component granted control).
            Some((_, w)) => {
                let m = self.filter(now, w);
                if m != self.modified {
                    self.send_output(ctx, m);
                }
            }
            None => {}
        }
    }
}

impl<O: ObstacleSource> StockReflexiveDriver<O> {
    /// Sends `w` to the output component if this driver controls it (a command sent
    /// without control would only be refused there); `modified` records what was sent.
    fn send_output(&mut self, ctx: &mut rd::Ctx<'_>, w: Wrench) {
        if ctx.has_control_of(self.config.output) {
            self.modified = w;
            ctx.send(self.config.output, wrench_message(&w));
        }
    }
}
