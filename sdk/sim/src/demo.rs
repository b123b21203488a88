//! The `jaus demo` main job: a complete simulated subsystem on the in-process bus.
//!
//! Node 1 of subsystem 1 hosts the Primitive Driver, the Reflexive Driver, the Global
//! and Local Pose Sensors, the Velocity State Sensor, the Global Waypoint Driver, the
//! Local and Global Path Segment Drivers, the Range and Visual Sensors, the World Model
//! Vector Knowledge Store, the Mission Spooler and the Subsystem Commander, all over one
//! simulated skid-steer vehicle; the drivers
//! drive through the Reflexive Driver (Part 1 Figures 5-9 and 5-16). An operator (a System
//! Commander on node 2, taking and keeping control through `jaus::stock::commander`)
//! takes control of both drivers, sends a waypoint mission in
//! WGS 84, then the two path segments of Part 1 Figures 5-12 and 5-14, waiting each time
//! for the driver to report Standby (Part 1: back to Standby at the final point). The
//! run reports arrival times and the cross-track error of every leg, measured on the
//! vehicle's true trajectory against the commanded path, and draws both in an SVG.
//!
//! Third phase: the operator stores an obstacle in the World Model Vector Knowledge
//! Store, queries it for objects along its mission (a line region with a clearance
//! buffer), plans a detour waypoint round each object it finds, and hands the mission —
//! blocking moves, a payload action (the horn), a blocking move home — to the
//! subsystem's Subsystem Commander (1.1.32.1, `jaus::stock::commander::subsystem`). The
//! Subsystem Commander takes control of the Mission Spooler, spools the mission to it,
//! runs it, watches it and reports its status back to the operator; the spooler drives
//! the waypoint driver. The world also holds an obstacle nobody
//! stored ([`UNKNOWN_OBSTACLE`], on the way home): the vehicle's Range Sensor detects
//! it and keeps it in the world model (`jaus::stock::environment::map_feed`), so the
//! same query finds it and the vehicle goes round it too. At the start the operator asks
//! the Visual Sensor for an image (the simulated camera's view ahead, both obstacles in
//! it).

use std::time::{Duration, Instant};

use nalgebra::{Vector2, Vector3};

use crate::camera::SimCamera;
use crate::host::HostConfig;
use crate::scanner::{ScannerParams, Scene, SimScanner};
use crate::vehicle::{SimVehicle, VehicleParams};
use jaus::component::local::{Endpoint, LocalBus};
use jaus::component::{Config, CoreState, Refused};
use jaus::components::system_commander::{self, Ctx, SystemCommander};
use jaus::components::{
    global_path_segment_driver, global_pose_sensor, global_waypoint_driver,
    local_path_segment_driver, local_pose_sensor, mission_spooler, primitive_driver, range_sensor,
    reflexive_driver, subsystem_commander, velocity_state_sensor, visual_sensor,
    world_model_vector_knowledge_store,
};
use jaus::messages::*;
use jaus::stock::commander::{
    ControlEvent, ControlKeeper, KeeperConfig, StockSubsystemCommander, SubsystemConfig,
};
use jaus::stock::drivers::{
    PrimitiveConfig, ReflexiveConfig, StockGlobalPathSegmentDriver, StockGlobalWaypointDriver,
    StockLocalPathSegmentDriver, StockPrimitiveDriver, StockReflexiveDriver,
};
use jaus::stock::environment::camera::{StockVisualSensor, VisualConfig};
use jaus::stock::environment::map_feed::MapFeedConfig;
use jaus::stock::environment::range::{RangeConfig, StockRangeSensor};
use jaus::stock::geo::LocalFrame;
use jaus::stock::motion::DriverConfig;
use jaus::stock::path::{Path, PathSegment};
use jaus::stock::sensors::{StockGlobalPoseSensor, StockLocalPoseSensor, StockVelocityStateSensor};
use jaus::stock::spooler::{command, leaf_task, mission_of, SpoolerConfig, StockMissionSpooler};
use jaus::stock::world_model::{StockWorldModel, WorldModelConfig};
use jaus::Address;

/// Addresses of the demo subsystem.
pub mod addr {
    use jaus::components as c;
    use jaus::Address;
    /// Primitive Driver.
    pub const PD: Address = Address::new(1, 1, c::primitive_driver::ID, 1);
    /// Reflexive Driver.
    pub const RD: Address = Address::new(1, 1, c::reflexive_driver::ID, 1);
    /// Global Pose Sensor.
    pub const GPS: Address = Address::new(1, 1, c::global_pose_sensor::ID, 1);
    /// Local Pose Sensor.
    pub const LPS: Address = Address::new(1, 1, c::local_pose_sensor::ID, 1);
    /// Velocity State Sensor.
    pub const VSS: Address = Address::new(1, 1, c::velocity_state_sensor::ID, 1);
    /// Global Waypoint Driver.
    pub const GWD: Address = Address::new(1, 1, c::global_waypoint_driver::ID, 1);
    /// Local Path Segment Driver.
    pub const LPSD: Address = Address::new(1, 1, c::local_path_segment_driver::ID, 1);
    /// Global Path Segment Driver (not used by the scripted run; operator stations
    /// such as `jaus ocu` drive path segments in WGS 84 with it).
    pub const GPSD: Address = Address::new(1, 1, c::global_path_segment_driver::ID, 1);
    /// Mission Spooler.
    pub const MS: Address = Address::new(1, 1, c::mission_spooler::ID, 1);
    /// World Model Vector Knowledge Store.
    pub const WM: Address = Address::new(1, 1, c::world_model_vector_knowledge_store::ID, 1);
    /// Range Sensor.
    pub const RS: Address = Address::new(1, 1, c::range_sensor::ID, 1);
    /// Visual Sensor.
    pub const VS: Address = Address::new(1, 1, c::visual_sensor::ID, 1);
    /// Subsystem Commander (it hands the operator's missions to the spooler).
    pub const SC: Address = Address::new(1, 1, c::subsystem_commander::ID, 1);
    /// The operator (System Commander).
    pub const OCU: Address = Address::new(1, 2, c::system_commander::ID, 1);

