//! Services: a `service_def` with its references (inherits from, client of), its
//! message set, its internal events and its protocol behaviour: state machines with
//! nested states, initial states, entry and exit actions, transitions with parameters,
//! guards and actions, default states and transitions, and the `extending` and
//! `redefine` interpretations.

use crate::error::Result;
use crate::fields::{join, Mode};
use crate::import::{At, Importer};
use crate::names::pascal;
use crate::xml::{child, collapse, description, elements, interpretation, tag, Node};
use jaus_spec::model::{
    ActionDef, BehaviourDef, DefaultStateDef, EventDef, GuardDef, MachineDef, ParamDef, ServiceDef,
    ServiceRef, ServiceTransitionDef, StartDef, StateDef, TransitionKind,
};

/// `extending ...` or `redefine ...` at the start of an interpretation.
fn starts(text: Option<&str>, word: &str) -> bool {
    text.and_then(collapse)
        .is_some_and(|t| t.to_ascii_lowercase().starts_with(word))
}

/// Whether a `state_machine` extends an inherited one: its interpretation says
/// `extending`, or its name is an inherited machine's (`base.ReceiveFSM`, the local
/// name of the parent service in front) in a service that inherits.
fn machine_extends(m: Node<'_>) -> bool {
    let inherits = m
        .ancestors()
        .find(|n| tag(*n) == "service_def")
        .and_then(|sv| child(sv, "references"))
        .and_then(|r| child(r, "inherits_from"))
        .is_some();
    starts(m.attribute("interpretation"), "extending")
        || (inherits && m.attribute("name").is_some_and(|n| n.contains('.')))
}

/// The spelling the behaviour of service `sv` uses for its parent's local name `name`,
/// when it differs only in case and is never spelt as declared (the published HMI set
/// declares `name="Events"` and writes `events.transport.Send`): the references are the
/// name the machines use.
fn spelling_in_use(sv: Node<'_>, name: &str) -> Option<String> {
    let mut other = None;
    for n in sv.descendants().filter(|n| n.is_element()) {
        for a in n.attributes() {
            let Some((head, _)) = a.value().split_once('.') else {
                continue;
            };
            if head == name {
                return None;
            }
            if other.is_none() && head.eq_ignore_ascii_case(name) {
                other = Some(head.to_string());
            }
        }
    }
    other
}

