//! What every closed-loop driver shares: pose and velocity feedback by service
//! connection, the watchdog on stale feedback, control of the component that receives
//! the wrench (Primitive or Reflexive Driver), and the heading/speed law that turns a
//! desired speed and heading into a wrench effort.

use std::time::{Duration, Instant};

use nalgebra::{Vector2, Vector3};

use super::geo::{local_pose, wrap_angle, LocalFrame};
use super::hardware::Wrench;
use super::output::OutputControl;
use crate::component::{Context, EmittedBy, Interface};
use crate::messages::{ReportGlobalPose, ReportLocalPose, ReportVelocityState, SetWrenchEffort};
use crate::{Address, CommandCode};

/// Settings shared by the vector, waypoint and path-segment drivers.
#[derive(Debug, Clone)]
pub struct DriverConfig {
    /// Where the wrench goes: the Primitive Driver, or the Reflexive Driver.
    pub output: Address,
    /// The pose sensor (Global Pose Sensor for global drivers, Local Pose Sensor for
    /// local ones).
    pub pose_sensor: Address,
    /// The Velocity State Sensor, if any (speed feedback).
    pub velocity_sensor: Option<Address>,
    /// Rate of the pose and velocity service connections, Hz.
    pub feedback_rate_hz: f64,
    /// Feedback older than this stops the vehicle (watchdog).
    pub feedback_timeout: Duration,
    /// A vector command older than this stops the vehicle (`None`: commands never go
    /// stale). Waypoint and path drivers do not use it.
    pub command_timeout: Option<Duration>,
    /// Platform speed at 100 % linear effort, m/s.
    pub max_speed: f64,
    /// Platform yaw rate at 100 % rotational effort, rad/s.
    pub max_yaw_rate: f64,
    /// Heading gain: commanded yaw rate per radian of heading error, 1/s.
    pub heading_gain: f64,
    /// Speed gain: extra effort (fraction of full) per m/s of speed error.
    pub speed_gain: f64,
    /// Pursuit look-ahead distance along the path, m.
    pub lookahead: f64,
    /// Distance to the final point at which a path or waypoint list is complete, m.
    pub arrival_tolerance: f64,
    /// Deceleration used to slow down before the final point and into turns, m/s².
    pub deceleration: f64,
    /// How far the vehicle may stray from the path where it turns (a waypoint's corner,
    /// a tight curve), m: paths are driven slowly enough through their turns to keep
    /// within it (`Path::turn_speed`). Default 0.05 m.
    pub corner_tolerance: f64,
    /// The WGS 84 origin of the local frame global drivers work in (`None`: the first
    /// global fix).
    pub origin: Option<LocalFrame>,
}

/// The defaults: output 1.1.33.1 (the Primitive Driver), pose sensor 1.1.41.1,
/// velocity sensor 1.1.42.1, feedback at 20 Hz with a 300 ms watchdog, vector commands
/// stale after 2 s, 2 m/s and 1.5 rad/s at full effort, heading gain 2.5 /s, speed gain
/// 0.5, look-ahead 0.5 m, arrival within 0.15 m, deceleration 0.8 m/s², turns within
/// 0.05 m, origin at the first fix.
///
/// ```
/// use std::time::Duration;
/// let d = jaus::stock::motion::DriverConfig::default();
/// assert_eq!((d.feedback_rate_hz, d.feedback_timeout), (20.0, Duration::from_millis(300)));
/// assert_eq!(d.command_timeout, Some(Duration::from_secs(2)));
/// assert_eq!((d.max_speed, d.max_yaw_rate, d.heading_gain, d.speed_gain), (2.0, 1.5, 2.5, 0.5));
/// assert_eq!((d.lookahead, d.arrival_tolerance, d.deceleration), (0.5, 0.15, 0.8));
/// assert_eq!(d.corner_tolerance, 0.05);
/// assert_eq!(d.output, jaus::Address::new(1, 1, 33, 1));
/// ```
impl Default for DriverConfig {
    fn default() -> Self {
        Self {
            output: Address::new(1, 1, 33, 1),
            pose_sensor: Address::new(1, 1, 41, 1),
            velocity_sensor: Some(Address::new(1, 1, 42, 1)),
            feedback_rate_hz: 20.0,
            feedback_timeout: Duration::from_millis(300),
            command_timeout: Some(Duration::from_secs(2)),
            max_speed: 2.0,
            max_yaw_rate: 1.5,
            heading_gain: 2.5,
            speed_gain: 0.5,
            lookahead: 0.5,
            arrival_tolerance: 0.15,
            deceleration: 0.8,
            corner_tolerance: 0.05,
            origin: None,
        }
    }
}

