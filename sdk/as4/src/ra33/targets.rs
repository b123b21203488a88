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
    /// Primitive Manipulator (answers Query Manipulator Specifications).
    pub primitive_manipulator: Option<Address>,
    /// Manipulator Joint Position Sensor.
    pub joint_position_sensor: Option<Address>,
    /// Manipulator Joint Velocity Sensor.
    pub joint_velocity_sensor: Option<Address>,
    /// Manipulator Joint Positions Driver.
    pub joint_positions_driver: Option<Address>,
    /// Manipulator End-Effector Pose Driver.
    pub end_effector_pose_driver: Option<Address>,
    /// Visual Sensor.
    pub visual_sensor: Option<Address>,
}

/// What a driver moves: drivers of one group contend for the same hardware (the
/// vehicle's through the Reflexive Driver, the arm's through the Primitive Manipulator),
/// so only one of a group is resumed at a time ([`Ra33Side::activate`](super::Ra33Side::activate)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Group {
    /// The waypoint and path segment drivers, the Primitive Driver.
    Vehicle,
    /// The manipulator's joint positions and end-effector pose drivers.
    Arm,
}

impl Targets {
    /// The drivers the gateway takes RA 3.3 control of as soon as an AS-4 client
    /// controls it: the waypoint and path segment drivers and the manipulator's joint
    /// positions and end-effector pose drivers. The Primitive Driver is
    /// taken only when the AS-4 client commands efforts
    /// ([`Ra33Side::ensure_control`](super::Ra33Side::ensure_control)): the other
    /// drivers reach it through the Reflexive Driver, which must hold it.
    pub fn drivers(&self) -> impl Iterator<Item = Address> {
        [
            self.local_waypoint_driver,
            self.global_waypoint_driver,
            self.local_path_segment_driver,
            self.global_path_segment_driver,
            self.joint_positions_driver,
            self.end_effector_pose_driver,
        ]
        .into_iter()
        .flatten()
    }

    /// Takes the components of `found` whose slot is still empty; returns those it took
    /// (every other slot `None`): the components to offer services for now.
    pub fn adopt(&mut self, found: &Targets) -> Targets {
        let mut new = Targets::default();
        macro_rules! slots {
            ($($f:ident),*) => {$(
                if self.$f.is_none() && found.$f.is_some() {
                    self.$f = found.$f;
                    new.$f = found.$f;
                }
            )*};
        }
        slots!(
            velocity_state_sensor,
            local_pose_sensor,
            global_pose_sensor,
            primitive_driver,
            local_waypoint_driver,
            global_waypoint_driver,
            local_path_segment_driver,
            global_path_segment_driver,
            primitive_manipulator,
            joint_position_sensor,
            joint_velocity_sensor,
            joint_positions_driver,
            end_effector_pose_driver,
            visual_sensor
        );
        new
    }

    /// The group `driver` belongs to (the vehicle's unless it is one of the arm's).
    pub fn group(&self, driver: Address) -> Group {
        if [self.joint_positions_driver, self.end_effector_pose_driver].contains(&Some(driver)) {
            Group::Arm
        } else {
            Group::Vehicle
        }
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
            self.primitive_manipulator,
            self.joint_position_sensor,
            self.joint_velocity_sensor,
            self.joint_positions_driver,
            self.end_effector_pose_driver,
            self.visual_sensor,
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
            primitive_manipulator: find(c::primitive_manipulator::ID),
            joint_position_sensor: find(c::manipulator_joint_position_sensor::ID),
            joint_velocity_sensor: find(c::manipulator_joint_velocity_sensor::ID),
            joint_positions_driver: find(c::manipulator_joint_positions_driver::ID),
            end_effector_pose_driver: find(c::manipulator_end_effector_pose_driver::ID),
            visual_sensor: find(c::visual_sensor::ID),
        }
    }
}
