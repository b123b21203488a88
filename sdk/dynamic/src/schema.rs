//! The wire layout of every message and named type of a validated definition set,
//! compiled once from [`jaus_spec::Spec`] into the form the run-time codec walks.
//!
//! The compilation applies the same reading of the definitions as `jaus-gen` and the
//! derive macros: which fields publish their value for later fields (`count_field`,
//! `present_if`, `tag_field` anywhere in the set name them: [`Spec::vars`], which
//! `jaus-gen` reads too), which count field is
//! written from the length of the list it counts, which list's elements an offsets
//! field points at, and the presence bits a body defines.

use crate::intern;
use jaus::codec::ScaledField;
use jaus::CommandCode;
use jaus_spec::{Bits, Int, Len, MessageClass, Spec, TypeForm, Wire};
use std::collections::{BTreeSet, HashMap};
use std::hash::{BuildHasherDefault, Hasher};
use std::path::Path;

/// The layouts of a definition set: what [`crate::Schema`] decodes and encodes with.
#[derive(Debug)]
pub(crate) struct Layouts {
    pub(crate) messages: Vec<MessageLayout>,
    /// By command code, hashed by [`CodeHasher`] (looked up on every decode).
    pub(crate) by_code: HashMap<u16, usize, BuildHasherDefault<CodeHasher>>,
    pub(crate) by_name: HashMap<&'static str, usize>,
    pub(crate) types: Vec<TypeLayout>,
}

/// One message of the set: its name, code, class and where it is defined.
#[derive(Debug, Clone)]
pub struct MessageLayout {
    /// PascalCase name, as in JSON (`"message": NAME`).
    pub name: &'static str,
    /// Command code.
    pub code: CommandCode,
    /// Its class (by code range, or the explicit `class:` of an experimental code).
    pub class: MessageClass,
    /// For a query: the code of the report answering it.
    pub report: Option<CommandCode>,
    /// Defined by an overlay (not by the base definitions it extends).
    pub own: bool,
    /// `file:line` of the definition.
    pub at: String,
    pub(crate) body: Body,
}

/// The fields of a message body or record, with its presence vector.
#[derive(Debug, Clone)]
pub(crate) struct Body {
    /// `Name.presence_vector`, for errors.
    pub(crate) pv_path: &'static str,
    pub(crate) presence: Option<Int>,
    pub(crate) fields: Vec<FieldLayout>,
    /// Presence bits the definition defines.
    pub(crate) known: u64,
}

/// One field of a body.
#[derive(Debug, Clone)]
pub(crate) struct FieldLayout {
    pub(crate) name: &'static str,
    /// `Owner.field`, for errors.
    pub(crate) path: &'static str,
    pub(crate) wire: WireLayout,
    /// Presence bit of an optional field, or the bit of a flag.
    pub(crate) bit: Option<u32>,
    /// An optional field present when this variable is non-zero.
    pub(crate) present_if: Option<&'static str>,
    /// This field publishes its value under this name.
    pub(crate) var: Option<&'static str>,
    /// The list of this body this count field counts (its index, and whether it is
    /// optional): the count is written from the list's length.
    pub(crate) counts: Option<(usize, bool)>,
    /// This field holds the byte offsets of the elements of that list of this body.
    pub(crate) offsets_of: Option<usize>,
    /// The offsets of this list's elements are kept in that field of this body.
    pub(crate) patched_by: Option<usize>,
}

