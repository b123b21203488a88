//! The World Model Vector Knowledge Store (Part 1 §5.5.3): every operation of the
//! `VectorStore`, buffer-zone queries checked against distances computed by hand, the
//! largest polygon the wire allows, the index checked against a linear scan, and the
//! `StockWorldModel` component answering encoded messages on a `LocalBus`.
//!
//! Hand arithmetic uses the WGS 84 radii of the store's local frame (module docs of
//! `jaus::stock::world_model`): a = 6,378,137 m, e² = f(2 − f) = 0.006694380,
//! meridian radius M(φ) = a(1 − e²)/w³, prime-vertical radius N(φ) = a/w,
//! w = √(1 − e² sin²φ).
//!   At the equator: M = 6,335,439.327 m → 110,574.276 m per degree of latitude,
//!   so 0.001° of latitude = 110.574 m and 0.0005° = 55.287 m;
//!   N = a → 111,319.491 m per degree of longitude, 0.001° = 111.319 m.
//!   At 45°: w = 0.998325, N = 6,388,838.29 m, M = 6,367,381.82 m, so 0.001° of
//!   longitude = N cos 45° · 0.001 · π/180 = 78.847 m and 0.001° of latitude = 111.132 m.

use std::sync::OnceLock;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::local::{LocalBus, Probe};
use jaus::component::{Component, Config};
use jaus::components::world_model_vector_knowledge_store::{self as wmvks, Dispatch};
use jaus::messages::*;
use jaus::stock::world_model::{
    point_in_polygon, point_segment_distance, segments_intersect, Bounds, Filter, Geometry, Shape,
    StockWorldModel, StoreConfig, StoreError, VectorStore, WorldModelConfig, ALL_FEATURE_CLASSES,
    MAX_VERTICES,
};
use jaus::{Address, Header, JausMessage};

fn p(latitude: f64, longitude: f64) -> VksPoint {
    VksPoint {
        latitude,
        longitude,
    }
}

fn fc(id: u16, attribute: VksAttribute) -> VksFeatureClass {
    VksFeatureClass { id, attribute }
}

fn obj(
    t: VksObjectType,
    buffer: f32,
    classes: Vec<VksFeatureClass>,
    points: Vec<VksPoint>,
) -> VksObject {
    VksObject {
        object_type: t,
        buffer: Some(buffer),
        feature_classes: classes,
        points,
    }
}

/// The objects of a Create VKS Objects whose `buffered` flag is clear (no buffer field).
fn unbuffered(objects: Vec<VksObject>) -> Vec<VksObject> {
    objects
        .into_iter()
        .map(|o| VksObject { buffer: None, ..o })
        .collect()
}

fn point(lat: f64, lon: f64) -> VksObject {
    obj(VksObjectType::Point, 0.0, vec![], vec![p(lat, lon)])
}

fn region(shape: Shape, points: Vec<VksPoint>, buffer: f64) -> Filter {
    Filter {
        region: Some(Geometry::new(shape, points, buffer).unwrap()),
        ..Filter::default()
    }
}

/// A square polygon of side 2·`h` degrees centred on (`lat`, `lon`).
fn square(lat: f64, lon: f64, h: f64) -> Vec<VksPoint> {
    vec![
        p(lat - h, lon - h),
        p(lat - h, lon + h),
        p(lat + h, lon + h),
        p(lat + h, lon - h),
    ]
}

// ---------------------------------------------------------------------------------
// Store operations

#[test]
fn create_assigns_unique_ids_and_keeps_the_objects() {
    let mut s = VectorStore::default();
    let a = s.create(&point(29.6, -82.3)).unwrap();
    let line = obj(
        VksObjectType::Line,
        2.5,
        vec![fc(7, VksAttribute::Byte(1))],
        vec![p(29.6, -82.3), p(29.61, -82.31), p(29.62, -82.3)],
    );
    let b = s.create(&line).unwrap();
    let c = s
        .create(&obj(
            VksObjectType::Polygon,
            0.0,
            vec![],
            square(29.6, -82.3, 0.01),
        ))
        .unwrap();
    assert!(a != 0 && b != 0 && c != 0);
    assert!(a != b && b != c && a != c);
    assert_eq!(s.len(), 3);
    assert_eq!(s.total_vertices(), 1 + 3 + 4);
    let got = s.get(b).unwrap();
    assert_eq!(got.object_id, b);
    assert_eq!(got.object_type, VksObjectType::Line);
    assert_eq!(got.buffer, 2.5);
    assert_eq!(got.points, line.points);
    assert_eq!(got.feature_classes, line.feature_classes);
    assert_eq!(s.ids().collect::<Vec<_>>(), vec![a, b, c]);
    // Results of a batch, in order.
    let r = s.create_all(&[point(0.0, 0.0), point(f64::NAN, 0.0)]);
    assert!(r[0].is_ok());
    assert!(matches!(
        r[1],
        Err(StoreError::NotFinite {
            index: 0,
            what: "latitude"
        })
    ));
}

#[test]
fn ids_are_not_reused_while_the_object_exists() {
    let mut s = VectorStore::default();
    let ids: Vec<u32> = (0..10)
        .map(|i| s.create(&point(1.0, f64::from(i))).unwrap())
        .collect();
    assert_eq!(s.delete(&[ids[3], ids[4], 999]), 2);
    let more: Vec<u32> = (0..10)
        .map(|i| s.create(&point(2.0, f64::from(i))).unwrap())
        .collect();
    let mut all: Vec<u32> = s.ids().collect();
    let n = all.len();
    all.dedup();
    assert_eq!(all.len(), n, "duplicate IDs");
    for id in &more {
        assert!(!ids[..3].contains(id) && !ids[5..].contains(id));
    }
    assert_eq!(s.len(), 18);
}

