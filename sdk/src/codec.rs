//! The wire codec runtime: byte cursors, the [`Encode`]/[`Decode`] traits, scaled
//! integers and typed errors.
//!
//! The derive macros of `jaus-derive` expand to calls into this module; nothing here
//! knows about any particular message. Every read is bounds-checked and returns a
//! [`DecodeError`] that names the offending field and byte offset: no input makes a
//! decoder panic.
//!
//! All multi-byte values are little-endian (WIRE.md §2.1).

use std::fmt;

/// A cursor over the bytes of one message body (or any part of it).
#[derive(Debug, Clone)]
pub struct Reader<'a> {
    buf: &'a [u8],
    pos: usize,
    /// Offset of `buf[0]` within the outermost buffer, so errors report absolute offsets.
    base: usize,
    /// Values of fields that later (possibly nested) fields depend on.
    vars: Vars,
    /// Nesting depth of records being decoded (bounded: recursive types such as task
    /// trees must not exhaust the stack on hostile input).
    depth: u16,
}

/// Deepest nesting of records a decoder accepts.
pub const MAX_DEPTH: u16 = 64;

/// Named integer values set while encoding/decoding, read by later fields: a count kept
/// in another field (`count_var`) or a flag deciding whether a nested field is present
/// (`present_if`). Small and fixed-size: no allocation.
#[derive(Debug, Clone, Copy, Default)]
pub struct Vars {
    names: [&'static str; 8],
    values: [u64; 8],
    len: usize,
}

impl Vars {
    /// Sets `name` (replacing an earlier value).
    #[inline]
    pub fn set(&mut self, name: &'static str, value: u64) {
        if let Some(i) = self.names[..self.len].iter().position(|n| *n == name) {
            self.values[i] = value;
        } else if self.len < self.names.len() {
            self.names[self.len] = name;
            self.values[self.len] = value;
            self.len += 1;
        } else {
            // Definitions never nest more than a few such fields; keep the newest.
            self.names.rotate_left(1);
            self.values.rotate_left(1);
            self.names[self.len - 1] = name;
            self.values[self.len - 1] = value;
        }
    }

    /// The value of `name`, if set.
    #[inline]
    pub fn get(&self, name: &'static str) -> Option<u64> {
        self.names[..self.len]
            .iter()
            .rposition(|n| *n == name)
            .map(|i| self.values[i])
    }
}

impl<'a> Reader<'a> {
    /// Starts reading at the first byte of `buf`.
    #[inline]
    pub fn new(buf: &'a [u8]) -> Self {
        Self {
            buf,
            pos: 0,
            base: 0,
            vars: Vars::default(),
            depth: 0,
        }
    }

    /// Variables set by fields decoded so far.
    #[inline]
    pub fn vars(&mut self) -> &mut Vars {
        &mut self.vars
    }

    /// Enters a nested record; fails beyond [`MAX_DEPTH`].
    #[inline]
    pub fn enter(&mut self) -> Result<(), DecodeError> {
        if self.depth >= MAX_DEPTH {
            return Err(DecodeError::new(
                DecodeErrorKind::TooDeep { max: MAX_DEPTH },
                self.offset(),
            ));
        }
        self.depth += 1;
        Ok(())
    }

    /// Leaves a nested record.
    #[inline]
    pub fn leave(&mut self) {
        self.depth = self.depth.saturating_sub(1);
    }

    /// The value of variable `name`, or a typed error if no earlier field set it.
    pub fn var(&self, name: &'static str) -> Result<u64, DecodeError> {
        self.vars.get(name).ok_or_else(|| {
            DecodeError::new(DecodeErrorKind::MissingVariable { name }, self.offset())
        })
    }

    /// Bytes not yet consumed.
    #[inline]
    pub fn remaining(&self) -> usize {
        self.buf.len() - self.pos
    }

    /// Absolute offset of the next byte to read.
    #[inline]
    pub fn offset(&self) -> usize {
        self.base + self.pos
    }

    /// Consumes exactly `n` bytes.
    #[inline]
    pub fn take(&mut self, n: usize) -> Result<&'a [u8], DecodeError> {
        match self.buf.get(self.pos..self.pos.saturating_add(n)) {
            Some(s) if n <= self.remaining() => {
                self.pos += n;
                Ok(s)
            }
            _ => Err(DecodeError::new(
                DecodeErrorKind::Truncated {
                    needed: n,
                    available: self.remaining(),
                },
                self.offset(),
            )),
        }
    }

    /// Consumes a fixed-size array.
    #[inline]
    pub fn array<const N: usize>(&mut self) -> Result<[u8; N], DecodeError> {
        // One bounds check on the hot path; the error is built out of line.
        match self.buf.get(self.pos..).and_then(<[u8]>::first_chunk::<N>) {
            Some(a) => {
                self.pos += N;
                Ok(*a)
            }
            None => Err(self.truncated(N)),
        }
    }

    #[cold]
    #[inline(never)]
    fn truncated(&self, needed: usize) -> DecodeError {
        DecodeError::new(
            DecodeErrorKind::Truncated {
                needed,
                available: self.remaining(),
            },
            self.offset(),
        )
    }

    /// The remaining bytes, without consuming them.
    #[inline]
    pub fn peek_rest(&self) -> &'a [u8] {
        &self.buf[self.pos..]
    }

    /// Consumes every remaining byte.
    #[inline]
    pub fn rest(&mut self) -> &'a [u8] {
        let s = &self.buf[self.pos..];
        self.pos = self.buf.len();
        s
    }

    /// Splits off a reader over the next `n` bytes (for size-prefixed fields) and
    /// advances past them.
    pub fn sub(&mut self, n: usize) -> Result<Reader<'a>, DecodeError> {
        let base = self.offset();
        let buf = self.take(n)?;
        Ok(Reader {
            buf,
            pos: 0,
            base,
            vars: self.vars,
            depth: self.depth,
        })
    }

    /// Checks a count kept in another field against the bytes left (elements take at
    /// least `min_elem` bytes each).
    pub fn check_count(&self, n: u64, min_elem: usize) -> Result<usize, DecodeError> {
        let n = usize::try_from(n).unwrap_or(usize::MAX);
        if !count_fits(n, min_elem, self.remaining()) {
            return Err(DecodeError::new(
                DecodeErrorKind::CountBeyondBuffer {
                    count: n,
                    remaining: self.remaining(),
                },
                self.offset(),
            ));
        }
        Ok(n)
    }

    /// Fails with [`DecodeErrorKind::TrailingBytes`] unless every byte was consumed.
    #[inline]
    pub fn finish(&self) -> Result<(), DecodeError> {
        if self.remaining() == 0 {
            Ok(())
        } else {
            Err(DecodeError::new(
                DecodeErrorKind::TrailingBytes {
                    count: self.remaining(),
                },
                self.offset(),
            ))
        }
    }
}

