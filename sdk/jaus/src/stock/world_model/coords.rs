//! The vocabulary of the store's geometry: shapes, edges and boxes in (latitude,
//! unwrapped longitude) degrees, and the constants of the distance frame.

use rstar::AABB;

use crate::stock::geo::{WGS84_A, WGS84_F};

pub(super) const DEG: f64 = std::f64::consts::PI / 180.0;
/// First eccentricity squared of WGS 84.
pub(super) const E2: f64 = WGS84_F * (2.0 - WGS84_F);
/// The smallest meridian radius of curvature (at the equator), metres per radian.
pub(super) const M_MIN: f64 = WGS84_A * (1.0 - E2);

/// The shape of an object or region.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Shape {
    /// One vertex.
    Point,
    /// A line or polyline: two or more vertices.
    Line,
    /// A polygon: three or more vertices, closed implicitly, filled by the even-odd rule.
    Polygon,
}

/// An edge: two vertices in (latitude, unwrapped longitude) degrees (equal for a point).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Seg {
    pub(super) a: [f64; 2],
    pub(super) b: [f64; 2],
}

impl Seg {
    pub(super) fn bbox(&self) -> Box4 {
        Box4::of(self.a, self.b)
    }
    pub(super) fn shifted(self, lon: f64) -> Seg {
        Seg {
            a: [self.a[0], self.a[1] + lon],
            b: [self.b[0], self.b[1] + lon],
        }
    }
}

/// A box in (latitude, unwrapped longitude) degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Box4 {
    pub(super) lat_lo: f64,
    pub(super) lat_hi: f64,
    pub(super) lon_lo: f64,
    pub(super) lon_hi: f64,
}

impl Box4 {
    pub(super) fn of(a: [f64; 2], b: [f64; 2]) -> Box4 {
        Box4 {
            lat_lo: a[0].min(b[0]),
            lat_hi: a[0].max(b[0]),
            lon_lo: a[1].min(b[1]),
            lon_hi: a[1].max(b[1]),
        }
    }

    pub(super) fn shifted(self, lon: f64) -> Box4 {
        Box4 {
            lon_lo: self.lon_lo + lon,
            lon_hi: self.lon_hi + lon,
            ..self
        }
    }

    pub(super) fn overlaps(&self, o: &Box4) -> bool {
        self.lat_lo <= o.lat_hi
            && o.lat_lo <= self.lat_hi
            && self.lon_lo <= o.lon_hi
            && o.lon_lo <= self.lon_hi
    }

    /// The box widened by `d` metres, conservatively for the distance frame (docs of
    /// `geometry`): no point of the frame within `d` of the box lies outside.
    pub(super) fn expand(self, d: f64) -> Box4 {
        if d <= 0.0 {
            return self;
        }
        let dlat = d / M_MIN / DEG;
        let phi = self.lat_lo.abs().max(self.lat_hi.abs()) + dlat;
        let c = if phi >= 90.0 { 0.0 } else { (phi * DEG).cos() };
        let dlon = if c < 1e-9 {
            360.0
        } else {
            (d / (WGS84_A * c) / DEG).min(360.0)
        };
        Box4 {
            lat_lo: self.lat_lo - dlat,
            lat_hi: self.lat_hi + dlat,
            lon_lo: self.lon_lo - dlon,
            lon_hi: self.lon_hi + dlon,
        }
    }

    /// The boxes that cover this one on the canonical longitude strip [-180, 180]: itself
    /// and a copy shifted by 360° when it reaches past ±180°, or the whole strip.
    pub(super) fn index_boxes(self) -> impl Iterator<Item = Box4> {
        let full = self.lon_hi - self.lon_lo >= 360.0;
        let main = if full {
            Box4 {
                lon_lo: -180.0,
                lon_hi: 180.0,
                ..self
            }
        } else {
            self
        };
        let east = (!full && self.lon_hi > 180.0).then(|| self.shifted(-360.0));
        let west = (!full && self.lon_lo < -180.0).then(|| self.shifted(360.0));
        std::iter::once(main).chain(east).chain(west)
    }

    pub(super) fn aabb(&self) -> AABB<[f64; 2]> {
        AABB::from_corners([self.lat_lo, self.lon_lo], [self.lat_hi, self.lon_hi])
    }
}
