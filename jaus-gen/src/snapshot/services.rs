//! The services of a definition set (`services:`, AS-4 service sets) as a diff and a lock
//! file see them: per service its URI, version and parent, the methods of its generated
//! trait (guards and actions), and its state machines flattened into states and
//! transitions, each with where it is defined.

use super::Loc;
use jaus_spec::model::{
    ActionDef, DefaultStateDef, ServiceTransitionDef, StateDef, TransitionKind,
};
use jaus_spec::Spec;
use std::collections::{BTreeMap, BTreeSet};

/// A service.
#[derive(Debug, Clone)]
pub struct ServiceSnap {
    /// Its name (also its trait's).
    pub name: String,
    /// Its URI.
    pub id: String,
    /// Its version.
    pub version: String,
    /// The service it inherits from: `URI version`.
    pub inherits: Option<String>,
    /// The methods of its generated trait, by name.
    pub methods: Vec<MethodSnap>,
    /// Its states (of its own machines, not the inherited ones), by path.
    pub states: Vec<StateSnap>,
    /// Its transitions, in definition order.
    pub transitions: Vec<TransSnap>,
    /// Where it is defined.
    pub at: Loc,
}

/// A method of a service's trait: a guard or an action a vendor implements.
#[derive(Debug, Clone)]
pub struct MethodSnap {
    /// The method's name (`is_controlling_client`).
    pub name: String,
    /// A guard (`-> bool`), else an action.
    pub guard: bool,
    /// The signature as generated (`fn is_x(&self, msg: &RequestControl) -> bool`), when
    /// the set's services generate (a parent outside the set leaves it unknown).
    pub sig: Option<String>,
    /// Where it is first called (a guard or action of a transition or state).
    pub at: Loc,
}

/// A state.
#[derive(Debug, Clone)]
pub struct StateSnap {
    /// `Machine/State.Sub` (the machine's name, then the state's path from its top).
    pub path: String,
    /// Entry actions as written (`init()`).
    pub entry: Vec<String>,
    /// Exit actions as written.
    pub exit: Vec<String>,
    /// Where it is defined.
    pub at: Loc,
}

/// A transition.
#[derive(Debug, Clone)]
pub struct TransSnap {
    /// The state it belongs to (`Machine/State.Sub`), with ` (default)` for the default
    /// state of that state (or of the machine: `Machine (default)`).
    pub state: String,
    /// Its trigger; `None` for a default transition (any trigger).
    pub on: Option<String>,
    /// The types of the trigger's parameters (the message first, by convention).
    pub params: Vec<String>,
    /// The guard condition as written.
    pub guard: Option<String>,
    /// `internal`, `simple`, `push` or `pop`.
    pub kind: String,
    /// The state it leads to (for `pop`: what it raises).
    pub to: Option<String>,
    /// Its actions as written, in order.
    pub actions: Vec<String>,
    /// Where it is defined.
    pub at: Loc,
}

/// The text of a kind as written in YAML.
pub(crate) fn kind_text(k: TransitionKind) -> &'static str {
    match k {
        TransitionKind::Internal => "internal",
        TransitionKind::Simple => "simple",
        TransitionKind::Push => "push",
        TransitionKind::Pop => "pop",
    }
}

fn call_text(a: &ActionDef) -> String {
    let args: Vec<String> = a.args.iter().map(|x| squash(x)).collect();
    format!("{}({})", a.name, args.join(", "))
}

/// Collects states and transitions of one service, with the YAML path of each.
struct Walk<'a> {
    loc: &'a dyn Fn(&str) -> Loc,
    states: Vec<StateSnap>,
    transitions: Vec<TransSnap>,
    /// Calls of guards and actions named without a prefix: (name, guard, where).
    calls: Vec<(String, bool, Loc)>,
}

