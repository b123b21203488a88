//! Stock manipulator components (Part 1 §5.4): a serial arm of revolute and prismatic
//! joints, its kinematics from Report Manipulator Specifications, and the ten manipulator
//! components over two small hardware traits ([`hardware`]). `jaus_sim::arm` implements
//! those traits with a simulated arm, so every component runs end to end without hardware.
//!
//! | component | stock implementation | hardware / input |
//! |---|---|---|
//! | Primitive Manipulator (49) | [`StockPrimitiveManipulator`] | [`hardware::JointActuators`], the arm's [`kinematics::Chain`] |
//! | Joint Position / Velocity / Force-Torque Sensor (51–53) | [`StockJointSensor`] | [`hardware::JointSensors`] |
//! | Joint Positions Driver (54) | [`StockJointPositionsDriver`] | positions by service connection |
//! | End-Effector Pose Driver (55) | [`StockEndEffectorPoseDriver`] | positions; inverse kinematics |
//! | Joint Velocities Driver (56) | [`StockJointVelocitiesDriver`] | velocities by service connection |
//! | End-Effector Velocity State Driver (57) | [`StockEndEffectorVelocityStateDriver`] | positions, velocities; Jacobian |
//! | Joint Move Driver (58) | [`StockJointMoveDriver`] | positions, velocities; trapezoidal profiles |
//! | End-Effector Discrete Pose Driver (59) | [`StockEndEffectorDiscretePoseDriver`] | positions, velocities; interpolated poses, inverse kinematics |
//!
//! The drivers ask the Primitive Manipulator for its specifications, so they work with
//! whatever arm it reports, and send it Set Joint Efforts from one joint servo
//! ([`servo`]) as Part 1 draws them. Common safety rules: only the controlling component
//! commands them (the runtime); wrong joint counts, values beyond a joint's limits,
//! unreachable poses, moves too fast for the joints and values that are not finite are
//! refused ([`Refused::Invalid`](crate::component::Refused), a NAK when one was asked
//! for) and nothing moves; every effort goes to zero on emergency, on leaving Ready,
//! when control is lost and when joint feedback goes stale; the Primitive Manipulator
//! zeroes the efforts when they are not refreshed.

pub mod driver;
pub mod hardware;
pub mod joint_drivers;
pub mod kinematics;
pub mod link;
pub mod pose_drivers;
pub mod primitive;
pub mod profile;
pub mod sensors;
pub mod servo;

pub use joint_drivers::{
    StockJointMoveDriver, StockJointPositionsDriver, StockJointVelocitiesDriver,
};
pub use pose_drivers::{
    StockEndEffectorDiscretePoseDriver, StockEndEffectorPoseDriver,
    StockEndEffectorVelocityStateDriver,
};
pub use primitive::{PrimitiveManipulatorConfig, StockPrimitiveManipulator};
pub use sensors::StockJointSensor;
