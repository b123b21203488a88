//! Component interfaces: names, ids, the messages they list, and their modes.

use super::names::{is_pascal, is_snake};
use super::Ctx;
use crate::model::{MessageClass, ModesDef};
use crate::resolved::Component;
use std::collections::HashMap;

/// Core states a mode transition may lead the component into.
const MODE_CORE_STATES: &[&str] = &["Standby", "Failure"];

/// Every component: its name and id ([`check_identity`]), the messages it lists
/// ([`check_any_message`], [`check_message_lists`]) and its modes ([`check_modes`]).
pub(super) fn check_components(cx: &mut Ctx<'_>) {
    let spec = cx.spec;
    let mut ids: HashMap<u8, &str> = HashMap::new();
    let mut names: HashMap<&str, ()> = HashMap::new();
    for c in &spec.components {
        let ctx = format!("component `{}`", c.def.name);
        check_identity(cx, c, &ctx, &mut names, &mut ids);
        check_any_message(cx, c, &ctx);
        check_message_lists(cx, c, &ctx);
        if let Some(m) = &c.def.modes {
            check_modes(cx, c, m, &ctx);
        }
    }
}

/// The name is `PascalCase` and used by no other component or message; the id is in
/// 1..=254 and used by no other component.
fn check_identity<'s>(
    cx: &mut Ctx<'_>,
    c: &'s Component,
    ctx: &str,
    names: &mut HashMap<&'s str, ()>,
    ids: &mut HashMap<u8, &'s str>,
) {
    let d = &c.def;
    let at = |k: &str| format!("{}.{k}", c.path);
    if !is_pascal(&d.name) {
        cx.err(
            c.source,
            &at("name"),
            ctx.to_string(),
            "component name must be PascalCase",
        );
    }
    if names.insert(&d.name, ()).is_some() || cx.spec.message(&d.name).is_some() {
        cx.err(
            c.source,
            &at("name"),
            ctx.to_string(),
            format!("name `{}` is already used", d.name),
        );
    }
    if d.id == 0 || d.id == 255 {
        cx.err(
            c.source,
            &at("id"),
            ctx.to_string(),
            format!("component id {} is not in 1..=254", d.id),
        );
    } else if let Some(o) = ids.insert(d.id, &d.name) {
        cx.err(
            c.source,
            &at("id"),
            ctx.to_string(),
            format!("component id {} is already used by `{o}`", d.id),
        );
    }
}

/// A component with `any_message: true` lists no messages.
fn check_any_message(cx: &mut Ctx<'_>, c: &Component, ctx: &str) {
    let d = &c.def;
    if d.any_message && !(d.commands.is_empty() && d.accepts.is_empty() && d.emits.is_empty()) {
        cx.err(
            c.source,
            &format!("{}.any_message", c.path),
            ctx.to_string(),
            "a component with `any_message: true` takes and sends every message: leave `commands`, `accepts` and `emits` empty",
        );
    }
}

/// The messages of `commands`, `accepts` and `emits` exist; a message is in one of
/// `commands` and `accepts` once, and not one the runtime handles itself; `commands`
/// holds commands.
fn check_message_lists(cx: &mut Ctx<'_>, c: &Component, ctx: &str) {
    let spec = cx.spec;
    let d = &c.def;
    let mut seen: HashMap<&str, &str> = HashMap::new();
    for (key, list) in [
        ("commands", &d.commands),
        ("accepts", &d.accepts),
        ("emits", &d.emits),
    ] {
        for (i, name) in list.iter().enumerate() {
            let path = format!("{}.{key}[{i}]", c.path);
            let Some(m) = spec.message(name) else {
                cx.err(
                    c.source,
                    &path,
                    ctx.to_string(),
                    format!("`{key}` names unknown message `{name}`"),
                );
                continue;
            };
            let code = m.def.code.0;
            if key != "emits" {
                if let Some(prev) = seen.insert(name.as_str(), key) {
                    let msg = if prev == key {
                        format!("`{name}` is listed twice in `{key}`")
                    } else {
                        format!("`{name}` is in both `{prev}` and `{key}`: a message is either a controlled command or accepted from anyone")
                    };
                    cx.err(c.source, &path, ctx.to_string(), msg);
                    continue;
                }
                if m.def.runtime_owned() {
                    cx.err(
                        c.source,
                        &path,
                        ctx.to_string(),
                        format!("`{name}` (0x{code:04X}) is handled by the component runtime for every component: remove it from `{key}`"),
                    );
                    continue;
                }
            }
            if key == "commands" && m.def.class() != MessageClass::Command {
                cx.err(
                    c.source,
                    &path,
                    ctx.to_string(),
                    format!(
                        "`{name}` (0x{code:04X}) is not a command ({}, or `class: command` for an experimental code): list it in `accepts`",
                        MessageClass::Command.codes_text()
                    ),
                );
            }
        }
    }
}

