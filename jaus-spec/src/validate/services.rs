//! Services (`services:` of a file): names, the messages of their input and output
//! sets, their internal events, and their state machines (start states, initial
//! states, sibling names, transition targets and kinds).

use super::names::{is_pascal, is_snake, KEYWORDS};
use super::Ctx;
use crate::model::{
    DefaultStateDef, EventDef, MachineDef, ServiceTransitionDef, StateDef, TransitionKind,
};
use crate::resolved::{Int, Service};
use std::collections::HashMap;

/// Every service, and that no two share a name or a URI and version.
pub(super) fn check_services(cx: &mut Ctx<'_>) {
    let spec = cx.spec;
    let mut names: HashMap<&str, &Service> = HashMap::new();
    let mut ids: HashMap<(&str, &str), &str> = HashMap::new();
    for s in &spec.services {
        let d = &s.def;
        let ctx = format!("service `{}`", d.name);
        if !is_pascal(&d.name) {
            cx.err(
                s.source,
                &format!("{}.name", s.path),
                ctx.clone(),
                format!("name `{}` must be PascalCase", d.name),
            );
        }
        if let Some(first) = names.insert(&d.name, s) {
            let f = &spec.sources[first.source];
            let pos = f.index.find(&format!("{}.name", first.path));
            cx.err(
                s.source,
                &format!("{}.name", s.path),
                ctx.clone(),
                format!(
                    "duplicate service name `{}` (first defined at {}:{}:{})",
                    d.name,
                    f.path.display(),
                    pos.line,
                    pos.column
                ),
            );
        }
        if let Some(first) = ids.insert((&d.id, &d.version), &d.name) {
            cx.err(
                s.source,
                &format!("{}.id", s.path),
                ctx.clone(),
                format!(
                    "`{}` version {} is already defined by service `{first}`",
                    d.id, d.version
                ),
            );
        }
        if d.id.trim().is_empty() || d.version.trim().is_empty() {
            cx.err(
                s.source,
                &format!("{}.id", s.path),
                ctx.clone(),
                "a service needs its URI (`id`) and `version`",
            );
        }
        check_message_sets(cx, s, &ctx);
        for (i, e) in d.events.iter().enumerate() {
            check_event(cx, s, &format!("{}.events[{i}]", s.path), e, &ctx);
        }
        if let Some(b) = &d.behaviour {
            let mut machines: HashMap<&str, ()> = HashMap::new();
            for (i, m) in b.machines.iter().enumerate() {
                let p = format!("{}.behaviour.machines[{i}]", s.path);
                if machines.insert(&m.name, ()).is_some() {
                    cx.err(
                        s.source,
                        &format!("{p}.name"),
                        ctx.clone(),
                        format!("duplicate state machine `{}`", m.name),
                    );
                }
                check_machine(cx, s, &p, m, &ctx);
            }
            for (i, st) in b.start.iter().enumerate() {
                let p = format!("{}.behaviour.start[{i}]", s.path);
                match b.machines.iter().find(|m| m.name == st.machine) {
                    None => cx.err(
                        s.source,
                        &format!("{p}.machine"),
                        ctx.clone(),
                        format!(
                            "start names no state machine of the service: `{}`",
                            st.machine
                        ),
                    ),
                    Some(m) if !m.extends && find_state(&m.states, &st.state).is_none() => cx.err(
                        s.source,
                        &format!("{p}.state"),
                        ctx.clone(),
                        format!(
                            "start state `{}` is not a state of machine `{}`",
                            st.state, m.name
                        ),
                    ),
                    Some(_) => {}
                }
            }
        }
    }
}

