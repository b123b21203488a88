//! The World Model Vector Knowledge Store of Part 1 §5.5.3 (component 61): a
//! [`VectorStore`] of points, lines/polylines and polygons in WGS 84 with region
//! buffers, feature classes and feature-class metadata, indexed with an R*-tree, and
//! [`WorldModelCore`], the generated [`WorldModelVectorKnowledgeStore`] trait
//! implemented over it.
//!
//! # Geometry
//!
//! * **Vertices** are WGS 84 latitude/longitude in degrees (latitude in [-90, 90],
//!   longitude in [-180, 180]), as on the wire. A point object has one vertex, a line
//!   at least two, a polygon at least three (the closing edge from the last vertex back
//!   to the first is implied); none has more than 65,535
//!   ([`StoreConfig::max_vertices`]).
//! * **Edges** are straight lines in (latitude, longitude) and go the short way round:
//!   an edge from 179.9° E to 179.9° W crosses the antimeridian and is 0.2° long. A
//!   polygon whose edges encircle a pole, or an object whose longitudes, followed edge
//!   by edge, span 360° or more, is refused ([`StoreError::WrapsAround`]).
//! * **Polygons** are filled by the **even-odd** rule (a point is inside when a ray
//!   from it crosses the boundary an odd number of times), so self-intersecting
//!   polygons are accepted and have holes where their loops overlap.
//! * **Buffers.** The region buffer `r` of an object (metres, Part 1 §5.5.3) turns the
//!   object into its Minkowski sum with a disc of radius `r`: discs around the vertices
//!   joined by their tangents. Two buffered geometries intersect when the distance
//!   between the unbuffered ones is at most `r₁ + r₂`; the distance is 0 when their
//!   edges cross or one polygon contains the other.
//!
//! # Distances: the local approximation and its error
//!
//! Distances are computed edge pair by edge pair in a local **equirectangular** frame
//! (x north, y east, metres). For a pair of edges within a latitude band of each other,
//! each is first clipped to the other's latitude band widened by the distance sought
//! (points outside it cannot be that close); then `x = Δlat · M(φm)` and
//! `y = Δlon · N(φm) · cos φ₀`, where `M`, `N` are the WGS 84 meridian and prime-vertical
//! radii of curvature (as in [`LocalFrame`](super::geo::LocalFrame)) at the mean latitude
//! `φm` of the clipped pair and `φ₀` is the latitude of the clipped pair closest to the
//! equator. The point–segment and segment–segment distances are then exact in that
//! plane. Taking the east–west scale at `φ₀` keeps every distance at least its value
//! under any other latitude of the pair, which is what makes the index search below
//! exact. The relative error of a distance against the ellipsoid is about
//! `tan|φ| · Δφ + 0.01 · Δφ + (d / 6.4e6 m)²`, with `Δφ` the latitude extent of the
//! clipped pair in radians and `d` the distance: below 6·10⁻⁴ (6 cm in 100 m) for
//! objects and buffers under 1 km at latitudes below 60°, growing with the length of
//! north–south edges that run side by side and with latitude (the approximation
//! degrades within a few kilometres of a pole).
//!
//! # Spatial index
//!
//! Objects are indexed in **degrees**: every object puts the bounding box of its
//! vertices, in (latitude, unwrapped longitude), widened by its buffer converted to
//! degrees with the smallest metres-per-degree the frame above can use (the meridian
//! radius at the equator for latitude; the equatorial radius times the cosine of the
//! highest latitude the box reaches for longitude), into an [`rstar`] R*-tree. A box
//! that crosses the antimeridian is entered once more shifted by 360°. A region query
//! widens the region's box by the region buffer the same way, collects the objects whose
//! boxes intersect it (never a scan of every object) and runs the exact test above on
//! each; the widening is conservative for the frame, so the index never drops an object
//! the exact test would keep ([`VectorStore::query_linear`] is the scan used to check
//! that, and the baseline of `benches/world_model.rs`).
//!
//! # Bounds on memory
//!
//! [`StoreConfig`] limits the number of objects, the vertices of one object and of the
//! whole store, the buffer, the feature classes of an object and the metadata text;
//! what exceeds a limit is refused with a [`StoreError`] naming that limit.
//!
//! # Long answers
//!
//! Query VKS Objects is answered by exactly one Report VKS Objects (the interface does
//! not let the component send that report on its own, and no message carries a
//! transfer identifier or a continuation). A report holds at most
//! [`WorldModelConfig::max_report_objects`] objects (at most 65,535: the count is a
//! u16) and about [`WorldModelConfig::max_report_bytes`] bytes of object data, taken in
//! ascending object ID order. When the answer is longer, [`WorldModelCore`] opens a
//! **data transfer** for the requester: sending the *same* query again (same request
//! ID, same filter) returns the next page, until the last page closes the transfer
//! (the next identical query starts over). A different query from the same requester
//! replaces its transfer; Terminate VKS Data Transfer ends the requester's transfer
//! and is answered with Report VKS Data Transfer Termination; a transfer not continued
//! within [`WorldModelConfig::transfer_timeout`] is dropped. A query whose response
//! presence vector leaves bit 0 clear gets only the number of matching objects (capped
//! at 65,535), which tells a requester how many pages to expect. Pages reflect the
//! store when they are built: objects deleted meanwhile are skipped, objects created
//! meanwhile with a higher ID are included.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::time::{Duration, Instant};

use rstar::{RTree, RTreeObject, AABB};

use super::geo::{WGS84_A, WGS84_F};
use crate::codec::Encode;
use crate::component::Refused;
use crate::components::world_model_vector_knowledge_store::{Ctx, WorldModelVectorKnowledgeStore};
use crate::messages::*;
use crate::Address;

/// The identifier the store gives an object (never 0, which Report VKS Objects Creation
/// uses for "not created").
pub type ObjectId = u32;

/// Feature-class ID that Query VKS Bounds uses for "every object" (an SDK convention:
/// the message has no such value of its own).
pub const ALL_FEATURE_CLASSES: u16 = u16::MAX;

/// Most vertices of one object (Part 1 §5.5.3; the u16 count of the wire).
pub const MAX_VERTICES: usize = 65_535;

/// Largest region buffer of a query or deletion region, metres (half a meridian).
pub const MAX_REGION_BUFFER: f64 = 2.0e7;

const DEG: f64 = std::f64::consts::PI / 180.0;
/// First eccentricity squared of WGS 84.
const E2: f64 = WGS84_F * (2.0 - WGS84_F);
/// The smallest meridian radius of curvature (at the equator), metres per radian.
const M_MIN: f64 = WGS84_A * (1.0 - E2);
/// Segment counts above which a region's edges get an R-tree of their own.
const SEGMENT_TREE_MIN: usize = 16;

// ---------------------------------------------------------------------------------
// Configuration and errors

/// Limits of a [`VectorStore`].
#[derive(Debug, Clone, PartialEq)]
pub struct StoreConfig {
    /// Most objects stored at once.
    pub max_objects: usize,
    /// Most vertices of one object (at most [`MAX_VERTICES`]; larger values are taken
    /// as [`MAX_VERTICES`]).
    pub max_vertices: usize,
    /// Most vertices of all objects together.
    pub max_total_vertices: usize,
    /// Largest region buffer of a stored object, metres.
    pub max_buffer: f32,
    /// Most feature classes of one object (the wire allows 255).
    pub max_feature_classes: usize,
    /// Most bytes of feature-class metadata text, all classes together (one class holds
    /// at most 65,535, the u16 length of the wire).
    pub max_metadata_bytes: usize,
}

