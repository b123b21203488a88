use std::f64::consts::{FRAC_PI_2, PI};

use super::*;
use crate::codec::Encode;
use crate::JausMessage;

const A2: f64 = 0.4318;
const A3: f64 = 0.0203;
const D3: f64 = 0.15005;
const D4: f64 = 0.4318;

/// The PUMA 560 in Craig's modified Denavit–Hartenberg table (Introduction to Robotics,
/// §3.7): α = 0, −90°, 0, −90°, 90°, −90°; a2, a3; d3, d4; with its published joint
/// ranges (±160°, −225°..45°, −45°..225°, ±266°, ±100°, ±266°).
pub(crate) fn puma() -> Chain {
    let r = |a, alpha, d, min: f64, max: f64| {
        Joint::revolute(a, alpha, d, min.to_radians(), max.to_radians(), 2.0)
    };
    Chain::new(
        vec![
            r(0.0, 0.0, 0.0, -160.0, 160.0),
            r(0.0, -FRAC_PI_2, 0.0, -225.0, 45.0),
            r(A2, 0.0, D3, -45.0, 225.0),
            r(A3, -FRAC_PI_2, D4, -266.0, 266.0),
            r(0.0, FRAC_PI_2, 0.0, -100.0, 100.0),
            r(0.0, -FRAC_PI_2, 0.0, -266.0, 266.0),
        ],
        Isometry3::identity(),
        Vector3::zeros(),
    )
    .unwrap()
}

/// Craig's closed form of the wrist centre (frame 6 origin), written out by hand.
fn puma_position(t1: f64, t2: f64, t3: f64) -> Vector3<f64> {
    let (s1, c1) = t1.sin_cos();
    let (s2, c2) = t2.sin_cos();
    let (s23, c23) = (t2 + t3).sin_cos();
    let reach = A2 * c2 + A3 * c23 - D4 * s23;
    Vector3::new(
        c1 * reach - D3 * s1,
        s1 * reach + D3 * c1,
        -A3 * s23 - A2 * s2 - D4 * c23,
    )
}

fn close(a: &Vector3<f64>, b: &Vector3<f64>) -> bool {
    (a - b).norm() < 1e-12
}

#[test]
fn puma_forward_kinematics_matches_hand_computed_poses() {
    let arm = puma();
    // Zero pose: reach a2 + a3 forward, d3 to the side, d4 below the shoulder; the
    // twists alone compose to a half turn about x.
    let p = arm.forward(&[0.0; 6]);
    assert!(close(
        &p.translation.vector,
        &Vector3::new(A2 + A3, D3, -D4)
    ));
    let half_turn_x = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), PI);
    assert!(p.rotation.angle_to(&half_turn_x) < 1e-12);
    // Shoulder at −90°: the upper arm points along z, the forearm forward.
    let p = arm.forward(&[0.0, -FRAC_PI_2, 0.0, 0.0, 0.0, 0.0]);
    assert!(close(&p.translation.vector, &Vector3::new(D4, D3, A2 + A3)));
    // Waist at 90°: the zero pose turned a quarter about z.
    let p = arm.forward(&[FRAC_PI_2, 0.0, 0.0, 0.0, 0.0, 0.0]);
    assert!(close(
        &p.translation.vector,
        &Vector3::new(-D3, A2 + A3, -D4)
    ));
    // And the closed form at an arbitrary arm configuration (the wrist joints do not
    // move the wrist centre).
    for q in [
        [0.3, -0.7, 1.1, 0.4, -0.9, 2.0],
        [-1.2, 0.2, -0.3, -1.0, 0.5, -2.5],
    ] {
        let p = arm.forward(&q);
        assert!(
            close(&p.translation.vector, &puma_position(q[0], q[1], q[2])),
            "{q:?}"
        );
    }
}

#[test]
fn a_prismatic_joint_slides_along_its_axis() {
    // A turntable, then a vertical slide 0.5 m out.
    let arm = Chain::new(
        vec![
            Joint::revolute(0.0, 0.0, 0.0, -PI, PI, 1.0),
            Joint::prismatic(0.5, 0.0, 0.0, 0.0, 0.4, 0.2),
        ],
        Isometry3::identity(),
        Vector3::new(0.0, 0.0, 0.05),
    )
    .unwrap();
    let t: f64 = 0.6;
    let p = arm.tool_pose(&[t, 0.3]).translation.vector;
    assert!(close(&p, &Vector3::new(0.5 * t.cos(), 0.5 * t.sin(), 0.35)));
    let mut j = OMatrix::<f64, U6, Dyn>::zeros(2);
    arm.jacobian(&[t, 0.3], &mut j);
    assert!((j.fixed_view::<3, 1>(0, 1).into_owned() - Vector3::z()).norm() < 1e-12);
    assert!(j.fixed_view::<3, 1>(3, 1).norm() < 1e-12);
}

fn lcg(state: &mut u64) -> f64 {
    *state = state
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    (*state >> 11) as f64 / (1u64 << 53) as f64
}

fn random_q(arm: &Chain, s: &mut u64) -> Vec<f64> {
    arm.joints
        .iter()
        .map(|j| j.min + lcg(s) * (j.max - j.min))
        .collect()
}

