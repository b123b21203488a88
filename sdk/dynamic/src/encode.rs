//! [`Value`] → bytes, walking a layout with the SDK codec's writer: lengths, counts,
//! presence vectors, computed offsets and every check are those of the derived
//! encoders. The value was checked against the layout when it was built
//! ([`crate::json`]), so a value of the wrong kind is an error here, never a panic.

use crate::ints;
use crate::schema::{Body, FieldLayout, FormLayout, Layouts, WireLayout};
use crate::value::Value;
use jaus::codec::{
    latin1_len, put_cstring, put_fixed_bytes, put_fixed_string, put_latin1, Encode, EncodeError,
    Writer,
};
use jaus_spec::{Int, Len};

/// Encodes a message body of layout `b` into a new vector.
pub(crate) fn message(
    l: &Layouts,
    name: &'static str,
    b: &Body,
    v: &Value,
) -> Result<Vec<u8>, EncodeError> {
    let run = || {
        let mut out = vec![0u8; body_len(l, b, v)?];
        let mut w = Writer::new(&mut out);
        body(l, b, v, &mut w)?;
        let end = w.position();
        out.truncate(end);
        Ok(out)
    };
    run().map_err(|e: EncodeError| e.in_message(name))
}

/// The error of a value that does not fit its layout (only reachable with a value
/// built by hand).
fn mismatch(field: &'static str) -> EncodeError {
    EncodeError::ValueKind { field }
}

fn get<'v>(v: &'v Value, name: &str) -> Option<&'v Value> {
    v.field(name)
}

fn list_len(v: Option<&Value>) -> usize {
    match v {
        Some(Value::List(l)) => l.len(),
        _ => 0,
    }
}

fn body_len(l: &Layouts, b: &Body, v: &Value) -> Result<usize, EncodeError> {
    let mut n = b.presence.map_or(0, Int::bytes);
    for f in &b.fields {
        let fv = get(v, f.name);
        n += match (&f.wire, fv) {
            (WireLayout::Flag, _) => 0,
            (_, None) if f.is_optional() => 0,
            (_, None) => return Err(mismatch(f.path)),
            (_, Some(_)) if f.offsets_of.is_some() => {
                4 * list_len(f.offsets_of.and_then(|t| get(v, b.fields[t].name)))
            }
            (w, Some(x)) => len(l, w, x, f.path)?,
        };
    }
    Ok(n)
}

fn body(l: &Layouts, b: &Body, v: &Value, w: &mut Writer<'_>) -> Result<(), EncodeError> {
    // Slots of computed offsets: reserved by the offsets field, patched while the
    // list it points at is written.
    let mut slots: Vec<Option<usize>> = vec![None; b.fields.len()];
    if let Some(p) = b.presence {
        let mut pv = 0u64;
        for f in &b.fields {
            let (Some(bit), Some(x)) = (f.bit, get(v, f.name)) else {
                continue;
            };
            let set = match (&f.wire, x) {
                (WireLayout::Flag, Value::Bool(on)) => *on,
                (WireLayout::Flag, _) => return Err(mismatch(f.path)),
                _ => true,
            };
            if set {
                pv |= 1u64 << bit;
            }
        }
        ints::write_u(p, pv, w)?;
    }
    for (i, f) in b.fields.iter().enumerate() {
        let x = get(v, f.name);
        match (&f.wire, f.bit, f.present_if) {
            (WireLayout::Flag, ..) => {
                if let Some(var) = f.var {
                    w.vars().set(var, x.and_then(Value::as_u64).unwrap_or(0));
                }
            }
            (_, Some(_), _) => {
                if let Some(x) = x {
                    field(l, b, f, i, x, v, &mut slots, w)?;
                }
            }
            (_, None, Some(flag)) => {
                let want = w.var(flag, f.path)? != 0;
                if want != x.is_some() {
                    return Err(EncodeError::PresenceMismatch {
                        field: f.path,
                        flag,
                        expected: want,
                    });
                }
                if let Some(x) = x {
                    field(l, b, f, i, x, v, &mut slots, w)?;
                }
            }
            (_, None, None) => {
                let x = x.ok_or_else(|| mismatch(f.path))?;
                match (f.var, &f.wire) {
                    // A count kept in its own field: written from the list it counts
                    // when that list is here, and published for nested lists.
                    (Some(var), WireLayout::Int(int)) => {
                        let n = match f.counts {
                            Some((list, optional)) => match get(v, b.fields[list].name) {
                                Some(Value::List(items)) => Some(items.len()),
                                Some(_) => return Err(mismatch(f.path)),
                                None if optional => None,
                                None => return Err(mismatch(f.path)),
                            },
                            None => None,
                        };
                        let value = match n {
                            Some(n) => {
                                let n64 = n as u64;
                                if !ints::fits_u(*int, n64) {
                                    return Err(EncodeError::CountOverflow {
                                        field: f.path,
                                        count: n,
                                        max: ints::max_usize(*int),
                                    });
                                }
                                n64
                            }
                            None => x.as_u64().ok_or_else(|| mismatch(f.path))?,
                        };
                        w.vars().set(var, value);
                        ints::write_u(*int, value, w)?;
                    }
                    _ => field(l, b, f, i, x, v, &mut slots, w)?,
                }
            }
        }
    }
    Ok(())
}

