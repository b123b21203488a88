//! A simulated serial arm implementing the manipulator hardware traits of
//! `jaus::stock::manipulator::hardware`, on the caller's (virtual or real) clock.
//!
//! Each joint is driven by its actuator (effort percent × the joint's maximum force or
//! torque) against its inertia, viscous and Coulomb friction and gravity: point masses
//! sit at the joint frames' origins and at the tool point, and their weight (along
//! vehicle z, which points down) acts on every joint through the transposed Jacobian of
//! its point. Integration is semi-implicit Euler in fixed 1 ms steps up to the time asked
//! for, so a run is deterministic for a seed. Joint rates are limited to the chain's
//! maxima and the positions stop hard at the joint limits. The sensors add seeded
//! Gaussian noise.

use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rand::rngs::StdRng;
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};

use jaus::stock::manipulator::hardware::{JointActuators, JointSensors, JointState};
use jaus::stock::manipulator::hold::{GravityModel, HoldConfig, HoldingController};
use jaus::stock::manipulator::kinematics::{Chain, Joint, JointKind};
use jaus::stock::manipulator::servo::ServoGains;

/// Parameters of a simulated arm (one entry per joint in every list).
#[derive(Debug, Clone)]
pub struct ArmParams {
    /// The arm's kinematics.
    pub chain: Chain,
    /// Force (N) or torque (N·m) at 100 % effort.
    pub max_effort: Vec<f64>,
    /// Effective inertia (kg·m² or kg).
    pub inertia: Vec<f64>,
    /// Viscous friction (N·m·s/rad or N·s/m).
    pub viscous: Vec<f64>,
    /// Coulomb friction (N·m or N).
    pub coulomb: Vec<f64>,
    /// Point mass at each joint frame's origin, kg (index 0 is at the base joint and
    /// never moves the others).
    pub link_mass: Vec<f64>,
    /// Point mass at the tool point, kg.
    pub tool_mass: f64,
    /// The tool point the tool mass sits at (end-effector frame, m).
    pub tool: Vector3<f64>,
    /// Whether gravity acts.
    pub gravity: bool,
    /// Joint position noise (standard deviation, rad or m).
    pub position_noise: f64,
    /// Joint velocity noise (standard deviation, rad/s or m/s).
    pub velocity_noise: f64,
    /// Seed of the noise.
    pub seed: u64,
    /// Joint positions at the start.
    pub initial: Vec<f64>,
}

impl ArmParams {
    /// A 6-axis arm of the PUMA layout (modified DH: α = 0, −90°, 0, −90°, 90°, −90°;
    /// upper arm 0.40 m, forearm 0.40 m with a 0.05 m elbow offset, 0.08 m flange), its
    /// base at the vehicle origin with z up (a half turn about vehicle x). Reach about
    /// 0.85 m; joint rates 1.5 rad/s (arm) and 2.5 rad/s (wrist); holding the arm out
    /// against gravity takes under 40 % effort.
    pub fn six_axis() -> Self {
        use std::f64::consts::FRAC_PI_2;
        let r = Joint::revolute;
        let chain = Chain::new(
            vec![
                r(0.0, 0.0, 0.0, -3.0, 3.0, 1.5),
                r(0.0, -FRAC_PI_2, 0.0, -3.0, 1.0, 1.5),
                r(0.40, 0.0, 0.0, -1.0, 3.0, 1.5),
                r(0.05, -FRAC_PI_2, 0.40, -3.0, 3.0, 2.5),
                r(0.0, FRAC_PI_2, 0.0, -2.0, 2.0, 2.5),
                r(0.0, -FRAC_PI_2, 0.08, -3.0, 3.0, 2.5),
            ],
            Isometry3::from_parts(
                Translation3::identity(),
                UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI),
            ),
            Vector3::zeros(),
        )
        .expect("the default arm is valid");
        Self {
            chain,
            max_effort: vec![80.0, 100.0, 40.0, 10.0, 10.0, 10.0],
            inertia: vec![1.5, 1.5, 0.5, 0.1, 0.1, 0.1],
            viscous: vec![2.0, 2.0, 1.0, 0.2, 0.2, 0.2],
            coulomb: vec![1.0, 1.0, 0.5, 0.1, 0.1, 0.1],
            link_mass: vec![0.0, 0.0, 4.0, 2.0, 0.5, 0.3],
            tool_mass: 0.5,
            tool: Vector3::new(0.0, 0.0, 0.1),
            gravity: true,
            position_noise: 0.0,
            velocity_noise: 0.0,
            seed: 1,
            initial: vec![0.0, -0.6, 1.4, 0.0, 0.8, 0.0],
        }
    }

    /// Defaults for any chain: 50 N·m (or N) per joint, unit inertia, light friction,
    /// 1 kg at each joint frame beyond the first, gravity on, no noise, the middle of
    /// the ranges to start.
    pub fn from_chain(chain: Chain) -> Self {
        let n = chain.dof();
        Self {
            initial: chain.mid_range(),
            chain,
            max_effort: vec![50.0; n],
            inertia: vec![1.0; n],
            viscous: vec![1.0; n],
            coulomb: vec![0.2; n],
            link_mass: (0..n).map(|i| if i == 0 { 0.0 } else { 1.0 }).collect(),
            tool_mass: 0.0,
            tool: Vector3::zeros(),
            gravity: true,
            position_noise: 0.0,
            velocity_noise: 0.0,
            seed: 1,
        }
    }
}