/// A cursor writing into a caller-provided buffer. Never reallocates.
#[derive(Debug)]
pub struct Writer<'a> {
    buf: &'a mut [u8],
    pos: usize,
    vars: Vars,
}

impl<'a> Writer<'a> {
    /// Starts writing at the first byte of `buf`.
    #[inline]
    pub fn new(buf: &'a mut [u8]) -> Self {
        Self {
            buf,
            pos: 0,
            vars: Vars::default(),
        }
    }

    /// Variables set by fields encoded so far.
    #[inline]
    pub fn vars(&mut self) -> &mut Vars {
        &mut self.vars
    }

    /// The value of variable `name`, or a typed error if no earlier field set it.
    pub fn var(&self, name: &'static str, field: &'static str) -> Result<u64, EncodeError> {
        self.vars
            .get(name)
            .ok_or(EncodeError::MissingVariable { field, name })
    }

    /// Bytes written so far.
    #[inline]
    pub fn position(&self) -> usize {
        self.pos
    }

    /// Appends `bytes`.
    #[inline]
    pub fn put(&mut self, bytes: &[u8]) -> Result<(), EncodeError> {
        let end = self.pos + bytes.len();
        match self.buf.get_mut(self.pos..end) {
            Some(dst) => {
                dst.copy_from_slice(bytes);
                self.pos = end;
                Ok(())
            }
            None => Err(EncodeError::BufferTooSmall {
                needed: end,
                capacity: self.buf.len(),
            }),
        }
    }

    /// Appends `n` zero bytes (padding of fixed-length fields).
    pub fn zeros(&mut self, n: usize) -> Result<(), EncodeError> {
        let end = self.pos + n;
        match self.buf.get_mut(self.pos..end) {
            Some(dst) => {
                dst.fill(0);
                self.pos = end;
                Ok(())
            }
            None => Err(EncodeError::BufferTooSmall {
                needed: end,
                capacity: self.buf.len(),
            }),
        }
    }

    /// Reserves `n` bytes to be filled later with [`Writer::patch`]; returns their offset.
    pub fn reserve(&mut self, n: usize) -> Result<usize, EncodeError> {
        let at = self.pos;
        self.zeros(n)?;
        Ok(at)
    }

    /// Overwrites bytes previously reserved at `at`.
    pub fn patch(&mut self, at: usize, bytes: &[u8]) {
        self.buf[at..at + bytes.len()].copy_from_slice(bytes);
    }
}

/// A value with a JAUS wire encoding.
pub trait Encode {
    /// Number of bytes [`Encode::encode`] writes.
    fn encoded_len(&self) -> usize;

    /// Writes the value.
    fn encode(&self, w: &mut Writer<'_>) -> Result<(), EncodeError>;

    /// Encodes into a new vector of exactly [`Encode::encoded_len`] bytes.
    fn to_bytes(&self) -> Result<Vec<u8>, EncodeError> {
        let mut out = vec![0u8; self.encoded_len()];
        let mut w = Writer::new(&mut out);
        self.encode(&mut w)?;
        debug_assert_eq!(w.position(), out.len(), "encoded_len disagrees with encode");
        Ok(out)
    }

    /// Clamps every scaled field of the value to its limits, through nested records,
    /// lists, optional fields and unions; NaN is left as it is (and stays an encode
    /// error). Encoding refuses a value beyond its field's limits
    /// ([`EncodeError::OutOfRange`], see [`scale_to`]); call this first to saturate
    /// instead. Values received are never clamped.
    ///
    /// The derives implement it for messages, records and unions; every other type
    /// has no scaled field and keeps this default, which does nothing.
    #[inline]
    fn clamp_to_range(&mut self) {}

    /// The value with every scaled field clamped to its limits
    /// ([`Encode::clamp_to_range`]).
    #[inline]
    fn clamped(mut self) -> Self
    where
        Self: Sized,
    {
        self.clamp_to_range();
        self
    }
}

/// A value that can be read back from its JAUS wire encoding.
pub trait Decode: Sized {
    /// The fewest bytes any encoding of this type occupies (used to reject impossible
    /// element counts before allocating).
    const MIN_LEN: usize;

