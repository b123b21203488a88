//! [`Station`]: an operator station's logic (see the module documentation of
//! [`commander`](super)).

use std::collections::{BTreeMap, VecDeque};
use std::time::{Duration, Instant};

use nalgebra::Vector2;

use super::keeper::{ControlEvent, ControlKeeper, KeeperConfig};
use super::view::{
    ComponentView, MissionView, NodeView, Notice, ObjectView, PoseView, Roles, SubsystemView,
    SystemView, VelocityView,
};
use crate::component::{Context, CoreState, Interface};
use crate::messages::{
    AbortMission, ClearEmergency, ClearEmergencyCode, ControlResponse, CreateVksObjects,
    EmergencyCode, Message, MissionCommand, MissionStatusType, PauseMission, QueryComponentControl,
    QueryComponentStatus, QueryGlobalPose, QueryMissionStatus, QueryVelocityState, QueryVksObjects,
    ReportGlobalPose, ReportVelocityState, Resume, ResumeMission, RunMission, SetEmergency,
    SetGlobalPathSegment, SetGlobalWaypoint, SetTravelSpeed, SpoolMission, Standby, VksAttribute,
    VksFeatureClass, VksObject, VksObjectType, VksPoint,
};
use crate::stock::geo::LocalFrame;
use crate::stock::spooler::{command, leaf_task, mission_of};
use crate::{Address, JausMessage};

/// Component ids the station gives a role (Part 1 §5).
mod id {
    pub const NODE_MANAGER: u8 = 1;
    pub const PRIMITIVE_DRIVER: u8 = 33;
    pub const MISSION_SPOOLER: u8 = 36;
    pub const GLOBAL_POSE: u8 = 38;
    pub const LOCAL_POSE: u8 = 41;
    pub const VELOCITY: u8 = 42;
    pub const GLOBAL_WAYPOINT_DRIVER: u8 = 45;
    pub const GLOBAL_PATH_SEGMENT_DRIVER: u8 = 47;
    pub const WORLD_MODEL: u8 = 61;
}

/// Report Global Pose fields followed: latitude, longitude, yaw.
const POSE_PRESENCE: u16 = 0x43;
/// Report Velocity State fields followed: velocity x and y, yaw rate.
const VELOCITY_PRESENCE: u32 = 0x43;
/// The request id of the station's Query VKS Objects.
const VKS_REQUEST: u8 = 0xC1;
/// Request id of the station's Create VKS Objects.
const CREATE_REQUEST: u8 = 0xC2;
/// Largest obstacle radius the station stores, m.
pub const MAX_RADIUS: f64 = 1000.0;
/// Most points of one waypoint list, path or mission.
pub const MAX_POINTS: usize = 255;

/// Settings of a [`Station`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StationConfig {
    /// Rate of the pose and velocity service connections, Hz.
    pub pose_rate: f64,
    /// How often every component's status and controller are queried.
    pub status_period: Duration,
    /// How often world models are asked for their objects.
    pub world_model_period: Duration,
    /// How often a spooled mission's status is queried.
    pub mission_period: Duration,
    /// A subsystem not heard from for this long is shown stale.
    pub stale_after: Duration,
    /// When a service connection is not active this long after it was asked for, the
    /// pose and velocity are queried at `pose_rate` instead.
    pub poll_after: Duration,
    /// Positions kept per subsystem.
    pub trail_max: usize,
    /// Commands waiting to be sent (more are refused).
    pub max_pending: usize,
    /// Notices kept.
    pub max_notices: usize,
    /// Highest travel speed accepted, m/s.
    pub max_speed: f64,
    /// How control is asked for and kept.
    pub keeper: KeeperConfig,
}

/// Poses at 10 Hz, status every second, world models every 2 s, stale after 2 s,
/// 3,000 positions per subsystem, 64 pending commands, 200 notices, at most 10 m/s.
impl Default for StationConfig {
    fn default() -> Self {
        Self {
            pose_rate: 10.0,
            status_period: Duration::from_secs(1),
            world_model_period: Duration::from_secs(2),
            mission_period: Duration::from_secs(1),
            stale_after: Duration::from_secs(2),
            poll_after: Duration::from_secs(3),
            trail_max: 3_000,
            max_pending: 64,
            max_notices: 200,
            max_speed: 10.0,
            keeper: KeeperConfig {
                resume: false,
                ..KeeperConfig::default()
            },
        }
    }
}

/// A WGS 84 position.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeoPoint {
    /// Latitude, degrees.
    pub latitude: f64,
    /// Longitude, degrees.
    pub longitude: f64,
}

/// What to do with a spooled mission.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MissionAction {
    /// Run Mission.
    Run,
    /// Pause Mission (the whole mission).
    Pause,
    /// Resume Mission.
    Resume,
    /// Abort Mission.
    Abort,
}

