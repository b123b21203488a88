//! Which checks apply to a component: the core checks for every component, and the
//! checks the definitions make possible for its type (its interface in Report Services,
//! a read-back check per command with a `readback:` query). A vendor's overlay
//! definitions give its own components and messages checks the same way.

use jaus_spec::Spec;

use crate::check::{Check, Kind, Level, Malformed, Rule, StateCommand};

/// Every rule the checks cite.
pub mod rules {
    use crate::check::Rule;

    /// Identification.
    pub const IDENTIFICATION: Rule = Rule {
        id: "identification",
        source: "Part 1 §4.2, core rule",
        text: "Every component answers Query Identification (component level) with Report Identification naming itself.",
    };
    /// Services.
    pub const SERVICES: Rule = Rule {
        id: "services",
        source: "Part 1 §4.3, §5 (component interfaces)",
        text: "Report Services lists the core service and the component's own service with the messages its definition says it takes.",
    };
    /// Status.
    pub const STATUS: Rule = Rule {
        id: "status",
        source: "Part 1 §4.3, core rule",
        text: "Every component answers Query Component Status with its core state.",
    };
    /// Heartbeat.
    pub const HEARTBEAT: Rule = Rule {
        id: "heartbeat",
        source: "communications message set (Part 1 does not require every component to answer)",
        text: "Query Heartbeat Pulse is answered with Report Heartbeat Pulse, so that a peer can tell the component is alive.",
    };
    /// Authority.
    pub const AUTHORITY: Rule = Rule {
        id: "authority",
        source: "core rule",
        text: "Query Component Authority is answered with the component's own authority.",
    };
    /// Control granted.
    pub const CONTROL_GRANT: Rule = Rule {
        id: "control.grant",
        source: "core rule (component control)",
        text: "A request for control at no less than the component's authority, while nobody holds control, is confirmed (Control Accepted).",
    };
    /// Control reported.
    pub const CONTROL_REPORT: Rule = Rule {
        id: "control.report",
        source: "core rule (component control)",
        text: "Query Component Control names the component in control and its authority.",
    };
    /// Equal authority rejected.
    pub const CONTROL_EQUAL: Rule = Rule {
        id: "control.equal",
        source: "core rule (component control)",
        text: "While a component holds control, another requester at an authority no higher than the controller's is not given control.",
    };
    /// Below the component's authority.
    pub const CONTROL_BELOW: Rule = Rule {
        id: "control.authority",
        source: "Part 1 §4.3, core rule (component control)",
        text: "A component hands control only to a requester whose authority is at least its own; a request at a lower authority is refused (Confirm Component Control, insufficient authority).",
    };
    /// Preemption.
    pub const CONTROL_PREEMPT: Rule = Rule {
        id: "control.preempt",
        source: "core rule (component control)",
        text: "A requester at a higher authority than the controller's takes control, and the old controller receives Reject Component Control.",
    };
    /// Release.
    pub const CONTROL_RELEASE: Rule = Rule {
        id: "control.release",
        source: "core rule (component control)",
        text: "Release Component Control from the controller leaves the component without a controller.",
    };
    /// Service connections.
    pub const SERVICE_CONNECTIONS: Rule = Rule {
        id: "service-connections",
        source: "core rule (service connections)",
        text: "A service connection for a report the component answers is confirmed; its reports come at the confirmed rate with the service-connection flag, stop while suspended, resume when activated and end when terminated.",
    };
    /// Events.
    pub const EVENTS: Rule = Rule {
        id: "events",
        source: "core rule (events)",
        text: "Create Event on a report the component answers is confirmed with the request's id; Event messages then carry that report, periodically at the confirmed rate or on every change of its value; Query Events lists the event and Cancel Event ends it.",
    };
    /// Time.
    pub const TIME: Rule = Rule {
        id: "time",
        source: "core rule (time)",
        text: "Query Time is answered with the component's time of day (UTC), which a fielded system keeps within a minute of its peers'.",
    };
    /// Queries answered.
    pub const QUERIES: Rule = Rule {
        id: "queries",
        source: "Part 1 §5 (component interfaces)",
        text: "Every query the component's interface accepts is answered with its report.",
    };
    /// Only the controller commands.
    pub const CONTROLLER_ONLY: Rule = Rule {
        id: "controller-only",
        source: "Part 1 §4.3, core rule (component control)",
        text: "While a component is controlled, it carries out commands (core state commands and its own commands) only from the component in control.",
    };
    /// State commands from the controller.
    pub const STATE: Rule = Rule {
        id: "state",
        source: "Part 1 §4.3, core rule (component states)",
        text: "Standby takes a Ready component to Standby and Resume takes it back to Ready, when sent by the component in control.",
    };
    /// Emergency from anyone.
    pub const EMERGENCY: Rule = Rule {
        id: "emergency",
        source: "core rule (emergency)",
        text: "Set Emergency and Clear Emergency are honoured from any sender, controller or not: Set enters Emergency, Clear leaves it (to Standby).",
    };
    /// Read-back.
    pub const READBACK: Rule = Rule {
        id: "readback",
        source: "Part 1 §5 (component function), definitions `readback:`",
        text: "A value set by a command from the controller is what the command's read-back query reports, within one count of its scaling.",
    };
    /// The tester's clean-up (`teardown.as-found`, run by the engine after the checks
    /// it plans).
    pub const TEARDOWN: Rule = Rule {
        id: "teardown",
        source: "jaus conform",
        text: "The tester leaves the component as it found it: nobody in control, its core state as before the run.",
    };
    /// Robustness.
    pub const ROBUST: Rule = Rule {
        id: "robust",
        source: "core rule (message handling)",
        text:
            "A malformed or unknown message is discarded: the component keeps answering afterwards.",
    };
}

