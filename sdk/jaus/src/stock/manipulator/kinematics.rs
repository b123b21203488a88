//! Kinematics of a serial arm of revolute and prismatic joints (Part 1 §5.4.1, §5.4.2).
//!
//! # Convention
//!
//! Part 1 describes an arm in the notation of Duffy and Crane: between the joint axes
//! S_i and S_j a link of length a_ij and twist α_ij, along each axis S_j an offset, and
//! about it a joint angle θ_j. This module writes the same chain in the modified
//! (proximal) Denavit–Hartenberg form: frame i sits on joint axis i (z along S_i), and
//!
//! ```text
//! T(i-1 → i) = RotX(α_{i-1}) · TransX(a_{i-1}) · RotZ(θ_i) · TransZ(d_i)
//! ```
//!
//! where [`Joint::link_length`] = a_{i-1} and [`Joint::twist`] = α_{i-1} describe the
//! link *leading to* joint i (both zero for the first joint), a revolute joint varies θ
//! and keeps d = [`Joint::offset`], and a prismatic joint varies d and keeps
//! θ = [`Joint::offset`]. The manipulator base frame (z along S_1) is placed in the
//! vehicle frame (x forward, y right, z down) by [`Chain::base`]; the end-effector frame
//! is the last joint's frame, its origin the last offset along the last axis as §5.4.1
//! says; the tool point ([`Chain::tool`], Set Tool Point) is a point of the end-effector
//! frame. Joint values are radians (revolute) or metres (prismatic).
//!
//! # On the wire
//!
//! Report Manipulator Specifications carries some fields raw (OpenJAUS does not give them
//! units); this SDK reads them as follows, and writes them the same way:
//!
//! * link lengths: raw `u16` in millimetres;
//! * revolute joints: offset (a length in this convention) in the field's thousandths,
//!   read as metres; twist, minimum, maximum as scaled angles in [0, 65.535] rad, where a
//!   value of π or more stands for that value − 2π (so −π/2 travels as 3π/2); a maximum
//!   that wraps below its minimum gets 2π back; maximum rate in rad/s;
//! * prismatic joints: offset (the constant joint angle) raw in milliradians (wrapped
//!   like the angles above), minimum and maximum raw in millimetres, maximum rate raw in
//!   mm/s;
//! * the base frame: position (m) and quaternion d (scalar), a, b, c.

use std::f64::consts::PI;

use nalgebra::{
    Dyn, Isometry3, Matrix6, OMatrix, Quaternion, Translation3, UnitQuaternion, Vector3, Vector6,
    U6,
};

use crate::messages::{
    ManipulatorCoordinateSystem, ManipulatorJoint, ManipulatorLinkedJoint, PrismaticJointLimits,
    PrismaticLinkedLimits, ReportManipulatorSpecifications, RevoluteJointLimits,
    RevoluteLinkedLimits,
};

/// Revolute or prismatic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointKind {
    /// Rotates about its axis (joint value in rad).
    Revolute,
    /// Slides along its axis (joint value in m).
    Prismatic,
}

/// One joint and the link leading to it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// a_{i-1}: length of the link from the previous joint axis, m (0 for the first).
    pub link_length: f64,
    /// α_{i-1}: twist of that link, rad (0 for the first).
    pub twist: f64,
    /// The constant joint parameter: d (m) of a revolute joint, θ (rad) of a prismatic one.
    pub offset: f64,
    /// Lowest joint value (rad or m).
    pub min: f64,
    /// Highest joint value (rad or m).
    pub max: f64,
    /// Highest joint rate (rad/s or m/s).
    pub max_rate: f64,
}

impl Joint {
    /// A revolute joint after a link of `link_length` (m) and `twist` (rad), offset `d`.
    pub fn revolute(
        link_length: f64,
        twist: f64,
        d: f64,
        min: f64,
        max: f64,
        max_rate: f64,
    ) -> Self {
        Self {
            kind: JointKind::Revolute,
            link_length,
            twist,
            offset: d,
            min,
            max,
            max_rate,
        }
    }