/// A component's modes: unique `PascalCase` states, an initial one among them, and
/// unique `snake_case` transitions between known modes.
fn check_modes(cx: &mut Ctx<'_>, c: &Component, m: &ModesDef, ctx: &str) {
    let base = format!("{}.modes", c.path);
    let mut states: HashMap<&str, ()> = HashMap::new();
    for (i, s) in m.states.iter().enumerate() {
        let path = format!("{base}.states[{i}].name");
        if !is_pascal(&s.name) {
            cx.err(
                c.source,
                &path,
                ctx.to_string(),
                format!("mode name `{}` must be PascalCase", s.name),
            );
        }
        if states.insert(&s.name, ()).is_some() {
            cx.err(
                c.source,
                &path,
                ctx.to_string(),
                format!("mode `{}` is defined twice", s.name),
            );
        }
    }
    if m.states.is_empty() {
        cx.err(
            c.source,
            &format!("{base}.states"),
            ctx.to_string(),
            "`modes` needs at least one state",
        );
    }
    if !states.contains_key(m.initial.as_str()) {
        cx.err(
            c.source,
            &format!("{base}.initial"),
            ctx.to_string(),
            format!("initial mode `{}` is not one of `states`", m.initial),
        );
    }
    let mut names: HashMap<&str, ()> = HashMap::new();
    for (i, t) in m.transitions.iter().enumerate() {
        let tp = format!("{base}.transitions[{i}]");
        if !is_snake(&t.name) {
            cx.err(
                c.source,
                &format!("{tp}.name"),
                ctx.to_string(),
                format!("transition name `{}` must be snake_case", t.name),
            );
        }
        if names.insert(&t.name, ()).is_some() {
            cx.err(
                c.source,
                &format!("{tp}.name"),
                ctx.to_string(),
                format!("transition `{}` is defined twice", t.name),
            );
        }
        if t.from.is_empty() {
            cx.err(
                c.source,
                &format!("{tp}.from"),
                ctx.to_string(),
                format!("transition `{}` starts from no mode", t.name),
            );
        }
        for (j, f) in t.from.iter().enumerate() {
            if !states.contains_key(f.as_str()) {
                cx.err(
                    c.source,
                    &format!("{tp}.from[{j}]"),
                    ctx.to_string(),
                    format!("transition `{}` starts from unknown mode `{f}`", t.name),
                );
            }
        }
        if !states.contains_key(t.to.as_str()) {
            cx.err(
                c.source,
                &format!("{tp}.to"),
                ctx.to_string(),
                format!("transition `{}` leads to unknown mode `{}`", t.name, t.to),
            );
        }
        if let Some(core) = &t.core {
            if !MODE_CORE_STATES.contains(&core.as_str()) {
                cx.err(
                    c.source,
                    &format!("{tp}.core"),
                    ctx.to_string(),
                    format!(
                        "transition `{}` may lead the component into {}, not `{core}`",
                        t.name,
                        MODE_CORE_STATES.join(" or ")
                    ),
                );
            }
        }
    }
}
