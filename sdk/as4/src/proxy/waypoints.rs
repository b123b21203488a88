//! The proxy's Global and Local Waypoint Drivers over the vehicle's AS-4 Global and
//! Local Waypoint List Drivers; the Path Segment Drivers ([`super::segments`]) are the
//! same machinery over other kinds ([`Kind`]).
//!
//! RA 3.3 gives a waypoint driver numbered waypoints (number 0 starts a new list) and a
//! travel speed, and it drives in Ready while the speed is not zero. The proxy keeps
//! both; once it is Ready with waypoints, a speed above zero and AS-4 control, it
//! replaces the vehicle's list (Delete Element of every element, then one Set Element
//! holding the waypoints as AS-4 Set Global/Local Waypoint messages, UIDs 1…n linked
//! in order) and sends Execute List from UID 1 at that speed. A new speed while the list
//! runs is an Execute List from the active element. The proxy then polls Query Active
//! Element: Query Waypoint Count answers the elements not yet passed; when the active
//! element is 0 again (the list is done) the driver returns to Standby, as Part 1 asks
//! at the final waypoint.

use std::fmt;
use std::marker::PhantomData;
use std::time::{Duration, Instant};

use jaus::component::{Behaviour, Context, CoreState, Interface, Refused, StopReason};
use jaus::components::{global_waypoint_driver as gwd, local_waypoint_driver as lwd};
use jaus::messages::{self as ra, Message as Ra33Message};
use jaus::stock::drivers::elements;
use jaus::JausMessage;

use super::behaviours::state_to_as4;
use super::shared::{lock, Shared, SharedRef};
use super::Role;
use crate::core::lists::DELETE_ALL;
use crate::messages::{self as as4, Element, Message};

/// An active element of 0 this long after Execute List, never having seen another:
/// the list was done before the first answer.
const DONE_WITHOUT_PROGRESS: Duration = Duration::from_secs(1);

