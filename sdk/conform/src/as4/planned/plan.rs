//! From definitions and a component's Report Services to a list of checks: per service
//! the component lists and the definitions have, its queries (answered with the report
//! the definitions give), its commands that need control (refused from a client
//! without it; carried out by the controller where that is safe and can be read back),
//! and the subscriptions its queries allow (Create Event, when the service inherits
//! Events).

use super::defs::{Definitions, ServiceModel, TransitionModel};
use super::rules;
use crate::check::{Check, Kind, Level, Rule};

/// URIs of the Core services whose commands the planner leaves alone: they are the
/// protocol itself (control, life cycle, events, discovery), which the IOP scenario and
/// the RA 3.3 checks exercise step by step; sending them blindly could take the
/// component away from its owner (Shutdown) or lose its subscriptions.
const PROTOCOL: &[&str] = &[
    "urn:jaus:jss:core:Transport",
    "urn:jaus:jss:core:Events",
    "urn:jaus:jss:core:AccessControl",
    "urn:jaus:jss:core:Management",
    "urn:jaus:jss:core:Discovery",
    "urn:jaus:jss:core:Liveness",
];

/// Whether message `name` is one a [`PROTOCOL`] service takes: left alone wherever it
/// appears, as in a service that redefines how it is taken (the Mission Spooler takes
/// Request Control its own way, pausing its mission first): sent blindly from an
/// outsider, Request Control is granted, as it must be.
fn is_protocol_message(defs: &Definitions, name: &str) -> bool {
    defs.services()
        .iter()
        .filter(|p| PROTOCOL.contains(&p.uri.as_str()))
        .any(|p| p.transitions.iter().any(|t| t.message == name))
}

/// The Events service: a service inheriting it lets clients subscribe to its queries.
pub(super) const EVENTS: &str = "urn:jaus:jss:core:Events";

/// What a planned check does.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Step {
    /// Send the query; the report named answers, and decodes by the definitions.
    Query {
        /// The query.
        query: String,
        /// The report the definitions answer it with.
        report: String,
        /// The transition may not be taken (a guard on the data): no answer is
        /// inconclusive rather than a failure.
        guarded: bool,
    },
    /// Send the command without control: refused or ignored.
    Outsider {
        /// The command.
        command: String,
        /// The query reading back what it sets, if the definitions give one.
        readback: Option<String>,
    },
    /// Take control, send the command, read it back, put the value back, give control
    /// back.
    Controller {
        /// The command.
        command: String,
        /// The query reading it back.
        readback: String,
        /// The component must be Ready (its transition lies under Ready).
        needs_ready: bool,
    },
    /// Send the command inside a Create Command Event without control: refused (Reject
    /// Event Request), or confirmed and reported Unsuccessful; the read-back unchanged.
    CommandEvent {
        /// The command.
        command: String,
        /// The query reading back what it sets.
        readback: String,
    },
    /// Create Event (periodic) on the query: confirmed, and an Event carries the report.
    Event {
        /// The query subscribed.
        query: String,
        /// Its report.
        report: String,
    },
}

/// One planned check: the check as reported, and what it does.
#[derive(Debug, Clone)]
pub struct Planned {
    /// The check (id, title, rule cited with the service and the transition, level).
    pub check: Check,
    /// What it does.
    pub step: Step,
    /// Why it is not run, when the planner decided so (a motion command without
    /// `--allow-motion`): reported as inconclusive with this reason.
    pub skip: Option<String>,
}

/// What the plan is told besides the definitions.
#[derive(Debug, Clone, Copy, Default)]
pub struct PlanOptions {
    /// Commands that move the vehicle (a Driver service's) are carried out too.
    pub allow_motion: bool,
    /// The component offers Core v1.1 command events (it lists Events 1.1 or later and
    /// the definitions hold Create Command Event): each command checked from a client
    /// without control is also sent inside a Create Command Event. [`plan`] sets it
    /// from the services listed.
    pub command_events: bool,
}

/// A lower-case, `_`-separated form of a PascalCase name (`LocalPoseSensor` →
/// `local_pose_sensor`), for check ids.
pub fn snake(name: &str) -> String {
    let mut out = String::new();
    for (i, c) in name.chars().enumerate() {
        if c.is_ascii_uppercase() && i > 0 {
            out.push('_');
        }
        out.push(c.to_ascii_lowercase());
    }
    out
}

