//! # jaus-as4 — the SAE AS-4 JAUS service sets' messages
//!
//! The messages of the **Core Service Set v1.1** (SAE AS5710A, `urn:jaus:jss:core`:
//! Events, Access Control, Management, Time, Liveness, Discovery and List Manager; 57
//! messages) and of the **Mobility Service Set v1.0** (SAE AS6009, `urn:jaus:jss:mobility`:
//! Primitive Driver, Global and Local Pose Sensors, Velocity State Sensor and Driver,
//! Acceleration State Sensor, Global and Local Vector, Waypoint, Waypoint List and Path
//! Segment Drivers; 56 messages, of which the 10 List Manager messages are the Core's)
//! and of the **Manipulator Service Set v2.0** (SAE AS6057A, `urn:jaus:jss:manipulator`:
//! joint and end-effector sensors and drivers, list driver, specification, tool offset,
//! motion profile, pan-tilt; 72 messages, of which the 10 List Manager messages are the
//! Core's) and of the **Environment Sensing Service Set** (SAE AS6060,
//! `urn:jaus:jss:environmentSensing`: Range Sensor, Visual Sensor, Digital and Analog
//! Video, Still Image; 35 messages), the **Unmanned Ground Vehicle Service Set** (SAE
//! AS6091, `urn:jaus:jss:ugv`: Skid Steer, Ackermann, Stabilizer, Drive Train and Parking
//! Brake Drivers, Platform Specifications, Power Plant Manager, Illumination, Annunciator,
//! Odometry; 47 messages), the **Mission Spooling Service Set** (SAE AS6062,
//! `urn:jaus:jss:missionSpooler`: Mission Spooler; 17 messages) and the
//! **Human-Machine Interface Service Set** (SAE AS6040, `urn:jaus:jss:HMI`: Drawing, Pointing
//! Device, Keyboard, Digital Control, Analog Control; 19 messages), as typed Rust: 283
//! messages in all.
//!
//! The definitions are this crate's own YAML (`defs/core.yaml`, `defs/mobility.yaml`,
//! `defs/manipulator.yaml`, `defs/environment.yaml`, `defs/ugv.yaml`,
//! `defs/mission_spooling.yaml`, `defs/hmi.yaml`, each a standalone set,
//! `extends: none`), written by hand from the layout facts of the
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
//! The services' behaviour is in the definitions too (`defs/*_services.yaml`: states,
//! triggers, guards and actions), generated into [`messages::services`] and run by the
//! runtime below: the Core on [`core::Core`], the Mobility ([`mobility`]) and Manipulator
//! ([`manipulator`]) services a gateway presents over RA 3.3 components on
//! [`machined`], with the Still Image ([`environment`]) and the UGV Parking Brake Driver
//! and Platform Specifications, the Skid Steer Driver, Annunciator, Power Plant Manager,
//! Odometry and Illumination ([`ugv`]), and the Mission Spooler ([`mission`]: a
//! mission's messages run as Core v1.1 command events on their destinations). The
//! other UGV services (the Ackermann, Stabilizer and Drive Train Drivers), the
//! Manipulator services an RA 3.3 arm cannot carry (motion profile, end-effector pose
//! list, actuator force/torque, primitive and pan-tilt services) and the HMI services
//! are defined and generated (their traits and machines) without an implementation in
//! this crate.
//!
//! ## Running AS-4 services
//!
//! The Core services (Transport, Events, Access Control, Management, Time, Liveness,
//! Discovery, List Manager) run sans-IO in [`core::Core`]; a component
//! ([`component::As4Component`]) puts them together with its other services
//! ([`service::Service`]) behind one id; a node ([`node::As4Node`]) hosts components
//! and is the [`As4Endpoint`](jaus::net::as5669a::As4Endpoint) an
//! [`As4Mux`](jaus::net::as5669a::As4Mux) hands AS5669A messages to, on the socket of
//! an RA 3.3 node. A standalone component with a toy service, exchanging datagrams with
//! a client's [`As4Stack`](jaus::net::as5669a::As4Stack) without a socket:
//!
//! ```
//! use std::net::SocketAddr;
//! use std::time::Instant;
//!
//! use jaus::net::as5669a::{As4Config, As4Endpoint, As4Id, As4Message, As4Stack};
//! use jaus::{CommandCode, JausMessage};
//! use jaus_as4::component::As4Component;
//! use jaus_as4::core::CoreConfig;
//! use jaus_as4::node::As4Node;
//! use jaus_as4::service::{Cx, Handled, Request, Service, ServiceId};
//! use jaus_as4::{embedded, Message, QueryTravelSpeed, ReportTravelSpeed};
//!
//! /// Answers Query Travel Speed with a constant.
//! #[derive(Debug)]
//! struct Cruise;
//!
//! impl Service<()> for Cruise {
//!     fn id(&self) -> ServiceId {
//!         ServiceId::new("urn:example:Cruise", 1, 0)
//!     }
//!     fn receives(&self, code: CommandCode) -> bool {
//!         code == QueryTravelSpeed::CODE
//!     }
//!     fn handle(&mut self, _cx: &mut Cx<'_, ()>, _request: &Request<'_>) -> Handled {
//!         Handled::Reply(ReportTravelSpeed { speed: 2.0 }.into())
//!     }
//! }
//!
//! let vehicle = As4Id::new(7, 1, 1);
//! let mut node: As4Node<(), SocketAddr> = As4Node::new(())
//!     .with_component(As4Component::new(vehicle, CoreConfig::named("rover")).with_service(Cruise));
//!
//! let (judge, judge_at) = (As4Id::new(42, 1, 1), SocketAddr::from(([10, 0, 0, 42], 3794)));
//! let node_at = SocketAddr::from(([10, 0, 0, 7], 3794));
//! let mut client: As4Stack<SocketAddr> = As4Stack::new(As4Config::default());
//! let mut server: As4Stack<SocketAddr> = As4Stack::new(As4Config::default());
//! let now = Instant::now();
//!
//! // The client's query goes out as a datagram...
//! client.send(node_at, &[As4Message::new(QueryTravelSpeed::CODE.0, vehicle, judge, vec![])]);
//! let datagram = client.poll_transmit().unwrap();
//! // ... the node's side reads it and answers (what an As4Mux does on its socket) ...
//! let messages = server.receive(now, judge_at, &datagram.bytes)?;
//! let replies = node.handle(now, judge_at, messages);
//! server.send(judge_at, &replies);
//! // ... and the client reads the report.
//! let answer = client.receive(now, node_at, &server.poll_transmit().unwrap().bytes)?;
//! let mut payload = answer[0].message_id.to_le_bytes().to_vec();
//! payload.extend_from_slice(&answer[0].body);
//! let Message::ReportTravelSpeed(report) = embedded::decode(&payload)? else { panic!() };
//! assert!((report.speed - 2.0).abs() < 0.01); // a scaled 16-bit value
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! On a real socket: `As4Mux::new(ra33_node, as4_node, As4Config::default())` and run it
//! like the RA 3.3 node ([`jaus::net::udp::run_on`]).
//!
//! ## Between the generations
//!
//! [`gateway`] presents RA 3.3 components as one AS-4 component (AS-4 clients drive an
//! RA 3.3 vehicle); [`proxy`] presents an AS-4 vehicle as RA 3.3 components (RA 3.3
//! clients, the console, drive an AS-4 vehicle). Both may share a node's socket: the
//! [`As4Mux`](jaus::net::as5669a::As4Mux) gives each AS-4 endpoint the messages for its
//! ids.