impl Default for StoreConfig {
    fn default() -> Self {
        Self {
            max_objects: 1 << 20,
            max_vertices: MAX_VERTICES,
            max_total_vertices: 1 << 24,
            max_buffer: 1.0e6,
            max_feature_classes: 255,
            max_metadata_bytes: 1 << 22,
        }
    }
}

/// Why the store refused an object, a region, a filter or a metadata change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StoreError {
    /// The store holds [`StoreConfig::max_objects`] objects.
    #[error("the store is full: it holds the maximum of {max} objects (max_objects)")]
    TooManyObjects {
        /// The limit.
        max: usize,
    },
    /// More vertices than [`StoreConfig::max_vertices`].
    #[error("{count} vertices exceed the maximum of {max} per object (max_vertices)")]
    TooManyVertices {
        /// Vertices given.
        count: usize,
        /// The limit.
        max: usize,
    },
    /// The store would hold more than [`StoreConfig::max_total_vertices`] vertices.
    #[error("{count} more vertices would exceed the store's maximum of {max} vertices (max_total_vertices)")]
    TotalVertices {
        /// Vertices of the object.
        count: usize,
        /// The limit.
        max: usize,
    },
    /// More feature classes than [`StoreConfig::max_feature_classes`].
    #[error(
        "{count} feature classes exceed the maximum of {max} per object (max_feature_classes)"
    )]
    TooManyFeatureClasses {
        /// Feature classes given.
        count: usize,
        /// The limit.
        max: usize,
    },
    /// An object type other than point, line or polygon.
    #[error("unknown object type {0} (0 point, 1 line, 2 polygon)")]
    UnknownType(u8),
    /// Too few (or, for a point, too many) vertices for the shape.
    #[error("a {shape:?} needs {need} vertices, {count} given")]
    VertexCount {
        /// The shape.
        shape: Shape,
        /// Vertices given.
        count: usize,
        /// What the shape needs ("exactly 1", "at least 2", "at least 3").
        need: &'static str,
    },
    /// A latitude or longitude that is NaN or infinite.
    #[error("vertex {index}: {what} is not a finite number")]
    NotFinite {
        /// Index of the vertex.
        index: usize,
        /// "latitude" or "longitude".
        what: &'static str,
    },
    /// A latitude outside [-90, 90].
    #[error("vertex {index}: latitude {value} is outside [-90, 90] degrees")]
    Latitude {
        /// Index of the vertex.
        index: usize,
        /// The latitude.
        value: f64,
    },
    /// A longitude outside [-180, 180].
    #[error("vertex {index}: longitude {value} is outside [-180, 180] degrees")]
    Longitude {
        /// Index of the vertex.
        index: usize,
        /// The longitude.
        value: f64,
    },
    /// A buffer that is NaN, negative or above the limit.
    #[error("region buffer {value} m is not a number in [0, {max}] m (max_buffer)")]
    Buffer {
        /// The buffer.
        value: f64,
        /// The limit.
        max: f64,
    },
    /// Edges that go all the way round the Earth (or a polygon around a pole).
    #[error("the object goes all the way round the Earth in longitude (a polygon around a pole, or a line spanning 360 degrees or more); split it")]
    WrapsAround,
    /// A delete filter with no criterion (it would delete everything).
    #[error("the delete filter has no criterion (object IDs, region or feature classes); it would delete every object")]
    EmptyFilter,
    /// A region given only in part.
    #[error("incomplete region: {0}")]
    Region(&'static str),
    /// Feature-class criteria with neither IDs nor attributes.
    #[error("feature-class criteria carry neither class IDs nor attributes")]
    EmptyCriteria,
    /// A metadata option other than append, prepend, overwrite and erase.
    #[error("unknown metadata option {0} (0 append, 1 prepend, 2 overwrite, 255 erase)")]
    MetadataOption(u8),
    /// Metadata of one class longer than 65,535 bytes.
    #[error("metadata of feature class {class} would be {len} bytes, more than 65535")]
    MetadataTooLong {
        /// The feature class.
        class: u16,
        /// The resulting length.
        len: usize,
    },
    /// Metadata of all classes above [`StoreConfig::max_metadata_bytes`].
    #[error(
        "metadata would total {total} bytes, more than the maximum of {max} (max_metadata_bytes)"
    )]
    MetadataFull {
        /// The resulting total.
        total: usize,
        /// The limit.
        max: usize,
    },
}

// ---------------------------------------------------------------------------------
// Shapes, footprints, geometry views

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

impl Shape {
    /// The shape of a wire object type.
    pub fn from_wire(t: VksObjectType) -> Result<Shape, StoreError> {
        match t {
            VksObjectType::Point => Ok(Shape::Point),
            VksObjectType::Line => Ok(Shape::Line),
            VksObjectType::Polygon => Ok(Shape::Polygon),
            VksObjectType::Unknown(v) => Err(StoreError::UnknownType(v)),
        }
    }

    /// The wire object type of this shape.
    pub fn to_wire(self) -> VksObjectType {
        match self {
            Shape::Point => VksObjectType::Point,
            Shape::Line => VksObjectType::Line,
            Shape::Polygon => VksObjectType::Polygon,
        }
    }

    fn check_count(self, count: usize) -> Result<(), StoreError> {
        let (ok, need) = match self {
            Shape::Point => (count == 1, "exactly 1"),
            Shape::Line => (count >= 2, "at least 2"),
            Shape::Polygon => (count >= 3, "at least 3"),
        };
        if ok {
            Ok(())
        } else {
            Err(StoreError::VertexCount {
                shape: self,
                count,
                need,
            })
        }
    }
}

/// A box in (latitude, unwrapped longitude) degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Box4 {
    lat_lo: f64,
    lat_hi: f64,
    lon_lo: f64,
    lon_hi: f64,
}

impl Box4 {
    fn of(a: [f64; 2], b: [f64; 2]) -> Box4 {
        Box4 {
            lat_lo: a[0].min(b[0]),
            lat_hi: a[0].max(b[0]),
            lon_lo: a[1].min(b[1]),
            lon_hi: a[1].max(b[1]),
        }
    }

    fn shifted(self, lon: f64) -> Box4 {
        Box4 {
            lon_lo: self.lon_lo + lon,
            lon_hi: self.lon_hi + lon,
            ..self
        }
    }

    fn overlaps(&self, o: &Box4) -> bool {
        self.lat_lo <= o.lat_hi
            && o.lat_lo <= self.lat_hi
            && self.lon_lo <= o.lon_hi
            && o.lon_lo <= self.lon_hi
    }