    /// A prismatic joint after a link of `link_length` (m) and `twist` (rad), joint angle
    /// `theta`.
    pub fn prismatic(
        link_length: f64,
        twist: f64,
        theta: f64,
        min: f64,
        max: f64,
        max_rate: f64,
    ) -> Self {
        Self {
            kind: JointKind::Prismatic,
            link_length,
            twist,
            offset: theta,
            min,
            max,
            max_rate,
        }
    }

    /// The transform from the previous joint's frame to this one's at joint value `q`.
    pub fn transform(&self, q: f64) -> Isometry3<f64> {
        let (theta, d) = match self.kind {
            JointKind::Revolute => (q, self.offset),
            JointKind::Prismatic => (self.offset, q),
        };
        let link = Isometry3::from_parts(
            Translation3::new(self.link_length, 0.0, 0.0),
            UnitQuaternion::from_axis_angle(&Vector3::x_axis(), self.twist),
        );
        let joint = Isometry3::from_parts(
            Translation3::new(0.0, 0.0, d),
            UnitQuaternion::from_axis_angle(&Vector3::z_axis(), theta),
        );
        link * joint
    }
}

/// Why a chain cannot be used.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ChainError {
    /// No joints, or more than a message can carry.
    #[error("an arm has 1 to 255 joints; this one has {0}")]
    JointCount(usize),
    /// A value is not finite.
    #[error("joint {joint}: {field} is not a finite number")]
    NotFinite {
        /// Joint index, 0 = first.
        joint: usize,
        /// The parameter.
        field: &'static str,
    },
    /// Limits in the wrong order or a rate that is not positive.
    #[error("joint {joint}: limits [{min}, {max}] with maximum rate {max_rate} are not usable")]
    Limits {
        /// Joint index, 0 = first.
        joint: usize,
        /// Lowest value.
        min: f64,
        /// Highest value.
        max: f64,
        /// Highest rate.
        max_rate: f64,
    },
    /// The specifications message is incomplete or its counts disagree.
    #[error("Report Manipulator Specifications: {0}")]
    Message(String),
}

/// A serial arm: its joints, where its base is on the vehicle, and its tool point.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    /// The joints, base first.
    pub joints: Vec<Joint>,
    /// The manipulator base frame in the vehicle frame.
    pub base: Isometry3<f64>,
    /// The tool point in the end-effector frame, m.
    pub tool: Vector3<f64>,
}

