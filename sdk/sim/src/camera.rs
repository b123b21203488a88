//! A simulated camera on the simulated vehicle, implementing
//! `jaus::stock::environment::camera::Cameras`: a top-down view of the ground ahead of
//! the lens, as wide as the horizontal field of view is at half [`SimCamera::reach`]
//! and as deep as the image's shape makes it with square pixels, with a 1 m grid, the
//! obstacles of the scene and the vehicle's nose at the bottom edge. The mount's pan
//! turns the view; its tilt is reported in the camera's pose but does not change a view
//! from above.

use std::time::Instant;

use nalgebra::{Rotation2, Vector2, Vector3};

use crate::scanner::Scene;
use crate::vehicle::SimVehicle;
use jaus::stock::environment::camera::{CameraSettings, CameraSpec, Cameras};
use jaus::stock::environment::image::RgbImage;

const GROUND: [u8; 3] = [104, 140, 72];
const GRID: [u8; 3] = [128, 160, 98];
const OBSTACLE: [u8; 3] = [70, 70, 76];
const EDGE: [u8; 3] = [20, 20, 24];
const VEHICLE: [u8; 3] = [214, 39, 40];

/// One camera looking at `scene` from `vehicle`.
#[derive(Debug, Clone)]
pub struct SimCamera {
    vehicle: SimVehicle,
    scene: Scene,
    specs: Vec<CameraSpec>,
    /// Twice the distance at which the view is as wide as the field of view, m.
    pub reach: f64,
}

impl SimCamera {
    /// A pan/tilt camera ("front camera", ±90° pan, ±30° tilt, 30°–90° field of view,
    /// 16×12 to 640×480 pixels, 10 frames/s) 0.5 m ahead of the reference point and
    /// 1 m up; at 90° the view is 12 m wide.
    pub fn new(vehicle: SimVehicle, scene: Scene) -> Self {
        Self {
            vehicle,
            scene,
            specs: vec![CameraSpec {
                name: "front camera".into(),
                description: "simulated pan/tilt camera, top-down view ahead".into(),
                origin: Vector3::new(0.5, 0.0, -1.0),
                pan_limit: std::f64::consts::FRAC_PI_2,
                tilt_limit: 30f64.to_radians(),
                horizontal_fov: (30f64.to_radians(), 90f64.to_radians()),
                resolution: ((16, 12), (640, 480)),
                max_frame_rate: 10,
            }],
            reach: 12.0,
        }
    }
}

impl Cameras for SimCamera {
    fn specs(&self) -> &[CameraSpec] {
        &self.specs
    }

    fn capture(&mut self, index: usize, now: Instant, s: &CameraSettings) -> Option<RgbImage> {
        let spec = self.specs.get(index)?;
        let (position, yaw) = {
            let mut v = self.vehicle.lock();
            v.advance(now);
            (v.position(), v.yaw())
        };
        let (w, h) = (usize::from(s.width), usize::from(s.height));
        if w == 0 || h == 0 {
            return None;
        }
        // The lens on the ground, looking along yaw + pan; the view is a rectangle
        // `depth` deep and as wide as the field of view is at half depth, pixels square
        // in metres where the shape allows.
        let lens = position + Rotation2::new(yaw) * Vector2::new(spec.origin.x, spec.origin.y);
        let heading = Rotation2::new(yaw + s.pan);
        let width_m = 2.0 * (self.reach / 2.0) * (s.horizontal_fov / 2.0).tan();
        let depth = width_m * h as f64 / w as f64;
        let mut img = RgbImage::filled(s.width, s.height, GROUND);
        for v in 0..h {
            let ahead = (1.0 - (v as f64 + 0.5) / h as f64) * depth;
            for u in 0..w {
                let right = ((u as f64 + 0.5) / w as f64 - 0.5) * width_m;
                let p = lens + heading * Vector2::new(ahead, right);
                let colour = self
                    .scene
                    .circles
                    .iter()
                    .find_map(|(c, r)| {
                        // Squared distances: no square root per pixel.
                        let d2 = (p - c).norm_squared();
                        let inner = (r - 0.06).max(0.0);
                        (d2 <= r * r).then_some(if d2 > inner * inner { EDGE } else { OBSTACLE })
                    })
                    .unwrap_or_else(|| {
                        let on_line = |x: f64| (x - x.round()).abs() < 0.03;
                        if on_line(p.x) || on_line(p.y) {
                            GRID
                        } else {
                            GROUND
                        }
                    });
                img.put(u, v, colour);
            }
        }
        // The vehicle's nose at the bottom centre.
        let n = (h / 16).max(1);
        for dv in 0..n {
            for du in 0..=(2 * dv) {
                img.put((w / 2 + du).saturating_sub(dv), h - n + dv, VEHICLE);
            }
        }
        Some(img)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vehicle::VehicleParams;
    use jaus::messages::ImageFormat;

    fn settings(pan: f64) -> CameraSettings {
        CameraSettings {
            width: 120,
            height: 120,
            horizontal_fov: 90f64.to_radians(),
            frame_rate: 10,
            format: ImageFormat::Png,
            pan,
            tilt: 0.0,
        }
    }

    #[test]
    fn an_obstacle_ahead_is_drawn_where_it_is() {
        // Facing north; a 1 m obstacle 8.5 m ahead of the lens (which is 0.5 m ahead
        // of the reference point), on the centre column.
        let vehicle = SimVehicle::new(VehicleParams::default());
        let scene = Scene {
            circles: vec![(Vector2::new(9.0, 0.0), 1.0)],
        };
        let mut cam = SimCamera::new(vehicle, scene);
        let img = cam.capture(0, Instant::now(), &settings(0.0)).unwrap();
        assert_eq!((img.width, img.height), (120, 120));
        // Row of 8.5 m ahead: v = (1 - 8.5/12) * 120 - 0.5 = 34.5.
        assert_eq!(img.get(60, 35), Some(OBSTACLE));
        // 3 m to the side of it is ground (or grid).
        let side = img.get(60 + 30, 35).unwrap();
        assert!(side == GROUND || side == GRID, "{side:?}");
        // Panned 90° to the right (east), the obstacle is 8.5 m to the left of a view
        // 12 m wide: out of it.
        let img = cam
            .capture(0, Instant::now(), &settings(std::f64::consts::FRAC_PI_2))
            .unwrap();
        assert!(!img.pixels.chunks(3).any(|p| p == OBSTACLE));
        assert!(cam.capture(1, Instant::now(), &settings(0.0)).is_none());
    }
}