/// An operator's command to a [`Station`].
#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    /// Take control of `target` with `authority` and keep it (asking again when lost).
    TakeControl {
        /// The component.
        target: Address,
        /// Authority to ask with.
        authority: u8,
    },
    /// Give control of `target` back and stop keeping it.
    ReleaseControl {
        /// The component.
        target: Address,
    },
    /// Set Emergency on every component of `subsystem` (no control needed).
    Emergency {
        /// The subsystem.
        subsystem: u8,
    },
    /// Clear Emergency on every component of `subsystem`.
    ClearEmergency {
        /// The subsystem.
        subsystem: u8,
    },
    /// Resume a controlled component (Standby → Ready).
    Resume {
        /// The component.
        target: Address,
    },
    /// Put a controlled component in Standby.
    Standby {
        /// The component.
        target: Address,
    },
    /// Drive through `points` with a controlled Global Waypoint Driver: Resume, the
    /// waypoints (a new list), the travel speed.
    Waypoints {
        /// The driver.
        driver: Address,
        /// The waypoints, in order.
        points: Vec<GeoPoint>,
        /// Travel speed, m/s.
        speed: f64,
    },
    /// Drive along straight path segments through `points` with a controlled Global Path
    /// Segment Driver (each segment's weighting factor 0: a straight line to its P2).
    PathSegments {
        /// The driver.
        driver: Address,
        /// The segments' end points, in order.
        points: Vec<GeoPoint>,
        /// Travel speed, m/s.
        speed: f64,
    },
    /// Spool a mission on a controlled spooler: one task per point, each a blocking move
    /// of `driver` (Resume, Set Travel Speed, Set Global Waypoint). The station gives up
    /// its own control of `driver`: the spooler takes it.
    SpoolMission {
        /// The spooler.
        spooler: Address,
        /// The waypoint driver the spooler commands.
        driver: Address,
        /// The moves, in order.
        points: Vec<GeoPoint>,
        /// Travel speed, m/s.
        speed: f64,
    },
    /// Run, pause, resume or abort the mission last spooled on `spooler`.
    Mission {
        /// The spooler.
        spooler: Address,
        /// What to do.
        action: MissionAction,
    },
    /// Store an obstacle in a World Model Vector Knowledge Store (no control needed: the
    /// store takes objects from anyone): a point object with a buffer of `radius` metres
    /// and feature class `class`, which planners querying the store then avoid.
    StoreObstacle {
        /// The World Model Vector Knowledge Store.
        world_model: Address,
        /// Where the obstacle is.
        point: GeoPoint,
        /// Its radius (the object's buffer), m.
        radius: f64,
        /// Feature class id given to it.
        class: u16,
    },
}

impl Command {
    /// The component the command is for (the first of a subsystem's for emergencies).
    fn target(&self) -> Option<Address> {
        match self {
            Command::TakeControl { target, .. }
            | Command::ReleaseControl { target }
            | Command::Resume { target }
            | Command::Standby { target } => Some(*target),
            Command::Waypoints { driver, .. } | Command::PathSegments { driver, .. } => {
                Some(*driver)
            }
            Command::SpoolMission { spooler, .. } | Command::Mission { spooler, .. } => {
                Some(*spooler)
            }
            Command::StoreObstacle { world_model, .. } => Some(*world_model),
            Command::Emergency { .. } | Command::ClearEmergency { .. } => None,
        }
    }
}

/// Why a [`Station`] refused a command.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StationError {
    /// No such component in the system tree.
    #[error("{0}: no such component in the system tree")]
    Unknown(Address),
    /// No such subsystem in the system tree.
    #[error("subsystem {0}: not in the system tree")]
    UnknownSubsystem(u8),
    /// The command needs control of the component, which the station does not hold.
    #[error("{target}: {what} needs control of it, which this station does not hold (take control first)")]
    NotInControl {
        /// The component.
        target: Address,
        /// The command.
        what: &'static str,
    },
    /// The command is for a component of another kind.
    #[error("{target}: {what} is for a {expected} (component id {id})")]
    WrongComponent {
        /// The component.
        target: Address,
        /// The command.
        what: &'static str,
        /// What it needs.
        expected: &'static str,
        /// The id it needs.
        id: u8,
    },
    /// A coordinate is not a number or out of range.
    #[error("point {index}: {field} {value} is not within [{min}, {max}] degrees")]
    Coordinate {
        /// Index of the point.
        index: usize,
        /// `latitude` or `longitude`.
        field: &'static str,
        /// The value given.
        value: f64,
        /// Lowest accepted.
        min: f64,
        /// Highest accepted.
        max: f64,
    },
    /// No points, or too many.
    #[error("{0} points: give between 1 and {MAX_POINTS}")]
    Points(usize),
    /// The speed is not a number or out of range.
    #[error("travel speed {value} m/s is not within (0, {max}] m/s")]
    Speed {
        /// The value given.
        value: f64,
        /// Highest accepted.
        max: f64,
    },
    /// No mission was spooled on the spooler.
    #[error("{0}: no mission spooled by this station")]
    NoMission(Address),
    /// An obstacle's radius is not a number or out of range.
    #[error("obstacle radius {value} m is not within (0, {max}] m")]
    Radius {
        /// The value given.
        value: f64,
        /// Highest accepted (what the object's buffer field carries).
        max: f64,
    },
    /// Too many commands waiting.
    #[error("{0} commands are waiting to be sent: try again")]
    Busy(usize),
}

#[derive(Debug, Clone, Default)]
struct Known {
    name: Option<String>,
    state: Option<(CoreState, Instant)>,
    controller: Option<(Address, u8)>,
}

#[derive(Debug, Clone, Default)]
struct Vehicle {
    pose: Option<(PoseView, Instant)>,
    velocity: Option<(VelocityView, Instant)>,
    trail: VecDeque<(f64, f64)>,
    pose_count: u64,
    objects: Vec<ObjectView>,
    mission: Option<(Address, MissionView)>,
    route: Vec<(f64, f64)>,
    emergency: bool,
}

/// Names of the subsystems and nodes, and the components, of the system tree.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct TreeInput {
    /// Subsystem names.
    pub subsystems: BTreeMap<u8, Option<String>>,
    /// Node names.
    pub nodes: BTreeMap<(u8, u8), Option<String>>,
    /// Components with their names.
    pub components: BTreeMap<Address, Option<String>>,
}

