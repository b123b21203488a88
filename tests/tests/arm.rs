//! The stock manipulator components over the simulated arm on the in-process bus: the
//! demo's pick-and-place sequence, control, emergency, watchdogs and refusals.

use std::time::Duration;

use jaus_sim::arm_demo::{self, ArmOptions};

#[test]
fn the_arm_demo_runs_its_pick_and_place_sequence_within_tolerance() {
    // Refusals and watchdogs are logged as warnings: `RUST_LOG=warn` shows them.
    let _ = tracing_subscriber::fmt()
        .with_env_filter(tracing_subscriber::EnvFilter::from_default_env())
        .with_test_writer()
        .try_init();
    let report = arm_demo::run(
        &ArmOptions {
            timeout: Duration::from_secs(60),
            progress: Some(Duration::from_secs(1)),
            ..ArmOptions::default()
        },
        |l| println!("{l}"),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    for m in &report.moves {
        println!(
            "{:<42} {:6.2} s  {:7.3} mm  {:6.3}°",
            m.name, m.seconds, m.position_error_mm, m.angle_error_deg
        );
    }
    assert_eq!(report.moves.len(), 6);
    for m in &report.moves {
        // Issue 13's settling target for the pose driver: 1 mm / 0.1°. The joint move
        // settles on joints (0.2° at the tool); the jog's end point is only as exact as
        // the integration of the commanded velocity, so it is not held to a target.
        let (mm, deg) = match m.driver.component {
            55 => (1.0, 0.1),
            58 => (1.0, 0.2),
            _ => continue,
        };
        assert!(
            m.position_error_mm <= mm && m.angle_error_deg <= deg,
            "{m:?}"
        );
    }
    assert!(report.duration < 60.0);
}