/// Writes field `i` (`f`, value `x`) of a body whose whole value is `whole`.
#[allow(clippy::too_many_arguments)]
fn field(
    l: &Layouts,
    b: &Body,
    f: &FieldLayout,
    i: usize,
    x: &Value,
    whole: &Value,
    slots: &mut [Option<usize>],
    w: &mut Writer<'_>,
) -> Result<(), EncodeError> {
    match &f.wire {
        WireLayout::ListVar { var, minus, elem } => {
            let Value::List(items) = x else {
                return Err(mismatch(f.path));
            };
            let expected = w.var(var, f.path)?.saturating_sub(*minus);
            // Offsets of another list: as many as it has elements.
            let target = f.offsets_of.map(|t| list_len(get(whole, b.fields[t].name)));
            let n = target.unwrap_or(items.len());
            if n as u64 != expected {
                return Err(EncodeError::CountMismatch {
                    field: f.path,
                    len: n,
                    count_field: var,
                    expected,
                });
            }
            if target.is_some() {
                // Offsets given with one per element are written as given (a received
                // message re-encodes byte for byte); otherwise computed.
                if items.len() == n {
                    for e in items {
                        value(l, elem, e, f.path, w)?;
                    }
                } else {
                    slots[i] = Some(w.reserve(4 * n)?);
                }
                return Ok(());
            }
            let slot = f.patched_by.and_then(|o| slots[o]);
            for (k, e) in items.iter().enumerate() {
                if let Some(at) = slot {
                    let here = u32::try_from(w.position()).unwrap_or(u32::MAX);
                    w.patch(at + 4 * k, &here.to_le_bytes());
                }
                value(l, elem, e, f.path, w)?;
            }
            Ok(())
        }
        wire => value(l, wire, x, f.path, w),
    }
}

