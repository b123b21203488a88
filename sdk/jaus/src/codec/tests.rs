//! Unit tests of the codec runtime.

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
    // (value, lo, hi, expected integer) — the OpenJAUS table of docs/wire.md §2.2, with
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

/// The quotient rounded half away from zero: the rule `scale_to` implements (by
/// multiplying where that gives the same integer).
fn by_division<T: ScaledRepr>(v: f64, lo: f64, hi: f64) -> T {
    let sf = (hi - lo) / T::DIVISOR;
    let bias = if T::SIGNED { (hi + lo) / 2.0 } else { lo };
    let q = (v - bias) / sf;
    T::from_count(if q >= 0.0 { q + 0.5 } else { q - 0.5 })
}

/// The float `k` ulps from `v` (nonzero), away from zero for positive `k`.
fn ulp(v: f64, k: i64) -> f64 {
    f64::from_bits(v.to_bits().wrapping_add_signed(k))
}

fn agrees_with_division<T: ScaledRepr + PartialEq + std::fmt::Debug>(lo: f64, hi: f64) {
    let s = f(lo, hi);
    let step = scale_step::<T>(lo, hi);
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    for i in 0..20_000 {
        // Random values, and values at (or a few ulps from) a tie between two counts.
        let v = lo + (hi - lo) * next();
        let n = scale_to::<T>(v, s).unwrap();
        let tie = scale_from::<T>(n, lo, hi) + step / 2.0;
        let at = lo + step * (i as f64 + 0.5);
        let near = [
            v,
            tie,
            ulp(tie, 1),
            ulp(tie, -1),
            ulp(tie, 3),
            ulp(tie, -3),
            at,
        ];
        for v in near.into_iter().filter(|v| (lo..=hi).contains(v)) {
            assert_eq!(
                scale_to::<T>(v, s).unwrap(),
                by_division::<T>(v, lo, hi),
                "{v} in [{lo}, {hi}]"
            );
        }
    }
}