impl Chain {
    /// A chain, checked: 1 to 255 joints, finite values, min ≤ max, positive rates.
    pub fn new(
        joints: Vec<Joint>,
        base: Isometry3<f64>,
        tool: Vector3<f64>,
    ) -> Result<Chain, ChainError> {
        if joints.is_empty() || joints.len() > 255 {
            return Err(ChainError::JointCount(joints.len()));
        }
        for (i, j) in joints.iter().enumerate() {
            for (field, v) in [
                ("link_length", j.link_length),
                ("twist", j.twist),
                ("offset", j.offset),
                ("min", j.min),
                ("max", j.max),
                ("max_rate", j.max_rate),
            ] {
                if !v.is_finite() {
                    return Err(ChainError::NotFinite { joint: i, field });
                }
            }
            if j.min > j.max || j.max_rate <= 0.0 {
                return Err(ChainError::Limits {
                    joint: i,
                    min: j.min,
                    max: j.max,
                    max_rate: j.max_rate,
                });
            }
        }
        if !(base.translation.vector.iter().all(|v| v.is_finite())
            && base.rotation.coords.iter().all(|v| v.is_finite())
            && tool.iter().all(|v| v.is_finite()))
        {
            return Err(ChainError::NotFinite {
                joint: 0,
                field: "base or tool",
            });
        }
        Ok(Chain { joints, base, tool })
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    /// The middle of every joint's range.
    pub fn mid_range(&self) -> Vec<f64> {
        self.joints.iter().map(|j| 0.5 * (j.min + j.max)).collect()
    }

    /// Whether every value of `q` is within its joint's limits.
    pub fn within_limits(&self, q: &[f64]) -> bool {
        q.len() == self.dof()
            && q.iter()
                .zip(&self.joints)
                .all(|(v, j)| *v >= j.min && *v <= j.max)
    }

    /// `q` clamped into the limits.
    pub fn clamp(&self, q: &mut [f64]) {
        for (v, j) in q.iter_mut().zip(&self.joints) {
            *v = v.clamp(j.min, j.max);
        }
    }

    /// Every joint's frame in the vehicle frame at `q`, into `out` (base joint first; the
    /// last is the end-effector frame).
    pub fn frames(&self, q: &[f64], out: &mut Vec<Isometry3<f64>>) {
        out.clear();
        let mut t = self.base;
        for (j, v) in self.joints.iter().zip(q) {
            t *= j.transform(*v);
            out.push(t);
        }
    }

    /// The end-effector frame in the vehicle frame at `q`.
    pub fn forward(&self, q: &[f64]) -> Isometry3<f64> {
        self.joints
            .iter()
            .zip(q)
            .fold(self.base, |t, (j, v)| t * j.transform(*v))
    }

    /// The tool frame (the end-effector frame moved to the tool point) in the vehicle
    /// frame at `q`.
    pub fn tool_pose(&self, q: &[f64]) -> Isometry3<f64> {
        self.forward(q) * Translation3::from(self.tool)
    }

    /// The geometric Jacobian of the tool point at `q`, in the vehicle frame, into `out`
    /// (6 × dof; rows 0–2 the tool point's linear velocity, rows 3–5 the angular
    /// velocity, per unit rate of each joint).
    pub fn jacobian(&self, q: &[f64], out: &mut OMatrix<f64, U6, Dyn>) {
        let n = self.dof();
        if out.ncols() != n {
            *out = OMatrix::<f64, U6, Dyn>::zeros(n);
        }
        // Frames first, then the tool point: one pass with a small stack of frames.
        let mut t = self.base;
        let mut axes = [(Vector3::zeros(), Vector3::zeros()); 16];
        let mut heap = Vec::new();
        for (i, (j, v)) in self.joints.iter().zip(q).enumerate() {
            t *= j.transform(*v);
            let entry = (t.rotation * Vector3::z(), t.translation.vector);
            if i < axes.len() {
                axes[i] = entry;
            } else {
                heap.push(entry);
            }
        }
        let p = (t * Translation3::from(self.tool)).translation.vector;
        for (i, j) in self.joints.iter().enumerate() {
            let (z, o) = if i < axes.len() {
                axes[i]
            } else {
                heap[i - axes.len()]
            };
            let (lin, ang) = match j.kind {
                JointKind::Revolute => (z.cross(&(p - o)), z),
                JointKind::Prismatic => (z, Vector3::zeros()),
            };
            out.fixed_view_mut::<3, 1>(0, i).copy_from(&lin);
            out.fixed_view_mut::<3, 1>(3, i).copy_from(&ang);
        }
    }

    /// The chain a Report Manipulator Specifications describes (see the module
    /// documentation for the units), with the tool point at the end-effector origin.
    pub fn from_specifications(r: &ReportManipulatorSpecifications) -> Result<Chain, ChainError> {
        let n = r.num_joints as usize;
        let (Some(first), Some(cs)) = (&r.first_joint, &r.coordinate_system) else {
            return Err(ChainError::JointCount(n));
        };
        if r.linked_joints.len() + 1 != n {
            return Err(ChainError::Message(format!(
                "num_joints = {n} but {} joints follow the first",
                r.linked_joints.len()
            )));
        }
        let mut joints = vec![match first {
            ManipulatorJoint::Revolute(l) => revolute_of(0.0, 0.0, l),
            ManipulatorJoint::Prismatic(l) => prismatic_of(0.0, 0.0, l),
        }];
        for l in &r.linked_joints {
            joints.push(match l {
                ManipulatorLinkedJoint::Revolute(x) => revolute_of(
                    x.link_length as f64 / 1000.0,
                    wrap(x.twist_angle),
                    &x.limits,
                ),
                ManipulatorLinkedJoint::Prismatic(x) => prismatic_of(
                    x.link_length as f64 / 1000.0,
                    wrap(x.twist_angle),
                    &x.limits,
                ),
            });
        }
        let q = Quaternion::new(
            cs.coordinate_sys_d,
            cs.coordinate_sys_a,
            cs.coordinate_sys_b,
            cs.coordinate_sys_c,
        );
        if !(q.norm() > 1e-6 && q.norm().is_finite()) {
            return Err(ChainError::Message(
                "the base frame's quaternion has no length".into(),
            ));
        }
        let base = Isometry3::from_parts(
            Translation3::new(
                cs.coordinate_sys_x,
                cs.coordinate_sys_y,
                cs.coordinate_sys_z,
            ),
            UnitQuaternion::from_quaternion(q),
        );
        Chain::new(joints, base, Vector3::zeros())
    }

    /// The Report Manipulator Specifications describing this chain (values beyond what
    /// a field carries are saturated at its limit).
    pub fn to_specifications(&self) -> ReportManipulatorSpecifications {
        let first = &self.joints[0];
        let q = self.base.rotation.into_inner();
        let p = self.base.translation.vector;
        let c30 = |v: f64| v.clamp(-30.0, 30.0);
        ReportManipulatorSpecifications {
            num_joints: self.dof().min(255) as u8,
            first_joint: Some(match first.kind {
                JointKind::Revolute => ManipulatorJoint::Revolute(revolute_limits(first)),
                JointKind::Prismatic => ManipulatorJoint::Prismatic(prismatic_limits(first)),
            }),
            coordinate_system: Some(ManipulatorCoordinateSystem {
                coordinate_sys_x: c30(p.x),
                coordinate_sys_y: c30(p.y),
                coordinate_sys_z: c30(p.z),
                coordinate_sys_d: q.w,
                coordinate_sys_a: q.i,
                coordinate_sys_b: q.j,
                coordinate_sys_c: q.k,
            }),
            linked_joints: self.joints[1..]
                .iter()
                .take(254)
                .map(|j| {
                    let link_length = millis(j.link_length);
                    let twist_angle = unwrap(j.twist);
                    match j.kind {
                        JointKind::Revolute => {
                            ManipulatorLinkedJoint::Revolute(RevoluteLinkedLimits {
                                link_length,
                                twist_angle,
                                limits: revolute_limits(j),
                            })
                        }
                        JointKind::Prismatic => {
                            ManipulatorLinkedJoint::Prismatic(PrismaticLinkedLimits {
                                link_length,
                                twist_angle,
                                limits: prismatic_limits(j),
                            })
                        }
                    }
                })
                .collect(),
        }
    }
}

/// The wire's angle in [0, 65.535] read as an angle in [−π, π) where it is π or more.
fn wrap(a: f64) -> f64 {
    if a >= PI {
        a - 2.0 * PI
    } else {
        a
    }
}

/// An angle written into [0, 65.535] (negative angles as angle + 2π).
fn unwrap(a: f64) -> f64 {
    let a = if a < 0.0 { a + 2.0 * PI } else { a };
    a.clamp(0.0, 65.535)
}

fn millis(v: f64) -> u16 {
    (v * 1000.0).round().clamp(0.0, 65535.0) as u16
}

fn limits(min: f64, max: f64) -> (f64, f64) {
    let (min, mut max) = (wrap(min), wrap(max));
    if max < min {
        max += 2.0 * PI;
    }
    (min, max)
}

fn revolute_of(a: f64, alpha: f64, l: &RevoluteJointLimits) -> Joint {
    let (min, max) = limits(l.joint_min_value, l.joint_max_value);
    Joint::revolute(a, alpha, l.joint_offset, min, max, l.joint_max_velocity)
}

fn prismatic_of(a: f64, alpha: f64, l: &PrismaticJointLimits) -> Joint {
    Joint::prismatic(
        a,
        alpha,
        wrap(l.joint_offset as f64 / 1000.0),
        l.joint_min_value as f64 / 1000.0,
        l.joint_max_value as f64 / 1000.0,
        l.joint_max_velocity as f64 / 1000.0,
    )
}

fn revolute_limits(j: &Joint) -> RevoluteJointLimits {
    RevoluteJointLimits {
        joint_offset: j.offset.clamp(0.0, 65.535),
        joint_min_value: unwrap(j.min),
        joint_max_value: unwrap(j.max),
        joint_max_velocity: j.max_rate.clamp(0.0, 65.535),
    }
}

fn prismatic_limits(j: &Joint) -> PrismaticJointLimits {
    PrismaticJointLimits {
        joint_offset: millis(unwrap(j.offset)),
        joint_min_value: millis(j.min),
        joint_max_value: millis(j.max),
        joint_max_velocity: millis(j.max_rate),
    }
}

/// Why inverse kinematics found no joint values.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IkError {
    /// The target or the seed is not finite.
    #[error("the target or the seed is not finite")]
    NotFinite,
    /// The seed has another joint count than the arm.
    #[error("the seed has {got} joints; the arm has {dof}")]
    Dof {
        /// Joints in the seed.
        got: usize,
        /// Joints of the arm.
        dof: usize,
    },
    /// No solution within the joint limits reaches the target.
    #[error("out of reach within the joint limits (closest: {:.2} mm, {:.3}°)", position_error * 1000.0, angle_error.to_degrees())]
    Unreachable {
        /// Closest position error found, m.
        position_error: f64,
        /// Closest orientation error found, rad.
        angle_error: f64,
    },
}

