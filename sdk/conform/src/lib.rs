//! `jaus conform`: a conformance tester for JAUS RA 3.3 components on the network.
//!
//! It reads what to test from the same YAML definitions that generate the SDK
//! ([`jaus_spec::Spec`], a vendor's overlays included): every component gets the core
//! checks (identification, services, status, heartbeat, component control, commands
//! from the controller only, emergencies from anyone, a service connection, robustness
//! against malformed packets), and every command its definition lists with a
//! `readback:` query gets a read-back check and a check that a component not in control
//! cannot change it.
//!
//! * [`check`]: checks as data (id, title, the rule cited, required or advisory) and
//!   what they found (a verdict with the messages exchanged as evidence);
//! * [`plan`]: which checks apply to a component type;
//! * [`session`]: the seam to the network; [`memory`] runs a target node in the same
//!   process on a virtual clock, [`udp`] talks to a real one;
//! * [`engine`]: the one engine: runs the checks of one component through a voice,
//!   each with its evidence, a profile's selection applied, and reports them;
//! * [`ra33`]: the RA 3.3 voice, four System Commanders that run the planned checks
//!   and leave the component as found;
//! * [`report`]: the terminal summary, JSON, JUnit XML and an HTML page;
//! * [`capture`]: the datagrams of a run, for a pcap file;
//! * [`catalogue`]: every check as data (`jaus conform --list`);
//! * [`profile`]: named sets of checks (`jaus conform --profile`);
//! * [`as4`]: the AS-4 voices over AS5669A (`jaus conform --as4`): the judge's side
//!   of the IOP challenge scenario, and checks planned from AS-4 service definitions
//!   ([`as4::planned`]), run by the same engine and reported the same way.
//!
//! ```
//! use std::time::Instant;
//! use jaus::net::{Node, NodeConfig};
//! use jaus_conform::{memory::{MemorySession, TESTER}, session::Voices, Options};
//!
//! // A node with no components but its node manager: nothing to check beyond it.
//! let t0 = Instant::now();
//! let target = Node::new(NodeConfig { peers: vec![TESTER], ..NodeConfig::default() }, t0);
//! let voices = Voices::on(200, 1);
//! let mut session = MemorySession::new(target, &voices, t0).unwrap();
//! let spec = jaus_spec::load_sdk().unwrap();
//! let run = jaus_conform::run(&mut session, &spec, voices, &[], Options::default());
//! assert!(run.components.is_empty() && run.passed());
//! ```

pub mod as4;
pub mod capture;
pub mod catalogue;
pub mod check;
pub mod engine;
pub mod memory;
pub mod offline;
pub mod plan;
pub mod profile;
pub mod ra33;
pub mod report;
pub mod selection;
pub mod session;
pub mod udp;

pub use check::{Check, Exchange, Level, Outcome, Rule, Verdict};
pub use engine::{check_component, ComponentReport, Options, RunReport, Voice};
pub use ra33::{run, targets_in, Ra33Voice};
