//! Validation of a whole definition set, and resolution of every field into its wire
//! form. Every rule reports with the position of the offending key and names the
//! message/type and field concerned. The validated [`Spec`] is built only when no rule
//! is broken, so every field, representation and bit-field member in it is resolved.

use crate::model::*;
use crate::{
    Bits, Component, Field, Group, Int, Len, Member, Message, Source, Spec, SpecError, Type,
    TypeForm, Variant, Wire,
};
use std::collections::HashMap;

/// A definition as parsed, with the file it came from.
#[derive(Debug)]
pub(crate) struct Parsed<D> {
    /// The definition.
    pub def: D,
    /// Group name.
    pub group: String,
    /// Index into [`Draft::sources`].
    pub source: usize,
    /// YAML path of the definition (`messages[3]`).
    pub path: String,
}

/// Every file parsed, nothing checked or resolved yet.
#[derive(Debug)]
pub(crate) struct Draft {
    /// How many of the first sources are the base definitions an overlay extends.
    pub base_sources: usize,
    pub sources: Vec<Source>,
    pub groups: Vec<Group>,
    pub types: Vec<Parsed<TypeDef>>,
    pub messages: Vec<Parsed<MessageDef>>,
    pub components: Vec<Component>,
}

impl Draft {
    fn message(&self, name: &str) -> Option<&Parsed<MessageDef>> {
        self.messages.iter().find(|m| m.def.name == name)
    }

    fn ty(&self, name: &str) -> Option<&Parsed<TypeDef>> {
        self.types.iter().find(|t| t.def.name == name)
    }

    fn report_of(&self, query: &MessageDef) -> Option<&Parsed<MessageDef>> {
        crate::report_of(
            query,
            |n| self.message(n),
            |c| self.messages.iter().find(|m| m.def.code.0 == c),
        )
    }
}

const KEYWORDS: &[&str] = &[
    "as", "async", "await", "break", "const", "continue", "crate", "dyn", "else", "enum", "extern",
    "false", "fn", "for", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub",
    "ref", "return", "self", "Self", "static", "struct", "super", "trait", "true", "type",
    "unsafe", "use", "where", "while", "abstract", "become", "box", "do", "final", "macro",
    "override", "priv", "typeof", "unsized", "virtual", "yield", "try", "gen",
];

fn is_snake(s: &str) -> bool {
    !s.is_empty()
        && s.starts_with(|c: char| c.is_ascii_lowercase())
        && s.chars()
            .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
}

fn is_pascal(s: &str) -> bool {
    !s.is_empty()
        && s.starts_with(|c: char| c.is_ascii_uppercase())
        && s.chars().all(|c| c.is_ascii_alphanumeric())
}

struct Ctx<'a> {
    spec: &'a Draft,
    errors: Vec<SpecError>,
}

impl Ctx<'_> {
    fn err(&mut self, source: usize, path: &str, context: String, message: impl Into<String>) {
        let s = &self.spec.sources[source];
        self.errors.push(SpecError {
            file: s.path.clone(),
            pos: s.index.find(path),
            context,
            message: message.into(),
        });
    }
}

fn count_type(name: &str) -> Result<Int, String> {
    match Int::parse(name) {
        Some(i) if i.is_count() => Ok(i),
        _ => Err(format!(
            "`{name}` is not a count type: use an unsigned integer u8, u16 or u32"
        )),
    }
}

