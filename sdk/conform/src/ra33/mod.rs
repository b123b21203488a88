//! The RA 3.3 voice of the engine ([`crate::engine`]): four System Commanders on the
//! tester's node ([`Voices`]) run the checks [`crate::plan`] plans for a component
//! type, keep the packets of each as its evidence, and leave the target as they found
//! it (control released, its core state restored: `teardown.as-found`, the last check).

mod connections;
mod control;
mod core;
mod events;
mod readback;
mod robust;
mod state;
mod talk;
mod watch;

use std::collections::VecDeque;
use std::time::Instant;

use jaus::messages::{ComponentState, ReleaseComponentControl};
use jaus::Address;
use jaus_spec::Spec;

use crate::check::{Check, Kind, Level, Rule, Verdict};
use crate::engine::{check_component, Evidence, Found, Options, RunReport, Subject, Voice};
use crate::selection::Selection;
use crate::session::{Session, Voices};

/// The RA 3.3 voice testing one component.
pub struct Ra33Voice<'a> {
    session: &'a mut dyn Session,
    spec: &'a Spec,
    voices: Voices,
    target: Address,
    opts: Options,
    evidence: Evidence,
    /// The checks not run yet.
    queue: VecDeque<Check>,
    /// The core state found before the first check (what the teardown restores).
    initial: Option<ComponentState>,
    /// The component's own authority (0 until Query Component Authority says).
    authority: u8,
    /// Its identification, once answered.
    identification: Option<String>,
    /// The definitions as a codec: messages by name, a vendor overlay's included.
    schema: jaus_dynamic::Schema,
    /// Whether the component has granted the tester's controller control in this run
    /// (from then on, only the tester's voices took control of it).
    granted: bool,
}

impl std::fmt::Debug for Ra33Voice<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Ra33Voice")
            .field("target", &self.target)
            .field("voices", &self.voices)
            .finish()
    }
}

/// The check recording the tester's clean-up (its rule is the catalogue's).
const TEARDOWN: Rule = crate::plan::rules::TEARDOWN;

/// The tester's clean-up, the last check on every RA 3.3 component (the catalogue
/// lists it from here).
pub fn teardown_check() -> Check {
    Check {
        id: "teardown.as-found".into(),
        title: "The component is left as it was found".into(),
        rule: TEARDOWN,
        level: Level::Advisory,
        kind: Kind::Teardown,
    }
}

impl<'a> Ra33Voice<'a> {
    /// The voice testing `target` through `session` with `voices`, its checks read
    /// from `spec`.
    pub fn new(
        session: &'a mut dyn Session,
        spec: &'a Spec,
        voices: Voices,
        target: Address,
        opts: Options,
    ) -> Self {
        let now = session.now();
        Ra33Voice {
            session,
            spec,
            voices,
            target,
            opts,
            evidence: Evidence::new(now),
            queue: VecDeque::new(),
            initial: None,
            authority: 0,
            identification: None,
            schema: jaus_dynamic::Schema::from_spec(spec),
            granted: false,
        }
    }

    fn dispatch(&mut self, check: &Check) -> Found {
        match &check.kind {
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
            Kind::Teardown => self.teardown(),
            Kind::As4 => (
                Verdict::Inconclusive,
                "an AS-4 check: run by the AS-4 voice, not the RA 3.3 one".to_string(),
            ),
            Kind::Offline => (
                Verdict::Inconclusive,
                "a finding on recorded traffic: judged by jaus_conform::offline, not run"
                    .to_string(),
            ),
        }
    }

    /// Releases control from every voice that may hold it, and brings the core state
    /// back to `initial` (Ready or Standby).
    fn teardown(&mut self) -> Found {
        let initial = self.initial;
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
        match (initial, now) {
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
        }
    }
}

impl Voice for Ra33Voice<'_> {
    fn now(&self) -> Instant {
        self.session.now()
    }

    fn evidence(&mut self) -> &mut Evidence {
        &mut self.evidence
    }

    /// Reads the core state the teardown restores, and plans the component type's
    /// checks with the teardown last.
    fn start(&mut self) {
        self.initial = self.status();
        self.evidence.take();
        self.queue = crate::plan::plan(self.spec, self.target.component).into();
        self.queue.push_back(teardown_check());
    }

    fn next_check(&mut self) -> Option<Check> {
        self.queue.pop_front()
    }

    /// The teardown runs whatever a profile selects.
    fn needed(&self, check: &Check) -> bool {
        check.kind == Kind::Teardown
    }

    fn run(&mut self, check: &Check) -> Found {
        self.dispatch(check)
    }

    fn subject(&self) -> Subject {
        Subject {
            address: self.target.to_string(),
            component_id: self.target.component,
            component_type: crate::plan::type_name(self.spec, self.target.component)
                .map(str::to_string),
            identification: self.identification.clone(),
        }
    }

    fn dropped(&self) -> u64 {
        self.session.dropped()
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
            check_component(
                &mut Ra33Voice::new(session, spec, voices, *t, opts),
                selection,
            )
        })
        .collect();
    RunReport::new(
        "jaus conform",
        String::new(),
        components,
        session.dropped(),
        selection,
    )
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