    /// `a` moved to node `node` of subsystem `ss`.
    pub const fn on(a: Address, ss: u8, node: u8) -> Address {
        Address::new(ss, node, a.component, a.instance)
    }
}

/// Options of a demo run.
#[derive(Debug, Clone)]
pub struct Options {
    /// Seed of the sensor noise.
    pub seed: u64,
    /// Standard deviation of the position noise of the pose sensors, m.
    pub position_noise: f64,
    /// Waypoint travel speed, m/s.
    pub waypoint_speed: f64,
    /// Path-segment travel speed, m/s.
    pub path_speed: f64,
    /// Run at wall-clock speed instead of as fast as possible.
    pub realtime: bool,
    /// Print progress every this much simulated time (`None`: quiet).
    pub progress: Option<Duration>,
    /// Give up after this much simulated time.
    pub timeout: Duration,
}

impl Default for Options {
    fn default() -> Self {
        Self {
            seed: 7,
            position_noise: 0.02,
            waypoint_speed: 1.0,
            path_speed: 1.0,
            realtime: false,
            progress: None,
            timeout: Duration::from_secs(300),
        }
    }
}

/// The WGS 84 origin of the demo's local frame (x north, y east).
pub const ORIGIN: (f64, f64, f64) = (29.6436, -82.3549, 40.0);

/// The waypoint mission, local metres (sent as WGS 84); it ends at P0 of Figure 5-12,
/// arriving along the direction of P0→P1.
pub const WAYPOINTS: [(f64, f64); 5] = [
    (10.0, 0.0),
    (10.0, -6.0),
    (-3.0, -6.0),
    (-1.0, -1.0),
    (1.0, 2.0),
];

/// The path segments of Part 1 Figures 5-12 and 5-14: (P1, P2, w1); P0 of the first is
/// the vehicle's position, [1, 2, 0].
pub const SEGMENTS: [SegmentDef; 2] = [
    ((3.0, 5.0), (5.0, 1.0), 1.5),
    ((6.0, -1.0), (8.0, -1.0), 2.0),
];

/// A path segment as sent: P1 (x, y), P2 (x, y), w1.
pub type SegmentDef = ((f64, f64), (f64, f64), f64);

/// Named commanded legs.
type Legs = Vec<(String, Path)>;

/// The spooled mission (local metres, sent as WGS 84): a blocking move, a payload action
/// (the horn of the primitive driver's discrete devices), a blocking move home.
pub const MISSION: [(f64, f64); 2] = [(3.0, -4.0), (0.0, 0.0)];

/// An obstacle the operator stores in the world model before the mission: centre
/// (local metres) and radius (the object's region buffer), on the straight line from P4
/// to the first mission point, so the operator's planner must go round it.
pub const OBSTACLE: ((f64, f64), f64) = ((5.5, -2.5), 0.6);

/// An obstacle on the way home that nobody stores: only the Range Sensor's detections
/// put it in the world model. Centre (local metres) and radius.
pub const UNKNOWN_OBSTACLE: ((f64, f64), f64) = ((1.5, -2.0), 0.4);

/// The demo's world as it is: the obstacle the operator stores ([`OBSTACLE`]) and one
/// nobody stores ([`UNKNOWN_OBSTACLE`]).
pub fn scene() -> Scene {
    let circle = |((x, y), r): ((f64, f64), f64)| (Vector2::new(x, y), r);
    Scene {
        circles: vec![circle(OBSTACLE), circle(UNKNOWN_OBSTACLE)],
    }
}

/// The demo's world for a [`Host`](crate::host::Host) (`Host::with_config`): its
/// frame's origin ([`ORIGIN`]), its [`scene`] and the arm demo's control period.
pub fn host_config() -> HostConfig {
    HostConfig {
        origin: LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2),
        scene: scene(),
        arm_control_period: crate::arm_demo::CONTROL_PERIOD,
    }
}

/// Feature class of the objects the operator stores (the Range Sensor's are class 2).
pub const OPERATOR_CLASS: u16 = 1;

/// Clearance the operator's planner keeps from a stored obstacle's buffer, m.
pub const CLEARANCE: f64 = 0.6;

/// One leg of the run.
#[derive(Debug, Clone, PartialEq)]
pub struct Leg {
    /// "waypoint 2", "path segment 0".
    pub name: String,
    /// Simulated time the leg's end was reached, s (`None`: never).
    pub arrival: Option<f64>,
    /// Cross-track error RMS, m.
    pub xte_rms: f64,
    /// Cross-track error maximum, m.
    pub xte_max: f64,
}

