//! Parts shared by component interfaces (`parts:` of a file, `parts: [Name]` of a
//! component): a part names messages that several components handle alike, and every
//! component that shares it lists those messages in the same role.

use super::names::is_pascal;
use super::Ctx;
use crate::resolved::{Component, Part};
use std::collections::HashMap;

/// Names a part may not take: its accessor method (`snake_case` of the name) would be
/// one of the methods every component trait has.
const HOOKS: &[&str] = &[
    "Initialize",
    "StateChanged",
    "Tick",
    "Stop",
    "OnOtherMessage",
];

/// Every part ([`check_part`]) and every component's `parts` ([`check_shares`]); a part
/// no component shares is reported too.
pub(super) fn check_parts(cx: &mut Ctx<'_>) {
    let spec = cx.spec;
    let mut names: HashMap<&str, ()> = HashMap::new();
    for p in &spec.parts {
        check_part(cx, p, &mut names);
    }
    for c in &spec.components {
        check_shares(cx, c);
    }
    for p in &spec.parts {
        let shared = spec
            .components
            .iter()
            .any(|c| c.def.parts.contains(&p.def.name));
        if !shared {
            cx.err(
                p.source,
                &format!("{}.name", p.path),
                format!("part `{}`", p.def.name),
                "no component shares this part: add it to the `parts` of the components that handle its messages, or remove it",
            );
        }
    }
}

/// The name is `PascalCase`, not taken by another part, component or message, nor one
/// whose accessor would clash with a method of the component traits; the messages
/// exist, each in one list once; `optional` names entries of `commands` or `accepts`;
/// the part has at least one message.
fn check_part<'s>(cx: &mut Ctx<'_>, p: &'s Part, names: &mut HashMap<&'s str, ()>) {
    let spec = cx.spec;
    let d = &p.def;
    let ctx = format!("part `{}`", d.name);
    let name_at = format!("{}.name", p.path);
    if !is_pascal(&d.name) {
        cx.err(
            p.source,
            &name_at,
            ctx.clone(),
            "part name must be PascalCase",
        );
    } else if HOOKS.contains(&d.name.as_str())
        || (d.name.starts_with("On") && d.name[2..].starts_with(|c: char| c.is_ascii_uppercase()))
    {
        cx.err(
            p.source,
            &name_at,
            ctx.clone(),
            format!(
                "`{}` would clash with a method of the component traits: choose another name",
                d.name
            ),
        );
    }
    let taken = names.insert(&d.name, ()).is_some()
        || spec.message(&d.name).is_some()
        || spec.components.iter().any(|c| c.def.name == d.name);
    if taken {
        cx.err(
            p.source,
            &name_at,
            ctx.clone(),
            format!("name `{}` is already used", d.name),
        );
    }
    let mut seen: HashMap<&str, &str> = HashMap::new();
    for (key, list) in [
        ("commands", &d.commands),
        ("accepts", &d.accepts),
        ("emits", &d.emits),
    ] {
        for (i, name) in list.iter().enumerate() {
            let path = format!("{}.{key}[{i}]", p.path);
            if spec.message(name).is_none() {
                cx.err(
                    p.source,
                    &path,
                    ctx.clone(),
                    format!("`{key}` names unknown message `{name}`"),
                );
                continue;
            }
            if key == "emits" {
                continue;
            }
            if let Some(prev) = seen.insert(&**name, key) {
                cx.err(
                    p.source,
                    &path,
                    ctx.clone(),
                    format!("`{name}` is already listed in `{prev}`"),
                );
            }
        }
    }
    for (i, name) in d.optional.iter().enumerate() {
        if !seen.contains_key(&**name) {
            cx.err(
                p.source,
                &format!("{}.optional[{i}]", p.path),
                ctx.clone(),
                format!("`{name}` is not in the part's `commands` or `accepts`: only those may be optional"),
            );
        }
    }
    if d.commands.is_empty() && d.accepts.is_empty() {
        cx.err(
            p.source,
            &name_at,
            ctx,
            "a part has messages to handle: list them in `commands` or `accepts`",
        );
    }
}

/// Each part a component names exists (in the base definitions, or in the same set as
/// the component), once; the component is no `any_message` one; it lists every
/// message of the part in the part's role (the optional ones, if it lists them at all);
/// no message belongs to two of its parts.
fn check_shares(cx: &mut Ctx<'_>, c: &Component) {
    let spec = cx.spec;
    let d = &c.def;
    let ctx = format!("component `{}`", d.name);
    let mut owner: HashMap<&str, &str> = HashMap::new();
    for (i, name) in d.parts.iter().enumerate() {
        let path = format!("{}.parts[{i}]", c.path);
        if d.parts[..i].contains(name) {
            cx.err(
                c.source,
                &path,
                ctx.clone(),
                format!("part `{name}` is listed twice"),
            );
            continue;
        }
        let part = spec.parts.iter().find(|p| p.def.name == *name);
        let Some(part) =
            part.filter(|p| p.source < spec.base_sources || c.source >= spec.base_sources)
        else {
            cx.err(
                c.source,
                &path,
                ctx.clone(),
                format!("unknown part `{name}`"),
            );
            continue;
        };
        if d.any_message {
            cx.err(
                c.source,
                &path,
                ctx.clone(),
                "a component with `any_message: true` receives everything in `on_other_message`: it shares no part",
            );
            continue;
        }
        let p = &part.def;
        for (key, list, own) in [
            ("commands", &p.commands, &d.commands),
            ("accepts", &p.accepts, &d.accepts),
            ("emits", &p.emits, &d.emits),
        ] {
            for m in list {
                if own.contains(m) {
                    if key == "emits" {
                        continue;
                    }
                    if let Some(other) = owner.insert(m.as_str(), name.as_str()) {
                        cx.err(
                            c.source,
                            &path,
                            ctx.clone(),
                            format!("`{m}` belongs to both part `{other}` and part `{name}`: a message is handled by one part"),
                        );
                    }
                    continue;
                }
                if p.optional.contains(m) {
                    let elsewhere = [("commands", &d.commands), ("accepts", &d.accepts)]
                        .into_iter()
                        .find(|(_, l)| l.contains(m));
                    if let Some((k, _)) = elsewhere {
                        cx.err(
                            c.source,
                            &path,
                            ctx.clone(),
                            format!("`{m}` is in the component's `{k}` but in part `{name}`'s `{key}`: list it in `{key}`"),
                        );
                    }
                    continue;
                }
                cx.err(
                    c.source,
                    &path,
                    ctx.clone(),
                    format!("part `{name}` has `{m}` in `{key}`, which the component's `{key}` does not list: add it there"),
                );
            }
        }
    }
}