    /// Reads one value.
    fn decode(r: &mut Reader<'_>) -> Result<Self, DecodeError>;

    /// Decodes a whole buffer, failing if bytes are left over.
    #[inline]
    fn from_bytes(bytes: &[u8]) -> Result<Self, DecodeError> {
        let mut r = Reader::new(bytes);
        let v = Self::decode(&mut r)?;
        r.finish()?;
        Ok(v)
    }
}

macro_rules! primitive {
    ($($t:ty),*) => {$(
        impl Encode for $t {
            #[inline]
            fn encoded_len(&self) -> usize { std::mem::size_of::<$t>() }
            #[inline]
            fn encode(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
                w.put(&self.to_le_bytes())
            }
        }
        impl Decode for $t {
            const MIN_LEN: usize = std::mem::size_of::<$t>();
            #[inline]
            fn decode(r: &mut Reader<'_>) -> Result<Self, DecodeError> {
                Ok(<$t>::from_le_bytes(r.array()?))
            }
        }
    )*};
}
primitive!(u8, u16, u32, u64, i8, i16, i32, i64, f32, f64);

/// An unsigned integer usable as a count or size prefix.
pub trait CountRepr: Encode + Decode + Copy {
    /// Largest count representable.
    const MAX: usize;
    /// Widens to `usize`.
    fn to_usize(self) -> usize;
    /// Narrows from `usize`; the caller has checked `n <= MAX`.
    fn from_usize(n: usize) -> Self;
}

macro_rules! count_repr {
    ($($t:ty),*) => {$(
        impl CountRepr for $t {
            const MAX: usize = <$t>::MAX as usize;
            #[inline]
            fn to_usize(self) -> usize { self as usize }
            #[inline]
            fn from_usize(n: usize) -> Self { n as $t }
        }
    )*};
}
count_repr!(u8, u16, u32);

/// Writes a count/size prefix, failing if `n` does not fit.
#[inline]
pub fn put_count<C: CountRepr>(
    w: &mut Writer<'_>,
    n: usize,
    field: &'static str,
) -> Result<(), EncodeError> {
    if n > C::MAX {
        return Err(EncodeError::CountOverflow {
            field,
            count: n,
            max: C::MAX,
        });
    }
    C::from_usize(n).encode(w)
}

/// Reads a count prefix for a list whose elements take at least `min_elem` bytes, and
/// rejects counts that cannot fit in the bytes left.
#[inline]
pub fn get_count<C: CountRepr>(r: &mut Reader<'_>, min_elem: usize) -> Result<usize, DecodeError> {
    let at = r.offset();
    let n = C::decode(r)?.to_usize();
    if !count_fits(n, min_elem, r.remaining()) {
        return Err(DecodeError::new(
            DecodeErrorKind::CountBeyondBuffer {
                count: n,
                remaining: r.remaining(),
            },
            at,
        ));
    }
    Ok(n)
}

/// Encodes a list of values after its count prefix.
pub fn encode_list<C: CountRepr, T: Encode>(
    w: &mut Writer<'_>,
    items: &[T],
    field: &'static str,
) -> Result<(), EncodeError> {
    put_count::<C>(w, items.len(), field)?;
    items.iter().try_for_each(|i| i.encode(w))
}

/// Decodes a count-prefixed list.
pub fn decode_list<C: CountRepr, T: Decode>(r: &mut Reader<'_>) -> Result<Vec<T>, DecodeError> {
    let n = get_count::<C>(r, T::MIN_LEN)?;
    let mut v = Vec::with_capacity(n.min(r.remaining()));
    for _ in 0..n {
        v.push(T::decode(r)?);
    }
    Ok(v)
}

/// Decodes elements until the reader is exhausted.
pub fn decode_rest<T: Decode>(r: &mut Reader<'_>) -> Result<Vec<T>, DecodeError> {
    let mut v = Vec::new();
    while r.remaining() > 0 {
        let before = r.remaining();
        v.push(T::decode(r)?);
        if r.remaining() == before {
            // An element that takes no bytes would repeat forever.
            return Err(DecodeError::new(
                DecodeErrorKind::CountBeyondBuffer {
                    count: v.len(),
                    remaining: before,
                },
                r.offset(),
            ));
        }
    }
    Ok(v)
}

/// Most elements a list of elements that may take no bytes can have beyond the bytes
/// left (such lists must still be bounded: a count from the wire could claim billions).
pub const MAX_EMPTY_ELEMENTS: usize = 65_535;

/// Whether `n` elements of at least `min_elem` bytes can come from `remaining` bytes.
#[inline]
fn count_fits(n: usize, min_elem: usize, remaining: usize) -> bool {
    if min_elem == 0 {
        n <= remaining.saturating_add(MAX_EMPTY_ELEMENTS)
    } else {
        n.saturating_mul(min_elem) <= remaining
    }
}

// ---------------------------------------------------------------------------------
// Scaled integers (WIRE.md §2.2).

/// An integer type that can carry a scaled real value.
pub trait ScaledRepr: Encode + Decode + Copy {
    /// The divisor `D` of the scale factor `(hi - lo) / D`.
    const DIVISOR: f64;
    /// Signed types use the midpoint as bias; unsigned ones the lower limit.
    const SIGNED: bool;
    /// Smallest integer value.
    const MIN_F: f64;
    /// Largest integer value.
    const MAX_F: f64;
    /// Converts an in-range, already rounded count.
    fn from_count(x: f64) -> Self;
    /// Widens to f64.
    fn to_count(self) -> f64;
}

macro_rules! scaled_repr {
    ($($t:ty => $d:expr, $signed:expr;)*) => {$(
        impl ScaledRepr for $t {
            const DIVISOR: f64 = $d;
            const SIGNED: bool = $signed;
            const MIN_F: f64 = <$t>::MIN as f64;
            const MAX_F: f64 = <$t>::MAX as f64;
            #[inline]
            fn from_count(x: f64) -> Self { x as $t }
            #[inline]
            fn to_count(self) -> f64 { self as f64 }
        }
    )*};
}
// Divisors as used by OpenJAUS 3.3 (WIRE.md §2.2), which the reference vectors follow.
scaled_repr! {
    u8 => 255.0, false;
    u16 => 65_535.0, false;
    u32 => 4_294_967_294.0, false;
    u64 => 18_446_744_073_709_551_615.0, false;
    i16 => 65_534.0, true;
    i32 => 4_294_967_294.0, true;
    i64 => 18_446_744_073_709_551_614.0, true;
}

/// Scale factor and bias of a scaled field with limits `[lo, hi]`.
#[inline(always)]
fn scale_bias<T: ScaledRepr>(lo: f64, hi: f64) -> (f64, f64) {
    let sf = (hi - lo) / T::DIVISOR;
    let bias = if T::SIGNED { (hi + lo) / 2.0 } else { lo };
    (sf, bias)
}

/// A scaled field as its encoder sees it: its path, limits and unit. The derive emits
/// one constant per scaled field; encode errors refer to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScaledField {
    /// `Type.field`.
    pub field: &'static str,
    /// Lower limit.
    pub lo: f64,
    /// Upper limit.
    pub hi: f64,
    /// Unit of the real value (`deg`, `m/s`), or empty.
    pub unit: &'static str,
}

/// Real value → integer of the scaled field `s`: round to nearest (ties away from zero).
///
/// A value in `[lo, hi]` is encoded. A value beyond a limit is an
/// [`EncodeError::OutOfRange`], as are NaN and the infinities, with one exception:
/// a finite value whose nearest integer is at most one count beyond the integer of the
/// limit (so less than 1.5 resolution steps beyond it) is encoded as the limit. That
/// margin holds the two integers that lie outside the limits and that this encoder
/// never produces (the most negative value of a signed type, whose range is symmetric,
/// and `u32::MAX` under the OpenJAUS divisor 2³²−2): a received one decodes faithfully,
/// one step beyond the limit, and re-encodes as the limit. It also absorbs rounding
/// noise of computations that end at a limit. Every integer this encoder produces
/// decodes to a value that re-encodes to the same integer.
///
/// [`Encode::clamp_to_range`] clamps every scaled field of a value to its limits first,
/// for callers who want saturation rather than an error.
#[inline(always)]
pub fn scale_to<T: ScaledRepr>(v: f64, s: &'static ScaledField) -> Result<T, EncodeError> {
    // One test for NaN, the infinities and values beyond the limits.
    if !(v >= s.lo && v <= s.hi) {
        return beyond_limits(v, s);
    }
    Ok(to_count(v, s.lo, s.hi))
}

/// The integer of an in-range value.
#[inline(always)]
fn to_count<T: ScaledRepr>(v: f64, lo: f64, hi: f64) -> T {
    let (sf, bias) = scale_bias::<T>(lo, hi);
    // Divide (not multiply by the inverse): exact ties such as 50 % in a u8 [0, 100]
    // then round as OpenJAUS rounds them (128).
    let counts = (v - bias) / sf;
    // Round half away from zero by truncating `x ± 0.5` (a single conversion
    // instruction; `f64::round` is a library call on baseline x86-64). `from_count` is
    // an `as` conversion: it truncates toward zero and saturates at the type's limits.
    let x = if counts >= 0.0 {
        counts + 0.5
    } else {
        counts - 0.5
    };
    T::from_count(x)
}

/// The nearest integer count of `v` (as a float, so that it cannot overflow).
fn nearest_count<T: ScaledRepr>(v: f64, lo: f64, hi: f64) -> f64 {
    let (sf, bias) = scale_bias::<T>(lo, hi);
    ((v - bias) / sf).round()
}

#[cold]
#[inline(never)]
fn beyond_limits<T: ScaledRepr>(v: f64, s: &'static ScaledField) -> Result<T, EncodeError> {
    let (lo, hi) = (s.lo, s.hi);
    let n = nearest_count::<T>(v, lo, hi);
    if v < lo && n >= nearest_count::<T>(lo, lo, hi) - 1.0 {
        return Ok(to_count(lo, lo, hi));
    }
    if v > hi && n <= nearest_count::<T>(hi, lo, hi) + 1.0 {
        return Ok(to_count(hi, lo, hi));
    }
    Err(EncodeError::OutOfRange {
        scaled: s,
        value: v,
        message: None,
    })
}

/// `v` clamped to `[lo, hi]` (NaN stays NaN): what [`Encode::clamp_to_range`] does to
/// a scaled field.
#[inline]
pub fn clamp_scaled(v: f64, lo: f64, hi: f64) -> f64 {
    if v < lo {
        lo
    } else if v > hi {
        hi
    } else {
        v
    }
}

/// Integer → real value: `n * scale + bias`.
#[inline(always)]
pub fn scale_from<T: ScaledRepr>(n: T, lo: f64, hi: f64) -> f64 {
    let (sf, bias) = scale_bias::<T>(lo, hi);
    n.to_count() * sf + bias
}

/// One count of a scaled field: the resolution of its real value.
pub fn scale_step<T: ScaledRepr>(lo: f64, hi: f64) -> f64 {
    scale_bias::<T>(lo, hi).0
}

// ---------------------------------------------------------------------------------
// Strings and blobs. JAUS strings are 8-bit characters; they are decoded as
// ISO-8859-1 so that every byte sequence maps to a `String` and back losslessly.

/// Converts wire bytes to a string (ISO-8859-1).
pub fn latin1_to_string(bytes: &[u8]) -> String {
    if bytes.is_ascii() {
        // ASCII is valid UTF-8.
        String::from_utf8(bytes.to_vec()).unwrap_or_default()
    } else {
        bytes.iter().map(|&b| b as char).collect()
    }
}

/// Number of wire bytes of `s` (one per character).
pub fn latin1_len(s: &str) -> usize {
    if s.is_ascii() {
        s.len()
    } else {
        s.chars().count()
    }
}

/// Writes `s` as ISO-8859-1, failing on characters above U+00FF.
pub fn put_latin1(w: &mut Writer<'_>, s: &str, field: &'static str) -> Result<(), EncodeError> {
    if s.is_ascii() {
        return w.put(s.as_bytes());
    }
    for c in s.chars() {
        let b = u8::try_from(u32::from(c)).map_err(|_| EncodeError::NotLatin1 { field, ch: c })?;
        w.put(&[b])?;
    }
    Ok(())
}

/// Writes a fixed-length, NUL-padded string field.
pub fn put_fixed_string(
    w: &mut Writer<'_>,
    s: &str,
    len: usize,
    field: &'static str,
) -> Result<(), EncodeError> {
    let n = latin1_len(s);
    if n > len {
        return Err(EncodeError::TooLong {
            field,
            len: n,
            max: len,
        });
    }
    put_latin1(w, s, field)?;
    w.zeros(len - n)
}

/// Reads a fixed-length string field, stopping at the first NUL. With `accept_short`,
/// a body that ends early yields the bytes that are there.
pub fn get_fixed_string(
    r: &mut Reader<'_>,
    len: usize,
    accept_short: bool,
) -> Result<String, DecodeError> {
    let n = if accept_short {
        len.min(r.remaining())
    } else {
        len
    };
    let raw = r.take(n)?;
    let end = raw.iter().position(|&b| b == 0).unwrap_or(raw.len());
    Ok(latin1_to_string(&raw[..end]))
}

/// Writes a fixed-length blob, zero padded.
pub fn put_fixed_bytes(
    w: &mut Writer<'_>,
    b: &[u8],
    len: usize,
    field: &'static str,
) -> Result<(), EncodeError> {
    if b.len() > len {
        return Err(EncodeError::TooLong {
            field,
            len: b.len(),
            max: len,
        });
    }
    w.put(b)?;
    w.zeros(len - b.len())
}

/// Writes a NUL-terminated string (the text may not contain NUL).
pub fn put_cstring(w: &mut Writer<'_>, s: &str, field: &'static str) -> Result<(), EncodeError> {
    if s.contains('\0') {
        return Err(EncodeError::NulInText { field });
    }
    put_latin1(w, s, field)?;
    w.put(&[0])
}

/// Reads a NUL-terminated string.
pub fn get_cstring(r: &mut Reader<'_>) -> Result<String, DecodeError> {
    let at = r.offset();
    let rest = r.peek_rest();
    let Some(end) = rest.iter().position(|&b| b == 0) else {
        return Err(DecodeError::new(
            DecodeErrorKind::Truncated {
                needed: rest.len() + 1,
                available: rest.len(),
            },
            at,
        ));
    };
    let text = latin1_to_string(&rest[..end]);
    r.take(end + 1)?;
    Ok(text)
}

/// Reads a string that runs to the end of the body; trailing NULs are dropped.
pub fn get_rest_string(r: &mut Reader<'_>) -> String {
    let raw = r.rest();
    let end = raw.iter().rposition(|&b| b != 0).map_or(0, |i| i + 1);
    latin1_to_string(&raw[..end])
}

/// True when `v` equals its type's default (used to omit zero reserved bits in JSON).
pub fn is_default<T: Default + PartialEq>(v: &T) -> bool {
    *v == T::default()
}

// ---------------------------------------------------------------------------------
// Errors.

/// What went wrong while decoding, and where.
///
/// Boxed, so that `Result<T, DecodeError>` stays one word wider than `T` on the hot
/// path; the allocation happens only when decoding fails.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DecodeError(Box<DecodeErrorInner>);

#[derive(Debug, Clone, PartialEq, Eq)]
struct DecodeErrorInner {
    kind: DecodeErrorKind,
    offset: usize,
    /// The fields being decoded, innermost first (`Record.field`, then the field of
    /// the enclosing record or message that holds it, ...).
    path: Vec<&'static str>,
    message: Option<&'static str>,
}

/// The kinds of decoding failure.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum DecodeErrorKind {
    /// The buffer ended before the field did.
    Truncated {
        /// Bytes the field needed.
        needed: usize,
        /// Bytes that were left.
        available: usize,
    },
    /// A count prefix promises more elements than the remaining bytes can hold.
    CountBeyondBuffer {
        /// The count read.
        count: usize,
        /// Bytes left after it.
        remaining: usize,
    },
    /// A size prefix does not match the size of what it wraps.
    SizeMismatch {
        /// Size announced by the prefix.
        announced: usize,
        /// Size actually consumed.
        consumed: usize,
    },
    /// Records nest deeper than [`MAX_DEPTH`].
    TooDeep {
        /// The limit.
        max: u16,
    },
    /// A field depends on an earlier field (a count or flag) that was not decoded.
    MissingVariable {
        /// The variable name.
        name: &'static str,
    },
    /// The body is longer than the message's fields (and no presence bit the
    /// definition does not know is set).
    TrailingBytes {
        /// Bytes left over.
        count: usize,
    },
    /// A presence bit the definition does not define is set where the fields a newer
    /// revision adds under it cannot be skipped (see [`check_presence`]).
    UndefinedPresenceBit {
        /// The lowest such bit.
        bit: u32,
        /// Why its fields cannot be skipped.
        why: UndefinedBit,
    },
    /// A tag of a tagged union, or a value of a closed enumeration, that the
    /// definition does not name.
    UndefinedValue {
        /// The value read.
        value: u64,
    },
    /// A command code that no known message has.
    UnknownCommandCode {
        /// The code.
        code: u16,
    },
    /// The packet is shorter than the 16-byte header.
    TruncatedHeader {
        /// Bytes present.
        len: usize,
    },
    /// The header's data size disagrees with the bytes that follow it.
    DataSizeMismatch {
        /// Size in the header.
        header: usize,
        /// Bytes actually present after the header.
        actual: usize,
    },
}