/// How a solve went.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IkReport {
    /// Iterations over all attempts.
    pub iterations: usize,
    /// Attempts (1 = converged from the seed).
    pub attempts: usize,
    /// Final position error, m.
    pub position_error: f64,
    /// Final orientation error, rad.
    pub angle_error: f64,
}

/// Inverse kinematics by damped least squares (Levenberg–Marquardt) within the joint
/// limits: `Δq = Jᵀ (J Jᵀ + λ² I)⁻¹ e`, λ adapted to the progress, every step clamped
/// into the limits, and when the seed leads nowhere, a few deterministic restarts (the
/// middle of the ranges, then spread points). It keeps its buffers: no allocation per
/// solve after the first for an arm.
#[derive(Debug, Clone)]
pub struct IkSolver {
    /// Position tolerance, m (default 1e-5).
    pub position_tolerance: f64,
    /// Orientation tolerance, rad (default 1e-5).
    pub angle_tolerance: f64,
    /// Iterations per attempt (default 300).
    pub max_iterations: usize,
    /// Attempts including the seed (default 48).
    pub max_attempts: usize,
    jac: OMatrix<f64, U6, Dyn>,
    q: Vec<f64>,
    trial: Vec<f64>,
}

impl IkSolver {
    /// A solver for arms of `dof` joints (it adapts to another count when asked).
    pub fn new(dof: usize) -> Self {
        Self {
            position_tolerance: 1e-5,
            angle_tolerance: 1e-5,
            max_iterations: 300,
            max_attempts: 48,
            jac: OMatrix::<f64, U6, Dyn>::zeros(dof),
            q: vec![0.0; dof],
            trial: vec![0.0; dof],
        }
    }