impl ArmParams {
    /// The arm's weight as a Primitive Manipulator's holding controller models it: these
    /// masses, tool point and maximum efforts (no gravity when `gravity` is off).
    pub fn gravity_model(&self) -> GravityModel {
        GravityModel {
            link_mass: self.link_mass.clone(),
            tool_mass: self.tool_mass,
            tool: self.tool,
            max_effort: self.max_effort.clone(),
            gravity: if self.gravity {
                Vector3::new(0.0, 0.0, G)
            } else {
                Vector3::zeros()
            },
        }
    }
}

/// Standard gravity, m/s².
const G: f64 = jaus::stock::manipulator::hold::STANDARD_GRAVITY;
/// Integration step.
const STEP: Duration = Duration::from_millis(1);

/// The simulated arm's state.
#[derive(Debug)]
pub struct ArmSim {
    params: ArmParams,
    q: Vec<f64>,
    qd: Vec<f64>,
    torque: Vec<f64>,
    efforts: Vec<f64>,
    now: Option<Instant>,
    rng: StdRng,
    frames: Vec<Isometry3<f64>>,
    garbage: u64,
}

impl ArmSim {
    fn new(params: ArmParams) -> Self {
        let n = params.chain.dof();
        let mut q = params.initial.clone();
        q.resize(n, 0.0);
        params.chain.clamp(&mut q);
        Self {
            rng: StdRng::seed_from_u64(params.seed),
            q,
            qd: vec![0.0; n],
            torque: vec![0.0; n],
            efforts: vec![0.0; n],
            now: None,
            frames: Vec::with_capacity(n),
            garbage: 0,
            params,
        }
    }

    /// The arm's kinematics.
    pub fn chain(&self) -> &Chain {
        &self.params.chain
    }

    /// The arm's parameters.
    pub fn params(&self) -> &ArmParams {
        &self.params
    }

    /// True joint positions.
    pub fn positions(&self) -> &[f64] {
        &self.q
    }

    /// True joint velocities.
    pub fn velocities(&self) -> &[f64] {
        &self.qd
    }

    /// The efforts applied last (percent).
    pub fn efforts(&self) -> &[f64] {
        &self.efforts
    }

    /// Effort commands that were not usable (wrong length, not finite) and were
    /// replaced by zero.
    pub fn garbage(&self) -> u64 {
        self.garbage
    }

    /// The true pose of the tool point `tool` (end-effector frame) in the vehicle frame.
    pub fn tool_pose(&self, tool: &Vector3<f64>) -> Isometry3<f64> {
        self.params.chain.forward(&self.q) * Translation3::from(*tool)
    }

    /// Moves the simulation to `now`.
    pub fn advance(&mut self, now: Instant) {
        let Some(mut t) = self.now else {
            self.now = Some(now);
            return;
        };
        while t + STEP <= now {
            self.step(STEP.as_secs_f64());
            t += STEP;
        }
        self.now = Some(t);
    }

