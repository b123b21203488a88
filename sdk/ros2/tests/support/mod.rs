//! Shared by the tests that play a ROS 2 robot or operator with Python's `cyclonedds`
//! (jaus-ros2's `cyclone.rs` and `vehicle.rs`, jaus-cli's `ros2_iop.rs`, which includes
//! this file by path): finding the interpreter, and skipping (or, in CI, failing) when
//! there is none.

use std::io::Write;
use std::process::Command;

/// Says why test `test` is skipped on the real stderr (the harness captures
/// `println!`); with `JAUS_REQUIRE_ROS2=1` (CI, once it installed cyclonedds) a skip is
/// a failure.
pub fn skip(test: &str, why: &str) {
    if std::env::var("JAUS_REQUIRE_ROS2").is_ok_and(|v| v == "1") {
        panic!("JAUS_REQUIRE_ROS2=1 but the test cannot run: {why}");
    }
    let _ = writeln!(std::io::stderr(), "SKIPPED {test}: {why}");
}

/// The Python of `JAUS_ROS2_PYTHON` when it imports `cyclonedds`; else test `test` is
/// skipped ([`skip`]) and `None`.
pub fn python(test: &str) -> Option<String> {
    let Ok(py) = std::env::var("JAUS_ROS2_PYTHON") else {
        skip(
            test,
            "set JAUS_ROS2_PYTHON to a python with the cyclonedds package \
             (python3 -m venv /tmp/ros2venv && /tmp/ros2venv/bin/pip install cyclonedds; \
             JAUS_ROS2_PYTHON=/tmp/ros2venv/bin/python)",
        );
        return None;
    };
    let ok = Command::new(&py)
        .args(["-c", "import cyclonedds"])
        .output()
        .map(|o| o.status.success())
        .unwrap_or(false);
    if !ok {
        skip(
            test,
            &format!("{py} cannot import cyclonedds (pip install cyclonedds)"),
        );
        return None;
    }
    Some(py)
}
