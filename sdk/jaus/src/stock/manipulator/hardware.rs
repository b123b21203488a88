//! The arm hardware a vendor connects: two small traits. The stock manipulator components
//! are generic over them; `jaus_sim::arm` implements both with a simulated serial arm.

use std::time::Instant;

/// The most joints a manipulator message can carry (the joint count is a `u8`).
pub const MAX_JOINTS: usize = 255;

/// One reading of every joint, first joint (at the base) first. Revolute joints in rad,
/// rad/s and N·m; prismatic joints in m, m/s and N.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct JointState {
    /// Joint positions.
    pub positions: Vec<f64>,
    /// Joint velocities.
    pub velocities: Vec<f64>,
    /// Force or torque acting at each joint of the kinematic model.
    pub efforts: Vec<f64>,
}

impl JointState {
    /// Number of joints in the reading.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// Whether the reading has no joints.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Whether the three lists have the same length and every value is finite.
    pub fn is_valid(&self) -> bool {
        self.velocities.len() == self.positions.len()
            && self.efforts.len() == self.positions.len()
            && self
                .positions
                .iter()
                .chain(&self.velocities)
                .chain(&self.efforts)
                .all(|v| v.is_finite())
    }
}

/// Applies joint efforts to the arm's actuators (the Primitive Manipulator's hardware).
pub trait JointActuators: Send + 'static {
    /// Applies `efforts` from `now` on: one value per joint, first joint first, each in
    /// percent of that joint's maximum effort (−100..=100). All zero means no effort at
    /// all (the emergency and watchdog output).
    fn apply_efforts(&mut self, now: Instant, efforts: &[f64]);
}

/// Reads the arm's joint sensors (the joint position, velocity and force/torque
/// sensors' hardware).
pub trait JointSensors: Send + 'static {
    /// The latest reading into `out` (its lists are resized), or `false` without one.
    fn read_joints(&mut self, now: Instant, out: &mut JointState) -> bool;
}