/// The report answering `query` per transition `t`: the message a `send` action names,
/// else the report an action named `send<Report>` sends, else the definitions'
/// complement (`report:` or the query's code + 0x2000).
pub fn report_of(defs: &Definitions, t: &TransitionModel) -> Option<String> {
    if let Some(s) = t.sends.first() {
        return Some(s.clone());
    }
    for a in &t.actions {
        if let Some(rest) = a.strip_prefix("send") {
            if rest.starts_with("Report") && defs.schema().message(rest).is_some() {
                return Some(rest.to_string());
            }
        }
    }
    complement(defs, &t.message)
}

/// The report the definitions pair with `query` (`report:`, or its code + 0x2000: the
/// rule of jaus-spec), else `Report<X>` for a `Query<X>` when the definitions have it.
fn complement(defs: &Definitions, query: &str) -> Option<String> {
    let layout = defs.schema().message(query)?;
    if let Some(l) = layout.report.and_then(|r| defs.schema().by_code(r)) {
        return Some(l.name.to_string());
    }
    let r = format!("Report{}", query.strip_prefix("Query")?);
    defs.schema().message(&r).map(|_| r)
}

/// The query reading back what `command` sets: its `readback:`, else `Query<X>` for a
/// `Set<X>` when the definitions have it.
pub fn readback_of(defs: &Definitions, command: &str) -> Option<String> {
    if let Some(r) = defs.message(command).and_then(|m| m.def.readback.clone()) {
        return Some(r);
    }
    let rest = command.strip_prefix("Set")?;
    let q = format!("Query{rest}");
    defs.schema().message(&q).map(|_| q)
}

/// The report answering query `query`: the one a transition taking it sends, else the
/// definitions' complement (`report:`, or its code + 0x2000), else `Report<X>` for a
/// `Query<X>`.
pub fn report_name(defs: &Definitions, query: &str) -> Option<String> {
    let by_transition = defs
        .services()
        .iter()
        .flat_map(|s| &s.transitions)
        .filter(|t| t.message == query)
        .find_map(|t| report_of(defs, t));
    by_transition.or_else(|| complement(defs, query))
}

/// Whether the command moves the vehicle: a command of a Driver service (the
/// Mobility drivers), or Execute List.
fn moves(service: &ServiceModel, command: &str) -> bool {
    service.name.contains("Driver") || service.uri.contains("Driver") || command == "ExecuteList"
}

fn citation(s: &ServiceModel, t: &TransitionModel) -> String {
    format!(
        "{} v{} ({}), {} {} on {}{}, {}",
        s.uri,
        s.version,
        s.at,
        t.machine,
        t.state,
        t.message,
        t.guard
            .as_deref()
            .map(|g| format!(" [{g}]"))
            .unwrap_or_default(),
        t.at
    )
}

fn check(id: String, title: String, base: Rule, source: String, level: Level) -> Check {
    Check {
        id,
        title,
        rule: Rule {
            source: super::intern(&source),
            ..base
        },
        level,
        kind: Kind::As4,
    }
}

