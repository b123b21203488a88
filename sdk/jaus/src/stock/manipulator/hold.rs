//! The Primitive Manipulator's holding controller: while no driver commands the arm (at
//! start, between drivers, after a driver's commands stopped), it holds the joints where
//! the last command left them, with the arm's weight compensated from a [`GravityModel`]
//! and a joint servo ([`JointServo`]) on the remaining error. Handing the arm from a
//! driver to the hold and back is bumpless: the hold starts from the efforts applied last
//! (its integral term takes what the model does not explain), and a driver starts from
//! the efforts the Primitive Manipulator reports (Query Joint Efforts).

use std::time::Instant;

use nalgebra::{Isometry3, Translation3, Vector3};

use super::hardware::{JointSensors, JointState};
use super::kinematics::{Chain, JointKind};
use super::servo::{JointServo, ServoGains};

/// Standard gravity, m/s².
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// The arm's weight as point masses: one at each joint frame's origin and one at the
/// tool point, and what 100 % effort means at each joint.
#[derive(Debug, Clone, PartialEq)]
pub struct GravityModel {
    /// Point mass at each joint frame's origin, kg (first joint first).
    pub link_mass: Vec<f64>,
    /// Point mass at the tool point, kg.
    pub tool_mass: f64,
    /// Where the tool mass sits (end-effector frame, m).
    pub tool: Vector3<f64>,
    /// Force (N) or torque (N·m) at 100 % effort, per joint.
    pub max_effort: Vec<f64>,
    /// Gravitational acceleration in the vehicle frame, m/s² (vehicle z points down:
    /// `(0, 0, 9.80665)` on a level vehicle).
    pub gravity: Vector3<f64>,
}

impl GravityModel {
    /// The efforts (percent of each joint's maximum, not clamped) that balance the arm's
    /// weight at joint positions `q`, into `out` (one per joint). Joints without a usable
    /// maximum effort get 0. `frames` is scratch space.
    pub fn efforts(
        &self,
        chain: &Chain,
        q: &[f64],
        frames: &mut Vec<Isometry3<f64>>,
        out: &mut [f64],
    ) {
        out.iter_mut().for_each(|v| *v = 0.0);
        if q.len() != chain.dof() || out.len() != chain.dof() {
            return;
        }
        chain.frames(q, frames);
        let Some(last) = frames.last() else {
            return;
        };
        let tool = (last * Translation3::from(self.tool)).translation.vector;
        let points = frames
            .iter()
            .enumerate()
            .map(|(k, f)| {
                (
                    k,
                    f.translation.vector,
                    self.link_mass.get(k).copied().unwrap_or(0.0),
                )
            })
            .chain(std::iter::once((frames.len() - 1, tool, self.tool_mass)));
        for (k, p, m) in points {
            if !(m.is_finite() && m > 0.0) {
                continue;
            }
            let weight = self.gravity * m;
            // The joints up to k move the point; gravity's torque about joint i is
            // balanced by the opposite effort.
            for (i, joint) in chain.joints.iter().enumerate().take(k + 1) {
                let z = frames[i].rotation * Vector3::z();
                let jv = match joint.kind {
                    JointKind::Revolute => z.cross(&(p - frames[i].translation.vector)),
                    JointKind::Prismatic => z,
                };
                out[i] -= jv.dot(&weight);
            }
        }
        for (e, max) in out.iter_mut().zip(&self.max_effort) {
            *e = if max.is_finite() && *max > 0.0 && e.is_finite() {
                *e / max * 100.0
            } else {
                0.0
            };
        }
    }
}

/// Settings of the holding controller.
#[derive(Debug, Clone, PartialEq)]
pub struct HoldConfig {
    /// The servo's gains (its feed-forward term is unused: the hold's reference is still).
    pub gains: ServoGains,
    /// The arm's weight (`None`: the integral term alone carries it, as a driver's servo
    /// does).
    pub gravity: Option<GravityModel>,
}

/// The holding controller of a Primitive Manipulator: its joint sensors, the joint
/// positions it holds and its servo.
pub struct HoldingController {
    sensors: Box<dyn JointSensors>,
    config: HoldConfig,
    servo: JointServo,
    target: Option<Vec<f64>>,
    reading: JointState,
    gravity: Vec<f64>,
    frames: Vec<Isometry3<f64>>,
    pid: Vec<f64>,
    last: Option<Instant>,
}

impl std::fmt::Debug for HoldingController {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("HoldingController")
            .field("config", &self.config)
            .field("target", &self.target)
            .finish_non_exhaustive()
    }
}

impl HoldingController {
    /// Reading the joints from `sensors`, with `config`.
    pub fn new(sensors: impl JointSensors, config: HoldConfig) -> Self {
        Self {
            sensors: Box::new(sensors),
            config,
            servo: JointServo::default(),
            target: None,
            reading: JointState::default(),
            gravity: Vec::new(),
            frames: Vec::new(),
            pid: Vec::new(),
            last: None,
        }
    }

    /// The joint positions being held, once holding.
    pub fn target(&self) -> Option<&[f64]> {
        self.target.as_deref()
    }

    /// Stops holding (the next [`efforts`](Self::efforts) starts again from where the
    /// arm is).
    pub fn release(&mut self) {
        self.target = None;
        self.servo.reset();
        self.last = None;
    }

