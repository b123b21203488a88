//! The Local and Global Waypoint List Drivers over RA 3.3 waypoint drivers, and the
//! machinery the Path Segment Drivers share with them ([`super::segments`]).
//!
//! The list lives in the AS-4 component's List Manager ([`crate::core::lists::Lists`]),
//! its elements holding Set Local (or Global) Waypoint messages (or Path Segment ones).
//! Execute List sends the elements from the start UID on to the RA 3.3 driver as
//! numbered waypoints or segments (element 0 starts a new RA 3.3 list; local ones are
//! moved from the AS-4 local frame into the RA 3.3 one), then the travel speed. RA 3.3
//! has no active-element query: the driver counts an element reached when the RA 3.3
//! pose comes within the element's tolerance (default [`DEFAULT_TOLERANCE`]) of its
//! position (a waypoint, a segment's P2) or has passed it along the path to the next
//! element (by [`PAST_MARGIN`]), in order; the list is done (no element active, UID 0)
//! when the RA 3.3 driver reports an empty list (Report Waypoint Count or Report Path
//! Segment Count, polled) after the execution, which it does at the final point, or the
//! last element is within tolerance.

use jaus::messages as ra;
use jaus::{Address, CommandCode, JausMessage};

use super::ServiceIds;
use crate::core::lists::Lists;
use crate::core::machine::Host;
use crate::machined::{Machined, On, OnMachines};
use crate::messages::services::global_path_segment_driver;
use crate::messages::services::transport::event::Receive;
use crate::messages::services::{global_waypoint_list_driver, list_manager};
use crate::messages::services::{local_path_segment_driver, local_waypoint_list_driver};
use crate::messages::{
    ExecuteList, QueryGlobalPathSegment, QueryGlobalWaypoint, QueryLocalPathSegment,
    QueryLocalWaypoint, ReportActiveElement, ReportGlobalWaypoint, ReportLocalWaypoint,
    ReportTravelSpeed, SetGlobalPathSegment, SetGlobalWaypoint, SetLocalPathSegment,
    SetLocalWaypoint,
};
use crate::ra33::Ra33Side;
use crate::service::{Cx, ServiceId};
use crate::Message;

/// How close counts as reached when an element gives no waypoint tolerance, metres.
pub const DEFAULT_TOLERANCE: f64 = 1.0;

/// How far along the leg to the next element the vehicle must be to have passed an
/// element it did not come within tolerance of, metres.
pub const PAST_MARGIN: f64 = 0.25;

/// Where an element takes the vehicle, in the terms of [`Kind::position`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Goal {
    /// The element's position (a waypoint; a path segment's P2).
    pub at: [f64; 2],
    /// The point the path heads for as it leaves the previous element toward this one
    /// (a waypoint itself; a curved segment's P1): "passed" is judged along it.
    pub toward: [f64; 2],
    /// How close counts as reached, metres.
    pub tolerance: f64,
}

impl Goal {
    /// A goal reached at `at` within `tolerance`, the path heading straight to it.
    pub fn point(at: [f64; 2], tolerance: f64) -> Self {
        Self {
            at,
            toward: at,
            tolerance,
        }
    }
}

/// What differs between the list drivers (implemented by [`Local`] and [`Global`]
/// waypoints and by the path segment kinds of [`super::segments`] only).
pub trait Kind: std::fmt::Debug + Send + 'static {
    /// The Set message of one element (a waypoint, a path segment).
    type Element: Clone + std::fmt::Debug + Send + 'static;
    /// The service.
    const ID: ServiceId;
    /// The query of the active element.
    const QUERY: CommandCode;
    /// The RA 3.3 report of how many elements the driver holds.
    const COUNT: CommandCode;
    /// The element a List Manager element's message is, if it is one of this kind.
    fn element(m: &Message) -> Option<Self::Element>;
    /// The RA 3.3 message setting element `number`, and where it takes the vehicle in
    /// the RA 3.3 frame (local x, y; or latitude, longitude); why not, when the element
    /// cannot be moved into RA 3.3 terms yet (Execute List is then refused with it).
    fn to_ra33(
        e: &Self::Element,
        number: u16,
        side: &Ra33Side,
    ) -> Result<(ra::Message, Goal), String>;
    /// The RA 3.3 query of how many elements the driver holds (answered with `COUNT`).
    fn count_query() -> ra::Message;
    /// The count in an RA 3.3 `COUNT` report.
    fn count(report: &ra::Message) -> Option<u16>;
    /// The vehicle's position from the RA 3.3 reports, in the same terms as `to_ra33`.
    fn position(side: &Ra33Side) -> Option<[f64; 2]>;
    /// `b` relative to `a`, metres (east/north or local x/y).
    fn offset(a: [f64; 2], b: [f64; 2]) -> [f64; 2];
    /// The report of the element (masked by the query).
    fn report(e: &Self::Element, query: &Message) -> Message;

    /// The generated machines of the service (one of the list drivers'), and how they run:
    /// `list_machines!` writes these for a module of `crate::messages::services`.
    type Machines: std::fmt::Debug + Send + Default + 'static;
    /// The messages the machines take (the generated `RECEIVES`).
    const RECEIVES: &'static [CommandCode];
    /// The engine's machines inside [`Self::Machines`].
    fn hsm(m: &mut Self::Machines) -> &mut jaus::hsm::Machines;
    /// Offers `message` to the machines (the generated `Machines::receive`).
    fn run(
        m: &mut Self::Machines,
        on: &mut On<'_, ListDriver<Self>>,
        core: &mut Host<'_>,
        message: &Message,
        transport: &Receive,
    ) -> Option<bool>
    where
        Self: Sized;
    /// Follows the Core's state (the generated `Machines::follow`).
    fn follow(m: &mut Self::Machines, on: &mut On<'_, ListDriver<Self>>, path: &str) -> bool
    where
        Self: Sized;
}

