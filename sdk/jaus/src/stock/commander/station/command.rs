//! What an operator asks a [`Station`](super::Station) ([`Command`]) and why the station
//! refuses it ([`StationError`]).

use super::MAX_POINTS;
use crate::Address;

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

/// An operator's command to a [`Station`](super::Station).
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
    pub(super) fn target(&self) -> Option<Address> {
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

/// Why a [`Station`](super::Station) refused a command.
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
