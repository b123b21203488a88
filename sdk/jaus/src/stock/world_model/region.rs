//! Regions of queries and deletions ([`Geometry`]: a checked shape with a buffer and
//! its edges indexed) and the [`Filter`] that selects objects by ID, region and feature
//! class.

use rstar::RTree;

use super::coords::{Box4, Seg};
use super::error::StoreError;
use super::geometry::{analyse, inside, seg_within, segments, Shape, Unwrap, View, MAX_VERTICES};
use super::index::{SegEntry, SegIndex};
use crate::messages::{
    DeleteVksObjects, QueryVksObjects, VksFeatureClassFilter, VksObjectType, VksPoint,
    VksStoredObject,
};

/// The id of a stored object (assigned by the store; never reused while in use).
pub type ObjectId = u32;

/// Largest region buffer of a query or deletion region, metres (half a meridian).
pub const MAX_REGION_BUFFER: f64 = 2.0e7;

/// Segment counts above which a region's edges get an R-tree of their own.
const SEGMENT_TREE_MIN: usize = 16;

/// A validated shape with a buffer: the region of a query or deletion, or a stand-alone
/// geometry to test with [`Geometry::intersects`].
#[derive(Debug, Clone)]
pub struct Geometry {
    shape: Shape,
    points: Vec<VksPoint>,
    buffer: f64,
    shift: f64,
    fp: Box4,
    segs: SegIndex,
}

impl PartialEq for Geometry {
    fn eq(&self, o: &Self) -> bool {
        self.shape == o.shape && self.points == o.points && self.buffer == o.buffer
    }
}

impl Geometry {
    /// A shape of `points` (WGS 84 degrees) with a `buffer` in metres; refused when a
    /// vertex is NaN or out of range, the count does not fit the shape or exceeds
    /// 65,535, the buffer is NaN, negative or above [`MAX_REGION_BUFFER`], or the
    /// shape goes round the Earth.
    pub fn new(shape: Shape, points: Vec<VksPoint>, buffer: f64) -> Result<Geometry, StoreError> {
        if !(0.0..=MAX_REGION_BUFFER).contains(&buffer) {
            return Err(StoreError::Buffer {
                value: buffer,
                max: MAX_REGION_BUFFER,
            });
        }
        let (fp, shift) = analyse(shape, &points, MAX_VERTICES)?;
        let segs: Vec<Seg> = segments(shape, Unwrap::new(&points, shift)).collect();
        let segs = if segs.len() > SEGMENT_TREE_MIN {
            SegIndex::Tree(RTree::bulk_load(segs.into_iter().map(SegEntry).collect()))
        } else {
            SegIndex::Few(segs)
        };
        Ok(Geometry {
            shape,
            points,
            buffer,
            shift,
            fp,
            segs,
        })
    }

    /// The shape.
    pub fn shape(&self) -> Shape {
        self.shape
    }

    /// The vertices.
    pub fn points(&self) -> &[VksPoint] {
        &self.points
    }

    /// The buffer, metres.
    pub fn buffer(&self) -> f64 {
        self.buffer
    }

    fn view(&self) -> View<'_> {
        View {
            shape: self.shape,
            points: &self.points,
            shift: self.shift,
            fp: self.fp,
        }
    }

    /// Whether the buffered shapes intersect: the distance between the shapes is at
    /// most the sum of the buffers.
    pub fn intersects(&self, other: &Geometry) -> bool {
        within(&other.view(), self, other.buffer + self.buffer)
    }

    /// The index boxes a region query looks up.
    pub(super) fn query_boxes(&self) -> impl Iterator<Item = Box4> {
        self.fp.expand(self.buffer).index_boxes()
    }
}

/// Whether the shape `a` and the region `b` are within `d` metres of each other.
pub(super) fn within(a: &View<'_>, b: &Geometry, d: f64) -> bool {
    let reach = a.fp.expand(d);
    (-1..=1).any(|k| {
        let sh = 360.0 * f64::from(k);
        reach.shifted(sh).overlaps(&b.fp) && within_shifted(a, sh, b, d)
    })
}