/// What a run measured.
#[derive(Debug, Clone)]
pub struct Report {
    /// Every leg, in order.
    pub legs: Vec<Leg>,
    /// When the waypoint driver returned to Standby, s.
    pub waypoints_done: Option<f64>,
    /// When the path-segment driver returned to Standby, s.
    pub path_done: Option<f64>,
    /// When the spooler reported the mission finished, s.
    pub mission_done: Option<f64>,
    /// When the operator saw the mission's payload action (the horn), s.
    pub horn_at: Option<f64>,
    /// Closest approach of the vehicle to the obstacle's centre during the mission, m
    /// (the obstacle's radius is `OBSTACLE.1`).
    pub obstacle_clearance: f64,
    /// Closest approach to [`UNKNOWN_OBSTACLE`]'s centre during the mission, m.
    pub unknown_clearance: f64,
    /// Objects along the mission the world model returned: (stored by the operator,
    /// detected by the Range Sensor), after merging those that overlap.
    pub objects_found: (usize, usize),
    /// The mission's moves as the operator planned them from the world model.
    pub planned: Vec<(f64, f64)>,
    /// The image the operator received from the Visual Sensor at the start.
    pub image: Option<ReportImage>,
    /// Distance from the final point of each phase when it ended, m.
    pub final_errors: Vec<f64>,
    /// Simulated duration, s.
    pub duration: f64,
    /// Messages delivered on the bus.
    pub messages: u64,
    /// The commanded paths and the driven trajectory (local metres).
    pub commanded: Vec<Vec<Vector2<f64>>>,
    /// The driven trajectory.
    pub trail: Vec<Vector2<f64>>,
}

/// The scripted operator.
#[derive(Debug, Default)]
pub struct Operator {
    step: Step,
    waypoint_speed: f64,
    path_speed: f64,
    seen_ready: bool,
    started: Option<Instant>,
    waypoints_done: Option<Instant>,
    path_done: Option<Instant>,
    mission_done: Option<Instant>,
    horn_at: Option<Instant>,
    /// The mission's move targets as planned (a detour first if an obstacle is in the way).
    planned: Vec<(f64, f64)>,
    /// Positions received from the Local Pose Sensor (at most `TRAIL_MAX`).
    trail: Vec<(Instant, Vector2<f64>)>,
    /// Objects along the mission the world model returned: (stored by the operator,
    /// detected by the range sensor).
    objects_found: (usize, usize),
    path_started: Option<Instant>,
    next_query: Option<Instant>,
    /// The Visual Sensor's image, and how often it was asked for.
    image: Option<ReportImage>,
    image_queries: u32,
    next_image: Option<Instant>,
    /// Control of the drivers, then of the spooler (`jaus::stock::commander`).
    keeper: ControlKeeper,
}

#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
enum Step {
    #[default]
    TakeControl,
    StartWaypoints,
    Waypoints,
    StartPath,
    Path,
    StartMission,
    StoreObstacle,
    PlanMission,
    Mission,
    Done,
}

impl Operator {
    fn watch(&mut self, ctx: &mut Ctx<'_>, driver: Address) {
        let now = ctx.now();
        if self.next_query.is_none_or(|t| now >= t) {
            self.next_query = Some(now + Duration::from_millis(100));
            ctx.send(driver, QueryComponentStatus {});
        }
    }
}

/// Most positions the operator keeps (an hour at 10 Hz).
const TRAIL_MAX: usize = 36_000;

