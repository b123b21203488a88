//! The waypoints: a short list of local waypoints a few metres from the pose set,
//! loaded through the List Manager, then (with motion allowed) driven by the Local
//! Waypoint List Driver to its end while the judge reads the active element, the
//! travel speed and the active waypoint.

use std::time::{Duration, Instant};

use jaus_as4::messages::{
    ComponentState, Element, Message, QueryActiveElement, QueryElementCount, QueryElementList,
    QueryLocalPose, QueryLocalWaypoint, QueryTravelSpeed, SetElement, SetLocalWaypoint, Standby,
};
use jaus_as4::ExecuteList;

use super::Scenario;
use crate::check::Verdict;
use crate::engine::{fail, inconclusive, pass, Found};

/// The waypoints' offsets from the pose set (m): a 2 m square's three other corners.
const OFFSETS: [(f64, f64); 3] = [(2.0, 0.0), (2.0, 2.0), (0.0, 2.0)];
/// The request id of Set Element.
const REQUEST_ID: u8 = 42;
/// How often the active element is asked while the list runs.
const POLL: Duration = Duration::from_millis(500);
/// How far a reported waypoint may be from the one loaded (m): a few counts of its
/// 32-bit scaling.
const WAYPOINT_TOLERANCE: f64 = 0.01;
/// How far the reported travel speed may be from the one executed (m/s): a count of its
/// 16-bit scaling, and some.
const SPEED_TOLERANCE: f64 = 0.01;

