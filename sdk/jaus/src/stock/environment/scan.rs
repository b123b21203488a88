//! What a scanning range finder gives: sweeps of beams in the platform frame
//! ([`Beam`], [`RangeScanner`]) and the objects found in a sweep ([`Detection`],
//! [`detections`]). The Range Sensor ([`range`](super::range)) and the world-model feed
//! ([`map_feed`](super::map_feed)) both work on them.

use std::time::Instant;

/// One beam of a sweep, in the platform frame (x forward, y right).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Beam {
    /// Direction, rad, 0 = forward, growing toward the right.
    pub bearing: f64,
    /// Distance to the first return, m (`None`: nothing within range).
    pub range: Option<f64>,
}

/// What a scanner is, for the services that report it (the AS-4 Range Sensor's
/// capabilities, configuration and placement): its beams' spread and reach.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScannerSpec {
    /// Bearing of its first (leftmost) beam, rad, as [`Beam::bearing`].
    pub first_bearing: f64,
    /// Bearing of its last (rightmost) beam, rad.
    pub last_bearing: f64,
    /// Beams in a sweep.
    pub beams: usize,
    /// Farthest return, m.
    pub max_range: f64,
    /// Range noise (standard deviation), m.
    pub range_noise: f64,
    /// Where ranges are measured from: forward and right of the platform's reference
    /// point, m (bearings are the platform's directions, whatever the mount's yaw).
    pub mount: (f64, f64),
}

/// A scanning range finder (a 2-D lidar, a sonar ring, ...).
pub trait RangeScanner: Send + 'static {
    /// The latest sweep into `out` (cleared first), or `false` without one.
    fn scan(&mut self, now: Instant, out: &mut Vec<Beam>) -> bool;

    /// Its geometry, when known (default: not known).
    fn spec(&self) -> Option<ScannerSpec> {
        None
    }
}

/// An object found in a sweep: its nearest return.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Detection {
    /// Range of the nearest return, m.
    pub range: f64,
    /// Its bearing, rad (0 forward, positive to the right).
    pub bearing: f64,
    /// Beams that saw the object.
    pub beams: usize,
    /// Angle between the object's first and last beam, rad (0 for one beam).
    pub span: f64,
}

/// Groups a sweep's returns into objects: neighbouring beams (in the order given)
/// whose ranges differ by at most `gap` metres belong to one object.
pub fn detections(beams: &[Beam], gap: f64) -> Vec<Detection> {
    let mut out: Vec<Detection> = Vec::new();
    let mut last: Option<f64> = None;
    let mut first_bearing = 0.0;
    for b in beams {
        let Some(r) = b.range.filter(|r| r.is_finite() && *r >= 0.0) else {
            last = None;
            continue;
        };
        match (last, out.last_mut()) {
            (Some(prev), Some(d)) if (r - prev).abs() <= gap => {
                d.beams += 1;
                d.span = (b.bearing - first_bearing).abs();
                if r < d.range {
                    d.range = r;
                    d.bearing = b.bearing;
                }
            }
            _ => {
                first_bearing = b.bearing;
                out.push(Detection {
                    range: r,
                    bearing: b.bearing,
                    beams: 1,
                    span: 0.0,
                });
            }
        }
        last = Some(r);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn beam(bearing_deg: f64, range: Option<f64>) -> Beam {
        Beam {
            bearing: bearing_deg.to_radians(),
            range,
        }
    }

    #[test]
    fn neighbouring_returns_make_one_object_and_gaps_split_them() {
        let beams = [
            beam(-10.0, None),
            beam(-5.0, Some(4.2)),
            beam(0.0, Some(4.0)),
            beam(5.0, Some(4.1)),
            beam(10.0, Some(9.0)),
            beam(15.0, None),
            beam(20.0, Some(2.0)),
        ];
        let d = detections(&beams, 0.3);
        assert_eq!(d.len(), 3);
        assert_eq!((d[0].range, d[0].beams), (4.0, 3));
        assert!((d[0].span - 10f64.to_radians()).abs() < 1e-12);
        assert_eq!(d[2].span, 0.0);
        assert!(d[0].bearing.abs() < 1e-12);
        assert_eq!((d[1].range, d[2].range), (9.0, 2.0));
        assert!(detections(&[beam(0.0, Some(f64::NAN))], 0.3).is_empty());
    }
}
