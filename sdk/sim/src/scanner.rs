//! A simulated scanning range finder on the simulated vehicle, implementing
//! `jaus::stock::environment::range::RangeScanner`: beams spread over a field of view
//! from a mount point on the vehicle, ray-cast against the circular obstacles of a
//! scene (local frame: x north, y east), with seeded range noise.

use std::sync::{Arc, Mutex};
use std::time::Instant;

use nalgebra::{Rotation2, Vector2};
use rand::rngs::StdRng;
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

use crate::vehicle::SimVehicle;
use jaus::stock::environment::range::{Beam, RangeScanner, ScannerSpec};

/// Obstacles of the simulated world: circles (centre in the local frame, radius), m.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Scene {
    /// The circles.
    pub circles: Vec<(Vector2<f64>, f64)>,
}

/// The scanner's geometry and noise.
#[derive(Debug, Clone, PartialEq)]
pub struct ScannerParams {
    /// Number of beams (evenly spread over the field of view, first on the left).
    pub beams: usize,
    /// Field of view, rad, centred on the mount's forward direction.
    pub field_of_view: f64,
    /// Farthest return, m.
    pub max_range: f64,
    /// Where it sits on the vehicle: forward and right of the reference point, m.
    pub mount: Vector2<f64>,
    /// Its yaw relative to the vehicle, rad (positive to the right).
    pub mount_yaw: f64,
    /// Range noise (standard deviation, m).
    pub noise: f64,
    /// Seed of the noise.
    pub seed: u64,
}

/// 181 beams over 180°, 20 m, at the vehicle's reference point, no noise.
impl Default for ScannerParams {
    fn default() -> Self {
        Self {
            beams: 181,
            field_of_view: std::f64::consts::PI,
            max_range: 20.0,
            mount: Vector2::zeros(),
            mount_yaw: 0.0,
            noise: 0.0,
            seed: 1,
        }
    }
}

#[derive(Debug)]
struct State {
    params: ScannerParams,
    scene: Scene,
    rng: StdRng,
}

/// A scanner on `vehicle` looking at a scene (clone the handle for each user: the
/// Range Sensor and the Reflexive Driver's obstacle source share one scanner).
#[derive(Debug, Clone)]
pub struct SimScanner {
    vehicle: SimVehicle,
    state: Arc<Mutex<State>>,
}

impl SimScanner {
    /// On `vehicle`, looking at `scene`.
    pub fn new(vehicle: SimVehicle, scene: Scene, params: ScannerParams) -> Self {
        Self {
            vehicle,
            state: Arc::new(Mutex::new(State {
                rng: StdRng::seed_from_u64(params.seed),
                params,
                scene,
            })),
        }
    }

    /// The scene as it is now.
    pub fn scene(&self) -> Scene {
        self.state
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .scene
            .clone()
    }

    /// Adds an obstacle to the scene (one the world model may not know about).
    pub fn add_obstacle(&self, centre: Vector2<f64>, radius: f64) {
        let mut s = self.state.lock().unwrap_or_else(|e| e.into_inner());
        s.scene.circles.push((centre, radius));
    }
}

/// Distance along the unit ray `o + t·d` to the first point of circle (`c`, `r`), if
/// ahead of `o`.
pub fn ray_circle(o: Vector2<f64>, d: Vector2<f64>, c: Vector2<f64>, r: f64) -> Option<f64> {
    let oc = c - o;
    let along = oc.dot(&d);
    let disc = along * along - (oc.norm_squared() - r * r);
    if disc < 0.0 {
        return None;
    }
    let root = disc.sqrt();
    let t = if along - root >= 0.0 {
        along - root
    } else {
        along + root
    };
    (t >= 0.0).then_some(t)
}