/// Resolves a field definition to its wire form, or says what is wrong with it.
fn resolve(spec: &Draft, f: &FieldDef) -> Result<Wire, String> {
    let ty = f.ty.as_str();
    let size = f.size.as_deref().map(count_type).transpose()?;
    let no = |what: &str, ok: bool| {
        if ok {
            Ok(())
        } else {
            Err(format!("`{what}` does not apply to a `{ty}` field"))
        }
    };
    no("scale", f.scale.is_none() || Int::parse(ty).is_some())?;
    no("of", f.of.is_none() || ty == "list")?;
    no(
        "length",
        f.length.is_none() || matches!(ty, "string" | "bytes" | "list"),
    )?;
    no("nul", !f.nul || ty == "string")?;
    no(
        "accept_short",
        !f.accept_short || matches!(f.length, Some(Length::Fixed(_))),
    )?;
    no("code_field", f.code_field.is_none() || ty == "bytes")?;
    no("count_field", f.count_field.is_none() || ty == "list")?;
    no(
        "offsets_of",
        f.offsets_of.is_none() || (ty == "list" && f.count_field.is_some()),
    )?;
    if ty == "flag" {
        if f.bit.is_none() {
            return Err("a `flag` is a presence-vector bit: give its `bit`".into());
        }
        return Ok(Wire::Flag);
    }
    if f.complement && f.code_field.is_none() {
        return Err("`complement` needs `code_field`".into());
    }
    if let Some(int) = Int::parse(ty) {
        no("count", f.count.is_none())?;
        no("size", size.is_none())?;
        return Ok(match f.scale {
            Some([lo, hi]) => {
                if lo.is_nan() || hi.is_nan() || lo >= hi || !lo.is_finite() || !hi.is_finite() {
                    return Err(format!(
                        "scale lower limit {lo} must be below upper limit {hi}"
                    ));
                }
                Wire::Scaled { int, lo, hi }
            }
            None => Wire::Int(int),
        });
    }
    let len = |f: &FieldDef| -> Result<Len, String> {
        match (f.length, &f.count) {
            (Some(_), Some(_)) => Err("give either `length` or `count`, not both".into()),
            (Some(Length::Fixed(n)), None) => Ok(Len::Fixed { n, accept_short: f.accept_short }),
            (Some(Length::Rest), None) => Ok(Len::Rest { nul: f.nul }),
            (Some(Length::Nul), None) if ty == "string" => Ok(Len::Nul),
            (Some(Length::Nul), None) => Err("`length: nul` applies to a string".into()),
            (None, Some(c)) => Ok(Len::Prefix(count_type(c)?)),
            (None, None) => Err(format!(
                "count field missing: a `{ty}` needs `length: N` (fixed), `length: rest` or `count: u8|u16|u32` (length prefix)"
            )),
        }
    };
    match ty {
        "f32" | "float" => Ok(Wire::F32),
        "f64" | "long float" | "double" => Ok(Wire::F64),
        "string" => {
            no("size", size.is_none())?;
            if f.nul && !matches!(f.length, Some(Length::Rest)) {
                return Err("`nul` applies to a string with `length: rest`".into());
            }
            Ok(Wire::Str(len(f)?))
        }
        "bytes" => {
            no("size", size.is_none())?;
            Ok(Wire::Bytes(len(f)?))
        }
        "message" => {
            no("count", f.count.is_none())?;
            Ok(Wire::Packet { size })
        }
        "list" => {
            no("size", size.is_none())?;
            let elem = f.of.as_ref().ok_or("a list needs `of:` (its element type)")?;
            if elem.0.bit.is_some() || !elem.0.name.is_empty() {
                return Err("a list element has no `name` or `bit`".into());
            }
            let elem = resolve(spec, &elem.0).map_err(|e| format!("list element: {e}"))?;
            if matches!(elem, Wire::Str(_) | Wire::Bytes(_)) {
                return Err("a list element cannot be a string or blob: make it a field of a record".into());
            }
            if let Some(field) = &f.count_field {
                if f.count.is_some() || f.length.is_some() {
                    return Err("give one of `count`, `count_field` and `length: rest`".into());
                }
                return Ok(Wire::ListField { field: field.clone(), elem: Box::new(elem), offsets_of: f.offsets_of.clone() });
            }
            let count = match (&f.count, f.length) {
                (Some(c), None) => Some(count_type(c)?),
                (None, Some(Length::Rest)) => None,
                (None, Some(Length::Nul)) => {
                    return Err("a list takes `count: T` or `length: rest`, not `nul`".into())
                }
                (None, Some(Length::Fixed(_))) => {
                    return Err("a list takes `count: T` or `length: rest`, not a fixed length".into())
                }
                (Some(_), Some(_)) => return Err("give either `count` or `length: rest`, not both".into()),
                (None, None) => {
                    return Err("count field missing: a list needs `count: u8|u16|u32` (or `length: rest`)".into())
                }
            };
            Ok(Wire::List { count, elem: Box::new(elem) })
        }
        name => match spec.ty(name) {
            Some(t) => {
                no("count", f.count.is_none())?;
                if f.tag_field.is_some() && t.def.kind != TypeKind::Union {
                    return Err("`tag_field` applies to a union-typed field".into());
                }
                Ok(Wire::Named { name: name.to_string(), kind: t.def.kind, size, tag_field: f.tag_field.clone() })
            }
            None => Err(format!(
                "unknown type `{name}`: use a basic type (u8, u16, u32, u64, i16, i32, i64, f32, f64 or their JAUS names), string, bytes, list, message, or a type defined under `types:`"
            )),
        },
    }
}