/// Why the fields under an undefined presence bit cannot be skipped
/// ([`DecodeErrorKind::UndefinedPresenceBit`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum UndefinedBit {
    /// The presence vector is a nested record's: the end of that record is not known.
    InRecord,
    /// The bit is below this defined bit: newer fields are only known to come after
    /// the known ones when their bits are above every defined bit.
    BelowDefinedBit(u32),
    /// The message's last field runs to the end of the body (`rest`) and is present.
    RestField,
}

/// Checks the presence vector `pv` of a message body (`outermost`) or of a nested
/// record against the bits its definition defines (`known`); `rest_present` says
/// whether the last field runs to the end of the body and is present. `at` is the
/// offset of the presence vector.
///
/// The forward-compatibility rule: a newer revision of a message appends optional
/// fields at the end of the body, under presence bits above every bit the older
/// revision defines. So when bits the definition does not define are set in a message
/// body, the known fields come first and the decoder skips the rest of the body (whose
/// size the header gives): `Ok(true)`. Where that cannot be known to hold, the
/// undefined bit is a [`DecodeErrorKind::UndefinedPresenceBit`]: in a nested record
/// (where the end of the record is not known), below a defined bit, or when the last
/// field runs to the end of the body. `Ok(false)`: every set bit is defined.
#[inline]
pub fn check_presence(
    pv: u64,
    known: u64,
    outermost: bool,
    rest_present: bool,
    at: usize,
) -> Result<bool, DecodeError> {
    let unknown = pv & !known;
    if unknown == 0 {
        return Ok(false);
    }
    undefined_presence(unknown, known, outermost, rest_present, at)
}