impl Scenario<'_> {
    /// Where the list starts from: the pose set, else the pose reported, else 0, 0.
    fn base(&mut self) -> (f64, f64) {
        if self.pose_set {
            let (x, y, _) = self.j.opts.pose;
            return (x, y);
        }
        match self.j.ask(
            QueryLocalPose {
                presence_vector: 0x0003,
            }
            .into(),
        ) {
            Ok(Message::ReportLocalPose(r)) => (r.x.unwrap_or(0.0), r.y.unwrap_or(0.0)),
            _ => (0.0, 0.0),
        }
    }

    /// The active element, or why not.
    fn active(&mut self) -> Result<u16, String> {
        match self.j.ask(QueryActiveElement {}.into())? {
            Message::ReportActiveElement(r) => Ok(r.element_uid),
            m => Err(format!("Query Active Element answered by {}", m.name())),
        }
    }

    /// `as4.waypoints.set_element`.
    pub(super) fn set_element(&mut self) -> Found {
        if let Some(f) = self.needs_control() {
            return f;
        }
        if let Err(e) = self.ensure_ready() {
            return inconclusive(e);
        }
        let (x0, y0) = self.base();
        let n = OFFSETS.len() as u16;
        let mut elements = Vec::new();
        self.waypoints.clear();
        for (i, (dx, dy)) in OFFSETS.iter().enumerate() {
            let uid = i as u16 + 1;
            let (x, y) = (x0 + dx, y0 + dy);
            let wp = SetLocalWaypoint {
                x,
                y,
                ..SetLocalWaypoint::default()
            };
            let next = if uid == n { 0 } else { uid + 1 };
            match Element::holding(uid, uid - 1, next, &wp.into()) {
                Ok(e) => elements.push(e),
                Err(e) => return inconclusive(format!("cannot encode waypoint {uid}: {e}")),
            }
            self.waypoints.push((uid, x, y));
        }
        let list: Vec<String> = self
            .waypoints
            .iter()
            .map(|(u, x, y)| format!("{u}: ({x:.1}, {y:.1})"))
            .collect();
        self.j.send(
            &SetElement {
                request_id: REQUEST_ID,
                elements,
            }
            .into(),
        );
        let peer = self.j.peer;
        let Some(a) = self
            .j
            .wait_for(self.j.opts.wait, Some(peer), &[0x041C, 0x041D])
        else {
            return fail(format!(
                "no Confirm Element Request within {:.1} s",
                self.j.opts.wait.as_secs_f64()
            ));
        };
        match Message::decode(jaus::CommandCode(a.message.message_id), &a.message.body) {
            Ok(Message::ConfirmElementRequest(c)) if c.request_id == REQUEST_ID => {
                self.listed = true;
                pass(format!(
                    "Confirm Element Request {REQUEST_ID} for {} local waypoints {}",
                    n,
                    list.join(", ")
                ))
            }
            Ok(Message::ConfirmElementRequest(c)) => fail(format!(
                "Confirm Element Request with request id {}, not {REQUEST_ID}",
                c.request_id
            )),
            Ok(Message::RejectElementRequest(r)) => fail(format!(
                "Reject Element Request {:?} (request id {})",
                r.response_code, r.request_id
            )),
            Ok(m) => fail(format!("Set Element answered by {}", m.name())),
            Err(e) => fail(format!("the answer does not decode: {e}")),
        }
    }

    /// The UIDs loaded, in order.
    fn uids(&self) -> Vec<u16> {
        self.waypoints.iter().map(|w| w.0).collect()
    }

    /// `as4.waypoints.element_list`: the UIDs loaded, in order (other elements the
    /// vehicle kept from before are noted, not counted against it).
    pub(super) fn element_list(&mut self) -> Found {
        if !self.listed {
            return inconclusive("not run: Set Element was not confirmed");
        }
        let got = match self.j.ask(QueryElementList {}.into()) {
            Ok(Message::ReportElementList(r)) => r.element_uids,
            Ok(m) => return fail(format!("Query Element List answered by {}", m.name())),
            Err(e) => return fail(e),
        };
        self.list_len = Some(got.len());
        let want = self.uids();
        if got == want {
            pass(format!("{got:?}"))
        } else if got.windows(want.len()).any(|w| w == want.as_slice()) {
            pass(format!(
                "{got:?}: the {} loaded in order, among elements kept from before",
                want.len()
            ))
        } else {
            fail(format!("{got:?}, not {want:?} in order"))
        }
    }

    /// `as4.waypoints.element_count`.
    pub(super) fn element_count(&mut self) -> Found {
        if !self.listed {
            return inconclusive("not run: Set Element was not confirmed");
        }
        let got = match self.j.ask(QueryElementCount {}.into()) {
            Ok(Message::ReportElementCount(r)) => usize::from(r.element_count),
            Ok(m) => return fail(format!("Query Element Count answered by {}", m.name())),
            Err(e) => return fail(e),
        };
        let want = self.list_len.unwrap_or(self.waypoints.len());
        if got == want {
            pass(format!("{got}"))
        } else {
            fail(format!(
                "{got}, but {want} elements are listed ({} loaded)",
                self.waypoints.len()
            ))
        }
    }

    /// Why the checks of the list driven cannot run: no motion allowed, no control, no
    /// list loaded, or (after the first) Execute List did not start it. They run in
    /// time order: Execute List, then travel speed and local waypoint while the list
    /// runs, then the active element to the list's end.
    pub(super) fn mission_blocked(&self, id: &str) -> Option<&'static str> {
        if !self.j.opts.allow_motion {
            Some("Execute List moves the vehicle: give --allow-motion to run it")
        } else if !self.controlled {
            Some("the judge does not hold control (as4.control.request)")
        } else if !self.listed {
            Some("no list was loaded (as4.waypoints.set_element)")
        } else if id != "as4.waypoints.execute" && self.executed.is_none() {
            Some("Execute List did not start the list")
        } else {
            None
        }
    }

    /// `as4.waypoints.execute`, remembering when the list started if it did.
    pub(super) fn execute_list(&mut self) -> Found {
        let started = self.j.now();
        let found = self.execute();
        if found.0 == Verdict::Pass {
            self.executed = Some(started);
        }
        found
    }

    /// `as4.waypoints.active_element`: followed from when Execute List started it.
    pub(super) fn active_element(&mut self) -> Found {
        match self.executed {
            Some(started) => self.follow(started),
            None => inconclusive("Execute List did not start the list"),
        }
    }

    /// `as4.waypoints.execute`: Ready, Execute List from the first UID, then the active
    /// element is one of the list.
    fn execute(&mut self) -> Found {
        if let Err(e) = self.ensure_ready() {
            return inconclusive(e);
        }
        let uids = self.uids();
        let first = uids.first().copied().unwrap_or(1);
        let speed = self.j.opts.speed;
        self.j.command(
            ExecuteList {
                speed,
                element_uid: Some(first),
            }
            .into(),
        );
        match self.active() {
            Ok(a) if uids.contains(&a) => pass(format!(
                "Execute List at {speed} m/s from {first}: active element {a}"
            )),
            Ok(a) => fail(format!(
                "after Execute List at {speed} m/s from {first} the active element is {a}, not one of {uids:?}"
            )),
            Err(e) => fail(format!("after Execute List: {e}")),
        }
    }

    /// `as4.waypoints.travel_speed`, while the list runs.
    pub(super) fn travel_speed(&mut self) -> Found {
        let want = self.j.opts.speed;
        match self.j.ask(QueryTravelSpeed {}.into()) {
            Ok(Message::ReportTravelSpeed(r)) if (r.speed - want).abs() <= SPEED_TOLERANCE => {
                pass(format!("{:.3} m/s (executed at {want})", r.speed))
            }
            Ok(Message::ReportTravelSpeed(r)) => fail(format!(
                "{:.3} m/s, but the list was executed at {want} m/s",
                r.speed
            )),
            Ok(m) => fail(format!("Query Travel Speed answered by {}", m.name())),
            Err(e) => fail(e),
        }
    }

    /// `as4.waypoints.local_waypoint`, while the list runs: the waypoint of the active
    /// element (asked before and after, in case the vehicle moved on between).
    pub(super) fn local_waypoint(&mut self) -> Found {
        let before = self.active().ok();
        let r = match self.j.ask(QueryLocalWaypoint { presence_vector: 0 }.into()) {
            Ok(Message::ReportLocalWaypoint(r)) => r,
            Ok(m) => return fail(format!("Query Local Waypoint answered by {}", m.name())),
            Err(e) => return fail(e),
        };
        let after = self.active().ok();
        let near = |uid: Option<u16>| {
            self.waypoints.iter().find(|w| {
                Some(w.0) == uid
                    && (w.1 - r.x).abs() <= WAYPOINT_TOLERANCE
                    && (w.2 - r.y).abs() <= WAYPOINT_TOLERANCE
            })
        };
        match near(before).or_else(|| near(after)) {
            Some((uid, _, _)) => pass(format!(
                "({:.3}, {:.3}): element {uid}'s waypoint",
                r.x, r.y
            )),
            None => fail(format!(
                "({:.3}, {:.3}), not the waypoint of the active element ({before:?} before, {after:?} after; loaded {:?})",
                r.x,
                r.y,
                self.waypoints
            )),
        }
    }

    /// `as4.waypoints.active_element`: asked every half second until the list is done
    /// (active element 0, or the last element with the vehicle at its waypoint), at
    /// most the mission timeout after `started`; the vehicle is put in Standby when it
    /// runs out.
    fn follow(&mut self, started: Instant) -> Found {
        let uids = self.uids();
        let last = uids.last().copied().unwrap_or(0);
        let (_, lx, ly) = self.waypoints.last().copied().unwrap_or((0, 0.0, 0.0));
        let deadline = started + self.j.opts.mission_timeout;
        let mut seen: Vec<u16> = Vec::new();
        let from = self.position();
        loop {
            let a = match self.active() {
                Ok(a) => a,
                Err(e) => return fail(format!("{e} (seen {seen:?})")),
            };
            if seen.last() != Some(&a) {
                seen.push(a);
            }
            let took = self
                .j
                .now()
                .saturating_duration_since(started)
                .as_secs_f64();
            if a != 0 && !uids.contains(&a) {
                return fail(format!(
                    "active element {a} is not one of {uids:?} (seen {seen:?})"
                ));
            }
            if a == 0 {
                return if seen.len() > 1 {
                    pass(format!("{seen:?}: the list done in {took:.1} s"))
                } else {
                    fail("active element 0 without any element of the list before it")
                };
            }
            if a == last && self.at(lx, ly) {
                return pass(format!(
                    "{seen:?}: the last element's waypoint reached in {took:.1} s"
                ));
            }
            if self.j.now() >= deadline {
                let moved = match (from, self.position()) {
                    (Some((x0, y0)), Some((x1, y1))) => {
                        let to = self.waypoints.iter().find(|w| w.0 == a);
                        format!(
                            "; the vehicle went from ({x0:.2}, {y0:.2}) to ({x1:.2}, {y1:.2}){}",
                            to.map_or(String::new(), |w| format!(
                                ", {:.2} m from element {a}'s waypoint",
                                (w.1 - x1).hypot(w.2 - y1)
                            ))
                        )
                    }
                    _ => String::new(),
                };
                self.j.command(Standby {}.into());
                let state = self
                    .j
                    .status()
                    .map_or_else(|e| e, |s: ComponentState| format!("{s:?}"));
                return fail(format!(
                    "{seen:?}: the list not done after {took:.1} s (--mission-timeout){moved}; Standby sent to stop the vehicle, now {state}"
                ));
            }
            let next = (self.j.now() + POLL).min(deadline);
            self.j.drain_until(next);
        }
    }

    /// The vehicle's local position, when reported.
    fn position(&mut self) -> Option<(f64, f64)> {
        match self.j.ask(
            QueryLocalPose {
                presence_vector: 0x0003,
            }
            .into(),
        ) {
            Ok(Message::ReportLocalPose(r)) => Some((r.x?, r.y?)),
            _ => None,
        }
    }

    /// Whether the vehicle is within the pose tolerance of (x, y).
    fn at(&mut self, x: f64, y: f64) -> bool {
        let tol = self.j.opts.pose_tolerance;
        self.position()
            .is_some_and(|(rx, ry)| (rx - x).abs() <= tol && (ry - y).abs() <= tol)
    }
}