/// A presence vector type and fields, resolved.
type Body = (Option<Int>, Vec<Field>);

/// Checks the presence vector and fields of a message or record and resolves them;
/// `None` when an error was reported.
fn check_fields(
    cx: &mut Ctx<'_>,
    source: usize,
    owner_path: &str,
    owner: &str,
    presence: &Option<String>,
    fields: &[FieldDef],
) -> Option<Body> {
    let mut resolved = Some(Vec::with_capacity(fields.len()));
    let pv = match presence {
        None => None,
        Some(p) => match Int::parse(p) {
            Some(i) if i.is_count() => Some(i),
            _ => {
                cx.err(
                    source,
                    &format!("{owner_path}.presence"),
                    owner.to_string(),
                    format!("presence vector type `{p}` must be u8, u16 or u32"),
                );
                resolved = None;
                None
            }
        },
    };
    let mut bits: HashMap<u32, &str> = HashMap::new();
    let mut names: HashMap<&str, ()> = HashMap::new();
    for (i, f) in fields.iter().enumerate() {
        let path = format!("{owner_path}.fields[{i}]");
        let ctx = format!("{owner}, field `{}`", f.name);
        if !is_snake(&f.name) {
            cx.err(
                source,
                &format!("{path}.name"),
                ctx.clone(),
                format!("field name `{}` must be snake_case", f.name),
            );
        } else if KEYWORDS.contains(&f.name.as_str()) {
            cx.err(
                source,
                &format!("{path}.name"),
                ctx.clone(),
                format!("field name `{}` is a Rust keyword; choose another", f.name),
            );
        }
        if names.insert(&f.name, ()).is_some() {
            cx.err(
                source,
                &format!("{path}.name"),
                ctx.clone(),
                format!("duplicate field name `{}`", f.name),
            );
        }
        if let Some(b) = f.bit {
            match (presence, pv) {
                (None, _) => cx.err(
                    source,
                    &format!("{path}.bit"),
                    ctx.clone(),
                    format!("presence bit {b} but {owner} has no presence vector: add `presence: u8|u16|u32`"),
                ),
                (Some(_), Some(p)) if b as usize >= p.bytes() * 8 => cx.err(
                    source,
                    &format!("{path}.bit"),
                    ctx.clone(),
                    format!("presence bit {b} is out of range for a {} presence vector (bits 0-{})", p.rust(), p.bytes() * 8 - 1),
                ),
                _ => {}
            }
            if let Some(other) = bits.insert(b, &f.name) {
                cx.err(
                    source,
                    &format!("{path}.bit"),
                    ctx.clone(),
                    format!("presence bit {b} is already used by field `{other}`"),
                );
            }
        }
        match resolve(cx.spec, f) {
            Ok(w) => {
                let rest = matches!(
                    w,
                    Wire::Str(Len::Rest { .. })
                        | Wire::Bytes(Len::Rest { .. })
                        | Wire::List { count: None, .. }
                ) || f.accept_short;
                if rest && i + 1 != fields.len() {
                    cx.err(
                        source,
                        &format!("{path}.length"),
                        ctx.clone(),
                        "a field that runs to the end of the body (`length: rest`, `accept_short`) must be the last field",
                    );
                }
                if let Some(r) = &mut resolved {
                    r.push(Field {
                        def: f.clone(),
                        wire: w,
                    });
                }
            }
            Err(e) => {
                resolved = None;
                let key = if e.starts_with("unknown type") {
                    "type"
                } else if e.starts_with("scale") {
                    "scale"
                } else {
                    "type"
                };
                cx.err(source, &format!("{path}.{key}"), ctx.clone(), e);
            }
        }
        if let Some(tf) = &f.tag_field {
            if !fields[..i].iter().any(|g| &g.name == tf) && !in_container(cx.spec, owner, tf) {
                cx.err(
                    source,
                    &format!("{path}.tag_field"),
                    ctx.clone(),
                    format!("`tag_field: {tf}` names no earlier field"),
                );
            }
        }
        // Fields this one depends on: earlier in this struct, or in a struct that
        // contains it (a record nested in a message).
        let count_dep = f
            .count_field
            .as_deref()
            .map(|c| c.split('-').next().unwrap_or(c).trim().to_string());
        if let Some((_, m)) = f.count_field.as_deref().and_then(|c| c.split_once('-')) {
            if m.trim().parse::<u64>().is_err() {
                cx.err(
                    source,
                    &format!("{path}.count_field"),
                    ctx.clone(),
                    "`count_field` is a field name, optionally minus a constant (`num_joints - 1`)",
                );
            }
        }
        // The field depended on must be able to carry a count or a flag.
        for (key, dep) in [
            ("count_field", &count_dep),
            ("present_if", &f.present_if),
            ("tag_field", &f.tag_field),
        ] {
            let Some(dep) = dep else { continue };
            let target = fields[..i]
                .iter()
                .find(|g| &g.name == dep)
                .or_else(|| container_field(cx.spec, owner, dep));
            if let Some(t) = target {
                let ok = Int::parse(&t.ty).is_some_and(Int::unsigned)
                    || (key == "present_if" && t.ty == "flag");
                if !ok {
                    cx.err(
                        source,
                        &format!("{path}.{key}"),
                        ctx.clone(),
                        format!("`{key}: {dep}` names a field of type `{}`; it must be an unsigned integer{}", t.ty, if key == "present_if" { " or a flag" } else { "" }),
                    );
                }
            }
        }
        for (key, dep) in [("count_field", &count_dep), ("present_if", &f.present_if)] {
            if let Some(dep) = dep {
                let here = fields[..i].iter().any(|g| &g.name == dep);
                if !here && !in_container(cx.spec, owner, dep) {
                    cx.err(
                        source,
                        &format!("{path}.{key}"),
                        ctx.clone(),
                        format!("`{key}: {dep}` names no earlier field of `{}` or of a message containing it", owner_name(owner)),
                    );
                }
            }
        }
        if let Some(target) = &f.offsets_of {
            if !fields[i + 1..]
                .iter()
                .any(|g| &g.name == target && g.ty == "list")
            {
                cx.err(
                    source,
                    &format!("{path}.offsets_of"),
                    ctx.clone(),
                    format!("`offsets_of: {target}` names no later list field"),
                );
            }
        }
        if let Some(cf) = &f.code_field {
            let ok = fields[..i]
                .iter()
                .any(|g| &g.name == cf && Int::parse(&g.ty) == Some(Int::U16));
            if !ok {
                cx.err(
                    source,
                    &format!("{path}.code_field"),
                    ctx.clone(),
                    format!("`code_field: {cf}` must name an earlier u16 field of `{owner}`"),
                );
            }
        }
    }
    resolved.map(|fields| (pv, fields))
}