/// The [`Kind`] items that tie a kind to the generated list driver service `$module`.
macro_rules! list_machines {
    ($module:ident) => {
        type Machines = $crate::messages::services::$module::Machines;
        const RECEIVES: &'static [::jaus::CommandCode] =
            $crate::messages::services::$module::RECEIVES;

        fn hsm(m: &mut Self::Machines) -> &mut ::jaus::hsm::Machines {
            &mut m.0
        }

        fn run(
            m: &mut Self::Machines,
            on: &mut $crate::machined::On<'_, $crate::mobility::lists::ListDriver<Self>>,
            core: &mut $crate::core::machine::Host<'_>,
            message: &$crate::Message,
            transport: &$crate::messages::services::transport::event::Receive,
        ) -> Option<bool> {
            m.receive(on, core, message, transport)
        }

        fn follow(
            m: &mut Self::Machines,
            on: &mut $crate::machined::On<'_, $crate::mobility::lists::ListDriver<Self>>,
            path: &str,
        ) -> bool {
            m.follow(on, path)
        }
    };
}
pub(crate) use list_machines;

/// The generated trait of list driver service `$module` for every kind whose elements
/// are `$element`: the active element's query `$query` (guard `$exists`, report
/// `$report`), Execute List, the travel speed and the active element.
macro_rules! list_driver_trait {
    ($module:ident :: $trait:ident, $element:ty, $query:ty, $exists:ident, $report:ident) => {
        impl<K: Kind<Element = $element>> $module::$trait for On<'_, ListDriver<K>> {
            fn $exists(&self, _msg: &$query) -> bool {
                self.svc.active().is_some()
            }

            fn start_element_exists(&self, msg: &ExecuteList) -> bool {
                start_of(self.lists, msg).is_some()
            }

            fn execute_list(&mut self, msg: &ExecuteList) {
                if let Err(why) = execute(self, msg) {
                    self.refuse(why);
                }
            }

            fn refuse_execute_list(&mut self, msg: &ExecuteList) {
                self.refuse(match msg.element_uid {
                    Some(uid) => format!("Execute List: no element with UID {uid}"),
                    None => "Execute List with an empty list".to_string(),
                });
            }

            fn send_report_active_element(&mut self, transport: &Receive) {
                let element_uid = self.svc.active_uid();
                self.reply(transport, ReportActiveElement { element_uid });
            }

            fn reset_travel_speed(&mut self) {
                // The RA 3.3 driver stops on standby and forgets its path: so does the
                // run.
                if let Some(r) = self.svc.run.as_mut() {
                    r.active = r.elements.len();
                    r.speed = 0.0;
                }
            }

            fn send_report_travel_speed(&mut self, transport: &Receive) {
                let speed = self.svc.run.as_ref().map_or(0.0, |r| r.speed);
                self.reply(transport, ReportTravelSpeed { speed });
            }

            fn $report(&mut self, msg: &$query, transport: &Receive) {
                if let Some(e) = self.svc.active().cloned() {
                    let report = K::report(&e, &Message::from(msg.clone()));
                    self.reply(transport, report);
                }
            }
        }
    };
}