#[test]
fn invalid_objects_are_refused_with_the_reason() {
    let mut s = VectorStore::new(StoreConfig {
        max_objects: 3,
        max_total_vertices: 70_000,
        max_feature_classes: 2,
        max_buffer: 100.0,
        ..StoreConfig::default()
    });
    let e = |s: &mut VectorStore, o: VksObject| s.create(&o).unwrap_err();
    assert_eq!(
        e(&mut s, point(f64::NAN, 0.0)),
        StoreError::NotFinite {
            index: 0,
            what: "latitude"
        }
    );
    assert_eq!(
        e(&mut s, point(0.0, f64::INFINITY)),
        StoreError::NotFinite {
            index: 0,
            what: "longitude"
        }
    );
    assert_eq!(
        e(&mut s, point(90.5, 0.0)),
        StoreError::Latitude {
            index: 0,
            value: 90.5
        }
    );
    assert_eq!(
        e(&mut s, point(0.0, -180.5)),
        StoreError::Longitude {
            index: 0,
            value: -180.5
        }
    );
    let poly = |pts| obj(VksObjectType::Polygon, 0.0, vec![], pts);
    assert!(matches!(
        e(&mut s, poly(vec![])),
        StoreError::VertexCount {
            shape: Shape::Polygon,
            count: 0,
            ..
        }
    ));
    assert!(matches!(
        e(&mut s, poly(vec![p(0.0, 0.0), p(1.0, 1.0)])),
        StoreError::VertexCount { count: 2, .. }
    ));
    assert!(matches!(
        e(
            &mut s,
            obj(VksObjectType::Line, 0.0, vec![], vec![p(0.0, 0.0)])
        ),
        StoreError::VertexCount {
            shape: Shape::Line,
            count: 1,
            ..
        }
    ));
    assert!(matches!(
        e(
            &mut s,
            obj(
                VksObjectType::Point,
                0.0,
                vec![],
                vec![p(0.0, 0.0), p(0.0, 1.0)]
            )
        ),
        StoreError::VertexCount {
            shape: Shape::Point,
            count: 2,
            ..
        }
    ));
    assert_eq!(
        e(
            &mut s,
            obj(VksObjectType::Unknown(7), 0.0, vec![], vec![p(0.0, 0.0)])
        ),
        StoreError::UnknownType(7)
    );
    for b in [-1.0f32, f32::NAN, 100.5] {
        assert!(matches!(
            e(&mut s, obj(VksObjectType::Point, b, vec![], vec![p(0.0, 0.0)])),
            StoreError::Buffer { max, .. } if max == 100.0
        ));
    }
    let line = |n: usize| {
        obj(
            VksObjectType::Line,
            0.0,
            vec![],
            (0..n).map(|i| p(0.0, i as f64 * 1e-5)).collect(),
        )
    };
    assert_eq!(
        e(&mut s, line(65_536)),
        StoreError::TooManyVertices {
            count: 65_536,
            max: 65_535
        }
    );
    assert!(e(&mut s, line(65_536)).to_string().contains("max_vertices"));
    let three = vec![
        fc(1, VksAttribute::Default),
        fc(2, VksAttribute::Default),
        fc(3, VksAttribute::Default),
    ];
    assert_eq!(
        e(
            &mut s,
            obj(VksObjectType::Point, 0.0, three, vec![p(0.0, 0.0)])
        ),
        StoreError::TooManyFeatureClasses { count: 3, max: 2 }
    );
    // A polygon around the North Pole: its edges go all the way round in longitude.
    let polar = poly(vec![p(80.0, 0.0), p(80.0, 120.0), p(80.0, -120.0)]);
    assert_eq!(e(&mut s, polar), StoreError::WrapsAround);
    // The total vertex limit, then the object limit.
    s.create(&line(65_535)).unwrap();
    assert_eq!(
        e(&mut s, line(5_000)),
        StoreError::TotalVertices {
            count: 5_000,
            max: 70_000
        }
    );
    s.create(&point(0.0, 0.0)).unwrap();
    s.create(&point(0.0, 0.0)).unwrap();
    let full = e(&mut s, point(0.0, 0.0));
    assert_eq!(full, StoreError::TooManyObjects { max: 3 });
    assert!(full.to_string().contains("max_objects"));
    assert_eq!(s.len(), 3, "nothing refused was stored");
}

// ---------------------------------------------------------------------------------
// Geometry primitives and buffer zones, against hand-computed distances

#[test]
fn primitives_match_hand_computed_distances() {
    // Equator: 0.001° of longitude = 111.319 m, of latitude = 110.574 m (header).
    let d = point_segment_distance(&p(0.0, 0.001), &p(0.0, 0.0), &p(0.0, 0.0));
    assert!((d - 111.319).abs() < 0.001, "{d}");
    let d = point_segment_distance(&p(0.001, 0.0), &p(0.0, -0.005), &p(0.0, 0.005));
    assert!((d - 110.574).abs() < 0.001, "{d}");
    // Beyond the end of the segment: the distance is to the end point (0, 0.005):
    // √(110.574² + 111.319²) = √(12226.6 + 12392.1) = 156.904 m.
    let d = point_segment_distance(&p(0.001, 0.006), &p(0.0, -0.005), &p(0.0, 0.005));
    assert!((d - 156.904).abs() < 0.01, "{d}");
    // 45° N: 0.001° of longitude = 78.847 m (both points at 45°, so cos φ₀ = cos 45°).
    let d = point_segment_distance(&p(45.0, 0.001), &p(45.0, 0.0), &p(45.0, 0.0));
    assert!((d - 78.847).abs() < 0.001, "{d}");
    // Across the antimeridian: 179.9995° E to 179.9995° W is 0.001° = 111.319 m.
    let d = point_segment_distance(&p(0.0, 179.9995), &p(0.0, -179.9995), &p(0.0, -179.9995));
    assert!((d - 111.319).abs() < 0.001, "{d}");

    assert!(segments_intersect(
        &p(-1.0, 0.0),
        &p(1.0, 0.0),
        &p(0.0, -1.0),
        &p(0.0, 1.0)
    ));
    assert!(!segments_intersect(
        &p(-1.0, 0.0),
        &p(1.0, 0.0),
        &p(0.0, 0.5),
        &p(0.0, 1.0)
    ));
    // Touching at an end point, and collinear overlapping.
    assert!(segments_intersect(
        &p(0.0, 0.0),
        &p(1.0, 0.0),
        &p(1.0, 0.0),
        &p(2.0, 5.0)
    ));
    assert!(segments_intersect(
        &p(0.0, 0.0),
        &p(2.0, 0.0),
        &p(1.0, 0.0),
        &p(3.0, 0.0)
    ));
    assert!(!segments_intersect(
        &p(0.0, 0.0),
        &p(1.0, 0.0),
        &p(2.0, 0.0),
        &p(3.0, 0.0)
    ));
    // Crossing the antimeridian: (0, 179.5)–(0, -179.5) crosses (-1, 180)–(1, 180).
    assert!(segments_intersect(
        &p(0.0, 179.5),
        &p(0.0, -179.5),
        &p(-1.0, 180.0),
        &p(1.0, -180.0)
    ));

    let sq = square(10.0, 20.0, 1.0);
    assert!(point_in_polygon(&p(10.0, 20.0), &sq));
    assert!(!point_in_polygon(&p(10.0, 21.5), &sq));
    assert!(!point_in_polygon(&p(0.0, 0.0), &sq[..2]));
    // Even-odd: a pentagram's centre is outside, its points are inside.
    let star: Vec<VksPoint> = (0..5)
        .map(|i| {
            let a = (f64::from(i) * 144.0 + 90.0).to_radians();
            p(a.sin(), a.cos())
        })
        .collect();
    assert!(!point_in_polygon(&p(0.0, 0.0), &star));
    assert!(point_in_polygon(&p(0.8, 0.0), &star));
    // A polygon across the antimeridian.
    let across = vec![
        p(-1.0, 179.0),
        p(-1.0, -179.0),
        p(1.0, -179.0),
        p(1.0, 179.0),
    ];
    assert!(point_in_polygon(&p(0.0, 180.0), &across));
    assert!(point_in_polygon(&p(0.0, -179.5), &across));
    assert!(!point_in_polygon(&p(0.0, 0.0), &across));
}

