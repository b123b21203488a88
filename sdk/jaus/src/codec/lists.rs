//! Counts, size prefixes and lists.

use super::{Decode, DecodeError, DecodeErrorKind, Encode, EncodeError, Reader, Writer};

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
pub(super) fn count_fits(n: usize, min_elem: usize, remaining: usize) -> bool {
    if min_elem == 0 {
        n <= remaining.saturating_add(MAX_EMPTY_ELEMENTS)
    } else {
        n.saturating_mul(min_elem) <= remaining
    }
}
