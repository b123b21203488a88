//! The other direction of the gateway: an AS-4 vehicle presented as RA 3.3 components,
//! so that RA 3.3 clients (our console, `jaus ocu`) see and drive it.
//!
//! [`install`] puts, for each presented Mobility service of the vehicle, an RA 3.3
//! component into an RA 3.3 [`Node`] (at the standard component id of Part 1, so the
//! console gives it its role) and returns the AS-4 side, [`As4Proxy`]: an AS-4 client
//! with its own AS-4 id, an [`As4Endpoint`](jaus::net::as5669a::As4Endpoint) to add to
//! the node's [`As4Mux`](jaus::net::as5669a::As4Mux) (one socket; the mux gives the
//! proxy the messages for its id, and a gateway on the same socket the messages for its
//! own). The proxy finds the vehicle's services with AS-4 Discovery (Query
//! Identification and Query Services, to the configured address: to the configured id,
//! or to every component), keeps its sensors' reports fresh with AS-4 periodic events at
//! the poll period's rate ([`events`]: Create Event once a sensor is found; a sensor
//! whose event is refused, unanswered or gone silent is queried every poll period
//! instead), and carries the RA 3.3 components' commands over. Its sensor and wrench
//! effort queries ask for every field the reports' definitions have and for no other
//! presence bit ([`presence`]).
//!
//! | RA 3.3 component (id) | AS-4 service | what crosses |
//! |---|---|---|
//! | Velocity State Sensor (42) | Velocity State Sensor | Query → Report Velocity State, from the latest AS-4 report (by event, or polled) |
//! | Local Pose Sensor (41) | Local Pose Sensor | Query → Report Local Pose (the AS-4 local frame moved by [`ProxyConfig::frame`]; identity by default) |
//! | Global Pose Sensor (38) | Global Pose Sensor | Query → Report Global Pose (altitude → elevation) |
//! | Primitive Driver (33) | Primitive Driver | Set Wrench Effort → Set Wrench Effort; Query Wrench Effort from the latest AS-4 report |
//! | Global Waypoint Driver (45) | Global Waypoint List Driver | numbered Set Global Waypoint + Set Travel Speed, in Ready → Delete Element (all), Set Element (UIDs 1…n, linked), Execute List at that speed; Query Waypoint Count → the elements not yet passed (Query Active Element); Query Global Waypoint / Travel Speed from what was set; the list done → Standby, as Part 1 asks |
//! | Local Waypoint Driver (46) | Local Waypoint List Driver | the same with Set Local Waypoint |
//! | Global Path Segment Driver (47) | Global Path Segment Driver | the same with numbered Set Global Path Segment (P1, P2, weighting factor) as AS-4 Set Global Path Segment elements; Query Path Segment Count → the elements not yet passed |
//! | Local Path Segment Driver (48) | Local Path Segment Driver | the same with Set Local Path Segment (P1, P2 into the AS-4 frame) |
//!
//! The RA 3.3 components run on the SDK's component runtime
//! ([`jaus::component::Component`]): service connections, events, heartbeats, status
//! and control queries, authority and emergencies work as for any RA 3.3 component
//! (the console follows the pose through a service connection). Each sits in an
//! [`endpoint::ProxyEndpoint`], which adds what crosses to AS-4:
//!
//! * **Control.** An RA 3.3 client's Request Component Control of a proxy driver makes
//!   the proxy request AS-4 control of the vehicle's component (with
//!   [`ProxyConfig::authority`]); the client is confirmed only once AS-4 control is
//!   granted (refused: Confirm Component Control "not available", or "insufficient
//!   authority" when the vehicle said so; no answer in 5 s: "not available"). AS-4
//!   control is kept while any RA 3.3 client controls a driver on that component and
//!   released after. Losing it (Reject Control, or Report Control naming another
//!   client) sends the RA 3.3 controller Reject Component Control.
//! * **State.** RA 3.3 Resume / Standby / Set Emergency / Clear Emergency of a proxy
//!   driver become the AS-4 ones for the vehicle's component. The driver's Report
//!   Component Status follows the AS-4 Report Status the proxy polls: the AS-4
//!   component leaving Ready puts it in Standby, an AS-4 emergency it did not raise puts
//!   it in Emergency until the vehicle leaves Emergency.
//!
//! A presented component whose AS-4 service is not found (yet) answers no query and
//! refuses control ("not available").

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use jaus::component::{Component, Config};
use jaus::components as c;
use jaus::net::as5669a::As4Id;
use jaus::net::{NetError, Node, PeerAddr};
use jaus::Address;