#[test]
fn buffer_zone_queries_match_hand_computed_distances() {
    let mut s = VectorStore::default();
    // A point 0.001° east of the origin: 111.319 m away.
    let east = s.create(&point(0.0, 0.001)).unwrap();
    // An east-west line 0.001° north: 110.574 m from the origin.
    let north = s
        .create(&obj(
            VksObjectType::Line,
            0.0,
            vec![],
            vec![p(0.001, -0.003), p(0.001, 0.003)],
        ))
        .unwrap();
    // A point 0.002° south with a 30 m buffer: 2 × 110.574 = 221.149 m away, its zone
    // starts at 221.149 − 30 = 191.149 m.
    let south = s
        .create(&obj(
            VksObjectType::Point,
            30.0,
            vec![],
            vec![p(-0.002, 0.0)],
        ))
        .unwrap();
    let q = |s: &VectorStore, b: f64| s.query(&region(Shape::Point, vec![p(0.0, 0.0)], b));
    assert_eq!(q(&s, 110.5), Vec::<u32>::new());
    assert_eq!(q(&s, 110.6), vec![north]);
    assert_eq!(q(&s, 111.3), vec![north]);
    assert_eq!(q(&s, 111.33), vec![east, north]);
    assert_eq!(q(&s, 191.1), vec![east, north]);
    assert_eq!(q(&s, 191.2), vec![east, north, south]);

    // A line region: the meridian segment (−0.01, 0.0005)–(0.01, 0.0005). The point
    // (0, 0.001) is 0.0005° of longitude = 55.660 m from it; the line at 0.001° N
    // crosses it (distance 0); the south point is 55.660 m − 30 m = 25.660 m away.
    let line = |b| region(Shape::Line, vec![p(-0.01, 0.0005), p(0.01, 0.0005)], b);
    assert_eq!(s.query(&line(0.0)), vec![north]);
    assert_eq!(s.query(&line(25.6)), vec![north]);
    assert_eq!(s.query(&line(25.7)), vec![north, south]);
    assert_eq!(s.query(&line(55.6)), vec![north, south]);
    assert_eq!(s.query(&line(55.7)), vec![east, north, south]);

    // A polygon region holding the origin: the square ±0.0015°. East and north lie
    // inside or cross it (distance 0); the south point is 0.0005° of latitude
    // = 55.287 m outside its southern edge, its zone 25.287 m away.
    let sq = |b| region(Shape::Polygon, square(0.0, 0.0, 0.0015), b);
    assert_eq!(s.query(&sq(0.0)), vec![east, north]);
    assert_eq!(s.query(&sq(25.2)), vec![east, north]);
    assert_eq!(s.query(&sq(25.4)), vec![east, north, south]);

    // Parallel segments 0.0005° of latitude apart = 55.287 m.
    let mut t = VectorStore::default();
    let a = t
        .create(&obj(
            VksObjectType::Line,
            0.0,
            vec![],
            vec![p(0.0005, 0.0), p(0.0005, 0.01)],
        ))
        .unwrap();
    let par = |b| region(Shape::Line, vec![p(0.0, 0.002), p(0.0, 0.005)], b);
    assert!(t.query(&par(55.2)).is_empty());
    assert_eq!(t.query(&par(55.35)), vec![a]);
    // The same split between the two buffers: 20 m on the object + 35.35 m on the region.
    let b = t
        .create(&obj(
            VksObjectType::Line,
            20.0,
            vec![],
            vec![p(-0.0005, 0.0), p(-0.0005, 0.01)],
        ))
        .unwrap();
    assert_eq!(t.query(&par(35.2)), Vec::<u32>::new());
    assert_eq!(t.query(&par(35.35)), vec![b]);

    // 45° N: a point 0.001° east is 78.847 m away; 0.001° north is 111.132 m away.
    let mut u = VectorStore::default();
    let e45 = u.create(&point(45.0, 0.001)).unwrap();
    let n45 = u.create(&point(45.001, 0.0)).unwrap();
    let q45 = |b| u.query(&region(Shape::Point, vec![p(45.0, 0.0)], b));
    assert!(q45(78.8).is_empty());
    assert_eq!(q45(78.9), vec![e45]);
    assert_eq!(q45(111.1), vec![e45]);
    assert_eq!(q45(111.2), vec![e45, n45]);

    // Geometry::intersects is the same test between two stand-alone geometries.
    let g1 = Geometry::new(Shape::Point, vec![p(0.0, 0.0)], 60.0).unwrap();
    let g2 = Geometry::new(Shape::Point, vec![p(0.0, 0.001)], 51.4).unwrap();
    let g3 = Geometry::new(Shape::Point, vec![p(0.0, 0.001)], 51.3).unwrap();
    assert!(g1.intersects(&g2) && g2.intersects(&g1)); // 111.4 ≥ 111.319
    assert!(!g1.intersects(&g3)); // 111.3 < 111.319
}

#[test]
fn containment_and_antimeridian() {
    let mut s = VectorStore::default();
    // A polygon object around a point region, no buffers: the region is inside.
    let big = s
        .create(&obj(
            VksObjectType::Polygon,
            0.0,
            vec![],
            square(5.0, 5.0, 1.0),
        ))
        .unwrap();
    assert_eq!(
        s.query(&region(Shape::Point, vec![p(5.0, 5.0)], 0.0)),
        vec![big]
    );
    // A small polygon object inside a big region polygon.
    let small = s
        .create(&obj(
            VksObjectType::Polygon,
            0.0,
            vec![],
            square(-5.0, -5.0, 0.001),
        ))
        .unwrap();
    assert_eq!(
        s.query(&region(Shape::Polygon, square(-5.0, -5.0, 1.0), 0.0)),
        vec![small]
    );
    // A line along the equator across the antimeridian, and a point on each side.
    let line = s
        .create(&obj(
            VksObjectType::Line,
            0.0,
            vec![],
            vec![p(0.0, 179.999), p(0.0, -179.999)],
        ))
        .unwrap();
    let w = s.create(&point(0.0, -179.9995)).unwrap();
    let e = s.create(&point(0.0, 179.9995)).unwrap();
    assert_eq!(
        s.query(&region(Shape::Point, vec![p(0.0, 180.0)], 0.0)),
        vec![line]
    );
    assert_eq!(
        s.query(&region(Shape::Point, vec![p(0.0, -180.0)], 60.0)),
        vec![line, w, e]
    );
    // A polygon region across the antimeridian holds all three.
    let across = vec![
        p(-1.0, 179.0),
        p(-1.0, -179.0),
        p(1.0, -179.0),
        p(1.0, 179.0),
    ];
    assert_eq!(
        s.query(&region(Shape::Polygon, across, 0.0)),
        vec![line, w, e]
    );
    // A buffer reaching across: 0.0005° of longitude at the equator = 55.660 m.
    let q = |b| s.query(&region(Shape::Point, vec![p(0.0, 179.9990)], b));
    assert_eq!(q(0.0), vec![line]);
    assert_eq!(q(55.6), vec![line]);
    assert_eq!(q(55.7), vec![line, e]);
}

