//! Reference documentation of a message set: one Markdown page per group and an index,
//! rendered from `templates/docs/`.

use crate::error::Error;
use jaus_spec::{Bits, Field, Len, Spec, Type, TypeForm, Wire};
use minijinja::Environment;
use serde::Serialize;
use std::path::{Path, PathBuf};

/// Templates of the documentation (from the crate's `templates/docs/`).
pub const DOC_TEMPLATES: &[(&str, &str)] = &[
    ("group.md.j2", include_str!("../templates/docs/group.md.j2")),
    ("index.md.j2", include_str!("../templates/docs/index.md.j2")),
];

#[derive(Debug, Serialize)]
struct DocField {
    name: String,
    ty: String,
    unit: String,
    range: String,
    presence: String,
    description: String,
}

#[derive(Debug, Serialize)]
struct DocItem {
    name: String,
    code: String,
    title: String,
    kind: String,
    description: String,
    report: String,
    presence: String,
    fields: Vec<DocField>,
    values: Vec<(String, String, String)>,
}

#[derive(Debug, Serialize)]
struct DocGroup {
    name: String,
    title: String,
    description: String,
    messages: Vec<DocItem>,
    types: Vec<DocItem>,
}

fn one_line(s: Option<&str>) -> String {
    s.unwrap_or("")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
        .replace('|', "\\|")
}

fn type_link(spec: &Spec, name: &str, here: &str) -> String {
    match spec.ty(name) {
        Some(t) if t.group == here => format!("[{name}](#{})", name.to_lowercase()),
        Some(t) => format!("[{name}]({}.md#{})", t.group, name.to_lowercase()),
        None => name.to_string(),
    }
}

fn len_text(len: &Len, what: &str) -> String {
    match len {
        Len::Fixed { n, .. } => format!("{what} ({n} bytes)"),
        Len::Prefix(i) => format!("{what} (length {})", i.rust()),
        Len::Rest { nul: true } => format!("{what} (to end, NUL-terminated)"),
        Len::Rest { nul: false } => format!("{what} (to end)"),
        Len::Nul => format!("{what} (NUL-terminated)"),
    }
}

fn wire_text(spec: &Spec, w: &Wire, here: &str) -> (String, String) {
    match w {
        Wire::Int(i) => (i.rust().into(), String::new()),
        Wire::F32 => ("f32".into(), String::new()),
        Wire::F64 => ("f64".into(), String::new()),
        Wire::Scaled { int, lo, hi } => {
            let d = int.divisor();
            (
                format!("scaled {}", int.rust()),
                format!("[{lo}, {hi}], step {:.3e}", (hi - lo) / d),
            )
        }
        Wire::Named {
            name,
            size,
            tag_field,
            ..
        } => {
            let t = type_link(spec, name, here);
            let t = tag_field
                .as_ref()
                .map_or(t.clone(), |f| format!("{t} (tag in `{f}`)"));
            (
                size.map_or(t.clone(), |s| format!("{t} (size {})", s.rust())),
                String::new(),
            )
        }
        Wire::Str(len) => (len_text(len, "string"), String::new()),
        Wire::Bytes(len) => (len_text(len, "bytes"), String::new()),
        Wire::List { count, elem } => {
            let (e, r) = wire_text(spec, elem, here);
            let c = count.map_or("to end".to_string(), |c| format!("count {}", c.rust()));
            (format!("list of {e} ({c})"), r)
        }
        Wire::ListField {
            field,
            elem,
            offsets_of,
        } => {
            let (e, r) = wire_text(spec, elem, here);
            let extra = offsets_of
                .as_ref()
                .map_or(String::new(), |t| format!(", byte offsets of `{t}`"));
            (format!("list of {e} (count in `{field}`{extra})"), r)
        }
        Wire::Flag => ("flag (no bytes)".into(), String::new()),
        Wire::Packet { size } => (
            size.map_or("JAUS message with header".into(), |s| {
                format!("JAUS message with header (size {})", s.rust())
            }),
            String::new(),
        ),
    }
}

fn doc_fields(spec: &Spec, fields: &[Field], here: &str) -> Vec<DocField> {
    fields
        .iter()
        .map(|field| {
            let (ty, range) = wire_text(spec, &field.wire, here);
            let f = &field.def;
            let presence = match (f.bit, &f.present_if) {
                (Some(b), _) => format!("bit {b}"),
                (None, Some(p)) => format!("if `{p}`"),
                _ => String::new(),
            };
            let mut description = one_line(f.description.as_deref());
            if let Some(c) = &f.code_field {
                description.push_str(&format!(
                    " (message code in `{c}`{})",
                    if f.complement { ", complement" } else { "" }
                ));
            }
            if f.embeds.is_some() {
                description.push_str(" (a message: its 16-bit ID, then its body");
                if let Some(c) = &f.embeds_if {
                    description.push_str(&format!(", when `{c}`"));
                }
                description.push(')');
            }
            DocField {
                name: f.name.clone(),
                ty,
                unit: f.unit.clone().unwrap_or_default(),
                range,
                presence,
                description,
            }
        })
        .collect()
}