    /// The box widened by `d` metres, conservatively for the distance frame (module
    /// docs): no point of the frame within `d` of the box lies outside.
    fn expand(self, d: f64) -> Box4 {
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
    fn index_boxes(self) -> impl Iterator<Item = Box4> {
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

    fn aabb(&self) -> AABB<[f64; 2]> {
        AABB::from_corners([self.lat_lo, self.lon_lo], [self.lat_hi, self.lon_hi])
    }
}

/// Checks the vertices of a shape and finds its footprint: the box of its vertices in
/// (latitude, unwrapped longitude), with the lowest longitude in [-180, 180), and the
/// longitude shift (a multiple of 360°) of the first vertex.
fn analyse(
    shape: Shape,
    points: &[VksPoint],
    max_vertices: usize,
) -> Result<(Box4, f64), StoreError> {
    if points.len() > max_vertices {
        return Err(StoreError::TooManyVertices {
            count: points.len(),
            max: max_vertices,
        });
    }
    shape.check_count(points.len())?;
    for (index, p) in points.iter().enumerate() {
        if !p.latitude.is_finite() {
            return Err(StoreError::NotFinite {
                index,
                what: "latitude",
            });
        }
        if !p.longitude.is_finite() {
            return Err(StoreError::NotFinite {
                index,
                what: "longitude",
            });
        }
        if !(-90.0..=90.0).contains(&p.latitude) {
            return Err(StoreError::Latitude {
                index,
                value: p.latitude,
            });
        }
        if !(-180.0..=180.0).contains(&p.longitude) {
            return Err(StoreError::Longitude {
                index,
                value: p.longitude,
            });
        }
    }
    let mut b = Box4 {
        lat_lo: f64::INFINITY,
        lat_hi: f64::NEG_INFINITY,
        lon_lo: f64::INFINITY,
        lon_hi: f64::NEG_INFINITY,
    };
    let mut it = Unwrap::new(points, 0.0);
    for v in it.by_ref() {
        b.lat_lo = b.lat_lo.min(v[0]);
        b.lat_hi = b.lat_hi.max(v[0]);
        b.lon_lo = b.lon_lo.min(v[1]);
        b.lon_hi = b.lon_hi.max(v[1]);
    }
    if shape == Shape::Polygon {
        // The closing edge must bring the longitude back to where it started.
        let (first, last) = (points[0].longitude, points[points.len() - 1].longitude);
        if it.offset + wrap_step(first - last) != 0.0 {
            return Err(StoreError::WrapsAround);
        }
    }
    if b.lon_hi - b.lon_lo >= 360.0 {
        return Err(StoreError::WrapsAround);
    }
    let shift = -360.0 * ((b.lon_lo + 180.0) / 360.0).floor();
    Ok((b.shifted(shift), shift))
}

/// The change of the 360° offset an edge with longitude difference `d` needs so that
/// it goes the short way: edges span (-180°, 180°].
fn wrap_step(d: f64) -> f64 {
    if d > 180.0 {
        -360.0
    } else if d <= -180.0 {
        360.0
    } else {
        0.0
    }
}

/// The vertices of an object as (latitude, unwrapped longitude).
#[derive(Debug, Clone)]
struct Unwrap<'a> {
    points: std::slice::Iter<'a, VksPoint>,
    prev: Option<f64>,
    offset: f64,
}

impl<'a> Unwrap<'a> {
    fn new(points: &'a [VksPoint], shift: f64) -> Self {
        Unwrap {
            points: points.iter(),
            prev: None,
            offset: shift,
        }
    }
}

impl Iterator for Unwrap<'_> {
    type Item = [f64; 2];
    fn next(&mut self) -> Option<[f64; 2]> {
        let p = self.points.next()?;
        if let Some(prev) = self.prev {
            self.offset += wrap_step(p.longitude - prev);
        }
        self.prev = Some(p.longitude);
        Some([p.latitude, p.longitude + self.offset])
    }
}

/// An edge: two vertices in (latitude, unwrapped longitude) degrees (equal for a point).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Seg {
    a: [f64; 2],
    b: [f64; 2],
}

impl Seg {
    fn bbox(&self) -> Box4 {
        Box4::of(self.a, self.b)
    }
    fn shifted(self, lon: f64) -> Seg {
        Seg {
            a: [self.a[0], self.a[1] + lon],
            b: [self.b[0], self.b[1] + lon],
        }
    }
}

/// The edges of a shape given by its unwrapped vertices (a point is one zero-length
/// edge; a polygon's closing edge comes last).
fn segments(shape: Shape, verts: Unwrap<'_>) -> impl Iterator<Item = Seg> + '_ {
    let mut verts = verts;
    let first = verts.next();
    let mut prev = first;
    let mut closing = shape == Shape::Polygon;
    let mut point = shape == Shape::Point;
    std::iter::from_fn(move || {
        let f = first?;
        if point {
            point = false;
            return Some(Seg { a: f, b: f });
        }
        if let Some(v) = verts.next() {
            let s = Seg { a: prev?, b: v };
            prev = Some(v);
            return Some(s);
        }
        if closing {
            closing = false;
            return Some(Seg { a: prev?, b: f });
        }
        None
    })
}

/// A shape seen by the geometry code.
#[derive(Debug, Clone, Copy)]
struct View<'a> {
    shape: Shape,
    points: &'a [VksPoint],
    shift: f64,
    fp: Box4,
}

impl<'a> View<'a> {
    fn verts(&self) -> Unwrap<'a> {
        Unwrap::new(self.points, self.shift)
    }
    fn segs(&self) -> impl Iterator<Item = Seg> + 'a {
        segments(self.shape, self.verts())
    }
    fn first(&self) -> [f64; 2] {
        self.verts().next().unwrap_or([0.0, 0.0])
    }
}

// ---------------------------------------------------------------------------------
// Geometry primitives

fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

fn on_segment(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> bool {
    p[0] >= a[0].min(b[0])
        && p[0] <= a[0].max(b[0])
        && p[1] >= a[1].min(b[1])
        && p[1] <= a[1].max(b[1])
}

/// Whether two closed segments share a point (orientation tests, collinear and
/// zero-length segments included).
fn seg_intersect(p1: [f64; 2], p2: [f64; 2], q1: [f64; 2], q2: [f64; 2]) -> bool {
    let d1 = orient(q1, q2, p1);
    let d2 = orient(q1, q2, p2);
    let d3 = orient(p1, p2, q1);
    let d4 = orient(p1, p2, q2);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    (d1 == 0.0 && on_segment(q1, q2, p1))
        || (d2 == 0.0 && on_segment(q1, q2, p2))
        || (d3 == 0.0 && on_segment(p1, p2, q1))
        || (d4 == 0.0 && on_segment(p1, p2, q2))
}

/// Even-odd point in polygon over the polygon's edges.
fn inside(p: [f64; 2], edges: impl Iterator<Item = Seg>) -> bool {
    let mut odd = false;
    for e in edges {
        let (a, b) = (e.a, e.b);
        if (a[0] > p[0]) != (b[0] > p[0]) {
            let lon = a[1] + (p[0] - a[0]) / (b[0] - a[0]) * (b[1] - a[1]);
            if p[1] < lon {
                odd = !odd;
            }
        }
    }
    odd
}

/// Distance in a plane from `p` to the segment `a`–`b`.
fn plane_point_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (x, y) = (a[0] + t * dx - p[0], a[1] + t * dy - p[1]);
    (x * x + y * y).sqrt()
}

