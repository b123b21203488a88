//! `jaus conform --as4 --plan`: checks planned from the AS-4 service definitions of
//! whatever component answers, not a fixed scenario.
//!
//! The judge's client asks the component's Report Services, finds each service it
//! lists (URI and version) in the definitions (every set of `jaus_as4::DEFS`, a
//! vendor's YAML on them, or a JSIDL import: [`Definitions::load`]) and plans from the
//! service's transitions ([`plan::plan`]):
//!
//! * each query a transition answers (triggered by Query X, its action sending Report
//!   Y) → `as4.<service>.query.<Query>`: sent, answered with Y, which decodes by the
//!   definitions with the length they give (required; advisory when the transition has
//!   a guard on the data, e.g. `elementExists`, and inconclusive when nothing answers);
//! * each command that needs control (`is_command`, or a transition guarded by
//!   `isControllingClient`) outside the Core's own protocol services →
//!   `as4.<service>.command.<Command>.outsider`: sent without control, it is refused or
//!   ignored (its read-back query, `readback:` or `Set<X>` → `Query<X>`, shows nothing
//!   of it; with none, Query Status and Query Control are unchanged and nothing
//!   confirms it) (required);
//! * the same command from the controlling client, when a read-back query carries
//!   what it sets → `...controller`: control taken, the command (the value read,
//!   moved a little) read back, the value read first put back, control given back
//!   (advisory; a Driver's commands only with `--allow-motion`);
//! * each query answered unguarded by a service inheriting Events →
//!   `as4.<service>.event.<Query>`: Create Event (periodic) is confirmed and an Event
//!   carries the report (required).
//!
//! Each check cites the service's URI and version and the transition (machine, state,
//! trigger, guard, and its `file:line` in the definitions) as its rule's source.

mod command_event;
mod defs;
mod exec;
pub mod plan;
mod sample;

use std::collections::{HashSet, VecDeque};
use std::sync::{Mutex, OnceLock, PoisonError};
use std::time::Instant;

use jaus::net::as5669a::As4Id;
use jaus_as4::messages::{
    IdentificationType, Message, NodeServicesQuery, QueryIdentification, QueryServices,
};

pub use defs::{Definitions, ServiceModel, TransitionModel};
pub use plan::{PlanOptions, Planned, Step};

use super::session::As4Session;
use super::talk::{Judge, BROADCAST};
use super::As4Options;
use crate::check::{Check, Kind, Level, Verdict};
use crate::engine::{check_component, inconclusive, Evidence, Found, RunReport, Subject, Voice};
use crate::selection::Selection;
use exec::Runner;

/// The rules planned checks cite; each check's `source` names the service and the
/// transition it was planned from.
pub mod rules {
    use crate::check::Rule;

    /// The services listed, planned.
    pub const SERVICES: Rule = Rule {
        id: "as4.planned.services",
        source: "AS5710A Discovery",
        text: "Query Services is answered with Report Services; each service it lists for the component is planned from the definitions of that URI and version.",
    };
    /// A query answered.
    pub const QUERY: Rule = Rule {
        id: "as4.planned.query",
        source: "the service's definitions",
        text: "A query a transition of the service takes is answered with the report its action sends, and that report decodes by the definitions with the length they give.",
    };
    /// A command refused without control.
    pub const OUTSIDER: Rule = Rule {
        id: "as4.planned.outsider",
        source: "the service's definitions; AS5710A Access Control",
        text: "A command that needs control (is_command, or a transition guarded by isControllingClient) from a client not in control is refused or ignored: nothing it sets changes, nothing confirms it.",
    };
    /// A command inside a command event refused without control.
    pub const COMMAND_EVENT: Rule = Rule {
        id: "as4.planned.command_event",
        source: "the service's definitions; AS5710A Events (Create Command Event) and Access Control",
        text: "A command that needs control, sent inside a Create Command Event by a client not in control, is not carried out: the component refuses the command event (Reject Event Request) or confirms it and reports it Unsuccessful (Command Event), and nothing the command sets changes.",
    };
    /// A command carried out for the controller.
    pub const CONTROLLER: Rule = Rule {
        id: "as4.planned.controller",
        source: "the service's definitions",
        text: "The same command from the controlling client is carried out: its read-back query shows the value sent.",
    };
    /// A query subscribed.
    pub const EVENT: Rule = Rule {
        id: "as4.planned.event",
        source: "the service's definitions; AS5710A Events",
        text: "A query answered by a service inheriting Events can be subscribed: Create Event (periodic) is confirmed and Events carry the query's report.",
    };
}

