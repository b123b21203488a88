//! Boxes in (latitude, unwrapped longitude) degrees, widened conservatively for the
//! distance frame of [`geometry`](super::geometry), and the R*-tree entries made of them:
//! the objects of the store and the edges of a large region.

use rstar::{RTree, RTreeObject, AABB};

use super::geometry::{Seg, DEG, M_MIN};
use crate::cores::geo::WGS84_A;

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

/// The edges of a region, indexed when there are many.
#[derive(Debug, Clone)]
pub(super) enum SegIndex {
    Few(Vec<Seg>),
    Tree(RTree<SegEntry>),
}

/// An edge in the R-tree of a region.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct SegEntry(pub(super) Seg);

impl RTreeObject for SegEntry {
    type Envelope = AABB<[f64; 2]>;
    fn envelope(&self) -> Self::Envelope {
        self.0.bbox().aabb()
    }
}

impl SegIndex {
    /// Whether `f` holds for an edge whose box meets `b`.
    pub(super) fn any_near(&self, b: &Box4, mut f: impl FnMut(Seg) -> bool) -> bool {
        match self {
            SegIndex::Few(v) => v.iter().any(|s| s.bbox().overlaps(b) && f(*s)),
            SegIndex::Tree(t) => t.locate_in_envelope_intersecting(&b.aabb()).any(|e| f(e.0)),
        }
    }
}

/// The box of an object (or of its copy across the antimeridian) in the store's
/// R*-tree.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Entry {
    /// Index of the object in `VectorStore::slots`.
    pub(super) slot: u32,
    pub(super) env: AABB<[f64; 2]>,
}

impl RTreeObject for Entry {
    type Envelope = AABB<[f64; 2]>;
    fn envelope(&self) -> Self::Envelope {
        self.env
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cores::world_model::geometry::point_segment_distance;
    use crate::messages::VksPoint;

    #[test]
    fn widened_boxes_hold_every_point_in_reach() {
        let p = |latitude, longitude| VksPoint {
            latitude,
            longitude,
        };
        // For boxes at many latitudes, a point just inside the distance in any
        // direction lies inside the widened box.
        for lat in [-89.0, -60.0, 0.0, 45.0, 80.0, 89.9] {
            let b = Box4 {
                lat_lo: lat,
                lat_hi: lat,
                lon_lo: 10.0,
                lon_hi: 10.0,
            };
            for d in [1.0, 100.0, 10_000.0] {
                let e = b.expand(d);
                for i in 0..32 {
                    let a = f64::from(i) / 32.0 * std::f64::consts::TAU;
                    // Walk outwards until the frame distance exceeds d.
                    let mut k = 0.0;
                    loop {
                        let q = p((lat + k * a.sin()).clamp(-90.0, 90.0), 10.0 + k * a.cos());
                        let dist = point_segment_distance(&q, &p(lat, 10.0), &p(lat, 10.0));
                        if dist > d || k > 10.0 {
                            break;
                        }
                        assert!(
                            q.latitude >= e.lat_lo
                                && q.latitude <= e.lat_hi
                                && q.longitude >= e.lon_lo
                                && q.longitude <= e.lon_hi,
                            "lat {lat} d {d} dir {i}: {q:?} outside {e:?}"
                        );
                        k += d / 200_000.0;
                    }
                }
            }
        }
    }
}