/// Global or local waypoints or path segments: what differs between the drivers
/// (implemented by [`Global`] and [`Local`] and the kinds of [`super::segments`] only).
pub trait Kind: Send + 'static {
    /// The RA 3.3 interface.
    type Iface: Interface<Messages = Ra33Message>;
    /// The role presented.
    const ROLE: Role;
    /// What one element is called in refusals ("waypoint", "path segment").
    const ELEMENT: &'static str;
    /// The element number of a Set Waypoint (or Path Segment) of this kind.
    fn set_number(m: &Ra33Message) -> Option<u16>;
    /// The element number a Query Waypoint (or Path Segment) of this kind asks for.
    fn query_number(m: &Ra33Message) -> Option<u16>;
    /// The report of a stored Set message, answering `query`.
    fn report(set: &Ra33Message, query: &Ra33Message) -> Option<Ra33Message>;
    /// The answer to `m` if it is this kind's count query (Query Waypoint Count, Query
    /// Path Segment Count): `remaining` elements.
    fn count(m: &Ra33Message, remaining: u16) -> Option<Ra33Message>;
    /// The AS-4 Set message of a stored RA 3.3 one (local: into the AS-4 frame).
    fn as4(set: &Ra33Message, s: &Shared) -> Option<Message>;
    /// The mode change to Navigating.
    fn start(ctx: &mut Context<'_, Self::Iface>);
    /// The mode change back to Idle, which puts the component in Standby.
    fn arrive(ctx: &mut Context<'_, Self::Iface>);
}

/// Global waypoints (RA 3.3 Global Waypoint Driver, AS-4 Global Waypoint List Driver).
#[derive(Debug)]
pub struct Global;

/// Local waypoints (RA 3.3 Local Waypoint Driver, AS-4 Local Waypoint List Driver).
#[derive(Debug)]
pub struct Local;

/// Report Waypoint Count with `remaining` if `m` is Query Waypoint Count.
fn waypoint_count(m: &Ra33Message, remaining: u16) -> Option<Ra33Message> {
    match m {
        Ra33Message::QueryWaypointCount(_) => Some(
            ra::ReportWaypointCount {
                waypoint_count: remaining,
            }
            .into(),
        ),
        _ => None,
    }
}

impl Kind for Global {
    type Iface = gwd::Interface;
    const ROLE: Role = Role::GlobalWaypointDriver;
    const ELEMENT: &'static str = "waypoint";

    fn set_number(m: &Ra33Message) -> Option<u16> {
        match m {
            Ra33Message::SetGlobalWaypoint(w) => Some(w.waypoint_number),
            _ => None,
        }
    }

    fn query_number(m: &Ra33Message) -> Option<u16> {
        match m {
            Ra33Message::QueryGlobalWaypoint(q) => Some(q.waypoint_number),
            _ => None,
        }
    }

    fn report(set: &Ra33Message, _query: &Ra33Message) -> Option<Ra33Message> {
        let Ra33Message::SetGlobalWaypoint(w) = set else {
            return None;
        };
        Some(elements::global_waypoint_report(w).into())
    }

    fn count(m: &Ra33Message, remaining: u16) -> Option<Ra33Message> {
        waypoint_count(m, remaining)
    }

    fn as4(set: &Ra33Message, _s: &Shared) -> Option<Message> {
        let Ra33Message::SetGlobalWaypoint(w) = set else {
            return None;
        };
        Some(
            as4::SetGlobalWaypoint {
                latitude: w.latitude,
                longitude: w.longitude,
                altitude: w.elevation,
                roll: w.roll,
                pitch: w.pitch,
                yaw: w.yaw,
                ..Default::default()
            }
            .into(),
        )
    }

    fn start(ctx: &mut Context<'_, gwd::Interface>) {
        let _ = ctx.transition(gwd::Transition::Start);
    }

    fn arrive(ctx: &mut Context<'_, gwd::Interface>) {
        let _ = ctx.transition(gwd::Transition::Arrive);
    }
}

impl Kind for Local {
    type Iface = lwd::Interface;
    const ROLE: Role = Role::LocalWaypointDriver;
    const ELEMENT: &'static str = "waypoint";

    fn set_number(m: &Ra33Message) -> Option<u16> {
        match m {
            Ra33Message::SetLocalWaypoint(w) => Some(w.waypoint_number),
            _ => None,
        }
    }

    fn query_number(m: &Ra33Message) -> Option<u16> {
        match m {
            Ra33Message::QueryLocalWaypoint(q) => Some(q.waypoint_number),
            _ => None,
        }
    }

    fn report(set: &Ra33Message, _query: &Ra33Message) -> Option<Ra33Message> {
        let Ra33Message::SetLocalWaypoint(w) = set else {
            return None;
        };
        Some(elements::local_waypoint_report(w).into())
    }

    fn count(m: &Ra33Message, remaining: u16) -> Option<Ra33Message> {
        waypoint_count(m, remaining)
    }

    fn as4(set: &Ra33Message, s: &Shared) -> Option<Message> {
        let Ra33Message::SetLocalWaypoint(w) = set else {
            return None;
        };
        let (x, y) = s.frame.to_as4(w.x, w.y);
        Some(
            as4::SetLocalWaypoint {
                x,
                y,
                z: w.z,
                roll: w.roll,
                pitch: w.pitch,
                yaw: w.yaw.map(|a| s.frame.yaw_to_as4(a)),
                ..Default::default()
            }
            .into(),
        )
    }

    fn start(ctx: &mut Context<'_, lwd::Interface>) {
        let _ = ctx.transition(lwd::Transition::Start);
    }

    fn arrive(ctx: &mut Context<'_, lwd::Interface>) {
        let _ = ctx.transition(lwd::Transition::Arrive);
    }
}

/// The list running on the vehicle.
#[derive(Debug, Clone, Copy)]
struct Run {
    /// Elements, UIDs 1…n.
    n: u16,
    /// When Execute List was queued.
    sent: Instant,
    /// Whether an active element other than 0 was reported since.
    seen: bool,
    /// The latest active element reported.
    active: u16,
}

/// A proxy waypoint (or path segment) driver of kind `K` (see the module's
/// documentation).
pub struct WaypointDriver<K: Kind> {
    shared: SharedRef,
    points: Vec<Ra33Message>,
    speed: f64,
    points_dirty: bool,
    speed_dirty: bool,
    run: Option<Run>,
    request_id: u8,
    _kind: PhantomData<fn() -> K>,
}

impl<K: Kind> fmt::Debug for WaypointDriver<K> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("WaypointDriver")
            .field("role", &K::ROLE)
            .field("points", &self.points.len())
            .field("speed", &self.speed)
            .field("run", &self.run)
            .finish()
    }
}