#[cold]
#[inline(never)]
fn undefined_presence(
    unknown: u64,
    known: u64,
    outermost: bool,
    rest_present: bool,
    at: usize,
) -> Result<bool, DecodeError> {
    let bit = unknown.trailing_zeros();
    // The lowest defined bit above the lowest undefined one, if any.
    let above = known & !((2u64 << bit).wrapping_sub(1));
    let why = if !outermost {
        UndefinedBit::InRecord
    } else if above != 0 {
        UndefinedBit::BelowDefinedBit(above.trailing_zeros())
    } else if rest_present {
        UndefinedBit::RestField
    } else {
        return Ok(true);
    };
    Err(DecodeError::new(
        DecodeErrorKind::UndefinedPresenceBit { bit, why },
        at,
    ))
}

impl DecodeError {
    /// A new error without field context.
    #[cold]
    pub fn new(kind: DecodeErrorKind, offset: usize) -> Self {
        Self(Box::new(DecodeErrorInner {
            kind,
            offset,
            path: Vec::new(),
            message: None,
        }))
    }

    /// Attaches the field being decoded: the first call names the innermost field,
    /// later calls the fields that enclose it (see [`DecodeError::path`]).
    #[cold]
    pub fn in_field(mut self, field: &'static str) -> Self {
        if self.0.path.last() != Some(&field) {
            self.0.path.push(field);
        }
        self
    }

    /// Attaches the message being decoded, keeping an inner one.
    #[cold]
    pub fn in_message(mut self, message: &'static str) -> Self {
        self.0.message.get_or_insert(message);
        self
    }

    /// The kind of failure.
    pub fn kind(&self) -> &DecodeErrorKind {
        &self.0.kind
    }