/// The part of a segment with latitude in `[lo, hi]`.
fn clip_lat(s: Seg, lo: f64, hi: f64) -> Option<Seg> {
    let (a, b) = (s.a, s.b);
    let dl = b[0] - a[0];
    if dl == 0.0 {
        return (a[0] >= lo && a[0] <= hi).then_some(s);
    }
    let (u1, u2) = ((lo - a[0]) / dl, (hi - a[0]) / dl);
    let (t0, t1) = (u1.min(u2).max(0.0), u1.max(u2).min(1.0));
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| {
        if t <= 0.0 {
            a
        } else if t >= 1.0 {
            b
        } else {
            [a[0] + t * dl, a[1] + t * (b[1] - a[1])]
        }
    };
    Some(Seg {
        a: at(t0),
        b: at(t1),
    })
}

/// Metres per degree of latitude and of longitude of the frame of a clipped pair of
/// edges (module docs).
fn frame_scale(lat_lo: f64, lat_hi: f64) -> (f64, f64) {
    let phi0 = if lat_lo <= 0.0 && lat_hi >= 0.0 {
        0.0
    } else {
        lat_lo.abs().min(lat_hi.abs())
    };
    let s = ((lat_lo + lat_hi) / 2.0 * DEG).sin();
    let w = (1.0 - E2 * s * s).sqrt();
    let m = WGS84_A * (1.0 - E2) / (w * w * w);
    let n = WGS84_A / w;
    (m * DEG, n * (phi0 * DEG).cos() * DEG)
}

/// Distance in metres between two edges in the frame of the pair, or `None` when it
/// is certainly above `d` (no parts within `d` of each other in latitude).
fn seg_distance(s: Seg, t: Seg, d: f64) -> Option<f64> {
    if seg_intersect(s.a, s.b, t.a, t.b) {
        return Some(0.0);
    }
    let dlat = d.max(0.0) / M_MIN / DEG;
    let tb = t.bbox();
    let s2 = clip_lat(s, tb.lat_lo - dlat, tb.lat_hi + dlat)?;
    let sb = s2.bbox();
    let t2 = clip_lat(t, sb.lat_lo - dlat, sb.lat_hi + dlat)?;
    let tb = t2.bbox();
    let (kx, ky) = frame_scale(sb.lat_lo.min(tb.lat_lo), sb.lat_hi.max(tb.lat_hi));
    let o = s2.a;
    let p = |v: [f64; 2]| [(v[0] - o[0]) * kx, (v[1] - o[1]) * ky];
    let (a1, b1, a2, b2) = (p(s2.a), p(s2.b), p(t2.a), p(t2.b));
    Some(
        plane_point_segment(a1, a2, b2)
            .min(plane_point_segment(b1, a2, b2))
            .min(plane_point_segment(a2, a1, b1))
            .min(plane_point_segment(b2, a1, b1)),
    )
}

fn seg_within(s: Seg, t: Seg, d: f64) -> bool {
    seg_distance(s, t, d).is_some_and(|x| x <= d)
}

fn to_pair(p: &VksPoint) -> [f64; 2] {
    [p.latitude, p.longitude]
}

fn unwrap_pair(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [b[0], b[1] + wrap_step(b[1] - a[1])]
}

/// Distance in metres from `p` to the segment `a`–`b` in the local equirectangular
/// frame of the module docs (the segment goes the short way round in longitude).
pub fn point_segment_distance(p: &VksPoint, a: &VksPoint, b: &VksPoint) -> f64 {
    let (a, b, p) = (to_pair(a), to_pair(b), to_pair(p));
    let b = unwrap_pair(a, b);
    let p = [p[0], p[1] + 360.0 * ((a[1] - p[1]) / 360.0).round()];
    seg_distance(Seg { a: p, b: p }, Seg { a, b }, f64::INFINITY).unwrap_or(f64::INFINITY)
}

/// Whether the closed segments `a`–`b` and `c`–`d` share a point (edges straight in
/// latitude/longitude, going the short way round).
pub fn segments_intersect(a: &VksPoint, b: &VksPoint, c: &VksPoint, d: &VksPoint) -> bool {
    let (a, c) = (to_pair(a), to_pair(c));
    let b = unwrap_pair(a, to_pair(b));
    let d = unwrap_pair(c, to_pair(d));
    let shift = 360.0 * ((a[1] - c[1]) / 360.0).round();
    let (c, d) = ([c[0], c[1] + shift], [d[0], d[1] + shift]);
    seg_intersect(a, b, c, d)
}

/// Whether `p` is inside the polygon of `vertices` (even-odd rule; a point on the
/// boundary may fall either way). `false` for fewer than three vertices or vertices
/// the store would refuse.
pub fn point_in_polygon(p: &VksPoint, vertices: &[VksPoint]) -> bool {
    let Ok((fp, shift)) = analyse(Shape::Polygon, vertices, MAX_VERTICES) else {
        return false;
    };
    let v = View {
        shape: Shape::Polygon,
        points: vertices,
        shift,
        fp,
    };
    let q = to_pair(p);
    (-1..=1).any(|k| {
        let q = [q[0], q[1] + 360.0 * f64::from(k)];
        q[1] >= fp.lon_lo && q[1] <= fp.lon_hi && inside(q, v.segs())
    })
}

// ---------------------------------------------------------------------------------
// Prepared geometry (regions)

/// The edges of a region, indexed when there are many.
#[derive(Debug, Clone)]
enum SegIndex {
    Few(Vec<Seg>),
    Tree(RTree<SegEntry>),
}

#[derive(Debug, Clone, PartialEq)]
struct SegEntry(Seg);

impl RTreeObject for SegEntry {
    type Envelope = AABB<[f64; 2]>;
    fn envelope(&self) -> Self::Envelope {
        self.0.bbox().aabb()
    }
}

impl SegIndex {
    /// Whether `f` holds for an edge whose box meets `b`.
    fn any_near(&self, b: &Box4, mut f: impl FnMut(Seg) -> bool) -> bool {
        match self {
            SegIndex::Few(v) => v.iter().any(|s| s.bbox().overlaps(b) && f(*s)),
            SegIndex::Tree(t) => t.locate_in_envelope_intersecting(&b.aabb()).any(|e| f(e.0)),
        }
    }
}

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
    fn query_boxes(&self) -> impl Iterator<Item = Box4> {
        self.fp.expand(self.buffer).index_boxes()
    }
}

/// Whether the shape `a` and the region `b` are within `d` metres of each other.
fn within(a: &View<'_>, b: &Geometry, d: f64) -> bool {
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

// ---------------------------------------------------------------------------------
// Filters

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
fn sorted_ids(f: &Filter) -> std::borrow::Cow<'_, Filter> {
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

fn class_matches(obj: &VksStoredObject, criteria: &[VksFeatureClassFilter]) -> bool {
    criteria.iter().any(|c| {
        obj.feature_classes.iter().any(|f| {
            c.id.is_none_or(|id| id == f.id)
                && c.attribute.as_ref().is_none_or(|a| *a == f.attribute)
        })
    })
}

// ---------------------------------------------------------------------------------
// The store

#[derive(Debug, Clone)]
struct Stored {
    object: VksStoredObject,
    shape: Shape,
    shift: f64,
    fp: Box4,
}

impl Stored {
    fn view(&self) -> View<'_> {
        View {
            shape: self.shape,
            points: &self.object.points,
            shift: self.shift,
            fp: self.fp,
        }
    }

    fn index_boxes(&self) -> impl Iterator<Item = Box4> {
        self.fp.expand(f64::from(self.object.buffer)).index_boxes()
    }
}