fn within_shifted(a: &View<'_>, sh: f64, b: &Geometry, d: f64) -> bool {
    for s in a.segs() {
        let s = s.shifted(sh);
        let e = s.bbox().expand(d);
        if e.overlaps(&b.fp) && b.segs.any_near(&e, |t| seg_within(s, t, d)) {
            return true;
        }
    }
    // No edges within `d`: the shapes meet only if one polygon holds the other.
    if b.shape == Shape::Polygon {
        let p = a.first();
        if inside([p[0], p[1] + sh], b.view().segs()) {
            return true;
        }
    }
    if a.shape == Shape::Polygon {
        let p = b.view().first();
        if inside([p[0], p[1] - sh], a.segs()) {
            return true;
        }
    }
    false
}

/// Which objects a query or deletion selects: every criterion given must hold.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Filter {
    /// Only these objects.
    pub ids: Option<Vec<ObjectId>>,
    /// Only objects whose buffered geometry intersects this buffered region.
    pub region: Option<Geometry>,
    /// Only objects with a feature class matching at least one criterion: its ID equal
    /// (when given) and its attribute equal (when given). An empty list is no criterion.
    pub classes: Option<Vec<VksFeatureClassFilter>>,
}

impl Filter {
    /// Whether the filter has no criterion (it selects every object).
    pub fn is_empty(&self) -> bool {
        self.ids.is_none()
            && self.region.is_none()
            && self.classes.as_ref().is_none_or(|c| c.is_empty())
    }

    /// The filter of a Query VKS Objects.
    pub fn from_query(q: &QueryVksObjects) -> Result<Filter, StoreError> {
        Filter::from_fields(
            &q.object_ids,
            q.region_type,
            q.region_buffer,
            &q.feature_classes,
            &q.region_points,
        )
    }

    /// The filter of a Delete VKS Objects.
    pub fn from_delete(q: &DeleteVksObjects) -> Result<Filter, StoreError> {
        Filter::from_fields(
            &q.object_ids,
            q.region_type,
            q.region_buffer,
            &q.feature_classes,
            &q.region_points,
        )
    }

    fn from_fields(
        ids: &Option<Vec<u32>>,
        region_type: Option<VksObjectType>,
        region_buffer: Option<f32>,
        classes: &Option<Vec<VksFeatureClassFilter>>,
        points: &Option<Vec<VksPoint>>,
    ) -> Result<Filter, StoreError> {
        let region = match (region_type, points) {
            (Some(t), Some(p)) => Some(Geometry::new(
                Shape::from_wire(t)?,
                p.clone(),
                f64::from(region_buffer.unwrap_or(0.0)),
            )?),
            (Some(_), None) => return Err(StoreError::Region("a region type without points")),
            (None, Some(_)) => return Err(StoreError::Region("region points without a type")),
            (None, None) if region_buffer.is_some() => {
                return Err(StoreError::Region("a region buffer without a region"))
            }
            (None, None) => None,
        };
        let classes = match classes {
            Some(c) if c.is_empty() => None,
            Some(c) if c.iter().any(|f| f.id.is_none() && f.attribute.is_none()) => {
                return Err(StoreError::EmptyCriteria)
            }
            other => other.clone(),
        };
        let ids = ids.as_ref().map(|v| {
            let mut v = v.clone();
            v.sort_unstable();
            v.dedup();
            v
        });
        Ok(Filter {
            ids,
            region,
            classes,
        })
    }
}

/// The filter with its ID list sorted (what [`VectorStore::query`] searches).
pub(super) fn sorted_ids(f: &Filter) -> std::borrow::Cow<'_, Filter> {
    match &f.ids {
        Some(ids) if !ids.is_sorted() => {
            let mut f = f.clone();
            if let Some(v) = f.ids.as_mut() {
                v.sort_unstable();
                v.dedup();
            }
            std::borrow::Cow::Owned(f)
        }
        _ => std::borrow::Cow::Borrowed(f),
    }
}

pub(super) fn class_matches(obj: &VksStoredObject, criteria: &[VksFeatureClassFilter]) -> bool {
    criteria.iter().any(|c| {
        obj.feature_classes.iter().any(|f| {
            c.id.is_none_or(|id| id == f.id)
                && c.attribute.as_ref().is_none_or(|a| *a == f.attribute)
        })
    })
}