impl Walk<'_> {
    fn action_calls(&mut self, list: &[ActionDef], at: &Loc) {
        for a in list {
            if !a.name.contains('.') {
                self.calls.push((a.name.clone(), false, at.clone()));
            }
        }
    }

    fn trans(&mut self, state: &str, path: &str, list: &[ServiceTransitionDef]) {
        for (i, t) in list.iter().enumerate() {
            let at = (self.loc)(&format!("{path}[{i}]"));
            if let Some(g) = &t.guard {
                let mut names = Vec::new();
                guard_calls(&g.condition, &mut names);
                for n in names.into_iter().filter(|n| !n.contains('.')) {
                    self.calls.push((n, true, at.clone()));
                }
            }
            self.action_calls(&t.actions, &at);
            let to = match (&t.to, &t.pop) {
                (Some(to), _) => Some(to.clone()),
                (None, Some(p)) => Some(format!("raise {}", call_text(p))),
                (None, None) => None,
            };
            self.transitions.push(TransSnap {
                state: state.to_string(),
                on: t.on.clone(),
                params: t.parameters.iter().map(|p| p.ty.clone()).collect(),
                guard: t.guard.as_ref().map(|g| guard_text(&g.condition)),
                kind: kind_text(t.kind).into(),
                to,
                actions: t.actions.iter().map(call_text).collect(),
                at,
            });
        }
    }

    fn default(&mut self, state: &str, path: &str, d: &DefaultStateDef) {
        let s = format!("{state} (default)");
        self.trans(&s, &format!("{path}.transitions"), &d.transitions);
        self.trans(
            &s,
            &format!("{path}.default_transitions"),
            &d.default_transitions,
        );
    }

    fn state(&mut self, machine: &str, prefix: &str, path: &str, s: &StateDef) {
        let name = if prefix.is_empty() {
            s.name.clone()
        } else {
            format!("{prefix}.{}", s.name)
        };
        let full = format!("{machine}/{name}");
        let at = (self.loc)(path);
        self.action_calls(&s.entry, &at);
        self.action_calls(&s.exit, &at);
        self.states.push(StateSnap {
            path: full.clone(),
            entry: s.entry.iter().map(call_text).collect(),
            exit: s.exit.iter().map(call_text).collect(),
            at,
        });
        self.trans(&full, &format!("{path}.transitions"), &s.transitions);
        self.trans(
            &full,
            &format!("{path}.default_transitions"),
            &s.default_transitions,
        );
        if let Some(d) = &s.default {
            self.default(&full, &format!("{path}.default"), d);
        }
        for (i, sub) in s.states.iter().enumerate() {
            self.state(machine, &name, &format!("{path}.states[{i}]"), sub);
        }
    }
}

/// A guard condition or argument with its whitespace made canonical: none but one space
/// between two words, quoted text as written (JSIDL wraps long conditions and spaces
/// arguments freely: `isX( data )` is `isX(data)`).
fn squash(s: &str) -> String {
    let word = |c: char| c.is_alphanumeric() || c == '_' || c == '.';
    let mut out = String::with_capacity(s.len());
    let mut quote = None;
    let mut gap = false;
    for c in s.chars() {
        if let Some(q) = quote {
            out.push(c);
            if c == q {
                quote = None;
            }
            continue;
        }
        if c.is_whitespace() {
            gap = true;
            continue;
        }
        if gap && out.chars().last().is_some_and(word) && word(c) {
            out.push(' ');
        }
        gap = false;
        if c == '\'' || c == '"' {
            quote = Some(c);
        }
        out.push(c);
    }
    out
}

/// A guard condition written canonically (`a(x) && !(b() || c())`), so that spacing
/// and redundant parentheses are no change; one that does not parse, with its spacing
/// made canonical.
fn guard_text(cond: &str) -> String {
    use crate::services::guard::{parse, Cond};
    fn text(c: &Cond, inside_and: bool) -> String {
        match c {
            Cond::Call(n, args) => {
                let a: Vec<String> = args.iter().map(|x| squash(x)).collect();
                format!("{n}({})", a.join(", "))
            }
            Cond::Const(b) => b.to_string(),
            Cond::Not(e) => match **e {
                Cond::And(_) | Cond::Or(_) => format!("!({})", text(e, false)),
                _ => format!("!{}", text(e, false)),
            },
            Cond::And(v) => v
                .iter()
                .map(|e| text(e, true))
                .collect::<Vec<_>>()
                .join(" && "),
            Cond::Or(v) => {
                let s = v
                    .iter()
                    .map(|e| text(e, false))
                    .collect::<Vec<_>>()
                    .join(" || ");
                if inside_and {
                    format!("({s})")
                } else {
                    s
                }
            }
        }
    }
    match parse(cond) {
        Ok(c) => text(&c, false),
        Err(_) => squash(cond),
    }
}

/// The names of the functions a guard condition calls (a condition that does not parse
/// gives the names before `(`).
fn guard_calls(cond: &str, out: &mut Vec<String>) {
    use crate::services::guard::{parse, Cond};
    fn walk(c: &Cond, out: &mut Vec<String>) {
        match c {
            Cond::Call(n, _) => out.push(n.clone()),
            Cond::Const(_) => {}
            Cond::Not(e) => walk(e, out),
            Cond::And(v) | Cond::Or(v) => v.iter().for_each(|e| walk(e, out)),
        }
    }
    match parse(cond) {
        Ok(c) => walk(&c, out),
        Err(_) => {
            for part in cond.split('(').filter(|p| !p.is_empty()) {
                let name: String = part
                    .chars()
                    .rev()
                    .take_while(|c| c.is_alphanumeric() || matches!(c, '_' | '.'))
                    .collect::<Vec<_>>()
                    .into_iter()
                    .rev()
                    .collect();
                if !name.is_empty() {
                    out.push(name);
                }
            }
        }
    }
}

