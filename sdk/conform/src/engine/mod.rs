//! The engine: runs the checks of one component through a [`Session`], keeps the
//! messages of each as its evidence, and leaves the target as it found it (control
//! released, its core state restored).

mod connections;
mod control;
mod core;
mod events;
mod readback;
mod robust;
mod state;
mod talk;
mod watch;

use std::time::Duration;

use jaus::messages::{ComponentState, ReleaseComponentControl};
use jaus::Address;
use jaus_spec::Spec;
use serde::Serialize;

use crate::check::{Check, Exchange, Kind, Level, Outcome, Rule, Verdict};
use crate::selection::Selection;
use crate::session::{Session, Voices};

/// How long the engine waits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Options {
    /// For an answer to a query or a control request.
    pub wait: Duration,
    /// After a command, before reading back what it did (or did not do).
    pub settle: Duration,
}

impl Default for Options {
    /// One second for answers, 200 ms to settle.
    fn default() -> Self {
        Options {
            wait: Duration::from_secs(1),
            settle: Duration::from_millis(200),
        }
    }
}

/// What the checks found on one component.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComponentReport {
    /// Its address.
    pub address: String,
    /// Its component id.
    pub component_id: u8,
    /// Its type, when the definitions know the id.
    pub component_type: Option<String>,
    /// Its identification text, when it answered.
    pub identification: Option<String>,
    /// Every check, in the order run.
    pub outcomes: Vec<Outcome>,
}

impl ComponentReport {
    /// How many checks have `verdict`.
    pub fn count(&self, verdict: Verdict) -> usize {
        self.outcomes
            .iter()
            .filter(|o| o.verdict == verdict)
            .count()
    }

    /// Required checks that failed.
    pub fn required_failures(&self) -> usize {
        self.outcomes
            .iter()
            .filter(|o| o.is_required_failure())
            .count()
    }
}

/// Runs the checks on one component.
pub struct Engine<'a> {
    session: &'a mut dyn Session,
    spec: &'a Spec,
    voices: Voices,
    target: Address,
    opts: Options,
    evidence: Vec<Exchange>,
    started: std::time::Instant,
    /// The component's own authority (0 until Query Component Authority says).
    authority: u8,
    /// Its identification, once answered.
    identification: Option<String>,
    /// The definitions as a codec: messages by name, a vendor overlay's included.
    schema: jaus_dynamic::Schema,
    /// The checks a profile selects (`None`: every check).
    selection: Option<Selection>,
    /// Whether the component has granted the tester's controller control in this run
    /// (from then on, only the tester's voices took control of it).
    granted: bool,
}

impl std::fmt::Debug for Engine<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Engine")
            .field("target", &self.target)
            .field("voices", &self.voices)
            .finish()
    }
}

/// The check recording the tester's clean-up (its rule is the catalogue's).
const TEARDOWN: Rule = crate::plan::rules::TEARDOWN;

impl<'a> Engine<'a> {
    /// An engine testing `target` through `session` with `voices`, its checks read
    /// from `spec`.
    pub fn new(
        session: &'a mut dyn Session,
        spec: &'a Spec,
        voices: Voices,
        target: Address,
        opts: Options,
    ) -> Self {
        let started = session.now();
        Engine {
            session,
            spec,
            voices,
            target,
            opts,
            evidence: Vec::new(),
            started,
            authority: 0,
            identification: None,
            schema: jaus_dynamic::Schema::from_spec(spec),
            selection: None,
            granted: false,
        }
    }

    /// Plans only the checks `selection` selects, at the levels it gives them
    /// (`jaus conform --profile`).
    pub fn with_selection(mut self, selection: Option<Selection>) -> Self {
        self.selection = selection;
        self
    }

    /// Runs every check that applies to the target, then restores it.
    pub fn run(mut self) -> ComponentReport {
        let checks = crate::selection::plan_selected(
            self.spec,
            self.target.component,
            self.selection.as_ref(),
        );
        let initial = self.status();
        self.evidence.clear();
        let mut outcomes = Vec::with_capacity(checks.len() + 1);
        for check in checks {
            outcomes.push(self.run_one(check));
        }
        outcomes.push(self.teardown(initial));
        ComponentReport {
            address: self.target.to_string(),
            component_id: self.target.component,
            component_type: crate::plan::type_name(self.spec, self.target.component)
                .map(str::to_string),
            identification: self.identification.clone(),
            outcomes,
        }
    }

