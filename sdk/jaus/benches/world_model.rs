//! The World Model Vector Knowledge Store at scale: 1,000,000 mixed objects (points,
//! short lines, small polygons) over about 50 km × 50 km around Gainesville, FL.
//! Prints the insert rate and the median latency of region queries returning about 100
//! objects, through the R*-tree and by a linear scan of every object, in the same run.
//!
//! Run: `cargo bench -p jaus --bench world_model` (a plain `main` timed with
//! `std::time::Instant`: building the store once takes seconds, which criterion's
//! repeated samples would multiply).

use std::hint::black_box;
use std::time::{Duration, Instant};

use jaus::messages::{VksAttribute, VksFeatureClass, VksObject, VksObjectType, VksPoint};
use jaus::stock::world_model::{Filter, Geometry, Shape, StoreConfig, VectorStore};

const OBJECTS: usize = 1_000_000;
const LAT0: f64 = 29.65;
const LON0: f64 = -82.35;
/// 50 km of latitude and of longitude at 29.65° N, in degrees.
const SPAN_LAT: f64 = 50_000.0 / 110_860.0;
const SPAN_LON: f64 = 50_000.0 / 96_760.0;
/// Metres to degrees here (for the sizes of the small objects).
const M_LAT: f64 = 1.0 / 110_860.0;
const M_LON: f64 = 1.0 / 96_760.0;

/// SplitMix64: deterministic and dependency-free.
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

fn pt(lat: f64, lon: f64) -> VksPoint {
    VksPoint {
        latitude: lat,
        longitude: lon,
    }
}

/// Half points, 30 % lines of 2-4 vertices with 5-20 m legs, 20 % polygons of 4-6
/// vertices within 3-10 m of their centre; buffers 0-5 m; four feature classes.
fn object(r: &mut Rng) -> VksObject {
    let lat = LAT0 + r.f(-SPAN_LAT / 2.0, SPAN_LAT / 2.0);
    let lon = LON0 + r.f(-SPAN_LON / 2.0, SPAN_LON / 2.0);
    let kind = r.next() % 10;
    let (object_type, points) = if kind < 5 {
        (VksObjectType::Point, vec![pt(lat, lon)])
    } else if kind < 8 {
        let n = 2 + (r.next() % 3) as usize;
        let mut p = vec![pt(lat, lon)];
        for _ in 1..n {
            let (a, d) = (r.f(0.0, std::f64::consts::TAU), r.f(5.0, 20.0));
            let (llat, llon) = (p[p.len() - 1].latitude, p[p.len() - 1].longitude);
            p.push(pt(llat + d * a.sin() * M_LAT, llon + d * a.cos() * M_LON));
        }
        (VksObjectType::Line, p)
    } else {
        let n = 4 + (r.next() % 3) as usize;
        let p = (0..n)
            .map(|i| {
                let a = i as f64 / n as f64 * std::f64::consts::TAU;
                let d = r.f(3.0, 10.0);
                pt(lat + d * a.sin() * M_LAT, lon + d * a.cos() * M_LON)
            })
            .collect();
        (VksObjectType::Polygon, p)
    };
    VksObject {
        object_type,
        buffer: Some(r.f(0.0, 5.0) as f32),
        feature_classes: vec![VksFeatureClass {
            id: (r.next() % 4) as u16,
            attribute: VksAttribute::Default,
        }],
        points,
    }
}

fn median(mut v: Vec<Duration>) -> Duration {
    v.sort();
    v[v.len() / 2]
}

