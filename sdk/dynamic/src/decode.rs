//! Bytes → [`Value`], walking a layout with the SDK codec's reader: the order of reads,
//! the checks and the errors are those of the derived decoders.

use crate::ints;
use crate::schema::{Body, FieldLayout, FormLayout, Layouts, WireLayout};
use crate::value::Value;
use jaus::codec::{
    check_presence, get_cstring, get_fixed_string, get_rest_string, latin1_to_string, Decode,
    DecodeError, DecodeErrorKind, Reader,
};
use jaus_spec::{Int, Len};

/// Decodes a message body (`body`) of layout `b`; the whole body must be used.
pub(crate) fn message(l: &Layouts, b: &Body, bytes: &[u8]) -> Result<Value, DecodeError> {
    let mut r = Reader::new(bytes);
    let v = body(l, b, &mut r, true)?;
    r.finish()?;
    Ok(v)
}

fn body(l: &Layouts, b: &Body, r: &mut Reader<'_>, is_message: bool) -> Result<Value, DecodeError> {
    // Records (which may nest, even recursively) count their depth.
    let nested = !is_message && !b.fields.is_empty();
    if nested {
        r.enter()?;
    }
    let mut pv = 0u64;
    let mut undefined = false;
    if let Some(p) = b.presence {
        let at = r.offset();
        pv = ints::read_u(p, r).map_err(|e| e.in_field(b.pv_path))?;
        let rest_present = match b.fields.last() {
            Some(f) if runs_to_end(&f.wire) => match f.bit {
                Some(bit) => pv & (1u64 << bit) != 0,
                None => true,
            },
            _ => false,
        };
        undefined = check_presence(pv, b.known, is_message, rest_present, at)
            .map_err(|e| e.in_field(b.pv_path))?;
    }
    let mut out = Vec::with_capacity(b.fields.len());
    for f in &b.fields {
        match (&f.wire, f.bit, f.present_if) {
            (WireLayout::Flag, ..) => {
                let set = f.bit.is_some_and(|bit| pv & (1u64 << bit) != 0);
                if let Some(var) = f.var {
                    r.vars().set(var, u64::from(set));
                }
                out.push((f.name, Value::Bool(set)));
            }
            (_, Some(bit), _) => {
                if pv & (1u64 << bit) != 0 {
                    out.push((f.name, field(l, f, r)?));
                }
            }
            (_, None, Some(flag)) => {
                let present = r.var(flag).map_err(|e| e.in_field(f.path))? != 0;
                if present {
                    out.push((f.name, field(l, f, r)?));
                }
            }
            _ => {
                let v = field(l, f, r)?;
                if let Some(var) = f.var {
                    r.vars().set(var, v.as_u64().unwrap_or(0));
                }
                out.push((f.name, v));
            }
        }
    }
    // Fields of a newer revision, appended under bits this one does not define.
    if undefined {
        r.rest();
    }
    if nested {
        r.leave();
    }
    Ok(Value::Record(out))
}

fn runs_to_end(w: &WireLayout) -> bool {
    matches!(
        w,
        WireLayout::Bytes(Len::Rest { .. })
            | WireLayout::Str(Len::Rest { .. })
            | WireLayout::List { count: None, .. }
    )
}

fn field(l: &Layouts, f: &FieldLayout, r: &mut Reader<'_>) -> Result<Value, DecodeError> {
    value(l, &f.wire, r).map_err(|e| e.in_field(f.path))
}