list_driver_trait!(
    local_waypoint_list_driver::LocalWaypointListDriver,
    SetLocalWaypoint,
    QueryLocalWaypoint,
    waypoint_exists,
    send_report_local_waypoint
);
list_driver_trait!(
    global_waypoint_list_driver::GlobalWaypointListDriver,
    SetGlobalWaypoint,
    QueryGlobalWaypoint,
    waypoint_exists,
    send_report_global_waypoint
);
list_driver_trait!(
    local_path_segment_driver::LocalPathSegmentDriver,
    SetLocalPathSegment,
    QueryLocalPathSegment,
    segment_exists,
    send_report_local_path_segment
);
list_driver_trait!(
    global_path_segment_driver::GlobalPathSegmentDriver,
    SetGlobalPathSegment,
    QueryGlobalPathSegment,
    segment_exists,
    send_report_global_path_segment
);

/// Waypoints in the local frame.
#[derive(Debug)]
pub struct Local;

/// Waypoints as latitude and longitude.
#[derive(Debug)]
pub struct Global;

impl Kind for Local {
    type Element = SetLocalWaypoint;
    const ID: ServiceId = ServiceIds::LOCAL_WAYPOINT_LIST_DRIVER;
    const QUERY: CommandCode = QueryLocalWaypoint::CODE;
    const COUNT: CommandCode = ra::ReportWaypointCount::CODE;
    list_machines!(local_waypoint_list_driver);

    fn element(m: &Message) -> Option<SetLocalWaypoint> {
        match m {
            Message::SetLocalWaypoint(w) => Some(w.clone()),
            _ => None,
        }
    }

    fn to_ra33(
        w: &SetLocalWaypoint,
        number: u16,
        side: &Ra33Side,
    ) -> Result<(ra::Message, Goal), String> {
        let (x, y) = side.frame.to_ra33(w.x, w.y);
        let m = ra::SetLocalWaypoint {
            waypoint_number: number,
            x,
            y,
            z: w.z,
            roll: w.roll,
            pitch: w.pitch,
            yaw: w.yaw.map(|a| side.frame.yaw_to_ra33(a)),
        };
        Ok((
            m.into(),
            Goal::point([x, y], w.waypoint_tolerance.unwrap_or(DEFAULT_TOLERANCE)),
        ))
    }

    fn count_query() -> ra::Message {
        ra::QueryWaypointCount {}.into()
    }

    fn count(report: &ra::Message) -> Option<u16> {
        waypoint_count(report)
    }

    fn position(side: &Ra33Side) -> Option<[f64; 2]> {
        let lps = side.targets().local_pose_sensor?;
        match side.latest(lps, ra::ReportLocalPose::CODE) {
            Some((_, ra::Message::ReportLocalPose(p))) => Some([p.x?, p.y?]),
            _ => None,
        }
    }

    fn offset(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
        [b[0] - a[0], b[1] - a[1]]
    }

    fn report(w: &SetLocalWaypoint, query: &Message) -> Message {
        let mut r = ReportLocalWaypoint {
            x: w.x,
            y: w.y,
            z: w.z,
            roll: w.roll,
            pitch: w.pitch,
            yaw: w.yaw,
            waypoint_tolerance: w.waypoint_tolerance,
            path_tolerance: w.path_tolerance,
        };
        if let Message::QueryLocalWaypoint(q) = query {
            jaus::codec::Encode::keep_present(&mut r, u64::from(q.presence_vector));
        }
        r.into()
    }
}

impl Kind for Global {
    type Element = SetGlobalWaypoint;
    const ID: ServiceId = ServiceIds::GLOBAL_WAYPOINT_LIST_DRIVER;
    const QUERY: CommandCode = QueryGlobalWaypoint::CODE;
    const COUNT: CommandCode = ra::ReportWaypointCount::CODE;
    list_machines!(global_waypoint_list_driver);

    fn element(m: &Message) -> Option<SetGlobalWaypoint> {
        match m {
            Message::SetGlobalWaypoint(w) => Some(w.clone()),
            _ => None,
        }
    }

    fn to_ra33(
        w: &SetGlobalWaypoint,
        number: u16,
        _side: &Ra33Side,
    ) -> Result<(ra::Message, Goal), String> {
        let m = ra::SetGlobalWaypoint {
            waypoint_number: number,
            latitude: w.latitude,
            longitude: w.longitude,
            elevation: w.altitude,
            roll: w.roll,
            pitch: w.pitch,
            yaw: w.yaw,
        };
        Ok((
            m.into(),
            Goal::point(
                [w.latitude, w.longitude],
                w.waypoint_tolerance.unwrap_or(DEFAULT_TOLERANCE),
            ),
        ))
    }

    fn count_query() -> ra::Message {
        ra::QueryWaypointCount {}.into()
    }

    fn count(report: &ra::Message) -> Option<u16> {
        waypoint_count(report)
    }

