//! The example vendor crate (`examples/vendor-rover`, written by `jaus-gen new`) on
//! loopback UDP, driven by the stock `jaus` CLI: the CLI discovers its Tank Monitor,
//! takes control, and sends the experimental command and query by name with the
//! vendor's overlay loaded at run time (`--spec defs/vendor_rover.yaml`); the replies
//! print by name in the JSON form of the vendor's generated crate. Without `--spec` the
//! same messages go and come back raw.

mod common;

use std::net::UdpSocket;
use std::process::Command;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use common::jaus_bin;
use jaus::net::NodeConfig;
use jaus::CommandCode;
use vendor_rover::messages::Message;

#[test]
fn the_stock_cli_drives_the_vendor_node_over_udp() {
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let node_addr = socket.local_addr().unwrap();
    let cli_port = common::free_port();
    let t0 = Instant::now();
    let config = NodeConfig {
        subsystem: 9,
        node: 1,
        peers: vec![format!("127.0.0.1:{cli_port}").parse().unwrap()],
        ..NodeConfig::default()
    };
    let mut node = vendor_rover::node(config, t0).unwrap();
    let stop = Arc::new(AtomicBool::new(false));
    let stop2 = stop.clone();
    let runner = std::thread::spawn(move || {
        let until = Some(Instant::now() + Duration::from_secs(30));
        jaus::net::udp::run_on(&mut node, &socket, &stop2, until, |_| {}).unwrap();
    });

    let cli = |args: &[&str], lines: &[&str]| {
        let out = Command::new(jaus_bin())
            .args(args)
            .args(["--me", "9.7.40.1", "--bind"])
            .arg(format!("127.0.0.1:{cli_port}"))
            .arg("--peer")
            .arg(node_addr.to_string())
            .args(lines)
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stdout).into_owned();
        assert!(
            out.status.success(),
            "{args:?}: {}\n{text}",
            String::from_utf8_lossy(&out.stderr)
        );
        text.lines()
            .map(|l| serde_json::from_str::<serde_json::Value>(l).unwrap())
            .collect::<Vec<_>>()
    };
    let spec = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/vendor-rover/defs/vendor_rover.yaml"
    );

    // Discovery: the vendor component is in the tree with its name and service.
    let out = Command::new(jaus_bin())
        .args(["discover", "--wait", "2", "--me", "9.7.40.1", "--bind"])
        .arg(format!("127.0.0.1:{cli_port}"))
        .arg("--peer")
        .arg(node_addr.to_string())
        .output()
        .unwrap();
    let tree = String::from_utf8_lossy(&out.stdout);
    assert!(
        tree.contains("9.1.210.1 'TankMonitor' services [0, 210]"),
        "{tree}"
    );

    // Control, Resume, the experimental command and query by name (`--spec`).
    let lines = cli(
        &["send", "--spec", spec, "--to", "9.1.210.1", "--hold", "2"],
        &[
            r#"{"message":"RequestComponentControl","fields":{"authority_code":10}}"#,
            r#"{"message":"Resume","fields":{}}"#,
            r#"{"message":"SetDrainValve","fields":{"tank":0,"open":1}}"#,
            r#"{"message":"QueryTankLevels"}"#,
        ],
    );
    // The reports print by name with their fields.
    let levels: Vec<Vec<f64>> = lines
        .iter()
        .filter(|l| l["message"] == "ReportTankLevels")
        .map(|l| {
            assert!(l["fields"]["time_stamp"].is_object(), "{l}");
            l["fields"]["levels"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect()
        })
        .collect();
    // The query alone returns as soon as its report (named by the overlay) is there.
    let answered = cli(
        &["query", "--spec", spec, "--to", "9.1.210.1"],
        &[r#"{"message":"QueryTankLevels"}"#],
    );
    assert!(
        answered.iter().any(|l| l["message"] == "ReportTankLevels"),
        "{answered:?}"
    );
    // A service connection on the vendor's report, named through the overlay.
    let watched = cli(
        &[
            "watch",
            "--spec",
            spec,
            "--to",
            "9.1.210.1",
            "--sc",
            "ReportTankLevels@5",
            "--seconds",
            "1.5",
        ],
        &[],
    );
    let streamed = watched
        .iter()
        .filter(|l| l["message"] == "ReportTankLevels" && l["header"]["service_connection"] == true)
        .count();
    assert!(streamed >= 3, "{watched:?}");
    // Without the overlay: the same query as a raw message, its report raw (the CLI
    // cannot know which report answers it, so `send` holds a second for it).
    let raw = cli(
        &["send", "--to", "9.1.210.1", "--hold", "1"],
        &[r#"{"message":"Raw","fields":{"code":"0xD100","body":""}}"#],
    );
    let raw_report = raw.iter().find(|l| l["message"] == "Raw").map(|l| {
        let code = CommandCode(l["fields"]["code"].as_u64().unwrap() as u16);
        Message::decode(code, &hex(l["fields"]["body"].as_str().unwrap())).unwrap()
    });
    assert!(
        matches!(raw_report, Some(Message::ReportTankLevels(_))),
        "{raw:?}"
    );
    stop.store(true, Ordering::Relaxed);
    runner.join().unwrap();
    assert!(levels.len() >= 3, "{lines:?}");
    // Tank 0 drains while its valve is open; tank 1 stays.
    let last = levels.last().unwrap();
    assert!(last[0] < 80.0 && (last[1] - 40.0).abs() < 0.01, "{last:?}");
}

fn hex(s: &str) -> Vec<u8> {
    (0..s.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&s[i..i + 2], 16).unwrap())
        .collect()
}

/// `jaus conform --spec` against the vendor node: the Tank Monitor's own command, read
/// back by its own query (`readback:` in the vendor's YAML), is checked on the wire like
/// the SDK's, from the controller (the valve opens, read back) and from a component not
/// in control (nothing changes); the run conforms.
#[test]
fn jaus_conform_checks_the_vendors_own_command_through_its_overlay() {
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let node_addr = socket.local_addr().unwrap();
    let tester_port = common::free_port();
    let t0 = Instant::now();
    let config = NodeConfig {
        subsystem: 9,
        node: 1,
        peers: vec![format!("127.0.0.1:{tester_port}").parse().unwrap()],
        ..NodeConfig::default()
    };
    let mut node = vendor_rover::node(config, t0).unwrap();
    let stop = Arc::new(AtomicBool::new(false));
    let stop2 = stop.clone();
    let runner = std::thread::spawn(move || {
        let until = Some(Instant::now() + Duration::from_secs(90));
        jaus::net::udp::run_on(&mut node, &socket, &stop2, until, |_| {}).unwrap();
    });
    let spec = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/vendor-rover/defs/vendor_rover.yaml"
    );
    let json =
        std::env::temp_dir().join(format!("jaus-vendor-conform-{}.json", std::process::id()));
    let out = Command::new(jaus_bin())
        .args([
            "conform",
            "--spec",
            spec,
            "--target",
            "9.1.210.1",
            "--me",
            "9.7.40.1",
        ])
        .args(["--settle-ms", "60", "--bind"])
        .arg(format!("127.0.0.1:{tester_port}"))
        .arg("--peer")
        .arg(node_addr.to_string())
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    stop.store(true, Ordering::Relaxed);
    runner.join().unwrap();
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let run: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let _ = std::fs::remove_file(&json);
    let outcomes = run["components"][0]["outcomes"].as_array().unwrap();
    let verdict = |id: &str| {
        outcomes
            .iter()
            .find(|o| o["id"] == id)
            .map(|o| {
                (
                    o["verdict"].as_str().unwrap().to_string(),
                    o["detail"].to_string(),
                )
            })
            .unwrap_or_else(|| panic!("{id} not run: {text}"))
    };
    let (v, detail) = verdict("readback.SetDrainValve");
    assert_eq!(v, "pass", "{detail}");
    assert!(detail.contains("open = 1"), "{detail}");
    assert_eq!(verdict("outsider.SetDrainValve").0, "pass");
    assert_eq!(verdict("query.QueryDrainValve").0, "pass");
    // The evidence names the overlay's messages.
    let evidence = outcomes
        .iter()
        .find(|o| o["id"] == "readback.SetDrainValve")
        .unwrap()["evidence"]
        .to_string();
    assert!(evidence.contains("\"ReportDrainValve\""), "{evidence}");
}