impl<K: Kind> WaypointDriver<K> {
    /// The driver presenting the vehicle's list driver from `shared`.
    pub fn new(shared: SharedRef) -> Self {
        Self {
            shared,
            points: Vec::new(),
            speed: 0.0,
            points_dirty: false,
            speed_dirty: false,
            run: None,
            request_id: 0,
            _kind: PhantomData,
        }
    }

    /// Elements not yet passed.
    fn remaining(&self) -> u16 {
        match &self.run {
            Some(r) if r.active == 0 => {
                if r.seen {
                    0
                } else {
                    r.n
                }
            }
            Some(r) => r.n.saturating_sub(r.active - 1),
            None => u16::try_from(self.points.len()).unwrap_or(u16::MAX),
        }
    }

    fn set_point(&mut self, n: u16, m: &Ra33Message) -> Result<(), Refused> {
        if n == 0 {
            self.points.clear();
        }
        let i = usize::from(n);
        if i < self.points.len() {
            self.points[i] = m.clone();
        } else if i == self.points.len() && i < MAX_WAYPOINTS {
            self.points.push(m.clone());
        } else {
            return Err(Refused::Invalid(format!(
                "{} number {n}: the next one is {} (at most {MAX_WAYPOINTS})",
                K::ELEMENT,
                self.points.len()
            )));
        }
        self.points_dirty = true;
        Ok(())
    }

    fn next_request(&mut self) -> u8 {
        self.request_id = self.request_id.wrapping_add(1);
        self.request_id
    }

    /// Replaces the vehicle's list and executes it; false when it cannot be sent yet.
    fn execute(&mut self, s: &mut Shared, now: Instant) -> bool {
        let Some(at) = s.service(K::ROLE) else {
            return false;
        };
        let n = self.points.len();
        let mut elements = Vec::with_capacity(n);
        for (i, p) in self.points.iter().enumerate() {
            let uid = i as u16 + 1;
            let next = if i + 1 < n { uid + 1 } else { 0 };
            let held = K::as4(p, s).map(|m| Element::holding(uid, uid - 1, next, &m));
            match held {
                Some(Ok(e)) => elements.push(e),
                Some(Err(e)) => {
                    tracing::warn!(role = ?K::ROLE, uid, "{} not encoded: {e}", K::ELEMENT);
                    return false;
                }
                None => return false,
            }
        }
        let (delete, set) = (self.next_request(), self.next_request());
        s.send(
            at,
            as4::DeleteElement {
                request_id: delete,
                element_uids: vec![DELETE_ALL],
            },
        );
        s.send(
            at,
            as4::SetElement {
                request_id: set,
                elements,
            },
        );
        s.send(
            at,
            as4::ExecuteList {
                speed: self.speed,
                element_uid: Some(1),
            },
        );
        s.set_executing(at, true);
        tracing::info!(role = ?K::ROLE, %at, elements = n, speed = self.speed, "list sent to the AS-4 vehicle");
        self.run = Some(Run {
            n: n as u16,
            sent: now,
            seen: false,
            active: 0,
        });
        true
    }

    /// Follows the vehicle's active element; true when the list is done.
    fn progress(&mut self, s: &Shared, now: Instant) -> bool {
        let Some(run) = self.run.as_mut() else {
            return false;
        };
        if let Some((t, Message::ReportActiveElement(a))) =
            s.report(K::ROLE, as4::ReportActiveElement::CODE)
        {
            if t > run.sent {
                if a.element_uid != 0 {
                    run.seen = true;
                    run.active = a.element_uid;
                } else if run.seen
                    || now.saturating_duration_since(run.sent) >= DONE_WITHOUT_PROGRESS
                {
                    run.active = 0;
                    return true;
                }
            }
        }
        false
    }

    fn end_run(&mut self, s: &mut Shared) {
        if self.run.take().is_some() {
            if let Some(at) = s.service(K::ROLE) {
                s.set_executing(at, false);
            }
        }
    }
}