/// One value of layout `w`.
fn value(l: &Layouts, w: &WireLayout, r: &mut Reader<'_>) -> Result<Value, DecodeError> {
    Ok(match w {
        WireLayout::Int(i) => match ints::read(*i, r)? {
            Ok(v) => Value::UInt(v),
            Err(v) => Value::Int(v),
        },
        WireLayout::F32 => Value::F32(f32::decode(r)?),
        WireLayout::F64 => Value::F64(f64::decode(r)?),
        WireLayout::Scaled(i, s) => Value::Real(ints::read_scaled(*i, s, r)?),
        WireLayout::Named {
            ty,
            tag_var: Some(var),
            ..
        } => {
            let tag = r.var(var)?;
            union_value(l, *ty, tag, r)?
        }
        WireLayout::Named {
            ty,
            size: Some(size),
            ..
        } => sized(*size, r, |r| named(l, *ty, r))?,
        WireLayout::Named { ty, .. } => named(l, *ty, r)?,
        WireLayout::Str(len) => Value::Text(match *len {
            Len::Nul => get_cstring(r)?,
            Len::Fixed { n, accept_short } => get_fixed_string(r, n, accept_short)?,
            Len::Prefix(c) => {
                let n = ints::read_count(c, r, 1)?;
                latin1_to_string(r.take(n)?)
            }
            Len::Rest { nul: true } => get_rest_string(r),
            Len::Rest { nul: false } => latin1_to_string(r.rest()),
        }),
        WireLayout::Bytes(len) => Value::Bytes(match *len {
            Len::Fixed { n, .. } => r.take(n)?.to_vec(),
            Len::Prefix(c) => {
                let n = ints::read_count(c, r, 1)?;
                r.take(n)?.to_vec()
            }
            Len::Rest { .. } | Len::Nul => r.rest().to_vec(),
        }),
        WireLayout::List { count, elem } => list(l, *count, elem, r)?,
        WireLayout::ListVar { var, minus, elem } => {
            let n = r.var(var)?.saturating_sub(*minus);
            let n = r.check_count(n, min_len(l, elem, 0))?;
            let mut out = Vec::with_capacity(n.min(r.remaining()));
            for _ in 0..n {
                out.push(value(l, elem, r)?);
            }
            Value::List(out)
        }
        // A flag has no bytes of its own (handled by the body).
        WireLayout::Flag => Value::Bool(false),
        WireLayout::Packet { size: Some(size) } => {
            sized(*size, r, |r| jaus::Packet::decode(r).map(Value::Packet))?
        }
        WireLayout::Packet { size: None } => Value::Packet(jaus::Packet::decode(r)?),
    })
}

