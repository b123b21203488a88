//! What a [`Station`](super::Station) knows of the system, as plain data for a user
//! interface: the tree (subsystems, nodes, components with their state, controller and
//! authority), each vehicle's pose, trail, velocity, world-model objects and mission,
//! and the operator's notices. Positions are WGS 84 degrees and, for drawing, metres east
//! (`x`) and north (`y`) of the view's origin (the first position the station received).
//! With the `serde` feature every type serialises (the console sends it as JSON).

#[cfg(feature = "serde")]
use serde::Serialize;

/// A snapshot of the system as the station sees it.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
pub struct SystemView {
    /// The local map's origin (latitude, longitude in degrees), once a position arrived.
    pub origin: Option<(f64, f64)>,
    /// Subsystems by id.
    pub subsystems: Vec<SubsystemView>,
    /// The most recent notices (errors and events), oldest first.
    pub notices: Vec<Notice>,
    /// Total notices so far (a UI shows the new ones: those past the count it saw).
    pub notice_count: u64,
}

/// One subsystem (a vehicle, an operator station, ...).
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
pub struct SubsystemView {
    /// Subsystem id.
    pub id: u8,
    /// Its name (Report Identification), when known.
    pub name: Option<String>,
    /// Its nodes.
    pub nodes: Vec<NodeView>,
    /// The last pose received (Global Pose Sensor, else Local Pose Sensor).
    pub pose: Option<PoseView>,
    /// The last velocity received (Velocity State Sensor).
    pub velocity: Option<VelocityView>,
    /// No pose (or, without a pose sensor, no status) heard for longer than the
    /// station's `stale_after`: the link may be lost; what is shown is old.
    pub stale: bool,
    /// Seconds since anything was heard from it (pose, velocity or status).
    pub heard_s: Option<f64>,
    /// Some component of it reports Emergency.
    pub emergency: bool,
    /// Positions received, oldest first (at most the station's `trail_max`); left empty
    /// when the view was asked for without trails.
    pub trail: Vec<(f64, f64)>,
    /// Positions received so far (grows by one per pose; a UI appends the new ones).
    pub pose_count: u64,
    /// World-model objects (Report VKS Objects).
    pub objects: Vec<ObjectView>,
    /// The mission the station spooled and its last status.
    pub mission: Option<MissionView>,
    /// The waypoints last sent to its driver (metres east, north of the origin).
    pub route: Vec<(f64, f64)>,
    /// Components by role, for the UI's commands.
    pub roles: Roles,
}

/// The components of a subsystem that a console commands or follows (first instance
/// found of each id).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
pub struct Roles {
    /// Global Pose Sensor (38).
    pub global_pose: Option<String>,
    /// Local Pose Sensor (41).
    pub local_pose: Option<String>,
    /// Velocity State Sensor (42).
    pub velocity: Option<String>,
    /// Primitive Driver (33).
    pub primitive_driver: Option<String>,
    /// Global Waypoint Driver (45).
    pub waypoint_driver: Option<String>,
    /// Global Path Segment Driver (47).
    pub path_segment_driver: Option<String>,
    /// Mission Spooler (36).
    pub spooler: Option<String>,
    /// World Model Vector Knowledge Store (61).
    pub world_model: Option<String>,
}

/// A node of a subsystem.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
pub struct NodeView {
    /// Node id.
    pub id: u8,
    /// Its name, when known.
    pub name: Option<String>,
    /// Its components.
    pub components: Vec<ComponentView>,
}

/// A component and what the station knows of it.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
pub struct ComponentView {
    /// Address (`subsystem.node.component.instance`).
    pub address: String,
    /// The component's name (Report Identification), else its Part 1 name by id.
    pub name: String,
    /// Core state (Report Component Status), when known.
    pub state: Option<String>,
    /// Seconds since the state was reported.
    pub state_age_s: Option<f64>,
    /// Its controller (Report Component Control), when one holds it.
    pub controller: Option<String>,
    /// The controller's authority.
    pub controller_authority: Option<u8>,
    /// This station holds control of it.
    pub held: bool,
    /// This station keeps asking for control of it, with this authority.
    pub keeping: Option<u8>,
}

/// A pose.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
pub struct PoseView {
    /// Latitude, degrees (a Local Pose Sensor's pose is placed through the origin).
    pub latitude: f64,
    /// Longitude, degrees.
    pub longitude: f64,
    /// Metres east of the origin.
    pub x: f64,
    /// Metres north of the origin.
    pub y: f64,
    /// Heading, radians (0 north, clockwise positive), when reported.
    pub yaw: Option<f64>,
    /// Seconds since it was received.
    pub age_s: f64,
    /// Milliseconds since the Unix epoch when the station received it (for measuring
    /// how long it takes to be drawn).
    pub received_unix_ms: f64,
}

/// A velocity.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
pub struct VelocityView {
    /// Forward speed, m/s.
    pub speed: f64,
    /// Yaw rate, rad/s, when reported.
    pub yaw_rate: Option<f64>,
}

/// A world-model object.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
pub struct ObjectView {
    /// Its id in the store.
    pub id: u32,
    /// Its vertices (metres east, north of the origin).
    pub points: Vec<(f64, f64)>,
    /// Region buffer, m.
    pub buffer: f64,
}

/// A mission and its status.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
pub struct MissionView {
    /// Mission id.
    pub id: u16,
    /// Last status reported (Spooling, Pending, Paused, Aborted, Finished), when any.
    pub status: Option<String>,
    /// Tasks spooled.
    pub tasks: usize,
}

/// Something the operator should see: a refused command, control refused or lost, a
/// component entering Emergency.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(Serialize))]
pub struct Notice {
    /// Running number (from 1).
    pub seq: u64,
    /// Milliseconds since the Unix epoch.
    pub unix_ms: u64,
    /// An error (else an event).
    pub error: bool,
    /// What happened, naming the component and the message.
    pub text: String,
}