impl<'a> Importer<'a> {
    /// A service definition.
    pub fn service(&mut self, sv: At<'a>) -> Result<()> {
        let name = pascal(self.req(sv, "name")?);
        let reference = |at: At<'a>| -> Result<ServiceRef> {
            Ok(ServiceRef {
                name: self.req(at, "name")?.to_string(),
                id: self.req(at, "id")?.to_string(),
                version: self.req(at, "version")?.to_string(),
            })
        };
        let refs = child(sv.node, "references").map(|r| self.at(sv, r));
        let mut inherits =
            match refs.and_then(|r| child(r.node, "inherits_from").map(|i| self.at(r, i))) {
                Some(i) => Some(reference(i)?),
                None => None,
            };
        if let Some(i) = inherits.as_mut() {
            if let Some(used) = spelling_in_use(sv.node, &i.name) {
                i.name = used;
            }
        }
        let mut client_of = Vec::new();
        if let Some(r) = refs {
            for c in elements(r.node).filter(|c| tag(*c) == "client_of") {
                client_of.push(reference(self.at(r, c))?);
            }
        }
        let mut inputs = Vec::new();
        let mut outputs = Vec::new();
        if let Some(ms) = child(sv.node, "message_set") {
            for set in elements(ms) {
                let list = match tag(set) {
                    "input_set" => &mut inputs,
                    "output_set" => &mut outputs,
                    other => {
                        return Err(self.err(
                            self.at(sv, set),
                            format!("<{other}> is not part of a message set"),
                        ))
                    }
                };
                for m in elements(set) {
                    let n = self.message(self.at(sv, m))?;
                    list.push(n);
                }
            }
        }
        let mut events = Vec::new();
        if let Some(es) = child(sv.node, "internal_events_set") {
            for e in elements(es) {
                events.push(self.event(self.at(sv, e), &name)?);
            }
        }
        let behaviour = match child(sv.node, "protocol_behavior") {
            Some(pb) => Some(self.behaviour(self.at(sv, pb))?),
            None => None,
        };
        let def = ServiceDef {
            name,
            id: self.req(sv, "id")?.to_string(),
            version: self.req(sv, "version")?.to_string(),
            description: description(sv.node),
            assumptions: child(sv.node, "assumptions")
                .and_then(|a| a.text())
                .and_then(collapse),
            inherits,
            client_of,
            inputs,
            outputs,
            events,
            behaviour,
        };
        self.out[sv.doc].services.push((sv.offset(), def));
        Ok(())
    }

    /// An internal event (`event_def`, or a `declared_event_def` naming one).
    fn event(&mut self, el: At<'a>, service: &str) -> Result<EventDef> {
        let def = self.resolve(el)?;
        if tag(def.node) != "event_def" {
            return Err(self.err(
                el,
                format!("expected an <event_def>, found <{}>", tag(def.node)),
            ));
        }
        let name = pascal(self.req(el, "name")?);
        let body = elements(def.node)
            .find(|c| matches!(tag(*c), "body" | "declared_body"))
            .map(|b| self.at(def, b))
            .ok_or_else(|| self.err(def, "the <body> is missing"))?;
        let (_, fields) = self.body_fields(body, &format!("{service}{name}"), Mode::Event)?;
        Ok(EventDef {
            name,
            description: description(def.node),
            fields,
        })
    }

    /// The protocol behaviour.
    fn behaviour(&self, pb: At<'a>) -> Result<BehaviourDef> {
        let mut b = BehaviourDef {
            stateless: matches!(pb.node.attribute("is_stateless"), Some("true" | "1")),
            start: Vec::new(),
            machines: Vec::new(),
        };
        for c in elements(pb.node) {
            let c = self.at(pb, c);
            match tag(c.node) {
                "start" => b.start.push(StartDef {
                    machine: self.req(c, "state_machine_name")?.to_string(),
                    state: self.req(c, "state_name")?.to_string(),
                }),
                "state_machine" => {
                    let mut m = MachineDef {
                        name: self.req(c, "name")?.to_string(),
                        description: interpretation(c.node),
                        extends: machine_extends(c.node),
                        states: Vec::new(),
                        default: None,
                    };
                    for s in elements(c.node) {
                        let s = self.at(c, s);
                        match tag(s.node) {
                            "state" => m.states.push(self.state(s)?),
                            "default_state" => m.default = Some(self.default_state(s)?),
                            other => {
                                return Err(self
                                    .err(s, format!("<{other}> is not part of a state machine")))
                            }
                        }
                    }
                    b.machines.push(m);
                }
                other => {
                    return Err(
                        self.err(c, format!("<{other}> is not part of a protocol behaviour"))
                    )
                }
            }
        }
        Ok(b)
    }

    /// A state with everything in it.
    fn state(&self, s: At<'a>) -> Result<StateDef> {
        let interp = s.node.attribute("interpretation");
        let mut st = StateDef {
            name: self.req(s, "name")?.to_string(),
            description: interpretation(s.node),
            initial: s.node.attribute("initial_state").map(str::to_string),
            redefine: starts(interp, "redefine"),
            entry: Vec::new(),
            exit: Vec::new(),
            transitions: Vec::new(),
            default_transitions: Vec::new(),
            states: Vec::new(),
            default: None,
        };
        for c in elements(s.node) {
            let c = self.at(s, c);
            match tag(c.node) {
                "entry" => st.entry = self.actions(c)?,
                "exit" => st.exit = self.actions(c)?,
                "transition" => st.transitions.push(self.transition(c)?),
                "default_transition" => st.default_transitions.push(self.transition(c)?),
                "state" => st.states.push(self.state(c)?),
                "default_state" => st.default = Some(self.default_state(c)?),
                other => return Err(self.err(c, format!("<{other}> is not part of a state"))),
            }
        }
        // A state of a machine that extends an inherited one, starting in a sub-state it
        // does not declare, can only start in the inherited state's: it extends that
        // state; and a state holding one that extends an inherited state extends its
        // inherited one too (the published sets leave out `redefine` there).
        let machine = s.node.ancestors().find(|n| tag(*n) == "state_machine");
        let extending = machine.is_some_and(machine_extends);
        // In a machine that extends an inherited one, a state of an inherited state's
        // name extends it, whatever its interpretation says (the JAUS Tool Set merges
        // by name; Manipulator v2.0's pose sensors write `NotControlled` without
        // `redefine` around the inherited `Available`), and one the parent lacks is
        // added, as any new state.
        if extending {
            st.redefine = true;
        }
        let starts_inherited = st
            .initial
            .as_ref()
            .is_some_and(|i| !st.states.iter().any(|c| &c.name == i));
        if extending && (starts_inherited || st.states.iter().any(|c| c.redefine)) {
            st.redefine = true;
        }
        Ok(st)
    }

    /// A default state.
    fn default_state(&self, d: At<'a>) -> Result<DefaultStateDef> {
        let mut ds = DefaultStateDef {
            description: interpretation(d.node),
            ..DefaultStateDef::default()
        };
        for c in elements(d.node) {
            let c = self.at(d, c);
            match tag(c.node) {
                "transition" => ds.transitions.push(self.transition(c)?),
                "default_transition" => ds.default_transitions.push(self.transition(c)?),
                other => {
                    return Err(self.err(c, format!("<{other}> is not part of a default state")))
                }
            }
        }
        Ok(ds)
    }

    /// The actions of an entry, exit or transition.
    fn actions(&self, parent: At<'a>) -> Result<Vec<ActionDef>> {
        let mut out = Vec::new();
        for c in elements(parent.node).filter(|c| matches!(tag(*c), "action" | "send_action")) {
            let c = self.at(parent, c);
            out.push(self.action(c, "name")?);
        }
        Ok(out)
    }

    /// An action (or `send_action`, or a `pop`'s trigger) with its arguments.
    fn action(&self, c: At<'a>, name_attr: &str) -> Result<ActionDef> {
        let mut args = Vec::new();
        for a in elements(c.node).filter(|a| tag(*a) == "argument") {
            let a = self.at(c, a);
            args.push(self.req(a, "value")?.trim().to_string());
        }
        Ok(ActionDef {
            name: c.node.attribute(name_attr).unwrap_or_default().to_string(),
            description: interpretation(c.node),
            args,
            send: tag(c.node) == "send_action",
        })
    }

    /// A transition or default transition.
    fn transition(&self, t: At<'a>) -> Result<ServiceTransitionDef> {
        let mut tr = ServiceTransitionDef {
            on: t.node.attribute("name").map(str::to_string),
            description: interpretation(t.node),
            parameters: Vec::new(),
            guard: None,
            kind: TransitionKind::Simple,
            to: None,
            pop: None,
            actions: self.actions(t)?,
        };
        let mut kinds = 0;
        for c in elements(t.node) {
            let c = self.at(t, c);
            match tag(c.node) {
                "parameter" => tr.parameters.push(ParamDef {
                    // A message or event by name, as the importer names them
                    // (`QueryDCM` → `QueryDcm`); a path (`Receive.Body.ReceiveRec`) as
                    // written.
                    ty: {
                        let ty = self.req(c, "type")?.trim();
                        if ty.contains('.') {
                            ty.to_string()
                        } else {
                            pascal(ty)
                        }
                    },
                    name: self.req(c, "value")?.trim().to_string(),
                    description: interpretation(c.node),
                }),
                "guard" => {
                    tr.guard = Some(GuardDef {
                        condition: collapse(self.req(c, "condition")?).unwrap_or_default(),
                        description: interpretation(c.node),
                    })
                }
                "internal" => {
                    kinds += 1;
                    tr.kind = TransitionKind::Internal;
                }
                "simple" | "push" => {
                    kinds += 1;
                    tr.kind = if tag(c.node) == "push" {
                        TransitionKind::Push
                    } else {
                        TransitionKind::Simple
                    };
                    tr.to = match child(c.node, "end_state") {
                        Some(e) => Some(self.req(self.at(c, e), "state")?.trim().to_string()),
                        None => None,
                    };
                    if tag(c.node) == "push" && child(c.node, "simple").is_some() {
                        return Err(
                            self.err(c, "a push with a nested simple transition is not supported")
                        );
                    }
                    tr.description = join(&[tr.description.take(), interpretation(c.node)]);
                }
                "pop" => {
                    kinds += 1;
                    tr.kind = TransitionKind::Pop;
                    if c.node.attribute("transition").is_some() || elements(c.node).next().is_some()
                    {
                        tr.pop = Some(self.action(c, "transition")?);
                    }
                }
                "action" | "send_action" => {}
                other => return Err(self.err(c, format!("<{other}> is not part of a transition"))),
            }
        }
        if kinds != 1 {
            return Err(self.err(
                t,
                "a transition is exactly one of internal, simple, push or pop",
            ));
        }
        Ok(tr)
    }
}