impl SystemCommander for Operator {
    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        let now = ctx.now();
        if self.started.is_none() {
            // The vehicle's position as the operator sees it (x, y).
            if let Err(e) = ctx.create_service_connection(
                addr::LPS,
                <ReportLocalPose as jaus::JausMessage>::CODE,
                10.0,
                0x03,
            ) {
                tracing::warn!("no position feedback: {e}");
            }
        }
        self.started.get_or_insert(now);
        // Control of what the operator commands, taken and kept by the commander logic.
        for e in self.keeper.tick(ctx) {
            if let ControlEvent::Lost(a) = e {
                tracing::warn!(component = %a, "control lost; asking again");
            }
        }
        // A picture of the scene before the run (a query a second, five at most: a
        // lost image does not hold anything up).
        if self.image.is_none()
            && self.image_queries < 5
            && self.next_image.is_none_or(|t| now >= t)
        {
            self.image_queries += 1;
            self.next_image = Some(now + Duration::from_secs(1));
            ctx.send(addr::VS, QueryImage {});
        }
        let frame = LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2);
        match self.step {
            Step::TakeControl => {
                if self.keeper.holds(addr::GWD) && self.keeper.holds(addr::LPSD) {
                    self.step = Step::StartWaypoints;
                }
            }
            Step::StartWaypoints => {
                ctx.send_core(addr::GWD, Resume {});
                for (i, (x, y)) in WAYPOINTS.iter().enumerate() {
                    let (latitude, longitude) = frame.to_global(Vector2::new(*x, *y));
                    ctx.send(
                        addr::GWD,
                        SetGlobalWaypoint {
                            waypoint_number: i as u16,
                            latitude,
                            longitude,
                            ..Default::default()
                        },
                    );
                }
                // After Resume: Part 1 resets the travel speed on Standby -> Ready.
                ctx.send(
                    addr::GWD,
                    SetTravelSpeed {
                        speed: self.waypoint_speed,
                    },
                );
                self.seen_ready = false;
                self.step = Step::Waypoints;
            }
            Step::Waypoints => self.watch(ctx, addr::GWD),
            Step::StartPath => {
                ctx.send_core(addr::LPSD, Resume {});
                for (i, (p1, p2, w1)) in SEGMENTS.iter().enumerate() {
                    ctx.send(
                        addr::LPSD,
                        SetLocalPathSegment {
                            path_segment_number: i as u16,
                            p1_x: p1.0,
                            p1_y: p1.1,
                            p1_z: None,
                            p2_x: p2.0,
                            p2_y: p2.1,
                            p2_z: None,
                            weighting_factor: *w1,
                        },
                    );
                }
                ctx.send(
                    addr::LPSD,
                    SetTravelSpeed {
                        speed: self.path_speed,
                    },
                );
                self.path_started = Some(now);
                self.seen_ready = false;
                self.step = Step::Path;
            }
            Step::Path => self.watch(ctx, addr::LPSD),
            Step::StartMission => {
                // Let go of the drivers: the spooler drives them in the mission, handed
                // to it by the Subsystem Commander.
                for d in [addr::GWD, addr::LPSD] {
                    self.keeper.release(ctx, d);
                }
                self.step = Step::StoreObstacle;
            }
            Step::StoreObstacle => {
                // Store the obstacle in the world model, then ask it what lies along the
                // first leg of the mission.
                let ((x, y), r) = OBSTACLE;
                let (latitude, longitude) = frame.to_global(Vector2::new(x, y));
                ctx.send(
                    addr::WM,
                    CreateVksObjects {
                        buffered: true,
                        message_properties: 0,
                        request_id: 1,
                        objects: vec![VksObject {
                            object_type: VksObjectType::Point,
                            buffer: Some(r as f32),
                            feature_classes: vec![VksFeatureClass {
                                id: OPERATOR_CLASS,
                                attribute: VksAttribute::Default,
                            }],
                            points: vec![VksPoint {
                                latitude,
                                longitude,
                            }],
                        }],
                    },
                );
                let region_points = mission_route()
                    .iter()
                    .map(|p| {
                        let (latitude, longitude) = frame.to_global(*p);
                        VksPoint {
                            latitude,
                            longitude,
                        }
                    })
                    .collect();
                ctx.send(
                    addr::WM,
                    QueryVksObjects {
                        filter_by_class_ids: false,
                        filter_by_attributes: false,
                        response_presence_vector: 1,
                        request_id: 2,
                        object_ids: None,
                        region_type: Some(VksObjectType::Line),
                        region_buffer: Some(CLEARANCE as f32),
                        feature_classes: None,
                        region_points: Some(region_points),
                    },
                );
                self.step = Step::PlanMission;
            }
            Step::PlanMission => {}
            Step::Mission => {
                let now = ctx.now();
                if self.horn_at.is_none() && self.next_query.is_none_or(|t| now >= t) {
                    self.next_query = Some(now + Duration::from_millis(100));
                    ctx.send(addr::PD, QueryDiscreteDevices { presence_vector: 2 });
                }
            }
            Step::Done => {}
        }
    }

    fn on_other_message(
        &mut self,
        ctx: &mut Ctx<'_>,
        msg: &Message,
    ) -> Result<Option<Message>, Refused> {
        match msg {
            Message::ReportLocalPose(p) => {
                if let (Some(x), Some(y)) = (p.x, p.y) {
                    if self.trail.len() < TRAIL_MAX {
                        self.trail.push((ctx.now(), Vector2::new(x, y)));
                    }
                }
            }
            Message::ReportVksObjects(r) if self.step == Step::PlanMission && r.request_id == 2 => {
                let frame = LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2);
                let objects: Vec<Found> = r
                    .objects
                    .iter()
                    .flatten()
                    .filter_map(|o| {
                        let p = o.points.first()?;
                        Some(Found {
                            centre: frame.to_local(p.latitude, p.longitude),
                            buffer: f64::from(o.buffer),
                            operator: o.feature_classes.iter().any(|c| c.id == OPERATOR_CLASS),
                        })
                    })
                    .collect();
                let objects = merge_overlapping(objects);
                self.objects_found = (
                    objects.iter().filter(|o| o.operator).count(),
                    objects.iter().filter(|o| !o.operator).count(),
                );
                let plan = plan_round(&mission_route(), &objects);
                self.planned = plan.clone();
                // The subsystem's missions go through its Subsystem Commander, which
                // holds the spooler, hands the mission over and reports back.
                ctx.send(
                    addr::SC,
                    mission_message(&frame, self.waypoint_speed, &plan),
                );
                ctx.send(addr::SC, RunMission { mission_id: 1 });
                self.step = Step::Mission;
            }
            Message::ReportMissionStatus(r)
                if self.step == Step::Mission
                    && r.status_type == MissionStatusType::Mission
                    && r.status == MissionStatus::Finished =>
            {
                self.mission_done = Some(ctx.now());
                self.step = Step::Done;
            }
            Message::ReportImage(r) if self.image.is_none() => {
                self.image = Some(r.clone());
            }
            Message::ReportDiscreteDevices(d)
                if self.horn_at.is_none() && d.parking_brake_and_horn.is_some_and(|p| p.horn) =>
            {
                self.horn_at = Some(ctx.now());
            }
            _ => {}
        }
        if let (Message::ReportComponentStatus(s), Some(from)) = (msg, ctx.source()) {
            self.keeper.on_status(from, s);
        }
        if let Message::ReportComponentStatus(s) = msg {
            let state = CoreState::from_wire(s.primary_status_code);
            let from = ctx.source();
            let (driver, next) = match self.step {
                Step::Waypoints => (addr::GWD, Step::StartPath),
                Step::Path => (addr::LPSD, Step::StartMission),
                _ => return Ok(None),
            };
            if from != Some(driver) {
                return Ok(None);
            }
            match state {
                Some(CoreState::Ready) => self.seen_ready = true,
                Some(CoreState::Standby) if self.seen_ready => {
                    match self.step {
                        Step::Waypoints => self.waypoints_done = Some(ctx.now()),
                        _ => self.path_done = Some(ctx.now()),
                    }
                    self.step = next;
                }
                _ => {}
            }
        }
        Ok(None)
    }
}

