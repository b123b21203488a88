//! The wire layout of a definition set: what [`crate::diff`] compares and what a lock
//! file stores.
//!
//! A [`Snapshot`] keeps, for every message, named type and component interface, only
//! what decides the bytes on the wire and the shape of the generated Rust: names, command
//! codes, presence vector types, fields in wire order with their resolved
//! [`Wire`] form, presence bit, `present_if` and unit, enum values, bit-field members,
//! union variants, and the messages and modes of each component. Descriptions, titles
//! and group names are left out: they change no byte. Services (AS-4) keep their URI,
//! version and parent, the guard and action methods of their generated traits, and their
//! states and transitions ([`ServiceSnap`]). Every item carries where it is defined
//! ([`Loc`]): in the YAML for a snapshot of a [`Spec`], in the JSIDL files for a set
//! imported from JSIDL ([`Snapshot::from_jsidl`]: the YAML of an import exists only in
//! memory), in the lock file for one read from a lock.
//!
//! Snapshots are canonical: messages are sorted by command code, types and components by
//! name, enum values by value, bit-field members by their lowest bit, union variants by
//! tag, and a component's messages and modes by name. Fields keep their wire order.

mod jsidl;
mod services;

pub use jsidl::JsidlPositions;
pub use services::{MethodSnap, ServiceSnap, StateSnap, TransSnap};

use jaus_spec::{Bits, CountRef, Int, Len, Spec, TypeForm, TypeKind, Wire};
use serde::Serialize;
use std::fmt;
use std::path::Path;

/// Where an item is defined: a file (its name only, as printed) and a 1-based line and
/// column.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub struct Loc {
    /// File name, e.g. `platform.yaml` or `jaus.lock`.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub col: usize,
}

impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.file, self.line)
    }
}

/// The wire layout of a whole definition set.
#[derive(Debug, Clone, Default)]
pub struct Snapshot {
    /// Messages, by command code.
    pub messages: Vec<MessageSnap>,
    /// Named types, by name.
    pub types: Vec<TypeSnap>,
    /// Component interfaces, by name.
    pub components: Vec<ComponentSnap>,
    /// Services (AS-4 service sets), by name.
    pub services: Vec<ServiceSnap>,
}

/// A message.
#[derive(Debug, Clone)]
pub struct MessageSnap {
    /// Its name.
    pub name: String,
    /// Its command code.
    pub code: u16,
    /// Presence vector type.
    pub presence: Option<Int>,
    /// Fields in wire order.
    pub fields: Vec<FieldSnap>,
    /// Where it is defined.
    pub at: Loc,
}

/// A field of a message or record.
#[derive(Debug, Clone)]
pub struct FieldSnap {
    /// Its name.
    pub name: String,
    /// Its wire form.
    pub wire: Wire,
    /// Presence bit.
    pub bit: Option<u32>,
    /// The flag or integer field it is present by.
    pub present_if: Option<String>,
    /// Unit of the real value.
    pub unit: Option<String>,
    /// Where it is defined.
    pub at: Loc,
}

/// A named type.
#[derive(Debug, Clone)]
pub struct TypeSnap {
    /// Its name.
    pub name: String,
    /// What it is.
    pub form: FormSnap,
    /// Where it is defined.
    pub at: Loc,
}

/// The form of a named type, by kind.
#[derive(Debug, Clone)]
pub enum FormSnap {
    /// A sequence of fields.
    Record {
        /// Presence vector type.
        presence: Option<Int>,
        /// Fields in wire order.
        fields: Vec<FieldSnap>,
    },
    /// Named values.
    Enum {
        /// Integer type.
        repr: Int,
        /// Values, by value.
        values: Vec<ValueSnap>,
    },
    /// Named bits.
    Bitfield {
        /// Integer type.
        repr: Int,
        /// Members, by lowest bit.
        members: Vec<MemberSnap>,
    },
    /// A tag and the value it selects.
    Union {
        /// Tag type.
        repr: Int,
        /// Variants, by tag.
        variants: Vec<VariantSnap>,
    },
}

impl FormSnap {
    /// The kind of type.
    pub fn kind(&self) -> TypeKind {
        match self {
            FormSnap::Record { .. } => TypeKind::Record,
            FormSnap::Enum { .. } => TypeKind::Enum,
            FormSnap::Bitfield { .. } => TypeKind::Bitfield,
            FormSnap::Union { .. } => TypeKind::Union,
        }
    }
}

/// A named enum value.
#[derive(Debug, Clone)]
pub struct ValueSnap {
    /// Its name.
    pub name: String,
    /// Its number.
    pub value: u64,
    /// Where it is defined.
    pub at: Loc,
}

