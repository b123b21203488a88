//! A simulated skid-steer ground vehicle that implements every hardware trait, so the
//! sensors and drivers run end to end without hardware. Time is whatever `now` the
//! callers pass: the plant integrates lazily, in fixed steps, up to the latest `now`,
//! so a run on a virtual clock is exactly reproducible (noise comes from a seeded RNG).

use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use nalgebra::{UnitQuaternion, Vector2, Vector3};
use rand::rngs::StdRng;
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

use jaus::stock::geo::{wrap_angle, LocalFrame};

use crate::lights::Lights;
use jaus::stock::hardware::{
    Actuators, GlobalPose, GlobalPoseSource, LocalPose, LocalPoseSource, OperationalData,
    VelocitySource, VelocityState, Wrench,
};

/// Parameters of the simulated vehicle.
#[derive(Debug, Clone)]
pub struct VehicleParams {
    /// Forward speed at 100 % linear effort, m/s.
    pub max_speed: f64,
    /// Yaw rate at 100 % rotational effort, rad/s.
    pub max_yaw_rate: f64,
    /// Time constant of the speed response, s.
    pub speed_lag: f64,
    /// Time constant of the yaw-rate response, s.
    pub yaw_lag: f64,
    /// Deceleration at 100 % resistive effort, m/s².
    pub max_brake: f64,
    /// Integration step.
    pub step: Duration,
    /// Standard deviation of position noise on pose reports, m (0: none).
    pub position_noise: f64,
    /// Standard deviation of heading noise, rad.
    pub heading_noise: f64,
    /// Noise seed.
    pub seed: u64,
    /// WGS 84 origin of the local frame.
    pub origin: LocalFrame,
    /// Start position (north, east), m, and heading, rad.
    pub start: (Vector2<f64>, f64),
}

impl Default for VehicleParams {
    fn default() -> Self {
        Self {
            max_speed: 2.0,
            max_yaw_rate: 1.5,
            speed_lag: 0.3,
            yaw_lag: 0.15,
            max_brake: 3.0,
            step: Duration::from_millis(10),
            position_noise: 0.0,
            heading_noise: 0.0,
            seed: 1,
            origin: LocalFrame::new(29.6436, -82.3549, 40.0),
            start: (Vector2::zeros(), 0.0),
        }
    }
}

/// The state of the plant.
#[derive(Debug)]
pub struct GroundVehicle {
    params: VehicleParams,
    t: Option<Instant>,
    position: Vector2<f64>,
    yaw: f64,
    speed: f64,
    yaw_rate: f64,
    effort: Wrench,
    rng: StdRng,
    trail: Vec<(Duration, Vector2<f64>)>,
    started: Option<Instant>,
    odometer: f64,
    lights: Lights,
}

/// Most trail points kept (one every 50 ms: over 13 hours).
const TRAIL_CAPACITY: usize = 1_000_000;

impl GroundVehicle {
    /// A vehicle at rest at `params.start`.
    pub fn new(params: VehicleParams) -> Self {
        Self {
            t: None,
            position: params.start.0,
            yaw: params.start.1,
            speed: 0.0,
            yaw_rate: 0.0,
            effort: Wrench::ZERO,
            rng: StdRng::seed_from_u64(params.seed),
            trail: Vec::new(),
            started: None,
            odometer: 0.0,
            lights: Lights::default(),
            params,
        }
    }

    /// Integrates up to `now`.
    pub fn advance(&mut self, now: Instant) {
        let Some(mut t) = self.t else {
            self.t = Some(now);
            self.started = Some(now);
            self.trail.push((Duration::ZERO, self.position));
            return;
        };
        let step = self.params.step;
        while t + step <= now {
            self.integrate(step.as_secs_f64());
            t += step;
            let since = t - self.started.unwrap_or(t);
            let last = self.trail.last().map_or(Duration::ZERO, |p| p.0);
            if since >= last + Duration::from_millis(50) && self.trail.len() < TRAIL_CAPACITY {
                self.trail.push((since, self.position));
            }
        }
        self.t = Some(t);
    }