/// The type or message name inside a context string such as ``type `Task` ``.
fn owner_name(owner: &str) -> &str {
    owner.split('`').nth(1).unwrap_or(owner)
}

/// The field called `name` of a message or record that uses the record named in `owner`.
fn container_field<'s>(spec: &'s Draft, owner: &str, name: &str) -> Option<&'s FieldDef> {
    let record = owner_name(owner);
    let uses = |fields: &[FieldDef]| {
        fields
            .iter()
            .any(|f| f.ty == record || f.of.as_ref().is_some_and(|e| e.0.ty == record))
    };
    spec.messages
        .iter()
        .map(|m| &m.def.fields)
        .chain(spec.types.iter().map(|t| &t.def.fields))
        .filter(|fields| uses(fields))
        .find_map(|fields| fields.iter().find(|f| f.name == name))
}

/// Whether some message or record that uses the record named in `owner` (directly, or
/// as a list element) has a field called `name`.
fn in_container(spec: &Draft, owner: &str, name: &str) -> bool {
    let record = owner_name(owner);
    let uses = |fields: &[FieldDef]| {
        fields
            .iter()
            .any(|f| f.ty == record || f.of.as_ref().is_some_and(|e| e.0.ty == record))
    };
    let has = |fields: &[FieldDef]| fields.iter().any(|f| f.name == name);
    spec.messages
        .iter()
        .any(|m| uses(&m.def.fields) && has(&m.def.fields))
        || spec
            .types
            .iter()
            .any(|t| uses(&t.def.fields) && (has(&t.def.fields) || t.def.name == record))
}