#[test]
fn the_jacobian_matches_finite_differences() {
    let mut arm = puma();
    arm.tool = Vector3::new(0.01, -0.02, 0.1);
    arm.base = Isometry3::from_parts(
        Translation3::new(0.2, 0.0, -0.3),
        UnitQuaternion::from_euler_angles(PI, 0.1, 0.2),
    );
    let mut s = 42;
    let mut j = OMatrix::<f64, U6, Dyn>::zeros(6);
    for _ in 0..50 {
        let q = random_q(&arm, &mut s);
        arm.jacobian(&q, &mut j);
        let p0 = arm.tool_pose(&q);
        for k in 0..6 {
            let h = 1e-7;
            let mut qh = q.clone();
            qh[k] += h;
            let p1 = arm.tool_pose(&qh);
            let v = (p1.translation.vector - p0.translation.vector) / h;
            let w = (p1.rotation * p0.rotation.inverse()).scaled_axis() / h;
            assert!(
                (v - j.fixed_view::<3, 1>(0, k)).norm() < 1e-5,
                "linear, joint {k}"
            );
            assert!(
                (w - j.fixed_view::<3, 1>(3, k)).norm() < 1e-5,
                "angular, joint {k}"
            );
        }
    }
}

#[test]
fn inverse_kinematics_round_trips_random_poses() {
    let mut arm = puma();
    arm.tool = Vector3::new(0.0, 0.0, 0.1);
    let mut solver = IkSolver::new(6);
    let mut s = 7;
    let seed = arm.mid_range();
    let mut out = vec![0.0; 6];
    let (mut worst_p, mut worst_a, mut iterations, mut restarts) = (0.0f64, 0.0f64, 0, 0);
    for i in 0..1000 {
        let q = random_q(&arm, &mut s);
        let target = arm.tool_pose(&q);
        let r = solver
            .solve(&arm, &target, &seed, &mut out)
            .unwrap_or_else(|e| panic!("pose {i} from {q:?}: {e}"));
        assert!(arm.within_limits(&out));
        let got = arm.tool_pose(&out);
        let dp = (got.translation.vector - target.translation.vector).norm();
        let da = got.rotation.angle_to(&target.rotation);
        assert!(
            dp <= 1e-4 && da <= 0.01f64.to_radians(),
            "pose {i}: {dp} m, {da} rad"
        );
        worst_p = worst_p.max(dp);
        worst_a = worst_a.max(da);
        iterations += r.iterations;
        restarts += r.attempts - 1;
    }
    println!(
        "1000 poses: worst {:.2e} mm, {:.2e}°; {:.1} iterations per pose, {restarts} restarts",
        worst_p * 1000.0,
        worst_a.to_degrees(),
        iterations as f64 / 1000.0
    );
}

#[test]
fn unreachable_and_bad_targets_are_errors() {
    let arm = puma();
    let mut solver = IkSolver::new(6);
    let mut out = vec![0.0; 6];
    let far = Isometry3::translation(3.0, 0.0, 0.0);
    assert!(matches!(
        solver.solve(&arm, &far, &arm.mid_range(), &mut out),
        Err(IkError::Unreachable { position_error, .. }) if position_error > 2.0
    ));
    let nan = Isometry3::translation(f64::NAN, 0.0, 0.0);
    assert_eq!(
        solver.solve(&arm, &nan, &arm.mid_range(), &mut out),
        Err(IkError::NotFinite)
    );
    assert!(matches!(
        solver.solve(&arm, &far, &[0.0; 3], &mut out),
        Err(IkError::Dof { dof: 6, .. })
    ));
    let bad = Chain::new(
        vec![Joint::revolute(0.0, 0.0, 0.0, 1.0, -1.0, 1.0)],
        Isometry3::identity(),
        Vector3::zeros(),
    );
    assert!(matches!(bad, Err(ChainError::Limits { joint: 0, .. })));
    assert!(matches!(
        Chain::new(vec![], Isometry3::identity(), Vector3::zeros()),
        Err(ChainError::JointCount(0))
    ));
}

#[test]
fn specifications_round_trip_through_the_wire() {
    let mut arm = puma();
    // The wire's angles span one turn [-π, π): wider published ranges do not travel.
    for (j, range) in [
        (1, (-3.0, 0.78)),
        (2, (-0.78, 3.0)),
        (3, (-3.0, 3.0)),
        (5, (-3.0, 3.0)),
    ] {
        (arm.joints[j].min, arm.joints[j].max) = range;
    }
    arm.base = Isometry3::from_parts(
        Translation3::new(0.3, -0.1, -0.4),
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), PI),
    );
    arm.joints
        .push(Joint::prismatic(0.05, FRAC_PI_2, 0.25, 0.0, 0.12, 0.05));
    let spec = arm.to_specifications();
    let bytes = spec.to_bytes().unwrap();
    let back = ReportManipulatorSpecifications::decode_body(&bytes).unwrap();
    let got = Chain::from_specifications(&back).unwrap();
    assert_eq!(got.dof(), 7);
    for (a, b) in arm.joints.iter().zip(&got.joints) {
        assert_eq!(a.kind, b.kind);
        for (x, y) in [
            (a.link_length, b.link_length),
            (a.twist, b.twist),
            (a.offset, b.offset),
            (a.min, b.min),
            (a.max, b.max),
            (a.max_rate, b.max_rate),
        ] {
            assert!((x - y).abs() <= 5e-4, "{a:?} vs {b:?}");
        }
    }
    assert!((got.base.translation.vector - arm.base.translation.vector).norm() < 1e-6);
    assert!(got.base.rotation.angle_to(&arm.base.rotation) < 1e-6);
    // The same joints give the same pose within the wire's resolution.
    let q = [0.3, -0.7, 1.1, 0.4, -0.9, 2.0, 0.05];
    let d = (arm.forward(&q).translation.vector - got.forward(&q).translation.vector).norm();
    assert!(d < 2e-3, "{d}");
    // An incomplete message is an error, not an arm.
    let mut broken = back.clone();
    broken.linked_joints.pop();
    assert!(matches!(
        Chain::from_specifications(&broken),
        Err(ChainError::Message(_))
    ));
}