/// A bit-field member.
#[derive(Debug, Clone)]
pub struct MemberSnap {
    /// Its name.
    pub name: String,
    /// Its bits.
    pub bits: Bits,
    /// Where it is defined.
    pub at: Loc,
}

/// A union variant.
#[derive(Debug, Clone)]
pub struct VariantSnap {
    /// Its name.
    pub name: String,
    /// Its tag.
    pub tag: u64,
    /// The value after the tag (none for a tag-only variant).
    pub wire: Option<Wire>,
    /// Where it is defined.
    pub at: Loc,
}

/// A component interface.
#[derive(Debug, Clone)]
pub struct ComponentSnap {
    /// Its name.
    pub name: String,
    /// Component id.
    pub id: u8,
    /// Takes and sends every message.
    pub any_message: bool,
    /// Commands executed from the component in control, by name.
    pub commands: Vec<Entry>,
    /// Messages accepted from anyone, by name.
    pub accepts: Vec<Entry>,
    /// Messages sent on its own, by name.
    pub emits: Vec<Entry>,
    /// Sub-states of Ready.
    pub modes: Option<ModesSnap>,
    /// Where it is defined.
    pub at: Loc,
}

/// A name in a list, with its position.
#[derive(Debug, Clone)]
pub struct Entry {
    /// The name.
    pub name: String,
    /// Where it is written.
    pub at: Loc,
}

/// A component's modes.
#[derive(Debug, Clone)]
pub struct ModesSnap {
    /// The initial mode.
    pub initial: Entry,
    /// The modes, by name.
    pub states: Vec<Entry>,
    /// The transitions, by name.
    pub transitions: Vec<TransitionSnap>,
}

/// A mode transition.
#[derive(Debug, Clone)]
pub struct TransitionSnap {
    /// Its name.
    pub name: String,
    /// Modes it starts from, as written.
    pub from: Vec<String>,
    /// The mode it leads to.
    pub to: String,
    /// The core state entered with it.
    pub core: Option<String>,
    /// Where it is defined.
    pub at: Loc,
}

/// The name under which a file appears in changes and errors: its file name.
/// (`REV:file.yaml` of a git revision at the repository root gives `file.yaml`).
pub(crate) fn label(path: &Path) -> String {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| path.display().to_string());
    match name.rsplit_once(':') {
        Some((_, file)) if !file.is_empty() => file.to_string(),
        _ => name,
    }
}

impl Snapshot {
    /// The snapshot of a validated definition set, positions in its YAML files.
    pub fn from_spec(spec: &Spec) -> Snapshot {
        Snapshot::located(spec, None)
    }

    /// The snapshot of a definition set imported from JSIDL: positions in the JSIDL files
    /// for what was imported (`jsidl`), in the YAML files for the rest (overlays).
    pub fn from_jsidl(spec: &Spec, jsidl: &JsidlPositions) -> Snapshot {
        Snapshot::located(spec, Some(jsidl))
    }