    /// Generalised gravity force on every joint at the current positions, into `out`.
    fn gravity(&mut self, out: &mut [f64]) {
        out.iter_mut().for_each(|v| *v = 0.0);
        if !self.params.gravity {
            return;
        }
        let chain = &self.params.chain;
        chain.frames(&self.q, &mut self.frames);
        let weight = Vector3::new(0.0, 0.0, G); // vehicle z points down
        let tool_point = self.frames.last().map(|f| {
            (f * Translation3::from(self.params.tool))
                .translation
                .vector
        });
        let points = self
            .frames
            .iter()
            .enumerate()
            .map(|(k, f)| {
                (
                    k,
                    f.translation.vector,
                    self.params.link_mass.get(k).copied().unwrap_or(0.0),
                )
            })
            .chain(tool_point.map(|p| (self.frames.len() - 1, p, self.params.tool_mass)));
        for (k, p, m) in points {
            if m == 0.0 {
                continue;
            }
            let force = weight * m;
            // Joints up to k move the point (joint k's own rotation moves points off its
            // axis only).
            for (i, joint) in chain.joints.iter().enumerate().take(k + 1) {
                let z = self.frames[i].rotation * Vector3::z();
                let o = self.frames[i].translation.vector;
                let jv = match joint.kind {
                    JointKind::Revolute => z.cross(&(p - o)),
                    JointKind::Prismatic => z,
                };
                out[i] += jv.dot(&force);
            }
        }
    }

    fn step(&mut self, dt: f64) {
        let n = self.q.len();
        let mut gravity = vec![0.0; n];
        self.gravity(&mut gravity);
        let p = &self.params;
        #[allow(clippy::needless_range_loop)] // eight parallel per-joint lists
        for j in 0..n {
            let motor = self.efforts[j] / 100.0 * p.max_effort[j];
            let v = self.qd[j];
            let friction =
                p.viscous[j] * v + p.coulomb[j] * v.signum() * (v.abs() > 1e-6) as u8 as f64;
            let net = motor + gravity[j] - friction;
            self.torque[j] = motor;
            let joint = &p.chain.joints[j];
            let mut v = v + net / p.inertia[j] * dt;
            v = v.clamp(-joint.max_rate, joint.max_rate);
            let mut q = self.q[j] + v * dt;
            if q <= joint.min {
                q = joint.min;
                v = v.max(0.0);
            } else if q >= joint.max {
                q = joint.max;
                v = v.min(0.0);
            }
            self.q[j] = q;
            self.qd[j] = v;
        }
    }
}

/// A shared handle to one simulated arm (clone it for each component).
#[derive(Debug, Clone)]
pub struct SimArm(Arc<Mutex<ArmSim>>);

impl SimArm {
    /// A new arm.
    pub fn new(params: ArmParams) -> Self {
        SimArm(Arc::new(Mutex::new(ArmSim::new(params))))
    }

    /// Locks the arm's state (recovering it if a holder panicked).
    pub fn lock(&self) -> MutexGuard<'_, ArmSim> {
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// A holding controller for a Primitive Manipulator over this arm: its joint sensors,
    /// its weight ([`ArmParams::gravity_model`]) and the default servo gains.
    pub fn holding_controller(&self) -> HoldingController {
        let gravity = Some(self.lock().params().gravity_model());
        HoldingController::new(
            self.clone(),
            HoldConfig {
                gains: ServoGains::default(),
                gravity,
            },
        )
    }
}

impl JointActuators for SimArm {
    fn apply_efforts(&mut self, now: Instant, efforts: &[f64]) {
        let mut a = self.lock();
        a.advance(now);
        let n = a.efforts.len();
        let usable = efforts.len() == n && efforts.iter().all(|e| e.is_finite());
        if !usable {
            a.garbage += 1;
        }
        for (j, e) in a.efforts.iter_mut().enumerate() {
            *e = if usable {
                efforts[j].clamp(-100.0, 100.0)
            } else {
                0.0
            };
        }
    }
}