#[derive(Debug, Clone, PartialEq)]
struct Entry {
    /// Index of the object in `VectorStore::slots`.
    slot: u32,
    env: AABB<[f64; 2]>,
}

impl RTreeObject for Entry {
    type Envelope = AABB<[f64; 2]>;
    fn envelope(&self) -> Self::Envelope {
        self.env
    }
}

/// The bounding box of stored objects' vertices, degrees. `west > east` when the box
/// crosses the antimeridian.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Southernmost latitude.
    pub south: f64,
    /// Western edge longitude.
    pub west: f64,
    /// Northernmost latitude.
    pub north: f64,
    /// Eastern edge longitude.
    pub east: f64,
}

/// Vector objects in WGS 84 with feature classes, a spatial index and feature-class
/// metadata. No I/O; every operation is bounded by its [`StoreConfig`].
#[derive(Debug)]
pub struct VectorStore {
    config: StoreConfig,
    /// Object ID → slot (ordered, for listings by ID).
    objects: BTreeMap<ObjectId, u32>,
    /// The objects; the index entries point here, so a region query reads no map.
    slots: Vec<Option<Stored>>,
    /// Empty slots.
    free: Vec<u32>,
    tree: RTree<Entry>,
    classes: HashMap<u16, BTreeSet<ObjectId>>,
    metadata: BTreeMap<u16, String>,
    metadata_bytes: usize,
    total_vertices: usize,
    next_id: ObjectId,
}

impl Default for VectorStore {
    fn default() -> Self {
        Self::new(StoreConfig::default())
    }
}

impl VectorStore {
    /// An empty store with these limits.
    pub fn new(mut config: StoreConfig) -> Self {
        config.max_vertices = config.max_vertices.min(MAX_VERTICES);
        Self {
            config,
            objects: BTreeMap::new(),
            slots: Vec::new(),
            free: Vec::new(),
            tree: RTree::new(),
            classes: HashMap::new(),
            metadata: BTreeMap::new(),
            metadata_bytes: 0,
            total_vertices: 0,
            next_id: 1,
        }
    }

    /// The limits.
    pub fn config(&self) -> &StoreConfig {
        &self.config
    }

    /// Number of objects.
    pub fn len(&self) -> usize {
        self.objects.len()
    }

    /// Whether the store holds no object.
    pub fn is_empty(&self) -> bool {
        self.objects.is_empty()
    }

    /// Vertices of all objects.
    pub fn total_vertices(&self) -> usize {
        self.total_vertices
    }

    /// The object with this ID.
    pub fn get(&self, id: ObjectId) -> Option<&VksStoredObject> {
        self.stored(id).map(|s| &s.object)
    }

    fn stored(&self, id: ObjectId) -> Option<&Stored> {
        self.objects.get(&id).and_then(|&slot| self.slot(slot))
    }

    fn slot(&self, slot: u32) -> Option<&Stored> {
        self.slots.get(slot as usize).and_then(Option::as_ref)
    }

