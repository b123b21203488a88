//! # jaus-cli — the `jaus` command-line tool
//!
//! The binary's commands live in this library so that they are testable:
//!
//! * [`commands`]: the offline commands (`messages`, `decode`, `encode`, `tour`);
//! * [`demo_operator`]: the demo's operator over UDP;
//! * [`ocu`]: the operator console in the browser (`jaus ocu`, crate `jaus-ocu`);
//! * [`report`]: the demo's table and SVG plot;
//! * [`arm_report`]: the arm demo's table and SVG plot;
//! * [`as4_drive`]: `jaus as4-drive`, an AS-4 operator driving a waypoint list;
//! * [`keygen`]: a node's key and certificate for authenticated QUIC data links.
//! * [`series`]: time series as stacked SVG panels (the soak test's plot).
//!
//! What a client of a JAUS system does (the session, control, captures, the catalogue)
//! is `jaus-client`'s; a node from its node file is `jaus-node`'s. This crate parses
//! the command line and prints.
//!
//! The SDK (`jaus`) carries none of this: a vendor's build pulls no clap, serde_yaml or
//! tracing-subscriber.

pub mod arm_report;
pub mod as4_drive;
pub mod as4_talk;
pub mod commands;
mod demo;
pub mod keygen;
pub mod ocu;
mod plot;
pub mod report;
pub mod ros2;
pub mod series;

pub use demo::demo_operator;