#[test]
fn polygon_of_65535_vertices_is_stored_queried_and_deleted() {
    let mut s = VectorStore::default();
    let n = MAX_VERTICES;
    // A circle of radius 0.05° around (30, -80), vertex by vertex.
    let ring: Vec<VksPoint> = (0..n)
        .map(|i| {
            let a = i as f64 / n as f64 * std::f64::consts::TAU;
            p(30.0 + 0.05 * a.sin(), -80.0 + 0.05 * a.cos())
        })
        .collect();
    let other = s.create(&point(31.0, -80.0)).unwrap();
    let big = s
        .create(&obj(
            VksObjectType::Polygon,
            0.0,
            vec![fc(9, VksAttribute::Default)],
            ring.clone(),
        ))
        .unwrap();
    assert_eq!(s.total_vertices(), n + 1);
    assert_eq!(s.get(big).unwrap().points.len(), n);
    // The centre is inside (containment); a point region 0.06° north is 0.01° of
    // latitude from the ring ≈ 1,109 m (0.01° × 110,874 m/° at 30°): in reach with
    // 1,120 m, not with 1,100 m.
    assert_eq!(
        s.query(&region(Shape::Point, vec![p(30.0, -80.0)], 0.0)),
        vec![big]
    );
    assert!(s
        .query(&region(Shape::Point, vec![p(30.06, -80.0)], 1_100.0))
        .is_empty());
    assert_eq!(
        s.query(&region(Shape::Point, vec![p(30.06, -80.0)], 1_120.0)),
        vec![big]
    );
    // Queried with itself as region (65,535 edges both sides).
    let f = region(Shape::Polygon, ring.clone(), 0.0);
    assert_eq!(s.query(&f), vec![big]);
    assert_eq!(s.query_linear(&f), vec![big]);
    // Bounds of its feature class: ±0.05° around the centre.
    let b = s.bounds(Some(9)).unwrap();
    assert!(
        (b.south - 29.95).abs() < 1e-6 && (b.north - 30.05).abs() < 1e-6,
        "{b:?}"
    );
    assert!(
        (b.west + 80.05).abs() < 1e-6 && (b.east + 79.95).abs() < 1e-6,
        "{b:?}"
    );
    // Deleted by region and feature class.
    let del = Filter {
        classes: Some(vec![VksFeatureClassFilter {
            id: Some(9),
            attribute: None,
        }]),
        ..region(Shape::Point, vec![p(30.0, -80.0)], 0.0)
    };
    assert_eq!(s.delete_matching(&del).unwrap(), vec![big]);
    assert_eq!(s.total_vertices(), 1);
    assert_eq!(s.ids().collect::<Vec<_>>(), vec![other]);
    assert!(s
        .query(&region(Shape::Point, vec![p(30.0, -80.0)], 0.0))
        .is_empty());
}

// ---------------------------------------------------------------------------------
// Filters, deletion, bounds, metadata

fn classified_store() -> (VectorStore, [u32; 5]) {
    let mut s = VectorStore::default();
    let road = |a| vec![fc(1, VksAttribute::UnsignedShort(a))];
    let ids = [
        s.create(&obj(
            VksObjectType::Line,
            0.0,
            road(10),
            vec![p(0.0, 0.0), p(0.0, 0.01)],
        ))
        .unwrap(),
        s.create(&obj(
            VksObjectType::Line,
            0.0,
            road(20),
            vec![p(0.01, 0.0), p(0.01, 0.01)],
        ))
        .unwrap(),
        s.create(&obj(
            VksObjectType::Point,
            0.0,
            vec![
                fc(2, VksAttribute::Byte(10)),
                fc(1, VksAttribute::UnsignedShort(20)),
            ],
            vec![p(0.02, 0.0)],
        ))
        .unwrap(),
        s.create(&obj(
            VksObjectType::Point,
            0.0,
            vec![fc(
                2,
                VksAttribute::Rgb(Rgb {
                    red: 1,
                    green: 2,
                    blue: 3,
                }),
            )],
            vec![p(1.0, 1.0)],
        ))
        .unwrap(),
        s.create(&point(2.0, 2.0)).unwrap(),
    ];
    (s, ids)
}

fn by_class(id: Option<u16>, attribute: Option<VksAttribute>) -> Filter {
    Filter {
        classes: Some(vec![VksFeatureClassFilter { id, attribute }]),
        ..Filter::default()
    }
}

#[test]
fn queries_by_ids_feature_class_and_attribute() {
    let (s, [a, b, c, d, e]) = classified_store();
    assert_eq!(s.query(&Filter::default()), vec![a, b, c, d, e]);
    assert_eq!(s.query(&by_class(Some(1), None)), vec![a, b, c]);
    assert_eq!(s.query(&by_class(Some(2), None)), vec![c, d]);
    assert_eq!(s.query(&by_class(Some(3), None)), Vec::<u32>::new());
    assert_eq!(
        s.query(&by_class(Some(1), Some(VksAttribute::UnsignedShort(20)))),
        vec![b, c]
    );
    // The attribute belongs to the class: class 2 with value 20 matches nothing.
    assert_eq!(
        s.query(&by_class(Some(2), Some(VksAttribute::UnsignedShort(20)))),
        Vec::<u32>::new()
    );
    // Attribute alone, in any class; same number but another type does not match.
    assert_eq!(
        s.query(&by_class(None, Some(VksAttribute::Byte(10)))),
        vec![c]
    );
    assert_eq!(
        s.query(&by_class(None, Some(VksAttribute::Byte(20)))),
        Vec::<u32>::new()
    );
    assert_eq!(
        s.query(&by_class(
            None,
            Some(VksAttribute::Rgb(Rgb {
                red: 1,
                green: 2,
                blue: 3
            }))
        )),
        vec![d]
    );
    // Several criteria: any of them.
    let either = Filter {
        classes: Some(vec![
            VksFeatureClassFilter {
                id: Some(2),
                attribute: None,
            },
            VksFeatureClassFilter {
                id: Some(1),
                attribute: Some(VksAttribute::UnsignedShort(10)),
            },
        ]),
        ..Filter::default()
    };
    assert_eq!(s.query(&either), vec![a, c, d]);
    // IDs (unknown ones ignored), and IDs with a class: both must hold.
    let ids = Filter {
        ids: Some(vec![e, a, 4242]),
        ..Filter::default()
    };
    assert_eq!(s.query(&ids), vec![a, e]);
    let ids_and_class = Filter {
        ids: Some(vec![a, d, e]),
        ..by_class(Some(1), None)
    };
    assert_eq!(s.query(&ids_and_class), vec![a]);
    // Region and class: near the origin (0.011° ≈ 1.2 km), class 1.
    let near = Filter {
        classes: Some(vec![VksFeatureClassFilter {
            id: Some(1),
            attribute: None,
        }]),
        ..region(Shape::Point, vec![p(0.0, 0.0)], 1_300.0)
    };
    assert_eq!(s.query(&near), vec![a, b]);
    assert_eq!(s.query_linear(&near), vec![a, b]);
}