    /// The IDs of all objects, ascending.
    pub fn ids(&self) -> impl Iterator<Item = ObjectId> + '_ {
        self.objects.keys().copied()
    }

    /// Stores an object (its buffer is 0 when `None`) and returns the ID it gets: never
    /// 0, never that of another stored object.
    pub fn create(&mut self, object: &VksObject) -> Result<ObjectId, StoreError> {
        let c = &self.config;
        if self.objects.len() >= c.max_objects {
            return Err(StoreError::TooManyObjects { max: c.max_objects });
        }
        let shape = Shape::from_wire(object.object_type)?;
        let n = object.points.len();
        if n > c.max_vertices {
            return Err(StoreError::TooManyVertices {
                count: n,
                max: c.max_vertices,
            });
        }
        if self.total_vertices + n > c.max_total_vertices {
            return Err(StoreError::TotalVertices {
                count: n,
                max: c.max_total_vertices,
            });
        }
        if object.feature_classes.len() > c.max_feature_classes {
            return Err(StoreError::TooManyFeatureClasses {
                count: object.feature_classes.len(),
                max: c.max_feature_classes,
            });
        }
        let buffer = object.buffer.unwrap_or(0.0);
        if !(0.0..=c.max_buffer).contains(&buffer) {
            return Err(StoreError::Buffer {
                value: f64::from(buffer),
                max: f64::from(c.max_buffer),
            });
        }
        let (fp, shift) = analyse(shape, &object.points, c.max_vertices)?;
        let id = self.free_id();
        let stored = Stored {
            object: VksStoredObject {
                object_id: id,
                object_type: shape.to_wire(),
                buffer,
                feature_classes: object.feature_classes.clone(),
                points: object.points.clone(),
            },
            shape,
            shift,
            fp,
        };
        // Slots never outnumber `max_objects` (< 2³²), so a slot fits in a u32.
        let slot = match self.free.pop() {
            Some(slot) => slot,
            None => {
                self.slots.push(None);
                (self.slots.len() - 1) as u32
            }
        };
        for b in stored.index_boxes() {
            self.tree.insert(Entry {
                slot,
                env: b.aabb(),
            });
        }
        for f in &object.feature_classes {
            self.classes.entry(f.id).or_default().insert(id);
        }
        self.total_vertices += n;
        self.objects.insert(id, slot);
        self.slots[slot as usize] = Some(stored);
        Ok(id)
    }

    fn free_id(&mut self) -> ObjectId {
        // At most `max_objects` (< 2³² − 1) IDs are taken, so this ends.
        loop {
            let id = self.next_id;
            self.next_id = if id == u32::MAX { 1 } else { id + 1 };
            if !self.objects.contains_key(&id) {
                return id;
            }
        }
    }

    /// Stores every object; the result of each, in order.
    pub fn create_all(&mut self, objects: &[VksObject]) -> Vec<Result<ObjectId, StoreError>> {
        objects.iter().map(|o| self.create(o)).collect()
    }

    /// Deletes the objects with these IDs (unknown IDs are ignored); returns how many
    /// were deleted.
    pub fn delete(&mut self, ids: &[ObjectId]) -> usize {
        ids.iter().filter(|id| self.remove(**id)).count()
    }

    fn remove(&mut self, id: ObjectId) -> bool {
        let Some(slot) = self.objects.remove(&id) else {
            return false;
        };
        let Some(s) = self.slots.get_mut(slot as usize).and_then(Option::take) else {
            return false;
        };
        self.free.push(slot);
        for b in s.index_boxes() {
            self.tree.remove(&Entry {
                slot,
                env: b.aabb(),
            });
        }
        for f in &s.object.feature_classes {
            if let Some(set) = self.classes.get_mut(&f.id) {
                set.remove(&id);
                if set.is_empty() {
                    self.classes.remove(&f.id);
                }
            }
        }
        self.total_vertices -= s.object.points.len();
        true
    }

    /// Deletes the objects a filter selects; refused for a filter with no criterion.
    /// Returns the IDs deleted.
    pub fn delete_matching(&mut self, filter: &Filter) -> Result<Vec<ObjectId>, StoreError> {
        if filter.is_empty() {
            return Err(StoreError::EmptyFilter);
        }
        let ids = self.query(filter);
        self.delete(&ids);
        Ok(ids)
    }

    /// Deletes every object (metadata stays).
    pub fn clear(&mut self) {
        self.objects.clear();
        self.slots.clear();
        self.free.clear();
        self.tree = RTree::new();
        self.classes.clear();
        self.total_vertices = 0;
    }

    /// The IDs of the objects a filter selects, ascending. A region is looked up in the
    /// spatial index; feature-class IDs in the class index; only a filter with neither
    /// reads every object.
    pub fn query(&self, filter: &Filter) -> Vec<ObjectId> {
        let filter = &*sorted_ids(filter);
        let keep = |s: &&Stored| self.matches(s, filter);
        if let Some(ids) = &filter.ids {
            // Sorted already.
            return ids
                .iter()
                .filter_map(|id| self.stored(*id))
                .filter(keep)
                .map(|s| s.object.object_id)
                .collect();
        }
        let mut ids: Vec<ObjectId> = if let Some(r) = &filter.region {
            let mut slots = Vec::new();
            for b in r.query_boxes() {
                slots.extend(
                    self.tree
                        .locate_in_envelope_intersecting(&b.aabb())
                        .map(|e| e.slot),
                );
            }
            // An object crossing the antimeridian has two entries.
            slots.sort_unstable();
            slots.dedup();
            slots
                .into_iter()
                .filter_map(|slot| self.slot(slot))
                .filter(keep)
                .map(|s| s.object.object_id)
                .collect()
        } else if let Some(c) = filter
            .classes
            .as_ref()
            .filter(|c| c.iter().all(|f| f.id.is_some()))
        {
            let mut v: Vec<ObjectId> = c
                .iter()
                .filter_map(|f| f.id.and_then(|id| self.classes.get(&id)))
                .flatten()
                .copied()
                .collect();
            v.sort_unstable();
            v.dedup();
            return v
                .into_iter()
                .filter_map(|id| self.stored(id))
                .filter(keep)
                .map(|s| s.object.object_id)
                .collect();
        } else {
            return self.query_linear(filter);
        };
        ids.sort_unstable();
        ids
    }

    /// The same as [`query`](Self::query) by reading every object (no index): the
    /// reference the index is checked and measured against.
    pub fn query_linear(&self, filter: &Filter) -> Vec<ObjectId> {
        let filter = &*sorted_ids(filter);
        let mut ids: Vec<ObjectId> = self
            .slots
            .iter()
            .flatten()
            .filter(|s| self.matches(s, filter))
            .map(|s| s.object.object_id)
            .collect();
        ids.sort_unstable();
        ids
    }

    fn matches(&self, s: &Stored, f: &Filter) -> bool {
        if let Some(ids) = &f.ids {
            if ids.binary_search(&s.object.object_id).is_err() {
                return false;
            }
        }
        if let Some(c) = &f.classes {
            if !class_matches(&s.object, c) {
                return false;
            }
        }
        if let Some(r) = &f.region {
            if !within(&s.view(), r, f64::from(s.object.buffer) + r.buffer) {
                return false;
            }
        }
        true
    }

    /// The bounding box of the vertices of every object (`class: None`) or of the
    /// objects in a feature class; `None` when there is none. Reads the objects
    /// selected (the whole store for `None`).
    pub fn bounds(&self, class: Option<u16>) -> Option<Bounds> {
        let fps: Vec<Box4> = match class {
            None => self.slots.iter().flatten().map(|s| s.fp).collect(),
            Some(c) => self
                .classes
                .get(&c)?
                .iter()
                .filter_map(|id| self.stored(*id).map(|s| s.fp))
                .collect(),
        };
        let south = fps.iter().map(|b| b.lat_lo).fold(f64::INFINITY, f64::min);
        let north = fps
            .iter()
            .map(|b| b.lat_hi)
            .fold(f64::NEG_INFINITY, f64::max);
        if fps.is_empty() {
            return None;
        }
        // Longitude: the shortest arc covering every object, i.e. the complement of the
        // largest gap between the merged longitude intervals on the circle. When the
        // objects span at most 180° without crossing ±180°, the gap round the back is
        // the largest: no sorting needed.
        let west = fps.iter().map(|b| b.lon_lo).fold(f64::INFINITY, f64::min);
        let east = fps
            .iter()
            .map(|b| b.lon_hi)
            .fold(f64::NEG_INFINITY, f64::max);
        if east <= 180.0 && east - west <= 180.0 {
            return Some(Bounds {
                south,
                west,
                north,
                east,
            });
        }
        let mut pieces: Vec<(f64, f64)> = Vec::with_capacity(fps.len() + 1);
        for b in &fps {
            pieces.push((b.lon_lo, b.lon_hi.min(180.0)));
            if b.lon_hi > 180.0 {
                pieces.push((-180.0, b.lon_hi - 360.0));
            }
        }
        pieces.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut merged: Vec<(f64, f64)> = Vec::new();
        for (lo, hi) in pieces {
            match merged.last_mut() {
                Some(last) if lo <= last.1 => last.1 = last.1.max(hi),
                _ => merged.push((lo, hi)),
            }
        }
        let (first, last) = (merged[0], merged[merged.len() - 1]);
        let mut best = (first.0 + 360.0 - last.1, first.0, last.1);
        for w in merged.windows(2) {
            let gap = w[1].0 - w[0].1;
            if gap > best.0 {
                best = (gap, w[1].0, w[0].1);
            }
        }
        let (west, east) = if best.0 <= 0.0 {
            (-180.0, 180.0)
        } else {
            (best.1, best.2)
        };
        Some(Bounds {
            south,
            west,
            north,
            east,
        })
    }

    /// Changes the metadata text of a feature class.
    pub fn set_metadata(
        &mut self,
        class: u16,
        option: VksMetadataOption,
        text: &str,
    ) -> Result<(), StoreError> {
        let old = self.metadata.get(&class).map_or("", String::as_str);
        let new = match option {
            VksMetadataOption::Append => format!("{old}{text}"),
            VksMetadataOption::Prepend => format!("{text}{old}"),
            VksMetadataOption::Overwrite => text.to_string(),
            VksMetadataOption::Erase => String::new(),
            VksMetadataOption::Unknown(v) => return Err(StoreError::MetadataOption(v)),
        };
        if new.len() > usize::from(u16::MAX) {
            return Err(StoreError::MetadataTooLong {
                class,
                len: new.len(),
            });
        }
        let total = self.metadata_bytes - old.len() + new.len();
        if total > self.config.max_metadata_bytes {
            return Err(StoreError::MetadataFull {
                total,
                max: self.config.max_metadata_bytes,
            });
        }
        self.metadata_bytes = total;
        if new.is_empty() {
            self.metadata.remove(&class);
        } else {
            self.metadata.insert(class, new);
        }
        Ok(())
    }

    /// The metadata text of a feature class (empty when none was set).
    pub fn metadata(&self, class: u16) -> &str {
        self.metadata.get(&class).map_or("", String::as_str)
    }
}

// ---------------------------------------------------------------------------------
// The component