/// The Spool Mission of the third phase.
fn mission_message(frame: &LocalFrame, speed: f64, moves: &[(f64, f64)]) -> SpoolMission {
    // Every message here encodes (fixed fields in range); an encoding error would be a
    // bug of this function, so fall back to an empty body rather than panic.
    let cmd = |uid: u16, to: Address, m: Message, blocking: bool| {
        command(uid, addr::MS, to, &m, blocking).unwrap_or(MissionCommand {
            uid,
            message: jaus::Packet::new(jaus::Header::new(m.code(), to, addr::MS), Vec::new()),
            blocking: u8::from(blocking),
        })
    };
    let goto = |uid: u16, (x, y): (f64, f64)| {
        let (latitude, longitude) = frame.to_global(Vector2::new(x, y));
        let w = SetGlobalWaypoint {
            waypoint_number: 0,
            latitude,
            longitude,
            ..Default::default()
        };
        vec![
            cmd(uid, addr::GWD, Resume {}.into(), false),
            cmd(uid + 1, addr::GWD, SetTravelSpeed { speed }.into(), false),
            cmd(uid + 2, addr::GWD, w.into(), true),
        ]
    };
    let leaf = leaf_task;
    let horn = SetDiscreteDevices {
        parking_brake_and_horn: Some(ParkingBrakeHorn {
            parking_brake: false,
            horn: true,
            reserved: 0,
        }),
        ..Default::default()
    };
    // Every move but the last, then the payload action, then the move home.
    let (home, outbound) = moves
        .split_last()
        .map_or((MISSION[1], &[][..]), |(h, o)| (*h, o));
    let mut children: Vec<MissionTask> = outbound
        .iter()
        .enumerate()
        .map(|(i, m)| leaf(i as u16 + 1, goto(10 * (i as u16 + 1), *m)))
        .collect();
    let n = children.len() as u16;
    children.push(leaf(n + 1, vec![cmd(500, addr::PD, horn.into(), false)]));
    children.push(leaf(n + 2, goto(600, home)));
    mission_of(1, children)
}

/// The mission as driven: from P4 (where the path segments end) through the moves.
fn mission_route() -> Vec<Vector2<f64>> {
    let mut route = vec![Vector2::new(SEGMENTS[1].1 .0, SEGMENTS[1].1 .1)];
    route.extend(MISSION.iter().map(|(x, y)| Vector2::new(*x, *y)));
    route
}

/// An object the world model returned.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Found {
    centre: Vector2<f64>,
    buffer: f64,
    /// Stored by the operator (else detected by the range sensor).
    operator: bool,
}

/// One object for each group of overlapping ones (the range sensor also detects the
/// obstacle the operator stored): the one with the largest buffer, the operator's
/// flag if either was the operator's.
fn merge_overlapping(objects: Vec<Found>) -> Vec<Found> {
    let mut out: Vec<Found> = Vec::new();
    for o in objects {
        match out
            .iter_mut()
            .find(|k| (k.centre - o.centre).norm() < k.buffer.max(o.buffer))
        {
            Some(k) => {
                let operator = k.operator || o.operator;
                if o.buffer > k.buffer {
                    *k = o;
                }
                k.operator = operator;
            }
            None => out.push(o),
        }
    }
    out
}

/// The moves of `route` (its first point is where the vehicle is) with a detour
/// waypoint before each leg's end for every object within its buffer plus
/// [`CLEARANCE`] of that leg, in the order the leg meets them.
fn plan_round(route: &[Vector2<f64>], objects: &[Found]) -> Vec<(f64, f64)> {
    let mut plan = Vec::new();
    for leg in route.windows(2) {
        let (from, to) = (leg[0], leg[1]);
        let Some(dir) = (to - from).try_normalize(1e-9) else {
            plan.push((to.x, to.y));
            continue;
        };
        let mut on_leg: Vec<(f64, (f64, f64))> = objects
            .iter()
            .filter_map(|o| {
                let along = (o.centre - from).dot(&dir).clamp(0.0, (to - from).norm());
                let off = (o.centre - (from + dir * along)).norm();
                (off < o.buffer + CLEARANCE).then(|| (along, detour(from, to, o.centre, o.buffer)))
            })
            .collect();
        on_leg.sort_by(|a, b| a.0.total_cmp(&b.0));
        plan.extend(on_leg.into_iter().map(|(_, p)| p));
        plan.push((to.x, to.y));
    }
    plan
}

/// A waypoint that takes the leg `from` → `to` round an obstacle at `c` with buffer `r`:
/// beside the obstacle's projection on the leg, `r` + [`CLEARANCE`] + a margin for the
/// corner the vehicle cuts, on the side the obstacle leaves free.
fn detour(from: Vector2<f64>, to: Vector2<f64>, c: Vector2<f64>, r: f64) -> (f64, f64) {
    let d = (to - from)
        .try_normalize(1e-9)
        .unwrap_or(Vector2::new(1.0, 0.0));
    let along = (c - from).dot(&d).clamp(0.0, (to - from).norm());
    let foot = from + d * along;
    let mut n = Vector2::new(-d.y, d.x);
    if (c - foot).dot(&n) > 0.0 {
        n = -n;
    }
    let p = c + n * (r + CLEARANCE + 0.3) - (c - foot);
    (p.x, p.y)
}

fn driver_config(pose_sensor: Address, ss: u8, node: u8) -> DriverConfig {
    DriverConfig {
        // Part 1 Figures 5-9 and 5-16: driving through the Reflexive Driver.
        output: addr::on(addr::RD, ss, node),
        pose_sensor,
        velocity_sensor: Some(addr::on(addr::VSS, ss, node)),
        origin: Some(LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2)),
        ..DriverConfig::default()
    }
}