#[test]
fn delete_by_filter() {
    let (mut s, [a, b, c, d, e]) = classified_store();
    assert_eq!(
        s.delete_matching(&Filter::default()),
        Err(StoreError::EmptyFilter)
    );
    assert_eq!(s.len(), 5);
    assert_eq!(
        s.delete_matching(&by_class(Some(1), Some(VksAttribute::UnsignedShort(20))))
            .unwrap(),
        vec![b, c]
    );
    assert_eq!(s.ids().collect::<Vec<_>>(), vec![a, d, e]);
    // The class index forgets deleted objects.
    assert_eq!(s.query(&by_class(Some(2), None)), vec![d]);
    assert_eq!(
        s.delete_matching(&region(Shape::Polygon, square(1.5, 1.5, 0.6), 0.0))
            .unwrap(),
        vec![d, e]
    );
    assert_eq!(
        s.delete_matching(&Filter {
            ids: Some(vec![a, 77]),
            ..Filter::default()
        })
        .unwrap(),
        vec![a]
    );
    assert!(s.is_empty());
    assert_eq!(s.total_vertices(), 0);
    // A store emptied by deletion takes new objects as before.
    assert!(s.create(&point(0.0, 0.0)).is_ok());
    s.clear();
    assert!(s.is_empty());
}

#[test]
fn bounds_of_all_objects_and_of_a_class() {
    let (s, _) = classified_store();
    assert_eq!(
        s.bounds(None),
        Some(Bounds {
            south: 0.0,
            west: 0.0,
            north: 2.0,
            east: 2.0
        })
    );
    assert_eq!(
        s.bounds(Some(1)),
        Some(Bounds {
            south: 0.0,
            west: 0.0,
            north: 0.02,
            east: 0.01
        })
    );
    assert_eq!(
        s.bounds(Some(2)),
        Some(Bounds {
            south: 0.02,
            west: 0.0,
            north: 1.0,
            east: 1.0
        })
    );
    assert_eq!(s.bounds(Some(99)), None);
    assert_eq!(VectorStore::default().bounds(None), None);
    // Objects on both sides of the antimeridian: the short box crosses it.
    let mut t = VectorStore::default();
    t.create(&point(-1.0, 179.5)).unwrap();
    t.create(&point(1.0, -179.0)).unwrap();
    t.create(&obj(
        VksObjectType::Line,
        0.0,
        vec![],
        vec![p(0.0, 178.0), p(0.5, -179.5)],
    ))
    .unwrap();
    assert_eq!(
        t.bounds(None),
        Some(Bounds {
            south: -1.0,
            west: 178.0,
            north: 1.0,
            east: -179.0
        })
    );
    // Spread round the world: longitudes -179, -100, 0, 90 and 178 to 179.5 (and on
    // to -179.5). The gaps are 79°, 100°, 90° and 88°: the box is everything but the
    // widest, from 0° east round to -100°.
    t.create(&point(0.0, 0.0)).unwrap();
    t.create(&point(0.0, 90.0)).unwrap();
    t.create(&point(0.0, -100.0)).unwrap();
    assert_eq!(
        t.bounds(None),
        Some(Bounds {
            south: -1.0,
            west: 0.0,
            north: 1.0,
            east: -100.0
        })
    );
}

#[test]
fn feature_class_metadata() {
    let mut s = VectorStore::new(StoreConfig {
        max_metadata_bytes: 100_000,
        ..StoreConfig::default()
    });
    assert_eq!(s.metadata(3), "");
    s.set_metadata(3, VksMetadataOption::Overwrite, "roads")
        .unwrap();
    s.set_metadata(3, VksMetadataOption::Append, " (paved)")
        .unwrap();
    s.set_metadata(3, VksMetadataOption::Prepend, "US ")
        .unwrap();
    assert_eq!(s.metadata(3), "US roads (paved)");
    s.set_metadata(3, VksMetadataOption::Overwrite, "trails")
        .unwrap();
    assert_eq!(s.metadata(3), "trails");
    s.set_metadata(3, VksMetadataOption::Erase, "ignored")
        .unwrap();
    assert_eq!(s.metadata(3), "");
    assert_eq!(
        s.set_metadata(3, VksMetadataOption::Unknown(9), "x"),
        Err(StoreError::MetadataOption(9))
    );
    let long = "x".repeat(40_000);
    s.set_metadata(1, VksMetadataOption::Overwrite, &long)
        .unwrap();
    assert_eq!(
        s.set_metadata(1, VksMetadataOption::Append, &long),
        Err(StoreError::MetadataTooLong {
            class: 1,
            len: 80_000
        })
    );
    s.set_metadata(2, VksMetadataOption::Overwrite, &long)
        .unwrap();
    assert_eq!(
        s.set_metadata(4, VksMetadataOption::Overwrite, &long),
        Err(StoreError::MetadataFull {
            total: 120_000,
            max: 100_000
        })
    );
    assert_eq!(s.metadata(1).len(), 40_000);
}

#[test]
fn invalid_regions_and_filters_are_refused() {
    assert!(matches!(
        Geometry::new(Shape::Point, vec![p(0.0, 0.0)], -1.0),
        Err(StoreError::Buffer { .. })
    ));
    assert!(matches!(
        Geometry::new(Shape::Point, vec![p(0.0, 0.0)], f64::NAN),
        Err(StoreError::Buffer { .. })
    ));
    assert!(matches!(
        Geometry::new(Shape::Polygon, vec![], 0.0),
        Err(StoreError::VertexCount { .. })
    ));
    assert!(matches!(
        Geometry::new(Shape::Line, vec![p(0.0, f64::NAN), p(0.0, 0.0)], 0.0),
        Err(StoreError::NotFinite { .. })
    ));
    let q = QueryVksObjects {
        region_type: Some(VksObjectType::Point),
        ..Default::default()
    };
    assert!(matches!(Filter::from_query(&q), Err(StoreError::Region(_))));
    let q = QueryVksObjects {
        region_points: Some(vec![p(0.0, 0.0)]),
        ..Default::default()
    };
    assert!(matches!(Filter::from_query(&q), Err(StoreError::Region(_))));
    let q = QueryVksObjects {
        region_buffer: Some(3.0),
        ..Default::default()
    };
    assert!(matches!(Filter::from_query(&q), Err(StoreError::Region(_))));
    let q = QueryVksObjects {
        feature_classes: Some(vec![VksFeatureClassFilter {
            id: None,
            attribute: None,
        }]),
        ..Default::default()
    };
    assert_eq!(Filter::from_query(&q), Err(StoreError::EmptyCriteria));
    let d = DeleteVksObjects {
        region_type: Some(VksObjectType::Unknown(5)),
        region_points: Some(vec![p(0.0, 0.0)]),
        ..Default::default()
    };
    assert_eq!(Filter::from_delete(&d), Err(StoreError::UnknownType(5)));
}

// ---------------------------------------------------------------------------------
// The index against a linear scan

/// A small deterministic generator (SplitMix64).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn f(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

