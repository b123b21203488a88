//! Arm kinematics (issue 13): forward kinematics, the geometric Jacobian, and inverse
//! kinematics of a 6-axis arm (the PUMA 560 of Craig's table with its published joint
//! ranges and a 10 cm tool), per pose:
//!
//! * `ik/tracking`: the target moved 1 mm and 0.1° from the previous solution, which is
//!   the seed (what the pose drivers do each control period);
//! * `ik/cold`: from the middle of the joint ranges to random reachable poses (what a new
//!   Set End Effector Pose costs), restarts included.
//!
//! `cargo bench -p jaus --bench kinematics`

use std::f64::consts::FRAC_PI_2;

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use jaus::stock::manipulator::kinematics::{Chain, IkSolver, Joint};
use jaus::stock::nalgebra::{Dyn, Isometry3, OMatrix, Translation3, UnitQuaternion, Vector3, U6};

fn puma() -> Chain {
    let r = |a, alpha, d, min: f64, max: f64| {
        Joint::revolute(a, alpha, d, min.to_radians(), max.to_radians(), 2.0)
    };
    Chain::new(
        vec![
            r(0.0, 0.0, 0.0, -160.0, 160.0),
            r(0.0, -FRAC_PI_2, 0.0, -225.0, 45.0),
            r(0.4318, 0.0, 0.15005, -45.0, 225.0),
            r(0.0203, -FRAC_PI_2, 0.4318, -266.0, 266.0),
            r(0.0, FRAC_PI_2, 0.0, -100.0, 100.0),
            r(0.0, -FRAC_PI_2, 0.0, -266.0, 266.0),
        ],
        Isometry3::identity(),
        Vector3::new(0.0, 0.0, 0.1),
    )
    .expect("valid arm")
}

/// Deterministic joint vectors within the limits (away from the wrist singularity).
fn configurations(arm: &Chain, n: usize) -> Vec<Vec<f64>> {
    let mut s: u64 = 11;
    let mut next = || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| {
            arm.joints
                .iter()
                .map(|j| j.min + (0.1 + 0.8 * next()) * (j.max - j.min))
                .collect()
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    let arm = puma();
    let qs = configurations(&arm, 200);
    let mut g = c.benchmark_group("kinematics");
    let mut i = 0;
    g.bench_function("forward", |b| {
        b.iter(|| {
            i = (i + 1) % qs.len();
            arm.tool_pose(&qs[i])
        })
    });
    let mut jac = OMatrix::<f64, U6, Dyn>::zeros(6);
    g.bench_function("jacobian", |b| {
        b.iter(|| {
            i = (i + 1) % qs.len();
            arm.jacobian(&qs[i], &mut jac);
            jac[(0, 0)]
        })
    });
    let mut solver = IkSolver::new(6);
    let mut out = vec![0.0; 6];
    let nudge = Isometry3::from_parts(
        Translation3::new(0.001, 0.0, 0.0),
        UnitQuaternion::from_euler_angles(0.0, 0.0, 0.1f64.to_radians()),
    );
    // Nudges that leave the reachable set within the limits (near a limit or a
    // singularity) are left out, and counted.
    let tracking: Vec<(Vec<f64>, Isometry3<f64>)> = qs
        .iter()
        .map(|q| (q.clone(), nudge * arm.tool_pose(q)))
        .filter(|(q, t)| solver.solve(&arm, t, q, &mut out).is_ok())
        .collect();
    eprintln!(
        "ik/tracking: {} of {} nudged poses reachable",
        tracking.len(),
        qs.len()
    );
    g.bench_function("ik/tracking", |b| {
        b.iter_batched(
            || {
                i = (i + 1) % tracking.len();
                i
            },
            |k| {
                let (seed, target) = &tracking[k];
                solver
                    .solve(&arm, target, seed, &mut out)
                    .expect("reachable")
            },
            BatchSize::SmallInput,
        )
    });
    let mid = arm.mid_range();
    let cold: Vec<Isometry3<f64>> = qs.iter().map(|q| arm.tool_pose(q)).collect();
    g.bench_function("ik/cold", |b| {
        b.iter(|| {
            i = (i + 1) % cold.len();
            solver
                .solve(&arm, &cold[i], &mid, &mut out)
                .expect("reachable")
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
