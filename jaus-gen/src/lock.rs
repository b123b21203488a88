//! The lock file: a [`Snapshot`] written as canonical YAML, one line per field, enum
//! value, bit-field member, union variant and mode transition, so that a change of the
//! wire layout is a one-line diff in review.
//!
//! ```yaml
//! # jaus.lock: wire layout of the JAUS definitions, written by jaus-gen. Commit it.
//! # A build whose definitions differ from it fails and lists the changes; after
//! # reviewing them: JAUS_UPDATE_LOCK=1 cargo build
//! version: 1
//! messages:
//!   - name: SetTravelSpeed
//!     code: 0x040A
//!     fields:
//!       - { name: speed, wire: "scaled u16 [0, 327.67]", unit: "m/s" }
//! types:
//!   - name: ComponentState
//!     kind: enum
//!     repr: u8
//!     values:
//!       - { name: Initialize, value: 0 }
//! components:
//!   - name: GlobalWaypointDriver
//!     id: 45
//!     commands: [SetGlobalWaypoint, SetTravelSpeed]
//! ```
//!
//! A set with services (AS-4) also pins them: `services:` holds each service's URI,
//! version and parent, the guards and actions of its generated trait, its states and
//! one line per transition (see the `services` part below).
//!
//! [`to_text`] writes it, [`parse`] reads it back into a [`Snapshot`] whose positions
//! are the lock file's own lines.

mod services;

use crate::snapshot::*;
use jaus_spec::location::LocationIndex;
use jaus_spec::{Bits, Code, Int, TypeKind};
use serde::Deserialize;
use std::fmt::Write as _;

/// Version of the lock file format.
pub const LOCK_VERSION: u32 = 1;

/// The environment variable that makes a build rewrite its lock file.
pub const UPDATE_ENV: &str = "JAUS_UPDATE_LOCK";

/// The command that rewrites a crate's lock file after a reviewed change.
pub const UPDATE_COMMAND: &str = "JAUS_UPDATE_LOCK=1 cargo build";

/// What the build says while a crate's lock file does not exist: the layout is not
/// pinned, nothing is checked, and how to pin it.
pub fn unpinned_note(path: &std::path::Path) -> String {
    format!(
        "{p}: the wire layout is not pinned yet, so the definitions are not checked and \
         may change freely.\n\
         When they are ready for peers, pin the layout and commit {p}:\n    {UPDATE_COMMAND}\n\
         From then on every change of the wire layout fails the build until reviewed.",
        p = path.display()
    )
}

/// A double-quoted YAML scalar (JSON string escapes are valid YAML).
fn quoted(s: &str) -> String {
    let mut o = String::with_capacity(s.len() + 2);
    o.push('"');
    for c in s.chars() {
        match c {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(o, "\\u{:04x}", c as u32);
            }
            c => o.push(c),
        }
    }
    o.push('"');
    o
}

/// A name as a YAML scalar: plain when it is an identifier YAML reads as a string,
/// quoted otherwise (`null`, `true`, a leading digit).
fn name(s: &str) -> String {
    let plain = s.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && !matches!(
            s.to_ascii_lowercase().as_str(),
            "null" | "true" | "false" | "y" | "n" | "yes" | "no" | "on" | "off"
        );
    if plain {
        s.to_string()
    } else {
        quoted(s)
    }
}

fn field_line(f: &FieldSnap) -> String {
    let mut s = format!(
        "{{ name: {}, wire: {}",
        name(&f.name),
        quoted(&wire_text(&f.wire))
    );
    if let Some(u) = &f.unit {
        let _ = write!(s, ", unit: {}", quoted(u));
    }
    if let Some(b) = f.bit {
        let _ = write!(s, ", bit: {b}");
    }
    if let Some(p) = &f.present_if {
        let _ = write!(s, ", present_if: {}", name(p));
    }
    s.push_str(" }");
    s
}

fn fields_block(out: &mut String, indent: &str, fields: &[FieldSnap]) {
    if fields.is_empty() {
        return;
    }
    let _ = writeln!(out, "{indent}fields:");
    for f in fields {
        let _ = writeln!(out, "{indent}  - {}", field_line(f));
    }
}