    /// Joint values into `out` placing the tool frame of `chain` at `target` (vehicle
    /// frame), starting from `seed`. The result is within the joint limits.
    pub fn solve(
        &mut self,
        chain: &Chain,
        target: &Isometry3<f64>,
        seed: &[f64],
        out: &mut [f64],
    ) -> Result<IkReport, IkError> {
        let n = chain.dof();
        if seed.len() != n || out.len() != n {
            return Err(IkError::Dof {
                got: seed.len().min(out.len()),
                dof: n,
            });
        }
        if !(seed.iter().all(|v| v.is_finite())
            && target.translation.vector.iter().all(|v| v.is_finite())
            && target.rotation.coords.iter().all(|v| v.is_finite()))
        {
            return Err(IkError::NotFinite);
        }
        if self.q.len() != n {
            self.q = vec![0.0; n];
            self.trial = vec![0.0; n];
            self.jac = OMatrix::<f64, U6, Dyn>::zeros(n);
        }
        let mut best = (f64::INFINITY, f64::INFINITY);
        let mut iterations = 0;
        for attempt in 0..self.max_attempts.max(1) {
            self.q.copy_from_slice(seed);
            if attempt > 0 {
                restart(chain, attempt, &mut self.q);
            }
            chain.clamp(&mut self.q);
            let (ok, it, err) = self.attempt(chain, target);
            iterations += it;
            if err.0 + err.1 < best.0 + best.1 {
                best = err;
            }
            if ok {
                out.copy_from_slice(&self.q);
                return Ok(IkReport {
                    iterations,
                    attempts: attempt + 1,
                    position_error: err.0,
                    angle_error: err.1,
                });
            }
        }
        Err(IkError::Unreachable {
            position_error: best.0,
            angle_error: best.1,
        })
    }