/// The vehicle side of the demo (node 1.1): primitive and reflexive drivers, pose and
/// velocity sensors, the global waypoint and local path-segment drivers, over one
/// simulated vehicle.
pub fn vehicle(t0: Instant, opts: &Options) -> (Vec<Box<dyn Endpoint>>, SimVehicle) {
    vehicle_at(t0, opts, 1, 1)
}

/// [`vehicle`] on node `node` of subsystem `ss` (the components keep their ids and
/// instances of [`addr`]; the drivers' outputs and sensors follow them).
pub fn vehicle_at(
    t0: Instant,
    opts: &Options,
    ss: u8,
    node: u8,
) -> (Vec<Box<dyn Endpoint>>, SimVehicle) {
    let at = |a: Address| addr::on(a, ss, node);
    let vehicle = SimVehicle::new(VehicleParams {
        position_noise: opts.position_noise,
        heading_noise: opts.position_noise * 0.5,
        seed: opts.seed,
        origin: LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2),
        start: (Vector2::zeros(), 0.0),
        ..VehicleParams::default()
    });
    let cfg = config();
    let pd = StockPrimitiveDriver::new(vehicle.clone(), PrimitiveConfig::default());
    let rd = StockReflexiveDriver::new(
        (),
        ReflexiveConfig {
            output: at(addr::PD),
            ..Default::default()
        },
    );
    let scene = scene();
    let vs = StockVisualSensor::new(
        SimCamera::new(vehicle.clone(), scene.clone()),
        VisualConfig::default(),
    );
    let scanner = SimScanner::new(
        vehicle.clone(),
        scene,
        ScannerParams {
            noise: 0.01,
            seed: opts.seed,
            ..ScannerParams::default()
        },
    );
    let rs = StockRangeSensor::new(scanner, RangeConfig::default()).with_map_feed(MapFeedConfig {
        origin: Some(LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2)),
        ..MapFeedConfig::new(at(addr::WM), at(addr::GPS))
    });
    let gwd = StockGlobalWaypointDriver::new(driver_config(at(addr::GPS), ss, node));
    let lpsd = StockLocalPathSegmentDriver::new(driver_config(at(addr::LPS), ss, node));
    let gpsd = StockGlobalPathSegmentDriver::new(driver_config(at(addr::GPS), ss, node));
    let parts: Vec<Box<dyn Endpoint>> = vec![
        Box::new(primitive_driver::component(
            at(addr::PD),
            pd,
            cfg.clone(),
            t0,
        )),
        Box::new(reflexive_driver::component(
            at(addr::RD),
            rd,
            cfg.clone(),
            t0,
        )),
        Box::new(global_pose_sensor::component(
            at(addr::GPS),
            StockGlobalPoseSensor(vehicle.clone()),
            cfg.clone(),
            t0,
        )),
        Box::new(local_pose_sensor::component(
            at(addr::LPS),
            StockLocalPoseSensor(vehicle.clone()),
            cfg.clone(),
            t0,
        )),
        Box::new(velocity_state_sensor::component(
            at(addr::VSS),
            StockVelocityStateSensor(vehicle.clone()),
            cfg.clone(),
            t0,
        )),
        Box::new(global_waypoint_driver::component(
            at(addr::GWD),
            gwd,
            cfg.clone(),
            t0,
        )),
        Box::new(local_path_segment_driver::component(
            at(addr::LPSD),
            lpsd,
            cfg.clone(),
            t0,
        )),
        Box::new(global_path_segment_driver::component(
            at(addr::GPSD),
            gpsd,
            cfg.clone(),
            t0,
        )),
        Box::new(range_sensor::component(at(addr::RS), rs, cfg.clone(), t0)),
        Box::new(visual_sensor::component(at(addr::VS), vs, cfg.clone(), t0)),
        Box::new(world_model_vector_knowledge_store::component(
            at(addr::WM),
            StockWorldModel::new(WorldModelConfig::default()),
            cfg.clone(),
            t0,
        )),
        // The Subsystem Commander takes the spooler's control with authority 150 (the
        // spooler accepts 100 and above; an operator station at 200 can still take it).
        Box::new(subsystem_commander::component(
            at(addr::SC),
            StockSubsystemCommander::new(SubsystemConfig::new(at(addr::MS))),
            Config {
                authority: 150,
                ..cfg.clone()
            },
            t0,
        )),
        // The spooler outranks the reflexive driver so that it can borrow the primitive
        // driver for the mission's payload action (the horn).
        Box::new(mission_spooler::component(
            at(addr::MS),
            StockMissionSpooler::new(SpoolerConfig::default()),
            Config {
                authority: 100,
                ..cfg
            },
            t0,
        )),
    ];
    (parts, vehicle)
}

/// The demo's vehicle on a node of its own (`subsystem.node`, the node's other settings
/// from `config`), as `jaus node` with `host: [vehicle]` runs it.
pub fn vehicle_node(
    t0: Instant,
    mut config: jaus::net::NodeConfig,
    subsystem: u8,
    node: u8,
) -> Result<jaus::net::Node, jaus::net::NetError> {
    config.subsystem = subsystem;
    config.node = node;
    let mut n = jaus::net::Node::new(config, t0);
    for p in vehicle_at(t0, &Options::default(), subsystem, node).0 {
        n.add_boxed(p)?;
    }
    Ok(n)
}

/// The operator side of the demo (1.2.40.1).
pub fn operator(t0: Instant, opts: &Options) -> Ocu {
    // The drivers are resumed by the operator once their orders are loaded.
    let mut keeper = ControlKeeper::new(KeeperConfig {
        resume: false,
        ..KeeperConfig::default()
    });
    keeper.keep(addr::GWD);
    keeper.keep(addr::LPSD);
    let ocu = Operator {
        waypoint_speed: opts.waypoint_speed,
        path_speed: opts.path_speed,
        keeper,
        ..Operator::default()
    };
    // The operator outranks everything it commands.
    system_commander::component(
        addr::OCU,
        ocu,
        Config {
            authority: 200,
            ..config()
        },
        t0,
    )
}

