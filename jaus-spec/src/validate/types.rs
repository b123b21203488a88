//! Named types: each resolved into its form by kind (a record's fields, an enum's
//! values, a bit field's members, a union's variants), and records that contain
//! themselves.

use super::fields::check_fields;
use super::names::{is_pascal, is_snake};
use super::wire::resolve;
use super::{Ctx, Parsed};
use crate::model::{FieldDef, TypeDef, TypeKind};
use crate::resolved::{Bits, Int, Member, TypeForm, Variant};
use std::collections::HashMap;

/// Checks every named type and resolves its form; `None` for a type with an error
/// reported.
pub(super) fn check_types(cx: &mut Ctx<'_>) -> Vec<Option<TypeForm>> {
    let spec = cx.spec;
    let mut forms = Vec::with_capacity(spec.types.len());
    for t in &spec.types {
        let ctx = format!("type `{}`", t.def.name);
        let d = &t.def;
        let form = match d.kind {
            TypeKind::Record => check_fields(cx, t.source, &t.path, &ctx, &d.presence, &d.fields)
                .map(|(presence, fields)| TypeForm::Record { presence, fields }),
            TypeKind::Enum => check_enum(cx, t, &ctx),
            TypeKind::Bitfield => check_bitfield(cx, t, &ctx),
            TypeKind::Union => check_union(cx, t, &ctx),
        };
        forms.push(form);
    }
    forms
}

/// The `repr:` of an enum, bit field or union (`what`): an unsigned integer type, u64
/// only if `allow_u64`.
fn need_repr(
    cx: &mut Ctx<'_>,
    t: &Parsed<TypeDef>,
    ctx: &str,
    what: &str,
    allow_u64: bool,
) -> Option<Int> {
    let repr = t.def.repr.as_deref().map(|r| (r, Int::parse(r)));
    match repr {
        Some((_, Some(i))) if i.unsigned() && (allow_u64 || i.is_count()) => Some(i),
        Some((r, _)) => {
            cx.err(
                t.source,
                &format!("{}.repr", t.path),
                ctx.to_string(),
                format!("`{r}` is not an unsigned integer type for {what}"),
            );
            None
        }
        None => {
            cx.err(
                t.source,
                &format!("{}.kind", t.path),
                ctx.to_string(),
                format!("{what} needs `repr: u8|u16|u32`"),
            );
            None
        }
    }
}

/// An enum has values, each `PascalCase` (not `Unknown`), unique and fitting its
/// `repr`.
fn check_enum(cx: &mut Ctx<'_>, t: &Parsed<TypeDef>, ctx: &str) -> Option<TypeForm> {
    let d = &t.def;
    if d.values.is_empty() {
        cx.err(
            t.source,
            &format!("{}.values", t.path),
            ctx.to_string(),
            "an enum needs at least one named value",
        );
    }
    let r = need_repr(cx, t, ctx, "an enum", true);
    let mut vals: HashMap<u64, &str> = HashMap::new();
    for (i, v) in d.values.iter().enumerate() {
        let p = format!("{}.values[{i}]", t.path);
        if !is_pascal(&v.name) || v.name == "Unknown" {
            cx.err(
                t.source,
                &format!("{p}.name"),
                ctx.to_string(),
                format!(
                    "value name `{}` must be PascalCase and not `Unknown` (reserved for undefined values)",
                    v.name
                ),
            );
        }
        if let Some(o) = vals.insert(v.value, &v.name) {
            cx.err(
                t.source,
                &format!("{p}.value"),
                ctx.to_string(),
                format!("value {} is already used by `{o}`", v.value),
            );
        }
        if let Some(r) = r {
            if r.bytes() < 8 && v.value >> (r.bytes() * 8) != 0 {
                cx.err(
                    t.source,
                    &format!("{p}.value"),
                    ctx.to_string(),
                    format!("value {} does not fit in {}", v.value, r.rust()),
                );
            }
        }
    }
    r.map(|repr| TypeForm::Enum { repr })
}

/// A bit field's members each take one bit or a range of bits inside its `repr`,
/// overlap no other member and are named `snake_case` (not `reserved`).
fn check_bitfield(cx: &mut Ctx<'_>, t: &Parsed<TypeDef>, ctx: &str) -> Option<TypeForm> {
    let d = &t.def;
    let repr = need_repr(cx, t, ctx, "a bitfield", true);
    let width = repr.map_or(64, |r| r.bytes() as u32 * 8);
    let mut members = Some(Vec::with_capacity(d.bits.len()));
    let mut used: u64 = 0;
    for (i, b) in d.bits.iter().enumerate() {
        let p = format!("{}.bits[{i}]", t.path);
        let bits = match (b.bit, b.bits) {
            (Some(x), None) => Bits::Flag(x),
            (None, Some([lo, hi])) => Bits::Range { lo, hi },
            _ => {
                cx.err(
                    t.source,
                    &p,
                    ctx.to_string(),
                    format!(
                        "member `{}` needs exactly one of `bit: N` or `bits: [low, high]`",
                        b.name
                    ),
                );
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
                ctx.to_string(),
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
                ctx.to_string(),
                format!("bits of `{}` overlap another member", b.name),
            );
        }
        used |= mask;
        if !is_snake(&b.name) || b.name == "reserved" {
            cx.err(
                t.source,
                &format!("{p}.name"),
                ctx.to_string(),
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

/// A union's tags are unique and each variant's type (if any) resolves.
fn check_union(cx: &mut Ctx<'_>, t: &Parsed<TypeDef>, ctx: &str) -> Option<TypeForm> {
    let d = &t.def;
    let repr = need_repr(cx, t, ctx, "a union tag", false);
    if d.variants.is_empty() {
        // Nothing could be decoded (every tag unknown) and no Rust enum can be empty.
        cx.err(
            t.source,
            &format!("{}.variants", t.path),
            ctx.to_string(),
            "a union needs at least one variant".to_string(),
        );
        return None;
    }
    let mut variants = Some(Vec::with_capacity(d.variants.len()));
    let mut tags: HashMap<u64, &str> = HashMap::new();
    for (i, v) in d.variants.iter().enumerate() {
        let p = format!("{}.variants[{i}]", t.path);
        if let Some(o) = tags.insert(v.tag, &v.name) {
            cx.err(
                t.source,
                &format!("{p}.tag"),
                ctx.to_string(),
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
                match resolve(cx.spec, &f) {
                    Ok(w) => Some(w),
                    Err(e) => {
                        cx.err(t.source, &format!("{p}.type"), ctx.to_string(), e);
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

/// A record may hold itself only through a list (which can be empty).
pub(super) fn check_record_cycles(cx: &mut Ctx<'_>) {
    let spec = cx.spec;
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
}
