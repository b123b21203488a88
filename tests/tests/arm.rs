//! The stock manipulator components over the simulated arm on the in-process bus: the
//! demo's pick-and-place sequence, control, emergency, watchdogs and refusals.

mod common;
mod plots;

use std::process::Command;
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
        // Issue 13's settling target for the pose driver, and issue 51's for every move
        // with a target: 1 mm / 0.1° (the operator waits for the tool to settle in
        // position and orientation). The jog's end point is only as exact as the
        // integration of the commanded velocity, so it is not held to a target.
        let (mm, deg) = match m.driver.component {
            55 | 58 | 59 => (1.0, 0.1),
            _ => continue,
        };
        assert!(
            m.position_error_mm <= mm && m.angle_error_deg <= deg,
            "{m:?}"
        );
    }
    assert!(report.duration < 60.0);
}

#[test]
fn jaus_demo_arm_prints_the_table_and_writes_the_plot() {
    let dir = std::env::temp_dir().join(format!("jaus-arm-demo-{}", std::process::id()));
    let out = Command::new(common::jaus_bin())
        .args(["demo", "--arm", "--progress", "0", "--out"])
        .arg(&dir)
        .output()
        .expect("run jaus");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for row in [
        "pose: above the pick point",
        "joint move: to the place configuration",
        "velocity state: sideways jog",
        "discrete poses: a timed square",
        "6 moves in",
        "plot:",
    ] {
        assert!(stdout.contains(row), "missing {row:?} in\n{stdout}");
    }
    // Per move its hand-over and overshoot, in degrees.
    let measured = stdout
        .lines()
        .filter(|l| l.contains("hand-over") && l.contains("overshoot") && l.ends_with('°'))
        .count();
    assert_eq!(measured, 6, "{stdout}");
    let svg = std::fs::read_to_string(dir.join("arm.svg")).expect("arm.svg");
    // Where each move starts: a thin grey mark on the joint panel.
    assert_eq!(svg.matches(r##"fill="#A0A0A0""##).count(), 6, "move marks");
    let texts = plots::check_document(
        &svg,
        &[
            "time (s)",
            "joint angle (°)",
            "joint 1",
            "joint 6",
            "y, right (m)",
            "x, forward (m)",
            "height, −z (m)",
            "tool point (true)",
            "commanded target",
        ],
    );
    let traces = plots::traces(&svg);
    assert_eq!(
        traces.len(),
        8,
        "six joints and two views of the tool: {traces:?}"
    );
    let mut colours: Vec<&str> = traces.iter().map(|(c, _)| c.as_str()).collect();
    colours.sort();
    colours.dedup();
    assert_eq!(
        colours.len(),
        7,
        "a colour per joint, one for the tool: {traces:?}"
    );
    assert!(traces.iter().all(|(_, p)| p.len() > 50), "{traces:?}");
    // The time axis starts at 0 s: its first tick is 0, on the joint panel's left edge
    // (the leftmost vertical axis) where the joint traces start, and none is negative.
    // (Its ticks are those left of the side view's axis label.)
    let side = texts
        .iter()
        .find(|t| t.content == "height, −z (m)")
        .map_or(f64::INFINITY, |t| t.x);
    let ticks = plots::x_ticks(&texts, "time (s)", side);
    assert!(ticks.len() >= 4, "time ticks {ticks:?}");
    assert_eq!(ticks[0].1, 0.0, "time ticks {ticks:?}");
    assert!(ticks.iter().all(|(_, t)| *t >= 0.0), "time ticks {ticks:?}");
    assert!(
        ticks.windows(2).all(|w| w[1].1 > w[0].1),
        "time ticks {ticks:?}"
    );
    let axes = plots::y_axes(&svg);
    assert_eq!(axes.len(), 3, "joint panel and two views: {axes:?}");
    assert!(
        (ticks[0].0 - axes[0]).abs() <= 1.5,
        "the 0 s tick at x {} is not on the time axis' left end at {}",
        ticks[0].0,
        axes[0]
    );
    let starts: Vec<f64> = traces
        .iter()
        .filter_map(|(_, p)| p.first().map(|xy| xy.0))
        .filter(|x| *x < side)
        .collect();
    assert_eq!(starts.len(), 6, "six joint traces: {starts:?}");
    assert!(
        starts.iter().all(|x| (x - ticks[0].0).abs() <= 1.5),
        "joint traces start at x {starts:?}, the 0 s tick is at {}",
        ticks[0].0
    );
    let _ = std::fs::remove_dir_all(&dir);
}