use crate::mobility::ServiceIds;
use crate::ra33::Frame;
use crate::service::ServiceId;

pub mod behaviours;
pub mod endpoint;
pub mod events;
pub mod hub;
pub mod presence;
pub mod segments;
pub mod shared;
pub mod waypoints;

pub use endpoint::ProxyEndpoint;
pub use events::{EventState, SensorEvents};
pub use hub::As4Proxy;
pub use shared::{As4Control, ProxyStats, Shared};

/// A Mobility service of the vehicle presented as an RA 3.3 component.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Role {
    /// Velocity State Sensor (RA 3.3 id 42).
    VelocityStateSensor,
    /// Local Pose Sensor (41).
    LocalPoseSensor,
    /// Global Pose Sensor (38).
    GlobalPoseSensor,
    /// Primitive Driver (33).
    PrimitiveDriver,
    /// Local Waypoint Driver (46) over the Local Waypoint List Driver.
    LocalWaypointDriver,
    /// Global Waypoint Driver (45) over the Global Waypoint List Driver.
    GlobalWaypointDriver,
    /// Global Path Segment Driver (47) over the Global Path Segment Driver.
    GlobalPathSegmentDriver,
    /// Local Path Segment Driver (48) over the Local Path Segment Driver.
    LocalPathSegmentDriver,
}

impl Role {
    /// Every role, in this order.
    pub const ALL: [Role; 8] = [
        Role::VelocityStateSensor,
        Role::LocalPoseSensor,
        Role::GlobalPoseSensor,
        Role::PrimitiveDriver,
        Role::LocalWaypointDriver,
        Role::GlobalWaypointDriver,
        Role::GlobalPathSegmentDriver,
        Role::LocalPathSegmentDriver,
    ];

    /// The RA 3.3 component id (Part 1).
    pub fn component_id(self) -> u8 {
        match self {
            Role::VelocityStateSensor => c::velocity_state_sensor::ID,
            Role::LocalPoseSensor => c::local_pose_sensor::ID,
            Role::GlobalPoseSensor => c::global_pose_sensor::ID,
            Role::PrimitiveDriver => c::primitive_driver::ID,
            Role::LocalWaypointDriver => c::local_waypoint_driver::ID,
            Role::GlobalWaypointDriver => c::global_waypoint_driver::ID,
            Role::GlobalPathSegmentDriver => c::global_path_segment_driver::ID,
            Role::LocalPathSegmentDriver => c::local_path_segment_driver::ID,
        }
    }

    /// The AS-4 service it presents.
    pub fn service(self) -> ServiceId {
        match self {
            Role::VelocityStateSensor => ServiceIds::VELOCITY_STATE_SENSOR,
            Role::LocalPoseSensor => ServiceIds::LOCAL_POSE_SENSOR,
            Role::GlobalPoseSensor => ServiceIds::GLOBAL_POSE_SENSOR,
            Role::PrimitiveDriver => ServiceIds::PRIMITIVE_DRIVER,
            Role::LocalWaypointDriver => ServiceIds::LOCAL_WAYPOINT_LIST_DRIVER,
            Role::GlobalWaypointDriver => ServiceIds::GLOBAL_WAYPOINT_LIST_DRIVER,
            Role::GlobalPathSegmentDriver => ServiceIds::GLOBAL_PATH_SEGMENT_DRIVER,
            Role::LocalPathSegmentDriver => ServiceIds::LOCAL_PATH_SEGMENT_DRIVER,
        }
    }

    /// Whether it is a driver (control and state cross to AS-4).
    pub fn is_driver(self) -> bool {
        matches!(
            self,
            Role::PrimitiveDriver
                | Role::LocalWaypointDriver
                | Role::GlobalWaypointDriver
                | Role::GlobalPathSegmentDriver
                | Role::LocalPathSegmentDriver
        )
    }

    /// The role of an AS-4 service URI (any version), if the proxy presents it.
    pub fn of_uri(uri: &str) -> Option<Role> {
        Role::ALL.into_iter().find(|r| r.service().uri == uri)
    }
}

