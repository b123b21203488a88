//! Bytes → values, walking a layout with the SDK codec's reader: the order of reads,
//! the checks and the errors are those of the derived decoders.
//!
//! One walk serves two ends ([`Build`]): [`Tree`] makes the [`Value`] tree
//! ([`crate::Schema::decode`]); [`Check`] makes nothing, only what later fields read
//! (counts, flags, tags), so that [`crate::Schema::check`] runs every check of the
//! decode — the same reads in the same order, the same errors — without allocating.

use crate::ints;
use crate::schema::{Body, FieldLayout, FormLayout, Layouts, WireLayout};
use crate::value::Value;
use jaus::codec::{
    check_presence, get_cstring, get_fixed_string, get_rest_string, latin1_to_string, Decode,
    DecodeError, DecodeErrorKind, Reader, ScaledField,
};
use jaus_spec::{Int, Len};

/// What a walk makes of the values it reads. The walk itself (reads, checks, errors)
/// does not depend on it; only [`Build::as_u64`] flows back into it (a field that
/// publishes its value for later fields).
pub(crate) trait Build {
    /// A value.
    type V;
    /// A record being made.
    type Rec;
    /// A list being made.
    type List;
    fn record(capacity: usize) -> Self::Rec;
    fn field(rec: &mut Self::Rec, name: &'static str, v: Self::V);
    fn end_record(rec: Self::Rec) -> Self::V;
    fn list(capacity: usize) -> Self::List;
    fn item(list: &mut Self::List, v: Self::V);
    fn end_list(list: Self::List) -> Self::V;
    fn uint(v: u64) -> Self::V;
    fn int(v: i64) -> Self::V;
    fn f32(v: f32) -> Self::V;
    fn f64(v: f64) -> Self::V;
    /// A scaled integer of type `int` read from `r` (its real value, for [`Tree`]).
    fn scaled(int: Int, s: &ScaledField, r: &mut Reader<'_>) -> Result<Self::V, DecodeError>;
    fn flag(v: bool) -> Self::V;
    /// Text the codec has made.
    fn text(s: String) -> Self::V;
    /// ISO-8859-1 bytes (every byte is a character: never fails).
    fn latin1(b: &[u8]) -> Self::V;
    fn bytes(b: &[u8]) -> Self::V;
    fn enumeration(values: &[(&'static str, u64)], v: u64) -> Self::V;
    fn bits(
        members: &[(&'static str, &'static str, u32, u32, bool)],
        x: u64,
        undefined: u64,
    ) -> Self::V;
    fn union(name: &'static str, v: Option<Self::V>) -> Self::V;
    fn packet(p: jaus::Packet) -> Self::V;
    /// The value a field publishes for later fields ([`Value::as_u64`]).
    fn as_u64(v: &Self::V) -> Option<u64>;
}

/// The [`Value`] tree.
pub(crate) enum Tree {}

impl Build for Tree {
    type V = Value;
    type Rec = Vec<(&'static str, Value)>;
    type List = Vec<Value>;
    #[inline]
    fn record(capacity: usize) -> Self::Rec {
        Vec::with_capacity(capacity)
    }
    #[inline]
    fn field(rec: &mut Self::Rec, name: &'static str, v: Value) {
        rec.push((name, v));
    }
    #[inline]
    fn end_record(rec: Self::Rec) -> Value {
        Value::Record(rec)
    }
    #[inline]
    fn list(capacity: usize) -> Self::List {
        Vec::with_capacity(capacity)
    }
    #[inline]
    fn item(list: &mut Self::List, v: Value) {
        list.push(v);
    }
    #[inline]
    fn end_list(list: Self::List) -> Value {
        Value::List(list)
    }
    #[inline]
    fn uint(v: u64) -> Value {
        Value::UInt(v)
    }
    #[inline]
    fn int(v: i64) -> Value {
        Value::Int(v)
    }
    #[inline]
    fn f32(v: f32) -> Value {
        Value::F32(v)
    }
    #[inline]
    fn f64(v: f64) -> Value {
        Value::F64(v)
    }
    #[inline]
    fn scaled(int: Int, s: &ScaledField, r: &mut Reader<'_>) -> Result<Value, DecodeError> {
        ints::read_scaled(int, s, r).map(Value::Real)
    }
    #[inline]
    fn flag(v: bool) -> Value {
        Value::Bool(v)
    }
    fn text(s: String) -> Value {
        Value::Text(s)
    }
    fn latin1(b: &[u8]) -> Value {
        Value::Text(latin1_to_string(b))
    }
    fn bytes(b: &[u8]) -> Value {
        Value::Bytes(b.to_vec())
    }
    fn enumeration(values: &[(&'static str, u64)], v: u64) -> Value {
        match values.iter().find(|(_, x)| *x == v) {
            Some((name, _)) => Value::Enum(name, v),
            None => Value::UnknownEnum(v),
        }
    }
    fn bits(
        members: &[(&'static str, &'static str, u32, u32, bool)],
        x: u64,
        undefined: u64,
    ) -> Value {
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
        Value::Bits(m, x & undefined)
    }
    fn union(name: &'static str, v: Option<Value>) -> Value {
        Value::Union(name, v.map(Box::new))
    }
    fn packet(p: jaus::Packet) -> Value {
        Value::Packet(p)
    }
    #[inline]
    fn as_u64(v: &Value) -> Option<u64> {
        v.as_u64()
    }
}

/// Nothing but the numbers later fields may read: `Some` exactly where
/// [`Value::as_u64`] of the value [`Tree`] makes is.
pub(crate) enum Check {}

impl Build for Check {
    type V = Option<u64>;
    type Rec = ();
    type List = ();
    #[inline]
    fn record(_: usize) {}
    #[inline]
    fn field(_: &mut (), _: &'static str, _: Option<u64>) {}
    #[inline]
    fn end_record(_: ()) -> Option<u64> {
        None
    }
    #[inline]
    fn list(_: usize) {}
    #[inline]
    fn item(_: &mut (), _: Option<u64>) {}
    #[inline]
    fn end_list(_: ()) -> Option<u64> {
        None
    }
    #[inline]
    fn uint(v: u64) -> Option<u64> {
        Some(v)
    }
    #[inline]
    fn int(v: i64) -> Option<u64> {
        u64::try_from(v).ok()
    }
    #[inline]
    fn f32(_: f32) -> Option<u64> {
        None
    }
    #[inline]
    fn f64(_: f64) -> Option<u64> {
        None
    }
    /// The integer read as [`Tree`] reads it (the same type's decoder: the same
    /// errors), not scaled.
    #[inline]
    fn scaled(int: Int, _: &ScaledField, r: &mut Reader<'_>) -> Result<Option<u64>, DecodeError> {
        ints::read(int, r).map(|_| None)
    }
    #[inline]
    fn flag(v: bool) -> Option<u64> {
        Some(u64::from(v))
    }
    #[inline]
    fn text(_: String) -> Option<u64> {
        None
    }
    #[inline]
    fn latin1(_: &[u8]) -> Option<u64> {
        None
    }
    #[inline]
    fn bytes(_: &[u8]) -> Option<u64> {
        None
    }
    #[inline]
    fn enumeration(_: &[(&'static str, u64)], v: u64) -> Option<u64> {
        Some(v)
    }
    #[inline]
    fn bits(_: &[(&'static str, &'static str, u32, u32, bool)], _: u64, _: u64) -> Option<u64> {
        None
    }
    #[inline]
    fn union(_: &'static str, _: Option<Option<u64>>) -> Option<u64> {
        None
    }
    #[inline]
    fn packet(_: jaus::Packet) -> Option<u64> {
        None
    }
    #[inline]
    fn as_u64(v: &Option<u64>) -> Option<u64> {
        *v
    }
}

/// Decodes a message body (`body`) of layout `b`; the whole body must be used.
pub(crate) fn message<B: Build>(l: &Layouts, b: &Body, bytes: &[u8]) -> Result<B::V, DecodeError> {
    let mut r = Reader::new(bytes);
    let v = body::<B>(l, b, &mut r, true)?;
    r.finish()?;
    Ok(v)
}

fn body<B: Build>(
    l: &Layouts,
    b: &Body,
    r: &mut Reader<'_>,
    is_message: bool,
) -> Result<B::V, DecodeError> {
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
    let mut out = B::record(b.fields.len());
    for f in &b.fields {
        match (&f.wire, f.bit, f.present_if) {
            (WireLayout::Flag, ..) => {
                let set = f.bit.is_some_and(|bit| pv & (1u64 << bit) != 0);
                if let Some(var) = f.var {
                    r.vars().set(var, u64::from(set));
                }
                B::field(&mut out, f.name, B::flag(set));
            }
            (_, Some(bit), _) => {
                if pv & (1u64 << bit) != 0 {
                    B::field(&mut out, f.name, field::<B>(l, f, r)?);
                }
            }
            (_, None, Some(flag)) => {
                let present = r.var(flag).map_err(|e| e.in_field(f.path))? != 0;
                if present {
                    B::field(&mut out, f.name, field::<B>(l, f, r)?);
                }
            }
            _ => {
                let v = field::<B>(l, f, r)?;
                if let Some(var) = f.var {
                    r.vars().set(var, B::as_u64(&v).unwrap_or(0));
                }
                B::field(&mut out, f.name, v);
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
    Ok(B::end_record(out))
}

fn runs_to_end(w: &WireLayout) -> bool {
    matches!(
        w,
        WireLayout::Bytes(Len::Rest { .. })
            | WireLayout::Str(Len::Rest { .. })
            | WireLayout::List { count: None, .. }
    )
}

fn field<B: Build>(l: &Layouts, f: &FieldLayout, r: &mut Reader<'_>) -> Result<B::V, DecodeError> {
    value::<B>(l, &f.wire, r).map_err(|e| e.in_field(f.path))
}

/// One value of layout `w`.
fn value<B: Build>(l: &Layouts, w: &WireLayout, r: &mut Reader<'_>) -> Result<B::V, DecodeError> {
    Ok(match w {
        WireLayout::Int(i) => match ints::read(*i, r)? {
            Ok(v) => B::uint(v),
            Err(v) => B::int(v),
        },
        WireLayout::F32 => B::f32(f32::decode(r)?),
        WireLayout::F64 => B::f64(f64::decode(r)?),
        WireLayout::Scaled(i, s) => B::scaled(*i, s, r)?,
        WireLayout::Named {
            ty,
            tag_var: Some(var),
            ..
        } => {
            let tag = r.var(var)?;
            union_value::<B>(l, *ty, tag, r)?
        }
        WireLayout::Named {
            ty,
            size: Some(size),
            ..
        } => sized(*size, r, |r| named::<B>(l, *ty, r))?,
        WireLayout::Named { ty, .. } => named::<B>(l, *ty, r)?,
        WireLayout::Str(len) => match *len {
            Len::Nul => B::text(get_cstring(r)?),
            Len::Fixed { n, accept_short } => B::text(get_fixed_string(r, n, accept_short)?),
            Len::Prefix(c) => {
                let n = ints::read_count(c, r, 1)?;
                B::latin1(r.take(n)?)
            }
            Len::Rest { nul: true } => B::text(get_rest_string(r)),
            Len::Rest { nul: false } => B::latin1(r.rest()),
        },
        WireLayout::Bytes(len) => B::bytes(match *len {
            Len::Fixed { n, .. } => r.take(n)?,
            Len::Prefix(c) => {
                let n = ints::read_count(c, r, 1)?;
                r.take(n)?
            }
            Len::Rest { .. } | Len::Nul => r.rest(),
        }),
        WireLayout::List { count, elem } => list::<B>(l, *count, elem, r)?,
        WireLayout::ListVar { var, minus, elem } => {
            let n = r.var(var)?.saturating_sub(*minus);
            let n = r.check_count(n, min_len(l, elem, 0))?;
            let mut out = B::list(n.min(r.remaining()));
            for _ in 0..n {
                B::item(&mut out, value::<B>(l, elem, r)?);
            }
            B::end_list(out)
        }
        // A flag has no bytes of its own (handled by the body).
        WireLayout::Flag => B::flag(false),
        WireLayout::Packet { size: Some(size) } => {
            sized(*size, r, |r| jaus::Packet::decode(r).map(B::packet))?
        }
        WireLayout::Packet { size: None } => B::packet(jaus::Packet::decode(r)?),
    })
}

/// A value behind its byte length, which must match what the value's decoder uses.
fn sized<V>(
    size: Int,
    r: &mut Reader<'_>,
    decode: impl FnOnce(&mut Reader<'_>) -> Result<V, DecodeError>,
) -> Result<V, DecodeError> {
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

fn list<B: Build>(
    l: &Layouts,
    count: Option<Int>,
    elem: &WireLayout,
    r: &mut Reader<'_>,
) -> Result<B::V, DecodeError> {
    if let WireLayout::Scaled(i, s) = elem {
        let size = i.bytes();
        let n = match count {
            Some(c) => ints::read_count(c, r, size)?,
            None => r.remaining() / size,
        };
        let mut out = B::list(n);
        for _ in 0..n {
            B::item(&mut out, B::scaled(*i, s, r)?);
        }
        if count.is_none() && r.remaining() != 0 {
            return Err(DecodeError::new(
                DecodeErrorKind::TrailingBytes {
                    count: r.remaining(),
                },
                r.offset(),
            ));
        }
        return Ok(B::end_list(out));
    }
    match count {
        Some(c) => {
            let n = ints::read_count(c, r, min_len(l, elem, 0))?;
            let mut out = B::list(n.min(r.remaining()));
            for _ in 0..n {
                B::item(&mut out, value::<B>(l, elem, r)?);
            }
            Ok(B::end_list(out))
        }
        None => {
            let mut out = B::list(0);
            let mut n = 0usize;
            while r.remaining() > 0 {
                let before = r.remaining();
                B::item(&mut out, value::<B>(l, elem, r)?);
                n += 1;
                if r.remaining() == before {
                    // An element that takes no bytes would repeat forever.
                    return Err(DecodeError::new(
                        DecodeErrorKind::CountBeyondBuffer {
                            count: n,
                            remaining: before,
                        },
                        r.offset(),
                    ));
                }
            }
            Ok(B::end_list(out))
        }
    }
}

/// A value of the named type `ty`.
fn named<B: Build>(l: &Layouts, ty: usize, r: &mut Reader<'_>) -> Result<B::V, DecodeError> {
    let Some(t) = l.types.get(ty) else {
        return Err(DecodeError::new(
            DecodeErrorKind::UndefinedValue { value: ty as u64 },
            r.offset(),
        ));
    };
    match &t.form {
        FormLayout::Record(b) => body::<B>(l, b, r, false),
        FormLayout::Enum { repr, values } => {
            let v = ints::read_u(*repr, r)?;
            Ok(B::enumeration(values, v))
        }
        FormLayout::Bits {
            repr,
            members,
            undefined,
        } => {
            let x = ints::read_u(*repr, r)?;
            Ok(B::bits(members, x, *undefined))
        }
        FormLayout::Union { tag, .. } => {
            let at = r.offset();
            let t = ints::read_u(*tag, r)?;
            match union_value::<B>(l, ty, t, r) {
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
fn union_value<B: Build>(
    l: &Layouts,
    ty: usize,
    tag: u64,
    r: &mut Reader<'_>,
) -> Result<B::V, DecodeError> {
    let at = r.offset();
    let variant = match l.types.get(ty).map(|t| &t.form) {
        Some(FormLayout::Union { variants, .. }) => variants.iter().find(|v| v.2 == tag),
        _ => None,
    };
    match variant {
        Some((name, path, _, Some(w))) => value::<B>(l, w, r)
            .map(|v| B::union(name, Some(v)))
            .map_err(|e| e.in_field(path)),
        Some((name, _, _, None)) => Ok(B::union(name, None)),
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