/// The checks of service `s` (its definitions), in order: queries, commands without
/// control, commands from the controller, subscriptions.
pub fn plan_service(defs: &Definitions, s: &ServiceModel, opts: PlanOptions) -> Vec<Planned> {
    let svc = snake(&s.name);
    let mut queries = Vec::new();
    let mut outsiders = Vec::new();
    let mut controllers = Vec::new();
    let mut events = Vec::new();
    let mut command_events = Vec::new();
    let seen = |list: &Vec<Planned>, id: &str| list.iter().any(|p| p.check.id == id);
    let evented = defs.inherits(&s.uri, EVENTS) && s.uri != EVENTS;
    for t in &s.transitions {
        let name = t.message.as_str();
        let is_query = defs.schema().message(name).is_some_and(|l| {
            l.class == jaus_spec::MessageClass::Query || name.starts_with("Query")
        });
        if is_query {
            let Some(report) = report_of(defs, t) else {
                continue;
            };
            let id = format!("as4.{svc}.query.{name}");
            if seen(&queries, &id) {
                continue;
            }
            let guarded = t.has_data_guard();
            queries.push(Planned {
                check: check(
                    id,
                    format!("{name} is answered with {report}, which decodes"),
                    rules::QUERY,
                    citation(s, t),
                    if guarded {
                        Level::Advisory
                    } else {
                        Level::Required
                    },
                ),
                step: Step::Query {
                    query: name.to_string(),
                    report: report.clone(),
                    guarded,
                },
                skip: None,
            });
            if evented && !guarded {
                events.push(Planned {
                    check: check(
                        format!("as4.{svc}.event.{name}"),
                        format!("Create Event on {name} is confirmed and Events carry {report}"),
                        rules::EVENT,
                        citation(s, t),
                        Level::Required,
                    ),
                    step: Step::Event {
                        query: name.to_string(),
                        report,
                    },
                    skip: None,
                });
            }
            continue;
        }
        if PROTOCOL.contains(&s.uri.as_str())
            || is_protocol_message(defs, name)
            || !(defs.needs_control(name) || t.needs_controller())
        {
            continue;
        }
        let id = format!("as4.{svc}.command.{name}.outsider");
        if seen(&outsiders, &id) {
            continue;
        }
        // A read-back only counts when its report carries a field the command sets.
        let readback = readback_of(defs, name).filter(|q| {
            report_name(defs, q).is_some_and(|r| {
                !super::sample::shared(defs, name, &r).is_empty()
                    && !super::sample::conflicts(defs, name, &r)
            })
        });
        outsiders.push(Planned {
            check: check(
                id,
                format!(
                    "{name} from a client without control is refused or ignored ({})",
                    readback
                        .as_deref()
                        .map_or("Query Status and Query Control unchanged".into(), |r| {
                            format!("{r} unchanged")
                        })
                ),
                rules::OUTSIDER,
                citation(s, t),
                Level::Required,
            ),
            step: Step::Outsider {
                command: name.to_string(),
                readback: readback.clone(),
            },
            // A target that wrongly obeys would move: a Driver's commands go out only
            // when motion is allowed.
            skip: (moves(s, name) && !opts.allow_motion).then(|| {
                format!(
                    "{name} would move a vehicle that obeys it: run with --allow-motion to send it"
                )
            }),
        });
        let Some(readback) = readback else {
            continue;
        };
        if opts.command_events {
            command_events.push(Planned {
                check: check(
                    format!("as4.{svc}.command.{name}.command_event"),
                    format!(
                        "{name} inside a Create Command Event from a client without control is not carried out ({readback} unchanged)"
                    ),
                    rules::COMMAND_EVENT,
                    citation(s, t),
                    Level::Required,
                ),
                step: Step::CommandEvent {
                    command: name.to_string(),
                    readback: readback.clone(),
                },
                skip: (moves(s, name) && !opts.allow_motion).then(|| {
                    format!(
                        "{name} would move a vehicle that obeys it: run with --allow-motion to send it"
                    )
                }),
            });
        }
        let skip = (moves(s, name) && !opts.allow_motion)
            .then(|| format!("{name} moves the vehicle: run with --allow-motion to send it"));
        controllers.push(Planned {
            check: check(
                format!("as4.{svc}.command.{name}.controller"),
                format!("{name} from the controlling client is read back by {readback}"),
                rules::CONTROLLER,
                citation(s, t),
                Level::Advisory,
            ),
            step: Step::Controller {
                command: name.to_string(),
                readback,
                needs_ready: t.needs_ready(),
            },
            skip,
        });
    }
    queries
        .into_iter()
        .chain(outsiders)
        .chain(controllers)
        .chain(events)
        .chain(command_events)
        .collect()
}