fn config() -> Config {
    Config {
        utc: Some(Duration::from_secs(1_795_000_000)),
        ..Config::default()
    }
}

/// Builds the demo subsystem on a bus starting at `t0`; returns the bus and the vehicle.
pub fn build(t0: Instant, opts: &Options) -> (LocalBus, SimVehicle) {
    let (parts, vehicle) = vehicle(t0, opts);
    let mut bus = LocalBus::new(t0);
    for p in parts {
        bus.add_boxed(p);
    }
    bus.add(operator(t0, opts));
    (bus, vehicle)
}

/// Progress of the operator: (phase, waypoints done at, path done at, mission done at).
pub fn progress(
    ocu: &Ocu,
) -> (
    &'static str,
    Option<Instant>,
    Option<Instant>,
    Option<Instant>,
) {
    let o = &ocu.behaviour().0;
    (
        phase_name(o.step),
        o.waypoints_done,
        o.path_done,
        o.mission_done,
    )
}

fn phase_name(s: Step) -> &'static str {
    match s {
        Step::TakeControl => "taking control",
        Step::StartWaypoints | Step::Waypoints => "waypoints",
        Step::StartPath | Step::Path => "path segments",
        Step::StartMission | Step::StoreObstacle | Step::PlanMission | Step::Mission => {
            "spooled mission"
        }
        Step::Done => "done",
    }
}

/// The operator component.
pub type Ocu = jaus::component::Component<system_commander::Dispatch<Operator>>;

/// Runs the demo; `print` receives progress lines.
pub fn run(opts: &Options, mut print: impl FnMut(&str)) -> Result<Report, String> {
    let t0 = Instant::now();
    let (mut bus, vehicle) = build(t0, opts);
    let slice = Duration::from_millis(100);
    let mut next_progress = Duration::ZERO;
    let wall = Instant::now();
    loop {
        let elapsed = bus.now() - t0;
        let (step, done_at, horn_at) = {
            let o = &bus
                .get::<Ocu>(addr::OCU)
                .ok_or("operator missing")?
                .behaviour()
                .0;
            (
                o.step,
                [o.waypoints_done, o.path_done, o.mission_done],
                o.horn_at,
            )
        };
        if let Some(every) = opts.progress {
            if elapsed >= next_progress || step == Step::Done {
                next_progress = elapsed + every;
                let v = vehicle.lock();
                let p = v.position();
                print(&format!(
                    "t = {:6.1} s  {:<16} x {:6.2} m  y {:6.2} m  heading {:6.1}°  speed {:4.2} m/s",
                    elapsed.as_secs_f64(),
                    phase_name(step),
                    p.x,
                    p.y,
                    v.yaw().to_degrees(),
                    v.speed()
                ));
            }
        }
        if step == Step::Done {
            let (planned, found, image) = bus
                .get::<Ocu>(addr::OCU)
                .map(|o| {
                    let o = &o.behaviour().0;
                    (o.planned.clone(), o.objects_found, o.image.clone())
                })
                .unwrap_or_default();
            let trail: Vec<(f64, Vector2<f64>)> = vehicle
                .lock()
                .trail()
                .iter()
                .map(|(d, p)| (d.as_secs_f64(), *p))
                .collect();
            let run = ((bus.now() - t0).as_secs_f64(), bus.stats().delivered);
            return Ok(Report {
                image,
                ..measure(t0, &trail, done_at, horn_at, (&planned, found), run)
            });
        }
        if elapsed > opts.timeout {
            return Err(format!(
                "the mission did not finish within {:?} of simulated time (stuck at {step:?})",
                opts.timeout
            ));
        }
        bus.run_for(slice);
        if opts.realtime {
            let target = wall + (bus.now() - t0);
            let now = Instant::now();
            if target > now {
                std::thread::sleep(target - now);
            }
        }
    }
}

/// Legs of the commanded paths: waypoint legs are straight lines from the previous
/// point; path segments are the curves of Part 1.
fn commanded_legs(mission: &[(f64, f64)]) -> (Legs, Legs, Legs) {
    let mut wp = Vec::new();
    let mut from = Vector2::new(0.0, 0.0);
    for (i, (x, y)) in WAYPOINTS.iter().enumerate() {
        let to = Vector2::new(*x, *y);
        wp.push((format!("waypoint {i}"), Path::new([from, to])));
        from = to;
    }
    let mut ps = Vec::new();
    let mut p0 = from;
    for (i, (p1, p2, w1)) in SEGMENTS.iter().enumerate() {
        let seg = PathSegment {
            p0: Vector3::new(p0.x, p0.y, 0.0),
            p1: Vector3::new(p1.0, p1.1, 0.0),
            p2: Vector3::new(p2.0, p2.1, 0.0),
            w1: *w1,
        };
        let mut path = Path::default();
        path.push_segment(&seg);
        ps.push((format!("path segment {i}"), path));
        p0 = Vector2::new(p2.0, p2.1);
    }
    let mut ms = Vec::new();
    for (i, (x, y)) in mission.iter().enumerate() {
        let to = Vector2::new(*x, *y);
        ms.push((format!("mission move {i}"), Path::new([p0, to])));
        p0 = to;
    }
    (wp, ps, ms)
}