/// Settings of [`WorldModelCore`].
#[derive(Debug, Clone, PartialEq)]
pub struct WorldModelConfig {
    /// Limits of the store.
    pub store: StoreConfig,
    /// Most objects in one Report VKS Objects (at most 65,535).
    pub max_report_objects: usize,
    /// Most bytes of object data in one Report VKS Objects (a single object larger than
    /// this is still sent, alone).
    pub max_report_bytes: usize,
    /// Most data transfers open at once (the least recently used is dropped beyond).
    pub max_transfers: usize,
    /// A data transfer not continued for this long is dropped.
    pub transfer_timeout: Duration,
}

impl Default for WorldModelConfig {
    fn default() -> Self {
        Self {
            store: StoreConfig::default(),
            max_report_objects: 65_535,
            max_report_bytes: 1 << 20,
            max_transfers: 32,
            transfer_timeout: Duration::from_secs(30),
        }
    }
}

/// A long answer being paged out to a requester (module docs, "Long answers").
#[derive(Debug, Clone)]
struct Transfer {
    requester: Address,
    query: QueryVksObjects,
    /// Highest object ID sent so far.
    cursor: ObjectId,
    last: Instant,
}

/// The World Model Vector Knowledge Store: the generated trait over a [`VectorStore`].
///
/// * Create VKS Objects stores each object; Report VKS Objects Creation (when bit 0 of
///   the message properties asks for it) gives each object's ID, 0 for one refused. A
///   message with a refused object is counted as invalid although its valid objects
///   are stored.
/// * Delete VKS Objects deletes what its filter selects; a filter with no criterion is
///   refused.
/// * Query VKS Objects answers with the matching objects (module docs for long
///   answers); Query VKS Bounds with the box of a feature class's objects
///   ([`ALL_FEATURE_CLASSES`] for all), south-west (90, 180) and north-east (-90, -180)
///   when there is none; Query VKS Feature Class Metadata with the text (empty when
///   none).
/// * Terminate VKS Data Transfer ends the sender's transfer and is always answered with
///   Report VKS Data Transfer Termination.
#[derive(Debug)]
pub struct WorldModelCore {
    store: VectorStore,
    config: WorldModelConfig,
    transfers: Vec<Transfer>,
}

impl Default for WorldModelCore {
    fn default() -> Self {
        Self::new(WorldModelConfig::default())
    }
}

fn invalid(e: StoreError) -> Refused {
    Refused::Invalid(e.to_string())
}

impl WorldModelCore {
    /// An empty store.
    pub fn new(mut config: WorldModelConfig) -> Self {
        config.max_report_objects = config.max_report_objects.clamp(1, 65_535);
        Self {
            store: VectorStore::new(config.store.clone()),
            config,
            transfers: Vec::new(),
        }
    }

    /// The store.
    pub fn store(&self) -> &VectorStore {
        &self.store
    }

    /// The store, to fill or change it locally.
    pub fn store_mut(&mut self) -> &mut VectorStore {
        &mut self.store
    }

    /// Number of data transfers open.
    pub fn open_transfers(&self) -> usize {
        self.transfers.len()
    }

    fn page(
        &mut self,
        requester: Address,
        now: Instant,
        q: &QueryVksObjects,
        ids: &[ObjectId],
    ) -> Vec<VksStoredObject> {
        let pos = self.transfers.iter().position(|t| t.requester == requester);
        let mut cursor = 0;
        if let Some(i) = pos {
            if self.transfers[i].query == *q {
                cursor = self.transfers[i].cursor;
            } else {
                self.transfers.remove(i);
            }
        }
        let start = ids.partition_point(|&id| id <= cursor);
        let mut page = Vec::new();
        let mut bytes = 0usize;
        for id in &ids[start..] {
            let Some(o) = self.store.get(*id) else {
                continue;
            };
            let len = o.encoded_len();
            if page.len() >= self.config.max_report_objects
                || (!page.is_empty() && bytes + len > self.config.max_report_bytes)
            {
                break;
            }
            bytes += len;
            page.push(o.clone());
        }
        let done = start + page.len() >= ids.len();
        let at = self.transfers.iter().position(|t| t.requester == requester);
        match (done, at) {
            (true, Some(i)) => {
                self.transfers.remove(i);
            }
            (true, None) => {}
            (false, _) => {
                let cursor = page.last().map_or(cursor, |o| o.object_id);
                if let Some(i) = at {
                    self.transfers.remove(i);
                }
                if self.transfers.len() >= self.config.max_transfers.max(1) {
                    // The least recently used transfer goes.
                    if let Some(i) =
                        (0..self.transfers.len()).min_by_key(|&i| self.transfers[i].last)
                    {
                        self.transfers.remove(i);
                    }
                }
                self.transfers.push(Transfer {
                    requester,
                    query: q.clone(),
                    cursor,
                    last: now,
                });
            }
        }
        page
    }
}

impl WorldModelVectorKnowledgeStore for WorldModelCore {
    fn on_create_vks_objects(
        &mut self,
        ctx: &mut Ctx<'_>,
        msg: &CreateVksObjects,
    ) -> Result<(), Refused> {
        let mut ids = Vec::with_capacity(msg.objects.len());
        let mut refused = 0usize;
        let mut first_error = None;
        for (i, o) in msg.objects.iter().enumerate() {
            let r = if msg.buffered {
                self.store.create(o)
            } else {
                self.store.create(&VksObject {
                    buffer: None,
                    ..o.clone()
                })
            };
            match r {
                Ok(id) => ids.push(id),
                Err(e) => {
                    ids.push(0);
                    refused += 1;
                    first_error.get_or_insert((i, e));
                }
            }
        }
        if msg.message_properties & 1 != 0 {
            if let Some(src) = ctx.source() {
                ctx.send(
                    src,
                    ReportVksObjectsCreation {
                        request_id: msg.request_id,
                        object_ids: ids,
                    },
                );
            }
        }
        match first_error {
            None => Ok(()),
            Some((i, e)) => Err(Refused::Invalid(format!(
                "{refused} of {} objects refused; object {i}: {e}",
                msg.objects.len()
            ))),
        }
    }

    fn on_set_vks_feature_class_metadata(
        &mut self,
        _ctx: &mut Ctx<'_>,
        msg: &SetVksFeatureClassMetadata,
    ) -> Result<(), Refused> {
        self.store
            .set_metadata(msg.feature_class_id, msg.metadata_option, &msg.metadata)
            .map_err(invalid)
    }

    fn on_delete_vks_objects(
        &mut self,
        _ctx: &mut Ctx<'_>,
        msg: &DeleteVksObjects,
    ) -> Result<(), Refused> {
        let filter = Filter::from_delete(msg).map_err(invalid)?;
        self.store.delete_matching(&filter).map_err(invalid)?;
        Ok(())
    }

    fn on_terminate_vks_data_transfer(
        &mut self,
        ctx: &mut Ctx<'_>,
        _msg: &TerminateVksDataTransfer,
    ) -> Result<(), Refused> {
        if let Some(src) = ctx.source() {
            self.transfers.retain(|t| t.requester != src);
            ctx.send(src, ReportVksDataTransferTermination {});
        }
        Ok(())
    }

