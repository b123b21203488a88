//! The fields of a message or record: names, presence bits, wire forms, and the
//! fields they depend on (`count_field`, `present_if`, `tag_field`, `offsets_of`,
//! `code_field`), earlier in the same body or in a message or record containing it.

use super::names::{is_snake, KEYWORDS};
use super::wire::resolve;
use super::{Ctx, Draft};
use crate::count::CountRef;
use crate::model::{FieldDef, TypeKind};
use crate::resolved::{Field, Int, Len, Wire};
use std::collections::HashMap;

/// A presence vector type and fields, resolved.
pub(super) type Body = (Option<Int>, Vec<Field>);

/// The message or record whose fields are checked.
struct Owner<'a> {
    /// Index into the sources.
    source: usize,
    /// ``message `Name` `` or ``type `Name` ``.
    name: &'a str,
    /// Its fields, as written.
    fields: &'a [FieldDef],
}

/// One field being checked.
struct At<'a> {
    /// Its index in the owner's fields.
    i: usize,
    /// The definition.
    f: &'a FieldDef,
    /// Its YAML path (`messages[3].fields[2]`).
    path: String,
    /// ``message `Name`, field `name` ``.
    ctx: String,
}

impl At<'_> {
    /// The path of one of its keys.
    fn key(&self, key: &str) -> String {
        format!("{}.{key}", self.path)
    }
}

/// Checks the presence vector and fields of a message or record and resolves them;
/// `None` when an error was reported.
pub(super) fn check_fields(
    cx: &mut Ctx<'_>,
    source: usize,
    owner_path: &str,
    owner: &str,
    presence: &Option<String>,
    fields: &[FieldDef],
) -> Option<Body> {
    let o = Owner {
        source,
        name: owner,
        fields,
    };
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
        let at = At {
            i,
            f,
            path: format!("{owner_path}.fields[{i}]"),
            ctx: format!("{owner}, field `{}`", f.name),
        };
        check_name(cx, &o, &at, &mut names);
        if let Some(b) = f.bit {
            check_presence_bit(cx, &o, &at, b, presence.is_some(), pv, &mut bits);
        }
        match resolve_field(cx, &o, &at) {
            Some(field) => {
                if let Some(r) = &mut resolved {
                    r.push(field);
                }
            }
            None => resolved = None,
        }
        check_tag_field(cx, &o, &at);
        check_dependencies(cx, &o, &at);
        check_offsets_of(cx, &o, &at);
        check_code_field(cx, &o, &at);
        check_embeds_if(cx, &o, &at);
    }
    resolved.map(|fields| (pv, fields))
}

/// The field name is `snake_case`, no Rust keyword, and unique in its body.
fn check_name<'f>(cx: &mut Ctx<'_>, o: &Owner<'_>, at: &At<'f>, names: &mut HashMap<&'f str, ()>) {
    let name = &at.f.name;
    if !is_snake(name) {
        cx.err(
            o.source,
            &at.key("name"),
            at.ctx.clone(),
            format!("field name `{name}` must be snake_case"),
        );
    } else if KEYWORDS.contains(&name.as_str()) {
        cx.err(
            o.source,
            &at.key("name"),
            at.ctx.clone(),
            format!("field name `{name}` is a Rust keyword; choose another"),
        );
    }
    if names.insert(name, ()).is_some() {
        cx.err(
            o.source,
            &at.key("name"),
            at.ctx.clone(),
            format!("duplicate field name `{name}`"),
        );
    }
}

/// A presence bit `b` needs a presence vector (`has_presence`; `pv` when its type is
/// valid) wide enough, and is used by one field only.
fn check_presence_bit<'f>(
    cx: &mut Ctx<'_>,
    o: &Owner<'_>,
    at: &At<'f>,
    b: u32,
    has_presence: bool,
    pv: Option<Int>,
    bits: &mut HashMap<u32, &'f str>,
) {
    match (has_presence, pv) {
        (false, _) => cx.err(
            o.source,
            &at.key("bit"),
            at.ctx.clone(),
            format!(
                "presence bit {b} but {} has no presence vector: add `presence: u8|u16|u32`",
                o.name
            ),
        ),
        (true, Some(p)) if b as usize >= p.bytes() * 8 => cx.err(
            o.source,
            &at.key("bit"),
            at.ctx.clone(),
            format!(
                "presence bit {b} is out of range for a {} presence vector (bits 0-{})",
                p.rust(),
                p.bytes() * 8 - 1
            ),
        ),
        _ => {}
    }
    if let Some(other) = bits.insert(b, &at.f.name) {
        cx.err(
            o.source,
            &at.key("bit"),
            at.ctx.clone(),
            format!("presence bit {b} is already used by field `{other}`"),
        );
    }
}

/// The field's wire form ([`resolve`]), or `None` with the problem reported; a field
/// that runs to the end of the body must be the last.
fn resolve_field(cx: &mut Ctx<'_>, o: &Owner<'_>, at: &At<'_>) -> Option<Field> {
    let f = at.f;
    match resolve(cx.spec, f) {
        Ok(w) => {
            let rest = matches!(
                w,
                Wire::Str(Len::Rest { .. })
                    | Wire::Bytes(Len::Rest { .. })
                    | Wire::List { count: None, .. }
            ) || f.accept_short;
            if rest && at.i + 1 != o.fields.len() {
                cx.err(
                    o.source,
                    &at.key("length"),
                    at.ctx.clone(),
                    "a field that runs to the end of the body (`length: rest`, `accept_short`) must be the last field",
                );
            }
            Some(Field {
                def: f.clone(),
                wire: w,
            })
        }
        Err(e) => {
            let key = if e.starts_with("unknown type") {
                "type"
            } else if e.starts_with("scale") {
                "scale"
            } else if e == super::wire::COUNT_FIELD_SYNTAX {
                "count_field"
            } else {
                "type"
            };
            cx.err(o.source, &at.key(key), at.ctx.clone(), e);
            None
        }
    }
}