fn check(
    id: impl Into<String>,
    title: impl Into<String>,
    rule: Rule,
    level: Level,
    kind: Kind,
) -> Check {
    Check {
        id: id.into(),
        title: title.into(),
        rule,
        level,
        kind,
    }
}

/// Every check for the component with id `component` (a type the definitions may or
/// may not know), in the order the engine runs them.
pub fn plan(spec: &Spec, component: u8) -> Vec<Check> {
    use rules::*;
    use Level::{Advisory, Required};
    let def = spec.components.iter().find(|c| c.def.id == component);
    let mut v = vec![
        check(
            "core.identification",
            "Query Identification is answered",
            IDENTIFICATION,
            Required,
            Kind::Identification,
        ),
        check(
            "core.services",
            "Report Services lists the core service and the component's own",
            SERVICES,
            Required,
            Kind::ServicesListed,
        ),
    ];
    if def.is_some() {
        v.push(check(
            "core.services.inputs",
            "Report Services lists every message the definitions give the component",
            SERVICES,
            Advisory,
            Kind::ServicesInputs,
        ));
    }
    for name in def.iter().flat_map(|d| d.def.accepts.iter()) {
        if spec.message(name).is_some_and(|m| m.def.is_query()) {
            v.push(check(
                format!("query.{name}"),
                format!("{name} is answered"),
                QUERIES,
                Advisory,
                Kind::QueryAnswered {
                    query: name.clone(),
                },
            ));
        }
    }
    v.extend([
        check(
            "core.status",
            "Query Component Status is answered",
            STATUS,
            Required,
            Kind::Status,
        ),
        check(
            "core.heartbeat",
            "Query Heartbeat Pulse is answered",
            HEARTBEAT,
            Advisory,
            Kind::Heartbeat,
        ),
        check(
            "core.authority",
            "Query Component Authority is answered",
            AUTHORITY,
            Advisory,
            Kind::Authority,
        ),
        check(
            "control.grant",
            "Request Component Control is confirmed",
            CONTROL_GRANT,
            Required,
            Kind::ControlGrant,
        ),
        check(
            "control.report",
            "Query Component Control names the controller",
            CONTROL_REPORT,
            Advisory,
            Kind::ControlReport,
        ),
        check(
            "control.equal",
            "A second requester at equal authority is refused",
            CONTROL_EQUAL,
            Required,
            Kind::ControlEqual,
        ),
        check(
            "control.authority_below",
            "A request below the component's own authority is refused",
            CONTROL_BELOW,
            Required,
            Kind::ControlBelow,
        ),
    ]);
    for s in [StateCommand::Standby, StateCommand::Resume] {
        v.push(check(
            format!("state.{}.controller", s.name()),
            format!("{} from the controller is carried out", s.name()),
            STATE,
            Required,
            Kind::StateFromController(s),
        ));
    }
    for s in [
        StateCommand::Standby,
        StateCommand::Resume,
        StateCommand::Reset,
    ] {
        v.push(check(
            format!("state.{}.outsider", s.name()),
            format!("{} from a component not in control is refused", s.name()),
            CONTROLLER_ONLY,
            Required,
            Kind::StateFromOutsider(s),
        ));
    }
    v.push(check(
        "emergency.set.any",
        "Set Emergency from a component not in control is honoured",
        EMERGENCY,
        Required,
        Kind::EmergencySet,
    ));
    v.push(check(
        "emergency.clear.any",
        "Clear Emergency from a component not in control is honoured",
        EMERGENCY,
        Required,
        Kind::EmergencyClear,
    ));
    // The core commands every component takes (the runtime's), then the component's
    // own, each with a read-back query.
    let core = spec
        .messages
        .iter()
        .filter(|m| m.def.runtime_input())
        .map(|m| m.def.name.clone());
    let own = def.iter().flat_map(|d| d.def.commands.iter().cloned());
    for name in core.chain(own) {
        let Some(m) = spec.message(&name) else {
            continue;
        };
        let Some(q) = &m.def.readback else { continue };
        let title = m
            .def
            .title
            .clone()
            .unwrap_or_else(|| jaus_spec::title_of(&name));
        v.push(check(
            format!("readback.{name}"),
            format!("{title} from the controller is read back by {q}"),
            READBACK,
            Required,
            Kind::Readback {
                command: name.clone(),
                query: q.clone(),
            },
        ));
        v.push(check(
            format!("outsider.{name}"),
            format!("{title} from a component not in control changes nothing ({q})"),
            CONTROLLER_ONLY,
            Required,
            Kind::OutsiderCommand {
                command: name.clone(),
                query: q.clone(),
            },
        ));
    }
    v.push(check(
        "core.time",
        "Query Time is answered with the time of day",
        TIME,
        Advisory,
        Kind::Time,
    ));
    v.push(check(
        "events.periodic",
        "A periodic event on Report Component Status runs its course",
        EVENTS,
        Required,
        Kind::EventPeriodic,
    ));
    v.push(check(
        "events.every-change",
        "An every-change event on Report Component Status reports Standby and Resume",
        EVENTS,
        Advisory,
        Kind::EventEveryChange,
    ));
    v.push(check(
        "sc.component-status",
        "A service connection on Report Component Status runs its course",
        SERVICE_CONNECTIONS,
        Required,
        Kind::ServiceConnection,
    ));
    v.extend([
        check(
            "control.preempt",
            "A higher authority takes control; the old controller is rejected",
            CONTROL_PREEMPT,
            Required,
            Kind::ControlPreempt,
        ),
        check(
            "control.release",
            "Release Component Control frees the component",
            CONTROL_RELEASE,
            Required,
            Kind::ControlRelease,
        ),
        check(
            "robust.truncated",
            "A truncated body is discarded",
            ROBUST,
            Required,
            Kind::Robust(Malformed::TruncatedBody),
        ),
        check(
            "robust.data-size",
            "A wrong data size is discarded",
            ROBUST,
            Required,
            Kind::Robust(Malformed::WrongDataSize),
        ),
        check(
            "robust.unknown-code",
            "An unknown command code is discarded",
            ROBUST,
            Required,
            Kind::Robust(Malformed::UnknownCode),
        ),
        check(
            "robust.out-of-range",
            "A value outside its field's defined values is discarded",
            ROBUST,
            Required,
            Kind::Robust(Malformed::OutOfRange),
        ),
        check(
            "robust.incomplete-sequence",
            "Multi-packet sequences that never complete are discarded",
            ROBUST,
            Required,
            Kind::Robust(Malformed::IncompleteSequence),
        ),
        check(
            "state.Shutdown.outsider",
            "Shutdown from a component not in control is refused",
            CONTROLLER_ONLY,
            Required,
            Kind::StateFromOutsider(StateCommand::Shutdown),
        ),
    ]);
    v
}