/// Feedback, output control and the steering law.
#[derive(Debug)]
pub struct Motion {
    /// Settings.
    pub config: DriverConfig,
    pose: Option<(Instant, Vector2<f64>, f64)>,
    speed: Option<(Instant, f64)>,
    frame: Option<LocalFrame>,
    output: OutputControl,
    stopped: bool,
    last: Wrench,
    watchdog_trips: u64,
}

impl Motion {
    /// With `config`.
    pub fn new(config: DriverConfig) -> Self {
        Self {
            frame: config.origin,
            output: OutputControl::new(config.output),
            config,
            pose: None,
            speed: None,
            stopped: true,
            last: Wrench::ZERO,
            watchdog_trips: 0,
        }
    }

    /// Subscribes to pose and velocity feedback (`report` is Report Global Pose or Report
    /// Local Pose).
    pub fn subscribe<I: Interface>(&mut self, ctx: &mut Context<'_, I>, report: CommandCode) {
        let rate = self.config.feedback_rate_hz;
        // Position and attitude bits (0-6) of the pose report.
        let pose = ctx.create_service_connection(self.config.pose_sensor, report, rate, 0x7F);
        let velocity = self.config.velocity_sensor.map(|v| {
            // Velocities and rates (bits 0-2, 4-6).
            ctx.create_service_connection(v, CommandCode(0x4404), rate, 0x77)
        });
        for e in [Some(pose), velocity]
            .into_iter()
            .flatten()
            .filter_map(Result::err)
        {
            // The watchdog stops the vehicle while no feedback arrives.
            tracing::warn!(address = %ctx.address(), "feedback not requested: {e}");
        }
    }

    /// The local frame global positions are converted into.
    pub fn frame(&self) -> Option<LocalFrame> {
        self.frame
    }

    /// Takes a global pose report.
    pub fn on_global_pose(&mut self, now: Instant, r: &ReportGlobalPose) {
        let last_yaw = self.pose.map(|p| p.2);
        if let Some((p, yaw)) = local_pose(&mut self.frame, r, last_yaw) {
            self.pose = Some((now, p, yaw));
        }
    }

    /// Takes a local pose report.
    pub fn on_local_pose(&mut self, now: Instant, r: &ReportLocalPose) {
        let (Some(x), Some(y)) = (r.x, r.y) else {
            return;
        };
        let yaw = r.yaw.unwrap_or_else(|| self.pose.map_or(0.0, |p| p.2));
        self.pose = Some((now, Vector2::new(x, y), yaw));
    }

    /// Takes a velocity report.
    pub fn on_velocity(&mut self, now: Instant, r: &ReportVelocityState) {
        if let Some(v) = r.velocity_x {
            self.speed = Some((now, v));
        }
    }

    /// Position (local, m) and heading (rad), unless stale.
    pub fn pose(&self, now: Instant) -> Option<(Vector2<f64>, f64)> {
        self.pose
            .filter(|(t, ..)| now.saturating_duration_since(*t) <= self.config.feedback_timeout)
            .map(|(_, p, y)| (p, y))
    }

    /// The latest position even if stale (for planning, not for driving).
    pub fn last_position(&self) -> Option<Vector2<f64>> {
        self.pose.map(|(_, p, _)| p)
    }

    /// Measured forward speed, unless stale.
    pub fn speed(&self, now: Instant) -> Option<f64> {
        self.speed
            .filter(|(t, _)| now.saturating_duration_since(*t) <= self.config.feedback_timeout)
            .map(|(_, v)| v)
    }

    /// How often the watchdog stopped the vehicle for stale feedback.
    pub fn watchdog_trips(&self) -> u64 {
        self.watchdog_trips
    }

    /// The wrench sent last.
    pub fn last_output(&self) -> Wrench {
        self.last
    }

