//! The platform drivers of Part 1 §5.3: primitive, reflexive, global/local vector,
//! global/local waypoint and global/local path segment. Each is the generated trait of
//! its component implemented over the hardware traits and [`Motion`].
//!
//! Common safety rules: only the controlling component commands them (the runtime);
//! NaN, infinite and out-of-range commands are refused ([`Refused::Invalid`], a NAK when
//! one was asked for); the vehicle stops on leaving Ready (Standby, Emergency, ...), when
//! pose feedback goes stale, and when a vector or wrench command is not refreshed.

use std::time::{Duration, Instant};

use nalgebra::{Vector2, Vector3};

use super::geo::LocalFrame;
use super::hardware::{Actuators, Wrench};
use super::motion::{wrench_message, wrench_of, DriverConfig, Motion};
use super::path::{Path, PathSegment};
use crate::component::{Context, CoreState, EmittedBy, Interface, Modes, Refused, StopReason};
use crate::components::{
    global_path_segment_driver as gpsd, global_vector_driver as gvd, global_waypoint_driver as gwd,
    local_path_segment_driver as lpsd, local_vector_driver as lvd, local_waypoint_driver as lwd,
    primitive_driver as pd, reflexive_driver as rd,
};
use crate::messages::*;
use crate::{Address, CommandCode};

fn finite(v: f64, what: &str) -> Result<f64, Refused> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Refused::Invalid(format!("{what} is not a finite number")))
    }
}

// ---------------------------------------------------------------------------------
// Primitive Driver

/// Settings of the Primitive Driver.
#[derive(Debug, Clone)]
pub struct PrimitiveConfig {
    /// A wrench not refreshed within this time is replaced by brakes (watchdog).
    pub command_timeout: Duration,
}

impl Default for PrimitiveConfig {
    fn default() -> Self {
        Self {
            command_timeout: Duration::from_millis(300),
        }
    }
}

/// The Primitive Driver: applies wrench efforts to [`Actuators`] while Ready; brakes on
/// leaving Ready and when commands stop arriving.
#[derive(Debug)]
pub struct PrimitiveDriverCore<A> {
    actuators: A,
    config: PrimitiveConfig,
    commanded: Option<(Instant, SetWrenchEffort)>,
    applied: Wrench,
    devices: ReportDiscreteDevices,
    watchdog_trips: u64,
}