/// Checks every rule on the parsed files and resolves them into a [`Spec`], or returns
/// every problem found, in file order.
pub(crate) fn validate(draft: Draft) -> Result<Spec, Vec<SpecError>> {
    let spec = &draft;
    let mut cx = Ctx {
        spec,
        errors: Vec::new(),
    };

    // Groups.
    for (si, s) in spec.sources.iter().enumerate() {
        let _ = s;
        let group = spec
            .messages
            .iter()
            .find(|m| m.source == si)
            .map(|m| m.group.clone())
            .or_else(|| {
                spec.types
                    .iter()
                    .find(|t| t.source == si)
                    .map(|t| t.group.clone())
            });
        if let Some(g) = group {
            if !is_snake(&g) {
                cx.err(
                    si,
                    "group",
                    String::new(),
                    format!("group name `{g}` must be snake_case (it is also a cargo feature)"),
                );
            }
        }
    }

    // Unique names across messages and types (both become Rust types).
    let mut seen: HashMap<&str, (usize, &str)> = HashMap::new();
    let entries = spec
        .types
        .iter()
        .map(|t| (t.def.name.as_str(), t.source, t.path.as_str(), "type"))
        .chain(
            spec.messages
                .iter()
                .map(|m| (m.def.name.as_str(), m.source, m.path.as_str(), "message")),
        );
    for (name, source, path, what) in entries {
        if !is_pascal(name) {
            cx.err(
                source,
                &format!("{path}.name"),
                format!("{what} `{name}`"),
                format!("name `{name}` must be PascalCase"),
            );
        }
        if matches!(
            name,
            "Message" | "Header" | "Packet" | "Address" | "CommandCode"
        ) {
            cx.err(
                source,
                &format!("{path}.name"),
                format!("{what} `{name}`"),
                format!("`{name}` is reserved by the SDK"),
            );
        }
        if let Some((other_src, other_path)) = seen.insert(name, (source, path)) {
            let o = &spec.sources[other_src];
            let pos = o.index.find(other_path);
            cx.err(
                source,
                &format!("{path}.name"),
                format!("{what} `{name}`"),
                format!(
                    "duplicate name `{name}` (first defined at {}:{}:{})",
                    o.path.display(),
                    pos.line,
                    pos.column
                ),
            );
        }
    }

    // Unique command codes.
    let mut codes: HashMap<u16, &Parsed<MessageDef>> = HashMap::new();
    for m in &spec.messages {
        if let Some(first) = codes.insert(m.def.code.0, m) {
            let o = &spec.sources[first.source];
            let pos = o.index.find(&first.path);
            cx.err(
                m.source,
                &format!("{}.code", m.path),
                format!("message `{}`", m.def.name),
                format!(
                    "duplicate command code {} (also `{}` at {}:{}:{})",
                    m.def.code,
                    first.def.name,
                    o.path.display(),
                    pos.line,
                    pos.column
                ),
            );
        }
    }

    // Types.
    let mut forms = Vec::with_capacity(spec.types.len());
    for t in &spec.types {
        let ctx = format!("type `{}`", t.def.name);
        let d = &t.def;
        let repr = d.repr.as_deref().map(|r| (r, Int::parse(r)));
        let need_repr = |cx: &mut Ctx<'_>, what: &str, allow_u64: bool| -> Option<Int> {
            match repr {
                Some((_, Some(i))) if i.unsigned() && (allow_u64 || i.is_count()) => Some(i),
                Some((r, _)) => {
                    cx.err(
                        t.source,
                        &format!("{}.repr", t.path),
                        ctx.clone(),
                        format!("`{r}` is not an unsigned integer type for {what}"),
                    );
                    None
                }
                None => {
                    cx.err(
                        t.source,
                        &format!("{}.kind", t.path),
                        ctx.clone(),
                        format!("{what} needs `repr: u8|u16|u32`"),
                    );
                    None
                }
            }
        };
        let form = match d.kind {
            TypeKind::Record => {
                check_fields(&mut cx, t.source, &t.path, &ctx, &d.presence, &d.fields)
                    .map(|(presence, fields)| TypeForm::Record { presence, fields })
            }
            TypeKind::Enum => {
                if d.values.is_empty() {
                    cx.err(
                        t.source,
                        &format!("{}.values", t.path),
                        ctx.clone(),
                        "an enum needs at least one named value",
                    );
                }
                let r = need_repr(&mut cx, "an enum", true);
                let mut vals: HashMap<u64, &str> = HashMap::new();
                for (i, v) in d.values.iter().enumerate() {
                    let p = format!("{}.values[{i}]", t.path);
                    if !is_pascal(&v.name) || v.name == "Unknown" {
                        cx.err(t.source, &format!("{p}.name"), ctx.clone(), format!("value name `{}` must be PascalCase and not `Unknown` (reserved for undefined values)", v.name));
                    }
                    if let Some(o) = vals.insert(v.value, &v.name) {
                        cx.err(
                            t.source,
                            &format!("{p}.value"),
                            ctx.clone(),
                            format!("value {} is already used by `{o}`", v.value),
                        );
                    }
                    if let Some(r) = r {
                        if r.bytes() < 8 && v.value >> (r.bytes() * 8) != 0 {
                            cx.err(
                                t.source,
                                &format!("{p}.value"),
                                ctx.clone(),
                                format!("value {} does not fit in {}", v.value, r.rust()),
                            );
                        }
                    }
                }
                r.map(|repr| TypeForm::Enum { repr })
            }
            TypeKind::Bitfield => {
                let repr = need_repr(&mut cx, "a bitfield", true);
                let width = repr.map_or(64, |r| r.bytes() as u32 * 8);
                let mut members = Some(Vec::with_capacity(d.bits.len()));
                let mut used: u64 = 0;
                for (i, b) in d.bits.iter().enumerate() {
                    let p = format!("{}.bits[{i}]", t.path);
                    let bits = match (b.bit, b.bits) {
                        (Some(x), None) => Bits::Flag(x),
                        (None, Some([lo, hi])) => Bits::Range { lo, hi },
                        _ => {
                            cx.err(t.source, &p, ctx.clone(), format!("member `{}` needs exactly one of `bit: N` or `bits: [low, high]`", b.name));
                            members = None;
                            continue;
                        }
                    };
                    let (lo, hi) = match bits {
                        Bits::Flag(x) => (x, x),
                        Bits::Range { lo, hi } => (lo, hi),
                    };
                    if lo > hi || hi >= width {
                        cx.err(
                            t.source,
                            &p,
                            ctx.clone(),
                            format!(
                                "bits {lo}..{hi} of `{}` are out of range for a {width}-bit field",
                                b.name
                            ),
                        );
                        members = None;
                        continue;
                    }
                    if let Some(m) = &mut members {
                        m.push(Member {
                            def: b.clone(),
                            bits,
                        });
                    }
                    let mask = if hi - lo == 63 {
                        u64::MAX
                    } else {
                        ((1u64 << (hi - lo + 1)) - 1) << lo
                    };
                    if used & mask != 0 {
                        cx.err(
                            t.source,
                            &p,
                            ctx.clone(),
                            format!("bits of `{}` overlap another member", b.name),
                        );
                    }
                    used |= mask;
                    if !is_snake(&b.name) || b.name == "reserved" {
                        cx.err(
                            t.source,
                            &format!("{p}.name"),
                            ctx.clone(),
                            format!(
                                "member name `{}` must be snake_case and not `reserved`",
                                b.name
                            ),
                        );
                    }
                }
                repr.zip(members)
                    .map(|(repr, members)| TypeForm::Bitfield { repr, members })
            }
            TypeKind::Union => {
                let repr = need_repr(&mut cx, "a union tag", false);
                let mut variants = Some(Vec::with_capacity(d.variants.len()));
                let mut tags: HashMap<u64, &str> = HashMap::new();
                for (i, v) in d.variants.iter().enumerate() {
                    let p = format!("{}.variants[{i}]", t.path);
                    if let Some(o) = tags.insert(v.tag, &v.name) {
                        cx.err(
                            t.source,
                            &format!("{p}.tag"),
                            ctx.clone(),
                            format!("tag {} is already used by `{o}`", v.tag),
                        );
                    }
                    let wire = match &v.ty {
                        None => None,
                        Some(ty) => {
                            let f = FieldDef {
                                ty: ty.clone(),
                                ..FieldDef::default()
                            };
                            match resolve(spec, &f) {
                                Ok(w) => Some(w),
                                Err(e) => {
                                    cx.err(t.source, &format!("{p}.type"), ctx.clone(), e);
                                    variants = None;
                                    continue;
                                }
                            }
                        }
                    };
                    if let Some(vs) = &mut variants {
                        vs.push(Variant {
                            def: v.clone(),
                            wire,
                        });
                    }
                }
                repr.zip(variants)
                    .map(|(repr, variants)| TypeForm::Union { repr, variants })
            }
        };
        forms.push(form);
    }

    // A record may hold itself only through a list (which can be empty).
    for t in spec.types.iter().filter(|t| t.def.kind == TypeKind::Record) {
        let mut stack: Vec<&str> = vec![t.def.name.as_str()];
        let mut seen: Vec<&str> = Vec::new();
        let mut cycle = false;
        while let Some(name) = stack.pop() {
            let Some(r) = spec.ty(name) else { continue };
            for f in &r.def.fields {
                if f.ty == t.def.name {
                    cycle = true;
                }
                if spec.ty(&f.ty).is_some() && !seen.contains(&f.ty.as_str()) {
                    seen.push(f.ty.as_str());
                    stack.push(f.ty.as_str());
                }
            }
        }
        if cycle {
            cx.err(
                t.source,
                &format!("{}.name", t.path),
                format!("type `{}`", t.def.name),
                "the record contains itself other than through a list, so it has no finite size: hold the nested records in a list",
            );
        }
    }

    // Messages.
    let mut bodies = Vec::with_capacity(spec.messages.len());
    for m in &spec.messages {
        let ctx = format!("message `{}`", m.def.name);
        bodies.push(check_fields(
            &mut cx,
            m.source,
            &m.path,
            &ctx,
            &m.def.presence,
            &m.def.fields,
        ));
        check_runtime(&mut cx, m, &ctx);
        let code = m.def.code.0;
        if let Some(explicit) = m.def.class {
            match crate::model::MessageClass::of_code(code) {
                Some(by_code) if by_code != explicit => cx.err(
                    m.source,
                    &format!("{}.class", m.path),
                    ctx.clone(),
                    format!(
                        "`class: {}` contradicts the code 0x{code:04X}, which is a {} code; `class:` is for experimental codes (0xD000-0xFFFF)",
                        explicit.as_str(),
                        by_code.as_str()
                    ),
                ),
                _ if explicit == crate::model::MessageClass::Experimental => cx.err(
                    m.source,
                    &format!("{}.class", m.path),
                    ctx.clone(),
                    "`class: experimental` says nothing: name the class (command, query, inform, ...) or leave `class` out",
                ),
                _ => {}
            }
        }
        let is_query = m.def.is_query();
        if let Some(r) = &m.def.report {
            if !is_query {
                cx.err(
                    m.source,
                    &format!("{}.report", m.path),
                    ctx.clone(),
                    "`report` applies to query messages (0x2000..0x3FFF, or `class: query` for an experimental code)",
                );
            } else if spec.message(r).is_none() {
                cx.err(
                    m.source,
                    &format!("{}.report", m.path),
                    ctx.clone(),
                    format!("report `{r}` is not defined"),
                );
            }
        } else if is_query && !m.def.no_report && spec.report_of(&m.def).is_none() {
            let hint = if (0x2000..0x4000).contains(&code) {
                format!(
                    "define the message with code 0x{:04X} (the complement rule), name it with `report:`, or mark the query `no_report: true`",
                    code + 0x2000
                )
            } else {
                "an experimental query names its report with `report:` (or is marked `no_report: true`)".to_string()
            };
            cx.err(
                m.source,
                &format!("{}.code", m.path),
                ctx.clone(),
                format!("query {} has no report: {hint}", m.def.code),
            );
        }
    }

    // Components.
    validate_components(&mut cx);
    let mut errors = cx.errors;
    // Every definition that could not be resolved reported why, so with no errors
    // every form and body is there.
    let forms: Option<Vec<TypeForm>> = forms.into_iter().collect();
    let bodies: Option<Vec<Body>> = bodies.into_iter().collect();
    match (forms, bodies) {
        (Some(forms), Some(bodies)) if errors.is_empty() => Ok(assemble(draft, forms, bodies)),
        _ => {
            debug_assert!(
                !errors.is_empty(),
                "a definition failed to resolve silently"
            );
            errors.sort_by(|a, b| {
                (&a.file, a.pos.line, a.pos.column).cmp(&(&b.file, b.pos.line, b.pos.column))
            });
            Err(errors)
        }
    }
}