/// An operator station's logic (see the module documentation).
#[derive(Debug)]
pub struct Station {
    config: StationConfig,
    keeper: ControlKeeper,
    tree: TreeInput,
    known: BTreeMap<Address, Known>,
    vehicles: BTreeMap<u8, Vehicle>,
    frame: Option<LocalFrame>,
    pending: VecDeque<Command>,
    /// Sensors the station follows that came out of Emergency into Standby, to resume.
    wake: Vec<Address>,
    /// Sensors being resumed: control asked for (since then), Resume sent on the grant,
    /// control given back once they report Ready.
    waking: Vec<(Address, Instant)>,
    /// Notices with when they were made (the station's clock at the time).
    notices: VecDeque<(Option<Instant>, Notice)>,
    notice_count: u64,
    subscribed: BTreeMap<(Address, u16), Instant>,
    next_status: Option<Instant>,
    next_world: Option<Instant>,
    next_mission: Option<Instant>,
    next_poll: Option<Instant>,
    next_mission_id: u16,
    /// The station's own address (known from the first tick).
    me: Option<Address>,
    /// Poses received in all.
    poses: u64,
    /// The latest time the station was given (tick, message): it reads no clock itself.
    clock: Option<Instant>,
}

impl Default for Station {
    fn default() -> Self {
        Self::new(StationConfig::default())
    }
}

/// Sends a standard message from a component of any interface.
fn send_std<I: Interface>(ctx: &mut Context<'_, I>, to: Address, m: Message) {
    ctx.forward(to, <I::Messages as crate::MessageSet>::from_standard(m));
}

impl Station {
    /// With `config`, knowing nothing yet.
    pub fn new(config: StationConfig) -> Self {
        Self {
            config,
            keeper: ControlKeeper::new(config.keeper),
            tree: TreeInput::default(),
            known: BTreeMap::new(),
            vehicles: BTreeMap::new(),
            frame: None,
            pending: VecDeque::new(),
            wake: Vec::new(),
            waking: Vec::new(),
            notices: VecDeque::new(),
            notice_count: 0,
            subscribed: BTreeMap::new(),
            next_status: None,
            next_world: None,
            next_mission: None,
            next_poll: None,
            next_mission_id: 1,
            me: None,
            poses: 0,
            clock: None,
        }
    }

    /// The local map's frame (origin: the first position received).
    pub fn frame(&self) -> Option<&LocalFrame> {
        self.frame.as_ref()
    }

    /// Sets the local map's origin (else the first position received is).
    pub fn set_origin(&mut self, latitude: f64, longitude: f64) {
        self.frame = Some(LocalFrame::new(latitude, longitude, 0.0));
    }

    /// Takes the system tree discovery built (call it when it changed).
    pub fn set_tree(&mut self, tree: TreeInput) {
        for (a, name) in &tree.components {
            self.known.entry(*a).or_default().name.clone_from(name);
        }
        self.known.retain(|a, _| tree.components.contains_key(a));
        for a in tree.components.keys() {
            self.vehicles.entry(a.subsystem).or_default();
        }
        self.tree = tree;
    }

    /// The component of `subsystem` with component id `id` (the lowest instance).
    pub fn find(&self, subsystem: u8, id: u8) -> Option<Address> {
        self.tree
            .components
            .keys()
            .find(|a| a.subsystem == subsystem && a.component == id)
            .copied()
    }

    fn notice(&mut self, error: bool, text: String) {
        if error {
            tracing::warn!("{text}");
        } else {
            tracing::info!("{text}");
        }
        self.notice_count += 1;
        if self.notices.len() >= self.config.max_notices {
            self.notices.pop_front();
        }
        self.notices.push_back((
            self.clock,
            Notice {
                seq: self.notice_count,
                unix_ms: 0,
                error,
                text,
            },
        ));
    }

    /// Records an error of the user interface's own (bad input it could not turn into a
    /// command) among the notices.
    pub fn report_error(&mut self, text: String) {
        self.notice(true, text);
    }

    /// Checks `cmd` and queues it for the next [`tick`](Self::tick); a refused command
    /// is also recorded as a notice.
    pub fn submit(&mut self, cmd: Command) -> Result<(), StationError> {
        let checked = self.check(&cmd);
        if let Err(e) = &checked {
            self.notice(true, e.to_string());
            return checked;
        }
        if self.pending.len() >= self.config.max_pending {
            let e = StationError::Busy(self.pending.len());
            self.notice(true, e.to_string());
            return Err(e);
        }
        self.pending.push_back(cmd);
        Ok(())
    }