/// The checks for the services `listed` (URI, major, minor version) the component
/// says it has, planned from `defs`; the listed services the definitions lack.
pub fn plan(
    defs: &Definitions,
    listed: &[(String, u8, u8)],
    opts: PlanOptions,
) -> (Vec<Planned>, Vec<String>) {
    let mut out = Vec::new();
    let mut unknown = Vec::new();
    let mut done: Vec<&str> = Vec::new();
    let command_events = defs.schema().message("CreateCommandEvent").is_some()
        && listed
            .iter()
            .any(|(uri, major, minor)| uri == EVENTS && (*major, *minor) >= (1, 1));
    let opts = PlanOptions {
        command_events,
        ..opts
    };
    for (uri, major, minor) in listed {
        match defs.service(uri, *major, *minor) {
            Some(s) if !done.contains(&s.uri.as_str()) => {
                done.push(&s.uri);
                out.extend(plan_service(defs, s, opts));
            }
            Some(_) => {}
            None => unknown.push(format!("{uri} v{major}.{minor}")),
        }
    }
    (out, unknown)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ids(plan: &[Planned]) -> Vec<&str> {
        plan.iter().map(|p| p.check.id.as_str()).collect()
    }

    #[test]
    fn a_sensor_service_is_planned_from_its_transitions() {
        let defs = Definitions::as4().expect("jaus-as4's definitions");
        let s = defs
            .service("urn:jaus:jss:mobility:LocalPoseSensor", 1, 0)
            .expect("Local Pose Sensor");
        let plan = plan_service(&defs, s, PlanOptions::default());
        assert_eq!(
            ids(&plan),
            [
                "as4.local_pose_sensor.query.QueryLocalPose",
                "as4.local_pose_sensor.command.SetLocalPose.outsider",
                "as4.local_pose_sensor.command.SetLocalPose.controller",
                "as4.local_pose_sensor.event.QueryLocalPose",
            ]
        );
        assert!(matches!(
            &plan[0].step,
            Step::Query { report, guarded: false, .. } if report == "ReportLocalPose"
        ));
        assert_eq!(plan[0].check.level, Level::Required);
        assert_eq!(plan[2].check.level, Level::Advisory);
        assert!(matches!(
            &plan[2].step,
            Step::Controller { readback, needs_ready: false, .. } if readback == "QueryLocalPose"
        ));
        assert!(plan[0]
            .check
            .rule
            .source
            .contains("mobility_services.yaml:"));
    }

    #[test]
    fn guarded_queries_are_advisory_and_protocol_commands_are_left_alone() {
        let defs = Definitions::as4().expect("jaus-as4's definitions");
        let lm = defs
            .service("urn:jaus:jss:core:ListManager", 1, 1)
            .expect("List Manager");
        let plan = plan_service(&defs, lm, PlanOptions::default());
        let element = plan
            .iter()
            .find(|p| p.check.id == "as4.list_manager.query.QueryElement")
            .expect("Query Element");
        assert_eq!(element.check.level, Level::Advisory);
        assert!(!ids(&plan).contains(&"as4.list_manager.event.QueryElement"));
        let mgmt = defs
            .service("urn:jaus:jss:core:Management", 1, 1)
            .expect("Management");
        let plan = plan_service(&defs, mgmt, PlanOptions::default());
        assert_eq!(
            ids(&plan),
            [
                "as4.management.query.QueryStatus",
                "as4.management.event.QueryStatus"
            ]
        );
    }

    #[test]
    fn command_events_are_planned_for_a_component_listing_events_1_1() {
        let defs = Definitions::as4().expect("jaus-as4's definitions");
        let listed = |events_minor: u8| {
            vec![
                ("urn:jaus:jss:core:Events".to_string(), 1, events_minor),
                ("urn:jaus:jss:mobility:LocalPoseSensor".to_string(), 1, 0),
            ]
        };
        let (v11, _) = plan(&defs, &listed(1), PlanOptions::default());
        let id = "as4.local_pose_sensor.command.SetLocalPose.command_event";
        let p = v11.iter().find(|p| p.check.id == id).expect("planned");
        assert_eq!(p.check.level, Level::Required);
        assert!(matches!(
            &p.step,
            Step::CommandEvent { command, readback } if command == "SetLocalPose" && readback == "QueryLocalPose"
        ));
        // Events 1.0 has no command events.
        let (v10, _) = plan(&defs, &listed(0), PlanOptions::default());
        assert!(!ids(&v10).contains(&id));
    }

    #[test]
    fn names_and_guards() {
        assert_eq!(
            snake("LocalWaypointListDriver"),
            "local_waypoint_list_driver"
        );
        let t = |g: &str| TransitionModel {
            message: "SetX".into(),
            machine: "m".into(),
            state: "Receiving.Ready.Controlled.Available.Ready".into(),
            guard: Some(g.into()),
            actions: Vec::new(),
            sends: Vec::new(),
            at: String::new(),
        };
        assert!(t("isControllingClient(transportData)").needs_controller());
        assert!(!t("!isControllingClient(transportData)").needs_controller());
        assert!(!t("isControllingClient(transportData)").has_data_guard());
        assert!(t("isControllingClient(transportData) && elementExists(msg)").has_data_guard());
        assert!(t("x").needs_ready());
    }
}