impl<A: Actuators> PrimitiveDriverCore<A> {
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

impl<A: Actuators> pd::PrimitiveDriver for PrimitiveDriverCore<A> {
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

// ---------------------------------------------------------------------------------
// Reflexive Driver

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
pub struct ReflexiveDriverCore<O> {
    obstacles: O,
    config: ReflexiveConfig,
    motion: Motion,
    commanded: Option<(Instant, Wrench)>,
    modified: Wrench,
    interventions: u64,
}

impl<O: ObstacleSource> ReflexiveDriverCore<O> {
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

impl<O: ObstacleSource> rd::ReflexiveDriver for ReflexiveDriverCore<O> {
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

impl<O: ObstacleSource> ReflexiveDriverCore<O> {
    /// Sends `w` to the output component if this driver controls it (a command sent
    /// without control would only be refused there); `modified` records what was sent.
    fn send_output(&mut self, ctx: &mut rd::Ctx<'_>, w: Wrench) {
        if ctx.has_control_of(self.config.output) {
            self.modified = w;
            ctx.send(self.config.output, wrench_message(&w));
        }
    }
}

// ---------------------------------------------------------------------------------
// Vector drivers

/// A global or local vector command: speed (m/s) and heading (rad).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Vector {
    speed: f64,
    heading: f64,
}

/// The Global or Local Vector Driver: holds a heading and a speed.
#[derive(Debug)]
pub struct VectorDriverCore<M> {
    /// Feedback and output.
    pub motion: Motion,
    commanded: Option<(Instant, Vector, M)>,
}

impl<M: Clone> VectorDriverCore<M> {
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
        if v.speed < 0.0 || v.speed > self.motion.config.max_speed {
            return Err(Refused::OutOfRange {
                field: "speed",
                value: v.speed,
                min: 0.0,
                max: self.motion.config.max_speed,
                unit: "m/s",
            });
        }
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
pub type GlobalVectorDriverCore = VectorDriverCore<SetGlobalVector>;
/// The Local Vector Driver.
pub type LocalVectorDriverCore = VectorDriverCore<SetLocalVector>;

impl gvd::GlobalVectorDriver for GlobalVectorDriverCore {
    fn initialize(&mut self, ctx: &mut gvd::Ctx<'_>) -> Result<(), String> {
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

impl lvd::LocalVectorDriver for LocalVectorDriverCore {
    fn initialize(&mut self, ctx: &mut lvd::Ctx<'_>) -> Result<(), String> {
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

// ---------------------------------------------------------------------------------
// Waypoint and path-segment drivers

/// The local geometry of one list element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Geometry {
    /// A waypoint.
    Point(Vector2<f64>),
    /// A path segment from the previous end through control point `p1` to `p2`.
    Segment {
        /// Control point.
        p1: Vector2<f64>,
        /// End point.
        p2: Vector2<f64>,
        /// Weighting factor.
        w1: f64,
    },
}

/// An element of a waypoint or path-segment list (the Set message that defines it).
pub trait Element: Clone + std::fmt::Debug + Send + 'static {
    /// Its number in the list.
    fn number(&self) -> u16;
    /// Checks the values; the error names what is wrong.
    fn validate(&self) -> Result<(), String>;
    /// Its geometry in the local frame (`frame` converts global coordinates).
    fn geometry(&self, frame: Option<&LocalFrame>) -> Option<Geometry>;
    /// The element a message carries, if it is one.
    fn from_message(m: &Message) -> Option<Self>;
}

fn check_lat_lon(lat: f64, lon: f64, what: &str) -> Result<(), String> {
    if !(lat.is_finite() && lon.is_finite()) || lat.abs() > 90.0 || lon.abs() > 180.0 {
        return Err(format!(
            "{what}: latitude {lat} / longitude {lon} out of range"
        ));
    }
    Ok(())
}

fn check_xy(x: f64, y: f64, what: &str) -> Result<(), String> {
    if !(x.is_finite() && y.is_finite()) || x.abs() > 100_000.0 || y.abs() > 100_000.0 {
        return Err(format!("{what}: x {x} / y {y} out of range"));
    }
    Ok(())
}

impl Element for SetGlobalWaypoint {
    fn from_message(m: &Message) -> Option<Self> {
        match m {
            Message::SetGlobalWaypoint(e) => Some(e.clone()),
            _ => None,
        }
    }
    fn number(&self) -> u16 {
        self.waypoint_number
    }
    fn validate(&self) -> Result<(), String> {
        check_lat_lon(self.latitude, self.longitude, "waypoint")
    }
    fn geometry(&self, frame: Option<&LocalFrame>) -> Option<Geometry> {
        frame.map(|f| Geometry::Point(f.to_local(self.latitude, self.longitude)))
    }
}

impl Element for SetLocalWaypoint {
    fn from_message(m: &Message) -> Option<Self> {
        match m {
            Message::SetLocalWaypoint(e) => Some(e.clone()),
            _ => None,
        }
    }
    fn number(&self) -> u16 {
        self.waypoint_number
    }
    fn validate(&self) -> Result<(), String> {
        check_xy(self.x, self.y, "waypoint")
    }
    fn geometry(&self, _frame: Option<&LocalFrame>) -> Option<Geometry> {
        Some(Geometry::Point(Vector2::new(self.x, self.y)))
    }
}

fn check_w1(w1: f64) -> Result<(), String> {
    if !w1.is_finite() || w1 < 0.0 {
        return Err(format!("weighting factor {w1} must be a finite number ≥ 0"));
    }
    Ok(())
}

impl Element for SetGlobalPathSegment {
    fn from_message(m: &Message) -> Option<Self> {
        match m {
            Message::SetGlobalPathSegment(e) => Some(e.clone()),
            _ => None,
        }
    }
    fn number(&self) -> u16 {
        self.path_segment_number
    }
    fn validate(&self) -> Result<(), String> {
        check_lat_lon(self.p1_latitude, self.p1_longitude, "P1")?;
        check_lat_lon(self.p2_latitude, self.p2_longitude, "P2")?;
        check_w1(self.weighting_factor)
    }
    fn geometry(&self, frame: Option<&LocalFrame>) -> Option<Geometry> {
        frame.map(|f| Geometry::Segment {
            p1: f.to_local(self.p1_latitude, self.p1_longitude),
            p2: f.to_local(self.p2_latitude, self.p2_longitude),
            w1: self.weighting_factor,
        })
    }
}

impl Element for SetLocalPathSegment {
    fn from_message(m: &Message) -> Option<Self> {
        match m {
            Message::SetLocalPathSegment(e) => Some(e.clone()),
            _ => None,
        }
    }
    fn number(&self) -> u16 {
        self.path_segment_number
    }
    fn validate(&self) -> Result<(), String> {
        check_xy(self.p1_x, self.p1_y, "P1")?;
        check_xy(self.p2_x, self.p2_y, "P2")?;
        check_w1(self.weighting_factor)
    }
    fn geometry(&self, _frame: Option<&LocalFrame>) -> Option<Geometry> {
        Some(Geometry::Segment {
            p1: Vector2::new(self.p1_x, self.p1_y),
            p2: Vector2::new(self.p2_x, self.p2_y),
            w1: self.weighting_factor,
        })
    }
}

/// The four navigating interfaces: their Start/Arrive transitions and pose report.
pub trait NavInterface: Interface {
    /// Idle → Navigating.
    const START: <Self::Modes as Modes>::Transition;
    /// Navigating → Idle (and Standby).
    const ARRIVE: <Self::Modes as Modes>::Transition;
    /// Report Global Pose or Report Local Pose.
    const POSE_REPORT: CommandCode;
    /// Whether `m` is Navigating.
    fn navigating(m: Self::Modes) -> bool;
}

macro_rules! nav_interface {
    ($m:ident, $report:ty) => {
        impl NavInterface for $m::Interface {
            const START: $m::Transition = $m::Transition::Start;
            const ARRIVE: $m::Transition = $m::Transition::Arrive;
            const POSE_REPORT: CommandCode = <$report>::CODE;
            fn navigating(m: $m::Mode) -> bool {
                m == $m::Mode::Navigating
            }
        }
    };
}
nav_interface!(gwd, ReportGlobalPose);
nav_interface!(lwd, ReportLocalPose);
nav_interface!(gpsd, ReportGlobalPose);
nav_interface!(lpsd, ReportLocalPose);

/// Progress along the path being driven.
#[derive(Debug, Clone)]
struct Tracker {
    path: Path,
    /// Arc length at the end of each element.
    ends: Vec<f64>,
    s: f64,
}

/// A waypoint or path-segment driver: a list of elements, a travel speed, and a
/// pursuit controller along the path they define (straight legs between waypoints, the
/// rational quadratic curves of path segments).
#[derive(Debug)]
pub struct Navigator<E> {
    /// Feedback and output.
    pub motion: Motion,
    elements: Vec<E>,
    travel_speed: f64,
    tracker: Option<Tracker>,
    arrivals: u32,
    /// Spooler, mission, task and uid to report finished at the final point.
    spooled: Option<(Address, u16, u16, u16)>,
}

/// The Global Waypoint Driver.
pub type GlobalWaypointDriverCore = Navigator<SetGlobalWaypoint>;
/// The Local Waypoint Driver.
pub type LocalWaypointDriverCore = Navigator<SetLocalWaypoint>;
/// The Global Path Segment Driver.
pub type GlobalPathSegmentDriverCore = Navigator<SetGlobalPathSegment>;
/// The Local Path Segment Driver.
pub type LocalPathSegmentDriverCore = Navigator<SetLocalPathSegment>;

impl<E: Element> Navigator<E> {
    /// With `config`.
    pub fn new(config: DriverConfig) -> Self {
        Self {
            motion: Motion::new(config),
            elements: Vec::new(),
            travel_speed: 0.0,
            tracker: None,
            arrivals: 0,
            spooled: None,
        }
    }

    /// Applies the elements of a Spool Mission as if they had come one by one; the last
    /// blocking one is reported finished at the final point.
    fn spool<I: NavInterface>(
        &mut self,
        ctx: &Context<'_, I>,
        m: &SpoolMission,
    ) -> Result<(), Refused> {
        fn flat<'a>(t: &'a MissionTask, out: &mut Vec<(u16, &'a MissionCommand)>) {
            out.extend(t.messages.iter().map(|c| (t.task_id, c)));
            for c in &t.children {
                flat(c, out);
            }
        }
        let mut cmds = Vec::new();
        flat(&m.root, &mut cmds);
        for (task, c) in cmds {
            let msg = Message::decode(c.message.header.command_code, &c.message.body)
                .map_err(|e| Refused::Invalid(format!("spooled message {}: {e}", c.uid)))?;
            match (&msg, E::from_message(&msg)) {
                (Message::SetTravelSpeed(t), _) => self.set_speed(t.speed)?,
                (_, Some(e)) => self.set_element(ctx, &e)?,
                _ => {
                    return Err(Refused::Invalid(format!(
                        "spooled message {} ({}) is not for a {}",
                        c.uid,
                        msg.name(),
                        I::NAME
                    )))
                }
            }
            if c.blocking != 0 {
                self.spooled = ctx.source().map(|s| (s, m.mission_id, task, c.uid));
            }
        }
        Ok(())
    }

    /// The loaded elements.
    pub fn elements(&self) -> &[E] {
        &self.elements
    }

    /// The travel speed, m/s.
    pub fn travel_speed(&self) -> f64 {
        self.travel_speed
    }

    /// How many lists were driven to the end.
    pub fn arrivals(&self) -> u32 {
        self.arrivals
    }

    /// The path being driven (local frame), if navigating.
    pub fn path(&self) -> Option<&Path> {
        self.tracker.as_ref().map(|t| &t.path)
    }

    /// The element being driven toward.
    pub fn active_element(&self) -> Option<u16> {
        let t = self.tracker.as_ref()?;
        let i = t
            .ends
            .partition_point(|e| *e < t.s + 1e-9)
            .min(t.ends.len().saturating_sub(1));
        self.elements.get(i).map(Element::number)
    }

    fn set_element<I: NavInterface>(&mut self, ctx: &Context<'_, I>, e: &E) -> Result<(), Refused> {
        e.validate().map_err(Refused::Invalid)?;
        let n = usize::from(e.number());
        let navigating = I::navigating(ctx.mode()) && self.tracker.is_some();
        match n {
            0 => {
                self.elements.clear();
                self.elements.push(e.clone());
                self.tracker = None;
            }
            n if n == self.elements.len() => {
                if navigating {
                    let frame = self.motion.frame();
                    let (Some(t), Some(g)) = (self.tracker.as_mut(), e.geometry(frame.as_ref()))
                    else {
                        return Err(Refused::Invalid("no frame for a global element yet".into()));
                    };
                    extend(&mut t.path, &mut t.ends, g);
                }
                self.elements.push(e.clone());
            }
            n if n < self.elements.len() && !navigating => self.elements[n] = e.clone(),
            n if n < self.elements.len() => {
                return Err(Refused::Invalid(format!(
                "element {n} is part of the list being driven: send element 0 to start a new list"
            )))
            }
            n => {
                return Err(Refused::Invalid(format!(
                    "element {n} leaves a gap: the list has {} element(s), send {} next",
                    self.elements.len(),
                    self.elements.len()
                )))
            }
        }
        Ok(())
    }

    fn set_speed(&mut self, speed: f64) -> Result<(), Refused> {
        finite(speed, "travel speed")?;
        let max = self.motion.config.max_speed;
        if !(0.0..=max).contains(&speed) {
            return Err(Refused::OutOfRange {
                field: "speed",
                value: speed,
                min: 0.0,
                max,
                unit: "m/s",
            });
        }
        self.travel_speed = speed;
        Ok(())
    }

    fn build(&self, from: Vector2<f64>) -> Option<Tracker> {
        let frame = self.motion.frame();
        let mut path = Path::new([from]);
        let mut ends = Vec::with_capacity(self.elements.len());
        for e in &self.elements {
            extend(&mut path, &mut ends, e.geometry(frame.as_ref())?);
        }
        Some(Tracker { path, ends, s: 0.0 })
    }

    fn state_changed<I: NavInterface>(
        &mut self,
        ctx: &mut Context<'_, I>,
        from: CoreState,
        to: CoreState,
    ) where
        SetWrenchEffort: EmittedBy<I>,
    {
        if from == CoreState::Standby && to == CoreState::Ready {
            // Part 1: the travel speed is zero after every Standby -> Ready.
            self.travel_speed = 0.0;
        }
        if to != CoreState::Ready {
            self.tracker = None;
            self.motion.stop(ctx);
            self.motion.release_output(ctx);
        }
    }

    /// Stops the vehicle and forgets the path being followed; after an emergency or a
    /// loss of control the travel speed is zero too, so that nothing moves again until a
    /// controller sets one.
    fn stop<I: NavInterface>(&mut self, ctx: &mut Context<'_, I>, reason: StopReason)
    where
        SetWrenchEffort: EmittedBy<I>,
    {
        self.tracker = None;
        self.motion.stop(ctx);
        if matches!(
            reason,
            StopReason::Emergency | StopReason::ControlLost { .. }
        ) {
            self.travel_speed = 0.0;
        }
    }

    fn tick<I: NavInterface>(&mut self, ctx: &mut Context<'_, I>)
    where
        SetWrenchEffort: EmittedBy<I>,
        ReportMissionStatus: EmittedBy<I>,
    {
        if ctx.state() != CoreState::Ready {
            return;
        }
        self.motion.hold_output(ctx);
        let now = ctx.now();
        if !I::navigating(ctx.mode()) {
            if !self.elements.is_empty()
                && self.travel_speed > 0.0
                && ctx.transition(I::START).is_ok()
            {
                self.tracker = None;
            } else {
                self.motion.stop(ctx);
                return;
            }
        }
        let Some((pos, _)) = self.motion.pose(now) else {
            // Watchdog: drive() stops the vehicle when feedback is stale.
            self.motion.drive(ctx, 0.0, 0.0);
            return;
        };
        if self.tracker.is_none() {
            self.tracker = self.build(pos);
        }
        let c = self.motion.config.clone();
        let Some(t) = self.tracker.as_mut() else {
            self.motion.stop(ctx);
            return;
        };
        let len = t.path.length();
        if let Some(p) = t
            .path
            .project(pos, t.s - 0.2, t.s + c.lookahead * 2.0 + 0.5)
        {
            t.s = t.s.max(p.s);
        }
        let end = t.path.at(len);
        let to_end = (end - pos).norm();
        if to_end <= c.arrival_tolerance || (t.s >= len - 1e-6 && to_end <= c.lookahead) {
            self.motion.stop(ctx);
            self.elements.clear();
            self.tracker = None;
            self.arrivals += 1;
            tracing::info!(component = I::NAME, address = %ctx.address(), "final point reached");
            if let Some((spooler, mission, task, uid)) = self.spooled.take() {
                ctx.send(
                    spooler,
                    ReportMissionStatus {
                        status_type: MissionStatusType::Message,
                        status: MissionStatus::Finished,
                        secondary_status: MissionSecondaryStatus::NoError,
                        mission_id: mission,
                        task_id: task,
                        task_msg_id: uid,
                    },
                );
            }
            if let Err(e) = ctx.transition(I::ARRIVE) {
                tracing::warn!(component = I::NAME, "{e}");
            }
            return;
        }
        if self.travel_speed <= 0.0 {
            self.motion.stop(ctx);
            return;
        }
        let target = if len - t.s <= c.lookahead {
            end
        } else {
            t.path.at(t.s + c.lookahead)
        };
        let d = target - pos;
        let heading = d.y.atan2(d.x);
        let remaining = (len - t.s).max(to_end);
        let speed = self
            .travel_speed
            .min((2.0 * c.deceleration * remaining).sqrt())
            .max(0.05);
        self.motion.drive(ctx, speed, heading);
    }
}

fn extend(path: &mut Path, ends: &mut Vec<f64>, g: Geometry) {
    match g {
        Geometry::Point(p) => path.push(p),
        Geometry::Segment { p1, p2, w1 } => {
            let p0 = path.points().last().copied().unwrap_or(p1);
            path.push_segment(&PathSegment {
                p0: Vector3::new(p0.x, p0.y, 0.0),
                p1: Vector3::new(p1.x, p1.y, 0.0),
                p2: Vector3::new(p2.x, p2.y, 0.0),
                w1,
            });
        }
    }
    ends.push(path.length());
}

macro_rules! navigator_common {
    ($m:ident) => {
        fn on_set_travel_speed(
            &mut self,
            _ctx: &mut $m::Ctx<'_>,
            m: &SetTravelSpeed,
        ) -> Result<(), Refused> {
            self.set_speed(m.speed)
        }
        fn on_spool_mission(
            &mut self,
            ctx: &mut $m::Ctx<'_>,
            m: &SpoolMission,
        ) -> Result<(), Refused> {
            self.spool(ctx, m)
        }
        fn on_query_spooling_preference(
            &mut self,
            _ctx: &mut $m::Ctx<'_>,
            _q: &QuerySpoolingPreference,
        ) -> Result<ReportSpoolingPreference, Refused> {
            Ok(ReportSpoolingPreference {
                spool_type: SpoolingLimitType::MessageCount,
                data: 4096,
            })
        }
        fn on_query_travel_speed(
            &mut self,
            _ctx: &mut $m::Ctx<'_>,
            _q: &QueryTravelSpeed,
        ) -> Result<ReportTravelSpeed, Refused> {
            Ok(ReportTravelSpeed {
                speed: self.travel_speed,
            })
        }
        fn on_report_velocity_state(
            &mut self,
            ctx: &mut $m::Ctx<'_>,
            r: &ReportVelocityState,
        ) -> Result<(), Refused> {
            self.motion.on_velocity(ctx.now(), r);
            Ok(())
        }
        fn initialize(&mut self, ctx: &mut $m::Ctx<'_>) -> Result<(), String> {
            self.motion
                .subscribe(ctx, <$m::Interface as NavInterface>::POSE_REPORT);
            Ok(())
        }
        fn state_changed(&mut self, ctx: &mut $m::Ctx<'_>, from: CoreState, to: CoreState) {
            Navigator::state_changed(self, ctx, from, to);
        }
        fn stop(&mut self, ctx: &mut $m::Ctx<'_>, reason: StopReason) {
            Navigator::stop(self, ctx, reason);
        }
        fn tick(&mut self, ctx: &mut $m::Ctx<'_>) {
            Navigator::tick(self, ctx);
        }
    };
}

impl gwd::GlobalWaypointDriver for GlobalWaypointDriverCore {
    navigator_common!(gwd);
    fn on_set_global_waypoint(
        &mut self,
        ctx: &mut gwd::Ctx<'_>,
        m: &SetGlobalWaypoint,
    ) -> Result<(), Refused> {
        self.set_element(ctx, m)
    }
    fn on_query_global_waypoint(
        &mut self,
        _ctx: &mut gwd::Ctx<'_>,
        q: &QueryGlobalWaypoint,
    ) -> Result<ReportGlobalWaypoint, Refused> {
        let w = self
            .elements
            .get(usize::from(q.waypoint_number))
            .ok_or_else(|| Refused::Invalid(format!("no waypoint {}", q.waypoint_number)))?;
        Ok(ReportGlobalWaypoint {
            waypoint_number: w.waypoint_number,
            latitude: w.latitude,
            longitude: w.longitude,
            elevation: w.elevation,
            roll: w.roll,
            pitch: w.pitch,
            yaw: w.yaw,
        })
    }
    fn on_query_waypoint_count(
        &mut self,
        _ctx: &mut gwd::Ctx<'_>,
        _q: &QueryWaypointCount,
    ) -> Result<ReportWaypointCount, Refused> {
        Ok(ReportWaypointCount {
            waypoint_count: self.elements.len() as u16,
        })
    }
    fn on_report_global_pose(
        &mut self,
        ctx: &mut gwd::Ctx<'_>,
        r: &ReportGlobalPose,
    ) -> Result<(), Refused> {
        self.motion.on_global_pose(ctx.now(), r);
        Ok(())
    }
}

impl lwd::LocalWaypointDriver for LocalWaypointDriverCore {
    navigator_common!(lwd);
    fn on_set_local_waypoint(
        &mut self,
        ctx: &mut lwd::Ctx<'_>,
        m: &SetLocalWaypoint,
    ) -> Result<(), Refused> {
        self.set_element(ctx, m)
    }
    fn on_query_local_waypoint(
        &mut self,
        _ctx: &mut lwd::Ctx<'_>,
        q: &QueryLocalWaypoint,
    ) -> Result<ReportLocalWaypoint, Refused> {
        let w = self
            .elements
            .get(usize::from(q.waypoint_number))
            .ok_or_else(|| Refused::Invalid(format!("no waypoint {}", q.waypoint_number)))?;
        Ok(ReportLocalWaypoint {
            waypoint_number: w.waypoint_number,
            x: w.x,
            y: w.y,
            z: w.z,
            roll: w.roll,
            pitch: w.pitch,
            yaw: w.yaw,
        })
    }
    fn on_query_waypoint_count(
        &mut self,
        _ctx: &mut lwd::Ctx<'_>,
        _q: &QueryWaypointCount,
    ) -> Result<ReportWaypointCount, Refused> {
        Ok(ReportWaypointCount {
            waypoint_count: self.elements.len() as u16,
        })
    }
    fn on_report_local_pose(
        &mut self,
        ctx: &mut lwd::Ctx<'_>,
        r: &ReportLocalPose,
    ) -> Result<(), Refused> {
        self.motion.on_local_pose(ctx.now(), r);
        Ok(())
    }
}

impl gpsd::GlobalPathSegmentDriver for GlobalPathSegmentDriverCore {
    navigator_common!(gpsd);
    fn on_set_global_path_segment(
        &mut self,
        ctx: &mut gpsd::Ctx<'_>,
        m: &SetGlobalPathSegment,
    ) -> Result<(), Refused> {
        self.set_element(ctx, m)
    }
    fn on_query_global_path_segment(
        &mut self,
        _ctx: &mut gpsd::Ctx<'_>,
        q: &QueryGlobalPathSegment,
    ) -> Result<ReportGlobalPathSegment, Refused> {
        let s = self
            .elements
            .get(usize::from(q.path_segment_number))
            .ok_or_else(|| {
                Refused::Invalid(format!("no path segment {}", q.path_segment_number))
            })?;
        Ok(ReportGlobalPathSegment {
            path_segment_number: s.path_segment_number,
            p1_latitude: s.p1_latitude,
            p1_longitude: s.p1_longitude,
            p1_altitude: s.p1_altitude.filter(|_| q.presence_vector & 1 != 0),
            p2_latitude: s.p2_latitude,
            p2_longitude: s.p2_longitude,
            p2_altitude: s.p2_altitude.filter(|_| q.presence_vector & 2 != 0),
            weighting_factor: s.weighting_factor,
        })
    }
    fn on_query_path_segment_count(
        &mut self,
        _ctx: &mut gpsd::Ctx<'_>,
        _q: &QueryPathSegmentCount,
    ) -> Result<ReportPathSegmentCount, Refused> {
        Ok(ReportPathSegmentCount {
            path_segment_count: self.elements.len() as u16,
        })
    }
    fn on_report_global_pose(
        &mut self,
        ctx: &mut gpsd::Ctx<'_>,
        r: &ReportGlobalPose,
    ) -> Result<(), Refused> {
        self.motion.on_global_pose(ctx.now(), r);
        Ok(())
    }
}

impl lpsd::LocalPathSegmentDriver for LocalPathSegmentDriverCore {
    navigator_common!(lpsd);
    fn on_set_local_path_segment(
        &mut self,
        ctx: &mut lpsd::Ctx<'_>,
        m: &SetLocalPathSegment,
    ) -> Result<(), Refused> {
        self.set_element(ctx, m)
    }
    fn on_query_local_path_segment(
        &mut self,
        _ctx: &mut lpsd::Ctx<'_>,
        q: &QueryLocalPathSegment,
    ) -> Result<ReportLocalPathSegment, Refused> {
        let s = self
            .elements
            .get(usize::from(q.path_segment_number))
            .ok_or_else(|| {
                Refused::Invalid(format!("no path segment {}", q.path_segment_number))
            })?;
        Ok(ReportLocalPathSegment {
            path_segment_number: s.path_segment_number,
            p1_x: s.p1_x,
            p1_y: s.p1_y,
            p1_z: s.p1_z.filter(|_| q.presence_vector & 1 != 0),
            p2_x: s.p2_x,
            p2_y: s.p2_y,
            p2_z: s.p2_z.filter(|_| q.presence_vector & 2 != 0),
            weighting_factor: s.weighting_factor,
        })
    }
    fn on_query_path_segment_count(
        &mut self,
        _ctx: &mut lpsd::Ctx<'_>,
        _q: &QueryPathSegmentCount,
    ) -> Result<ReportPathSegmentCount, Refused> {
        Ok(ReportPathSegmentCount {
            path_segment_count: self.elements.len() as u16,
        })
    }
    fn on_report_local_pose(
        &mut self,
        ctx: &mut lpsd::Ctx<'_>,
        r: &ReportLocalPose,
    ) -> Result<(), Refused> {
        self.motion.on_local_pose(ctx.now(), r);
        Ok(())
    }
}

use crate::JausMessage;
