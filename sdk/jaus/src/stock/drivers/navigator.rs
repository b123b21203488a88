//! The Global and Local Waypoint and Path Segment Drivers (Part 1 §5.3): one
//! [`Navigator`] over element lists, pursuing straight legs or Part 1 path segments.

use nalgebra::{Vector2, Vector3};
use std::time::Instant;

use super::finite;
use crate::component::{
    Context, CoreState, EmittedBy, InitError, Interface, Modes, Refused, StopReason,
};
use crate::components::parts::NavigationDriver;
use crate::components::{
    global_path_segment_driver as gpsd, global_waypoint_driver as gwd,
    local_path_segment_driver as lpsd, local_waypoint_driver as lwd,
};
use crate::messages::*;
use crate::stock::geo::LocalFrame;
use crate::stock::motion::{DriverConfig, Motion};
use crate::stock::path::{Path, PathSegment};
use crate::{Address, CommandCode};

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
    /// The speed last commanded and when (speed rises at most at the deceleration
    /// rate, so that the vehicle leaves a turn on its new heading).
    commanded: Option<(Instant, f64)>,
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
pub type StockGlobalWaypointDriver = Navigator<SetGlobalWaypoint>;
/// The Local Waypoint Driver.
pub type StockLocalWaypointDriver = Navigator<SetLocalWaypoint>;
/// The Global Path Segment Driver.
pub type StockGlobalPathSegmentDriver = Navigator<SetGlobalPathSegment>;
/// The Local Path Segment Driver.
pub type StockLocalPathSegmentDriver = Navigator<SetLocalPathSegment>;

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
        Refused::check_range("speed", speed, 0.0, self.motion.config.max_speed, "m/s")?;
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
        Some(Tracker {
            path,
            ends,
            s: 0.0,
            commanded: None,
        })
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

