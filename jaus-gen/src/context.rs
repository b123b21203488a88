//! The template context: every message and type of a spec, with Rust types, derive
//! attributes and documentation already worked out.

use jaus_spec::{Bits, Code, Field, Len, MessageDef, Spec, TypeForm, TypeKind, Wire};
use serde::Serialize;

/// Everything the templates see.
#[derive(Debug, Serialize)]
pub struct Context {
    /// Groups in definition order, each with its types and messages.
    pub groups: Vec<GroupCtx>,
    /// Every message, in definition order.
    pub messages: Vec<MessageCtx>,
    /// Query → report pairs.
    pub queries: Vec<QueryCtx>,
    /// Command codes (`0x0001`) of the messages the component runtime takes for every
    /// component (`runtime: [handles]` or `[shares]`), in code order.
    pub runtime_inputs: Vec<String>,
    /// Command codes of the messages the component runtime sends for every component
    /// (`runtime: [emits]`), in code order.
    pub runtime_outputs: Vec<String>,
    /// The set is a vendor's overlay on the SDK's definitions: only its own items are
    /// generated, the SDK's are used from `::jaus::messages`, and its `Message` wraps
    /// the SDK's.
    pub vendor: bool,
    /// The SDK's feature-gated groups the overlay's items use, each with the first use
    /// (`file:line: message X, field y uses type Z`).
    pub requires: Vec<RequireCtx>,
}

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

/// One group.
#[derive(Debug, Serialize)]
pub struct GroupCtx {
    /// Identifier.
    pub name: String,
    /// Rust module name (the identifier, except where it would shadow a crate: `core`
    /// becomes `core_messages`).
    pub module: String,
    /// Title.
    pub title: String,
    /// Description lines.
    pub doc: Vec<String>,
    /// `#[cfg(...)]` condition text, if gated.
    pub cfg: Option<String>,
    /// Named types.
    pub types: Vec<TypeCtx>,
    /// Messages.
    pub messages: Vec<MessageCtx>,
}

/// A named type.
#[derive(Debug, Serialize)]
pub struct TypeCtx {
    /// Rust name.
    pub name: String,
    /// `record`, `enum`, `bitfield` or `union`.
    pub kind: String,
    /// Integer type of enum/bitfield/union tag.
    pub repr: String,
    /// Doc lines.
    pub doc: Vec<String>,
    /// `#[jaus(...)]` container attribute contents.
    pub container_attr: String,
    /// Derive `Default`.
    pub default: bool,
    /// Derive `Copy`.
    pub copy: bool,
    /// Record fields.
    pub fields: Vec<FieldCtx>,
    /// Enum values.
    pub values: Vec<ValueCtx>,
    /// Bitfield members.
    pub bits: Vec<BitCtx>,
    /// Union variants.
    pub variants: Vec<VariantCtx>,
}

/// A message.
#[derive(Debug, Clone, Serialize)]
pub struct MessageCtx {
    /// Rust name.
    pub name: String,
    /// Command code as `0x4402`.
    pub code: String,
    /// Title.
    pub title: String,
    /// Group identifier.
    pub group: String,
    /// `#[cfg(...)]` condition, if gated.
    pub cfg: Option<String>,
    /// Doc lines.
    pub doc: Vec<String>,
    /// `#[jaus(...)]` container attribute contents.
    pub container_attr: String,
    /// Derive `Default`.
    pub default: bool,
    /// Fields.
    pub fields: Vec<FieldCtx>,
    /// Accessors decoding embedded message bodies.
    pub embedded: Vec<EmbeddedCtx>,
    /// Report answering this query.
    pub report: Option<String>,
    /// Experimental.
    pub experimental: bool,
    /// Variant of `jaus::wire::MessageClass` (`Command`, `Query`, ...).
    pub class: String,
    /// `access: read`: a command that changes nothing a controller owns.
    pub read_only: bool,
}