    /// The holding efforts at `now` into `out` (percent, one per joint), or `false`
    /// without a usable joint reading (the caller then applies no effort). The first call
    /// after [`release`](Self::release) takes the measured positions as the ones to hold
    /// and, given `applied` (the efforts a command applied until now, which held the
    /// arm), starts from them so the effort does not jump; without, from the model alone
    /// (an arm that was without effort is caught by its modelled weight at once).
    pub fn efforts(
        &mut self,
        chain: &Chain,
        now: Instant,
        applied: Option<&[f64]>,
        out: &mut Vec<f64>,
    ) -> bool {
        let n = chain.dof();
        out.clear();
        if !(self.sensors.read_joints(now, &mut self.reading)
            && self.reading.is_valid()
            && self.reading.len() == n)
        {
            return false;
        }
        let q = &self.reading.positions;
        self.gravity.resize(n, 0.0);
        match &self.config.gravity {
            Some(g) => g.efforts(chain, q, &mut self.frames, &mut self.gravity),
            None => self.gravity.iter_mut().for_each(|v| *v = 0.0),
        }
        let gains = self.config.gains;
        if self.target.as_ref().map(Vec::len) != Some(n) {
            self.target = Some(q.clone());
            self.servo.reset();
            // What the model does not explain of the efforts applied until now goes into
            // the integral term: the hold starts where the last command left off.
            if let Some(applied) = applied.filter(|a| a.len() == n) {
                let rest: Vec<f64> = (0..n).map(|j| applied[j] - self.gravity[j]).collect();
                self.servo.preload(&gains, &rest);
            }
        }
        let dt = self.last.map_or(0.01, |t| {
            now.saturating_duration_since(t)
                .as_secs_f64()
                .clamp(0.001, 0.1)
        });
        self.last = Some(now);
        let Some(target) = &self.target else {
            return false;
        };
        let still = vec![0.0; n];
        self.servo.efforts(
            &gains,
            dt,
            q,
            &self.reading.velocities,
            target,
            &still,
            &mut self.pid,
        );
        out.extend(
            self.pid
                .iter()
                .zip(&self.gravity)
                .map(|(u, g)| (u + g).clamp(-100.0, 100.0)),
        );
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stock::manipulator::kinematics::Joint;

    /// One horizontal revolute link: joint axis along vehicle y, 1 kg at 0.5 m.
    fn pendulum() -> (Chain, GravityModel) {
        let chain = Chain::new(
            vec![
                Joint::revolute(0.0, -std::f64::consts::FRAC_PI_2, 0.0, -3.0, 3.0, 2.0),
                Joint::revolute(0.5, 0.0, 0.0, -3.0, 3.0, 2.0),
            ],
            Isometry3::identity(),
            Vector3::zeros(),
        )
        .unwrap();
        let model = GravityModel {
            link_mass: vec![0.0, 1.0],
            tool_mass: 0.0,
            tool: Vector3::zeros(),
            max_effort: vec![10.0, 10.0],
            gravity: Vector3::new(0.0, 0.0, STANDARD_GRAVITY),
        };
        (chain, model)
    }

    #[test]
    fn the_model_balances_a_point_mass_on_a_lever() {
        let (chain, model) = pendulum();
        let mut frames = Vec::new();
        let mut out = vec![0.0; 2];
        model.efforts(&chain, &[0.0, 0.0], &mut frames, &mut out);
        // 1 kg at 0.5 m: 4.9 N·m on joint 0 (axis horizontal), 49 % of 10 N·m.
        assert!((out[0].abs() - 49.033).abs() < 0.01, "{out:?}");
        assert_eq!(out[1], 0.0);
        // Wrong joint count: nothing.
        model.efforts(&chain, &[0.0], &mut frames, &mut out);
        assert_eq!(out, vec![0.0, 0.0]);
    }

    #[derive(Debug)]
    struct Fixed(JointState);
    impl JointSensors for Fixed {
        fn read_joints(&mut self, _now: Instant, out: &mut JointState) -> bool {
            *out = self.0.clone();
            !out.is_empty()
        }
    }

    #[test]
    fn the_hold_starts_from_the_applied_efforts_and_pushes_back() {
        let (chain, model) = pendulum();
        let reading = JointState {
            positions: vec![0.0, 0.0],
            velocities: vec![0.0, 0.0],
            efforts: vec![0.0, 0.0],
        };
        let config = HoldConfig {
            gains: ServoGains::default(),
            gravity: Some(model.clone()),
        };
        let mut hold = HoldingController::new(Fixed(reading.clone()), config.clone());
        let now = Instant::now();
        let mut out = Vec::new();
        assert!(hold.efforts(&chain, now, Some(&[45.0, 3.0]), &mut out));
        // Bumpless: the first output is the efforts applied until now (the model says
        // 49 % on joint 0; the 4 % it does not explain goes into the integral term).
        assert!((out[0] - 45.0).abs() < 0.5, "{out:?}");
        assert!((out[1] - 3.0).abs() < 0.5, "{out:?}");
        assert_eq!(hold.target(), Some(&[0.0, 0.0][..]));
        // Moved away from the held position: the effort pushes back.
        let mut moved = HoldingController::new(Fixed(reading), config);
        // Without a command before, the model alone: the weight is carried at once.
        moved.efforts(&chain, now, None, &mut out);
        assert!((out[0].abs() - 49.033).abs() < 0.01, "{out:?}");
        moved.target = Some(vec![0.1, -0.1]);
        moved.efforts(&chain, now, None, &mut out);
        assert!(out[1] < 0.0, "{out:?}");
        // No reading: no efforts.
        let mut blind = HoldingController::new(
            Fixed(JointState::default()),
            HoldConfig {
                gains: ServoGains::default(),
                gravity: None,
            },
        );
        assert!(!blind.efforts(&chain, now, None, &mut out));
        assert!(out.is_empty());
    }
}