fn random_shape(r: &mut Rng, lat: f64, lon: f64, size: f64) -> (Shape, Vec<VksPoint>) {
    let wrap = |l: f64| {
        if l > 180.0 {
            l - 360.0
        } else if l < -180.0 {
            l + 360.0
        } else {
            l
        }
    };
    let v = |r: &mut Rng| {
        p(
            (lat + r.f(-size, size)).clamp(-90.0, 90.0),
            wrap(lon + r.f(-size, size)),
        )
    };
    match r.next() % 3 {
        0 => (Shape::Point, vec![v(r)]),
        1 => {
            let n = 2 + (r.next() % 4) as usize;
            (Shape::Line, (0..n).map(|_| v(r)).collect())
        }
        _ => {
            // A convex-ish polygon: vertices round the centre in angle order.
            let n = 3 + (r.next() % 5) as usize;
            let pts = (0..n)
                .map(|i| {
                    let a = i as f64 / n as f64 * std::f64::consts::TAU;
                    let rad = size * r.f(0.3, 1.0);
                    p(
                        (lat + rad * a.sin()).clamp(-90.0, 90.0),
                        wrap(lon + rad * a.cos()),
                    )
                })
                .collect();
            (Shape::Polygon, pts)
        }
    }
}

#[test]
fn index_agrees_with_a_linear_scan() {
    let mut r = Rng(7);
    // Three areas: mid-latitudes, the antimeridian at the equator, and 80° N.
    let areas = [(29.65, -82.35), (0.0, 180.0), (80.0, 10.0)];
    let mut objects = Vec::new();
    for i in 0..6_000 {
        let (lat, lon) = areas[i % 3];
        let (clat, clon) = (lat + r.f(-0.05, 0.05), lon + r.f(-0.05, 0.05));
        let clon = if clon > 180.0 { clon - 360.0 } else { clon };
        let (shape, pts) = random_shape(&mut r, clat.min(90.0), clon, 0.001);
        let buffer = if r.next().is_multiple_of(2) {
            0.0
        } else {
            r.f(0.0, 50.0) as f32
        };
        objects.push(obj(
            shape.to_wire(),
            buffer,
            vec![fc((i % 4) as u16, VksAttribute::Default)],
            pts,
        ));
    }
    // Every way of indexing: a batch into the empty store (bulk load), a batch smaller
    // than the store (entry by entry), a batch larger than the store (rebuilt by bulk
    // load with what was there), and one object at a time.
    let mut s = VectorStore::default();
    for batch in [
        &objects[..1_000],
        &objects[1_000..1_500],
        &objects[1_500..4_000],
    ] {
        assert!(s.create_all(batch).iter().all(Result::is_ok));
    }
    for o in &objects[4_000..] {
        s.create(o).unwrap();
    }
    assert_eq!(s.len(), 6_000);
    let mut hits = 0;
    for i in 0..300 {
        let (lat, lon) = areas[i % 3];
        let (clat, clon) = (lat + r.f(-0.05, 0.05), lon + r.f(-0.05, 0.05));
        let clon = if clon > 180.0 { clon - 360.0 } else { clon };
        let (shape, pts) = random_shape(&mut r, clat, clon, 0.004);
        let mut f = Filter {
            region: Some(Geometry::new(shape, pts, r.f(0.0, 300.0)).unwrap()),
            ..Filter::default()
        };
        if i % 5 == 0 {
            f.classes = Some(vec![VksFeatureClassFilter {
                id: Some(1),
                attribute: None,
            }]);
        }
        let fast = s.query(&f);
        assert_eq!(fast, s.query_linear(&f), "region {i}: {:?}", f.region);
        hits += fast.len();
    }
    assert!(hits > 1_000, "the regions must select objects: {hits}");
}

// ---------------------------------------------------------------------------------
// The component on a LocalBus

const SS: u8 = 1;
const WM: Address = Address::new(SS, 1, 61, 1);
const CLIENT: Address = Address::new(SS, 2, 200, 1);

fn t0() -> Instant {
    static T0: OnceLock<Instant> = OnceLock::new();
    *T0.get_or_init(Instant::now)
}

fn config() -> Config {
    Config {
        heartbeat: None,
        ..Config::default()
    }
}

fn bus_with(core: StockWorldModel) -> LocalBus {
    let mut bus = LocalBus::new(t0());
    bus.add(wmvks::component(WM, core, config(), t0()));
    bus.add(Probe::new(CLIENT));
    bus.run_for(Duration::from_millis(10));
    bus
}

/// Sends `msg` from the client, runs the bus, returns what the client received.
fn ask(bus: &mut LocalBus, msg: impl Into<Message>) -> Vec<Message> {
    bus.get_mut::<Probe>(CLIENT).unwrap().clear();
    bus.send(CLIENT, WM, msg);
    bus.run_for(Duration::from_millis(10));
    bus.get::<Probe>(CLIENT)
        .unwrap()
        .messages()
        .cloned()
        .collect()
}

fn wm(bus: &LocalBus) -> &Component<Dispatch<StockWorldModel>> {
    bus.get(WM).unwrap()
}

fn objects_of(m: &[Message]) -> Vec<VksStoredObject> {
    match m {
        [Message::ReportVksObjects(r)] => r.objects.clone().unwrap_or_default(),
        other => panic!("expected one Report VKS Objects, got {other:?}"),
    }
}

fn query_all(request_id: u8) -> QueryVksObjects {
    QueryVksObjects {
        response_presence_vector: 1,
        request_id,
        ..Default::default()
    }
}