    fn integrate(&mut self, dt: f64) {
        let p = &self.params;
        let e = &self.effort;
        let target_v = e.linear.x.clamp(-100.0, 100.0) / 100.0 * p.max_speed;
        let target_w = e.rotational.z.clamp(-100.0, 100.0) / 100.0 * p.max_yaw_rate;
        self.speed += (target_v - self.speed) * (dt / p.speed_lag).min(1.0);
        let brake = e.resistive_linear.x.clamp(0.0, 100.0) / 100.0 * p.max_brake * dt;
        self.speed = if self.speed.abs() <= brake {
            0.0
        } else {
            self.speed - brake * self.speed.signum()
        };
        self.yaw_rate += (target_w - self.yaw_rate) * (dt / p.yaw_lag).min(1.0);
        self.yaw = wrap_angle(self.yaw + self.yaw_rate * dt);
        let d = Vector2::new(self.yaw.cos(), self.yaw.sin()) * self.speed * dt;
        self.odometer += d.norm();
        self.position += d;
    }

    /// True position (north, east), m.
    pub fn position(&self) -> Vector2<f64> {
        self.position
    }

    /// True heading, rad.
    pub fn yaw(&self) -> f64 {
        self.yaw
    }

    /// True forward speed, m/s.
    pub fn speed(&self) -> f64 {
        self.speed
    }

    /// The effort applied last.
    pub fn effort(&self) -> Wrench {
        self.effort
    }

    /// Distance driven, m: the path length integrated from the model's motion (|speed|
    /// × step, forward and reverse alike), so it never decreases.
    pub fn odometer(&self) -> f64 {
        self.odometer
    }

    /// Its lamps ([`crate::lights`]): which are on.
    pub fn lights(&self) -> &Lights {
        &self.lights
    }

    /// Its lamps, to switch them.
    pub fn lights_mut(&mut self) -> &mut Lights {
        &mut self.lights
    }

    /// The driven trajectory: (time since start, position) every 50 ms.
    pub fn trail(&self) -> &[(Duration, Vector2<f64>)] {
        &self.trail
    }

    /// The parameters.
    pub fn params(&self) -> &VehicleParams {
        &self.params
    }

    fn noisy(&mut self, sigma: f64) -> f64 {
        if sigma > 0.0 {
            Normal::new(0.0, sigma).map_or(0.0, |n| n.sample(&mut self.rng))
        } else {
            0.0
        }
    }

    fn measured(&mut self) -> (Vector2<f64>, f64) {
        let (pn, hn) = (self.params.position_noise, self.params.heading_noise);
        let p = self.position + Vector2::new(self.noisy(pn), self.noisy(pn));
        let y = wrap_angle(self.yaw + self.noisy(hn));
        (p, y)
    }
}

impl VehicleParams {
    /// What the model says of the platform, as RA 3.3 specifications: its top speed and
    /// yaw rate at full effort, and a turning radius of 0 (it turns in place, as a
    /// skid-steered vehicle does). The model has no body, so no dimensions are given.
    pub fn specifications(&self) -> jaus::messages::ReportPlatformSpecifications {
        jaus::messages::ReportPlatformSpecifications {
            platform_name: Some("jaus sim".into()),
            turning_radius: Some(0.0),
            maximum_velocity_x: Some(self.max_speed),
            maximum_yaw_rate: Some(self.max_yaw_rate),
            ..Default::default()
        }
    }
}

/// A shared handle to a simulated vehicle: clone it into the primitive driver and the
/// sensors. (One process, one virtual clock: the mutex is never contended for long.)
#[derive(Debug, Clone)]
pub struct SimVehicle(Arc<Mutex<GroundVehicle>>);

impl SimVehicle {
    /// A new simulated vehicle.
    pub fn new(params: VehicleParams) -> Self {
        SimVehicle(Arc::new(Mutex::new(GroundVehicle::new(params))))
    }

    /// The plant, advanced to nothing (read its state).
    pub fn lock(&self) -> MutexGuard<'_, GroundVehicle> {
        // A panic while holding the lock cannot leave the plant half-updated in a way
        // that matters to a simulation; keep going with the data.
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }
}

impl Actuators for SimVehicle {
    fn apply(&mut self, now: Instant, effort: &Wrench) {
        let mut v = self.lock();
        v.advance(now);
        v.effort = *effort;
    }

    /// The model's odometer (the distance it has driven, integrated up to `now`); it has
    /// no engine, battery, fuel or oil, so those are absent.
    fn operational_data(&mut self, now: Instant) -> Option<OperationalData> {
        let mut v = self.lock();
        v.advance(now);
        Some(OperationalData {
            odometer: Some(v.odometer),
            ..OperationalData::default()
        })
    }
}

