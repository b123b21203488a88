//! What a change of scaling does to the values peers exchange.
//!
//! A scaled value travels as an integer count; each revision turns counts into real
//! values with its own integer type and limits (jaus-spec's README, "Scaled integers":
//! `value = count * (hi - lo) / D + bias`, encoding rounds to the nearest count). When
//! the integer or the limits change, the bytes stay where they were but mean another
//! value: an old peer's 1.0 m arrives at a new peer as whatever the new scaling makes
//! of the old count. [`consequence`] computes that for a representative value, both
//! ways, so that a change report says what happens instead of only what changed.

use jaus_spec::Int;

/// A scaling: the integer on the wire and the limits of the real value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Scaling {
    pub(super) int: Int,
    pub(super) lo: f64,
    pub(super) hi: f64,
}

impl Scaling {
    fn scale_bias(self) -> (f64, f64) {
        let sf = (self.hi - self.lo) / self.int.divisor();
        let bias = if self.int.unsigned() {
            self.lo
        } else {
            (self.hi + self.lo) / 2.0
        };
        (sf, bias)
    }

    /// Smallest and largest count of the integer type.
    fn count_range(self) -> (f64, f64) {
        let bits = 8 * self.int.bytes() as i32;
        if self.int.unsigned() {
            (0.0, 2f64.powi(bits) - 1.0)
        } else {
            (-(2f64.powi(bits - 1)), 2f64.powi(bits - 1) - 1.0)
        }
    }

    /// The count the encoder puts on the wire for `v` (nearest, ties away from zero,
    /// saturated at the type's limits like the encoder's conversion).
    fn encode(self, v: f64) -> f64 {
        let (sf, bias) = self.scale_bias();
        let (min, max) = self.count_range();
        ((v - bias) / sf).round().clamp(min, max)
    }

    /// The real value of a count.
    fn decode(self, count: f64) -> f64 {
        let (sf, bias) = self.scale_bias();
        count * sf + bias
    }

    fn contains(self, v: f64) -> bool {
        self.lo <= v && v <= self.hi
    }
}

/// `count` of type `from` as the bytes a reader of type `to` (same width) sees:
/// the same bits, read signed or unsigned.
fn reinterpret(count: f64, from: Int, to: Int) -> f64 {
    let bits = 8 * from.bytes() as u32;
    // Counts of types up to 32 bits are exact in i128 and f64; 64-bit ones are as exact
    // as their f64 values.
    let n = count as i128;
    let modulus = 1i128 << bits;
    let raw = n.rem_euclid(modulus);
    let v = if !to.unsigned() && raw >= modulus / 2 {
        raw - modulus
    } else {
        raw
    };
    v as f64
}

/// What a reader with scaling `to` makes of the value `v` a writer with scaling `from`
/// sent; `None` when the integers differ in width (every later byte shifts, so there is
/// no value to speak of).
fn arrives_as(v: f64, from: Scaling, to: Scaling) -> Option<f64> {
    if from.int.bytes() != to.int.bytes() {
        return None;
    }
    let count = reinterpret(from.encode(v), from.int, to.int);
    Some(to.decode(count))
}

/// A value printed with 4 significant digits, trailing zeros dropped (`1.333`,
/// `0.75`, `0.035`, `13107`).
fn number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return if v.is_finite() {
            "0".into()
        } else {
            v.to_string()
        };
    }
    let magnitude = v.abs().log10().floor() as i32;
    let decimals = (3 - magnitude).max(0) as usize;
    let mut s = format!("{v:.decimals$}");
    if s.contains('.') {
        s = s.trim_end_matches('0').trim_end_matches('.').to_string();
    }
    if s == "-0" {
        s = "0".into();
    }
    s
}

fn with_unit(v: f64, unit: Option<&str>) -> String {
    match unit {
        Some(u) if !u.is_empty() => format!("{} {u}", number(v)),
        _ => number(v),
    }
}

/// What a change of scaling `old` → `new` does to a representative value, both ways:
/// `an old peer's 1 m arrives as 1.333 m; a new peer's 1 m arrives at an old peer as
/// 0.75 m`. The value is 1 unit when the old range holds it, else a point a quarter and
/// then three quarters up the old range (the first that the change moves). `None` when
/// the integers differ in width or no value moves.
pub(super) fn consequence(
    old: Scaling,
    new: Scaling,
    old_unit: Option<&str>,
    new_unit: Option<&str>,
) -> Option<String> {
    let width = old.hi - old.lo;
    let candidates = [1.0, old.lo + 0.75 * width, old.lo + 0.25 * width];
    let moved = |v: f64, to: f64| (to - v).abs() > 1e-9 * v.abs().max(1.0);
    let (v, there) = candidates
        .into_iter()
        .filter(|&v| old.contains(v))
        .filter_map(|v| arrives_as(v, old, new).map(|to| (v, to)))
        .find(|&(v, to)| moved(v, to))?;
    let mut s = format!(
        "an old peer's {} arrives as {}",
        with_unit(v, old_unit),
        with_unit(there, new_unit)
    );
    if new.contains(v) {
        if let Some(back) = arrives_as(v, new, old) {
            s += &format!(
                "; a new peer's {} arrives at an old peer as {}",
                with_unit(v, new_unit),
                with_unit(back, old_unit)
            );
        }
    }
    Some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s(int: Int, lo: f64, hi: f64) -> Scaling {
        Scaling { int, lo, hi }
    }

    #[test]
    fn a_wider_range_turns_an_old_metre_into_a_third_more() {
        let c = consequence(
            s(Int::U16, 0.0, 1.5),
            s(Int::U16, 0.0, 2.0),
            Some("m"),
            Some("m"),
        );
        assert_eq!(
            c.as_deref(),
            Some("an old peer's 1 m arrives as 1.333 m; a new peer's 1 m arrives at an old peer as 0.75 m")
        );
    }

    #[test]
    fn a_range_without_1_uses_a_point_up_the_range_and_signed_types_use_the_midpoint_bias() {
        // [-0.5, 0.5] does not hold 1: three quarters up is 0.25, read on [-1, 1] as 0.5.
        let c = consequence(
            s(Int::I16, -0.5, 0.5),
            s(Int::I16, -1.0, 1.0),
            Some("rad"),
            Some("rad"),
        )
        .unwrap();
        assert!(
            c.starts_with("an old peer's 0.25 rad arrives as 0.5 rad"),
            "{c}"
        );
    }

    #[test]
    fn a_signedness_change_reads_the_same_bits_and_a_width_change_has_no_value() {
        // 1 in u16 [0, 100] is count 655; read as i16 [0, 100] (bias 50): 50.999...
        let c = consequence(s(Int::U16, 0.0, 100.0), s(Int::I16, 0.0, 100.0), None, None).unwrap();
        assert!(c.starts_with("an old peer's 1 arrives as 51"), "{c}");
        // 90 is count 58982, above i16::MAX: its bits read back negative.
        assert!(arrives_as(90.0, s(Int::U16, 0.0, 100.0), s(Int::I16, 0.0, 100.0)).unwrap() < 50.0);
        assert_eq!(
            consequence(s(Int::U8, 0.0, 1.0), s(Int::U16, 0.0, 1.0), None, None),
            None
        );
    }

    #[test]
    fn numbers_keep_four_significant_digits() {
        for (v, t) in [
            (1.333_333, "1.333"),
            (0.750_01, "0.75"),
            (0.035_002, "0.035"),
            (13_107.2, "13107"),
            (-2.5, "-2.5"),
            (0.0, "0"),
            (-0.000_01, "-0.00001"),
        ] {
            assert_eq!(number(v), t);
        }
    }
}