    /// Keeps control of the output component and resumes it once controlled. Call every
    /// tick while the driver is Ready.
    pub fn hold_output<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        // `config` is public: follow a changed output address.
        if self.output.target() != self.config.output {
            self.output = OutputControl::new(self.config.output);
        }
        self.output.hold(ctx);
    }

    /// Gives control of the output component back (call on leaving Ready, after
    /// [`stop`](Self::stop)), so another driver can take it.
    pub fn release_output<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        self.output.release(ctx);
    }

    /// Drives at `speed` (m/s) toward `heading` (rad). Nothing is sent before the
    /// output component has granted control.
    pub fn drive<I: Interface>(&mut self, ctx: &mut Context<'_, I>, speed: f64, heading: f64)
    where
        SetWrenchEffort: EmittedBy<I>,
    {
        if !ctx.has_control_of(self.config.output) {
            return;
        }
        let now = ctx.now();
        let Some((_, yaw)) = self.pose(now) else {
            self.watchdog_stop(ctx);
            return;
        };
        let c = &self.config;
        let err = wrap_angle(heading - yaw);
        let yaw_rate = (c.heading_gain * err).clamp(-c.max_yaw_rate, c.max_yaw_rate);
        // Slow down while the heading is far off, so the vehicle turns before it goes.
        let speed = speed * err.cos().max(0.0);
        let measured = self.speed(now).unwrap_or(speed);
        let linear =
            (speed / c.max_speed + c.speed_gain * (speed - measured) / c.max_speed) * 100.0;
        let w = Wrench {
            linear: Vector3::new(linear.clamp(-100.0, 100.0), 0.0, 0.0),
            rotational: Vector3::new(
                0.0,
                0.0,
                (yaw_rate / c.max_yaw_rate * 100.0).clamp(-100.0, 100.0),
            ),
            ..Wrench::ZERO
        };
        self.stopped = false;
        self.send(ctx, w);
    }

    /// Stops the vehicle: sends brakes once (the Primitive Driver's own watchdog keeps
    /// it braked when no further wrench arrives).
    pub fn stop<I: Interface>(&mut self, ctx: &mut Context<'_, I>)
    where
        SetWrenchEffort: EmittedBy<I>,
    {
        if !self.stopped {
            self.stopped = true;
            self.send(ctx, Wrench::brake());
        }
    }

    fn watchdog_stop<I: Interface>(&mut self, ctx: &mut Context<'_, I>)
    where
        SetWrenchEffort: EmittedBy<I>,
    {
        if !self.stopped {
            self.watchdog_trips += 1;
            tracing::warn!(
                component = I::NAME,
                address = %ctx.address(),
                "watchdog: no pose from {} for {:?}; stopping",
                self.config.pose_sensor,
                self.config.feedback_timeout
            );
        }
        self.stop(ctx);
    }

    fn send<I: Interface>(&mut self, ctx: &mut Context<'_, I>, w: Wrench)
    where
        SetWrenchEffort: EmittedBy<I>,
    {
        self.last = w;
        ctx.send(self.config.output, wrench_message(&w));
    }
}

/// The Set Wrench Effort carrying `w` (only the axes a ground vehicle uses are sent:
/// linear x, rotational z, resistive linear x).
pub fn wrench_message(w: &Wrench) -> SetWrenchEffort {
    SetWrenchEffort {
        propulsive_linear_effort_x: Some(w.linear.x),
        propulsive_rotational_effort_z: Some(w.rotational.z),
        resistive_linear_effort_x: Some(w.resistive_linear.x),
        ..Default::default()
    }
}

/// The wrench a Set Wrench Effort carries (absent axes are zero).
pub fn wrench_of(m: &SetWrenchEffort) -> Wrench {
    let g = |v: Option<f64>| v.unwrap_or(0.0);
    Wrench {
        linear: Vector3::new(
            g(m.propulsive_linear_effort_x),
            g(m.propulsive_linear_effort_y),
            g(m.propulsive_linear_effort_z),
        ),
        rotational: Vector3::new(
            g(m.propulsive_rotational_effort_x),
            g(m.propulsive_rotational_effort_y),
            g(m.propulsive_rotational_effort_z),
        ),
        resistive_linear: Vector3::new(
            g(m.resistive_linear_effort_x),
            g(m.resistive_linear_effort_y),
            g(m.resistive_linear_effort_z),
        ),
        resistive_rotational: Vector3::new(
            g(m.resistive_rotational_effort_x),
            g(m.resistive_rotational_effort_y),
            g(m.resistive_rotational_effort_z),
        ),
    }
}