impl GlobalPoseSource for SimVehicle {
    fn global_pose(&mut self, now: Instant) -> Option<GlobalPose> {
        let mut v = self.lock();
        v.advance(now);
        let (p, yaw) = v.measured();
        let (latitude, longitude) = v.params.origin.to_global(p);
        Some(GlobalPose {
            latitude,
            longitude,
            elevation: v.params.origin.elevation,
            attitude: UnitQuaternion::from_euler_angles(0.0, 0.0, yaw),
            position_rms: v.params.position_noise,
        })
    }
}

impl LocalPoseSource for SimVehicle {
    fn local_pose(&mut self, now: Instant) -> Option<LocalPose> {
        let mut v = self.lock();
        v.advance(now);
        let (p, yaw) = v.measured();
        Some(LocalPose {
            position: Vector3::new(p.x, p.y, 0.0),
            attitude: UnitQuaternion::from_euler_angles(0.0, 0.0, yaw),
        })
    }
}

impl VelocitySource for SimVehicle {
    fn velocity(&mut self, now: Instant) -> Option<VelocityState> {
        let mut v = self.lock();
        v.advance(now);
        Some(VelocityState {
            linear: Vector3::new(v.speed, 0.0, 0.0),
            angular: Vector3::new(0.0, 0.0, v.yaw_rate),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn full_effort_reaches_max_speed_and_turns_at_max_rate() {
        let t0 = Instant::now();
        let mut v = SimVehicle::new(VehicleParams::default());
        let w = Wrench {
            linear: Vector3::new(50.0, 0.0, 0.0),
            rotational: Vector3::new(0.0, 0.0, 100.0),
            ..Wrench::ZERO
        };
        v.apply(t0, &w);
        v.lock().advance(t0 + Duration::from_secs(3));
        let g = v.lock();
        assert!((g.speed() - 1.0).abs() < 0.01, "{}", g.speed());
        assert!((g.yaw_rate - 1.5).abs() < 0.01);
        // A circle of radius v/ω = 0.667 m: the vehicle stays near it.
        assert!(g.position().norm() < 1.4);
    }

    #[test]
    fn brakes_stop_the_vehicle_and_noise_is_seeded() {
        let t0 = Instant::now();
        let params = VehicleParams {
            position_noise: 0.1,
            ..Default::default()
        };
        let mut a = SimVehicle::new(params.clone());
        let mut b = SimVehicle::new(params);
        for v in [&mut a, &mut b] {
            v.apply(
                t0,
                &Wrench {
                    linear: Vector3::new(100.0, 0.0, 0.0),
                    ..Wrench::ZERO
                },
            );
            v.apply(t0 + Duration::from_secs(2), &Wrench::brake());
        }
        let pa = a.local_pose(t0 + Duration::from_secs(4)).unwrap();
        let pb = b.local_pose(t0 + Duration::from_secs(4)).unwrap();
        assert_eq!(pa, pb, "same seed, same noise");
        assert_eq!(a.lock().speed(), 0.0);
    }

    #[test]
    fn odometer_counts_the_distance_driven_forward_and_back() {
        let t0 = Instant::now();
        let mut v = SimVehicle::new(VehicleParams::default());
        let at = |s: u64| t0 + Duration::from_secs(s);
        let effort = |x: f64| Wrench {
            linear: Vector3::new(x, 0.0, 0.0),
            ..Wrench::ZERO
        };
        assert_eq!(v.operational_data(t0).unwrap().odometer, Some(0.0));
        v.apply(t0, &effort(50.0));
        v.apply(at(10), &effort(-50.0));
        let forward = v.operational_data(at(10)).unwrap().odometer.unwrap();
        let ahead = v.lock().position().x;
        v.apply(at(20), &Wrench::brake());
        let total = v.operational_data(at(22)).unwrap().odometer.unwrap();
        let back = ahead - v.lock().position().x;
        assert!((forward - ahead).abs() < 1e-9, "{forward} vs {ahead}");
        assert!(forward > 9.0, "{forward}");
        // Reversing adds to it: the distance driven, not the displacement.
        assert!(back > 5.0, "{back}");
        assert!(total >= forward + back, "{total} < {forward} + {back}");
        assert!(total > v.lock().position().x.abs() + 10.0, "{total}");
        let d = v.operational_data(at(22)).unwrap();
        assert_eq!(d.engine_temperature.or(d.battery_voltage), None);
    }
}