    fn located(spec: &Spec, jsidl: Option<&JsidlPositions>) -> Snapshot {
        let loc = |source: usize, path: &str| {
            if let Some(l) = jsidl.and_then(|j| j.locate(source, path)) {
                return l;
            }
            let (file, pos) = spec.locate(source, path);
            Loc {
                file: label(file),
                line: pos.line,
                col: pos.column,
            }
        };
        let fields = |fs: &[jaus_spec::Field], source: usize, owner: &str| -> Vec<FieldSnap> {
            fs.iter()
                .enumerate()
                .map(|(i, f)| FieldSnap {
                    name: f.def.name.clone(),
                    wire: f.wire.clone(),
                    bit: f.def.bit,
                    present_if: f.def.present_if.clone(),
                    unit: f.def.unit.clone(),
                    at: loc(source, &format!("{owner}.fields[{i}]")),
                })
                .collect()
        };
        let mut messages: Vec<MessageSnap> = spec
            .messages
            .iter()
            .filter(|m| spec.is_own(m.source))
            .map(|m| MessageSnap {
                name: m.def.name.clone(),
                code: m.def.code.0,
                presence: m.presence,
                fields: fields(&m.fields, m.source, &m.path),
                at: loc(m.source, &m.path),
            })
            .collect();
        messages.sort_by(|a, b| (a.code, &a.name).cmp(&(b.code, &b.name)));

        let mut types: Vec<TypeSnap> = spec
            .types
            .iter()
            .filter(|t| spec.is_own(t.source))
            .map(|t| {
                let at = |key: &str, i: usize| loc(t.source, &format!("{}.{key}[{i}]", t.path));
                let form = match &t.form {
                    TypeForm::Record {
                        presence,
                        fields: fs,
                    } => FormSnap::Record {
                        presence: *presence,
                        fields: fields(fs, t.source, &t.path),
                    },
                    TypeForm::Enum { repr } => {
                        let mut values: Vec<ValueSnap> = t
                            .def
                            .values
                            .iter()
                            .enumerate()
                            .map(|(i, v)| ValueSnap {
                                name: v.name.clone(),
                                value: v.value,
                                at: at("values", i),
                            })
                            .collect();
                        values.sort_by(|a, b| (a.value, &a.name).cmp(&(b.value, &b.name)));
                        FormSnap::Enum {
                            repr: *repr,
                            values,
                        }
                    }
                    TypeForm::Bitfield { repr, members } => {
                        let mut members: Vec<MemberSnap> = members
                            .iter()
                            .enumerate()
                            .map(|(i, m)| MemberSnap {
                                name: m.def.name.clone(),
                                bits: m.bits,
                                at: at("bits", i),
                            })
                            .collect();
                        members.sort_by(|a, b| {
                            (bit_range(a.bits), &a.name).cmp(&(bit_range(b.bits), &b.name))
                        });
                        FormSnap::Bitfield {
                            repr: *repr,
                            members,
                        }
                    }
                    TypeForm::Union { repr, variants } => {
                        let mut variants: Vec<VariantSnap> = variants
                            .iter()
                            .enumerate()
                            .map(|(i, v)| VariantSnap {
                                name: v.def.name.clone(),
                                tag: v.def.tag,
                                wire: v.wire.clone(),
                                at: at("variants", i),
                            })
                            .collect();
                        variants.sort_by(|a, b| (a.tag, &a.name).cmp(&(b.tag, &b.name)));
                        FormSnap::Union {
                            repr: *repr,
                            variants,
                        }
                    }
                };
                TypeSnap {
                    name: t.def.name.clone(),
                    form,
                    at: loc(t.source, &t.path),
                }
            })
            .collect();
        types.sort_by(|a, b| a.name.cmp(&b.name));

        let mut components: Vec<ComponentSnap> = spec
            .components
            .iter()
            .filter(|c| spec.is_own(c.source))
            .map(|c| {
                let d = &c.def;
                let list = |key: &str, names: &[String]| {
                    let mut v: Vec<Entry> = names
                        .iter()
                        .enumerate()
                        .map(|(i, n)| Entry {
                            name: n.clone(),
                            at: loc(c.source, &format!("{}.{key}[{i}]", c.path)),
                        })
                        .collect();
                    v.sort_by(|a, b| a.name.cmp(&b.name));
                    v
                };
                let modes = d.modes.as_ref().map(|m| {
                    let base = format!("{}.modes", c.path);
                    let mut states: Vec<Entry> = m
                        .states
                        .iter()
                        .enumerate()
                        .map(|(i, s)| Entry {
                            name: s.name.clone(),
                            at: loc(c.source, &format!("{base}.states[{i}]")),
                        })
                        .collect();
                    states.sort_by(|a, b| a.name.cmp(&b.name));
                    let mut transitions: Vec<TransitionSnap> = m
                        .transitions
                        .iter()
                        .enumerate()
                        .map(|(i, t)| TransitionSnap {
                            name: t.name.clone(),
                            from: t.from.clone(),
                            to: t.to.clone(),
                            core: t.core.clone(),
                            at: loc(c.source, &format!("{base}.transitions[{i}]")),
                        })
                        .collect();
                    transitions.sort_by(|a, b| a.name.cmp(&b.name));
                    ModesSnap {
                        initial: Entry {
                            name: m.initial.clone(),
                            at: loc(c.source, &format!("{base}.initial")),
                        },
                        states,
                        transitions,
                    }
                });
                ComponentSnap {
                    name: d.name.clone(),
                    id: d.id,
                    any_message: d.any_message,
                    commands: list("commands", &d.commands),
                    accepts: list("accepts", &d.accepts),
                    emits: list("emits", &d.emits),
                    modes,
                    at: loc(c.source, &c.path),
                }
            })
            .collect();
        components.sort_by(|a, b| a.name.cmp(&b.name));
        let services = services::services(spec, &loc);
        Snapshot {
            messages,
            types,
            components,
            services,
        }
    }

    /// The named type `name`.
    pub fn ty(&self, name: &str) -> Option<&TypeSnap> {
        self.types.iter().find(|t| t.name == name)
    }
}

