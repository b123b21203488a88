//! [`Targets`]: the RA 3.3 components presented as AS-4 services.

use jaus::Address;

/// The RA 3.3 components a gateway presents as AS-4 services (any may be missing: the
/// service that needs it is then not offered).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Targets {
    /// Velocity State Sensor.
    pub velocity_state_sensor: Option<Address>,
    /// Local Pose Sensor.
    pub local_pose_sensor: Option<Address>,
    /// Global Pose Sensor.
    pub global_pose_sensor: Option<Address>,
    /// Primitive Driver.
    pub primitive_driver: Option<Address>,
    /// Local Waypoint Driver.
    pub local_waypoint_driver: Option<Address>,
    /// Global Waypoint Driver.
    pub global_waypoint_driver: Option<Address>,
    /// Local Path Segment Driver.
    pub local_path_segment_driver: Option<Address>,
    /// Global Path Segment Driver.
    pub global_path_segment_driver: Option<Address>,
}

impl Targets {
    /// The drivers the gateway takes RA 3.3 control of as soon as an AS-4 client
    /// controls it: the waypoint and path segment drivers. The Primitive Driver is
    /// taken only when the AS-4 client commands efforts
    /// ([`Ra33Side::ensure_control`](super::Ra33Side::ensure_control)): the other
    /// drivers reach it through the Reflexive Driver, which must hold it.
    pub fn drivers(&self) -> impl Iterator<Item = Address> {
        [
            self.local_waypoint_driver,
            self.global_waypoint_driver,
            self.local_path_segment_driver,
            self.global_path_segment_driver,
        ]
        .into_iter()
        .flatten()
    }

    /// Every component presented (sensors and drivers).
    pub fn all(&self) -> impl Iterator<Item = Address> {
        [
            self.velocity_state_sensor,
            self.local_pose_sensor,
            self.global_pose_sensor,
            self.primitive_driver,
            self.local_waypoint_driver,
            self.global_waypoint_driver,
            self.local_path_segment_driver,
            self.global_path_segment_driver,
        ]
        .into_iter()
        .flatten()
    }

    /// The components of subsystem `ss` with the standard component ids of Part 1
    /// (instance 1), on any node: for a gateway in front of a whole subsystem, before
    /// discovery tells it more.
    pub fn of_tree(tree: &jaus::net::SystemTree, ss: u8) -> Targets {
        use jaus::components as c;
        let all = tree.components();
        let find = |id: u8| {
            all.iter()
                .copied()
                .find(|a| a.subsystem == ss && a.component == id)
        };
        Targets {
            velocity_state_sensor: find(c::velocity_state_sensor::ID),
            local_pose_sensor: find(c::local_pose_sensor::ID),
            global_pose_sensor: find(c::global_pose_sensor::ID),
            primitive_driver: find(c::primitive_driver::ID),
            local_waypoint_driver: find(c::local_waypoint_driver::ID),
            global_waypoint_driver: find(c::global_waypoint_driver::ID),
            local_path_segment_driver: find(c::local_path_segment_driver::ID),
            global_path_segment_driver: find(c::global_path_segment_driver::ID),
        }
    }
}