/// How a value is carried on the wire.
#[derive(Debug, Clone)]
pub(crate) enum WireLayout {
    Int(Int),
    F32,
    F64,
    Scaled(Int, &'static ScaledField),
    /// A named type (an index into the types), behind a size prefix, or a union whose
    /// tag is an earlier field.
    Named {
        ty: usize,
        size: Option<Int>,
        tag_var: Option<&'static str>,
    },
    Str(Len),
    Bytes(Len),
    List {
        count: Option<Int>,
        elem: Box<WireLayout>,
    },
    ListVar {
        var: &'static str,
        minus: u64,
        elem: Box<WireLayout>,
    },
    Flag,
    Packet {
        size: Option<Int>,
    },
}

/// A named type.
#[derive(Debug, Clone)]
pub(crate) struct TypeLayout {
    pub(crate) form: FormLayout,
}

/// The form of a named type.
#[derive(Debug, Clone)]
pub(crate) enum FormLayout {
    Record(Body),
    Enum {
        repr: Int,
        values: Vec<(&'static str, u64)>,
    },
    Bits {
        repr: Int,
        /// (name, `Type.member`, lowest bit, highest bit, a flag).
        members: Vec<(&'static str, &'static str, u32, u32, bool)>,
        undefined: u64,
    },
    Union {
        tag: Int,
        /// (name, `Type::Variant`, tag, value).
        variants: Vec<(&'static str, &'static str, u64, Option<WireLayout>)>,
    },
}

/// Compiles the layouts of a validated set.
pub(crate) fn compile(spec: &Spec) -> Layouts {
    let type_index: HashMap<&str, usize> = spec
        .types
        .iter()
        .enumerate()
        .map(|(i, t)| (t.def.name.as_str(), i))
        .collect();
    let c = Compiler {
        types: type_index,
        vars: spec.vars(),
    };
    let types = spec
        .types
        .iter()
        .map(|t| {
            let name = t.def.name.as_str();
            let form = match &t.form {
                TypeForm::Record { presence, fields } => {
                    FormLayout::Record(c.body(name, *presence, fields))
                }
                TypeForm::Enum { repr } => FormLayout::Enum {
                    repr: *repr,
                    values: t
                        .def
                        .values
                        .iter()
                        .map(|v| (intern::name(&v.name), v.value))
                        .collect(),
                },
                TypeForm::Bitfield { repr, members } => {
                    let width = repr.bytes() as u32 * 8;
                    let all = if width == 64 {
                        u64::MAX
                    } else {
                        (1u64 << width) - 1
                    };
                    let mut defined = 0u64;
                    let members = members
                        .iter()
                        .map(|m| {
                            let (lo, hi, flag) = match m.bits {
                                Bits::Flag(b) => (b, b, true),
                                Bits::Range { lo, hi } => (lo, hi, false),
                            };
                            defined |= mask(hi - lo + 1) << lo;
                            (
                                intern::name(&m.def.name),
                                intern::name(&format!("{name}.{}", m.def.name)),
                                lo,
                                hi,
                                flag,
                            )
                        })
                        .collect();
                    FormLayout::Bits {
                        repr: *repr,
                        members,
                        undefined: !defined & all,
                    }
                }
                TypeForm::Union { repr, variants } => FormLayout::Union {
                    tag: *repr,
                    variants: variants
                        .iter()
                        .map(|v| {
                            (
                                intern::name(&v.def.name),
                                intern::name(&format!("{name}::{}", v.def.name)),
                                v.def.tag,
                                v.wire.as_ref().map(|w| c.wire(w, name, "")),
                            )
                        })
                        .collect(),
                },
            };
            TypeLayout { form }
        })
        .collect();
    let mut messages = Vec::with_capacity(spec.messages.len());
    let mut by_code = HashMap::default();
    let mut by_name = HashMap::new();
    for m in &spec.messages {
        let name = intern::name(&m.def.name);
        let (file, pos) = spec.locate(m.source, &m.path);
        let file = Path::new(file).file_name().map_or_else(
            || file.display().to_string(),
            |f| f.to_string_lossy().into(),
        );
        let layout = MessageLayout {
            name,
            code: CommandCode(m.def.code.0),
            class: m.def.class(),
            report: spec.report_of(&m.def).map(|r| CommandCode(r.def.code.0)),
            own: spec.is_own(m.source),
            at: format!("{file}:{}", pos.line),
            body: c.body(name, m.presence, &m.fields),
        };
        by_code.insert(m.def.code.0, messages.len());
        by_name.insert(name, messages.len());
        messages.push(layout);
    }
    Layouts {
        messages,
        by_code,
        by_name,
        types,
    }
}

/// The hash of a command code: one multiplication (Fibonacci hashing) instead of
/// SipHash, whose keying buys nothing against codes a schema defines itself (a code
/// looked up that it does not define costs a probe, as any other).
#[derive(Debug, Default, Clone, Copy)]
pub(crate) struct CodeHasher(u64);

impl Hasher for CodeHasher {
    #[inline]
    fn finish(&self) -> u64 {
        self.0
    }
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0.rotate_left(8) ^ u64::from(b)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        }
    }
    #[inline]
    fn write_u16(&mut self, v: u16) {
        self.0 = (self.0 ^ u64::from(v)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// `n` low bits set.
pub(crate) fn mask(n: u32) -> u64 {
    if n >= 64 {
        u64::MAX
    } else {
        (1u64 << n) - 1
    }
}

struct Compiler<'a> {
    types: HashMap<&'a str, usize>,
    vars: BTreeSet<String>,
}

impl Compiler<'_> {
    fn body(&self, owner: &str, presence: Option<Int>, fields: &[jaus_spec::Field]) -> Body {
        let mut out: Vec<FieldLayout> = fields
            .iter()
            .map(|f| {
                let d = &f.def;
                let unit = d
                    .unit
                    .as_deref()
                    .or(d.of.as_ref().and_then(|e| e.0.unit.as_deref()))
                    .unwrap_or("");
                let path = format!("{owner}.{}", d.name);
                FieldLayout {
                    name: intern::name(&d.name),
                    path: intern::name(&path),
                    wire: self.wire(&f.wire, owner, unit).with_path(&path, unit),
                    bit: d.bit,
                    present_if: if d.bit.is_none() {
                        d.present_if.as_deref().map(intern::name)
                    } else {
                        None
                    },
                    var: self.vars.contains(&d.name).then(|| intern::name(&d.name)),
                    counts: None,
                    offsets_of: None,
                    patched_by: None,
                }
            })
            .collect();
        // Links inside this body: a count field and the list it counts, an offsets
        // field and the list whose elements it points at.
        let lists: Vec<(usize, &'static str, bool)> = out
            .iter()
            .enumerate()
            .filter_map(|(i, f)| match &f.wire {
                WireLayout::ListVar { var, minus: 0, .. } => Some((i, *var, f.is_optional())),
                _ => None,
            })
            .collect();
        let offsets: Vec<(usize, usize)> = fields
            .iter()
            .enumerate()
            .filter_map(|(i, f)| {
                let target = f.def.offsets_of.as_deref()?;
                let t = fields.iter().position(|g| g.def.name == target)?;
                Some((i, t))
            })
            .collect();
        for f in &mut out {
            if let Some(v) = f.var {
                f.counts = lists
                    .iter()
                    .find(|(i, lv, _)| *lv == v && !offsets.iter().any(|(o, _)| o == i))
                    .map(|(i, _, opt)| (*i, *opt));
            }
        }
        for (o, t) in offsets {
            out[o].offsets_of = Some(t);
            if matches!(
                out[t].wire,
                WireLayout::ListVar { .. } | WireLayout::List { .. }
            ) {
                out[t].patched_by = Some(o);
            }
        }
        let known = out
            .iter()
            .filter_map(|f| f.bit)
            .fold(0u64, |m, b| m | 1u64.checked_shl(b).unwrap_or(0));
        Body {
            pv_path: intern::name(&format!("{owner}.presence_vector")),
            presence,
            fields: out,
            known,
        }
    }

    fn wire(&self, w: &Wire, owner: &str, unit: &str) -> WireLayout {
        match w {
            Wire::Int(i) => WireLayout::Int(*i),
            Wire::F32 => WireLayout::F32,
            Wire::F64 => WireLayout::F64,
            Wire::Scaled { int, lo, hi } => {
                WireLayout::Scaled(*int, intern::scaled(owner, *lo, *hi, unit))
            }
            Wire::Named {
                name,
                size,
                tag_field,
                ..
            } => WireLayout::Named {
                // Validation resolved every name.
                ty: self.types.get(name.as_str()).copied().unwrap_or(usize::MAX),
                size: *size,
                tag_var: tag_field.as_deref().map(intern::name),
            },
            Wire::Str(l) => WireLayout::Str(*l),
            Wire::Bytes(l) => WireLayout::Bytes(*l),
            Wire::List { count, elem } => WireLayout::List {
                count: *count,
                elem: Box::new(self.wire(elem, owner, unit)),
            },
            Wire::ListField { field, elem, .. } => WireLayout::ListVar {
                var: intern::name(&field.field),
                minus: field.minus,
                elem: Box::new(self.wire(elem, owner, unit)),
            },
            Wire::Flag => WireLayout::Flag,
            Wire::Packet { size } => WireLayout::Packet { size: *size },
        }
    }
}

impl WireLayout {
    /// The same layout with its scaled values (and those of its elements) named after
    /// the field `path`.
    fn with_path(self, path: &str, unit: &str) -> WireLayout {
        match self {
            WireLayout::Scaled(i, s) => {
                WireLayout::Scaled(i, intern::scaled(path, s.lo, s.hi, unit))
            }
            WireLayout::List { count, elem } => WireLayout::List {
                count,
                elem: Box::new(elem.with_path(path, unit)),
            },
            WireLayout::ListVar { var, minus, elem } => WireLayout::ListVar {
                var,
                minus,
                elem: Box::new(elem.with_path(path, unit)),
            },
            other => other,
        }
    }
}

impl FieldLayout {
    /// Optional: behind a presence bit (not a flag) or present by another field.
    pub(crate) fn is_optional(&self) -> bool {
        (self.bit.is_some() && !matches!(self.wire, WireLayout::Flag)) || self.present_if.is_some()
    }
}