/// A value behind its byte length, which must match what the value's decoder uses.
fn sized(
    size: Int,
    r: &mut Reader<'_>,
    decode: impl FnOnce(&mut Reader<'_>) -> Result<Value, DecodeError>,
) -> Result<Value, DecodeError> {
    let n = ints::read_count(size, r, 1)?;
    let mut sub = r.sub(n)?;
    let v = decode(&mut sub)?;
    if sub.remaining() != 0 {
        return Err(DecodeError::new(
            DecodeErrorKind::SizeMismatch {
                announced: n,
                consumed: n - sub.remaining(),
            },
            sub.offset(),
        ));
    }
    Ok(v)
}

fn list(
    l: &Layouts,
    count: Option<Int>,
    elem: &WireLayout,
    r: &mut Reader<'_>,
) -> Result<Value, DecodeError> {
    if let WireLayout::Scaled(i, s) = elem {
        let size = i.bytes();
        let n = match count {
            Some(c) => ints::read_count(c, r, size)?,
            None => r.remaining() / size,
        };
        let mut out = Vec::with_capacity(n);
        for _ in 0..n {
            out.push(Value::Real(ints::read_scaled(*i, s, r)?));
        }
        if count.is_none() && r.remaining() != 0 {
            return Err(DecodeError::new(
                DecodeErrorKind::TrailingBytes {
                    count: r.remaining(),
                },
                r.offset(),
            ));
        }
        return Ok(Value::List(out));
    }
    let mut out = Vec::new();
    match count {
        Some(c) => {
            let n = ints::read_count(c, r, min_len(l, elem, 0))?;
            out.reserve(n.min(r.remaining()));
            for _ in 0..n {
                out.push(value(l, elem, r)?);
            }
        }
        None => {
            while r.remaining() > 0 {
                let before = r.remaining();
                out.push(value(l, elem, r)?);
                if r.remaining() == before {
                    // An element that takes no bytes would repeat forever.
                    return Err(DecodeError::new(
                        DecodeErrorKind::CountBeyondBuffer {
                            count: out.len(),
                            remaining: before,
                        },
                        r.offset(),
                    ));
                }
            }
        }
    }
    Ok(Value::List(out))
}

/// A value of the named type `ty`.
fn named(l: &Layouts, ty: usize, r: &mut Reader<'_>) -> Result<Value, DecodeError> {
    let Some(t) = l.types.get(ty) else {
        return Err(DecodeError::new(
            DecodeErrorKind::UndefinedValue { value: ty as u64 },
            r.offset(),
        ));
    };
    match &t.form {
        FormLayout::Record(b) => body(l, b, r, false),
        FormLayout::Enum { repr, values } => {
            let v = ints::read_u(*repr, r)?;
            Ok(match values.iter().find(|(_, x)| *x == v) {
                Some((name, _)) => Value::Enum(name, v),
                None => Value::UnknownEnum(v),
            })
        }
        FormLayout::Bits {
            repr,
            members,
            undefined,
        } => {
            let x = ints::read_u(*repr, r)?;
            let m = members
                .iter()
                .map(|&(name, _, lo, hi, flag)| {
                    let v = (x >> lo) & crate::schema::mask(hi - lo + 1);
                    (
                        name,
                        if flag {
                            Value::Bool(v != 0)
                        } else {
                            Value::UInt(v)
                        },
                    )
                })
                .collect();
            Ok(Value::Bits(m, x & undefined))
        }
        FormLayout::Union { tag, .. } => {
            let at = r.offset();
            let t = ints::read_u(*tag, r)?;
            match union_value(l, ty, t, r) {
                Err(e)
                    if matches!(e.kind(), DecodeErrorKind::UndefinedValue { .. })
                        && e.offset() == at + tag.bytes() =>
                {
                    Err(DecodeError::new(e.kind().clone(), at))
                }
                other => other,
            }
        }
    }
}

/// The value of the variant of union `ty` with tag `tag` (the tag already read).
fn union_value(l: &Layouts, ty: usize, tag: u64, r: &mut Reader<'_>) -> Result<Value, DecodeError> {
    let at = r.offset();
    let variant = match l.types.get(ty).map(|t| &t.form) {
        Some(FormLayout::Union { variants, .. }) => variants.iter().find(|v| v.2 == tag),
        _ => None,
    };
    match variant {
        Some((name, path, _, Some(w))) => value(l, w, r)
            .map(|v| Value::Union(name, Some(Box::new(v))))
            .map_err(|e| e.in_field(path)),
        Some((name, _, _, None)) => Ok(Value::Union(name, None)),
        None => Err(DecodeError::new(
            DecodeErrorKind::UndefinedValue { value: tag },
            at,
        )),
    }
}

/// The fewest bytes a value of layout `w` takes (the derive's `MIN_LEN`), used to
/// reject impossible counts before allocating.
pub(crate) fn min_len(l: &Layouts, w: &WireLayout, depth: u32) -> usize {
    match w {
        WireLayout::Int(i) | WireLayout::Scaled(i, _) => i.bytes(),
        WireLayout::F32 => 4,
        WireLayout::F64 => 8,
        WireLayout::Named {
            tag_var: Some(_), ..
        } => 0,
        WireLayout::Named { size: Some(s), .. } => s.bytes(),
        WireLayout::Named { ty, .. } => match l.types.get(*ty).map(|t| &t.form) {
            Some(FormLayout::Record(b)) if depth < 16 => {
                b.presence.map_or(0, Int::bytes)
                    + b.fields
                        .iter()
                        .filter(|f| !f.is_optional() && !matches!(f.wire, WireLayout::Flag))
                        .map(|f| min_len(l, &f.wire, depth + 1))
                        .sum::<usize>()
            }
            Some(FormLayout::Enum { repr, .. }) | Some(FormLayout::Bits { repr, .. }) => {
                repr.bytes()
            }
            Some(FormLayout::Union { tag, .. }) => tag.bytes(),
            _ => 0,
        },
        WireLayout::Str(len) => match *len {
            Len::Nul => 1,
            Len::Fixed {
                accept_short: true, ..
            } => 0,
            Len::Fixed { n, .. } => n,
            Len::Prefix(c) => c.bytes(),
            Len::Rest { .. } => 0,
        },
        WireLayout::Bytes(len) => match *len {
            Len::Fixed { n, .. } => n,
            Len::Prefix(c) => c.bytes(),
            Len::Rest { .. } | Len::Nul => 0,
        },
        WireLayout::List { count, .. } => count.map_or(0, Int::bytes),
        WireLayout::ListVar { .. } | WireLayout::Flag => 0,
        WireLayout::Packet { size: Some(s) } => s.bytes(),
        WireLayout::Packet { size: None } => jaus::wire::HEADER_LEN,
    }
}