/// Settings of a proxy.
#[derive(Debug, Clone)]
pub struct ProxyConfig {
    /// The proxy's own AS-4 id (an AS-4 client of the vehicle).
    pub me: As4Id,
    /// The vehicle: a component id (Query Services goes to it), a subsystem with
    /// broadcast node and component (`S.255.255`), or `None` to ask every component at
    /// the vehicle's address (`65535.255.255`).
    pub vehicle: Option<As4Id>,
    /// The presented services (default all eight).
    pub roles: Vec<Role>,
    /// The RA 3.3 instance of the presented components (default 1).
    pub instance: u8,
    /// The authority with which it requests AS-4 control (default 200).
    pub authority: u8,
    /// The sensors' event period (Create Event at `1 / poll_period` Hz) and how often
    /// they are queried when their event is refused or silent; how often the active
    /// element is queried while a list runs (default 100 ms).
    pub poll_period: Duration,
    /// How often the drivers' components are asked for their status and controller,
    /// and Query Services is repeated while services are missing (default 500 ms).
    pub status_period: Duration,
    /// The AS-4 local frame relative to the RA 3.3 one (default identity).
    pub frame: Frame,
}

impl ProxyConfig {
    /// A proxy with AS-4 id `me` for the vehicle `vehicle`, the other settings default.
    pub fn new(me: As4Id, vehicle: Option<As4Id>) -> Self {
        Self {
            me,
            vehicle,
            roles: Role::ALL.to_vec(),
            instance: 1,
            authority: 200,
            poll_period: Duration::from_millis(100),
            status_period: Duration::from_millis(500),
            frame: Frame::default(),
        }
    }
}

/// Adds the RA 3.3 components presenting the vehicle at `peer` (the AS5669A address of
/// its node) to `node`, and returns the AS-4 side to put on the node's socket
/// (`As4Mux::new(node, proxy, …)`, or [`DualNode::with_endpoint`] beside a gateway).
///
/// [`DualNode::with_endpoint`]: crate::gateway::DualNode::with_endpoint
pub fn install<A: PeerAddr>(
    node: &mut Node<A>,
    config: ProxyConfig,
    peer: A,
    now: Instant,
) -> Result<As4Proxy<A>, NetError> {
    let shared = Arc::new(Mutex::new(Shared::new(config.me, config.frame)));
    let at = node.address();
    let name = config
        .vehicle
        .map_or_else(|| "AS-4 vehicle".to_string(), |v| format!("AS-4 {v}"));
    for role in &config.roles {
        let address = Address::new(at.subsystem, at.node, role.component_id(), config.instance);
        let settings = Config {
            identification: Some(format!("{name}: {}", role.service().uri)),
            ..Config::default()
        };
        let s = shared.clone();
        let added = match role {
            Role::VelocityStateSensor => node.add(ProxyEndpoint::new(
                Component::new(
                    address,
                    behaviours::Sensor::<c::velocity_state_sensor::Interface>::new(
                        *role,
                        s.clone(),
                    ),
                    settings,
                    now,
                ),
                *role,
                s,
                now,
            )),
            Role::LocalPoseSensor => node.add(ProxyEndpoint::new(
                Component::new(
                    address,
                    behaviours::Sensor::<c::local_pose_sensor::Interface>::new(*role, s.clone()),
                    settings,
                    now,
                ),
                *role,
                s,
                now,
            )),
            Role::GlobalPoseSensor => node.add(ProxyEndpoint::new(
                Component::new(
                    address,
                    behaviours::Sensor::<c::global_pose_sensor::Interface>::new(*role, s.clone()),
                    settings,
                    now,
                ),
                *role,
                s,
                now,
            )),
            Role::PrimitiveDriver => node.add(ProxyEndpoint::new(
                Component::new(
                    address,
                    behaviours::Primitive::new(s.clone()),
                    settings,
                    now,
                ),
                *role,
                s,
                now,
            )),
            Role::LocalWaypointDriver => node.add(ProxyEndpoint::new(
                Component::new(
                    address,
                    waypoints::WaypointDriver::<waypoints::Local>::new(s.clone()),
                    settings,
                    now,
                ),
                *role,
                s,
                now,
            )),
            Role::GlobalWaypointDriver => node.add(ProxyEndpoint::new(
                Component::new(
                    address,
                    waypoints::WaypointDriver::<waypoints::Global>::new(s.clone()),
                    settings,
                    now,
                ),
                *role,
                s,
                now,
            )),
            Role::GlobalPathSegmentDriver => node.add(ProxyEndpoint::new(
                Component::new(
                    address,
                    segments::PathSegmentDriver::<segments::GlobalSegments>::new(s.clone()),
                    settings,
                    now,
                ),
                *role,
                s,
                now,
            )),
            Role::LocalPathSegmentDriver => node.add(ProxyEndpoint::new(
                Component::new(
                    address,
                    segments::PathSegmentDriver::<segments::LocalSegments>::new(s.clone()),
                    settings,
                    now,
                ),
                *role,
                s,
                now,
            )),
        };
        added?;
    }
    Ok(As4Proxy::new(config, peer, shared, now))
}
