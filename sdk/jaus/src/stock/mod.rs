//! Stock components: the SDK's own implementations of the generated component traits for
//! the platform components of Part 1 §5.3, the Mission Spooler and the World Model, generic
//! over small hardware traits ([`hardware`]). The `jaus-sim` crate implements those traits with a
//! simulated vehicle, so every stock component runs end to end without hardware.
//!
//! | component | stock implementation | hardware |
//! |---|---|---|
//! | Global / Local Pose Sensor, Velocity State Sensor | [`sensors`] | [`hardware::GlobalPoseSource`], [`hardware::LocalPoseSource`], [`hardware::VelocitySource`] |
//! | Primitive Driver | [`drivers::StockPrimitiveDriver`] | [`hardware::Actuators`] |
//! | Reflexive Driver | [`drivers::StockReflexiveDriver`] | [`drivers::ObstacleSource`] |
//! | Global / Local Vector Driver | [`drivers::StockVectorDriver`] | — (pose by service connection) |
//! | Global / Local Waypoint Driver, Path Segment Driver | [`drivers::Navigator`] | — |
//! | Mission Spooler | [`spooler::StockMissionSpooler`] | — |
//! | World Model Vector Knowledge Store (feature `world_model`) | [`world_model::StockWorldModel`] over [`world_model::VectorStore`] | — (an in-memory store with an R*-tree) |
//! | Subsystem / System Commander (operator logic) | [`commander::ControlKeeper`] | — |
//! | Communicator (feature `communications`) | [`communicator::StockCommunicator`], hosted as the node's gateway by [`communicator::CommunicatorEndpoint`] | [`communicator::DataLink`] |

pub mod commander;
#[cfg(feature = "communications")]
pub mod communicator;
pub mod drivers;
#[cfg(feature = "environment")]
pub mod environment;
pub mod geo;
pub mod hardware;
pub mod journal;
#[cfg(feature = "manipulator")]
pub mod manipulator;
pub mod motion;
pub mod output;
pub mod path;
pub mod sensors;
pub mod spooler;
#[cfg(feature = "world_model")]
pub mod world_model;

/// The `nalgebra` the stock components use at their API (poses, quaternions, vectors).
pub use nalgebra;
