//! One field definition resolved into its wire form ([`Wire`]), or what is wrong with
//! it: which keys apply to which types, lengths and counts, list elements, and the
//! named type a field refers to.

use super::Draft;
use crate::count::CountRef;
use crate::model::{FieldDef, Length, TypeKind};
use crate::resolved::{Int, Len, Wire};

/// The integer type `name` if it can carry a count (u8, u16, u32).
fn count_type(name: &str) -> Result<Int, String> {
    match Int::parse(name) {
        Some(i) if i.is_count() => Ok(i),
        _ => Err(format!(
            "`{name}` is not a count type: use an unsigned integer u8, u16 or u32"
        )),
    }
}

/// What is wrong with a `count_field` that does not parse (reported at that key).
pub(super) const COUNT_FIELD_SYNTAX: &str =
    "`count_field` is a field name, optionally minus a constant (`num_joints - 1`)";

/// Resolves a field definition to its wire form, or says what is wrong with it.
pub(super) fn resolve(spec: &Draft, f: &FieldDef) -> Result<Wire, String> {
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
    no("embeds", f.embeds.is_none() || ty == "bytes")?;
    if f.embeds.is_some() && f.code_field.is_some() {
        return Err(
            "`embeds` and `code_field` are two forms of an embedded message: give one".into(),
        );
    }
    if f.embeds_if.is_some() && f.embeds.is_none() {
        return Err("`embeds_if` needs `embeds`".into());
    }
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
                let field = CountRef::parse(field).map_err(|_| COUNT_FIELD_SYNTAX)?;
                return Ok(Wire::ListField { field, elem: Box::new(elem), offsets_of: f.offsets_of.clone() });
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