#[test]
fn component_answers_create_query_delete_on_the_bus() {
    let mut bus = bus_with(StockWorldModel::default());
    let create = CreateVksObjects {
        buffered: true,
        message_properties: 1,
        request_id: 42,
        objects: vec![
            obj(
                VksObjectType::Point,
                5.0,
                vec![fc(1, VksAttribute::Byte(3))],
                vec![p(29.65, -82.35)],
            ),
            obj(
                VksObjectType::Line,
                0.0,
                vec![fc(2, VksAttribute::Default)],
                vec![p(29.65, -82.35), p(29.66, -82.34)],
            ),
            obj(
                VksObjectType::Polygon,
                1.5,
                vec![fc(1, VksAttribute::Byte(4))],
                square(29.7, -82.3, 0.001),
            ),
        ],
    };
    let r = ask(&mut bus, create.clone());
    let ids = match &r[..] {
        [Message::ReportVksObjectsCreation(c)] => {
            assert_eq!(c.request_id, 42);
            c.object_ids.clone()
        }
        other => panic!("{other:?}"),
    };
    assert_eq!(ids.len(), 3);
    assert!(ids.iter().all(|&id| id != 0));
    // Without bit 0 of the message properties, no report.
    let quiet = CreateVksObjects {
        message_properties: 0,
        objects: vec![point(0.0, 0.0)],
        ..create.clone()
    };
    assert!(ask(&mut bus, quiet).is_empty());
    assert_eq!(wm(&bus).behaviour().0.store().len(), 4);

    // Query by region: 200 m around the first point finds the point and the line.
    let q = QueryVksObjects {
        response_presence_vector: 1,
        request_id: 7,
        region_type: Some(VksObjectType::Point),
        region_buffer: Some(200.0),
        region_points: Some(vec![p(29.65, -82.35)]),
        ..Default::default()
    };
    let r = ask(&mut bus, q.clone());
    let Message::ReportVksObjects(rep) = &r[0] else {
        panic!("{r:?}")
    };
    assert_eq!(rep.request_id, 7);
    assert_eq!(rep.object_count, 2);
    let got = objects_of(&r);
    assert_eq!(
        got.iter().map(|o| o.object_id).collect::<Vec<_>>(),
        ids[..2].to_vec()
    );
    // Values come back as stored, within the wire resolution.
    assert_eq!(got[0].buffer, 5.0);
    assert_eq!(got[0].feature_classes, vec![fc(1, VksAttribute::Byte(3))]);
    assert!((got[0].points[0].latitude - 29.65).abs() < 1e-7);
    // Count only (response PV bit 0 clear).
    let r = ask(
        &mut bus,
        QueryVksObjects {
            response_presence_vector: 0,
            ..q.clone()
        },
    );
    assert!(matches!(
        &r[..],
        [Message::ReportVksObjects(ReportVksObjects {
            object_count: 2,
            objects: None,
            ..
        })]
    ));
    // By feature-class attribute.
    let by_attr = QueryVksObjects {
        filter_by_attributes: true,
        feature_classes: Some(vec![VksFeatureClassFilter {
            id: None,
            attribute: Some(VksAttribute::Byte(4)),
        }]),
        ..query_all(8)
    };
    assert_eq!(
        objects_of(&ask(&mut bus, by_attr))
            .iter()
            .map(|o| o.object_id)
            .collect::<Vec<_>>(),
        vec![ids[2]]
    );

    // Delete class 1, then everything is class 2 or unclassified.
    let del = DeleteVksObjects {
        filter_by_class_ids: true,
        feature_classes: Some(vec![VksFeatureClassFilter {
            id: Some(1),
            attribute: None,
        }]),
        ..Default::default()
    };
    assert!(ask(&mut bus, del).is_empty());
    let left: Vec<u32> = objects_of(&ask(&mut bus, query_all(9)))
        .iter()
        .map(|o| o.object_id)
        .collect();
    assert_eq!(left.len(), 2);
    assert_eq!(left[0], ids[1]);
    // Delete by ID.
    let del = DeleteVksObjects {
        object_ids: Some(left.clone()),
        ..Default::default()
    };
    ask(&mut bus, del);
    assert!(objects_of(&ask(&mut bus, query_all(10))).is_empty());

    // Bounds and metadata.
    ask(
        &mut bus,
        CreateVksObjects {
            objects: vec![point(10.0, 20.0), point(11.0, 21.0)],
            ..create.clone()
        },
    );
    let r = ask(
        &mut bus,
        QueryVksBounds {
            request_id: 3,
            feature_class_id: ALL_FEATURE_CLASSES,
        },
    );
    let Message::ReportVksBounds(b) = &r[0] else {
        panic!("{r:?}")
    };
    assert_eq!(b.request_id, 3);
    assert!(
        (b.south_west_latitude - 10.0).abs() < 1e-7 && (b.north_east_longitude - 21.0).abs() < 1e-7
    );
    let r = ask(
        &mut bus,
        QueryVksBounds {
            request_id: 4,
            feature_class_id: 77,
        },
    );
    let Message::ReportVksBounds(b) = &r[0] else {
        panic!("{r:?}")
    };
    assert!(
        b.south_west_latitude > b.north_east_latitude,
        "an empty class reports an inverted box"
    );
    ask(
        &mut bus,
        SetVksFeatureClassMetadata {
            metadata_option: VksMetadataOption::Overwrite,
            feature_class_id: 5,
            metadata: "buildings".into(),
        },
    );
    let r = ask(
        &mut bus,
        QueryVksFeatureClassMetadata {
            feature_class_id: 5,
        },
    );
    assert_eq!(
        r,
        vec![Message::ReportVksFeatureClassMetadata(
            ReportVksFeatureClassMetadata {
                feature_class_id: 5,
                metadata: "buildings".into()
            }
        )]
    );
    assert_eq!(wm(&bus).stats().invalid, 0);
    assert_eq!(wm(&bus).stats().unsupported, 0);
}

#[test]
fn long_answers_are_paged_and_terminated() {
    let core = StockWorldModel::new(WorldModelConfig {
        max_report_objects: 3,
        ..WorldModelConfig::default()
    });
    let mut bus = bus_with(core);
    let objects: Vec<VksObject> = (0..8).map(|i| point(1.0, f64::from(i) * 0.001)).collect();
    let create = CreateVksObjects {
        buffered: false,
        message_properties: 1,
        request_id: 1,
        objects: unbuffered(objects),
    };
    let r = ask(&mut bus, create);
    let Message::ReportVksObjectsCreation(c) = &r[0] else {
        panic!("{r:?}")
    };
    let all = c.object_ids.clone();
    let page = |bus: &mut LocalBus, q: QueryVksObjects| -> Vec<u32> {
        objects_of(&ask(bus, q))
            .iter()
            .map(|o| o.object_id)
            .collect()
    };
    // The count-only query gives the total; then 3 + 3 + 2, then it starts over.
    let r = ask(
        &mut bus,
        QueryVksObjects {
            response_presence_vector: 0,
            ..query_all(5)
        },
    );
    assert!(matches!(
        &r[..],
        [Message::ReportVksObjects(ReportVksObjects {
            object_count: 8,
            ..
        })]
    ));
    assert_eq!(page(&mut bus, query_all(5)), all[0..3]);
    assert_eq!(wm(&bus).behaviour().0.open_transfers(), 1);
    assert_eq!(page(&mut bus, query_all(5)), all[3..6]);
    assert_eq!(page(&mut bus, query_all(5)), all[6..8]);
    assert_eq!(wm(&bus).behaviour().0.open_transfers(), 0);
    assert_eq!(page(&mut bus, query_all(5)), all[0..3]);
    // Another request ID is another query: it starts at the beginning.
    assert_eq!(page(&mut bus, query_all(6)), all[0..3]);
    // Terminate ends the transfer and is confirmed.
    let r = ask(&mut bus, TerminateVksDataTransfer {});
    assert_eq!(
        r,
        vec![Message::ReportVksDataTransferTermination(
            ReportVksDataTransferTermination {}
        )]
    );
    assert_eq!(wm(&bus).behaviour().0.open_transfers(), 0);
    assert_eq!(page(&mut bus, query_all(6)), all[0..3]);
    // A transfer not continued within the timeout (30 s) is dropped.
    bus.run_for(Duration::from_secs(31));
    assert_eq!(wm(&bus).behaviour().0.open_transfers(), 0);
    assert_eq!(page(&mut bus, query_all(6)), all[0..3]);
    // A byte budget smaller than one object still sends one object per report.
    let core = StockWorldModel::new(WorldModelConfig {
        max_report_bytes: 1,
        ..WorldModelConfig::default()
    });
    let mut bus = bus_with(core);
    ask(
        &mut bus,
        CreateVksObjects {
            buffered: false,
            message_properties: 0,
            request_id: 1,
            objects: unbuffered(vec![point(0.0, 0.0), point(0.0, 1.0)]),
        },
    );
    assert_eq!(page(&mut bus, query_all(1)).len(), 1);
    assert_eq!(page(&mut bus, query_all(1)).len(), 1);
    assert!(wm(&bus).stats().invalid == 0);
}

