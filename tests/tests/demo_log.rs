//! Issue 37: the main job (`jaus demo`) runs without a single warning or error in its log,
//! and its waypoint legs hold the line through their corners.
//! (It once logged the Primitive Driver refusing a Set Wrench Effort from the Reflexive
//! Driver: the spooler borrows the Primitive Driver for the mission's payload action,
//! and the Reflexive Driver's brake crossed the Reject Component Control. Such a
//! crossing is normal in JAUS and is now logged at debug; a command from a sender that
//! never had control is still a warning.)

mod common;

use common::LogBuffer;

#[test]
fn the_demo_logs_no_warning_and_no_error() {
    let log = LogBuffer::default();
    let _guard = log.capture();
    let run = jaus_sim::demo::run(&jaus_sim::demo::Options::default(), |_| {}).expect("the demo");
    assert!(!run.legs.is_empty());
    let text = log.text();
    assert!(text.is_empty(), "the demo logged:\n{text}");
}

/// Every waypoint leg of the demo within 0.10 m of its line (they overshot 0.22 m at
/// the corners before the drivers slowed into turns and eased out of them), for the
/// demo's seed and a few others; the path-segment legs stay within 0.15 m.
#[test]
fn the_demo_holds_the_line_through_its_corners() {
    for seed in [7, 1, 2] {
        let opts = jaus_sim::demo::Options {
            seed,
            ..Default::default()
        };
        let run = jaus_sim::demo::run(&opts, |_| {}).expect("the demo");
        let waypoints: Vec<_> = run
            .legs
            .iter()
            .filter(|l| l.name.starts_with("waypoint"))
            .collect();
        assert_eq!(waypoints.len(), 5);
        for leg in waypoints {
            assert!(
                leg.xte_max <= 0.10,
                "seed {seed}: {} strays {:.3} m",
                leg.name,
                leg.xte_max
            );
        }
        for leg in run.legs.iter().filter(|l| l.name.starts_with("path")) {
            assert!(
                leg.xte_max <= 0.15,
                "seed {seed}: {} strays {:.3} m",
                leg.name,
                leg.xte_max
            );
        }
    }
}