    fn run_one(&mut self, check: Check) -> Outcome {
        self.evidence.clear();
        self.started = self.session.now();
        let (verdict, detail) = match &check.kind {
            Kind::Identification => self.identification(),
            Kind::ServicesListed => self.services(false),
            Kind::ServicesInputs => self.services(true),
            Kind::Status => self.status_check(),
            Kind::Heartbeat => self.heartbeat(),
            Kind::Authority => self.authority_check(),
            Kind::ControlGrant => self.control_grant(),
            Kind::ControlReport => self.control_report(),
            Kind::ControlEqual => self.control_equal(),
            Kind::ControlBelow => self.control_below(),
            Kind::ControlPreempt => self.control_preempt(),
            Kind::ControlRelease => self.control_release(),
            Kind::StateFromController(s) => self.state_from_controller(*s),
            Kind::StateFromOutsider(s) => self.state_from_outsider(*s),
            Kind::EmergencySet => self.emergency_set(),
            Kind::EmergencyClear => self.emergency_clear(),
            Kind::Readback { command, query } => self.readback(command, query),
            Kind::OutsiderCommand { command, query } => self.outsider_command(command, query),
            Kind::Robust(m) => self.robust(*m),
            Kind::ServiceConnection => self.service_connection(),
            Kind::QueryAnswered { query } => self.query_answered(query),
            Kind::EventPeriodic => self.event_periodic(),
            Kind::EventEveryChange => self.event_every_change(),
            Kind::Time => self.time(),
            Kind::As4 => (
                Verdict::Inconclusive,
                "an AS-4 scenario check: run by jaus_conform::as4, not on RA 3.3".to_string(),
            ),
            Kind::Offline => (
                Verdict::Inconclusive,
                "a finding on recorded traffic: judged by jaus_conform::offline, not run"
                    .to_string(),
            ),
        };
        Outcome {
            check,
            verdict,
            detail,
            evidence: std::mem::take(&mut self.evidence),
        }
    }

    /// Releases control from every voice that may hold it, and brings the core state
    /// back to `initial` (Ready or Standby).
    fn teardown(&mut self, initial: Option<ComponentState>) -> Outcome {
        self.evidence.clear();
        self.started = self.session.now();
        for v in [
            self.voices.controller,
            self.voices.senior,
            self.voices.rival,
        ] {
            self.send(v, &ReleaseComponentControl {}.into(), false);
        }
        self.drain(self.opts.settle);
        let mut now = self.status();
        if now == Some(ComponentState::Emergency) {
            self.clear_emergency(self.voices.outsider);
            now = self.status();
        }
        if let (Some(want), Some(is)) = (initial, now) {
            if want != is && matches!(want, ComponentState::Ready | ComponentState::Standby) {
                let c = self.voices.controller;
                if self.acquire(c, self.authority).is_some() {
                    self.set_state(c, want);
                    self.send(c, &ReleaseComponentControl {}.into(), false);
                    self.drain(self.opts.settle);
                }
                now = self.status();
            }
        }
        let controller = self.controller();
        let free = matches!(controller, Some(None));
        let (verdict, detail) = match (initial, now) {
            (Some(a), Some(b)) if a == b && free => (
                Verdict::Pass,
                format!("left in {a:?} with nobody in control"),
            ),
            (Some(a), Some(b)) => (
                Verdict::Fail,
                format!(
                    "found in {a:?}, left in {b:?}; controller: {}",
                    describe_controller(controller)
                ),
            ),
            _ => (
                Verdict::Inconclusive,
                "the component did not report its status".to_string(),
            ),
        };
        Outcome {
            check: Check {
                id: "teardown.as-found".into(),
                title: "The component is left as it was found".into(),
                rule: TEARDOWN,
                level: Level::Advisory,
                kind: Kind::Status,
            },
            verdict,
            detail,
            evidence: std::mem::take(&mut self.evidence),
        }
    }
}

/// `Some(None)`: nobody; `Some(Some(a))`: `a`; `None`: not answered.
fn describe_controller(c: Option<Option<(Address, u8)>>) -> String {
    match c {
        Some(None) => "nobody".into(),
        Some(Some((a, auth))) => format!("{a} at authority {auth}"),
        None => "not reported".into(),
    }
}

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
    session: &mut dyn Session,
    spec: &Spec,
    voices: Voices,
    targets: &[Address],
    opts: Options,
) -> RunReport {
    run_selected(session, spec, voices, targets, opts, None)
}

/// [`run`] planning only the checks `selection` selects ([`crate::profile::run`]).
pub(crate) fn run_selected(
    session: &mut dyn Session,
    spec: &Spec,
    voices: Voices,
    targets: &[Address],
    opts: Options,
    selection: Option<&Selection>,
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
pub fn targets_in(found: &[Address], subsystem: u8, voices: &Voices) -> Vec<Address> {
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