    fn check(&self, cmd: &Command) -> Result<(), StationError> {
        if let Some(t) = cmd.target() {
            if !self.tree.components.contains_key(&t) {
                return Err(StationError::Unknown(t));
            }
        }
        let kind = |target: Address, what, expected, id: u8| {
            if target.component == id {
                Ok(())
            } else {
                Err(StationError::WrongComponent {
                    target,
                    what,
                    expected,
                    id,
                })
            }
        };
        let held = |target: Address, what| {
            if self.keeper.holds(target) {
                Ok(())
            } else {
                Err(StationError::NotInControl { target, what })
            }
        };
        match cmd {
            Command::TakeControl { .. } | Command::ReleaseControl { .. } => Ok(()),
            Command::Emergency { subsystem } | Command::ClearEmergency { subsystem } => {
                if self
                    .tree
                    .components
                    .keys()
                    .any(|a| a.subsystem == *subsystem)
                {
                    Ok(())
                } else {
                    Err(StationError::UnknownSubsystem(*subsystem))
                }
            }
            Command::Resume { target } => held(*target, "Resume"),
            Command::Standby { target } => held(*target, "Standby"),
            Command::Waypoints {
                driver,
                points,
                speed,
            } => {
                kind(
                    *driver,
                    "Set Global Waypoint",
                    "Global Waypoint Driver",
                    id::GLOBAL_WAYPOINT_DRIVER,
                )?;
                self.check_route(points, *speed)?;
                held(*driver, "Set Global Waypoint")
            }
            Command::PathSegments {
                driver,
                points,
                speed,
            } => {
                kind(
                    *driver,
                    "Set Global Path Segment",
                    "Global Path Segment Driver",
                    id::GLOBAL_PATH_SEGMENT_DRIVER,
                )?;
                self.check_route(points, *speed)?;
                held(*driver, "Set Global Path Segment")
            }
            Command::SpoolMission {
                spooler,
                driver,
                points,
                speed,
            } => {
                kind(
                    *spooler,
                    "Spool Mission",
                    "Mission Spooler",
                    id::MISSION_SPOOLER,
                )?;
                kind(
                    *driver,
                    "a mission's moves",
                    "Global Waypoint Driver",
                    id::GLOBAL_WAYPOINT_DRIVER,
                )?;
                if !self.tree.components.contains_key(driver) {
                    return Err(StationError::Unknown(*driver));
                }
                self.check_route(points, *speed)?;
                held(*spooler, "Spool Mission")
            }
            Command::StoreObstacle {
                world_model,
                point,
                radius,
                ..
            } => {
                kind(
                    *world_model,
                    "Create VKS Objects",
                    "World Model Vector Knowledge Store",
                    id::WORLD_MODEL,
                )?;
                self.check_points(std::slice::from_ref(point))?;
                if radius.is_finite() && *radius > 0.0 && *radius <= MAX_RADIUS {
                    Ok(())
                } else {
                    Err(StationError::Radius {
                        value: *radius,
                        max: MAX_RADIUS,
                    })
                }
            }
            Command::Mission { spooler, .. } => {
                held(*spooler, "a mission command")?;
                let spooled = self
                    .vehicles
                    .get(&spooler.subsystem)
                    .and_then(|v| v.mission.as_ref())
                    .is_some_and(|(s, _)| s == spooler);
                if spooled {
                    Ok(())
                } else {
                    Err(StationError::NoMission(*spooler))
                }
            }
        }
    }

    fn check_route(&self, points: &[GeoPoint], speed: f64) -> Result<(), StationError> {
        if points.is_empty() || points.len() > MAX_POINTS {
            return Err(StationError::Points(points.len()));
        }
        self.check_points(points)?;
        if !(speed.is_finite() && speed > 0.0 && speed <= self.config.max_speed) {
            return Err(StationError::Speed {
                value: speed,
                max: self.config.max_speed,
            });
        }
        Ok(())
    }

    fn check_points(&self, points: &[GeoPoint]) -> Result<(), StationError> {
        for (index, p) in points.iter().enumerate() {
            for (field, value, max) in [
                ("latitude", p.latitude, 90.0),
                ("longitude", p.longitude, 180.0),
            ] {
                if !(value.is_finite() && (-max..=max).contains(&value)) {
                    return Err(StationError::Coordinate {
                        index,
                        field,
                        value,
                        min: -max,
                        max,
                    });
                }
            }
        }
        Ok(())
    }

