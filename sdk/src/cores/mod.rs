//! Hand-written control cores for the platform components of Part 1 §5.3, generic over
//! small hardware traits ([`hardware`]). The `jaus-sim` crate implements those traits with a
//! simulated vehicle, so every core runs end to end without hardware.
//!
//! | component | core | hardware |
//! |---|---|---|
//! | Global / Local Pose Sensor, Velocity State Sensor | [`sensors`] | [`hardware::GlobalPoseSource`], [`hardware::LocalPoseSource`], [`hardware::VelocitySource`] |
//! | Primitive Driver | [`drivers::PrimitiveDriverCore`] | [`hardware::Actuators`] |
//! | Reflexive Driver | [`drivers::ReflexiveDriverCore`] | [`drivers::ObstacleSource`] |
//! | Global / Local Vector Driver | [`drivers::VectorDriverCore`] | — (pose by service connection) |
//! | Global / Local Waypoint Driver, Path Segment Driver | [`drivers::Navigator`] | — |
//! | Mission Spooler | [`spooler::MissionSpoolerCore`] | — |
//! | World Model Vector Knowledge Store (feature `world_model`) | [`world_model::WorldModelCore`] over [`world_model::VectorStore`] | — (an in-memory store with an R*-tree) |

pub mod drivers;
pub mod geo;
pub mod hardware;
pub mod motion;
pub mod path;
pub mod sensors;
pub mod spooler;
#[cfg(feature = "world_model")]
pub mod world_model;

/// The `nalgebra` the cores use at their API (poses, quaternions, vectors).
pub use nalgebra;