/// The body of a type (everything but its name) as written in the lock file; two types
/// with the same body have the same wire layout.
pub(crate) fn type_body(form: &FormSnap) -> String {
    let mut out = String::new();
    let i = "    ";
    let _ = writeln!(out, "{i}kind: {}", kind_name(form.kind()));
    match form {
        FormSnap::Record { presence, fields } => {
            if let Some(p) = presence {
                let _ = writeln!(out, "{i}presence: {}", p.rust());
            }
            fields_block(&mut out, i, fields);
        }
        FormSnap::Enum { repr, values } => {
            let _ = writeln!(out, "{i}repr: {}", repr.rust());
            let _ = writeln!(out, "{i}values:");
            for v in values {
                let _ = writeln!(
                    out,
                    "{i}  - {{ name: {}, value: {} }}",
                    name(&v.name),
                    v.value
                );
            }
        }
        FormSnap::Bitfield { repr, members } => {
            let _ = writeln!(out, "{i}repr: {}", repr.rust());
            let _ = writeln!(out, "{i}bits:");
            for m in members {
                let bits = match m.bits {
                    Bits::Flag(b) => format!("bit: {b}"),
                    Bits::Range { lo, hi } => format!("bits: [{lo}, {hi}]"),
                };
                let _ = writeln!(out, "{i}  - {{ name: {}, {bits} }}", name(&m.name));
            }
        }
        FormSnap::Union { repr, variants } => {
            let _ = writeln!(out, "{i}repr: {}", repr.rust());
            let _ = writeln!(out, "{i}variants:");
            for v in variants {
                match &v.wire {
                    Some(w) => {
                        let _ = writeln!(
                            out,
                            "{i}  - {{ name: {}, tag: {}, wire: {} }}",
                            name(&v.name),
                            v.tag,
                            quoted(&wire_text(w))
                        );
                    }
                    None => {
                        let _ =
                            writeln!(out, "{i}  - {{ name: {}, tag: {} }}", name(&v.name), v.tag);
                    }
                }
            }
        }
    }
    out
}

fn name_list(names: &[Entry]) -> String {
    let v: Vec<String> = names.iter().map(|e| name(&e.name)).collect();
    format!("[{}]", v.join(", "))
}