/// The validated spec: each parsed definition with its resolved form.
fn assemble(draft: Draft, forms: Vec<TypeForm>, bodies: Vec<Body>) -> Spec {
    let warnings = overlay_warnings(&draft);
    Spec {
        base_sources: draft.base_sources,
        warnings,
        sources: draft.sources,
        groups: draft.groups,
        types: draft
            .types
            .into_iter()
            .zip(forms)
            .map(|(t, form)| Type {
                def: t.def,
                group: t.group,
                source: t.source,
                path: t.path,
                form,
            })
            .collect(),
        messages: draft
            .messages
            .into_iter()
            .zip(bodies)
            .map(|(m, (presence, fields))| Message {
                def: m.def,
                group: m.group,
                source: m.source,
                path: m.path,
                presence,
                fields,
            })
            .collect(),
        components: draft.components,
    }
}

/// `runtime:` names each role once, and `handles` and `shares` exclude each other.
fn check_runtime(cx: &mut Ctx<'_>, m: &Parsed<MessageDef>, ctx: &str) {
    let roles = &m.def.runtime;
    for (i, role) in roles.iter().enumerate() {
        if roles[..i].contains(role) {
            cx.err(
                m.source,
                &format!("{}.runtime[{i}]", m.path),
                ctx.to_string(),
                format!("runtime role `{role}` is listed twice"),
            );
        }
    }
    if m.def.runtime_owned() && roles.contains(&RuntimeRole::Shares) {
        cx.err(
            m.source,
            &format!("{}.runtime", m.path),
            ctx.to_string(),
            "runtime roles `handles` and `shares` exclude each other: `handles` keeps the message from component interfaces, `shares` lets them list it too",
        );
    }
}