impl RangeScanner for SimScanner {
    fn scan(&mut self, now: Instant, out: &mut Vec<Beam>) -> bool {
        let (position, yaw) = {
            let mut v = self.vehicle.lock();
            v.advance(now);
            (v.position(), v.yaw())
        };
        let mut s = self.state.lock().unwrap_or_else(|e| e.into_inner());
        let s = &mut *s;
        let p = &s.params;
        out.clear();
        let origin = position + Rotation2::new(yaw) * p.mount;
        let noise = Normal::new(0.0, p.noise.max(0.0)).ok();
        let n = p.beams.max(1);
        for i in 0..n {
            let bearing = if n == 1 {
                p.mount_yaw
            } else {
                p.mount_yaw - p.field_of_view / 2.0 + p.field_of_view * i as f64 / (n - 1) as f64
            };
            let a = yaw + bearing;
            let d = Vector2::new(a.cos(), a.sin());
            let hit = s
                .scene
                .circles
                .iter()
                .filter_map(|(c, r)| ray_circle(origin, d, *c, *r))
                .min_by(f64::total_cmp)
                .filter(|t| *t <= p.max_range)
                .map(|t| (t + noise.map_or(0.0, |n| n.sample(&mut s.rng))).max(0.0));
            out.push(Beam {
                bearing,
                range: hit,
            });
        }
        true
    }

    fn spec(&self) -> Option<ScannerSpec> {
        let s = self.state.lock().unwrap_or_else(|e| e.into_inner());
        let p = &s.params;
        let half = if p.beams > 1 {
            p.field_of_view / 2.0
        } else {
            0.0
        };
        Some(ScannerSpec {
            first_bearing: p.mount_yaw - half,
            last_bearing: p.mount_yaw + half,
            beams: p.beams.max(1),
            max_range: p.max_range,
            range_noise: p.noise.max(0.0),
            mount: (p.mount.x, p.mount.y),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vehicle::VehicleParams;
    use jaus::stock::drivers::ObstacleSource;
    use jaus::stock::environment::range::{detections, ScanObstacles};

    fn scanner_at(yaw: f64, circles: Vec<(Vector2<f64>, f64)>) -> SimScanner {
        let vehicle = SimVehicle::new(VehicleParams {
            start: (Vector2::zeros(), yaw),
            ..VehicleParams::default()
        });
        SimScanner::new(vehicle, Scene { circles }, ScannerParams::default())
    }

    #[test]
    fn ranges_match_hand_computed_geometry() {
        // A 1 m circle 5 m ahead (north): the centre beam hits at 4 m; a beam at
        // bearing b hits at 5 cos b - sqrt(1 - 25 sin² b).
        let mut s = scanner_at(0.0, vec![(Vector2::new(5.0, 0.0), 1.0)]);
        let mut beams = Vec::new();
        assert!(s.scan(Instant::now(), &mut beams));
        assert_eq!(beams.len(), 181);
        let centre = beams[90];
        assert!(centre.bearing.abs() < 1e-12);
        assert!((centre.range.unwrap() - 4.0).abs() < 1e-12);
        for b in &beams {
            let sin = b.bearing.sin();
            let expected = (1.0 - 25.0 * sin * sin >= 0.0 && b.bearing.cos() > 0.0)
                .then(|| 5.0 * b.bearing.cos() - (1.0 - 25.0 * sin * sin).sqrt());
            match (b.range, expected) {
                (Some(r), Some(e)) => assert!((r - e).abs() < 1e-9, "{b:?} vs {e}"),
                (None, None) => {}
                other => panic!("{b:?}: {other:?}"),
            }
        }
        // Facing east, an obstacle 5 m east is ahead; one 5 m north is on the left.
        let mut s = scanner_at(
            std::f64::consts::FRAC_PI_2,
            vec![(Vector2::new(0.0, 5.0), 1.0), (Vector2::new(5.0, 0.0), 0.5)],
        );
        s.scan(Instant::now(), &mut beams);
        assert!((beams[90].range.unwrap() - 4.0).abs() < 1e-12);
        let d = detections(&beams, 0.3);
        assert_eq!(d.len(), 2);
        let left = d.iter().find(|d| d.bearing < 0.0).unwrap();
        assert!((left.range - 4.5).abs() < 1e-9 && (left.bearing + FRAC_PI_2).abs() < 1e-9);
    }

    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn the_obstacle_source_sees_only_the_corridor_ahead() {
        let s = scanner_at(0.0, vec![(Vector2::new(3.0, 2.0), 0.5)]);
        let mut o = ScanObstacles::new(s.clone(), 1.0);
        // 2 m to the side of a 1 m corridor: nothing ahead.
        assert_eq!(o.obstacle_distance(Instant::now()), None);
        // One added straight ahead (not in any map) is seen.
        s.add_obstacle(Vector2::new(6.0, 0.0), 0.5);
        let d = o.obstacle_distance(Instant::now()).unwrap();
        assert!((d - 5.5).abs() < 0.05, "{d}");
    }
}