/// `tag_field` names an earlier field (of this body or of one containing it).
fn check_tag_field(cx: &mut Ctx<'_>, o: &Owner<'_>, at: &At<'_>) {
    let Some(tf) = &at.f.tag_field else { return };
    if !o.fields[..at.i].iter().any(|g| &g.name == tf) && !in_container(cx.spec, o.name, tf) {
        cx.err(
            o.source,
            &at.key("tag_field"),
            at.ctx.clone(),
            format!("`tag_field: {tf}` names no earlier field"),
        );
    }
}

/// The fields this one depends on (its count, the flag it is present by, its union
/// tag) can carry a count or a flag, and the count and the flag are earlier fields of
/// this body or of one containing it (a record nested in a message).
fn check_dependencies(cx: &mut Ctx<'_>, o: &Owner<'_>, at: &At<'_>) {
    let f = at.f;
    let fields = o.fields;
    let i = at.i;
    // (A `count_field` that does not parse was reported when resolving it: its name
    // part is still checked.)
    let count_dep = f.count_field.as_deref().map(|c| match CountRef::parse(c) {
        Ok(r) => r.field,
        Err(e) => e.field,
    });
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
            .or_else(|| container_field(cx.spec, o.name, dep));
        if let Some(t) = target {
            let ok = Int::parse(&t.ty).is_some_and(Int::unsigned)
                || (key == "present_if" && t.ty == "flag");
            if !ok {
                cx.err(
                    o.source,
                    &at.key(key),
                    at.ctx.clone(),
                    format!(
                        "`{key}: {dep}` names a field of type `{}`; it must be an unsigned integer{}",
                        t.ty,
                        if key == "present_if" { " or a flag" } else { "" }
                    ),
                );
            }
        }
    }
    for (key, dep) in [("count_field", &count_dep), ("present_if", &f.present_if)] {
        if let Some(dep) = dep {
            let here = fields[..i].iter().any(|g| &g.name == dep);
            if !here && !in_container(cx.spec, o.name, dep) {
                cx.err(
                    o.source,
                    &at.key(key),
                    at.ctx.clone(),
                    format!(
                        "`{key}: {dep}` names no earlier field of `{}` or of a message containing it",
                        owner_name(o.name)
                    ),
                );
            }
        }
    }
}

/// `offsets_of` names a later list field of this body.
fn check_offsets_of(cx: &mut Ctx<'_>, o: &Owner<'_>, at: &At<'_>) {
    let Some(target) = &at.f.offsets_of else {
        return;
    };
    if !o.fields[at.i + 1..]
        .iter()
        .any(|g| &g.name == target && g.ty == "list")
    {
        cx.err(
            o.source,
            &at.key("offsets_of"),
            at.ctx.clone(),
            format!("`offsets_of: {target}` names no later list field"),
        );
    }
}

/// `code_field` names an earlier u16 field of this body.
fn check_code_field(cx: &mut Ctx<'_>, o: &Owner<'_>, at: &At<'_>) {
    let Some(cf) = &at.f.code_field else { return };
    let ok = o.fields[..at.i]
        .iter()
        .any(|g| &g.name == cf && Int::parse(&g.ty) == Some(Int::U16));
    if !ok {
        cx.err(
            o.source,
            &at.key("code_field"),
            at.ctx.clone(),
            format!(
                "`code_field: {cf}` must name an earlier u16 field of `{}`",
                o.name
            ),
        );
    }
}

/// `embeds_if: FIELD == VALUE` names an earlier field of this body, an enumeration
/// with a value of that name or an integer that can hold the value.
fn check_embeds_if(cx: &mut Ctx<'_>, o: &Owner<'_>, at: &At<'_>) {
    let Some(cond) = &at.f.embeds_if else { return };
    let problem = match crate::model::embeds_condition(cond) {
        None => Some(format!(
            "`embeds_if: {cond}` is not of the form `FIELD == VALUE` (`format == JausMessage`)"
        )),
        Some((field, value)) => match o.fields[..at.i].iter().find(|g| g.name == field) {
            None => Some(format!(
                "`embeds_if: {cond}`: `{field}` is no earlier field of `{}`",
                o.name
            )),
            Some(g) => match (
                Int::parse(&g.ty),
                cx.spec
                    .types
                    .iter()
                    .map(|t| &t.def)
                    .find(|t| t.name == g.ty),
            ) {
                (Some(_), _) => value.parse::<u64>().is_err().then(|| {
                    format!("`embeds_if: {cond}`: `{field}` is an integer; `{value}` is not")
                }),
                (None, Some(t)) if t.kind == TypeKind::Enum => (!t
                    .values
                    .iter()
                    .any(|v| v.name == value || v.value.to_string() == value))
                .then(|| format!("`embeds_if: {cond}`: `{}` has no value `{value}`", g.ty)),
                _ => Some(format!(
                    "`embeds_if: {cond}`: `{field}` must be an integer or an enumeration"
                )),
            },
        },
    };
    if let Some(message) = problem {
        cx.err(o.source, &at.key("embeds_if"), at.ctx.clone(), message);
    }
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