/// Inputs and outputs name messages of the set, once each.
fn check_message_sets(cx: &mut Ctx<'_>, s: &Service, ctx: &str) {
    for (key, list) in [("inputs", &s.def.inputs), ("outputs", &s.def.outputs)] {
        let mut seen: HashMap<&str, ()> = HashMap::new();
        for (i, name) in list.iter().enumerate() {
            let p = format!("{}.{key}[{i}]", s.path);
            if cx.spec.message(name).is_none() {
                cx.err(
                    s.source,
                    &p,
                    ctx.to_string(),
                    format!("`{key}` names `{name}`, which is not a message of the set"),
                );
            }
            if seen.insert(name, ()).is_some() {
                cx.err(
                    s.source,
                    &p,
                    ctx.to_string(),
                    format!("`{name}` is listed twice in `{key}`"),
                );
            }
        }
    }
}

/// An event's name, and its fields' names and types (an event is not sent: its fields
/// need no count or length, only a known type).
fn check_event(cx: &mut Ctx<'_>, s: &Service, p: &str, e: &EventDef, ctx: &str) {
    let ctx = format!("{ctx}, event `{}`", e.name);
    if !is_pascal(&e.name) {
        cx.err(
            s.source,
            &format!("{p}.name"),
            ctx.clone(),
            format!("name `{}` must be PascalCase", e.name),
        );
    }
    let mut seen: HashMap<&str, ()> = HashMap::new();
    for (i, f) in e.fields.iter().enumerate() {
        let fp = format!("{p}.fields[{i}]");
        if !is_snake(&f.name) || KEYWORDS.contains(&f.name.as_str()) {
            cx.err(
                s.source,
                &format!("{fp}.name"),
                ctx.clone(),
                format!(
                    "field name `{}` must be snake_case and not a keyword",
                    f.name
                ),
            );
        }
        if seen.insert(&f.name, ()).is_some() {
            cx.err(
                s.source,
                &format!("{fp}.name"),
                ctx.clone(),
                format!("duplicate field `{}`", f.name),
            );
        }
        let elem = f.of.as_ref().map(|e| e.0.ty.as_str());
        for (key, ty) in [("type", Some(f.ty.as_str())), ("of", elem)] {
            let Some(ty) = ty else { continue };
            if !known_type(cx, ty) {
                cx.err(
                    s.source,
                    &format!("{fp}.{key}"),
                    ctx.clone(),
                    format!("field `{}`: unknown type `{ty}`", f.name),
                );
            }
        }
        if f.ty == "list" && f.of.is_none() {
            cx.err(
                s.source,
                &format!("{fp}.type"),
                ctx.clone(),
                format!("field `{}`: a list needs `of:` (its element type)", f.name),
            );
        }
    }
}

/// A basic type, `string`, `bytes`, `list`, `message` or a named type of the set.
fn known_type(cx: &Ctx<'_>, ty: &str) -> bool {
    Int::parse(ty).is_some()
        || matches!(
            ty,
            "f32"
                | "float"
                | "f64"
                | "double"
                | "long float"
                | "string"
                | "bytes"
                | "list"
                | "message"
                | "flag"
        )
        || cx.spec.ty(ty).is_some()
}

/// A machine's states, recursively, and its default state.
fn check_machine(cx: &mut Ctx<'_>, s: &Service, p: &str, m: &MachineDef, ctx: &str) {
    let ctx = format!("{ctx}, state machine `{}`", m.name);
    if m.states.is_empty() {
        cx.err(
            s.source,
            &format!("{p}.name"),
            ctx.clone(),
            "a state machine needs at least one state",
        );
    }
    check_states(cx, s, p, &m.states, m, &ctx);
    if let Some(d) = &m.default {
        check_default(cx, s, &format!("{p}.default"), d, m, &ctx);
    }
}

