//! The integer types of the wire chosen at run time: each helper dispatches to the SDK
//! codec's generic function for the concrete type, so that the byte rules (little
//! endian, scaled rounding, count checks) are the SDK's own.

use jaus::codec::{
    get_count, put_count, scale_from, scale_to, Decode, DecodeError, Encode, EncodeError, Reader,
    ScaledField, Writer,
};
use jaus_spec::Int;

/// Runs `$body` with `$t` bound to the Rust type of `$int`.
macro_rules! with_int {
    ($int:expr, $t:ident => $body:expr) => {
        match $int {
            Int::U8 => {
                type $t = u8;
                $body
            }
            Int::U16 => {
                type $t = u16;
                $body
            }
            Int::U32 => {
                type $t = u32;
                $body
            }
            Int::U64 => {
                type $t = u64;
                $body
            }
            Int::I8 => {
                type $t = i8;
                $body
            }
            Int::I16 => {
                type $t = i16;
                $body
            }
            Int::I32 => {
                type $t = i32;
                $body
            }
            Int::I64 => {
                type $t = i64;
                $body
            }
        }
    };
}

/// Reads an integer, widened: unsigned types to `u64` (`Ok(Ok(_))`), signed ones to
/// `i64` (`Ok(Err(_))`).
#[inline]
pub(crate) fn read(int: Int, r: &mut Reader<'_>) -> Result<Result<u64, i64>, DecodeError> {
    Ok(match int {
        Int::U8 => Ok(u64::from(u8::decode(r)?)),
        Int::U16 => Ok(u64::from(u16::decode(r)?)),
        Int::U32 => Ok(u64::from(u32::decode(r)?)),
        Int::U64 => Ok(u64::decode(r)?),
        Int::I8 => Err(i64::from(i8::decode(r)?)),
        Int::I16 => Err(i64::from(i16::decode(r)?)),
        Int::I32 => Err(i64::from(i32::decode(r)?)),
        Int::I64 => Err(i64::decode(r)?),
    })
}

/// Reads an unsigned integer (presence vectors, tags, enumerations, bit fields); a
/// signed type is read as its bit pattern.
#[inline]
pub(crate) fn read_u(int: Int, r: &mut Reader<'_>) -> Result<u64, DecodeError> {
    Ok(match read(int, r)? {
        Ok(v) => v,
        Err(v) => v as u64 & crate::schema::mask(int.bytes() as u32 * 8),
    })
}

/// Writes an unsigned value as `int`; the caller has checked that it fits.
pub(crate) fn write_u(int: Int, v: u64, w: &mut Writer<'_>) -> Result<(), EncodeError> {
    with_int!(int, T => (v as T).encode(w))
}

/// Writes a signed value as `int`; the caller has checked that it fits.
pub(crate) fn write_i(int: Int, v: i64, w: &mut Writer<'_>) -> Result<(), EncodeError> {
    with_int!(int, T => (v as T).encode(w))
}

/// Whether `v` fits `int`.
pub(crate) fn fits_u(int: Int, v: u64) -> bool {
    with_int!(int, T => T::try_from(v).is_ok())
}

/// Whether `v` fits `int`.
pub(crate) fn fits_i(int: Int, v: i64) -> bool {
    with_int!(int, T => T::try_from(v).is_ok())
}

/// The largest value of `int`, as the count errors report it.
pub(crate) fn max_usize(int: Int) -> usize {
    let max: u64 = match int {
        Int::U8 => u8::MAX.into(),
        Int::U16 => u16::MAX.into(),
        Int::U32 => u32::MAX.into(),
        Int::U64 => u64::MAX,
        Int::I8 => i8::MAX.unsigned_abs().into(),
        Int::I16 => i16::MAX.unsigned_abs().into(),
        Int::I32 => i32::MAX.unsigned_abs().into(),
        Int::I64 => i64::MAX.unsigned_abs(),
    };
    usize::try_from(max).unwrap_or(usize::MAX)
}

/// Reads a scaled integer and gives its real value.
#[inline]
pub(crate) fn read_scaled(
    int: Int,
    s: &ScaledField,
    r: &mut Reader<'_>,
) -> Result<f64, DecodeError> {
    with_int!(int, T => T::decode(r).map(|n| scale_from::<T>(n, s.lo, s.hi)))
}

/// Writes a real value as its scaled integer (the SDK's rounding and range rules).
pub(crate) fn write_scaled(
    int: Int,
    v: f64,
    s: &'static ScaledField,
    w: &mut Writer<'_>,
) -> Result<(), EncodeError> {
    with_int!(int, T => scale_to::<T>(v, s)?.encode(w))
}

/// Reads a count or size prefix (u8, u16 or u32) for elements of at least `min_elem`
/// bytes.
pub(crate) fn read_count(
    int: Int,
    r: &mut Reader<'_>,
    min_elem: usize,
) -> Result<usize, DecodeError> {
    match int {
        Int::U8 => get_count::<u8>(r, min_elem),
        Int::U16 => get_count::<u16>(r, min_elem),
        _ => get_count::<u32>(r, min_elem),
    }
}

/// Writes a count or size prefix, failing when `n` does not fit.
pub(crate) fn write_count(
    int: Int,
    w: &mut Writer<'_>,
    n: usize,
    field: &'static str,
) -> Result<(), EncodeError> {
    match int {
        Int::U8 => put_count::<u8>(w, n, field),
        Int::U16 => put_count::<u16>(w, n, field),
        _ => put_count::<u32>(w, n, field),
    }
}