    fn position(side: &Ra33Side) -> Option<[f64; 2]> {
        let gps = side.targets().global_pose_sensor?;
        match side.latest(gps, ra::ReportGlobalPose::CODE) {
            Some((_, ra::Message::ReportGlobalPose(p))) => Some([p.latitude?, p.longitude?]),
            _ => None,
        }
    }

    fn offset(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
        // An equirectangular approximation: exact enough between waypoints.
        const R: f64 = 6_371_000.0;
        let lat = (a[0] + b[0]).to_radians() / 2.0;
        let north = (b[0] - a[0]).to_radians() * R;
        let east = (b[1] - a[1]).to_radians() * R * lat.cos();
        [east, north]
    }

    fn report(w: &SetGlobalWaypoint, query: &Message) -> Message {
        let mut r = ReportGlobalWaypoint {
            latitude: w.latitude,
            longitude: w.longitude,
            altitude: w.altitude,
            roll: w.roll,
            pitch: w.pitch,
            yaw: w.yaw,
            waypoint_tolerance: w.waypoint_tolerance,
            path_tolerance: w.path_tolerance,
        };
        if let Message::QueryGlobalWaypoint(q) = query {
            jaus::codec::Encode::keep_present(&mut r, u64::from(q.presence_vector));
        }
        r.into()
    }
}

/// The count of an RA 3.3 Report Waypoint Count.
fn waypoint_count(report: &ra::Message) -> Option<u16> {
    match report {
        ra::Message::ReportWaypointCount(c) => Some(c.waypoint_count),
        _ => None,
    }
}

/// The list being executed.
#[derive(Debug, Clone)]
struct Run<W> {
    /// UIDs and elements, in list order from the start element.
    elements: Vec<(u16, W)>,
    /// Where each takes the vehicle (RA 3.3 terms), as `elements`.
    targets: Vec<Goal>,
    /// Index of the element being driven to (`elements.len()` when done).
    active: usize,
    speed: f64,
    /// When it was executed (a count of 0 reported after it: the driver finished the
    /// list).
    started: std::time::Instant,
}

/// The data of a list driver of kind `K` over the RA 3.3 waypoint or path segment
/// driver at an address; the service is an [`OnMachines`] of it.
#[derive(Debug)]
pub struct ListDriver<K: Kind> {
    driver: Address,
    run: Option<Run<K::Element>>,
}

/// The Local Waypoint List Driver.
pub type LocalWaypointListDriver = OnMachines<ListDriver<Local>>;
/// The Global Waypoint List Driver.
pub type GlobalWaypointListDriver = OnMachines<ListDriver<Global>>;

impl<K: Kind> OnMachines<ListDriver<K>> {
    /// The service over the RA 3.3 driver at `driver`.
    pub fn new(driver: Address) -> Self {
        OnMachines::from_impl(ListDriver { driver, run: None })
    }

    /// The UID of the element being driven to (0 when none).
    pub fn active_uid(&self) -> u16 {
        self.inner().active_uid()
    }
}

impl<K: Kind> ListDriver<K> {
    /// The element being driven to.
    fn active(&self) -> Option<&K::Element> {
        self.run
            .as_ref()
            .and_then(|r| r.elements.get(r.active).map(|e| &e.1))
    }

    /// The UID of the element being driven to (0 when none).
    pub fn active_uid(&self) -> u16 {
        self.run
            .as_ref()
            .and_then(|r| r.elements.get(r.active).map(|e| e.0))
            .unwrap_or(0)
    }
}

/// The UID Execute List starts from: the one it names, else the list's head; `None` when
/// the list holds no such element.
fn start_of(lists: &Lists, e: &ExecuteList) -> Option<u16> {
    match e.element_uid {
        Some(uid) => lists.get(uid).map(|_| uid),
        None => lists.head(),
    }
}

