//! # jaus-sim — simulators that stand in for hardware and networks
//!
//! Everything here exists so that the `jaus` SDK runs end to end on a laptop and in
//! tests, with no vehicle and no network:
//!
//! * [`vehicle`]: a simulated skid-steer ground vehicle implementing every hardware
//!   trait of `jaus::stock::hardware` (actuators, global/local pose, velocity), on the
//!   caller's (virtual or real) clock, with seeded sensor noise;
//! * [`arm`]: a simulated serial arm (6-axis by default, or any chain) implementing the
//!   manipulator hardware traits of `jaus::stock::manipulator::hardware`, with joint
//!   dynamics, gravity, limits and seeded sensor noise;
//! * [`arm_demo`]: the arm phase of `jaus demo` (`--arm`), the ten stock manipulator
//!   components and a scripted pick-and-place operator;
//! * [`scanner`]: a scanning range finder on the simulated vehicle, ray-cast against a
//!   scene of obstacles (the Range Sensor's and the Reflexive Driver's hardware);
//! * [`camera`]: a pan/tilt camera on the simulated vehicle drawing the scene from
//!   above (the Visual Sensor's hardware);
//! * [`network`]: [`network::SimNet`], several sans-IO [`jaus::net::Node`]s on a
//!   simulated lossy network (drops, duplicates, delays) with a virtual clock;
//! * [`radio`]: a simulated radio link (loss, latency, bandwidth, up/down), the data
//!   link of two `jaus::stock::communicator` Communicators;
//! * [`world`]: the simulated world the simulators share (the frame's origin, the
//!   obstacles, the arm's control period);
//! * [`demo`]: the scenario of `jaus demo`, a complete simulated subsystem (drivers,
//!   sensors, spooler, world model) and a scripted operator, measured leg by leg.
//!
//! The SDK itself does not depend on this crate; tests, benchmarks, `jaus-node` (which hosts
//! the stock components over these simulators) and the `jaus` CLI do.

pub mod arm;
pub mod arm_demo;
pub mod camera;
pub mod demo;
pub mod lights;
pub mod network;
pub mod radio;
pub mod scanner;
pub mod vehicle;
pub mod world;

pub use arm::{ArmParams, SimArm};
pub use lights::{Lamp, Lights};
pub use network::{LinkModel, SimNet};
pub use vehicle::{SimVehicle, VehicleParams};
pub use world::World;