/// `s` with a `'static` lifetime, allocated once per distinct text (the citations of a
/// definition set: bounded by the definitions a process loads).
pub(crate) fn intern(s: &str) -> &'static str {
    static TEXTS: OnceLock<Mutex<HashSet<&'static str>>> = OnceLock::new();
    let mut set = TEXTS
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(PoisonError::into_inner);
    if let Some(t) = set.get(s) {
        return t;
    }
    let t: &'static str = Box::leak(s.to_owned().into_boxed_str());
    set.insert(t);
    t
}

/// The id of the first check, the one that plans the others.
const SERVICES_CHECK: &str = "as4.planned.services";

fn services_check() -> Check {
    Check {
        id: SERVICES_CHECK.into(),
        title:
            "Report Services lists the component's services; each is planned from the definitions"
                .into(),
        rule: rules::SERVICES,
        level: Level::Required,
        kind: Kind::As4,
    }
}

/// What discovery found: the component, its identification, its services.
struct Discovered {
    target: Option<As4Id>,
    identification: Option<String>,
    listed: Vec<(String, u8, u8)>,
}

/// Finds the component (Query Identification, broadcast, unless the options give it)
/// and reads its Report Services.
fn discover(j: &mut Judge<'_>) -> (Discovered, Found) {
    let mut f = Discovered {
        target: j.opts.target,
        identification: None,
        listed: Vec::new(),
    };
    let to = f.target.unwrap_or(BROADCAST);
    let q = QueryIdentification {
        query_type: IdentificationType::Component,
    };
    match j.ask_raw(to, q.into()) {
        Ok((Message::ReportIdentification(r), _, from)) => {
            f.identification = Some(r.identification);
            f.target = Some(from);
        }
        Ok(_) | Err(_) if f.target.is_some() => {}
        Ok((m, _, _)) => {
            return (
                f,
                (
                    Verdict::Fail,
                    format!("Query Identification answered by {}", m.name()),
                ),
            )
        }
        Err(e) => {
            return (
                f,
                (Verdict::Inconclusive, format!("no component found: {e}")),
            )
        }
    }
    let Some(target) = f.target else {
        return (f, (Verdict::Inconclusive, "no component found".into()));
    };
    j.peer = target;
    let q = QueryServices {
        nodes: vec![NodeServicesQuery {
            node_id: target.node,
            component_ids: vec![target.component],
        }],
    };
    let report = match j.ask_raw(target, q.into()) {
        Ok((Message::ReportServices(r), _, _)) => r,
        Ok((m, _, _)) => {
            return (
                f,
                (
                    Verdict::Fail,
                    format!("Query Services answered by {}", m.name()),
                ),
            )
        }
        Err(e) => return (f, (Verdict::Fail, e)),
    };
    for n in report.nodes.iter().filter(|n| n.node_id == target.node) {
        for c in n
            .components
            .iter()
            .filter(|c| c.component_id == target.component)
        {
            for s in &c.services {
                f.listed
                    .push((s.uri.clone(), s.major_version, s.minor_version));
            }
        }
    }
    if f.listed.is_empty() {
        return (
            f,
            (
                Verdict::Fail,
                format!("Report Services lists no service for {target}"),
            ),
        );
    }
    (f, (Verdict::Pass, String::new()))
}

/// The engine's AS-4 voice for checks planned from definitions: first the services
/// the component lists (`as4.planned.services`, which plans the rest), then the
/// planned checks in plan order.
struct PlannedVoice<'a> {
    r: Runner<'a>,
    /// Whether `as4.planned.services` was given to the engine.
    asked: bool,
    /// What discovery found, once run.
    found: Option<Discovered>,
    /// The planned checks not run yet.
    queue: VecDeque<Planned>,
    /// The planned check running.
    current: Option<Planned>,
}

