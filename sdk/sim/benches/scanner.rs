//! The simulated range scanner and the Range Sensor's object grouping, per sweep
//! (issue 14): 181 beams over 180° (and 720 over 360°) against 20 obstacles, then the
//! returns grouped into objects; and a sweep taken into the world-model feed (its
//! objects placed in the local frame, tracks refreshed, nothing new to store).
//!
//! `cargo bench -p jaus-sim --bench scanner`

use std::time::Instant;

use criterion::{criterion_group, criterion_main, Criterion};
use jaus::messages::ReportGlobalPose;
use jaus::stock::environment::map_feed::{MapFeed, MapFeedConfig};
use jaus::stock::environment::range::{detections, Beam, RangeScanner};
use jaus::stock::geo::LocalFrame;
use jaus::Address;
use jaus_sim::scanner::{ScannerParams, Scene, SimScanner};
use jaus_sim::vehicle::{SimVehicle, VehicleParams};
use nalgebra::Vector2;

fn bench(c: &mut Criterion) {
    let circles = (0..20)
        .map(|i| {
            let a = i as f64 * 0.7;
            (
                Vector2::new(8.0 * a.cos(), 8.0 * a.sin()),
                0.4 + 0.05 * i as f64,
            )
        })
        .collect();
    let scene = Scene { circles };
    let mut g = c.benchmark_group("range");
    for (beams, fov) in [
        (181usize, std::f64::consts::PI),
        (720, 2.0 * std::f64::consts::PI),
    ] {
        let vehicle = SimVehicle::new(VehicleParams::default());
        let mut s = SimScanner::new(
            vehicle,
            scene.clone(),
            ScannerParams {
                beams,
                field_of_view: fov,
                ..ScannerParams::default()
            },
        );
        let mut out: Vec<Beam> = Vec::with_capacity(beams);
        let now = Instant::now();
        g.bench_function(format!("sweep_{beams}_beams_20_obstacles"), |b| {
            b.iter(|| {
                s.scan(now, &mut out);
                detections(&out, 0.3).len()
            })
        });
        let frame = LocalFrame::new(29.6436, -82.3549, 40.0);
        let mut feed = MapFeed::new(MapFeedConfig {
            origin: Some(frame),
            ..MapFeedConfig::new(Address::new(1, 1, 61, 1), Address::new(1, 1, 38, 1))
        });
        let (latitude, longitude) = frame.to_global(Vector2::zeros());
        feed.on_global_pose(
            now,
            &ReportGlobalPose {
                latitude: Some(latitude),
                longitude: Some(longitude),
                yaw: Some(0.0),
                ..Default::default()
            },
        );
        s.scan(now, &mut out);
        let found = detections(&out, 0.3);
        // The first sweep creates the tracks; the timed ones refresh them.
        feed.observe(now, &out, &found);
        g.bench_function(format!("map_feed_{beams}_beams_20_obstacles"), |b| {
            b.iter(|| feed.observe(now, &out, &found).len())
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
