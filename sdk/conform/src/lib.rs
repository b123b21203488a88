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
//! * [`engine`]: runs the checks on one component and leaves it as found;
//! * [`report`]: the terminal summary, JSON, JUnit XML and an HTML page;
//! * [`capture`]: the datagrams of a run, for a pcap file;
//! * [`catalogue`]: every check as data (`jaus conform --list`);
//! * [`profile`]: named sets of checks (`jaus conform --profile`);
//! * [`as4`]: the judge's side of the AS-4 IOP challenge scenario over AS5669A
//!   (`jaus conform --as4`), reported the same way.
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
pub mod report;
pub mod session;
pub mod udp;

use jaus::Address;
use jaus_spec::Spec;
use serde::Serialize;

pub use check::{Check, Exchange, Level, Outcome, Rule, Verdict};
pub use engine::{ComponentReport, Engine, Options};

/// Everything one run found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunReport {
    /// The tool and its version.
    pub tool: String,
    /// Where the targets were reached (the peers), for the reader.
    pub peer: String,
    /// One report per component tested.
    pub components: Vec<ComponentReport>,
    /// Packets for the tester's voices that were not kept because its inbox was full
    /// (a target flooding the tester); checks waiting for them may have failed.
    pub tester_dropped: u64,
}

impl RunReport {
    /// True when no required check failed.
    pub fn passed(&self) -> bool {
        self.components.iter().all(|c| c.required_failures() == 0)
    }

    /// Checks run in all.
    pub fn checks(&self) -> usize {
        self.components.iter().map(|c| c.outcomes.len()).sum()
    }
}

/// Tests every component of `targets` in turn through `session`.
pub fn run(
    session: &mut dyn session::Session,
    spec: &Spec,
    voices: session::Voices,
    targets: &[Address],
    opts: Options,
) -> RunReport {
    run_selected(session, spec, voices, targets, opts, None)
}

/// [`run`] planning only the checks `selection` selects ([`profile::run`]).
pub(crate) fn run_selected(
    session: &mut dyn session::Session,
    spec: &Spec,
    voices: session::Voices,
    targets: &[Address],
    opts: Options,
    selection: Option<&profile::Selection>,
) -> RunReport {
    let components = targets
        .iter()
        .map(|t| {
            Engine::new(session, spec, voices, *t, opts)
                .with_selection(selection.cloned())
                .run()
        })
        .collect();
    RunReport {
        tool: format!("jaus conform {}", env!("CARGO_PKG_VERSION")),
        peer: String::new(),
        components,
        tester_dropped: session.dropped(),
    }
}

/// The components worth testing among `found`: those of `subsystem`, not node
/// managers (component 1), not the tester's own node.
pub fn targets_in(found: &[Address], subsystem: u8, voices: &session::Voices) -> Vec<Address> {
    let mut v: Vec<Address> = found
        .iter()
        .copied()
        .filter(|a| {
            a.subsystem == subsystem
                && a.component != 1
                && !(a.subsystem == voices.controller.subsystem && a.node == voices.controller.node)
        })
        .collect();
    v.sort_by_key(|a| (a.node, a.component, a.instance));
    v.dedup();
    v
}