/// Core states a mode transition may lead the component into.
const MODE_CORE_STATES: &[&str] = &["Standby", "Failure"];

fn validate_components(cx: &mut Ctx<'_>) {
    let spec = cx.spec;
    let mut ids: HashMap<u8, &str> = HashMap::new();
    let mut names: HashMap<&str, ()> = HashMap::new();
    for c in &spec.components {
        let d = &c.def;
        let ctx = format!("component `{}`", d.name);
        let at = |k: &str| format!("{}.{k}", c.path);
        if !is_pascal(&d.name) {
            cx.err(
                c.source,
                &at("name"),
                ctx.clone(),
                "component name must be PascalCase",
            );
        }
        if names.insert(&d.name, ()).is_some() || spec.message(&d.name).is_some() {
            cx.err(
                c.source,
                &at("name"),
                ctx.clone(),
                format!("name `{}` is already used", d.name),
            );
        }
        if d.id == 0 || d.id == 255 {
            cx.err(
                c.source,
                &at("id"),
                ctx.clone(),
                format!("component id {} is not in 1..=254", d.id),
            );
        } else if let Some(o) = ids.insert(d.id, &d.name) {
            cx.err(
                c.source,
                &at("id"),
                ctx.clone(),
                format!("component id {} is already used by `{o}`", d.id),
            );
        }
        if d.any_message && !(d.commands.is_empty() && d.accepts.is_empty() && d.emits.is_empty()) {
            cx.err(
                c.source,
                &at("any_message"),
                ctx.clone(),
                "a component with `any_message: true` takes and sends every message: leave `commands`, `accepts` and `emits` empty",
            );
        }
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
                        ctx.clone(),
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
                        cx.err(c.source, &path, ctx.clone(), msg);
                        continue;
                    }
                    if m.def.runtime_owned() {
                        cx.err(
                            c.source,
                            &path,
                            ctx.clone(),
                            format!("`{name}` (0x{code:04X}) is handled by the component runtime for every component: remove it from `{key}`"),
                        );
                        continue;
                    }
                }
                if key == "commands" && m.def.class() != crate::model::MessageClass::Command {
                    cx.err(
                        c.source,
                        &path,
                        ctx.clone(),
                        format!("`{name}` (0x{code:04X}) is not a command (0x0000-0x1FFF, or `class: command` for an experimental code): list it in `accepts`"),
                    );
                }
            }
        }
        if let Some(m) = &d.modes {
            validate_modes(cx, c, m, &ctx);
        }
    }
}

fn validate_modes(cx: &mut Ctx<'_>, c: &crate::Component, m: &crate::model::ModesDef, ctx: &str) {
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

/// What is legal but probably wrong in a vendor's overlay: a message of its own with a
/// code outside the experimental range, which a later revision of the standard may
/// take.
fn overlay_warnings(draft: &Draft) -> Vec<SpecError> {
    if draft.base_sources == 0 {
        return Vec::new();
    }
    draft
        .messages
        .iter()
        .filter(|m| m.source >= draft.base_sources && m.def.code.0 < 0xD000)
        .map(|m| {
            let s = &draft.sources[m.source];
            SpecError {
                file: s.path.clone(),
                pos: s.index.find(&format!("{}.code", m.path)),
                context: format!("message `{}`", m.def.name),
                message: format!(
                    "code {} is outside the experimental range 0xD000-0xFFFF: a later revision of the standard may give it to another message",
                    m.def.code
                ),
            }
        })
        .collect()
}
