//! The simulated camera and the Visual Sensor's encodings, per frame (issue 14): the
//! top-down view rendered at 640×480 and 320×240 with 20 obstacles in the scene, then
//! encoded as PNG (and PPM, a header and a copy).
//!
//! `cargo bench -p jaus-sim --bench camera`

use std::time::Instant;

use criterion::{criterion_group, criterion_main, Criterion};
use jaus::messages::ImageFormat;
use jaus::stock::environment::camera::{CameraSettings, Cameras};
use jaus::stock::environment::image::encode;
use jaus_sim::camera::SimCamera;
use jaus_sim::scanner::Scene;
use jaus_sim::vehicle::{SimVehicle, VehicleParams};
use nalgebra::Vector2;

fn bench(c: &mut Criterion) {
    let circles = (0..20)
        .map(|i| {
            let a = i as f64 * 0.7;
            (
                Vector2::new(6.0 + 4.0 * a.cos(), 4.0 * a.sin()),
                0.3 + 0.03 * i as f64,
            )
        })
        .collect();
    let mut cam = SimCamera::new(SimVehicle::new(VehicleParams::default()), Scene { circles });
    let now = Instant::now();
    let mut g = c.benchmark_group("camera");
    g.sample_size(20);
    for (w, h) in [(640u16, 480u16), (320, 240)] {
        let settings = CameraSettings {
            width: w,
            height: h,
            ..CameraSettings::defaults_for(&cam.specs()[0])
        };
        g.bench_function(format!("render_{w}x{h}"), |b| {
            b.iter(|| cam.capture(0, now, &settings).map(|i| i.pixels.len()))
        });
        let Some(img) = cam.capture(0, now, &settings) else {
            return;
        };
        for f in [ImageFormat::Png, ImageFormat::Ppm] {
            let bytes = encode(&img, f).map(|d| d.len()).unwrap_or(0);
            g.bench_function(format!("encode_{f:?}_{w}x{h}_{bytes}_bytes"), |b| {
                b.iter(|| encode(&img, f).map(|d| d.len()))
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