pub mod component;

/// This crate's definitions (`defs/`, file name and text, in name order), built in: a
/// client that loads a vendor's AS-4 definitions at run time (`jaus as4-query --spec`)
/// loads them on these.
pub const DEFS: &[(&str, &str)] = &[
    ("core.yaml", include_str!("../defs/core.yaml")),
    (
        "core_services.yaml",
        include_str!("../defs/core_services.yaml"),
    ),
    ("environment.yaml", include_str!("../defs/environment.yaml")),
    (
        "environment_services.yaml",
        include_str!("../defs/environment_services.yaml"),
    ),
    ("hmi.yaml", include_str!("../defs/hmi.yaml")),
    (
        "hmi_services.yaml",
        include_str!("../defs/hmi_services.yaml"),
    ),
    ("manipulator.yaml", include_str!("../defs/manipulator.yaml")),
    (
        "manipulator_services.yaml",
        include_str!("../defs/manipulator_services.yaml"),
    ),
    (
        "mission_spooling.yaml",
        include_str!("../defs/mission_spooling.yaml"),
    ),
    (
        "mission_spooling_services.yaml",
        include_str!("../defs/mission_spooling_services.yaml"),
    ),
    ("mobility.yaml", include_str!("../defs/mobility.yaml")),
    (
        "mobility_services.yaml",
        include_str!("../defs/mobility_services.yaml"),
    ),
    ("ugv.yaml", include_str!("../defs/ugv.yaml")),
    (
        "ugv_services.yaml",
        include_str!("../defs/ugv_services.yaml"),
    ),
];

pub mod core;
pub mod embedded;
pub mod environment;
pub mod gateway;
pub mod machined;
pub mod manipulator;
pub mod mission;
pub mod mobility;
pub mod node;
pub mod outgoing;
pub mod proxy;
pub mod ra33;
pub mod service;
pub mod ugv;

/// The generated messages and types of both service sets (group `as4`), the
/// [`Message`] enum of all of them and the catalogue [`MESSAGES`].
#[allow(clippy::all)]
pub mod messages {
    include!(concat!(env!("OUT_DIR"), "/messages.rs"));

    /// The generated services of `defs/core_services.yaml` (Transport, Events, Access
    /// Control, Management): per service a trait of its guards and actions, its
    /// `Trigger`s (with [`received`](services::management::Trigger::received), the
    /// dispatch of a received message) and the tables of its merged state machine, run
    /// by `jaus::hsm`. [`crate::core::machine`] implements the traits.
    pub mod services {
        include!(concat!(env!("OUT_DIR"), "/services.rs"));
    }
}

pub use messages::*;

#[cfg(test)]
mod tests {
    #[test]
    fn the_built_in_definitions_are_the_files_of_the_directory() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("defs");
        let mut files: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.ends_with(".yaml"))
            .collect();
        files.sort();
        let built_in: Vec<&str> = super::DEFS.iter().map(|(n, _)| *n).collect();
        assert_eq!(files, built_in, "update jaus_as4::DEFS");
        for (name, text) in super::DEFS {
            assert_eq!(std::fs::read_to_string(dir.join(name)).unwrap(), *text);
        }
    }
}
