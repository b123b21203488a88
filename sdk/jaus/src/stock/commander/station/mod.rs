//! [`Station`]: an operator station's logic (see the module documentation of
//! [`commander`](super)).
//!
//! The station's jobs, one file each: [`command`] (what an operator asks and why it is
//! refused), [`check`] (checking and queueing commands), [`execute`] (turning them into
//! JAUS messages), [`poll`] (what each tick sends: control, service connections, polls,
//! status, world-model and mission queries), [`track`] (the reports it follows) and
//! [`snapshot`] (what it knows, as a [`SystemView`]).

mod check;
mod command;
mod execute;
mod poll;
mod snapshot;
mod track;

use std::collections::{BTreeMap, VecDeque};
use std::time::{Duration, Instant};

use super::keeper::{ControlKeeper, KeeperConfig};
use super::view::{MissionView, Notice, ObjectView, PoseView, VelocityView};
use crate::component::{Context, CoreState, Interface};
use crate::messages::Message;
use crate::stock::geo::LocalFrame;
use crate::Address;

pub use command::{Command, GeoPoint, MissionAction, StationError};

/// Component ids the station gives a role (Part 1 §5), from the generated interfaces.
mod id {
    use crate::component::Interface;
    use crate::components as c;

    pub const NODE_MANAGER: u8 = <c::node_manager::Interface as Interface>::ID;
    pub const PRIMITIVE_DRIVER: u8 = <c::primitive_driver::Interface as Interface>::ID;
    pub const MISSION_SPOOLER: u8 = <c::mission_spooler::Interface as Interface>::ID;
    pub const GLOBAL_POSE: u8 = <c::global_pose_sensor::Interface as Interface>::ID;
    pub const LOCAL_POSE: u8 = <c::local_pose_sensor::Interface as Interface>::ID;
    pub const VELOCITY: u8 = <c::velocity_state_sensor::Interface as Interface>::ID;
    pub const GLOBAL_WAYPOINT_DRIVER: u8 = <c::global_waypoint_driver::Interface as Interface>::ID;
    pub const GLOBAL_PATH_SEGMENT_DRIVER: u8 =
        <c::global_path_segment_driver::Interface as Interface>::ID;
    pub const WORLD_MODEL: u8 = <c::world_model_vector_knowledge_store::Interface as Interface>::ID;
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

#[derive(Debug, Clone, Default)]
struct Known {
    name: Option<String>,
    state: Option<(CoreState, Instant)>,
    controller: Option<(Address, u8)>,
    /// When the station last sent it Resume, until it reports Ready (or is reported
    /// still in Standby after `track::RESUME_GRACE`).
    resumed: Option<Instant>,
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

    /// Poses received in all (a user interface redraws when it grew).
    pub fn poses(&self) -> u64 {
        self.poses
    }
}