fn main() {
    // `cargo bench` passes `--bench`; `cargo test --benches` runs this too: keep that
    // short.
    let quick = !std::env::args().any(|a| a == "--bench");
    let n = if quick { 20_000 } else { OBJECTS };
    let mut r = Rng(2024);
    let objects: Vec<VksObject> = (0..n).map(|_| object(&mut r)).collect();
    let vertices: usize = objects.iter().map(|o| o.points.len()).sum();

    // One object at a time (each indexed on its own), then the same objects as one
    // batch (`create_all`, indexed by bulk loading), as a Create VKS Objects message
    // carries them.
    let mut single = VectorStore::new(StoreConfig::default());
    let t = Instant::now();
    for o in &objects {
        if let Err(e) = single.create(o) {
            panic!("object refused: {e}");
        }
    }
    let one_by_one = t.elapsed();
    drop(single);
    let mut store = VectorStore::new(StoreConfig::default());
    let t = Instant::now();
    for r in store.create_all(&objects) {
        if let Err(e) = r {
            panic!("object refused: {e}");
        }
    }
    let build = t.elapsed();
    drop(objects);
    println!(
        "world_model: {} objects ({} vertices) over 50 km x 50 km",
        store.len(),
        vertices
    );
    println!(
        "  insert one by one: {:.2} s, {:.0} objects/s ({:.2} us/object)",
        one_by_one.as_secs_f64(),
        n as f64 / one_by_one.as_secs_f64(),
        one_by_one.as_secs_f64() * 1e6 / n as f64
    );
    println!(
        "  insert as one batch (bulk load): {:.2} s, {:.0} objects/s ({:.2} us/object)",
        build.as_secs_f64(),
        n as f64 / build.as_secs_f64(),
        build.as_secs_f64() * 1e6 / n as f64
    );

    // ~100 objects per query: density 400 objects/km^2 (1e6 over 2,500 km^2), so a disc
    // of 0.25 km^2 (radius 282 m) or a 500 m square.
    let density = n as f64 / 2_500.0;
    let radius = (100.0 / density / std::f64::consts::PI).sqrt() * 1_000.0;
    let side = (100.0 / density).sqrt() * 1_000.0;
    let mut regions = Vec::new();
    for i in 0..200 {
        let lat = LAT0 + r.f(-SPAN_LAT * 0.4, SPAN_LAT * 0.4);
        let lon = LON0 + r.f(-SPAN_LON * 0.4, SPAN_LON * 0.4);
        let g = if i % 2 == 0 {
            Geometry::new(Shape::Point, vec![pt(lat, lon)], radius)
        } else {
            let (h, w) = (side / 2.0 * M_LAT, side / 2.0 * M_LON);
            Geometry::new(
                Shape::Polygon,
                vec![
                    pt(lat - h, lon - w),
                    pt(lat - h, lon + w),
                    pt(lat + h, lon + w),
                    pt(lat + h, lon - w),
                ],
                0.0,
            )
        };
        regions.push(Filter {
            region: Some(g.expect("valid region")),
            ..Filter::default()
        });
    }

    let mut times = Vec::new();
    let mut found = 0usize;
    for f in &regions {
        let t = Instant::now();
        let ids = black_box(store.query(f));
        times.push(t.elapsed());
        found += ids.len();
    }
    let indexed = median(times);
    println!(
        "  region query (R*-tree): median {:.1} us over {} queries, {:.1} objects per query (disc r = {:.0} m / square {:.0} m)",
        indexed.as_secs_f64() * 1e6,
        regions.len(),
        found as f64 / regions.len() as f64,
        radius,
        side
    );

    let scans = if quick { 3 } else { 7 };
    let mut times = Vec::new();
    for f in regions.iter().take(scans) {
        let t = Instant::now();
        let ids = black_box(store.query_linear(f));
        times.push(t.elapsed());
        assert_eq!(ids, store.query(f), "index and scan disagree");
    }
    let linear = median(times);
    println!(
        "  region query (linear scan): median {:.1} ms over {} queries",
        linear.as_secs_f64() * 1e3,
        scans
    );
    println!(
        "  speed-up of the index: {:.0}x",
        linear.as_secs_f64() / indexed.as_secs_f64()
    );

    let t = Instant::now();
    let b = black_box(store.bounds(None));
    println!(
        "  bounds of every object: {:.1} ms ({:?})",
        t.elapsed().as_secs_f64() * 1e3,
        b
    );
    let t = Instant::now();
    let mut deleted = 0;
    for f in regions.iter().take(50) {
        deleted += store.delete_matching(f).map_or(0, |v| v.len());
    }
    println!(
        "  delete by region: {} objects in {:.1} ms ({:.1} us/object)",
        deleted,
        t.elapsed().as_secs_f64() * 1e3,
        t.elapsed().as_secs_f64() * 1e6 / deleted.max(1) as f64
    );
}