/// A struct field.
#[derive(Debug, Clone, Serialize)]
pub struct FieldCtx {
    /// Rust name.
    pub name: String,
    /// Rust type.
    pub ty: String,
    /// `#[jaus(...)]` contents (empty for none).
    pub attr: String,
    /// `serde(...)` contents (empty for none).
    pub serde: String,
    /// Doc lines.
    pub doc: Vec<String>,
}

/// An enum value.
#[derive(Debug, Serialize)]
pub struct ValueCtx {
    /// Variant name.
    pub name: String,
    /// Wire value.
    pub value: u64,
    /// Doc lines.
    pub doc: Vec<String>,
}

/// A bitfield member.
#[derive(Debug, Serialize)]
pub struct BitCtx {
    /// Field name.
    pub name: String,
    /// Rust type.
    pub ty: String,
    /// `#[jaus(...)]` contents.
    pub attr: String,
    /// Doc lines.
    pub doc: Vec<String>,
}

/// A union variant.
#[derive(Debug, Serialize)]
pub struct VariantCtx {
    /// Variant name.
    pub name: String,
    /// Tag.
    pub tag: u64,
    /// Payload type, if any.
    pub ty: Option<String>,
    /// `serde(...)` contents for the payload, if any.
    pub serde: String,
    /// Doc lines.
    pub doc: Vec<String>,
}

/// An embedded message body with its code in another field.
#[derive(Debug, Clone, Serialize)]
pub struct EmbeddedCtx {
    /// The bytes field.
    pub field: String,
    /// The field holding the code.
    pub code_field: String,
    /// The body's code is the complement of that code.
    pub complement: bool,
    /// The field is optional: the accessor returns `None` when it is absent.
    pub optional: bool,
}

/// A query and its report.
#[derive(Debug, Serialize)]
pub struct QueryCtx {
    /// Query name.
    pub query: String,
    /// Report name.
    pub report: String,
    /// Query command code (`0x2402`).
    pub query_code: String,
    /// Report command code.
    pub report_code: String,
    /// Combined cfg.
    pub cfg: Option<String>,
}

/// The `jaus::wire::MessageClass` variant of a message: its explicit class, or its
/// code's range.
fn class_variant(d: &MessageDef) -> &'static str {
    use jaus_spec::MessageClass as C;
    match d.class() {
        C::Command => "Command",
        C::Query => "Query",
        C::Inform => "Inform",
        C::EventSetup => "EventSetup",
        C::EventNotification => "EventNotification",
        C::NodeManagement => "NodeManagement",
        C::Experimental if d.code.0 < 0xD000 => "Reserved",
        C::Experimental => "Experimental",
    }
}

fn doc_lines(text: Option<&str>) -> Vec<String> {
    text.map(|t| t.lines().map(|l| l.trim_end().to_string()).collect())
        .unwrap_or_default()
}

fn fmt_f64(v: f64) -> String {
    format!("{v:?}")
}

fn cfg_of(group: &str, gates: bool) -> Option<String> {
    (gates && group != "core").then(|| format!("feature = \"{group}\""))
}

struct Mapped {
    ty: String,
    attr: Vec<String>,
    serde: Vec<String>,
    doc: Vec<String>,
}

