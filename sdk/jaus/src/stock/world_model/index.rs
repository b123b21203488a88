//! Boxes in (latitude, unwrapped longitude) degrees, widened conservatively for the
//! distance frame of [`geometry`](super::geometry), and the R*-tree entries made of them:
//! the objects of the store and the edges of a large region.

use rstar::{RTree, RTreeObject, AABB};

use super::coords::{Box4, Seg};

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
    use crate::messages::VksPoint;
    use crate::stock::world_model::geometry::point_segment_distance;

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