    /// Byte offset within the body (or packet, for header errors).
    pub fn offset(&self) -> usize {
        self.0.offset
    }

    /// `Type.field` where decoding failed (innermost), if known.
    pub fn field(&self) -> Option<&'static str> {
        self.0.path.first().copied()
    }

    /// Where decoding failed, innermost field first, then each field that holds it:
    /// `["VksPoint.latitude", "VksObject.points", "ReportVksObjects.objects"]`.
    pub fn path(&self) -> &[&'static str] {
        &self.0.path
    }

    /// Name of the message being decoded, if known.
    pub fn message(&self) -> Option<&'static str> {
        self.0.message
    }
}

impl fmt::Display for DecodeErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Truncated { needed, available } => {
                write!(f, "truncated: needs {needed} byte(s), {available} left")
            }
            Self::CountBeyondBuffer { count, remaining } => {
                write!(f, "count {count} beyond buffer ({remaining} byte(s) left)")
            }
            Self::SizeMismatch {
                announced,
                consumed,
            } => {
                write!(
                    f,
                    "size prefix says {announced} byte(s) but content is {consumed}"
                )
            }
            Self::TrailingBytes { count } => write!(f, "{count} unexpected trailing byte(s)"),
            Self::UndefinedPresenceBit { bit, why } => {
                write!(f, "presence bit {bit} is not defined by this revision: ")?;
                match why {
                    UndefinedBit::InRecord => write!(
                        f,
                        "the size of what a newer revision adds under it inside a nested \
                         record is unknown, so nothing after it can be decoded"
                    ),
                    UndefinedBit::BelowDefinedBit(k) => write!(
                        f,
                        "it lies below defined bit {k}, so a newer revision may place its \
                         field before known ones, whose positions are then unknown"
                    ),
                    UndefinedBit::RestField => write!(
                        f,
                        "the body ends with a field that runs to its end, which would \
                         swallow what a newer revision appends"
                    ),
                }
            }
            Self::MissingVariable { name } => write!(f, "no earlier field sets `{name}`"),
            Self::TooDeep { max } => write!(f, "records nested deeper than {max} levels"),
            Self::UndefinedValue { value } => write!(f, "undefined value {value}"),
            Self::UnknownCommandCode { code } => write!(f, "unknown command code 0x{code:04X}"),
            Self::TruncatedHeader { len } => {
                write!(f, "truncated header: {len} byte(s), a header needs 16")
            }
            Self::DataSizeMismatch { header, actual } => write!(
                f,
                "data size mismatch: header says {header} byte(s), {actual} follow the header"
            ),
        }
    }
}

impl fmt::Display for DecodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some(m) = self.0.message {
            write!(f, "{m}: ")?;
        }
        write!(f, "{}", self.0.kind)?;
        if let Some((field, outer)) = self.0.path.split_first() {
            write!(f, " in field `{field}`")?;
            for o in outer {
                write!(f, " of `{o}`")?;
            }
        }
        // A command code is not a position in the body.
        if matches!(self.0.kind, DecodeErrorKind::UnknownCommandCode { .. }) {
            return Ok(());
        }
        write!(f, " at byte {}", self.0.offset)
    }
}

impl std::error::Error for DecodeError {}

/// Why a value could not be encoded.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum EncodeError {
    /// The output buffer is too small.
    #[error("buffer too small: needs {needed} byte(s), has {capacity}")]
    BufferTooSmall {
        /// Bytes needed so far.
        needed: usize,
        /// Buffer capacity.
        capacity: usize,
    },
    /// A list or blob has more elements than its count prefix can express.
    #[error("field `{field}`: {count} element(s) do not fit a count of at most {max}")]
    CountOverflow {
        /// Field path.
        field: &'static str,
        /// Elements present.
        count: usize,
        /// Largest count.
        max: usize,
    },
    /// A string or blob is longer than its fixed length.
    #[error("field `{field}`: {len} byte(s) exceed the fixed length {max}")]
    TooLong {
        /// Field path.
        field: &'static str,
        /// Length given.
        len: usize,
        /// Fixed length.
        max: usize,
    },
    /// A scaled value is beyond its field's limits, or NaN or infinite (see
    /// [`scale_to`] for the exact rule; [`Encode::clamp_to_range`] saturates instead).
    #[error("{}", OutOfRangeText { scaled, value: *value, message: *message })]
    OutOfRange {
        /// The field, its limits and unit.
        scaled: &'static ScaledField,
        /// The value given.
        value: f64,
        /// The message being encoded, when the field belongs to a record inside it.
        message: Option<&'static str>,
    },
    /// A field depends on an earlier field (a count or flag) that was not encoded.
    #[error("field `{field}`: no earlier field sets `{name}`")]
    MissingVariable {
        /// Field path.
        field: &'static str,
        /// The variable name.
        name: &'static str,
    },
    /// A list's length disagrees with the field that carries its count.
    #[error("field `{field}`: {len} element(s) but `{count_field}` says {expected}")]
    CountMismatch {
        /// Field path.
        field: &'static str,
        /// Elements present.
        len: usize,
        /// The field holding the count.
        count_field: &'static str,
        /// Its value.
        expected: u64,
    },
    /// An optional field is present (or absent) against the flag that governs it.
    #[error("field `{field}`: presence disagrees with `{flag}` (the field must be {})", if *expected { "present" } else { "absent" })]
    PresenceMismatch {
        /// Field path.
        field: &'static str,
        /// The governing flag.
        flag: &'static str,
        /// Whether the field must be present.
        expected: bool,
    },
    /// A union's tag disagrees with the field that carries it.
    #[error("field `{field}`: the value is of type code {tag} but `{tag_field}` says {expected}")]
    TagMismatch {
        /// Field path.
        field: &'static str,
        /// Tag of the value.
        tag: u64,
        /// The field carrying the tag.
        tag_field: &'static str,
        /// Its value.
        expected: u64,
    },
    /// A NUL-terminated string contains a NUL.
    #[error("field `{field}`: a NUL-terminated string cannot contain NUL")]
    NulInText {
        /// Field path.
        field: &'static str,
    },
    /// A value does not fit the bits of its bit field.
    #[error("field `{field}`: value {value} does not fit in {width} bit(s)")]
    BitsOverflow {
        /// Field path.
        field: &'static str,
        /// The value.
        value: u64,
        /// Width of the bit field.
        width: u32,
    },
    /// A string holds a character outside ISO-8859-1.
    #[error("field `{field}`: character {ch:?} is not an 8-bit character")]
    NotLatin1 {
        /// Field path.
        field: &'static str,
        /// The character.
        ch: char,
    },
    /// A whole message is larger than a body can be.
    #[error("message body of {len} byte(s) exceeds the maximum of {max}")]
    BodyTooLarge {
        /// Body length.
        len: usize,
        /// Maximum.
        max: usize,
    },
}