/// Most waypoints (or path segments) of one list.
pub const MAX_WAYPOINTS: usize = 1000;

impl<K: Kind> Behaviour for WaypointDriver<K> {
    type Interface = K::Iface;

    fn handle(
        &mut self,
        _ctx: &mut Context<'_, K::Iface>,
        msg: &Ra33Message,
    ) -> Result<Option<Ra33Message>, Refused> {
        if let Some(n) = K::set_number(msg) {
            self.set_point(n, msg)?;
            return Ok(None);
        }
        if let Some(n) = K::query_number(msg) {
            return self
                .points
                .get(usize::from(n))
                .and_then(|p| K::report(p, msg))
                .map(Some)
                .ok_or_else(|| {
                    let what = K::ELEMENT;
                    Refused::Invalid(format!("{what} number {n}: no such {what}"))
                });
        }
        if let Some(r) = K::count(msg, self.remaining()) {
            return Ok(Some(r));
        }
        match msg {
            Ra33Message::SetTravelSpeed(t) => {
                if !t.speed.is_finite() || t.speed < 0.0 {
                    return Err(Refused::Invalid(format!("speed {}: not a speed", t.speed)));
                }
                self.speed = t.speed;
                self.speed_dirty = true;
                Ok(None)
            }
            Ra33Message::QueryTravelSpeed(_) => {
                Ok(Some(ra::ReportTravelSpeed { speed: self.speed }.into()))
            }
            // Reports a navigation driver listens to: the vehicle drives itself.
            Ra33Message::ReportGlobalPose(_)
            | Ra33Message::ReportLocalPose(_)
            | Ra33Message::ReportVelocityState(_) => Ok(None),
            _ => Err(Refused::Unsupported),
        }
    }

    fn tick(&mut self, ctx: &mut Context<'_, K::Iface>) {
        let now = ctx.now();
        let done = {
            let shared = self.shared.clone();
            let mut s = lock(&shared);
            let done = self.progress(&s, now);
            if done {
                tracing::info!(role = ?K::ROLE, "AS-4 list done");
                self.end_run(&mut s);
                self.points.clear();
            }
            done
        };
        if done {
            // Part 1: back to Standby at the final point (which tells the vehicle).
            K::arrive(ctx);
            return;
        }
        if ctx.state() != CoreState::Ready || !(self.points_dirty || self.speed_dirty) {
            return;
        }
        let started = {
            let shared = self.shared.clone();
            let mut s = lock(&shared);
            if !s.holds(K::ROLE) {
                return;
            }
            if self.points_dirty && self.speed > 0.0 && !self.points.is_empty() {
                let sent = self.execute(&mut s, now);
                if sent {
                    self.points_dirty = false;
                    self.speed_dirty = false;
                }
                sent
            } else {
                if self.speed_dirty {
                    if let (Some(run), Some(at)) = (self.run, s.service(K::ROLE)) {
                        s.send(
                            at,
                            as4::ExecuteList {
                                speed: self.speed,
                                element_uid: Some(run.active.max(1)),
                            },
                        );
                    }
                    self.speed_dirty = false;
                }
                false
            }
        };
        if started {
            K::start(ctx);
        }
    }

    fn state_changed(&mut self, _ctx: &mut Context<'_, K::Iface>, from: CoreState, to: CoreState) {
        let shared = self.shared.clone();
        let mut s = lock(&shared);
        if from == CoreState::Standby && to == CoreState::Ready {
            // Part 1: the travel speed is zero after every Standby → Ready.
            self.speed = 0.0;
        }
        if from == CoreState::Ready && to != CoreState::Ready {
            self.end_run(&mut s);
            // Driven again from the first element after the next Resume and speed.
            self.points_dirty = !self.points.is_empty();
        }
        state_to_as4(&mut s, K::ROLE, from, to);
    }

    fn stop(&mut self, _ctx: &mut Context<'_, K::Iface>, reason: StopReason) {
        tracing::debug!(role = ?K::ROLE, %reason, "proxy list driver stops");
        let shared = self.shared.clone();
        self.end_run(&mut lock(&shared));
    }
}
