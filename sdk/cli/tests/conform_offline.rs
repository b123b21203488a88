//! `jaus conform --from-pcap`: a capture written with the CLI's own capture writer,
//! with an outsider's Standby carried out and a query left unanswered, judged by the
//! `jaus` binary.

use std::net::SocketAddr;
use std::path::Path;
use std::process::Command;
use std::time::Duration;

use jaus::codec::Encode;
use jaus::messages::{
    ComponentState, ConfirmComponentControl, ControlResponse, QueryComponentStatus,
    ReportComponentStatus, RequestComponentControl, Standby,
};
use jaus::net::Framing;
use jaus::{Address, Header, JausMessage, Packet};
use jaus_client::capture::CaptureWriter;

const TARGET: Address = Address::new(1, 1, 33, 1);
const CONTROLLER: Address = Address::new(1, 2, 40, 1);
const OUTSIDER: Address = Address::new(1, 2, 40, 4);

fn socket(a: Address) -> SocketAddr {
    SocketAddr::from(([127, 0, 0, a.node], 3794))
}

/// Writes `packets` (time in ms, source, destination, message) as JUDP datagrams,
/// after a DNS query (frame 1, no JAUS traffic) when `noise`.
fn write(path: &Path, packets: &[(u64, Address, Address, Vec<u8>)], noise: bool) {
    let mut w = CaptureWriter::create(path).unwrap();
    if noise {
        let dns: SocketAddr = "127.0.0.53:53".parse().unwrap();
        let t = Duration::from_secs(1_700_000_000);
        let me: SocketAddr = "127.0.0.9:40000".parse().unwrap();
        w.write(t, me, dns, &[0xAB, 0xCD, 1, 0, 0, 1]).unwrap();
    }
    for (ms, from, to, bytes) in packets {
        let t = Duration::from_secs(1_700_000_000) + Duration::from_millis(*ms);
        w.write(t, socket(*from), socket(*to), &Framing::Judp.encode(bytes))
            .unwrap();
    }
    w.flush().unwrap();
}

fn packet<M: JausMessage>(
    ms: u64,
    from: Address,
    to: Address,
    m: &M,
) -> (u64, Address, Address, Vec<u8>) {
    let p = Packet::new(Header::new(M::CODE, to, from), m.to_bytes().unwrap());
    (ms, from, to, p.to_bytes().unwrap())
}

fn status(ms: u64, state: ComponentState) -> (u64, Address, Address, Vec<u8>) {
    let r = ReportComponentStatus {
        primary_status_code: state,
        secondary_status_code: 0,
    };
    packet(ms, TARGET, OUTSIDER, &r)
}

fn conform(path: &Path, extra: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_jaus"))
        .args(["conform", "--from-pcap"])
        .arg(path)
        .args(extra)
        .output()
        .unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.code(), text)
}