/// Lowest and highest bit of a member.
pub(crate) fn bit_range(b: Bits) -> (u32, u32) {
    match b {
        Bits::Flag(n) => (n, n),
        Bits::Range { lo, hi } => (lo, hi),
    }
}

/// The name of a type kind as written in YAML.
pub(crate) fn kind_name(k: TypeKind) -> &'static str {
    match k {
        TypeKind::Record => "record",
        TypeKind::Enum => "enum",
        TypeKind::Bitfield => "bitfield",
        TypeKind::Union => "union",
    }
}

fn len_text(l: &Len) -> String {
    match l {
        Len::Fixed { n, accept_short } => {
            format!(
                "fixed {n}{}",
                if *accept_short { " accept_short" } else { "" }
            )
        }
        Len::Prefix(i) => format!("count {}", i.rust()),
        Len::Rest { nul } => format!("rest{}", if *nul { " nul" } else { "" }),
        Len::Nul => "nul".into(),
    }
}

/// The text of a wire form, as written in a lock file and in change details:
/// `u16`, `scaled i32 [-90, 90]`, `record Foo size u16`, `union Value tag_field kind`,
/// `string fixed 15`, `bytes count u32`, `string rest nul`, `list count u8 of record Foo`,
/// `list rest of u16`, `list count_field n-1 offsets_of children of u32`, `flag`,
/// `message size u32`. [`parse_wire`] reads it back.
pub fn wire_text(w: &Wire) -> String {
    match w {
        Wire::Int(i) => i.rust().into(),
        Wire::F32 => "f32".into(),
        Wire::F64 => "f64".into(),
        Wire::Scaled { int, lo, hi } => format!("scaled {} [{lo}, {hi}]", int.rust()),
        Wire::Named {
            name,
            kind,
            size,
            tag_field,
        } => {
            let mut s = format!("{} {name}", kind_name(*kind));
            if let Some(i) = size {
                s += &format!(" size {}", i.rust());
            }
            if let Some(t) = tag_field {
                s += &format!(" tag_field {t}");
            }
            s
        }
        Wire::Str(l) => format!("string {}", len_text(l)),
        Wire::Bytes(l) => format!("bytes {}", len_text(l)),
        Wire::List { count, elem } => match count {
            Some(c) => format!("list count {} of {}", c.rust(), wire_text(elem)),
            None => format!("list rest of {}", wire_text(elem)),
        },
        Wire::ListField {
            field,
            elem,
            offsets_of,
        } => {
            let field: String = field.to_string().split_whitespace().collect();
            match offsets_of {
                Some(o) => format!(
                    "list count_field {field} offsets_of {o} of {}",
                    wire_text(elem)
                ),
                None => format!("list count_field {field} of {}", wire_text(elem)),
            }
        }
        Wire::Flag => "flag".into(),
        Wire::Packet { size } => match size {
            Some(i) => format!("message size {}", i.rust()),
            None => "message".into(),
        },
    }
}

/// Reads the text of [`wire_text`] back into a wire form.
pub fn parse_wire(text: &str) -> Result<Wire, String> {
    let mut t = text.split_whitespace().peekable();
    let w = parse_tokens(&mut t)?;
    match t.next() {
        None => Ok(w),
        Some(extra) => Err(format!("unexpected `{extra}` in wire form `{text}`")),
    }
}

type Tokens<'a> = std::iter::Peekable<std::str::SplitWhitespace<'a>>;

fn int_of(tok: Option<&str>) -> Result<Int, String> {
    let tok = tok.ok_or("an integer type is missing")?;
    Int::parse(tok).ok_or_else(|| format!("`{tok}` is not an integer type"))
}

fn word<'a>(t: &mut Tokens<'a>, what: &str) -> Result<&'a str, String> {
    t.next().ok_or_else(|| format!("{what} is missing"))
}

fn parse_len(t: &mut Tokens<'_>) -> Result<Len, String> {
    match word(t, "a length")? {
        "fixed" => {
            let n = word(t, "a byte count")?;
            let n = n
                .parse()
                .map_err(|_| format!("`{n}` is not a byte count"))?;
            let accept_short = t.next_if_eq(&"accept_short").is_some();
            Ok(Len::Fixed { n, accept_short })
        }
        "count" => Ok(Len::Prefix(int_of(t.next())?)),
        "rest" => Ok(Len::Rest {
            nul: t.next_if_eq(&"nul").is_some(),
        }),
        "nul" => Ok(Len::Nul),
        other => Err(format!(
            "`{other}` is not a length: `fixed N`, `count T`, `rest` or `nul`"
        )),
    }
}