/// Rust type, derive attributes and documentation of a wire form.
fn map_wire(w: &Wire, rt: &str) -> Mapped {
    let mut m = Mapped {
        ty: String::new(),
        attr: Vec::new(),
        serde: Vec::new(),
        doc: Vec::new(),
    };
    match w {
        Wire::Int(i) => m.ty = i.rust().into(),
        Wire::F32 | Wire::F64 => {
            m.ty = if *w == Wire::F32 { "f32" } else { "f64" }.into();
            m.serde.push(format!("with = \"{rt}::codec::serde_float\""));
        }
        Wire::Scaled { int, lo, hi } => {
            m.ty = "f64".into();
            m.attr.push(format!(
                "scaled({}, {}, {})",
                int.rust(),
                fmt_f64(*lo),
                fmt_f64(*hi)
            ));
            let d = int.divisor();
            m.doc.push(format!(
                "Range `[{lo}, {hi}]`, carried as a scaled `{}` (resolution {:.3e}).",
                int.rust(),
                (hi - lo) / d
            ));
        }
        Wire::Named {
            name,
            size,
            tag_field,
            ..
        } => {
            m.ty = name.clone();
            if let Some(s) = size {
                m.attr.push(format!("size = {}", s.rust()));
            }
            if let Some(t) = tag_field {
                m.attr.push(format!("tag_var = \"{t}\""));
                m.doc.push(format!(
                    "Its tag is the field `{t}`, not sent with the value."
                ));
            }
        }
        Wire::Str(len) => {
            m.ty = "String".into();
            len_attrs(&mut m, *len, "string");
        }
        Wire::Bytes(len) => {
            m.ty = "Vec<u8>".into();
            len_attrs(&mut m, *len, "blob");
            m.serde.push(format!("with = \"{rt}::hex::serde\""));
        }
        Wire::Packet { size } => {
            m.ty = format!("{rt}::Packet");
            m.doc.push("A whole JAUS message, header included.".into());
            if let Some(s) = size {
                m.attr.push(format!("size = {}", s.rust()));
                m.doc.push(format!(
                    "Preceded on the wire by its byte length as `{}`.",
                    s.rust()
                ));
            }
        }
        Wire::List { count, elem } => {
            let e = map_wire(elem, rt);
            m.ty = format!("Vec<{}>", e.ty);
            match count {
                Some(c) => {
                    m.attr.push(format!("count = {}", c.rust()));
                    m.doc.push(format!(
                        "Preceded on the wire by its element count as `{}`.",
                        c.rust()
                    ));
                }
                None => {
                    m.attr.push("rest".into());
                    m.doc.push("Elements run to the end of the body.".into());
                }
            }
            // Element attributes (scaled) apply to each element.
            m.attr
                .extend(e.attr.into_iter().filter(|a| a.starts_with("scaled")));
            m.doc
                .extend(e.doc.into_iter().map(|d| format!("Each element: {d}")));
        }
        Wire::ListField {
            field,
            elem,
            offsets_of,
        } => {
            let e = map_wire(elem, rt);
            m.ty = format!("Vec<{}>", e.ty);
            m.attr.push(format!("count_var = \"{field}\""));
            m.doc
                .push(format!("Its element count is the field `{field}`."));
            if let Some(t) = offsets_of {
                m.attr.push(format!("offsets = \"{t}\""));
                m.doc.push(format!(
                    "Byte offsets of the elements of `{t}` from the start of the body: computed on encode, informational on decode."
                ));
            }
            m.attr
                .extend(e.attr.into_iter().filter(|a| a.starts_with("scaled")));
            m.doc
                .extend(e.doc.into_iter().map(|d| format!("Each element: {d}")));
        }
        Wire::Flag => m.ty = "bool".into(),
    }
    m
}

fn len_attrs(m: &mut Mapped, len: Len, what: &str) {
    match len {
        Len::Fixed { n, accept_short } => {
            m.attr.push(format!("fixed = {n}"));
            m.doc.push(format!("A fixed {n}-byte {what}, NUL padded."));
            if accept_short {
                m.attr.push("accept_short".into());
                m.doc.push("A shorter field is accepted on receive.".into());
            }
        }
        Len::Prefix(c) => {
            m.attr.push(format!("size = {}", c.rust()));
            m.doc.push(format!(
                "Preceded on the wire by its length as `{}`.",
                c.rust()
            ));
        }
        Len::Nul => {
            m.attr.push("nul_terminated".into());
            m.doc.push(format!("A NUL-terminated {what}."));
        }
        Len::Rest { nul } => {
            m.attr.push("rest".into());
            m.doc.push("Runs to the end of the body.".into());
            if nul {
                m.attr.push("nul".into());
                m.doc.push("Sent with a terminating NUL.".into());
            }
        }
    }
}