    fn on_query_vks_objects(
        &mut self,
        ctx: &mut Ctx<'_>,
        q: &QueryVksObjects,
    ) -> Result<ReportVksObjects, Refused> {
        let filter = Filter::from_query(q).map_err(invalid)?;
        let ids = self.store.query(&filter);
        if q.response_presence_vector & 1 == 0 {
            return Ok(ReportVksObjects {
                request_id: q.request_id,
                object_count: u16::try_from(ids.len()).unwrap_or(u16::MAX),
                objects: None,
            });
        }
        let requester = ctx.source().unwrap_or_default();
        let page = self.page(requester, ctx.now(), q, &ids);
        Ok(ReportVksObjects {
            request_id: q.request_id,
            // The page never exceeds `max_report_objects` <= 65,535.
            object_count: u16::try_from(page.len()).unwrap_or(u16::MAX),
            objects: Some(page),
        })
    }

    fn on_query_vks_feature_class_metadata(
        &mut self,
        _ctx: &mut Ctx<'_>,
        msg: &QueryVksFeatureClassMetadata,
    ) -> Result<ReportVksFeatureClassMetadata, Refused> {
        Ok(ReportVksFeatureClassMetadata {
            feature_class_id: msg.feature_class_id,
            metadata: self.store.metadata(msg.feature_class_id).to_string(),
        })
    }

    fn on_query_vks_bounds(
        &mut self,
        _ctx: &mut Ctx<'_>,
        msg: &QueryVksBounds,
    ) -> Result<ReportVksBounds, Refused> {
        let class = (msg.feature_class_id != ALL_FEATURE_CLASSES).then_some(msg.feature_class_id);
        let b = self.store.bounds(class).unwrap_or(Bounds {
            south: 90.0,
            west: 180.0,
            north: -90.0,
            east: -180.0,
        });
        Ok(ReportVksBounds {
            request_id: msg.request_id,
            feature_class: msg.feature_class_id,
            south_west_latitude: b.south,
            south_west_longitude: b.west,
            north_east_latitude: b.north,
            north_east_longitude: b.east,
        })
    }

    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        let now = ctx.now();
        let timeout = self.config.transfer_timeout;
        self.transfers
            .retain(|t| now.saturating_duration_since(t.last) < timeout);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(latitude: f64, longitude: f64) -> VksPoint {
        VksPoint {
            latitude,
            longitude,
        }
    }

    fn point(lat: f64, lon: f64) -> VksObject {
        VksObject {
            object_type: VksObjectType::Point,
            buffer: None,
            feature_classes: vec![],
            points: vec![p(lat, lon)],
        }
    }

    #[test]
    fn ids_wrap_round_and_skip_those_in_use() {
        let mut s = VectorStore::default();
        assert_eq!(s.create(&point(0.0, 0.0)), Ok(1));
        s.next_id = u32::MAX;
        assert_eq!(s.create(&point(0.0, 0.0)), Ok(u32::MAX));
        // 0 is never given; 1 is in use.
        assert_eq!(s.create(&point(0.0, 0.0)), Ok(2));
        assert_eq!(s.delete(&[1]), 1);
        s.next_id = u32::MAX;
        assert_eq!(s.create(&point(0.0, 0.0)), Ok(1));
        // Slots are reused: three objects, three slots.
        assert_eq!(s.slots.len(), 3);
        assert!(s.free.is_empty());
    }

    /// Vincenty's inverse formula on the WGS 84 ellipsoid (an independent reference).
    fn vincenty(a: [f64; 2], b: [f64; 2]) -> f64 {
        let (f, big_a) = (WGS84_F, WGS84_A);
        let small_b = big_a * (1.0 - f);
        let l = (b[1] - a[1]) * DEG;
        let u1 = ((1.0 - f) * (a[0] * DEG).tan()).atan();
        let u2 = ((1.0 - f) * (b[0] * DEG).tan()).atan();
        let (su1, cu1, su2, cu2) = (u1.sin(), u1.cos(), u2.sin(), u2.cos());
        let mut lambda = l;
        let mut iterations = 0;
        let (mut ss, mut cs, mut sigma, mut ca2, mut c2sm);
        loop {
            let (sl, cl) = (lambda.sin(), lambda.cos());
            ss = ((cu2 * sl).powi(2) + (cu1 * su2 - su1 * cu2 * cl).powi(2)).sqrt();
            cs = su1 * su2 + cu1 * cu2 * cl;
            sigma = ss.atan2(cs);
            let sa = cu1 * cu2 * sl / ss;
            ca2 = 1.0 - sa * sa;
            // On the equator cos²α = 0 and the term vanishes.
            c2sm = if ca2 > 0.0 {
                cs - 2.0 * su1 * su2 / ca2
            } else {
                0.0
            };
            let c = f / 16.0 * ca2 * (4.0 + f * (4.0 - 3.0 * ca2));
            let next = l
                + (1.0 - c)
                    * f
                    * sa
                    * (sigma + c * ss * (c2sm + c * cs * (-1.0 + 2.0 * c2sm * c2sm)));
            iterations += 1;
            if (next - lambda).abs() < 1e-13 || iterations > 200 {
                break;
            }
            lambda = next;
        }
        let u2b = ca2 * (big_a * big_a - small_b * small_b) / (small_b * small_b);
        let aa = 1.0 + u2b / 16384.0 * (4096.0 + u2b * (-768.0 + u2b * (320.0 - 175.0 * u2b)));
        let bb = u2b / 1024.0 * (256.0 + u2b * (-128.0 + u2b * (74.0 - 47.0 * u2b)));
        let ds = bb
            * ss
            * (c2sm
                + bb / 4.0
                    * (cs * (-1.0 + 2.0 * c2sm * c2sm)
                        - bb / 6.0 * c2sm * (-3.0 + 4.0 * ss * ss) * (-3.0 + 4.0 * c2sm * c2sm)));
        small_b * aa * (sigma - ds)
    }

    #[test]
    fn distance_error_is_within_the_documented_bound() {
        // Point pairs up to 1 km apart in every direction, latitudes 0° to 60°: the
        // relative error against Vincenty stays below tan|φ|·Δφ + 0.01·Δφ + (d/R)²
        // (module docs) and below 6e-4.
        for lat in [0.0, 15.0, 30.0, 45.0, 60.0] {
            for i in 0..16 {
                let a = f64::from(i) / 16.0 * std::f64::consts::TAU;
                for d in [10.0, 100.0, 1_000.0] {
                    let (dlat, dlon) = (
                        d * a.sin() / 111_000.0,
                        d * a.cos() / (111_000.0 * (lat * DEG).cos()),
                    );
                    let (x, y) = (p(lat, 10.0), p(lat + dlat, 10.0 + dlon));
                    let ours = point_segment_distance(&y, &x, &x);
                    let truth = vincenty([lat, 10.0], [lat + dlat, 10.0 + dlon]);
                    let rel = (ours - truth).abs() / truth;
                    let span = dlat.abs() * DEG;
                    let bound = (lat * DEG).tan().abs() * span
                        + 0.01 * span
                        + (truth / 6.4e6).powi(2)
                        + 1e-7;
                    assert!(
                        rel <= bound && rel < 6e-4,
                        "lat {lat} dir {i} d {d}: {ours} vs {truth} ({rel:e} > {bound:e})"
                    );
                }
            }
        }
    }

    #[test]
    fn widened_boxes_hold_every_point_in_reach() {
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