/// The encoded length of `x` as layout `wire`.
fn len(
    l: &Layouts,
    wire: &WireLayout,
    x: &Value,
    path: &'static str,
) -> Result<usize, EncodeError> {
    Ok(match (wire, x) {
        (WireLayout::Int(i), _) | (WireLayout::Scaled(i, _), _) => i.bytes(),
        (WireLayout::F32, _) => 4,
        (WireLayout::F64, _) => 8,
        (
            WireLayout::Named {
                ty,
                tag_var: Some(_),
                ..
            },
            _,
        ) => named_len(l, *ty, x, path)?.saturating_sub(union_tag_len(l, *ty)),
        (WireLayout::Named { ty, size, .. }, _) => {
            size.map_or(0, Int::bytes) + named_len(l, *ty, x, path)?
        }
        (WireLayout::Str(len), Value::Text(s)) => match *len {
            Len::Nul => latin1_len(s) + 1,
            Len::Fixed { n, .. } => n,
            Len::Prefix(c) => c.bytes() + latin1_len(s),
            Len::Rest { nul } => latin1_len(s) + usize::from(nul),
        },
        (WireLayout::Bytes(len), Value::Bytes(b)) => match *len {
            Len::Fixed { n, .. } => n,
            Len::Prefix(c) => c.bytes() + b.len(),
            Len::Rest { .. } | Len::Nul => b.len(),
        },
        (WireLayout::List { count, elem }, Value::List(items)) => {
            let mut n = count.map_or(0, Int::bytes);
            for e in items {
                n += len(l, elem, e, path)?;
            }
            n
        }
        (WireLayout::ListVar { elem, .. }, Value::List(items)) => {
            let mut n = 0;
            for e in items {
                n += len(l, elem, e, path)?;
            }
            n
        }
        (WireLayout::Flag, _) => 0,
        (WireLayout::Packet { size }, Value::Packet(p)) => {
            size.map_or(0, Int::bytes) + p.encoded_len()
        }
        _ => return Err(mismatch(path)),
    })
}

fn union_tag_len(l: &Layouts, ty: usize) -> usize {
    match l.types.get(ty).map(|t| &t.form) {
        Some(FormLayout::Union { tag, .. }) => tag.bytes(),
        _ => 0,
    }
}

fn named_len(l: &Layouts, ty: usize, x: &Value, path: &'static str) -> Result<usize, EncodeError> {
    match (l.types.get(ty).map(|t| &t.form), x) {
        (Some(FormLayout::Record(b)), Value::Record(_)) => body_len(l, b, x),
        (Some(FormLayout::Enum { repr, .. }), _) | (Some(FormLayout::Bits { repr, .. }), _) => {
            Ok(repr.bytes())
        }
        (Some(FormLayout::Union { tag, variants }), Value::Union(name, payload)) => {
            let v = variants
                .iter()
                .find(|v| v.0 == *name)
                .ok_or_else(|| mismatch(path))?;
            Ok(tag.bytes()
                + match (&v.3, payload) {
                    (Some(w), Some(p)) => len(l, w, p, v.1)?,
                    (None, None) => 0,
                    _ => return Err(mismatch(v.1)),
                })
        }
        _ => Err(mismatch(path)),
    }
}

/// Writes `x` as layout `wire` (field `path` for errors).
fn value(
    l: &Layouts,
    wire: &WireLayout,
    x: &Value,
    path: &'static str,
    w: &mut Writer<'_>,
) -> Result<(), EncodeError> {
    match (wire, x) {
        (WireLayout::Int(i), Value::UInt(v)) if ints::fits_u(*i, *v) => ints::write_u(*i, *v, w),
        (WireLayout::Int(i), Value::Int(v)) if ints::fits_i(*i, *v) => ints::write_i(*i, *v, w),
        (WireLayout::F32, Value::F32(v)) => v.encode(w),
        (WireLayout::F64, Value::F64(v)) => v.encode(w),
        (WireLayout::Scaled(i, s), Value::Real(v)) => ints::write_scaled(*i, *v, s, w),
        (
            WireLayout::Named {
                ty,
                tag_var: Some(var),
                ..
            },
            Value::Union(name, payload),
        ) => {
            let expected = w.var(var, path)?;
            let (tag, vw, vpath) = variant(l, *ty, name, path)?;
            if tag != expected {
                return Err(EncodeError::TagMismatch {
                    field: path,
                    tag,
                    tag_field: var,
                    expected,
                });
            }
            payload_value(l, vw, payload.as_deref(), vpath, w)
        }
        (
            WireLayout::Named {
                ty, size: Some(s), ..
            },
            _,
        ) => {
            ints::write_count(*s, w, named_len(l, *ty, x, path)?, path)?;
            named(l, *ty, x, path, w)
        }
        (WireLayout::Named { ty, .. }, _) => named(l, *ty, x, path, w),
        (WireLayout::Str(len), Value::Text(s)) => match *len {
            Len::Nul => put_cstring(w, s, path),
            Len::Fixed { n, .. } => put_fixed_string(w, s, n, path),
            Len::Prefix(c) => {
                ints::write_count(c, w, latin1_len(s), path)?;
                put_latin1(w, s, path)
            }
            Len::Rest { nul } => {
                put_latin1(w, s, path)?;
                if nul {
                    w.put(&[0])?;
                }
                Ok(())
            }
        },
        (WireLayout::Bytes(len), Value::Bytes(b)) => match *len {
            Len::Fixed { n, .. } => put_fixed_bytes(w, b, n, path),
            Len::Prefix(c) => {
                ints::write_count(c, w, b.len(), path)?;
                w.put(b)
            }
            Len::Rest { .. } | Len::Nul => w.put(b),
        },
        (WireLayout::List { count, elem }, Value::List(items)) => {
            if let Some(c) = count {
                ints::write_count(*c, w, items.len(), path)?;
            }
            items.iter().try_for_each(|e| value(l, elem, e, path, w))
        }
        (WireLayout::ListVar { elem, .. }, Value::List(items)) => {
            items.iter().try_for_each(|e| value(l, elem, e, path, w))
        }
        (WireLayout::Packet { size }, Value::Packet(p)) => {
            if let Some(s) = size {
                ints::write_count(*s, w, p.encoded_len(), path)?;
            }
            p.encode(w)
        }
        _ => Err(mismatch(path)),
    }
}