#[test]
fn scaled_encoding_rounds_as_the_division_does() {
    let ranges = [
        (-90.0, 90.0),
        (-180.0, 180.0),
        (0.0, 100.0),
        (-100.0, 100.0),
        (0.5, 0.75),
    ];
    for (lo, hi) in ranges {
        agrees_with_division::<i32>(lo, hi);
        agrees_with_division::<u32>(lo, hi);
        agrees_with_division::<i16>(lo, hi);
        agrees_with_division::<u16>(lo, hi);
        agrees_with_division::<u8>(lo, hi);
        agrees_with_division::<i64>(lo, hi);
    }
    agrees_with_division::<i16>(-std::f64::consts::PI, std::f64::consts::PI);
    agrees_with_division::<i32>(-10_000.0, 35_000.0);
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
    let err = decode_list::<u32, Empty>(&mut Reader::new(&[0xFF, 0xFF, 0xFF, 0xFF])).unwrap_err();
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

#[test]
fn text_is_fitted_to_a_fixed_string_field() {
    assert_eq!(fit_latin1("front camera", 15), "front camera");
    assert_eq!(fit_latin1("a very long camera name", 15), "a very long cam");
    // ISO-8859-1 characters are one byte each and kept; others become '?'.
    assert_eq!(fit_latin1("caméra → 1", 15), "caméra ? 1");
    let fitted = fit_latin1("ééééééééééééééééééé", 15);
    assert_eq!(latin1_len(&fitted), 15);
}

#[test]
fn chunks_are_taken_whole_or_not_at_all() {
    let mut buf = [0u8; 6];
    let mut w = Writer::new(&mut buf);
    w.put(&[1]).unwrap();
    assert!(w.chunk_mut::<6>().is_none());
    assert!(w.array_mut::<6>().is_none());
    assert_eq!(w.position(), 1);
    *w.array_mut::<2>().unwrap() = [2, 3];
    assert_eq!(w.position(), 3);
    w.chunk_mut::<3>().unwrap()[0] = 4;
    w.advance(1);
    assert_eq!(w.position(), 4);
    w.advance(10);
    assert_eq!(w.position(), 6);
    assert_eq!(buf[..4], [1, 2, 3, 4]);
}

/// A body written into every buffer too short for it fails where field-by-field
/// writing fails: `needed` is the end of the first field that does not fit (the
/// derive writes runs of fixed-size fields through one chunk when the whole run fits).
#[test]
fn short_buffers_report_the_first_field_that_does_not_fit() {
    use crate::messages::{SetGlobalPathSegment, SetWrenchEffort};
    let swe = SetWrenchEffort {
        propulsive_linear_effort_x: Some(10.0),
        propulsive_rotational_effort_z: Some(-20.0),
        resistive_linear_effort_x: Some(5.0),
        ..Default::default()
    };
    let bytes = swe.to_bytes().unwrap();
    // The presence vector u16, two i16, a u8 (resistive effort).
    let ends = [2usize, 4, 6, 7];
    assert_eq!(bytes.len(), 7);
    for cap in 0..bytes.len() {
        let mut buf = vec![0u8; cap];
        let err = swe.encode(&mut Writer::new(&mut buf)).unwrap_err();
        let needed = ends.iter().copied().find(|&e| e > cap).unwrap();
        assert!(
            matches!(err, EncodeError::BufferTooSmall { needed: n, capacity: c } if n == needed && c == cap),
            "{cap}: {err:?}"
        );
    }
    let sgps = SetGlobalPathSegment {
        path_segment_number: 3,
        p1_latitude: 10.0,
        p1_longitude: 20.0,
        p1_altitude: Some(30.0),
        ..Default::default()
    };
    let bytes = sgps.to_bytes().unwrap();
    // Presence vector u8, number u16, latitude, longitude and altitude i32, latitude
    // and longitude i32 (no second altitude), weighting factor u16.
    let ends = [1usize, 3, 7, 11, 15, 19, 23, 25];
    assert_eq!(bytes.len(), 25);
    for cap in 0..bytes.len() {
        let mut buf = vec![0u8; cap];
        let err = sgps.encode(&mut Writer::new(&mut buf)).unwrap_err();
        let needed = ends.iter().copied().find(|&e| e > cap).unwrap();
        assert!(
            matches!(err, EncodeError::BufferTooSmall { needed: n, .. } if n == needed),
            "{cap}: {err:?}"
        );
    }
    // Within a run written through one chunk, a value beyond its limits is still the
    // error of its own field.
    let mut bad = swe.clone();
    bad.propulsive_rotational_effort_z = Some(-150.0);
    let mut buf = vec![0u8; 64];
    let err = bad.encode(&mut Writer::new(&mut buf)).unwrap_err();
    assert!(
        matches!(err, EncodeError::OutOfRange { scaled, value, .. }
            if scaled.field == "SetWrenchEffort.propulsive_rotational_effort_z" && value == -150.0),
        "{err:?}"
    );
    let mut buf = vec![0u8; bytes.len()];
    let mut w = Writer::new(&mut buf);
    sgps.encode(&mut w).unwrap();
    assert_eq!(w.position(), bytes.len());
    assert_eq!(buf, bytes);
}

/// Lists of fixed-length records (written through one slice when the whole list fits)
/// fail as element-by-element writing does: on a short buffer at the element that does
/// not fit, on a value beyond its limits at that value's field.
#[test]
fn lists_of_fixed_length_records_fail_at_their_element() {
    use crate::messages::{VksPoint, VksStoredObject};
    assert_eq!(<VksPoint as Encode>::fixed_len(), 8);
    assert_eq!(<VksStoredObject as Encode>::fixed_len(), 0);
    let object = VksStoredObject {
        object_id: 7,
        buffer: 1.5,
        points: (0..3)
            .map(|i| VksPoint {
                latitude: 10.0 + f64::from(i),
                longitude: -20.0,
            })
            .collect(),
        ..Default::default()
    };
    let bytes = object.to_bytes().unwrap();
    // id u32, type u8, buffer f32, no feature class (count u8), point count u16, then
    // three points of two i32.
    let ends = [4usize, 5, 9, 10, 12, 16, 20, 24, 28, 32, 36];
    assert_eq!(bytes.len(), 36);
    let mut one_by_one = vec![0u8; 36];
    let mut w = Writer::new(&mut one_by_one);
    for (i, e) in [
        7u32.to_le_bytes().as_slice(),
        &[0],
        &1.5f32.to_le_bytes(),
        &[0],
        &[3, 0],
    ]
    .into_iter()
    .enumerate()
    {
        assert_eq!(w.position(), [0, 4, 5, 9, 10][i]);
        w.put(e).unwrap();
    }
    for p in &object.points {
        p.encode(&mut w).unwrap();
    }
    assert_eq!(bytes, one_by_one);
    for cap in 0..bytes.len() {
        let mut buf = vec![0u8; cap];
        let err = object.encode(&mut Writer::new(&mut buf)).unwrap_err();
        let needed = ends.iter().copied().find(|&e| e > cap).unwrap();
        assert!(
            matches!(err, EncodeError::BufferTooSmall { needed: n, capacity: c } if n == needed && c == cap),
            "{cap}: {err:?}"
        );
    }
    let mut bad = object.clone();
    bad.points[1].longitude = 200.0;
    let mut buf = vec![0u8; 64];
    let err = bad.encode(&mut Writer::new(&mut buf)).unwrap_err();
    assert!(
        matches!(err, EncodeError::OutOfRange { scaled, value, .. }
            if scaled.field == "VksPoint.longitude" && value == 200.0),
        "{err:?}"
    );
}