    /// Sends what is due: queued commands, control requests, service connections (or
    /// polls where they are not served), status, world-model and mission queries.
    pub fn tick<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        let now = ctx.now();
        let me = ctx.address();
        self.me = Some(me);
        self.clock = Some(now);
        while let Some(cmd) = self.pending.pop_front() {
            self.execute(ctx, cmd);
        }
        self.wake_sensors(ctx);
        for e in self.keeper.tick(ctx) {
            match e {
                ControlEvent::Gained(a) if self.waking.iter().any(|w| w.0 == a) => {
                    ctx.send_core(a, Resume {});
                }
                ControlEvent::Gained(a) => self.notice(false, format!("{a}: control gained")),
                ControlEvent::Lost(a) => {
                    self.notice(true, format!("{a}: control lost; asking again"));
                }
                ControlEvent::State(..) => {}
            }
        }
        // Follow every pose and velocity sensor.
        let sensors: Vec<(Address, u16, f64, u32)> = self
            .tree
            .components
            .keys()
            .filter_map(|a| match a.component {
                id::GLOBAL_POSE => Some((
                    *a,
                    ReportGlobalPose::CODE.0,
                    self.config.pose_rate,
                    u32::from(POSE_PRESENCE),
                )),
                id::VELOCITY => Some((
                    *a,
                    ReportVelocityState::CODE.0,
                    self.config.pose_rate,
                    VELOCITY_PRESENCE,
                )),
                _ => None,
            })
            .collect();
        let mut poll = Vec::new();
        for (a, code, rate, pv) in sensors {
            match self.subscribed.get(&(a, code)) {
                None => {
                    match ctx.create_service_connection(a, crate::CommandCode(code), rate, pv) {
                        Ok(()) => {
                            self.subscribed.insert((a, code), now);
                        }
                        Err(e) => {
                            self.notice(true, format!("{a}: no service connection: {e}"));
                            self.subscribed.insert((a, code), now);
                        }
                    }
                }
                Some(at) => {
                    if now.saturating_duration_since(*at) > self.config.poll_after
                        && !ctx.service_connection_active(a, crate::CommandCode(code))
                    {
                        poll.push((a, code));
                    }
                }
            }
        }
        let poll_period = Duration::from_secs_f64(1.0 / self.config.pose_rate.max(0.1));
        if !poll.is_empty() && self.next_poll.is_none_or(|t| now >= t) {
            self.next_poll = Some(now + poll_period);
            for (a, code) in poll {
                if code == ReportGlobalPose::CODE.0 {
                    send_std(
                        ctx,
                        a,
                        Message::from(QueryGlobalPose {
                            presence_vector: POSE_PRESENCE,
                        }),
                    );
                } else {
                    send_std(
                        ctx,
                        a,
                        Message::from(QueryVelocityState {
                            presence_vector: VELOCITY_PRESENCE as u16,
                        }),
                    );
                }
            }
        }
        if self.next_status.is_none_or(|t| now >= t) {
            self.next_status = Some(now + self.config.status_period);
            let targets: Vec<Address> = self
                .tree
                .components
                .keys()
                .filter(|a| **a != me && a.component != id::NODE_MANAGER)
                .copied()
                .collect();
            for a in targets {
                ctx.send_core(a, QueryComponentStatus {});
                ctx.send_core(a, QueryComponentControl {});
            }
        }
        if self.next_world.is_none_or(|t| now >= t) {
            self.next_world = Some(now + self.config.world_model_period);
            let stores: Vec<Address> = self
                .tree
                .components
                .keys()
                .filter(|a| a.component == id::WORLD_MODEL)
                .copied()
                .collect();
            for a in stores {
                send_std(
                    ctx,
                    a,
                    Message::from(QueryVksObjects {
                        response_presence_vector: 1,
                        request_id: VKS_REQUEST,
                        ..QueryVksObjects::default()
                    }),
                );
            }
        }
        if self.next_mission.is_none_or(|t| now >= t) {
            self.next_mission = Some(now + self.config.mission_period);
            let missions: Vec<(Address, u16)> = self
                .vehicles
                .values()
                .filter_map(|v| v.mission.as_ref().map(|(s, m)| (*s, m.id)))
                .collect();
            for (s, mission_id) in missions {
                send_std(
                    ctx,
                    s,
                    Message::from(QueryMissionStatus {
                        presence_vector: 1,
                        status_type: MissionStatusType::Mission,
                        mission_id,
                        task_id: 0,
                        task_msg_id: 0,
                    }),
                );
            }
        }
    }

    fn execute<I: Interface>(&mut self, ctx: &mut Context<'_, I>, cmd: Command) {
        let me = ctx.address();
        let send = send_std::<I>;
        match cmd {
            Command::TakeControl { target, authority } => {
                self.keeper.keep_with(target, authority);
                self.notice(
                    false,
                    format!("{target}: asking for control with authority {authority}"),
                );
            }
            Command::ReleaseControl { target } => {
                self.keeper.release(ctx, target);
                self.notice(false, format!("{target}: control released"));
            }
            Command::Emergency { subsystem } | Command::ClearEmergency { subsystem } => {
                let set = matches!(cmd, Command::Emergency { .. });
                let targets: Vec<Address> = self
                    .tree
                    .components
                    .keys()
                    .filter(|a| {
                        a.subsystem == subsystem && **a != me && a.component != id::NODE_MANAGER
                    })
                    .copied()
                    .collect();
                for a in &targets {
                    if set {
                        ctx.send_core(
                            *a,
                            SetEmergency {
                                emergency_code: EmergencyCode {
                                    transition_to_emergency: true,
                                    ..EmergencyCode::default()
                                },
                            },
                        );
                    } else {
                        ctx.send_core(
                            *a,
                            ClearEmergency {
                                emergency_code: ClearEmergencyCode {
                                    clear_emergency: true,
                                    ..ClearEmergencyCode::default()
                                },
                            },
                        );
                    }
                }
                // Ask at once how they are.
                self.next_status = None;
                self.notice(
                    set,
                    format!(
                        "subsystem {subsystem}: {} sent to {} component(s)",
                        if set {
                            "Set Emergency"
                        } else {
                            "Clear Emergency"
                        },
                        targets.len()
                    ),
                );
            }
            Command::Resume { target } => ctx.send_core(target, Resume {}),
            Command::Standby { target } => ctx.send_core(target, Standby {}),
            Command::Waypoints {
                driver,
                points,
                speed,
            } => {
                ctx.send_core(driver, Resume {});
                for (i, p) in points.iter().enumerate() {
                    send(
                        ctx,
                        driver,
                        SetGlobalWaypoint {
                            waypoint_number: i as u16,
                            latitude: p.latitude,
                            longitude: p.longitude,
                            ..SetGlobalWaypoint::default()
                        }
                        .into(),
                    );
                }
                self.route_sent(ctx, driver, &points, speed, "waypoint(s)");
            }
            Command::PathSegments {
                driver,
                points,
                speed,
            } => {
                ctx.send_core(driver, Resume {});
                let start = self
                    .vehicles
                    .get(&driver.subsystem)
                    .and_then(|v| v.pose.as_ref())
                    .map(|(p, _)| GeoPoint {
                        latitude: p.latitude,
                        longitude: p.longitude,
                    });
                let mut from = start.unwrap_or(points[0]);
                for (i, p) in points.iter().enumerate() {
                    let mid = GeoPoint {
                        latitude: (from.latitude + p.latitude) / 2.0,
                        longitude: (from.longitude + p.longitude) / 2.0,
                    };
                    send(
                        ctx,
                        driver,
                        SetGlobalPathSegment {
                            path_segment_number: i as u16,
                            p1_latitude: mid.latitude,
                            p1_longitude: mid.longitude,
                            p1_altitude: None,
                            p2_latitude: p.latitude,
                            p2_longitude: p.longitude,
                            p2_altitude: None,
                            weighting_factor: 0.0,
                        }
                        .into(),
                    );
                    from = *p;
                }
                self.route_sent(ctx, driver, &points, speed, "path segment(s)");
            }
            Command::SpoolMission {
                spooler,
                driver,
                points,
                speed,
            } => {
                if self.keeper.holds(driver) || self.keeper.kept().any(|(a, ..)| a == driver) {
                    self.keeper.release(ctx, driver);
                    self.notice(
                        false,
                        format!("{driver}: control released for the spooler {spooler}"),
                    );
                }
                let mission_id = self.next_mission_id;
                self.next_mission_id = self.next_mission_id.wrapping_add(1).max(1);
                match mission(spooler, driver, mission_id, &points, speed) {
                    Ok(m) => {
                        let tasks = m.root.children.len();
                        ctx.send_core(spooler, Resume {});
                        send(ctx, spooler, m.into());
                        self.set_route(driver.subsystem, &points);
                        if let Some(v) = self.vehicles.get_mut(&spooler.subsystem) {
                            v.mission = Some((
                                spooler,
                                MissionView {
                                    id: mission_id,
                                    status: None,
                                    tasks,
                                },
                            ));
                        }
                        self.notice(
                            false,
                            format!("{spooler}: mission {mission_id} spooled ({tasks} moves)"),
                        );
                    }
                    Err(e) => self.notice(true, format!("{spooler}: mission not spooled: {e}")),
                }
            }
            Command::StoreObstacle {
                world_model,
                point,
                radius,
                class,
            } => {
                let object = VksObject {
                    object_type: VksObjectType::Point,
                    buffer: Some(radius as f32),
                    feature_classes: vec![VksFeatureClass {
                        id: class,
                        attribute: VksAttribute::Default,
                    }],
                    points: vec![VksPoint {
                        latitude: point.latitude,
                        longitude: point.longitude,
                    }],
                };
                send(
                    ctx,
                    world_model,
                    CreateVksObjects {
                        buffered: true,
                        message_properties: 0,
                        request_id: CREATE_REQUEST,
                        objects: vec![object],
                    }
                    .into(),
                );
                // Drawn once the store lists it.
                self.next_world = None;
                self.notice(
                    false,
                    format!("{world_model}: obstacle of {radius} m stored (class {class})"),
                );
            }
            Command::Mission { spooler, action } => {
                let Some(id) = self
                    .vehicles
                    .get(&spooler.subsystem)
                    .and_then(|v| v.mission.as_ref())
                    .map(|(_, m)| m.id)
                else {
                    return;
                };
                let m: Message = match action {
                    MissionAction::Run => RunMission { mission_id: id }.into(),
                    MissionAction::Pause => PauseMission {
                        mission_id: id,
                        task_id: 0,
                    }
                    .into(),
                    MissionAction::Resume => ResumeMission {
                        mission_id: id,
                        task_id: 0,
                    }
                    .into(),
                    MissionAction::Abort => AbortMission {
                        mission_id: id,
                        task_id: 0,
                    }
                    .into(),
                };
                self.notice(false, format!("{spooler}: {} (mission {id})", m.name()));
                if matches!(action, MissionAction::Run | MissionAction::Resume) {
                    // The spooler runs missions only in Ready; after an emergency is
                    // cleared it is in Standby.
                    ctx.send_core(spooler, Resume {});
                }
                send(ctx, spooler, m);
                self.next_mission = None;
            }
        }
    }

    /// Resumes the sensors that came out of an emergency into Standby: a component runs
    /// core commands only from its controller, so control is taken for the Resume and
    /// given back once the sensor reports Ready (or after 5 s without it).
    fn wake_sensors<I: Interface>(&mut self, ctx: &mut Context<'_, I>) {
        let now = ctx.now();
        for a in std::mem::take(&mut self.wake) {
            let kept = self.keeper.kept().any(|(k, ..)| k == a);
            if kept || self.waking.iter().any(|w| w.0 == a) {
                // The operator keeps it (and resumes it) or it is being resumed already.
                continue;
            }
            self.keeper.keep(a);
            self.waking.push((a, now));
        }
        let ready: Vec<Address> = self
            .waking
            .iter()
            .filter(|w| {
                self.known
                    .get(&w.0)
                    .and_then(|k| k.state)
                    .is_some_and(|(s, at)| s == CoreState::Ready && at >= w.1)
            })
            .map(|w| w.0)
            .collect();
        for a in ready {
            self.waking.retain(|w| w.0 != a);
            self.keeper.release(ctx, a);
            self.notice(false, format!("{a}: sensor resumed after the emergency"));
        }
        let expired: Vec<Address> = self
            .waking
            .iter()
            .filter(|w| now.saturating_duration_since(w.1) >= Duration::from_secs(5))
            .map(|w| w.0)
            .collect();
        for a in expired {
            self.waking.retain(|w| w.0 != a);
            self.keeper.release(ctx, a);
            self.notice(true, format!("{a}: not resumed after the emergency (no control or still not Ready after 5 s)"));
        }
    }

    /// After a route's elements: the travel speed (after Resume: Part 1 resets it on
    /// Standby → Ready), the route drawn, a notice.
    fn route_sent<I: Interface>(
        &mut self,
        ctx: &mut Context<'_, I>,
        driver: Address,
        points: &[GeoPoint],
        speed: f64,
        what: &str,
    ) {
        send_std(ctx, driver, SetTravelSpeed { speed }.into());
        self.set_route(driver.subsystem, points);
        self.notice(
            false,
            format!("{driver}: {} {what} at {speed} m/s", points.len()),
        );
    }

    fn set_route(&mut self, subsystem: u8, points: &[GeoPoint]) {
        let Some(frame) = self.frame else { return };
        if let Some(v) = self.vehicles.get_mut(&subsystem) {
            v.route = points
                .iter()
                .map(|p| {
                    let l = frame.to_local(p.latitude, p.longitude);
                    (l.x, l.y)
                })
                .collect();
        }
    }

    /// Takes a message addressed to the station; returns whether it was one the
    /// station follows.
    pub fn on_message(&mut self, now: Instant, source: Address, msg: &Message) -> bool {
        self.clock = Some(now);
        let Some(k) = self.known.get_mut(&source) else {
            return false;
        };
        match msg {
            Message::ReportComponentStatus(r) => {
                let state = CoreState::from_wire(r.primary_status_code);
                let before = k.state.map(|s| s.0);
                if let Some(s) = state {
                    k.state = Some((s, now));
                }
                self.keeper.on_status(source, r);
                let emergency = self
                    .known
                    .iter()
                    .filter(|(a, _)| a.subsystem == source.subsystem)
                    .any(|(_, k)| k.state.is_some_and(|s| s.0 == CoreState::Emergency));
                if let Some(v) = self.vehicles.get_mut(&source.subsystem) {
                    v.emergency = emergency;
                }
                if state == Some(CoreState::Emergency) && before != Some(CoreState::Emergency) {
                    self.notice(true, format!("{source}: Emergency"));
                } else if before == Some(CoreState::Emergency) && state != before {
                    if let Some(s) = state {
                        self.notice(false, format!("{source}: left Emergency ({s:?})"));
                    }
                    // A pose or velocity sensor nobody controls is resumed: Clear
                    // Emergency leaves it in Standby, where some stop reporting
                    // (OpenJAUS 3.3's do), and the station and the drivers need it.
                    let sensor = matches!(
                        source.component,
                        id::GLOBAL_POSE | id::LOCAL_POSE | id::VELOCITY
                    );
                    let free = self
                        .known
                        .get(&source)
                        .is_some_and(|k| k.controller.is_none());
                    if sensor
                        && free
                        && state == Some(CoreState::Standby)
                        && !self.wake.contains(&source)
                        && self.wake.len() < 64
                    {
                        self.wake.push(source);
                    }
                }
            }
            Message::ReportComponentControl(r) => {
                let c = Address::new(r.subsystem_id, r.node_id, r.component_id, r.instance_id);
                k.controller = (c.subsystem != 0).then_some((c, r.authority_code));
            }
            Message::ConfirmComponentControl(c) => {
                if c.response_code != ControlResponse::ControlAccepted {
                    self.notice(
                        true,
                        format!("{source}: control refused ({:?})", c.response_code),
                    );
                }
            }
            Message::RejectComponentControl(_) => {
                self.notice(
                    true,
                    format!("{source}: control taken away (Reject Component Control)"),
                );
            }
            Message::ReportGlobalPose(p) => {
                let (Some(lat), Some(lon)) = (p.latitude, p.longitude) else {
                    return true;
                };
                let frame = *self
                    .frame
                    .get_or_insert_with(|| LocalFrame::new(lat, lon, 0.0));
                let l = frame.to_local(lat, lon);
                self.pose(now, source.subsystem, lat, lon, l, p.yaw);
            }
            Message::ReportLocalPose(p) => {
                let has_global = self.find(source.subsystem, id::GLOBAL_POSE).is_some();
                if let (false, Some(x), Some(y), Some(frame)) = (has_global, p.x, p.y, self.frame) {
                    // Local x is north, y east (Part 1's vehicle frames); the map's x east.
                    let l = Vector2::new(y, x);
                    let (lat, lon) = frame.to_global(l);
                    self.pose(now, source.subsystem, lat, lon, l, p.yaw);
                }
            }
            Message::ReportVelocityState(r) => {
                let speed = r
                    .velocity_x
                    .unwrap_or(0.0)
                    .hypot(r.velocity_y.unwrap_or(0.0));
                if let Some(v) = self.vehicles.get_mut(&source.subsystem) {
                    v.velocity = Some((
                        VelocityView {
                            speed,
                            yaw_rate: r.yaw_rate,
                        },
                        now,
                    ));
                }
            }
            Message::ReportVksObjects(r) if r.request_id == VKS_REQUEST => {
                let Some(frame) = self.frame else {
                    return true;
                };
                if let Some(v) = self.vehicles.get_mut(&source.subsystem) {
                    v.objects = r
                        .objects
                        .iter()
                        .flatten()
                        .map(|o| ObjectView {
                            id: o.object_id,
                            buffer: f64::from(o.buffer),
                            points: o
                                .points
                                .iter()
                                .map(|p| {
                                    let l = frame.to_local(p.latitude, p.longitude);
                                    (l.x, l.y)
                                })
                                .collect(),
                        })
                        .collect();
                }
            }
            Message::ReportMissionStatus(r) => {
                if let Some((_, m)) = self
                    .vehicles
                    .get_mut(&source.subsystem)
                    .and_then(|v| v.mission.as_mut())
                    .filter(|(s, m)| *s == source && m.id == r.mission_id)
                {
                    if r.status_type == MissionStatusType::Mission {
                        let s = format!("{:?}", r.status);
                        if m.status.as_deref() != Some(&s) {
                            m.status = Some(s.clone());
                            let text = format!("{source}: mission {} {s}", r.mission_id);
                            self.notice(false, text);
                        }
                    }
                }
            }
            _ => return false,
        }
        true
    }

    fn pose(
        &mut self,
        now: Instant,
        subsystem: u8,
        latitude: f64,
        longitude: f64,
        l: Vector2<f64>,
        yaw: Option<f64>,
    ) {
        let max = self.config.trail_max;
        let v = self.vehicles.entry(subsystem).or_default();
        v.pose = Some((
            PoseView {
                latitude,
                longitude,
                x: l.x,
                y: l.y,
                yaw,
                age_s: 0.0,
                received_unix_ms: 0.0,
            },
            now,
        ));
        if v.trail.len() >= max {
            v.trail.pop_front();
        }
        v.trail.push_back((l.x, l.y));
        v.pose_count += 1;
        self.poses += 1;
    }

    /// Poses received in all (a user interface redraws when it grew).
    pub fn poses(&self) -> u64 {
        self.poses
    }

    /// What the station knows, at `now`; `trails` includes every subsystem's trail.
    /// `unix_now` (the wall clock at `now`, since the Unix epoch) dates the notices and
    /// poses for the user interface: the station itself reads no clock.
    pub fn view(&self, now: Instant, unix_now: Duration, trails: bool) -> SystemView {
        let age = |t: Instant| now.saturating_duration_since(t).as_secs_f64();
        let unix_ms_of = |t: Instant| unix_now.as_secs_f64() * 1e3 - age(t) * 1e3;
        let role = |ss: u8, id: u8| self.find(ss, id).map(|a| a.to_string());
        let part1_name = |id: u8| {
            crate::components::COMPONENTS
                .iter()
                .find(|c| c.0 == id)
                .map_or_else(|| format!("component {id}"), |c| c.1.to_string())
        };
        let mut subsystems: BTreeMap<u8, SubsystemView> = BTreeMap::new();
        for (a, name) in &self.tree.components {
            let s = subsystems
                .entry(a.subsystem)
                .or_insert_with(|| SubsystemView {
                    id: a.subsystem,
                    name: self.tree.subsystems.get(&a.subsystem).cloned().flatten(),
                    ..SubsystemView::default()
                });
            if s.nodes.last().is_none_or(|n| n.id != a.node) {
                s.nodes.push(NodeView {
                    id: a.node,
                    name: self
                        .tree
                        .nodes
                        .get(&(a.subsystem, a.node))
                        .cloned()
                        .flatten(),
                    components: Vec::new(),
                });
            }
            let k = self.known.get(a);
            let keeping = self.keeper.kept().find(|k| k.0 == *a);
            if let Some(n) = s.nodes.last_mut() {
                n.components.push(ComponentView {
                    address: a.to_string(),
                    name: name.clone().unwrap_or_else(|| part1_name(a.component)),
                    state: k.and_then(|k| k.state).map(|s| format!("{:?}", s.0)),
                    state_age_s: k.and_then(|k| k.state).map(|s| age(s.1)),
                    controller: k.and_then(|k| k.controller).map(|c| c.0.to_string()),
                    controller_authority: k.and_then(|k| k.controller).map(|c| c.1),
                    held: self.keeper.holds(*a),
                    keeping: keeping.map(|k| k.1.unwrap_or(0)),
                });
            }
        }
        for (id, s) in &mut subsystems {
            s.roles = Roles {
                global_pose: role(*id, id::GLOBAL_POSE),
                local_pose: role(*id, id::LOCAL_POSE),
                velocity: role(*id, id::VELOCITY),
                primitive_driver: role(*id, id::PRIMITIVE_DRIVER),
                waypoint_driver: role(*id, id::GLOBAL_WAYPOINT_DRIVER),
                path_segment_driver: role(*id, id::GLOBAL_PATH_SEGMENT_DRIVER),
                spooler: role(*id, id::MISSION_SPOOLER),
                world_model: role(*id, id::WORLD_MODEL),
            };
            let statuses = self
                .known
                .iter()
                .filter(|(a, _)| a.subsystem == *id)
                .filter_map(|(_, k)| k.state.map(|s| s.1));
            let Some(v) = self.vehicles.get(id) else {
                continue;
            };
            let heard = v
                .pose
                .map(|p| p.1)
                .into_iter()
                .chain(v.velocity.map(|p| p.1))
                .chain(statuses)
                .max();
            s.heard_s = heard.map(age);
            let followed = v.pose.map(|p| p.1).or(heard);
            // The station's own subsystem is not watched, so never stale.
            let own = self.me.is_some_and(|m| m.subsystem == *id);
            s.stale =
                !own && followed.is_none_or(|t| age(t) > self.config.stale_after.as_secs_f64());
            s.pose = v.pose.map(|(p, t)| PoseView {
                age_s: age(t),
                received_unix_ms: unix_ms_of(t),
                ..p
            });
            s.velocity = v.velocity.map(|v| v.0);
            s.emergency = v.emergency;
            s.trail = if trails {
                v.trail.iter().copied().collect()
            } else {
                Vec::new()
            };
            s.pose_count = v.pose_count;
            s.objects.clone_from(&v.objects);
            s.mission = v.mission.as_ref().map(|m| m.1.clone());
            s.route.clone_from(&v.route);
        }
        SystemView {
            origin: self.frame.map(|f| (f.latitude, f.longitude)),
            subsystems: subsystems.into_values().collect(),
            notices: self
                .notices
                .iter()
                .map(|(at, n)| Notice {
                    unix_ms: at.map_or(unix_now.as_millis() as u64, |t| unix_ms_of(t) as u64),
                    ..n.clone()
                })
                .collect(),
            notice_count: self.notice_count,
        }
    }
}

/// A mission of blocking moves of `driver`, one task per point, as `spooler` sends it.
fn mission(
    spooler: Address,
    driver: Address,
    mission_id: u16,
    points: &[GeoPoint],
    speed: f64,
) -> Result<SpoolMission, crate::codec::EncodeError> {
    let mut children = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        let uid = 10 * (i as u16 + 1);
        let moves: [(Message, bool); 3] = [
            (Resume {}.into(), false),
            (SetTravelSpeed { speed }.into(), false),
            (
                SetGlobalWaypoint {
                    waypoint_number: 0,
                    latitude: p.latitude,
                    longitude: p.longitude,
                    ..SetGlobalWaypoint::default()
                }
                .into(),
                true,
            ),
        ];
        let messages = moves
            .iter()
            .enumerate()
            .map(|(j, (m, blocking))| command(uid + j as u16, spooler, driver, m, *blocking))
            .collect::<Result<Vec<MissionCommand>, _>>()?;
        children.push(leaf_task(i as u16 + 1, messages));
    }
    Ok(mission_of(mission_id, children))
}