#[test]
fn garbage_is_refused_and_counted() {
    let mut bus = bus_with(StockWorldModel::default());
    let creation = |m: &[Message]| match m {
        [Message::ReportVksObjectsCreation(c)] => c.object_ids.clone(),
        other => panic!("{other:?}"),
    };
    // A NaN buffer (a raw f32 on the wire), a two-vertex polygon, an unknown type and
    // a good point in one message: the good one is stored, the others get ID 0.
    let mixed = CreateVksObjects {
        buffered: true,
        message_properties: 1,
        request_id: 9,
        objects: vec![
            obj(VksObjectType::Point, f32::NAN, vec![], vec![p(0.0, 0.0)]),
            obj(
                VksObjectType::Polygon,
                0.0,
                vec![],
                vec![p(0.0, 0.0), p(1.0, 1.0)],
            ),
            obj(VksObjectType::Unknown(7), 0.0, vec![], vec![p(0.0, 0.0)]),
            point(0.0, 0.0),
        ],
    };
    let ids = creation(&ask(&mut bus, mixed));
    assert_eq!(ids[..3], [0, 0, 0]);
    assert_ne!(ids[3], 0);
    assert_eq!(wm(&bus).stats().invalid, 1);
    assert_eq!(wm(&bus).behaviour().0.store().len(), 1);

    // A latitude beyond -90°: the i32 -2³¹ decodes one step below the limit.
    let good = CreateVksObjects {
        buffered: false,
        message_properties: 1,
        request_id: 10,
        objects: unbuffered(vec![point(-90.0, 0.0)]),
    };
    let mut body = good.to_bytes().unwrap();
    let n = body.len();
    body[n - 8..n - 4].copy_from_slice(&i32::MIN.to_le_bytes());
    let now = bus.now();
    let header = Header::new(CreateVksObjects::CODE, WM, CLIENT);
    bus.get_mut::<Component<Dispatch<StockWorldModel>>>(WM)
        .unwrap()
        .handle(now, &header, &body);
    bus.get_mut::<Probe>(CLIENT).unwrap().clear();
    bus.run_for(Duration::from_millis(10));
    let r: Vec<Message> = bus
        .get::<Probe>(CLIENT)
        .unwrap()
        .messages()
        .cloned()
        .collect();
    assert_eq!(creation(&r), vec![0]);
    assert_eq!(wm(&bus).stats().invalid, 2);

    // 65,536 vertices cannot be encoded (u16 count): hand the typed message over.
    let huge = CreateVksObjects {
        buffered: false,
        message_properties: 0,
        request_id: 11,
        objects: unbuffered(vec![obj(
            VksObjectType::Line,
            0.0,
            vec![],
            (0..65_536).map(|i| p(0.0, f64::from(i) * 1e-5)).collect(),
        )]),
    };
    assert!(huge.to_bytes().is_err());
    let header = Header::new(CreateVksObjects::CODE, WM, CLIENT);
    let c = bus
        .get_mut::<Component<Dispatch<StockWorldModel>>>(WM)
        .unwrap();
    c.handle_message(now, &header, &Message::CreateVksObjects(huge));
    c.handle_message(
        now,
        &header,
        &Message::CreateVksObjects(CreateVksObjects {
            objects: unbuffered(vec![point(f64::NAN, 0.0), point(0.0, 181.0)]),
            ..good.clone()
        }),
    );
    assert_eq!(c.stats().invalid, 4);
    assert_eq!(c.behaviour().0.store().len(), 1);
    // The second asked for a creation report: every ID is 0.
    bus.get_mut::<Probe>(CLIENT).unwrap().clear();
    bus.run_for(Duration::from_millis(10));
    let r: Vec<Message> = bus
        .get::<Probe>(CLIENT)
        .unwrap()
        .messages()
        .cloned()
        .collect();
    assert_eq!(creation(&r), vec![0, 0]);

    // Queries and deletions with bad regions or filters.
    let bad_region = QueryVksObjects {
        region_type: Some(VksObjectType::Polygon),
        region_points: Some(vec![p(0.0, 0.0)]),
        ..query_all(1)
    };
    assert!(ask(&mut bus, bad_region).is_empty());
    let nan_buffer = QueryVksObjects {
        region_type: Some(VksObjectType::Point),
        region_buffer: Some(f32::NAN),
        region_points: Some(vec![p(0.0, 0.0)]),
        ..query_all(2)
    };
    assert!(ask(&mut bus, nan_buffer).is_empty());
    assert!(ask(&mut bus, DeleteVksObjects::default()).is_empty());
    assert!(ask(
        &mut bus,
        SetVksFeatureClassMetadata {
            metadata_option: VksMetadataOption::Unknown(3),
            feature_class_id: 1,
            metadata: String::new(),
        }
    )
    .is_empty());
    assert_eq!(wm(&bus).stats().invalid, 8);
    assert_eq!(wm(&bus).stats().decode_errors, 0);
    // Nothing was lost: the one good object is still there.
    assert_eq!(objects_of(&ask(&mut bus, query_all(3))).len(), 1);
}

#[test]
fn largest_polygon_crosses_the_bus() {
    let mut bus = bus_with(StockWorldModel::default());
    let ring: Vec<VksPoint> = (0..MAX_VERTICES)
        .map(|i| {
            let a = i as f64 / MAX_VERTICES as f64 * std::f64::consts::TAU;
            p(-33.9 + 0.02 * a.sin(), 151.2 + 0.02 * a.cos())
        })
        .collect();
    let create = CreateVksObjects {
        buffered: true,
        message_properties: 1,
        request_id: 1,
        objects: vec![obj(VksObjectType::Polygon, 0.0, vec![], ring)],
    };
    let r = ask(&mut bus, create);
    let Message::ReportVksObjectsCreation(c) = &r[0] else {
        panic!("{r:?}")
    };
    let id = c.object_ids[0];
    assert_ne!(id, 0);
    let inside = QueryVksObjects {
        region_type: Some(VksObjectType::Point),
        region_points: Some(vec![p(-33.9, 151.2)]),
        ..query_all(2)
    };
    let got = objects_of(&ask(&mut bus, inside.clone()));
    assert_eq!(got.len(), 1);
    assert_eq!(got[0].points.len(), MAX_VERTICES);
    ask(
        &mut bus,
        DeleteVksObjects {
            object_ids: Some(vec![id]),
            ..Default::default()
        },
    );
    assert!(objects_of(&ask(&mut bus, inside)).is_empty());
    assert_eq!(wm(&bus).behaviour().0.store().total_vertices(), 0);
}