/// The component type's name, when the definitions know it.
pub fn type_name(spec: &Spec, component: u8) -> Option<&str> {
    spec.components
        .iter()
        .find(|c| c.def.id == component)
        .map(|c| c.def.name.as_str())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ids(checks: &[Check]) -> Vec<&str> {
        checks.iter().map(|c| c.id.as_str()).collect()
    }

    #[test]
    fn a_driver_gets_read_back_checks_from_the_definitions() {
        let spec = jaus_spec::load_sdk().expect("definitions");
        let gwd = plan(&spec, 45);
        let ids = ids(&gwd);
        for id in [
            "core.identification",
            "control.authority_below",
            "control.preempt",
            "readback.SetComponentAuthority",
            "readback.SetTravelSpeed",
            "outsider.SetTravelSpeed",
            "robust.unknown-code",
        ] {
            assert!(ids.contains(&id), "{id} missing from {ids:?}");
        }
        // Ids are unique, each check cites a rule.
        let mut sorted = ids.clone();
        sorted.sort();
        sorted.dedup();
        assert_eq!(sorted.len(), ids.len());
        // A sensor has no command of its own: the core checks only.
        let sensor = plan(&spec, 38);
        assert!(sensor.len() < gwd.len());
        assert!(!sensor.iter().any(|c| c.id == "readback.SetTravelSpeed"));
    }

    #[test]
    fn an_unknown_component_type_gets_the_core_checks() {
        let spec = jaus_spec::load_sdk().expect("definitions");
        let p = plan(&spec, 200);
        assert!(p.iter().all(|c| !c.id.starts_with("core.services.inputs")));
        assert!(p.iter().any(|c| c.id == "control.equal"));
    }

    #[test]
    fn a_vendor_overlay_command_with_a_read_back_gets_checks() {
        let overlay = r#"
group: acme
messages:
  - name: SetPumpRate
    code: 0xD100
    class: command
    readback: QueryPumpRate
    fields:
      - { name: rate, type: u16, scale: [0, 100], unit: "l/min" }
  - name: QueryPumpRate
    code: 0xD101
    class: query
    report: ReportPumpRate
  - name: ReportPumpRate
    code: 0xD102
    class: inform
    fields:
      - { name: rate, type: u16, scale: [0, 100], unit: "l/min" }
components:
  - name: AcmePump
    id: 150
    function: Pumps.
    commands: [SetPumpRate]
    accepts: [QueryPumpRate]
"#;
        let spec = jaus_spec::load_overlay_texts(vec![("acme.yaml".into(), overlay.into())])
            .expect("overlay loads");
        let p = plan(&spec, 150);
        assert!(p.iter().any(|c| c.id == "readback.SetPumpRate"));
        assert!(p.iter().any(|c| c.id == "outsider.SetPumpRate"));
        assert_eq!(type_name(&spec, 150), Some("AcmePump"));
    }
}