/// Sibling states: unique names, each state's initial sub-state, its transitions, and
/// its sub-states.
fn check_states(
    cx: &mut Ctx<'_>,
    s: &Service,
    p: &str,
    states: &[StateDef],
    m: &MachineDef,
    ctx: &str,
) {
    let mut seen: HashMap<&str, ()> = HashMap::new();
    for (i, st) in states.iter().enumerate() {
        let sp = format!("{p}.states[{i}]");
        let sctx = format!("{ctx}, state `{}`", st.name);
        if st.name.is_empty() || st.name.contains('.') {
            cx.err(
                s.source,
                &format!("{sp}.name"),
                sctx.clone(),
                "a state's name is one word without dots",
            );
        }
        if seen.insert(&st.name, ()).is_some() {
            cx.err(
                s.source,
                &format!("{sp}.name"),
                sctx.clone(),
                format!("duplicate state `{}` among its siblings", st.name),
            );
        }
        if let Some(init) = &st.initial {
            // A redefined state may start in an inherited sub-state.
            if !st.redefine && !st.states.iter().any(|c| &c.name == init) {
                cx.err(
                    s.source,
                    &format!("{sp}.initial"),
                    sctx.clone(),
                    format!("initial state `{init}` is not a sub-state of `{}`", st.name),
                );
            }
        }
        for (j, t) in st.transitions.iter().enumerate() {
            check_transition(cx, s, &format!("{sp}.transitions[{j}]"), t, m, &sctx, true);
        }
        for (j, t) in st.default_transitions.iter().enumerate() {
            let tp = format!("{sp}.default_transitions[{j}]");
            check_transition(cx, s, &tp, t, m, &sctx, false);
        }
        check_states(cx, s, &sp, &st.states, m, &sctx);
        if let Some(d) = &st.default {
            check_default(cx, s, &format!("{sp}.default"), d, m, &sctx);
        }
    }
}

fn check_default(
    cx: &mut Ctx<'_>,
    s: &Service,
    p: &str,
    d: &DefaultStateDef,
    m: &MachineDef,
    ctx: &str,
) {
    for (j, t) in d.transitions.iter().enumerate() {
        check_transition(cx, s, &format!("{p}.transitions[{j}]"), t, m, ctx, true);
    }
    for (j, t) in d.default_transitions.iter().enumerate() {
        let tp = format!("{p}.default_transitions[{j}]");
        check_transition(cx, s, &tp, t, m, ctx, false);
    }
}

/// A transition: its trigger (required except for a default transition), its kind and
/// target (which must be a state of the machine, unless the machine extends an
/// inherited one whose states it may name).
fn check_transition(
    cx: &mut Ctx<'_>,
    s: &Service,
    p: &str,
    t: &ServiceTransitionDef,
    m: &MachineDef,
    ctx: &str,
    needs_trigger: bool,
) {
    let mut err =
        |key: &str, msg: String| cx.err(s.source, &format!("{p}.{key}"), ctx.to_string(), msg);
    match (&t.on, needs_trigger) {
        (None, true) => err("kind", "a transition needs its trigger (`on`)".into()),
        (Some(on), false) => err(
            "on",
            format!("a default transition has no trigger (`on: {on}`)"),
        ),
        _ => {}
    }
    match (t.kind, &t.to) {
        (TransitionKind::Internal | TransitionKind::Pop, Some(to)) => err(
            "to",
            format!("an internal or pop transition leads nowhere (`to: {to}`)"),
        ),
        (TransitionKind::Push, None) => err("kind", "a push transition needs `to`".into()),
        (TransitionKind::Simple | TransitionKind::Push, Some(to))
            if !m.extends && find_state(&m.states, to).is_none() =>
        {
            err(
                "to",
                format!("`{to}` is not a state of machine `{}`", m.name),
            )
        }
        _ => {}
    }
    if t.pop.is_some() && t.kind != TransitionKind::Pop {
        err("pop", "`pop` applies to a transition of kind `pop`".into());
    }
}

/// The state at a dotted path from the machine's top (`Receiving.Ready.Controlled`).
fn find_state<'a>(states: &'a [StateDef], path: &str) -> Option<&'a StateDef> {
    let mut level = states;
    let mut found = None;
    for name in path.split('.') {
        let st = level.iter().find(|s| s.name == name)?;
        level = &st.states;
        found = Some(st);
    }
    found
}