#[test]
fn a_capture_is_judged_offline_naming_its_packets() {
    let dir = std::env::temp_dir().join(format!("jaus-conform-offline-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let accepted = ConfirmComponentControl {
        response_code: ControlResponse::ControlAccepted,
    };
    let mut packets = vec![
        packet(
            0,
            CONTROLLER,
            TARGET,
            &RequestComponentControl { authority_code: 0 },
        ), // 1
        packet(1, TARGET, CONTROLLER, &accepted), // 2
        packet(10, OUTSIDER, TARGET, &QueryComponentStatus {}), // 3
        status(11, ComponentState::Ready),        // 4
    ];
    let clean = dir.join("clean.pcapng");
    let mut last = packets.clone();
    last.push(packet(2000, CONTROLLER, TARGET, &QueryComponentStatus {}));
    last.push(packet(
        2001,
        TARGET,
        CONTROLLER,
        &ReportComponentStatus::default(),
    ));
    write(&clean, &last, false);
    let (code, text) = conform(&clean, &[]);
    assert_eq!(code, Some(0), "{text}");
    assert!(
        text.contains("CONFORMS") && !text.contains("DOES NOT"),
        "{text}"
    );

    packets.push(packet(20, OUTSIDER, TARGET, &Standby {})); // frame 6: carried out
    packets.push(status(25, ComponentState::Standby)); // 6
    packets.push(packet(100, OUTSIDER, TARGET, &QueryComponentStatus {})); // frame 8: no answer
    packets.push(packet(3000, CONTROLLER, TARGET, &QueryComponentStatus {})); // 8
    let faulty = dir.join("faulty.pcapng");
    write(&faulty, &packets, true);
    let json = dir.join("run.json");
    let (code, text) = conform(&faulty, &["--json", json.to_str().unwrap()]);
    eprintln!("{text}");
    let report = std::fs::read_to_string(&json).unwrap_or_default();
    let _ = std::fs::remove_dir_all(&dir);
    assert_eq!(code, Some(1), "{text}");
    assert!(report.contains("\"offline.query.answered\""), "{report}");
    assert!(text.contains("DOES NOT CONFORM"), "{text}");
    assert!(
        text.contains("8 JAUS datagrams judged, 1 other UDP datagrams left aside"),
        "{text}"
    );
    assert!(
        text.contains("FAIL offline.control.outsider [required"),
        "{text}"
    );
    assert!(text.contains("Standby from 1.2.40.4 (not in control; 1.2.40.1 was) at packet 6 was carried out: Report Component Status at packet 7 shows Standby"), "{text}");
    assert!(
        text.contains("QueryComponentStatus from 1.2.40.4 (packet 8)"),
        "{text}"
    );
    assert!(
        text.contains("capture ending less than 1.0 s after them: packet 9"),
        "{text}"
    );

    // The live-only options are refused.
    let (code, text) = conform(&faulty, &["--target", "1.1.33.1"]);
    assert_eq!(code, Some(2), "{text}");
}

/// A UDP port free on 127.0.0.1 now.
fn free_port() -> u16 {
    std::net::UdpSocket::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port()
}

/// Our own node, captured while `jaus conform` tests one of its components: judged
/// offline, none of the node's components fails a required check (the tester's voices
/// do: its robustness checks send malformed packets on purpose).
#[test]
fn our_own_node_captured_under_test_has_no_required_failure() {
    let dir = std::env::temp_dir().join(format!("jaus-conform-own-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (node_port, tester_port) = (free_port(), free_port());
    let config = dir.join("node.yaml");
    std::fs::write(
        &config,
        format!(
            "subsystem: 1\nnode: 1\nbind: 127.0.0.1:{node_port}\nhost: [vehicle]\npeers: [127.0.0.1:{tester_port}]\n"
        ),
    )
    .unwrap();
    let capture = dir.join("node.pcapng");
    let mut node = Command::new(env!("CARGO_BIN_EXE_jaus"))
        .args(["node", "--seconds", "25", "--config"])
        .arg(&config)
        .arg("--capture")
        .arg(&capture)
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(Duration::from_secs(2));
    let live = Command::new(env!("CARGO_BIN_EXE_jaus"))
        .args(["conform", "--target", "1.1.42.1", "--me", "200.1.1.1"])
        .args(["--peer", &format!("127.0.0.1:{node_port}")])
        .args(["--bind", &format!("127.0.0.1:{tester_port}")])
        .output()
        .unwrap();
    let status = node.wait().unwrap();
    let live_text = String::from_utf8_lossy(&live.stdout).to_string();
    assert!(status.success(), "jaus node: {status}");
    assert_eq!(live.status.code(), Some(0), "{live_text}");
    let json = dir.join("run.json");
    let (_, text) = conform(&capture, &["--json", json.to_str().unwrap()]);
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let components = report["components"].as_array().unwrap();
    let ours: Vec<&serde_json::Value> = components
        .iter()
        .filter(|c| c["address"].as_str().unwrap().starts_with("1.1."))
        .collect();
    assert!(ours.len() > 10, "{text}");
    for c in &ours {
        for o in c["outcomes"].as_array().unwrap() {
            assert!(
                !(o["verdict"] == "fail" && o["level"] == "required"),
                "{}: {o}\n{text}",
                c["address"]
            );
        }
    }
    let tested = ours.iter().find(|c| c["address"] == "1.1.42.1").unwrap();
    let ids: Vec<&str> = tested["outcomes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| o["id"].as_str().unwrap())
        .collect();
    for id in [
        "offline.packet.malformed",
        "offline.query.answered",
        "offline.control.outsider",
    ] {
        assert!(ids.contains(&id), "{id} not judged: {text}");
    }
}