/// Execute List: sends the elements from the start on to the RA 3.3 driver, then the
/// speed; why not, when an element cannot be moved into RA 3.3 terms.
fn execute<K: Kind>(on: &mut On<'_, ListDriver<K>>, e: &ExecuteList) -> Result<(), String> {
    let start = start_of(on.lists, e).ok_or("Execute List: no such element")?;
    let mut elements = Vec::new();
    for el in on.lists.iter_from(start) {
        match el
            .message()
            .and_then(Result::ok)
            .as_ref()
            .and_then(K::element)
        {
            Some(w) => elements.push((el.uid, w)),
            None => {
                return Err(format!(
                    "Execute List: element {} is not a {}",
                    el.uid,
                    K::ID
                ))
            }
        }
    }
    if elements.len() > usize::from(u16::MAX) {
        return Err("Execute List: too many elements".into());
    }
    let mut messages = Vec::with_capacity(elements.len());
    let mut targets = Vec::with_capacity(elements.len());
    for (n, (uid, w)) in elements.iter().enumerate() {
        let (m, goal) = K::to_ra33(w, n as u16, on.env)
            .map_err(|why| format!("Execute List: element {uid}: {why}"))?;
        messages.push(m);
        targets.push(goal);
    }
    // This driver moves the vehicle now; the others (the other list drivers, the
    // Primitive Driver efforts the AS-4 client commanded) give way. The RA 3.3 driver
    // reaches the Primitive Driver through the Reflexive Driver.
    let driver = on.svc.driver;
    if let Some(pd) = on.env.targets().primitive_driver {
        on.env.release(pd);
    }
    on.env.activate(driver);
    for m in messages {
        on.env.send(driver, m);
    }
    on.env.send(driver, ra::SetTravelSpeed { speed: e.speed });
    tracing::info!(
        service = %K::ID, elements = elements.len(), speed = e.speed, "list executed"
    );
    on.env.keep_polling(on.now, driver, K::count_query());
    on.svc.run = Some(Run {
        elements,
        targets,
        active: 0,
        speed: e.speed,
        started: on.now,
    });
    Ok(())
}

/// Whether the component's list starts with an element that is not a waypoint of kind
/// `K` (the other list driver's list).
fn holds_other_kind<K: Kind>(lists: &Lists) -> bool {
    lists
        .head()
        .and_then(|h| lists.get(h))
        .and_then(|e| e.message())
        .and_then(Result::ok)
        .is_some_and(|m| K::element(&m).is_none())
}

impl<K: Kind> Machined for ListDriver<K> {
    type Machines = K::Machines;
    const ID: ServiceId = K::ID;
    const RECEIVES: &'static [CommandCode] = K::RECEIVES;
    const INHERITED: &'static [CommandCode] = list_manager::RECEIVES;

    fn hsm(m: &mut Self::Machines) -> &mut jaus::hsm::Machines {
        K::hsm(m)
    }

    fn run(
        m: &mut Self::Machines,
        on: &mut On<'_, Self>,
        core: &mut Host<'_>,
        message: &Message,
        transport: &Receive,
    ) -> Option<bool> {
        K::run(m, on, core, message, transport)
    }

    fn follow(m: &mut Self::Machines, on: &mut On<'_, Self>, path: &str) -> bool {
        K::follow(m, on, path)
    }

    fn claims(&self, lists: &Lists, message: &Message) -> bool {
        // One component, one list: while it holds another kind's elements, that other
        // list driver answers for it and executes it.
        match message {
            Message::ExecuteList(e) => start_of(lists, e).is_none_or(|start| {
                lists.iter_from(start).all(|el| {
                    el.message()
                        .and_then(Result::ok)
                        .as_ref()
                        .and_then(K::element)
                        .is_some()
                })
            }),
            Message::QueryActiveElement(_) | Message::QueryTravelSpeed(_) => {
                !holds_other_kind::<K>(lists)
            }
            _ => true,
        }
    }

    fn in_progress(&self, code: CommandCode) -> bool {
        // Execute List is carried out until the list is done (no element active).
        code == <ExecuteList as jaus::JausMessage>::CODE && self.active().is_some()
    }

    fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
        let Some(run) = self.run.as_mut() else { return };
        let n = run.elements.len();
        // The RA 3.3 driver empties its list at the final point.
        if let Some((at, count)) = cx.env.latest(self.driver, K::COUNT) {
            if at > run.started && K::count(count) == Some(0) && run.active < n {
                tracing::info!(service = %K::ID, "list finished");
                run.active = n;
            }
        }
        let Some(here) = K::position(cx.env) else {
            return;
        };
        while let Some(goal) = run.targets.get(run.active) {
            let d = K::offset(goal.at, here);
            let reached = d[0].hypot(d[1]) <= goal.tolerance
                || run.targets.get(run.active + 1).is_some_and(|next| {
                    // Past the element along the way to the next one (by PAST_MARGIN):
                    // a pursuit controller turns before it reaches a waypoint.
                    let leg = K::offset(goal.at, next.toward);
                    let len = leg[0].hypot(leg[1]);
                    len > 0.0 && (leg[0] * d[0] + leg[1] * d[1]) / len > PAST_MARGIN
                });
            if !reached {
                break;
            }
            tracing::info!(
                service = %K::ID,
                uid = run.elements[run.active].0,
                distance = d[0].hypot(d[1]),
                "element reached"
            );
            run.active += 1;
        }
    }
}