/// The lock file text of a snapshot: canonical, so the same layout always gives the same
/// bytes.
pub fn to_text(s: &Snapshot) -> String {
    let mut out = String::new();
    out.push_str(
        "# Wire layout of the JAUS definitions this crate is built from, written by jaus-gen.\n\
         # Commit it. A build whose definitions differ from it fails and lists every change;\n",
    );
    let _ = writeln!(
        out,
        "# after reviewing them, update it with: {UPDATE_COMMAND}"
    );
    let _ = writeln!(out, "version: {LOCK_VERSION}");
    if s.messages.is_empty() {
        out.push_str("messages: []\n");
    } else {
        out.push_str("messages:\n");
    }
    for m in &s.messages {
        let _ = writeln!(out, "  - name: {}", name(&m.name));
        let _ = writeln!(out, "    code: 0x{:04X}", m.code);
        if let Some(p) = m.presence {
            let _ = writeln!(out, "    presence: {}", p.rust());
        }
        fields_block(&mut out, "    ", &m.fields);
    }
    if s.types.is_empty() {
        out.push_str("types: []\n");
    } else {
        out.push_str("types:\n");
    }
    for t in &s.types {
        let _ = writeln!(out, "  - name: {}", name(&t.name));
        out.push_str(&type_body(&t.form));
    }
    if s.components.is_empty() {
        out.push_str("components: []\n");
    } else {
        out.push_str("components:\n");
    }
    for c in &s.components {
        let _ = writeln!(out, "  - name: {}", name(&c.name));
        let _ = writeln!(out, "    id: {}", c.id);
        if c.any_message {
            out.push_str("    any_message: true\n");
        }
        for (key, list) in [
            ("commands", &c.commands),
            ("accepts", &c.accepts),
            ("emits", &c.emits),
        ] {
            if !list.is_empty() {
                let _ = writeln!(out, "    {key}: {}", name_list(list));
            }
        }
        if let Some(m) = &c.modes {
            out.push_str("    modes:\n");
            let _ = writeln!(out, "      initial: {}", name(&m.initial.name));
            let _ = writeln!(out, "      states: {}", name_list(&m.states));
            if !m.transitions.is_empty() {
                out.push_str("      transitions:\n");
            }
            for t in &m.transitions {
                let from: Vec<String> = t.from.iter().map(|f| name(f)).collect();
                let _ = write!(
                    out,
                    "        - {{ name: {}, from: [{}], to: {}",
                    name(&t.name),
                    from.join(", "),
                    name(&t.to)
                );
                if let Some(core) = &t.core {
                    let _ = write!(out, ", core: {}", name(core));
                }
                out.push_str(" }\n");
            }
        }
    }
    services::write(&mut out, &s.services);
    out
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockFile {
    version: u32,
    #[serde(default)]
    messages: Vec<LockMessage>,
    #[serde(default)]
    types: Vec<LockType>,
    #[serde(default)]
    components: Vec<LockComponent>,
    #[serde(default)]
    services: Vec<services::LockService>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockMessage {
    name: String,
    code: Code,
    #[serde(default)]
    presence: Option<String>,
    #[serde(default)]
    fields: Vec<LockField>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockField {
    name: String,
    wire: String,
    #[serde(default)]
    unit: Option<String>,
    #[serde(default)]
    bit: Option<u32>,
    #[serde(default)]
    present_if: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockType {
    name: String,
    kind: TypeKind,
    #[serde(default)]
    repr: Option<String>,
    #[serde(default)]
    presence: Option<String>,
    #[serde(default)]
    fields: Vec<LockField>,
    #[serde(default)]
    values: Vec<LockValue>,
    #[serde(default)]
    bits: Vec<LockBits>,
    #[serde(default)]
    variants: Vec<LockVariant>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockValue {
    name: String,
    value: u64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockBits {
    name: String,
    #[serde(default)]
    bit: Option<u32>,
    #[serde(default)]
    bits: Option<[u32; 2]>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockVariant {
    name: String,
    tag: u64,
    #[serde(default)]
    wire: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockComponent {
    name: String,
    id: u8,
    #[serde(default)]
    any_message: bool,
    #[serde(default)]
    commands: Vec<String>,
    #[serde(default)]
    accepts: Vec<String>,
    #[serde(default)]
    emits: Vec<String>,
    #[serde(default)]
    modes: Option<LockModes>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockModes {
    initial: String,
    states: Vec<String>,
    #[serde(default)]
    transitions: Vec<LockTransition>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockTransition {
    name: String,
    from: Vec<String>,
    to: String,
    #[serde(default)]
    core: Option<String>,
}

/// Reads a lock file's text (`file` is the name used in positions and errors). An error
/// is `file:line:column: what`.
pub fn parse(text: &str, file: &str) -> Result<Snapshot, String> {
    let index = LocationIndex::build(text);
    let at = |path: &str| {
        let p = index.find(path);
        Loc {
            file: file.to_string(),
            line: p.line,
            col: p.column,
        }
    };
    let err = |path: &str, msg: String| {
        let l = at(path);
        format!("{}:{}:{}: {msg}", l.file, l.line, l.col)
    };
    let lock: LockFile = serde_yaml::from_str(text).map_err(|e| {
        let (line, col) = e.location().map_or((1, 1), |l| (l.line(), l.column()));
        let msg = e.to_string();
        let msg = msg.split(" at line ").next().unwrap_or(&msg).to_string();
        format!("{file}:{line}:{col}: not a jaus-gen lock file: {msg}")
    })?;
    if lock.version != LOCK_VERSION {
        return Err(err(
            "version",
            format!(
                "lock file version {} is not {LOCK_VERSION}: rewrite it with `{UPDATE_COMMAND}`",
                lock.version
            ),
        ));
    }
    let int = |path: &str, s: &Option<String>| -> Result<Option<Int>, String> {
        match s {
            None => Ok(None),
            Some(s) => Int::parse(s)
                .map(Some)
                .ok_or_else(|| err(path, format!("`{s}` is not an integer type"))),
        }
    };
    let fields = |owner: &str, fs: Vec<LockField>| -> Result<Vec<FieldSnap>, String> {
        fs.into_iter()
            .enumerate()
            .map(|(i, f)| {
                let path = format!("{owner}.fields[{i}]");
                Ok(FieldSnap {
                    wire: parse_wire(&f.wire).map_err(|e| err(&format!("{path}.wire"), e))?,
                    name: f.name,
                    bit: f.bit,
                    present_if: f.present_if,
                    unit: f.unit,
                    at: at(&path),
                })
            })
            .collect()
    };
    let mut snap = Snapshot::default();
    for (i, m) in lock.messages.into_iter().enumerate() {
        let path = format!("messages[{i}]");
        snap.messages.push(MessageSnap {
            name: m.name,
            code: m.code.0,
            presence: int(&format!("{path}.presence"), &m.presence)?,
            fields: fields(&path, m.fields)?,
            at: at(&path),
        });
    }
    for (i, t) in lock.types.into_iter().enumerate() {
        let path = format!("types[{i}]");
        let repr = || {
            int(&format!("{path}.repr"), &t.repr)?
                .ok_or_else(|| err(&path, format!("type `{}` needs `repr`", t.name)))
        };
        let form = match t.kind {
            TypeKind::Record => FormSnap::Record {
                presence: int(&format!("{path}.presence"), &t.presence)?,
                fields: fields(&path, t.fields)?,
            },
            TypeKind::Enum => FormSnap::Enum {
                repr: repr()?,
                values: t
                    .values
                    .into_iter()
                    .enumerate()
                    .map(|(j, v)| ValueSnap {
                        name: v.name,
                        value: v.value,
                        at: at(&format!("{path}.values[{j}]")),
                    })
                    .collect(),
            },
            TypeKind::Bitfield => FormSnap::Bitfield {
                repr: repr()?,
                members: t
                    .bits
                    .into_iter()
                    .enumerate()
                    .map(|(j, b)| {
                        let p = format!("{path}.bits[{j}]");
                        let bits = match (b.bit, b.bits) {
                            (Some(n), None) => Bits::Flag(n),
                            (None, Some([lo, hi])) => Bits::Range { lo, hi },
                            _ => return Err(err(&p, "give `bit` or `bits`".into())),
                        };
                        Ok(MemberSnap {
                            name: b.name,
                            bits,
                            at: at(&p),
                        })
                    })
                    .collect::<Result<_, String>>()?,
            },
            TypeKind::Union => FormSnap::Union {
                repr: repr()?,
                variants: t
                    .variants
                    .into_iter()
                    .enumerate()
                    .map(|(j, v)| {
                        let p = format!("{path}.variants[{j}]");
                        Ok(VariantSnap {
                            wire: v
                                .wire
                                .as_deref()
                                .map(parse_wire)
                                .transpose()
                                .map_err(|e| err(&format!("{p}.wire"), e))?,
                            name: v.name,
                            tag: v.tag,
                            at: at(&p),
                        })
                    })
                    .collect::<Result<_, String>>()?,
            },
        };
        snap.types.push(TypeSnap {
            name: t.name,
            form,
            at: at(&path),
        });
    }
    for (i, c) in lock.components.into_iter().enumerate() {
        let path = format!("components[{i}]");
        let list = |key: &str, names: Vec<String>| -> Vec<Entry> {
            names
                .into_iter()
                .enumerate()
                .map(|(j, name)| Entry {
                    name,
                    at: at(&format!("{path}.{key}[{j}]")),
                })
                .collect()
        };
        let modes = c.modes.map(|m| {
            let base = format!("{path}.modes");
            ModesSnap {
                initial: Entry {
                    name: m.initial,
                    at: at(&format!("{base}.initial")),
                },
                states: m
                    .states
                    .into_iter()
                    .enumerate()
                    .map(|(j, name)| Entry {
                        name,
                        at: at(&format!("{base}.states[{j}]")),
                    })
                    .collect(),
                transitions: m
                    .transitions
                    .into_iter()
                    .enumerate()
                    .map(|(j, t)| TransitionSnap {
                        name: t.name,
                        from: t.from,
                        to: t.to,
                        core: t.core,
                        at: at(&format!("{base}.transitions[{j}]")),
                    })
                    .collect(),
            }
        });
        snap.components.push(ComponentSnap {
            commands: list("commands", c.commands),
            accepts: list("accepts", c.accepts),
            emits: list("emits", c.emits),
            name: c.name,
            id: c.id,
            any_message: c.any_message,
            modes,
            at: at(&path),
        });
    }
    snap.services = services::read(lock.services, &at, &err)?;
    Ok(snap)
}