impl PlannedVoice<'_> {
    /// `as4.planned.services`: discovery, then the plan from the services listed.
    fn discover_and_plan(&mut self) -> Found {
        let (found, (verdict, mut detail)) = discover(&mut self.r.j);
        let plan_opts = PlanOptions {
            allow_motion: self.r.j.opts.allow_motion,
            command_events: false,
        };
        let (planned, unknown) = plan::plan(self.r.defs, &found.listed, plan_opts);
        if verdict == Verdict::Pass {
            let listed: Vec<String> = found
                .listed
                .iter()
                .map(|(u, a, b)| format!("{u} v{a}.{b}"))
                .collect();
            detail = format!(
                "{} services listed, {} checks planned: {}",
                listed.len(),
                planned.len(),
                listed.join(", ")
            );
            if !unknown.is_empty() {
                detail.push_str(&format!(
                    "; not in the definitions (not planned; give them with --as4-spec or --jsidl): {}",
                    unknown.join(", ")
                ));
            }
        }
        self.queue = planned.into();
        self.found = Some(found);
        (verdict, detail)
    }

    fn known(&self) -> bool {
        self.found.as_ref().is_some_and(|f| f.target.is_some())
    }
}

impl Voice for PlannedVoice<'_> {
    fn now(&self) -> Instant {
        self.r.j.now()
    }

    fn evidence(&mut self) -> &mut Evidence {
        &mut self.r.j.evidence
    }

    fn next_check(&mut self) -> Option<Check> {
        if !self.asked {
            self.asked = true;
            return Some(services_check());
        }
        self.current = self.queue.pop_front();
        self.current.as_ref().map(|p| p.check.clone())
    }

    fn skip(&mut self, check: &Check) -> Option<String> {
        if check.id == SERVICES_CHECK {
            return None;
        }
        match self.current.as_ref().and_then(|p| p.skip.clone()) {
            Some(why) => Some(why),
            None if !self.known() => Some("no component answered".into()),
            None => None,
        }
    }

    /// The services listed plan every other check: they are read whatever a profile
    /// selects.
    fn needed(&self, check: &Check) -> bool {
        check.id == SERVICES_CHECK
    }

    fn run(&mut self, check: &Check) -> Found {
        if check.id == SERVICES_CHECK {
            return self.discover_and_plan();
        }
        match self.current.take() {
            Some(p) => self.r.run(&p.step),
            None => inconclusive(format!("{} was not planned", check.id)),
        }
    }

    fn subject(&self) -> Subject {
        let peer = self.r.j.peer;
        Subject {
            address: if self.known() {
                peer.to_string()
            } else {
                "(not found)".into()
            },
            component_id: peer.component,
            component_type: Some("AS-4 component (checks planned from its definitions)".into()),
            identification: self.found.as_ref().and_then(|f| f.identification.clone()),
        }
    }

    fn dropped(&self) -> u64 {
        self.r.j.dropped()
    }
}

/// Runs the checks planned from `defs` for the component `opts` names (or whichever
/// answers Query Identification) through `session`, and reports them as that
/// component's checks: `as4.planned.services` first, then the planned ones in plan order.
pub fn run_planned(
    session: &mut dyn As4Session,
    defs: &Definitions,
    opts: &As4Options,
) -> RunReport {
    run_planned_selected(session, defs, opts, None)
}

/// [`run_planned`] running the checks `selection` selects, at its levels (the services
/// listed always run: they plan the rest).
pub fn run_planned_selected(
    session: &mut dyn As4Session,
    defs: &Definitions,
    opts: &As4Options,
    selection: Option<&Selection>,
) -> RunReport {
    let placeholder = opts.target.unwrap_or(BROADCAST);
    let j = Judge::new(session, *opts, placeholder).with_schema(defs.schema());
    let mut voice = PlannedVoice {
        r: Runner::new(j, defs),
        asked: false,
        found: None,
        queue: VecDeque::new(),
        current: None,
    };
    let component = check_component(&mut voice, selection);
    RunReport::new(
        "jaus conform --as4 --plan",
        opts.vehicle.map(|v| v.to_string()).unwrap_or_default(),
        vec![component],
        voice.dropped(),
        selection,
    )
}