fn field_ctx(spec: &Spec, field: &Field, rt: &str) -> FieldCtx {
    let (f, w) = (&field.def, &field.wire);
    let mut m = map_wire(w, rt);
    // The unit of a scaled value (of the field, or of each element of a list) goes into
    // the encoder's error messages.
    let unit = f
        .unit
        .as_ref()
        .or(f.of.as_ref().and_then(|e| e.0.unit.as_ref()));
    if let Some(u) = unit {
        if let Some(i) = m.attr.iter().position(|a| a.starts_with("scaled(")) {
            m.attr.insert(i + 1, format!("unit = {u:?}"));
        }
    }
    if spec.vars().contains(&f.name) {
        m.attr.push(format!("var = \"{}\"", f.name));
    }
    let mut doc = doc_lines(f.description.as_deref());
    if let Some(u) = &f.unit {
        doc.push(String::new());
        doc.push(format!("Unit: {u}."));
    } else if !m.doc.is_empty() {
        doc.push(String::new());
    }
    doc.append(&mut m.doc);
    let mut attr = m.attr;
    let mut serde = m.serde;
    let ty = match (f.bit, &f.present_if) {
        (Some(b), _) if *w == Wire::Flag => {
            attr.insert(0, format!("flag = {b}"));
            doc.push(format!("Presence-vector bit {b} (no bytes of its own)."));
            m.ty
        }
        (None, Some(flag)) => {
            attr.insert(0, format!("present_if = \"{flag}\""));
            doc.push(format!("Present exactly when `{flag}` is set."));
            if serde.iter().any(|s| s.contains("hex::serde")) {
                serde = vec![format!("with = \"{rt}::hex::serde_opt\"")];
            }
            if serde.iter().any(|s| s.contains("serde_float")) {
                serde = vec![format!("with = \"{rt}::codec::serde_float::option\"")];
            }
            serde.insert(
                0,
                "default, skip_serializing_if = \"Option::is_none\"".into(),
            );
            format!("Option<{}>", m.ty)
        }
        (Some(b), _) => {
            attr.insert(0, format!("bit = {b}"));
            doc.push(format!("Optional: presence bit {b}."));
            if serde.iter().any(|s| s.contains("hex::serde")) {
                serde = vec![format!("with = \"{rt}::hex::serde_opt\"")];
            }
            if serde.iter().any(|s| s.contains("serde_float")) {
                serde = vec![format!("with = \"{rt}::codec::serde_float::option\"")];
            }
            serde.insert(
                0,
                "default, skip_serializing_if = \"Option::is_none\"".into(),
            );
            format!("Option<{}>", m.ty)
        }
        (None, None) => m.ty,
    };
    FieldCtx {
        name: f.name.clone(),
        ty,
        attr: attr.join(", "),
        serde: serde.join(", "),
        doc,
    }
}

/// Whether a struct of these fields can derive `Default`.
fn all_default(spec: &Spec, fields: &[Field]) -> bool {
    fields.iter().all(|f| has_default(spec, f))
}

/// Whether values of this field have a `Default`.
fn has_default(spec: &Spec, f: &Field) -> bool {
    if f.def.bit.is_some() {
        return true;
    }
    match &f.wire {
        Wire::Named { name, kind, .. } => match kind {
            TypeKind::Union => false,
            TypeKind::Enum | TypeKind::Bitfield => true,
            TypeKind::Record => spec.ty(name).is_some_and(|t| all_default(spec, t.fields())),
        },
        Wire::Packet { .. } => false,
        _ => true,
    }
}