    /// One damped least-squares descent from `self.q`: (converged, iterations, errors).
    fn attempt(&mut self, chain: &Chain, target: &Isometry3<f64>) -> (bool, usize, (f64, f64)) {
        let mut lambda: f64 = 0.05;
        let mut e = error(chain, target, &self.q);
        let mut cost = e.norm_squared();
        for it in 0..self.max_iterations {
            let (ep, ea) = (e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm());
            if ep <= self.position_tolerance && ea <= self.angle_tolerance {
                return (true, it, (ep, ea));
            }
            chain.jacobian(&self.q, &mut self.jac);
            // Active set: a joint at a limit that the step would push past is taken out
            // of the Jacobian and the step solved again without it.
            let mut solved = false;
            for _pass in 0..4 {
                let a: Matrix6<f64> =
                    &self.jac * self.jac.transpose() + Matrix6::identity() * (lambda * lambda);
                let Some(w) = a.cholesky().map(|c| c.solve(&e)) else {
                    break;
                };
                let mut blocked = false;
                for (j, joint) in chain.joints.iter().enumerate() {
                    // A bounded step keeps the linearisation honest.
                    let step = self.jac.column(j).dot(&w).clamp(-0.5, 0.5);
                    let at_min = self.q[j] <= joint.min && step < 0.0;
                    let at_max = self.q[j] >= joint.max && step > 0.0;
                    if (at_min || at_max) && self.jac.column(j).norm_squared() > 0.0 {
                        self.jac.column_mut(j).fill(0.0);
                        blocked = true;
                    }
                    self.trial[j] = self.q[j] + step;
                }
                // The last pass's step is used even if it was still blocked: the
                // clamp below keeps it within the limits.
                solved = true;
                if !blocked {
                    break;
                }
            }
            if !solved {
                lambda *= 10.0;
                if lambda > 1e3 {
                    let err = (e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm());
                    return (false, it + 1, err);
                }
                continue;
            }
            chain.clamp(&mut self.trial);
            let e_trial = error(chain, target, &self.trial);
            let c_trial = e_trial.norm_squared();
            if c_trial < cost {
                std::mem::swap(&mut self.q, &mut self.trial);
                e = e_trial;
                cost = c_trial;
                lambda = (lambda * 0.3).max(1e-6);
            } else {
                lambda *= 4.0;
                if lambda > 1e3 {
                    let err = (e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm());
                    return (false, it + 1, err);
                }
            }
        }
        let err = (e.fixed_rows::<3>(0).norm(), e.fixed_rows::<3>(3).norm());
        (
            err.0 <= self.position_tolerance && err.1 <= self.angle_tolerance,
            self.max_iterations,
            err,
        )
    }
}

/// Restart point `attempt` (≥ 1): the middle of the ranges, then points spread over
/// them by a fixed pseudo-random sequence (deterministic: the same target and seed give
/// the same answer).
fn restart(chain: &Chain, attempt: usize, q: &mut [f64]) {
    let mut state = (attempt as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    for (v, joint) in q.iter_mut().zip(&chain.joints) {
        let f = if attempt == 1 {
            0.5
        } else {
            // SplitMix64: independent coordinates per joint and attempt.
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            z ^= z >> 31;
            (z >> 11) as f64 / (1u64 << 53) as f64
        };
        *v = joint.min + f * (joint.max - joint.min);
    }
}

/// The 6-vector error from the tool pose at `q` to `target`: position (m), then the
/// rotation vector (rad) taking the current orientation to the target's.
fn error(chain: &Chain, target: &Isometry3<f64>, q: &[f64]) -> Vector6<f64> {
    let p = chain.tool_pose(q);
    let dp = target.translation.vector - p.translation.vector;
    let dr = (target.rotation * p.rotation.inverse()).scaled_axis();
    Vector6::new(dp.x, dp.y, dp.z, dr.x, dr.y, dr.z)
}

#[cfg(test)]
mod tests;