/// The part the four drivers share (`NavigationDriver` of `platform.yaml`): the travel
/// speed, the pose and velocity feedback, the element count, spooled lists, subscribing
/// to the pose report, and what happens on state changes and every tick.
impl<E: Element, I: NavInterface> NavigationDriver<I> for Navigator<E>
where
    SetWrenchEffort: EmittedBy<I>,
    ReportMissionStatus: EmittedBy<I>,
{
    fn on_set_travel_speed(
        &mut self,
        _ctx: &mut Context<'_, I>,
        m: &SetTravelSpeed,
    ) -> Result<(), Refused> {
        self.set_speed(m.speed)
    }

    fn on_spool_mission(
        &mut self,
        ctx: &mut Context<'_, I>,
        m: &SpoolMission,
    ) -> Result<(), Refused> {
        self.spool(ctx, m)
    }

    fn on_query_spooling_preference(
        &mut self,
        _ctx: &mut Context<'_, I>,
        _q: &QuerySpoolingPreference,
    ) -> Result<ReportSpoolingPreference, Refused> {
        Ok(ReportSpoolingPreference {
            spool_type: SpoolingLimitType::MessageCount,
            data: 4096,
        })
    }

    fn on_query_travel_speed(
        &mut self,
        _ctx: &mut Context<'_, I>,
        _q: &QueryTravelSpeed,
    ) -> Result<ReportTravelSpeed, Refused> {
        Ok(ReportTravelSpeed {
            speed: self.travel_speed,
        })
    }

    fn on_report_velocity_state(
        &mut self,
        ctx: &mut Context<'_, I>,
        r: &ReportVelocityState,
    ) -> Result<(), Refused> {
        self.motion.on_velocity(ctx.now(), r);
        Ok(())
    }

    fn on_query_waypoint_count(
        &mut self,
        _ctx: &mut Context<'_, I>,
        _q: &QueryWaypointCount,
    ) -> Result<ReportWaypointCount, Refused> {
        Ok(ReportWaypointCount {
            waypoint_count: self.elements.len() as u16,
        })
    }

    fn on_query_path_segment_count(
        &mut self,
        _ctx: &mut Context<'_, I>,
        _q: &QueryPathSegmentCount,
    ) -> Result<ReportPathSegmentCount, Refused> {
        Ok(ReportPathSegmentCount {
            path_segment_count: self.elements.len() as u16,
        })
    }

    fn on_report_global_pose(
        &mut self,
        ctx: &mut Context<'_, I>,
        r: &ReportGlobalPose,
    ) -> Result<(), Refused> {
        self.motion.on_global_pose(ctx.now(), r);
        Ok(())
    }

    fn on_report_local_pose(
        &mut self,
        ctx: &mut Context<'_, I>,
        r: &ReportLocalPose,
    ) -> Result<(), Refused> {
        self.motion.on_local_pose(ctx.now(), r);
        Ok(())
    }

    fn initialize(&mut self, ctx: &mut Context<'_, I>) -> Result<(), InitError> {
        self.motion.subscribe(ctx, I::POSE_REPORT);
        Ok(())
    }

    fn state_changed(&mut self, ctx: &mut Context<'_, I>, from: CoreState, to: CoreState) {
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

    fn tick(&mut self, ctx: &mut Context<'_, I>) {
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
        let remaining = (len - t.s).max(to_end);
        // Slow enough to stop at the end, and to take the turns ahead within the
        // corner tolerance (turning at half the platform's yaw rate, the rest kept for
        // steering).
        let speed = t
            .path
            .turn_speed(
                t.s,
                self.travel_speed
                    .min((2.0 * c.deceleration * remaining).sqrt()),
                (
                    0.5 * c.deceleration,
                    c.corner_tolerance,
                    0.5 * c.max_yaw_rate,
                    0.3,
                ),
            )
            .max(0.05);
        // From the speed last commanded, or at the start from the speed measured.
        let (at, last) = t
            .commanded
            .unwrap_or((now, self.motion.speed(now).unwrap_or(0.0).max(0.0)));
        let dt = now.saturating_duration_since(at).as_secs_f64();
        let speed = speed.min(last + c.deceleration * dt).max(0.05);
        t.commanded = Some((now, speed));
        // Look ahead less when slow (through a turn) so the pursuit cuts less of it.
        let lookahead = c.lookahead.min(0.15 + 0.5 * speed);
        let target = if len - t.s <= lookahead {
            end
        } else {
            t.path.at(t.s + lookahead)
        };
        let d = target - pos;
        let heading = d.y.atan2(d.x);
        self.motion.drive(ctx, speed, heading);
    }
}

impl gwd::GlobalWaypointDriver for StockGlobalWaypointDriver {
    fn navigation_driver(&mut self) -> Option<&mut dyn NavigationDriver<gwd::Interface>> {
        Some(self)
    }
    fn stop(&mut self, ctx: &mut gwd::Ctx<'_>, reason: StopReason) {
        Navigator::stop(self, ctx, reason);
    }
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
        Ok(super::elements::global_waypoint_report(w))
    }
}

impl lwd::LocalWaypointDriver for StockLocalWaypointDriver {
    fn navigation_driver(&mut self) -> Option<&mut dyn NavigationDriver<lwd::Interface>> {
        Some(self)
    }
    fn stop(&mut self, ctx: &mut lwd::Ctx<'_>, reason: StopReason) {
        Navigator::stop(self, ctx, reason);
    }
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
        Ok(super::elements::local_waypoint_report(w))
    }
}

impl gpsd::GlobalPathSegmentDriver for StockGlobalPathSegmentDriver {
    fn navigation_driver(&mut self) -> Option<&mut dyn NavigationDriver<gpsd::Interface>> {
        Some(self)
    }
    fn stop(&mut self, ctx: &mut gpsd::Ctx<'_>, reason: StopReason) {
        Navigator::stop(self, ctx, reason);
    }
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
        Ok(super::elements::global_path_segment_report(
            s,
            q.presence_vector,
        ))
    }
}

impl lpsd::LocalPathSegmentDriver for StockLocalPathSegmentDriver {
    fn navigation_driver(&mut self) -> Option<&mut dyn NavigationDriver<lpsd::Interface>> {
        Some(self)
    }
    fn stop(&mut self, ctx: &mut lpsd::Ctx<'_>, reason: StopReason) {
        Navigator::stop(self, ctx, reason);
    }
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
        Ok(super::elements::local_path_segment_report(
            s,
            q.presence_vector,
        ))
    }
}

use crate::JausMessage;