/// The reference entry of a named type of group `here`.
fn doc_type(spec: &Spec, t: &Type, here: &str) -> DocItem {
    let d = &t.def;
    let values = match &t.form {
        TypeForm::Enum { .. } => d
            .values
            .iter()
            .map(|v| {
                (
                    v.value.to_string(),
                    v.name.clone(),
                    one_line(v.description.as_deref()),
                )
            })
            .collect(),
        TypeForm::Bitfield { members, .. } => members
            .iter()
            .map(|b| {
                let at = match b.bits {
                    Bits::Flag(x) => x.to_string(),
                    Bits::Range { lo, hi } => format!("{lo}–{hi}"),
                };
                (
                    at,
                    b.def.name.clone(),
                    one_line(b.def.description.as_deref()),
                )
            })
            .collect(),
        TypeForm::Union { variants, .. } => variants
            .iter()
            .map(|v| {
                let ty = v
                    .wire
                    .as_ref()
                    .map_or("(none)".to_string(), |w| wire_text(spec, w, here).0);
                (
                    v.def.tag.to_string(),
                    format!("{} — {ty}", v.def.name),
                    one_line(v.def.description.as_deref()),
                )
            })
            .collect(),
        TypeForm::Record { .. } => Vec::new(),
    };
    DocItem {
        name: d.name.clone(),
        code: String::new(),
        title: d.name.clone(),
        kind: format!("{:?}", d.kind).to_lowercase(),
        description: one_line(d.description.as_deref()),
        report: String::new(),
        presence: d
            .presence
            .clone()
            .unwrap_or_else(|| d.repr.clone().unwrap_or_default()),
        fields: doc_fields(spec, t.fields(), here),
        values,
    }
}

/// Renders the documentation pages of `spec` into `out` (`index.md` and one page per
/// group); returns the files written.
pub fn render_docs(spec: &Spec, out: &Path) -> Result<Vec<PathBuf>, Error> {
    let mut env = Environment::new();
    env.set_trim_blocks(true);
    env.set_lstrip_blocks(true);
    env.set_undefined_behavior(minijinja::UndefinedBehavior::Strict);
    for (name, text) in DOC_TEMPLATES {
        env.add_template(name, text)?;
    }
    let mut groups = Vec::new();
    for g in &spec.groups {
        let messages = spec
            .messages
            .iter()
            .filter(|m| m.group == g.name)
            .map(|m| DocItem {
                name: m.def.name.clone(),
                code: m.def.code.to_string(),
                title: m
                    .def
                    .title
                    .clone()
                    .unwrap_or_else(|| jaus_spec::title_of(&m.def.name)),
                kind: if m.def.experimental {
                    "experimental".into()
                } else {
                    String::new()
                },
                description: one_line(m.def.description.as_deref()),
                report: spec
                    .report_of(&m.def)
                    .map(|r| r.def.name.clone())
                    .unwrap_or_default(),
                presence: m.def.presence.clone().unwrap_or_default(),
                fields: doc_fields(spec, &m.fields, &g.name),
                values: Vec::new(),
            })
            .collect();
        let types = spec
            .types
            .iter()
            .filter(|t| t.group == g.name)
            .map(|t| doc_type(spec, t, &g.name))
            .collect();
        groups.push(DocGroup {
            name: g.name.clone(),
            title: g.title.clone(),
            description: one_line(g.description.as_deref()),
            messages,
            types,
        });
    }
    std::fs::create_dir_all(out).map_err(|source| Error::Io {
        path: out.to_path_buf(),
        source,
    })?;
    let mut files = Vec::new();
    let mut by_code: Vec<(String, String, String, String)> = groups
        .iter()
        .flat_map(|g| {
            g.messages.iter().map(|m| {
                (
                    m.code.clone(),
                    m.title.clone(),
                    m.name.to_lowercase(),
                    g.name.clone(),
                )
            })
        })
        .collect();
    by_code.sort();
    let titles: std::collections::HashMap<&str, &str> = groups
        .iter()
        .map(|g| (g.name.as_str(), g.title.as_str()))
        .collect();
    let by_code: Vec<_> = by_code
        .into_iter()
        .map(|(code, title, anchor, group)| {
            let group_title = titles
                .get(group.as_str())
                .copied()
                .unwrap_or_default()
                .to_string();
            minijinja::context! { code, title, anchor, group, group_title }
        })
        .collect();
    let index = env
        .get_template("index.md.j2")?
        .render(minijinja::context! { groups => &groups, by_code => by_code })?;
    let p = out.join("index.md");
    crate::output::write_if_changed(&p, &index)?;
    files.push(p);
    for g in &groups {
        let page = env
            .get_template("group.md.j2")?
            .render(minijinja::context! { group => g })?;
        let p = out.join(format!("{}.md", g.name));
        crate::output::write_if_changed(&p, &page)?;
        files.push(p);
    }
    Ok(files)
}