impl EncodeError {
    /// Attaches the message being encoded to an error in a field of a record inside it
    /// (the path of a message's own field already names the message).
    #[cold]
    pub fn in_message(mut self, name: &'static str) -> Self {
        if let Self::OutOfRange { message, .. } = &mut self {
            message.get_or_insert(name);
        }
        self
    }
}

/// `ReportGlobalPose.latitude: 129.5 outside [-90, 90] deg`, with `Message: ` in front
/// when the field belongs to a record inside the message.
struct OutOfRangeText<'a> {
    scaled: &'a ScaledField,
    value: f64,
    message: Option<&'static str>,
}

impl fmt::Display for OutOfRangeText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let s = self.scaled;
        if let Some(m) = self.message {
            let own = s.field.strip_prefix(m).is_some_and(|r| r.starts_with('.'));
            if !own {
                write!(f, "{m}: ")?;
            }
        }
        let is = if self.value.is_nan() {
            "is not in"
        } else {
            "outside"
        };
        write!(f, "{}: {} {is} [{}, {}]", s.field, self.value, s.lo, s.hi)?;
        if !s.unit.is_empty() {
            write!(f, " {}", s.unit)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A scaled field with limits `[lo, hi]` (leaked: tests only).
    fn f(lo: f64, hi: f64) -> &'static ScaledField {
        Box::leak(Box::new(ScaledField {
            field: "T.x",
            lo,
            hi,
            unit: "",
        }))
    }

    #[test]
    fn scaled_examples_from_wire_md() {
        // (value, lo, hi, expected integer) — the OpenJAUS table of WIRE.md §2.2, with
        // round-to-nearest for negatives (−50 % → −16384, −100 % → −32767).
        let pct = f(-100.0, 100.0);
        assert_eq!(scale_to::<i16>(50.0, pct).unwrap(), 16384);
        assert_eq!(scale_to::<i16>(-50.0, pct).unwrap(), -16384);
        assert_eq!(scale_to::<i16>(100.0, pct).unwrap(), 32767);
        assert_eq!(scale_to::<i16>(-100.0, pct).unwrap(), -32767);
        assert_eq!(scale_to::<u8>(50.0, f(0.0, 100.0)).unwrap(), 128);
        assert_eq!(scale_to::<u16>(10.0, f(0.0, 1092.0)).unwrap(), 600);
        assert_eq!(scale_to::<i32>(29.0, f(-90.0, 90.0)).unwrap(), 691_966_953);
        assert_eq!(scale_to::<u32>(1.5, f(0.0, 100.0)).unwrap(), 64_424_509);
        assert!((scale_from::<i16>(16384, -100.0, 100.0) - 50.00153).abs() < 1e-5);
    }

    #[test]
    fn every_in_range_wire_integer_round_trips() {
        use std::f64::consts::PI;
        let angle = f(-PI, PI);
        for n in [-32767, -1, 0, 1, 32766, i16::MAX] {
            assert_eq!(scale_to::<i16>(scale_from(n, -PI, PI), angle).unwrap(), n);
        }
        let pct = f(0.0, 100.0);
        for n in [0u32, 1, 4_294_967_294] {
            assert_eq!(scale_to::<u32>(scale_from(n, 0.0, 100.0), pct).unwrap(), n);
        }
        // The two integers outside the limits decode faithfully and re-encode as the
        // limit (they are one count beyond it).
        assert!(scale_from(i16::MIN, -PI, PI) < -PI);
        assert_eq!(
            scale_to::<i16>(scale_from(i16::MIN, -PI, PI), angle).unwrap(),
            -32767
        );
        assert!(scale_from(u32::MAX, 0.0, 100.0) > 100.0);
        assert_eq!(
            scale_to::<u32>(scale_from(u32::MAX, 0.0, 100.0), pct).unwrap(),
            4_294_967_294
        );
        // So do those of every other signed type and range.
        for (lo, hi) in [(-90.0, 90.0), (-10_000.0, 35_000.0), (0.5, 0.75)] {
            let s = f(lo, hi);
            assert_eq!(
                scale_to::<i32>(scale_from(i32::MIN, lo, hi), s).unwrap(),
                -i32::MAX
            );
            assert_eq!(
                scale_to::<i16>(scale_from(i16::MIN, lo, hi), s).unwrap(),
                -i16::MAX
            );
        }
    }

    #[test]
    fn out_of_range_values_are_errors_beyond_one_count() {
        let pct = f(0.0, 100.0);
        let step = scale_step::<u8>(0.0, 100.0);
        let out = |r: Result<u8, EncodeError>| match r {
            Err(EncodeError::OutOfRange { value, .. }) => value,
            other => panic!("{other:?}"),
        };
        assert_eq!(out(scale_to::<u8>(1e9, pct)), 1e9);
        assert_eq!(out(scale_to::<u8>(-5.0, pct)), -5.0);
        assert!(out(scale_to::<u8>(f64::NAN, pct)).is_nan());
        assert_eq!(out(scale_to::<u8>(f64::INFINITY, pct)), f64::INFINITY);
        assert_eq!(
            out(scale_to::<u8>(f64::NEG_INFINITY, pct)),
            f64::NEG_INFINITY
        );
        // Up to (not including) 1.5 steps beyond a limit: the limit.
        assert_eq!(scale_to::<u8>(100.0 + 1.4 * step, pct).unwrap(), 255);
        assert_eq!(scale_to::<u8>(-1.4 * step, pct).unwrap(), 0);
        assert_eq!(
            out(scale_to::<u8>(100.0 + 1.6 * step, pct)),
            100.0 + 1.6 * step
        );
        assert_eq!(out(scale_to::<u8>(-1.6 * step, pct)), -1.6 * step);
        let one = f(-1.0, 1.0);
        assert!(scale_to::<i16>(-1e9, one).is_err());
        assert!(scale_to::<i64>(1.5, one).is_err());
        assert_eq!(scale_to::<i64>(1.0, one).unwrap(), i64::MAX);
        assert_eq!(scale_to::<u64>(1.0, f(0.0, 1.0)).unwrap(), u64::MAX);
    }

    #[test]
    fn out_of_range_errors_name_the_field_the_value_and_the_limits() {
        static LAT: ScaledField = ScaledField {
            field: "ReportGlobalPose.latitude",
            lo: -90.0,
            hi: 90.0,
            unit: "deg",
        };
        let e = scale_to::<i32>(129.5, &LAT).unwrap_err();
        assert_eq!(
            e.to_string(),
            "ReportGlobalPose.latitude: 129.5 outside [-90, 90] deg"
        );
        // The message is named only when the field is a record's.
        let own = e.clone().in_message("ReportGlobalPose");
        assert_eq!(own.to_string(), e.to_string());
        assert_eq!(
            e.in_message("ReportVksObjects").to_string(),
            "ReportVksObjects: ReportGlobalPose.latitude: 129.5 outside [-90, 90] deg"
        );
        assert_eq!(
            scale_to::<i32>(f64::NAN, &LAT).unwrap_err().to_string(),
            "ReportGlobalPose.latitude: NaN is not in [-90, 90] deg"
        );
        assert_eq!(clamp_scaled(129.5, -90.0, 90.0), 90.0);
        assert_eq!(clamp_scaled(-129.5, -90.0, 90.0), -90.0);
        assert!(clamp_scaled(f64::NAN, -90.0, 90.0).is_nan());
    }

    #[test]
    fn reader_never_panics_on_short_input() {
        let mut r = Reader::new(&[1, 2, 3]);
        assert!(u32::decode(&mut r).is_err());
        assert!(r.take(usize::MAX).is_err());
        assert_eq!(u16::decode(&mut r).unwrap(), 0x0201);
    }

    #[derive(Debug, PartialEq, crate::JausRecord)]
    struct Empty {}

    #[test]
    fn lists_of_elements_that_take_no_bytes_are_bounded() {
        // A u32 count claiming four billion empty elements is refused at once.
        let err =
            decode_list::<u32, Empty>(&mut Reader::new(&[0xFF, 0xFF, 0xFF, 0xFF])).unwrap_err();
        assert!(matches!(
            err.kind(),
            DecodeErrorKind::CountBeyondBuffer { .. }
        ));
        assert_eq!(
            decode_list::<u16, Empty>(&mut Reader::new(&[3, 0]))
                .unwrap()
                .len(),
            3
        );
        // Elements to the end of the body must make progress.
        assert!(decode_rest::<Empty>(&mut Reader::new(&[1])).is_err());
    }

    #[test]
    fn latin1_round_trip() {
        let bytes: Vec<u8> = (1..=255).collect();
        let s = latin1_to_string(&bytes);
        let mut out = vec![0; 255];
        put_latin1(&mut Writer::new(&mut out), &s, "").unwrap();
        assert_eq!(out, bytes);
    }
}

