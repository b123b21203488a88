//! The SDK groups (cargo features of `jaus`) a vendor overlay's own items need.

use jaus_spec::{Field, Spec, Wire};
use serde::Serialize;

/// An SDK group (cargo feature of `jaus`) a vendor's items need.
#[derive(Debug, Clone, Serialize)]
pub struct RequireCtx {
    /// Group (and feature) name.
    pub group: String,
    /// Where and why, for the compile error when the feature is off.
    pub why: String,
}

/// The SDK groups (other than `core`, which is always built) whose types the
/// overlay's own types and messages use, each with its first use.
pub fn requirements(spec: &Spec) -> Vec<RequireCtx> {
    fn walk<'a>(w: &'a Wire, out: &mut Vec<&'a str>) {
        match w {
            Wire::Named { name, .. } => out.push(name),
            Wire::List { elem, .. } | Wire::ListField { elem, .. } => walk(elem, out),
            _ => {}
        }
    }
    let mut req: Vec<RequireCtx> = Vec::new();
    let mut add = |group: &str, why: String| {
        if group != "core" && !req.iter().any(|r| r.group == group) {
            req.push(RequireCtx {
                group: group.to_string(),
                why,
            });
        }
    };
    let mut uses = |owner: String, source: usize, path: &str, fields: &[Field]| {
        for (i, f) in fields.iter().enumerate() {
            let mut names = Vec::new();
            walk(&f.wire, &mut names);
            for n in names {
                let Some(t) = spec.types.iter().find(|t| t.def.name == n) else {
                    continue;
                };
                if spec.is_own(t.source) {
                    continue;
                }
                let (file, pos) = spec.locate(source, &format!("{path}.fields[{i}]"));
                add(
                    &t.group,
                    format!(
                        "{}:{}:{}: {owner}, field `{}` uses `{n}` of group `{}`",
                        file.display(),
                        pos.line,
                        pos.column,
                        f.def.name,
                        t.group
                    ),
                );
            }
        }
    };
    for t in spec.types.iter().filter(|t| spec.is_own(t.source)) {
        uses(
            format!("type `{}`", t.def.name),
            t.source,
            &t.path,
            t.fields(),
        );
    }
    for m in spec.messages.iter().filter(|m| spec.is_own(m.source)) {
        uses(
            format!("message `{}`", m.def.name),
            m.source,
            &m.path,
            &m.fields,
        );
    }
    for c in spec.components.iter().filter(|c| spec.is_own(c.source)) {
        let d = &c.def;
        for (key, list) in [
            ("commands", &d.commands),
            ("accepts", &d.accepts),
            ("emits", &d.emits),
        ] {
            for (i, n) in list.iter().enumerate() {
                let Some(m) = spec.message(n) else { continue };
                if spec.is_own(m.source) {
                    continue;
                }
                let (file, pos) = spec.locate(c.source, &format!("{}.{key}[{i}]", c.path));
                add(
                    &m.group,
                    format!(
                        "{}:{}:{}: component `{}` uses message `{n}` of group `{}`",
                        file.display(),
                        pos.line,
                        pos.column,
                        d.name,
                        m.group
                    ),
                );
            }
        }
    }
    req
}