/// The services of `spec` that are its own, sorted by name; `loc` gives where a YAML
/// path of a source is.
pub(crate) fn services(spec: &Spec, loc: &dyn Fn(usize, &str) -> Loc) -> Vec<ServiceSnap> {
    // The generated traits' methods, when the set's services generate.
    let generated: Option<BTreeMap<String, Vec<String>>> =
        crate::services::build_services(spec, None, None, None)
            .ok()
            .map(|ctx| {
                ctx.services
                    .into_iter()
                    .map(|s| (s.name, s.methods.into_iter().map(|m| m.sig).collect()))
                    .collect()
            });
    let mut walks = Vec::new();
    for s in &spec.services {
        let one = |p: &str| loc(s.source, p);
        let mut w = Walk {
            loc: &one,
            states: Vec::new(),
            transitions: Vec::new(),
            calls: Vec::new(),
        };
        if let Some(b) = &s.def.behaviour {
            for (j, m) in b.machines.iter().enumerate() {
                let mp = format!("{}.behaviour.machines[{j}]", s.path);
                for (k, st) in m.states.iter().enumerate() {
                    w.state(&m.name, "", &format!("{mp}.states[{k}]"), st);
                }
                if let Some(d) = &m.default {
                    w.default(&m.name, &format!("{mp}.default"), d);
                }
            }
        }
        let (states, transitions, calls) = (w.states, w.transitions, w.calls);
        walks.push((states, transitions, calls));
    }
    // A method named without a prefix is its farthest ancestor's when that one calls it
    // too (as the generator declares it).
    let parent = |i: usize| -> Option<usize> {
        let r = spec.services[i].def.inherits.as_ref()?;
        spec.services
            .iter()
            .position(|p| p.def.id == r.id && p.def.version == r.version)
    };
    let declares = |i: usize, name: &str| walks[i].2.iter().any(|(n, _, _)| n == name);
    let mut out = Vec::new();
    for (i, s) in spec.services.iter().enumerate() {
        if !spec.is_own(s.source) {
            continue;
        }
        let (states, transitions, calls) = &walks[i];
        let mut first: BTreeMap<String, (bool, Loc)> = BTreeMap::new();
        for (n, guard, at) in calls {
            first
                .entry(crate::services::model::ident(n))
                .or_insert((*guard, at.clone()));
        }
        let mut methods: Vec<MethodSnap> = match generated.as_ref().and_then(|g| g.get(&s.def.name))
        {
            Some(sigs) => sigs
                .iter()
                .map(|sig| {
                    let name = sig
                        .strip_prefix("fn ")
                        .and_then(|x| x.split('(').next())
                        .unwrap_or(sig)
                        .to_string();
                    let at = first
                        .get(&name)
                        .map_or_else(|| loc(s.source, &s.path), |(_, at)| at.clone());
                    MethodSnap {
                        guard: sig.ends_with("-> bool"),
                        sig: Some(sig.clone()),
                        name,
                        at,
                    }
                })
                .collect(),
            None => {
                // Without the generator: the names this service calls that no ancestor
                // calls too.
                let mut ancestors = BTreeSet::new();
                let mut at = parent(i);
                while let Some(p) = at {
                    if !ancestors.insert(p) {
                        break;
                    }
                    at = parent(p);
                }
                calls
                    .iter()
                    .filter(|(n, _, _)| !ancestors.iter().any(|&a| declares(a, n)))
                    .map(|(n, g, at)| MethodSnap {
                        name: crate::services::model::ident(n),
                        guard: *g,
                        sig: None,
                        at: at.clone(),
                    })
                    .collect()
            }
        };
        methods.sort_by(|a, b| a.name.cmp(&b.name));
        methods.dedup_by(|a, b| a.name == b.name);
        let mut states = states.clone();
        states.sort_by(|a, b| a.path.cmp(&b.path));
        out.push(ServiceSnap {
            name: s.def.name.clone(),
            id: s.def.id.clone(),
            version: s.def.version.clone(),
            inherits: s
                .def
                .inherits
                .as_ref()
                .map(|r| format!("{} {}", r.id, r.version)),
            methods,
            states,
            transitions: transitions.clone(),
            at: loc(s.source, &s.path),
        });
    }
    out.sort_by(|a, b| a.name.cmp(&b.name));
    out
}
