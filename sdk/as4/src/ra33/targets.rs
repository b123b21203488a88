//! [`Targets`]: the RA 3.3 components presented as AS-4 services.

use jaus::components as c;
use jaus::Address;

/// Each slot once: its field, what it holds and its standard component id (Part 1). The
/// struct, [`Targets::adopt`], [`Targets::all`] and [`Targets::of_tree`] are written from
/// this list.
macro_rules! targets {
    ($($(#[doc = $doc:expr])* $field:ident: $id:expr),* $(,)?) => {
        /// The RA 3.3 components a gateway presents as AS-4 services (any may be missing:
        /// the service that needs it is then not offered).
        #[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
        pub struct Targets {
            $($(#[doc = $doc])* pub $field: Option<Address>,)*
        }

        impl Targets {
            /// Takes the components of `found` whose slot is still empty; returns those it
            /// took (every other slot `None`): the components to offer services for now.
            pub fn adopt(&mut self, found: &Targets) -> Targets {
                let mut new = Targets::default();
                $(
                    if self.$field.is_none() && found.$field.is_some() {
                        self.$field = found.$field;
                        new.$field = found.$field;
                    }
                )*
                new
            }

            /// Every component presented (sensors and drivers).
            pub fn all(&self) -> impl Iterator<Item = Address> {
                [$(self.$field),*].into_iter().flatten()
            }

            /// The components of subsystem `ss` with the standard component ids of Part 1
            /// (instance 1), on any node: for a gateway in front of a whole subsystem,
            /// before discovery tells it more.
            pub fn of_tree(tree: &jaus::net::SystemTree, ss: u8) -> Targets {
                let all = tree.components();
                let find = |id: u8| {
                    all.iter()
                        .copied()
                        .find(|a| a.subsystem == ss && a.component == id)
                };
                Targets {
                    $($field: find($id),)*
                }
            }
        }
    };
}

targets! {
    /// Velocity State Sensor.
    velocity_state_sensor: c::velocity_state_sensor::ID,
    /// Local Pose Sensor.
    local_pose_sensor: c::local_pose_sensor::ID,
    /// Global Pose Sensor.
    global_pose_sensor: c::global_pose_sensor::ID,
    /// Primitive Driver.
    primitive_driver: c::primitive_driver::ID,
    /// Local Waypoint Driver.
    local_waypoint_driver: c::local_waypoint_driver::ID,
    /// Global Waypoint Driver.
    global_waypoint_driver: c::global_waypoint_driver::ID,
    /// Local Path Segment Driver.
    local_path_segment_driver: c::local_path_segment_driver::ID,
    /// Global Path Segment Driver.
    global_path_segment_driver: c::global_path_segment_driver::ID,
    /// Primitive Manipulator (answers Query Manipulator Specifications).
    primitive_manipulator: c::primitive_manipulator::ID,
    /// Manipulator Joint Position Sensor.
    joint_position_sensor: c::manipulator_joint_position_sensor::ID,
    /// Manipulator Joint Velocity Sensor.
    joint_velocity_sensor: c::manipulator_joint_velocity_sensor::ID,
    /// Manipulator Joint Positions Driver.
    joint_positions_driver: c::manipulator_joint_positions_driver::ID,
    /// Manipulator End-Effector Pose Driver.
    end_effector_pose_driver: c::manipulator_end_effector_pose_driver::ID,
    /// Manipulator Joint Force/Torque Sensor.
    joint_force_torque_sensor: c::manipulator_joint_force_torque_sensor::ID,
    /// Manipulator Joint Velocities Driver.
    joint_velocities_driver: c::manipulator_joint_velocities_driver::ID,
    /// Manipulator End-Effector Velocity State Driver.
    end_effector_velocity_state_driver: c::manipulator_end_effector_velocity_state_driver::ID,
    /// Manipulator Joint Move Driver.
    joint_move_driver: c::manipulator_joint_move_driver::ID,
    /// Visual Sensor.
    visual_sensor: c::visual_sensor::ID,
}

/// What a driver moves: drivers of one group contend for the same hardware (the
/// vehicle's through the Reflexive Driver, the arm's through the Primitive Manipulator),
/// so only one of a group is resumed at a time ([`Ra33Side::activate`](super::Ra33Side::activate)).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Group {
    /// The waypoint and path segment drivers, the Primitive Driver.
    Vehicle,
    /// The manipulator's joint positions, end-effector pose, joint velocities,
    /// end-effector velocity state and joint move drivers.
    Arm,
}

impl Targets {
    /// The drivers the gateway takes RA 3.3 control of as soon as an AS-4 client
    /// controls it: the waypoint and path segment drivers and the manipulator's joint
    /// positions, end-effector pose, joint velocities, end-effector velocity state and
    /// joint move drivers. The Primitive Driver is
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
            self.joint_velocities_driver,
            self.end_effector_velocity_state_driver,
            self.joint_move_driver,
        ]
        .into_iter()
        .flatten()
    }

    /// The group `driver` belongs to (the vehicle's unless it is one of the arm's).
    pub fn group(&self, driver: Address) -> Group {
        if [
            self.joint_positions_driver,
            self.end_effector_pose_driver,
            self.joint_velocities_driver,
            self.end_effector_velocity_state_driver,
            self.joint_move_driver,
        ]
        .contains(&Some(driver))
        {
            Group::Arm
        } else {
            Group::Vehicle
        }
    }
}