/// Floats in JSON: finite values as numbers; NaN and infinities (which JSON numbers
/// cannot hold) as `"NaN"`, `"inf"`, `"-inf"`, or the bit pattern `"0x…"` for other NaNs,
/// so that every value decoded from the wire encodes back to the same bytes.
#[cfg(feature = "serde")]
pub mod serde_float {
    use serde::{Deserialize, Deserializer, Serializer};

    /// A float type the JSON form applies to.
    pub trait Float: Copy {
        /// Whether the value is finite.
        fn finite(self) -> bool;
        /// The canonical text of a non-finite value, or its bits.
        fn text(self) -> String;
        /// Parses the text form.
        fn parse(s: &str) -> Option<Self>;
        /// Widens to f64 for JSON.
        fn to_f64(self) -> f64;
        /// Narrows from a JSON number.
        fn from_f64(v: f64) -> Self;
    }

    macro_rules! float {
        ($t:ty, $bits:ty) => {
            impl Float for $t {
                fn finite(self) -> bool {
                    self.is_finite()
                }
                fn text(self) -> String {
                    if self.to_bits() == <$t>::NAN.to_bits() {
                        "NaN".into()
                    } else if self == <$t>::INFINITY {
                        "inf".into()
                    } else if self == <$t>::NEG_INFINITY {
                        "-inf".into()
                    } else {
                        format!("0x{:x}", self.to_bits())
                    }
                }
                fn parse(s: &str) -> Option<Self> {
                    match s {
                        "NaN" => Some(<$t>::NAN),
                        "inf" => Some(<$t>::INFINITY),
                        "-inf" => Some(<$t>::NEG_INFINITY),
                        _ => <$bits>::from_str_radix(s.strip_prefix("0x")?, 16)
                            .ok()
                            .map(<$t>::from_bits),
                    }
                }
                fn to_f64(self) -> f64 {
                    f64::from(self)
                }
                #[allow(clippy::cast_possible_truncation)]
                fn from_f64(v: f64) -> Self {
                    v as $t
                }
            }
        };
    }
    float!(f32, u32);
    float!(f64, u64);

    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Repr {
        Number(f64),
        Text(String),
    }

    /// Serialises a float.
    pub fn serialize<T: Float, S: Serializer>(v: &T, s: S) -> Result<S::Ok, S::Error> {
        if v.finite() {
            s.serialize_f64(v.to_f64())
        } else {
            s.serialize_str(&v.text())
        }
    }

    /// Deserialises a float.
    pub fn deserialize<'de, T: Float, D: Deserializer<'de>>(d: D) -> Result<T, D::Error> {
        match Repr::deserialize(d)? {
            Repr::Number(v) => Ok(T::from_f64(v)),
            Repr::Text(t) => T::parse(&t)
                .ok_or_else(|| serde::de::Error::custom(format!("`{t}` is not a float"))),
        }
    }

    /// The same for optional floats.
    pub mod option {
        use super::Float;
        use serde::{Deserializer, Serializer};

        /// Serialises an optional float.
        pub fn serialize<T: Float, S: Serializer>(v: &Option<T>, s: S) -> Result<S::Ok, S::Error> {
            match v {
                Some(v) => super::serialize(v, s),
                None => s.serialize_none(),
            }
        }

        /// Deserialises an optional float.
        pub fn deserialize<'de, T: Float, D: Deserializer<'de>>(
            d: D,
        ) -> Result<Option<T>, D::Error> {
            super::deserialize(d).map(Some)
        }
    }
}