/// Tag, value layout and path of variant `name` of union `ty`.
fn variant<'l>(
    l: &'l Layouts,
    ty: usize,
    name: &str,
    path: &'static str,
) -> Result<(u64, Option<&'l WireLayout>, &'static str), EncodeError> {
    match l.types.get(ty).map(|t| &t.form) {
        Some(FormLayout::Union { variants, .. }) => variants
            .iter()
            .find(|v| v.0 == name)
            .map(|v| (v.2, v.3.as_ref(), v.1))
            .ok_or_else(|| mismatch(path)),
        _ => Err(mismatch(path)),
    }
}

fn payload_value(
    l: &Layouts,
    vw: Option<&WireLayout>,
    payload: Option<&Value>,
    path: &'static str,
    w: &mut Writer<'_>,
) -> Result<(), EncodeError> {
    match (vw, payload) {
        (Some(vw), Some(p)) => value(l, vw, p, path, w),
        (None, None) => Ok(()),
        _ => Err(mismatch(path)),
    }
}

fn named(
    l: &Layouts,
    ty: usize,
    x: &Value,
    path: &'static str,
    w: &mut Writer<'_>,
) -> Result<(), EncodeError> {
    match (l.types.get(ty).map(|t| &t.form), x) {
        (Some(FormLayout::Record(b)), Value::Record(_)) => body(l, b, x, w),
        (Some(FormLayout::Enum { repr, .. }), Value::Enum(_, v) | Value::UnknownEnum(v))
            if ints::fits_u(*repr, *v) =>
        {
            ints::write_u(*repr, *v, w)
        }
        (
            Some(FormLayout::Bits {
                repr,
                members,
                undefined,
            }),
            Value::Bits(values, reserved),
        ) => {
            let mut x = 0u64;
            for &(name, mpath, lo, hi, flag) in members {
                let v = values
                    .iter()
                    .find(|(n, _)| *n == name)
                    .and_then(|(_, v)| v.as_u64())
                    .ok_or_else(|| mismatch(mpath))?;
                let width = hi - lo + 1;
                if !flag && v > crate::schema::mask(width) {
                    return Err(EncodeError::BitsOverflow {
                        field: mpath,
                        value: v,
                        width,
                    });
                }
                x |= (v & crate::schema::mask(width)) << lo;
            }
            x |= reserved & undefined;
            ints::write_u(*repr, x, w)
        }
        (Some(FormLayout::Union { tag, .. }), Value::Union(name, payload)) => {
            let (t, vw, vpath) = variant(l, ty, name, path)?;
            ints::write_u(*tag, t, w)?;
            payload_value(l, vw, payload.as_deref(), vpath, w)
        }
        _ => Err(mismatch(path)),
    }
}