/// What the run measured, from a trajectory `trail` (seconds since `t0`, local
/// metres): the simulated vehicle's true one in the in-process demo, the positions the
/// operator received in `--ocu-only`.
fn measure(
    t0: Instant,
    trail: &[(f64, Vector2<f64>)],
    done_at: [Option<Instant>; 3],
    horn_at: Option<Instant>,
    (planned, objects_found): (&[(f64, f64)], (usize, usize)),
    (duration, messages): (f64, u64),
) -> Report {
    let [wp_done, path_done, mission_done] = done_at;
    let secs = |t: Option<Instant>| t.map(|t| (t - t0).as_secs_f64());
    let (wp_legs, path_legs, mission_legs) = commanded_legs(planned);
    let wp_end = secs(wp_done).unwrap_or(f64::INFINITY);
    let path_end = secs(path_done).unwrap_or(f64::INFINITY);
    let mission_end = secs(mission_done).unwrap_or(f64::INFINITY);
    let mut legs = Vec::new();
    let phases = [
        (&wp_legs, 0.0, wp_end),
        (&path_legs, wp_end, path_end),
        (&mission_legs, path_end, mission_end),
    ];
    for (phase_legs, start, end) in phases {
        // Points of this phase, assigned to the leg they are nearest to, moving forward
        // only (a point near a corner belongs to the leg being driven).
        let pts: Vec<&(f64, Vector2<f64>)> = trail
            .iter()
            .filter(|(t, _)| *t >= start && *t <= end)
            .collect();
        let mut leg = 0usize;
        let mut errs: Vec<Vec<f64>> = vec![Vec::new(); phase_legs.len()];
        let mut arrivals: Vec<Option<f64>> = vec![None; phase_legs.len()];
        for (t, p) in pts {
            while leg + 1 < phase_legs.len() {
                let here = phase_legs[leg].1.project(*p, 0.0, f64::INFINITY);
                let next = phase_legs[leg + 1].1.project(*p, 0.0, f64::INFINITY);
                let end_reached = here.is_some_and(|h| h.s >= phase_legs[leg].1.length() - 0.3);
                match (here, next) {
                    (Some(h), Some(n)) if end_reached && n.distance <= h.distance => {
                        arrivals[leg] = Some(*t);
                        leg += 1;
                    }
                    _ => break,
                }
            }
            if let Some(h) = phase_legs[leg].1.project(*p, 0.0, f64::INFINITY) {
                errs[leg].push(h.distance);
            }
        }
        if end.is_finite() {
            arrivals[phase_legs.len() - 1] = Some(end);
        }
        for (i, (name, _)) in phase_legs.iter().enumerate() {
            let e = &errs[i];
            let rms = if e.is_empty() {
                0.0
            } else {
                (e.iter().map(|x| x * x).sum::<f64>() / e.len() as f64).sqrt()
            };
            legs.push(Leg {
                name: name.clone(),
                arrival: arrivals[i],
                xte_rms: rms,
                xte_max: e.iter().copied().fold(0.0, f64::max),
            });
        }
    }
    let at = |t: f64| {
        trail
            .iter()
            .find(|(s, _)| *s >= t)
            .or(trail.last())
            .map(|(_, p)| *p)
            .unwrap_or_default()
    };
    let clearance = |((ox, oy), _): ((f64, f64), f64)| {
        trail
            .iter()
            .filter(|(t, _)| *t >= path_end && *t <= mission_end)
            .map(|(_, p)| (p - Vector2::new(ox, oy)).norm())
            .fold(f64::INFINITY, f64::min)
    };
    let obstacle_clearance = clearance(OBSTACLE);
    let unknown_clearance = clearance(UNKNOWN_OBSTACLE);
    let final_errors = vec![
        (at(wp_end) - Vector2::new(WAYPOINTS[4].0, WAYPOINTS[4].1)).norm(),
        (at(path_end) - Vector2::new(SEGMENTS[1].1 .0, SEGMENTS[1].1 .1)).norm(),
        (at(mission_end) - Vector2::new(MISSION[1].0, MISSION[1].1)).norm(),
    ];
    let commanded: Vec<Vec<Vector2<f64>>> = wp_legs
        .iter()
        .chain(&path_legs)
        .chain(&mission_legs)
        .map(|(_, p)| p.points().to_vec())
        .collect();
    let trail_points: Vec<Vector2<f64>> = trail.iter().map(|(_, p)| *p).collect();
    Report {
        legs,
        waypoints_done: secs(wp_done),
        path_done: secs(path_done),
        mission_done: secs(mission_done),
        horn_at: secs(horn_at),
        obstacle_clearance,
        unknown_clearance,
        objects_found,
        planned: planned.to_vec(),
        image: None,
        final_errors,
        duration,
        messages,
        commanded,
        trail: trail_points,
    }
}

/// The report of an operator that drove the vehicle over a network (`jaus demo
/// --ocu-only`): measured on the positions it received from the Local Pose Sensor (a
/// 10 Hz service connection), so the errors include the sensor's noise and the link's
/// delay. `None` until the operator is done.
pub fn operator_report(t0: Instant, ocu: &Ocu) -> Option<Report> {
    let o = &ocu.behaviour().0;
    if o.step != Step::Done {
        return None;
    }
    let trail: Vec<(f64, Vector2<f64>)> = o
        .trail
        .iter()
        .map(|(t, p)| ((*t - t0).as_secs_f64(), *p))
        .collect();
    let end = o.trail.last().map_or(0.0, |(t, _)| (*t - t0).as_secs_f64());
    Some(Report {
        image: o.image.clone(),
        ..measure(
            t0,
            &trail,
            [o.waypoints_done, o.path_done, o.mission_done],
            o.horn_at,
            (&o.planned, o.objects_found),
            (end, ocu.stats().received),
        )
    })
}
