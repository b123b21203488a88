//! Stock manipulator components (Part 1 §5.4): a serial arm of revolute and prismatic
//! joints, its kinematics from Report Manipulator Specifications, and the ten manipulator
//! components over two small hardware traits ([`hardware`]). `jaus_sim::arm` implements
//! those traits with a simulated arm, so every component runs end to end without hardware.
//!
//! | component | stock implementation | hardware / input |
//! |---|---|---|
//! | Primitive Manipulator (49) | [`StockPrimitiveManipulator`] | [`hardware::JointActuators`], the arm's [`kinematics::Chain`]; holding: [`hardware::JointSensors`], a [`GravityModel`] |
//! | Joint Position / Velocity / Force-Torque Sensor (51–53) | [`StockJointSensor`] | [`hardware::JointSensors`] |
//! | Joint Positions Driver (54) | [`StockJointPositionsDriver`] | positions by service connection; synchronised jerk-limited profiles |
//! | End-Effector Pose Driver (55) | [`StockEndEffectorPoseDriver`] | positions; inverse kinematics, synchronised jerk-limited profiles |
//! | Joint Velocities Driver (56) | [`StockJointVelocitiesDriver`] | velocities by service connection |
//! | End-Effector Velocity State Driver (57) | [`StockEndEffectorVelocityStateDriver`] | positions, velocities; Jacobian |
//! | Joint Move Driver (58) | [`StockJointMoveDriver`] | positions, velocities; trapezoidal profiles, smoothed (jerk-limited) |
//! | End-Effector Discrete Pose Driver (59) | [`StockEndEffectorDiscretePoseDriver`] | positions, velocities; interpolated poses, inverse kinematics |
//!
//! The drivers ask the Primitive Manipulator for its specifications, so they work with
//! whatever arm it reports, and send it Set Joint Efforts from one joint servo
//! ([`servo`]) as Part 1 draws them. Common safety rules: only the controlling component
//! commands them (the runtime); wrong joint counts, values beyond a joint's limits,
//! unreachable poses, moves too fast for the joints and values that are not finite are
//! refused ([`Refused::Invalid`](crate::component::Refused), a NAK when one was asked
//! for) and nothing moves; every effort goes to zero on emergency and when joint
//! feedback goes stale.
//!
//! Hand-overs leave the arm under effort: a driver that goes to Standby stops commanding
//! and gives the Primitive Manipulator back, whose holding controller ([`hold`], gravity
//! compensated from the arm's [`GravityModel`]) holds the joints until the next driver
//! commands them; the next driver starts its servo from the efforts the Primitive
//! Manipulator reports (Query Joint Efforts), so the effort does not jump. The position
//! drivers move on synchronised, jerk-limited profiles that decelerate into the target
//! within each joint's rate and an acceleration limit ([`profile`]); the velocity drivers
//! change speed within the same limits.

pub mod driver;
pub mod hardware;
pub mod hold;
pub mod joint_drivers;
pub mod kinematics;
pub mod link;
pub mod pose_drivers;
pub mod primitive;
pub mod profile;
pub mod sensors;
pub mod servo;

pub use hold::{GravityModel, HoldConfig, HoldingController};
pub use joint_drivers::{
    StockJointMoveDriver, StockJointPositionsDriver, StockJointVelocitiesDriver,
};
pub use pose_drivers::{
    StockEndEffectorDiscretePoseDriver, StockEndEffectorPoseDriver,
    StockEndEffectorVelocityStateDriver,
};
pub use primitive::{PrimitiveManipulatorConfig, StockPrimitiveManipulator};
pub use sensors::StockJointSensor;