/// Builds the template context of a validated spec.
pub fn build_context(spec: &Spec, gates: bool, rt: &str) -> Context {
    let mut groups: Vec<GroupCtx> = spec
        .groups
        .iter()
        .map(|g| GroupCtx {
            name: g.name.clone(),
            module: if matches!(g.name.as_str(), "core" | "std" | "alloc") {
                format!("{}_messages", g.name)
            } else {
                g.name.clone()
            },
            title: g.title.clone(),
            doc: doc_lines(g.description.as_deref()),
            cfg: cfg_of(&g.name, gates),
            types: Vec::new(),
            messages: Vec::new(),
        })
        .collect();
    let vendor = spec.extends();
    for t in &spec.types {
        if !spec.is_own(t.source) {
            continue;
        }
        let d = &t.def;
        let mut tc = TypeCtx {
            name: d.name.clone(),
            kind: format!("{:?}", d.kind).to_lowercase(),
            repr: String::new(),
            doc: doc_lines(d.description.as_deref()),
            container_attr: String::new(),
            default: false,
            copy: false,
            fields: Vec::new(),
            values: Vec::new(),
            bits: Vec::new(),
            variants: Vec::new(),
        };
        match &t.form {
            TypeForm::Record { presence, fields } => {
                tc.container_attr =
                    presence.map_or_else(String::new, |p| format!("presence = {}", p.rust()));
                tc.fields = fields.iter().map(|f| field_ctx(spec, f, rt)).collect();
                tc.default = all_default(spec, fields);
            }
            TypeForm::Enum { repr } => {
                tc.repr = repr.rust().to_string();
                tc.container_attr = format!("repr = {}", tc.repr);
                tc.values = d
                    .values
                    .iter()
                    .map(|v| {
                        let mut doc = doc_lines(v.description.as_deref());
                        if doc.is_empty() {
                            doc.push(format!("{} ({}).", jaus_spec::title_of(&v.name), v.value));
                        }
                        ValueCtx {
                            name: v.name.clone(),
                            value: v.value,
                            doc,
                        }
                    })
                    .collect();
                tc.default = !tc.values.is_empty();
                tc.copy = true;
            }
            TypeForm::Bitfield { repr, members } => {
                tc.repr = repr.rust().to_string();
                tc.container_attr = format!("repr = {}", tc.repr);
                tc.bits = members
                    .iter()
                    .map(|b| {
                        let (ty, attr, extra) = match b.bits {
                            Bits::Flag(x) => (
                                "bool".to_string(),
                                format!("bit = {x}"),
                                format!("Bit {x}."),
                            ),
                            Bits::Range { lo, hi } => {
                                let w = hi - lo + 1;
                                let ty = if w <= 8 {
                                    "u8"
                                } else if w <= 16 {
                                    "u16"
                                } else if w <= 32 {
                                    "u32"
                                } else {
                                    "u64"
                                };
                                (
                                    ty.to_string(),
                                    format!("bits = {lo}..={hi}"),
                                    format!("Bits {lo}-{hi}."),
                                )
                            }
                        };
                        let mut doc = doc_lines(b.def.description.as_deref());
                        if !doc.is_empty() {
                            doc.push(String::new());
                        }
                        doc.push(extra);
                        BitCtx {
                            name: b.def.name.clone(),
                            ty,
                            attr,
                            doc,
                        }
                    })
                    .collect();
                tc.default = true;
                tc.copy = true;
            }
            TypeForm::Union { repr, variants } => {
                tc.repr = repr.rust().to_string();
                tc.container_attr = format!("tag = {}", tc.repr);
                tc.variants = variants
                    .iter()
                    .map(|v| {
                        let m = v.wire.as_ref().map(|w| map_wire(w, rt));
                        VariantCtx {
                            name: v.def.name.clone(),
                            tag: v.def.tag,
                            serde: m.as_ref().map(|m| m.serde.join(", ")).unwrap_or_default(),
                            ty: m.map(|m| m.ty),
                            doc: doc_lines(v.def.description.as_deref()),
                        }
                    })
                    .collect();
            }
        }
        if let Some(g) = groups.iter_mut().find(|g| g.name == t.group) {
            g.types.push(tc);
        }
    }
    let mut messages = Vec::new();
    for m in &spec.messages {
        if !spec.is_own(m.source) {
            continue;
        }
        let d = &m.def;
        let title = d
            .title
            .clone()
            .unwrap_or_else(|| jaus_spec::title_of(&d.name));
        let mut doc = vec![format!("{title} ({}).", d.code)];
        if !doc_lines(d.description.as_deref()).is_empty() {
            doc.push(String::new());
            doc.extend(doc_lines(d.description.as_deref()));
        }
        if let Some(i) = &d.interop {
            doc.push(String::new());
            doc.push("Interoperability:".into());
            doc.extend(doc_lines(Some(i)));
        }
        let report = spec.report_of(d).map(|r| r.def.name.clone());
        if let Some(r) = &report {
            doc.push(String::new());
            doc.push(format!("Answered by [`{r}`]."));
        }
        if d.experimental {
            doc.push(String::new());
            doc.push("Experimental (not part of RA 3.3).".into());
        }
        let mut container = vec![format!("code = {}", d.code)];
        if let Some(p) = m.presence {
            container.push(format!("presence = {}", p.rust()));
        }
        let embedded = m
            .fields
            .iter()
            .map(|f| &f.def)
            .filter_map(|f| {
                f.code_field.as_ref().map(|c| EmbeddedCtx {
                    field: f.name.clone(),
                    code_field: c.clone(),
                    complement: f.complement,
                    optional: f.bit.is_some(),
                })
            })
            .collect();
        let mc = MessageCtx {
            name: d.name.clone(),
            code: format!("{}", d.code),
            title,
            group: m.group.clone(),
            cfg: cfg_of(&m.group, gates),
            doc,
            container_attr: container.join(", "),
            default: all_default(spec, &m.fields),
            fields: m.fields.iter().map(|f| field_ctx(spec, f, rt)).collect(),
            embedded,
            report,
            experimental: d.experimental,
            class: class_variant(d).into(),
            read_only: d.access == Some(jaus_spec::Access::Read),
        };
        if let Some(g) = groups.iter_mut().find(|g| g.name == m.group) {
            g.messages.push(mc.clone());
        }
        messages.push(mc);
    }
    let queries = spec
        .messages
        .iter()
        .filter(|q| spec.is_own(q.source))
        .filter_map(|q| {
            let r = spec.report_of(&q.def)?;
            let cfg = match (cfg_of(&q.group, gates), cfg_of(&r.group, gates)) {
                (Some(a), Some(b)) if a != b => Some(format!("all({a}, {b})")),
                (Some(a), _) | (None, Some(a)) => Some(a),
                (None, None) => None,
            };
            Some(QueryCtx {
                query: q.def.name.clone(),
                report: r.def.name.clone(),
                query_code: q.def.code.to_string(),
                report_code: r.def.code.to_string(),
                cfg,
            })
        })
        .collect();
    if vendor {
        groups.retain(|g| !g.types.is_empty() || !g.messages.is_empty());
    }
    let runtime_codes = |role: fn(&MessageDef) -> bool| {
        let mut codes: Vec<Code> = spec
            .messages
            .iter()
            .filter(|m| spec.is_own(m.source) && role(&m.def))
            .map(|m| m.def.code)
            .collect();
        codes.sort();
        codes.iter().map(Code::to_string).collect()
    };
    Context {
        groups,
        messages,
        queries,
        runtime_inputs: runtime_codes(MessageDef::runtime_input),
        runtime_outputs: runtime_codes(MessageDef::runtime_output),
        vendor,
        requires: if vendor {
            requirements(spec)
        } else {
            Vec::new()
        },
    }
}