fn parse_tokens(t: &mut Tokens<'_>) -> Result<Wire, String> {
    let head = word(t, "a wire form")?;
    if let Some(i) = Int::parse(head) {
        return Ok(Wire::Int(i));
    }
    Ok(match head {
        "f32" => Wire::F32,
        "f64" => Wire::F64,
        "flag" => Wire::Flag,
        "scaled" => {
            let int = int_of(t.next())?;
            let lo = word(t, "the lower limit")?;
            let hi = word(t, "the upper limit")?;
            let num = |s: &str| -> Result<f64, String> {
                s.parse()
                    .map_err(|_| format!("`{s}` is not a scale limit (`[lo, hi]`)"))
            };
            let (Some(lo), Some(hi)) = (
                lo.strip_prefix('[').and_then(|s| s.strip_suffix(',')),
                hi.strip_suffix(']'),
            ) else {
                return Err(format!("scale limits `{lo} {hi}` are not `[lo, hi]`"));
            };
            Wire::Scaled {
                int,
                lo: num(lo)?,
                hi: num(hi)?,
            }
        }
        "record" | "enum" | "bitfield" | "union" => {
            let kind = match head {
                "record" => TypeKind::Record,
                "enum" => TypeKind::Enum,
                "bitfield" => TypeKind::Bitfield,
                _ => TypeKind::Union,
            };
            let name = word(t, "a type name")?.to_string();
            let mut size = None;
            let mut tag_field = None;
            loop {
                if t.next_if_eq(&"size").is_some() {
                    size = Some(int_of(t.next())?);
                } else if t.next_if_eq(&"tag_field").is_some() {
                    tag_field = Some(word(t, "a field name")?.to_string());
                } else {
                    break;
                }
            }
            Wire::Named {
                name,
                kind,
                size,
                tag_field,
            }
        }
        "string" => Wire::Str(parse_len(t)?),
        "bytes" => Wire::Bytes(parse_len(t)?),
        "message" => Wire::Packet {
            size: match t.next_if_eq(&"size") {
                Some(_) => Some(int_of(t.next())?),
                None => None,
            },
        },
        "list" => {
            let how = word(t, "`count T`, `rest` or `count_field F`")?;
            let (count, field, offsets_of) = match how {
                "count" => (Some(int_of(t.next())?), None, None),
                "rest" => (None, None, None),
                "count_field" => {
                    let f = word(t, "a field name")?
                        .parse::<CountRef>()
                        .map_err(|e| e.to_string())?;
                    let o = match t.next_if_eq(&"offsets_of") {
                        Some(_) => Some(word(t, "a field name")?.to_string()),
                        None => None,
                    };
                    (None, Some(f), o)
                }
                other => {
                    return Err(format!(
                        "`{other}` is not `count T`, `rest` or `count_field F`"
                    ))
                }
            };
            if t.next_if_eq(&"of").is_none() {
                return Err("a list needs `of` and its element".into());
            }
            let elem = Box::new(parse_tokens(t)?);
            match field {
                Some(field) => Wire::ListField {
                    field,
                    elem,
                    offsets_of,
                },
                None => Wire::List { count, elem },
            }
        }
        other => return Err(format!("`{other}` is not a wire form")),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_wire_form_of_the_ra33_set_reads_back() {
        let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).unwrap();
        let snap = Snapshot::from_spec(&spec);
        let mut n = 0;
        let all = snap
            .messages
            .iter()
            .flat_map(|m| &m.fields)
            .chain(snap.types.iter().flat_map(|t| match &t.form {
                FormSnap::Record { fields, .. } => fields.as_slice(),
                _ => &[],
            }));
        for f in all {
            let text = wire_text(&f.wire);
            assert_eq!(parse_wire(&text).as_ref(), Ok(&f.wire), "{text}");
            n += 1;
        }
        assert!(n > 500, "{n} fields");
        for text in [
            "scaled u32 [-25.13, 25.13]",
            "string fixed 80 accept_short",
            "string rest nul",
            "bytes count u32",
            "list count_field num_joints-1 offsets_of children of record Task",
            "union Value size u16 tag_field kind",
            "message size u32",
            "list rest of u16",
        ] {
            assert_eq!(wire_text(&parse_wire(text).unwrap()), text);
        }
        assert!(parse_wire("scaled u8 0 1").is_err());
        assert!(parse_wire("u8 u8").is_err());
        assert!(parse_wire("list count u8").is_err());
    }
}
