//! Scaled integers (docs/wire.md §2.2): real values carried as integers over a range.

use super::{Decode, Encode, EncodeError};

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
    /// The integer whose two's complement is the low bits of `bits`.
    fn from_low_bits(bits: u64) -> Self;
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
            #[inline]
            fn from_low_bits(bits: u64) -> Self { bits as $t }
        }
    )*};
}
// Divisors as used by OpenJAUS 3.3 (docs/wire.md §2.2), which the reference vectors follow.
scaled_repr! {
    u8 => 255.0, false;
    u16 => 65_535.0, false;
    u32 => 4_294_967_294.0, false;
    u64 => 18_446_744_073_709_551_615.0, false;
    i8 => 254.0, true;
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

/// The integer of an in-range value: the quotient `(v - bias) / sf` rounded half away
/// from zero. Divide (not multiply by the inverse): exact ties such as 50 % in a u8
/// [0, 100] then round as OpenJAUS rounds them (128).
///
/// Divisions are the slowest instructions of an encoding (a few scaled fields keep the
/// divider busy longer than the rest of the message takes), so for counts below 2³²
/// (every type up to 32 bits) the quotient is first estimated as the product by the
/// reciprocal, within 1.5 · 2⁻²⁰ of it (three roundings of relative error 2⁻⁵³), and
/// rounded to the nearest integer by adding 1.5 · 2⁵², whose low bits are then that
/// integer. Both roundings agree unless the estimate lies within [`NEAR_TIE`] of a
/// half-integer; only there (about one value in 2¹⁵, and exact ties) is the division
/// done.
#[inline(always)]
fn to_count<T: ScaledRepr>(v: f64, lo: f64, hi: f64) -> T {
    let (sf, bias) = scale_bias::<T>(lo, hi);
    let d = v - bias;
    if T::DIVISOR <= 4_294_967_295.0 {
        let estimate = d * (1.0 / sf);
        // The nearest integers of `estimate ± NEAR_TIE` (two independent roundings,
        // not one after the other): equal when no half-integer lies within NEAR_TIE
        // of the estimate, so none lies between the estimate and the quotient either
        // (the additions of NEAR_TIE round by at most 2⁻²¹ below 2³²).
        let up = (estimate + NEAR_TIE) + ROUNDER;
        let down = (estimate - NEAR_TIE) + ROUNDER;
        if up.to_bits() == down.to_bits() {
            return T::from_low_bits(up.to_bits());
        }
    }
    // Round half away from zero by truncating `x ± 0.5` (a single conversion
    // instruction; `f64::round` is a library call on baseline x86-64). `from_count` is
    // an `as` conversion: it truncates toward zero and saturates at the type's limits.
    let counts = d / sf;
    let x = if counts >= 0.0 {
        counts + 0.5
    } else {
        counts - 0.5
    };
    T::from_count(x)
}

/// 1.5 · 2⁵²: a float of magnitude below 2⁵¹ added to it is rounded to an integer
/// (ties to even), held in the low bits of the sum in two's complement.
const ROUNDER: f64 = 6_755_399_441_055_744.0;

/// Distance from a half-integer within which the reciprocal's estimate of a scaled
/// count is not trusted to round as the quotient does: 2⁻¹⁶, ten times its error.
const NEAR_TIE: f64 = 1.0 / 65_536.0;

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