impl JointSensors for SimArm {
    fn read_joints(&mut self, now: Instant, out: &mut JointState) -> bool {
        let mut a = self.lock();
        a.advance(now);
        let a = &mut *a;
        let pn = Normal::new(0.0, a.params.position_noise.max(0.0)).ok();
        let vn = Normal::new(0.0, a.params.velocity_noise.max(0.0)).ok();
        out.positions.clear();
        out.velocities.clear();
        out.efforts.clear();
        for j in 0..a.q.len() {
            let noise_p = pn.map_or(0.0, |d| d.sample(&mut a.rng));
            let noise_v = vn.map_or(0.0, |d| d.sample(&mut a.rng));
            out.positions.push(a.q[j] + noise_p);
            out.velocities.push(a.qd[j] + noise_v);
            out.efforts.push(a.torque[j]);
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn run(arm: &SimArm, t0: Instant, seconds: f64, mut control: impl FnMut(&ArmSim) -> Vec<f64>) {
        let mut handle = arm.clone();
        for i in 1..=(seconds * 100.0) as u64 {
            let now = t0 + Duration::from_millis(10 * i);
            let e = control(&arm.lock());
            handle.apply_efforts(now, &e);
        }
    }

    #[test]
    fn without_effort_the_arm_sags_to_its_stops_and_stays_within_limits() {
        let arm = SimArm::new(ArmParams::six_axis());
        let t0 = Instant::now();
        let before = arm.lock().tool_pose(&Vector3::zeros()).translation.vector;
        run(&arm, t0, 5.0, |_| vec![0.0; 6]);
        let a = arm.lock();
        assert!(a.chain().within_limits(a.positions()));
        let after = a.tool_pose(&Vector3::zeros()).translation.vector;
        // Vehicle z points down: the flange fell.
        assert!(after.z > before.z + 0.05, "{before} -> {after}");
    }

    #[test]
    fn a_constant_effort_without_gravity_reaches_the_rate_limit() {
        let mut p = ArmParams::six_axis();
        p.gravity = false;
        let arm = SimArm::new(p);
        run(&arm, Instant::now(), 0.5, |_| {
            vec![100.0, 0.0, 0.0, 0.0, 0.0, 0.0]
        });
        let a = arm.lock();
        assert!(
            (a.velocities()[0] - 1.5).abs() < 1e-9,
            "{:?}",
            a.velocities()
        );
        assert!(a.velocities()[1..].iter().all(|v| v.abs() < 1e-9));
    }

    #[test]
    fn a_pid_holds_a_pose_against_gravity() {
        let arm = SimArm::new(ArmParams::six_axis());
        let target = [0.3, -0.8, 1.2, 0.2, 0.6, -0.4];
        let mut integral = [0.0; 6];
        run(&arm, Instant::now(), 6.0, |a| {
            (0..6)
                .map(|j| {
                    let e = target[j] - a.positions()[j];
                    integral[j] += e * 0.01;
                    (900.0 * e + 1500.0 * integral[j] - 60.0 * a.velocities()[j])
                        .clamp(-100.0, 100.0)
                })
                .collect()
        });
        let a = arm.lock();
        #[allow(clippy::needless_range_loop)]
        for j in 0..6 {
            assert!(
                (a.positions()[j] - target[j]).abs() < 1e-3,
                "joint {j}: {:?}",
                a.positions()
            );
        }
        // Holding the arm out takes well under full effort.
        assert!(
            a.efforts().iter().all(|e| e.abs() < 60.0),
            "{:?}",
            a.efforts()
        );
    }

    #[test]
    fn the_same_seed_gives_the_same_run_and_garbage_is_zeroed() {
        let mut p = ArmParams::six_axis();
        p.position_noise = 0.001;
        p.seed = 9;
        let trace = |p: ArmParams| {
            let mut arm = SimArm::new(p);
            let t0 = Instant::now();
            let mut out = JointState::default();
            let mut seen = Vec::new();
            for i in 1..100u64 {
                let now = t0 + Duration::from_millis(10 * i);
                arm.apply_efforts(now, &[10.0, -5.0, 3.0, 0.0, 1.0, 0.0]);
                arm.read_joints(now, &mut out);
                seen.push(out.positions.clone());
            }
            seen
        };
        assert_eq!(trace(p.clone()), trace(p.clone()));
        let mut arm = SimArm::new(p);
        let now = Instant::now();
        arm.apply_efforts(now, &[f64::NAN, 1e9, 0.0, 0.0, 0.0, 0.0]);
        arm.apply_efforts(now, &[1.0]);
        assert_eq!(arm.lock().garbage(), 2);
        assert!(arm.lock().efforts().iter().all(|e| *e == 0.0));
        arm.apply_efforts(now, &[1e9, -1e9, 0.0, 0.0, 0.0, 0.0]);
        assert_eq!(arm.lock().efforts()[..2], [100.0, -100.0]);
    }
}
