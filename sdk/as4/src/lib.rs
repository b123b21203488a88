//! # jaus-as4 — the SAE AS-4 JAUS service sets' messages
//!
//! The messages of the **Core Service Set v1.1** (SAE AS5710A, `urn:jaus:jss:core`:
//! Events, Access Control, Management, Time, Liveness, Discovery and List Manager; 57
//! messages) and of the **Mobility Service Set v1.0** (SAE AS6009, `urn:jaus:jss:mobility`:
//! Primitive Driver, Global and Local Pose Sensors, Velocity State Sensor and Driver,
//! Acceleration State Sensor, Global and Local Vector, Waypoint, Waypoint List and Path
//! Segment Drivers; 56 messages, of which the 10 List Manager messages are the Core's),
//! as typed Rust: 103 messages in all.
//!
//! The definitions are this crate's own YAML (`defs/core.yaml`, `defs/mobility.yaml`,
//! each a standalone set, `extends: none`), written by hand from the layout facts of the
//! public JSIDL (message IDs, field order, types, scales, units, enumerated values,
//! presence bits, counts). The build script generates [`messages`] from them with the
//! SDK's generator, so every message has the codec, serde support (feature `serde`, on by
//! default) and catalogue entry that the SDK's RA 3.3 messages have. The test
//! `tests/public_jsidl.rs` compares the wire layout of every message with an import of
//! the public JSIDL (see the crate's README).
//!
//! ## The wire
//!
//! An AS-4 message (AS5669A) is its 16-bit message ID, little-endian, followed by the body
//! these types encode. [`embedded`] writes and reads that form, which is also how
//! messages travel inside others (the query of [`CreateEvent`], the report of [`Event`],
//! the data of a list [`Element`]).
//!
//! ```
//! use jaus::codec::Encode;
//! use jaus_as4::{embedded, Message, ReportVelocityState};
//!
//! let report = ReportVelocityState { yaw_rate: Some(0.0), ..Default::default() };
//! let bytes = embedded::encode(&report.clone().into())?;
//! assert_eq!(&bytes[..2], &[0x04, 0x44]); // message ID 0x4404
//! assert_eq!(embedded::decode(&bytes)?, Message::ReportVelocityState(report));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! ## Scaled values
//!
//! Scaled fields are `f64` in real units and are carried as the integers the YAML names.
//! The conversion is the SDK's (`jaus::codec`), the one RA 3.3 and OpenJAUS use: for a
//! 32-bit integer it divides the range by 2³²−2 and rounds to nearest. The JAUS Tool
//! Set's generated AS-4 code divides by 2³²−1 and truncates, so a 32-bit scaled value
//! may differ from it by a count (a fraction of a micrometre for the local positions);
//! 8- and 16-bit values use the same divisor and differ at most by the rounding.
//!
//! The services' behaviour (access control, events, management, discovery, the drivers)
//! is not in this crate's definitions: there is no `services:` section.

pub mod embedded;

/// The generated messages and types of both service sets (group `as4`), the
/// [`Message`] enum of all of them and the catalogue [`MESSAGES`].
#[allow(clippy::all)]
pub mod messages {
    include!(concat!(env!("OUT_DIR"), "/messages.rs"));
}

pub use messages::*;
