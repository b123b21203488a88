//! # jaus-cli — the `jaus` command-line tool
//!
//! The binary's commands live in this library so that they are testable:
//!
//! * [`catalogue`]: the messages spoken, the SDK's and a vendor's overlays (`--spec`);
//! * [`commands`]: the offline commands (`messages`, `decode`, `encode`, `tour`);
//! * [`net`]: the network commands (`node`, `discover`, `send`, `query`, the demo's
//!   operator over UDP);
//! * [`ocu`]: the operator console in the browser (`jaus ocu`, crate `jaus-ocu`);
//! * [`report`]: the demo's table and SVG plot;
//! * [`arm_report`]: the arm demo's table and SVG plot;
//! * [`capture`]: pcap/pcapng captures of JAUS traffic, written and read;
//! * [`traffic`]: captures decoded to JSON lines and replayed to a node;
//! * [`as4_drive`]: `jaus as4-drive`, an AS-4 operator driving a waypoint list;
//! * [`keygen`]: a node's key and certificate for authenticated QUIC data links.
//! * [`series`]: time series as stacked SVG panels (the soak test's plot).
//!
//! The SDK (`jaus`) carries none of this: a vendor's build pulls no clap, serde_yaml or
//! tracing-subscriber.

pub mod arm_report;
pub mod as4_drive;
pub mod as4_link;
pub mod as4_talk;
pub mod capture;
pub mod catalogue;
pub mod commands;
pub mod describe;
pub mod keygen;
pub mod net;
pub mod ocu;
mod plot;
pub mod report;
pub mod ros2;
pub mod series;
pub mod traffic;
