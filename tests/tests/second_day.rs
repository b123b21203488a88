//! Issue 29, a vendor's second day, the walls of the CLI and the runtime repeated
//! against a `jaus node` process hosting the demo vehicle (subsystem 21):
//!
//! 1. a refusal's reason reaches the sender: the CLI prints it from the SDK's Report
//!    Refusal beside the NAK (not "the receiver's log names the reason");
//! 2. a command nobody acknowledged fails with what the system tree says (no such
//!    component on a known node, no such node), and Clear Emergency from a sender that
//!    set no emergency is refused with the reason instead of acknowledged;
//! 8. a vendor's message name without `--spec` says an overlay is needed.

mod common;

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Output, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use common::{free_port, jaus_bin};

struct Running(Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// The demo vehicle as subsystem 21 in a `jaus node` process; its socket's port.
fn vehicle() -> (Running, u16) {
    let dir = std::env::temp_dir().join(format!("jaus-second-day-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let port = free_port();
    let cfg = dir.join(format!("vehicle-{port}.yaml"));
    std::fs::write(
        &cfg,
        format!("subsystem: 21\nnode: 1\nbind: 127.0.0.1:{port}\nhost: [vehicle]\n"),
    )
    .unwrap();
    let mut child = Command::new(jaus_bin())
        .args(["node", "--seconds", "60", "--config"])
        .arg(&cfg)
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let out = child.stdout.take().unwrap();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(out).lines().map_while(Result::ok) {
            let _ = tx.send(line);
        }
    });
    let until = Instant::now() + Duration::from_secs(15);
    loop {
        let line = rx
            .recv_timeout(until.saturating_duration_since(Instant::now()))
            .expect("the vehicle's tree");
        if line.contains("21.1.45.1") {
            break;
        }
    }
    (Running(child), port)
}

/// `jaus send` as `me` to the vehicle with `messages`.
fn send(port: u16, me: &str, to: &str, messages: &[&str], extra: &[&str]) -> (Output, String) {
    let out = Command::new(jaus_bin())
        .args(["send", "--me", me, "--to", to])
        .args(["--peer", &format!("127.0.0.1:{port}")])
        .args(["--bind", &format!("127.0.0.1:{}", free_port())])
        .args(extra)
        .args(messages)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    (out, err)
}

const SPEED_50: &str = r#"{"message":"SetTravelSpeed","fields":{"speed":50}}"#;
const CONTROL: &str = r#"{"message":"RequestComponentControl","fields":{"authority_code":200}}"#;
const EMERGENCY: &str =
    r#"{"message":"SetEmergency","fields":{"emergency_code":{"transition_to_emergency":true}}}"#;
const CLEAR: &str =
    r#"{"message":"ClearEmergency","fields":{"emergency_code":{"clear_emergency":true}}}"#;

#[test]
fn refusals_and_silence_reach_the_sender_with_their_reasons() {
    let (_v, port) = vehicle();

    // 1. Without control: NAKed, and the reason is printed by the sender.
    let (out, err) = send(port, "222.1.40.1", "21.1.45.1", &[SPEED_50], &[]);
    assert!(!out.status.success());
    assert!(
        err.contains(
            "NAK from 21.1.45.1 for SetTravelSpeed: sender is not the component in control"
        ),
        "{err}"
    );
    // With control, out of the component's own limit: the field, value and limit.
    let (out, err) = send(port, "222.1.40.1", "21.1.45.1", &[CONTROL, SPEED_50], &[]);
    assert!(!out.status.success());
    assert!(
        err.contains("NAK from 21.1.45.1 for SetTravelSpeed: field `speed` = 50")
            && err.contains("is outside this component's limit [0, 2] m/s"),
        "{err}"
    );
    assert!(err.contains("1 command(s) refused (NAK)"), "{err}");

    // 2. No such component on a node the system knows: named, with what the node has.
    let (out, err) = send(port, "222.1.40.1", "21.1.99.1", &[SPEED_50], &[]);
    assert!(!out.status.success(), "{err}");
    assert!(
        err.contains("SetTravelSpeed to 21.1.99.1: no such component: node 21.1 lists")
            && err.contains("21.1.45.1"),
        "{err}"
    );
    assert!(err.contains("1 command(s) not acknowledged"), "{err}");
    // No such node at all.
    let (out, err) = send(
        port,
        "222.1.40.1",
        "30.1.99.1",
        &[SPEED_50],
        &["--wait", "1"],
    );
    assert!(!out.status.success(), "{err}");
    assert!(err.contains("no node 30.1 answered"), "{err}");

    // 2. Clear Emergency from another run (another sender) is refused with the reason;
    // the one that set it clears it.
    let (out, err) = send(port, "223.1.40.1", "21.1.33.1", &[EMERGENCY], &[]);
    assert!(out.status.success(), "{err}");
    let (out, err) = send(port, "224.1.40.1", "21.1.33.1", &[CLEAR], &[]);
    assert!(!out.status.success(), "{err}");
    assert!(
        err.contains("NAK from 21.1.33.1 for ClearEmergency: this sender set no emergency; only the sender that set an emergency may clear it (set by 223.1.40.1)"),
        "{err}"
    );
    let (out, err) = send(port, "223.1.40.1", "21.1.33.1", &[CLEAR], &[]);
    assert!(out.status.success(), "{err}");
}

#[test]
fn a_vendor_message_without_its_overlay_says_so() {
    let out = Command::new(jaus_bin())
        .args(["encode"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .and_then(|mut c| {
            use std::io::Write;
            c.stdin
                .take()
                .unwrap()
                .write_all(br#"{"message":"SetImplementHeight","fields":{"height":1}}"#)?;
            c.wait_with_output()
        })
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("no message named `SetImplementHeight`"),
        "{err}"
    );
    assert!(err.contains("needs its YAML overlay, e.g. --spec"), "{err}");
    let out = Command::new(jaus_bin())
        .args(["messages", "SetImplementHeight"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("needs its YAML overlay"), "{err}");
}
