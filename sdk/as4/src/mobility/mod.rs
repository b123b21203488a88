//! The Mobility services (AS6009, `urn:jaus:jss:mobility`) over RA 3.3 components: what
//! a gateway (the `gateway` module) presents of an RA 3.3 subsystem, be it the stock
//! components of this SDK on the same node or OpenJAUS 3.3's vehicle across the network.
//!
//! Each runs its generated machines (`defs/mobility_services.yaml`, [`crate::machined`]) as a
//! [`Service`](crate::service::Service) over the gateway's RA 3.3 side
//! ([`Ra33Side`](crate::ra33::Ra33Side)): its own guards and actions are implemented
//! here, the inherited ones are the Core's. Sensors answer from the latest RA 3.3 report
//! (kept fresh by polling), drivers pass commands on to the RA 3.3 driver the gateway
//! controls while an AS-4 client controls it.
//!
//! | AS-4 service | RA 3.3 component | messages |
//! |---|---|---|
//! | Velocity State Sensor | Velocity State Sensor | Query/Report Velocity State (same fields and units) |
//! | Local Pose Sensor | Local Pose Sensor | Query/Report Local Pose; Set Local Pose places the AS-4 local frame (RA 3.3 cannot set a pose) |
//! | Global Pose Sensor | Global Pose Sensor | Query/Report Global Pose (elevation → altitude) |
//! | Primitive Driver | Primitive Driver | Set/Query/Report Wrench Effort |
//! | Local Waypoint List Driver | Local Waypoint Driver | Execute List → numbered Set Local Waypoint + Set Travel Speed; Query Active Element / Travel Speed / Local Waypoint |
//! | Global Waypoint List Driver | Global Waypoint Driver | the same with Set Global Waypoint |
//! | Local Path Segment Driver | Local Path Segment Driver | Execute List → numbered Set Local Path Segment (P1, P2 into the RA 3.3 frame) + Set Travel Speed, Query Path Segment Count polled; Query Active Element / Travel Speed / Local Path Segment |
//! | Global Path Segment Driver | Global Path Segment Driver | the same with Set Global Path Segment |
//!
//! A subsystem with a Global Pose Sensor and no Local Pose Sensor gets a Local Pose
//! Sensor over the global one, and with a Global Waypoint Driver and no Local Waypoint
//! Driver a Local Waypoint List Driver over the global one, in a local frame placed at
//! its first global position ([`derived`]).

use crate::core::generated_id;
use crate::service::ServiceId;

pub mod derived;
pub mod lists;
pub mod primitive;
pub mod segments;
pub mod sensors;

pub use crate::machined::{Machined, On, OnMachines};
pub use derived::LocalWaypointListDriverOnGlobal;
pub use lists::{GlobalWaypointListDriver, ListDriver, LocalWaypointListDriver};
pub use primitive::PrimitiveDriver;
pub use segments::{GlobalPathSegmentDriver, LocalPathSegmentDriver};
pub use sensors::{GlobalPoseSensor, LocalPoseSensor, VelocityStateSensor};

/// The URIs and versions of the Mobility services, as `defs/mobility_services.yaml` gives
/// them.
#[derive(Debug)]
pub struct ServiceIds;

impl ServiceIds {
    /// `urn:jaus:jss:mobility:PrimitiveDriver`.
    pub const PRIMITIVE_DRIVER: ServiceId = generated_id!(primitive_driver);
    /// `urn:jaus:jss:mobility:VelocityStateSensor`.
    pub const VELOCITY_STATE_SENSOR: ServiceId = generated_id!(velocity_state_sensor);
    /// `urn:jaus:jss:mobility:LocalPoseSensor`.
    pub const LOCAL_POSE_SENSOR: ServiceId = generated_id!(local_pose_sensor);
    /// `urn:jaus:jss:mobility:GlobalPoseSensor`.
    pub const GLOBAL_POSE_SENSOR: ServiceId = generated_id!(global_pose_sensor);
    /// `urn:jaus:jss:mobility:LocalWaypointListDriver`.
    pub const LOCAL_WAYPOINT_LIST_DRIVER: ServiceId = generated_id!(local_waypoint_list_driver);
    /// `urn:jaus:jss:mobility:GlobalWaypointListDriver`.
    pub const GLOBAL_WAYPOINT_LIST_DRIVER: ServiceId = generated_id!(global_waypoint_list_driver);
    /// `urn:jaus:jss:mobility:LocalPathSegmentDriver`.
    pub const LOCAL_PATH_SEGMENT_DRIVER: ServiceId = generated_id!(local_path_segment_driver);
    /// `urn:jaus:jss:mobility:GlobalPathSegmentDriver`.
    pub const GLOBAL_PATH_SEGMENT_DRIVER: ServiceId = generated_id!(global_path_segment_driver);
}

/// An RA 3.3 time stamp as AS-4's (the same fields, [`jaus::clock::TimeOfDay`]).
fn time_stamp(t: &jaus::messages::TimeStamp) -> crate::messages::TimeStamp {
    jaus::clock::TimeOfDay::from(t).into()
}
