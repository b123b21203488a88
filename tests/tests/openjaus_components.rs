//! OpenJAUS's local component interface (issue 15 item 3; docs/wire.md §8.5), both
//! sides, against byte-level test doubles written from the protocol's table (8-byte
//! control datagrams, raw JAUS packets on the data socket), not from this SDK's codec:
//!
//! * a `jaus node` serving `openjaus_components` gives a fake OpenJAUS component an
//!   address, answers its lookups, and routes a query from the network to it and its
//!   report back;
//! * `jaus attach` runs a stock component under a fake OpenJAUS node manager: check-in,
//!   heartbeat, a query answered, check-out.

mod common;

use std::io::{BufRead, BufReader};
use std::net::UdpSocket;
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use common::jaus_bin;

struct Running(Child);
impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// A 16-byte JAUS header (docs/wire.md §1.1) + body, written out by hand.
fn packet(code: u16, dst: [u8; 4], src: [u8; 4], body: &[u8]) -> Vec<u8> {
    let mut p = vec![0x06, 0x02]; // priority 6, version 2
    p.extend_from_slice(&code.to_le_bytes());
    // Addresses: instance, component, node, subsystem.
    p.extend_from_slice(&[dst[3], dst[2], dst[1], dst[0]]);
    p.extend_from_slice(&[src[3], src[2], src[1], src[0]]);
    p.extend_from_slice(&(body.len() as u16).to_le_bytes());
    p.extend_from_slice(&[0, 0]);
    p.extend_from_slice(body);
    p
}

fn recv(s: &UdpSocket, within: Duration) -> Option<(Vec<u8>, std::net::SocketAddr)> {
    s.set_read_timeout(Some(within)).unwrap();
    let mut buf = [0u8; 5000];
    s.recv_from(&mut buf)
        .ok()
        .map(|(n, a)| (buf[..n].to_vec(), a))
}

/// Waits for a datagram whose command code (bytes 2-3) is `code`.
fn recv_code(
    s: &UdpSocket,
    code: u16,
    within: Duration,
) -> Option<(Vec<u8>, std::net::SocketAddr)> {
    let end = Instant::now() + within;
    while Instant::now() < end {
        if let Some((d, a)) = recv(s, end.saturating_duration_since(Instant::now())) {
            if d.len() >= 16 && u16::from_le_bytes([d[2], d[3]]) == code {
                return Some((d, a));
            }
        }
    }
    None
}

#[test]
fn a_node_serves_an_openjaus_component_process() {
    let dir = std::env::temp_dir().join(format!("jaus-oj-node-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (pn, pc, pd) = (
        common::free_port(),
        common::free_port(),
        common::free_port(),
    );
    let cfg = dir.join("node.yaml");
    std::fs::write(
        &cfg,
        format!(
            "subsystem: 3\nnode: 1\nbind: 127.0.0.1:{pn}\nhost: [global_pose_sensor]\nopenjaus_components: {{ control: 127.0.0.1:{pc}, data: 127.0.0.1:{pd} }}\n"
        ),
    )
    .unwrap();
    let mut child = Command::new(jaus_bin())
        .args(["node", "--config"])
        .arg(&cfg)
        .args(["--seconds", "20"])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stdout.take().unwrap()).lines();
    let _node = Running(child);
    // Up once it prints the component interface.
    assert!(lines
        .by_ref()
        .take(20)
        .map_while(Result::ok)
        .any(|l| l.contains("OpenJAUS component interface")));

    let control = UdpSocket::bind("127.0.0.1:0").unwrap();
    let data = UdpSocket::bind("127.0.0.1:0").unwrap();
    let nm_control = format!("127.0.0.1:{pc}");
    let nm_data = format!("127.0.0.1:{pd}");
    // READY_CHECK -> REPORT_READY.
    control
        .send_to(&[0x0E, 0, 0, 0, 0, 0, 0, 0], &nm_control)
        .unwrap();
    assert_eq!(
        recv(&control, Duration::from_secs(2)).unwrap().0,
        [0x0F, 0, 0, 0, 0, 0, 0, 0]
    );
    // CHECK_IN as a Global Pose Sensor (id 38): the node hosts 3.1.38.1, so the
    // component gets instance 2: REPORT_ADDRESS [0x02, instance, component, node, ss].
    let port = data.local_addr().unwrap().port().to_le_bytes();
    control
        .send_to(&[0x01, 38, port[0], port[1], 0, 0, 0, 0], &nm_control)
        .unwrap();
    assert_eq!(
        recv(&control, Duration::from_secs(2)).unwrap().0,
        [0x02, 2, 38, 1, 3, 0, 0, 0]
    );
    // A refused id (0) gets no answer, as from OpenJAUS.
    control
        .send_to(&[0x01, 0, 0, 0, 0, 0, 0, 0], &nm_control)
        .unwrap();
    assert!(recv(&control, Duration::from_millis(300)).is_none());
    // The component's heartbeat (raw packet) makes the node learn its data socket.
    let me = [3, 1, 38, 2];
    let hb = packet(0x4202, [3, 1, 1, 1], me, &[]);
    data.send_to(&hb, &nm_data).unwrap();
    // A query from the network reaches it raw on its data socket ...
    let query = Command::new(jaus_bin())
        .args([
            "query", "--to", "3.1.38.2", "--me", "4.1.40.1", "--wait", "3",
        ])
        .arg("--bind")
        .arg(format!("127.0.0.1:{}", common::free_port()))
        .arg("--peer")
        .arg(format!("127.0.0.1:{pn}"))
        .arg(r#"{"message":"QueryGlobalPose","fields":{"presence_vector":3}}"#)
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut got = None;
    let end = Instant::now() + Duration::from_secs(5);
    while got.is_none() && Instant::now() < end {
        data.send_to(&hb, &nm_data).unwrap();
        got = recv_code(&data, 0x2402, Duration::from_millis(500));
    }
    let (q, _) = got.expect("Query Global Pose delivered to the component");
    assert_eq!(
        &q[4..8],
        &[2, 38, 1, 3],
        "addressed to 3.1.38.2, no framing before it"
    );
    let requester = [q[11], q[10], q[9], q[8]];
    // ... and its raw report goes back to the network.
    let lat = 0x8000_0000u32.to_le_bytes(); // the middle of the ±90° range
    let body = [&[3u8, 0][..], &lat, &lat].concat();
    data.send_to(&packet(0x4402, requester, me, &body), &nm_data)
        .unwrap();
    let out = query.wait_with_output().unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("\"ReportGlobalPose\""), "{text}");
    assert!(text.contains("\"source\":[3,1,38,2]"), "{text}");
    // Lookups in the system tree: VERIFY_ADDRESS, LOOKUP_ADDRESS with wildcards.
    control
        .send_to(&[0x04, 1, 38, 1, 3, 0, 0, 0], &nm_control)
        .unwrap();
    assert_eq!(
        recv(&control, Duration::from_secs(2)).unwrap().0[..2],
        [0x05, 1]
    );
    control
        .send_to(&[0x08, 0, 38, 0, 0, 0, 0, 0], &nm_control)
        .unwrap();
    let r = recv(&control, Duration::from_secs(2)).unwrap().0;
    assert_eq!((r[0], r[2], r[5]), (0x09, 38, 1), "{r:?}");
    // CHECK_OUT frees the instance for the next check-in.
    control
        .send_to(&[0x03, 2, 38, 1, 3, 0, 0, 0], &nm_control)
        .unwrap();
    std::thread::sleep(Duration::from_millis(100));
    control
        .send_to(&[0x01, 38, port[0], port[1], 0, 0, 0, 0], &nm_control)
        .unwrap();
    assert_eq!(
        recv(&control, Duration::from_secs(2)).unwrap().0,
        [0x02, 2, 38, 1, 3, 0, 0, 0]
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_stock_component_runs_under_an_openjaus_node_manager() {
    let control = UdpSocket::bind("127.0.0.1:0").unwrap();
    let data = UdpSocket::bind("127.0.0.1:0").unwrap();
    let child = Command::new(jaus_bin())
        .args(["attach", "--host", "global_pose_sensor", "--seconds", "4"])
        .arg("--control")
        .arg(control.local_addr().unwrap().to_string())
        .arg("--data")
        .arg(data.local_addr().unwrap().to_string())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let _running = Running(child);
    // CHECK_IN for id 38 with its data port; the fake node manager 10.1 gives 10.1.38.1.
    let (req, from) = recv(&control, Duration::from_secs(5)).expect("a check-in");
    assert_eq!((req.len(), req[0], req[1]), (8, 0x01, 38), "{req:?}");
    control
        .send_to(&[0x02, 1, 38, 1, 10, 0, 0, 0], from)
        .unwrap();
    // Its heartbeat arrives raw on the data socket, to the node manager 10.1.1.1.
    let (hb, component) =
        recv_code(&data, 0x4202, Duration::from_secs(3)).expect("a heartbeat from the component");
    assert_eq!(
        &hb[4..12],
        &[1, 1, 1, 10, 1, 38, 1, 10],
        "10.1.38.1 -> 10.1.1.1"
    );
    assert_eq!(
        component.port(),
        u16::from_le_bytes([req[2], req[3]]),
        "the data port it announced"
    );
    // A query sent to it is answered.
    let q = packet(0x2402, [10, 1, 38, 1], [10, 2, 40, 1], &[3, 0]);
    data.send_to(&q, component).unwrap();
    let (r, _) = recv_code(&data, 0x4402, Duration::from_secs(3)).expect("Report Global Pose");
    assert_eq!(&r[4..8], &[1, 40, 2, 10], "to the requester 10.2.40.1");
    // At the end it checks out: CHECK_OUT [0x03, 1, 38, 1, 10].
    let end = Instant::now() + Duration::from_secs(8);
    let mut out = None;
    while out.is_none() && Instant::now() < end {
        if let Some((d, _)) = recv(&control, Duration::from_millis(500)) {
            if d[0] == 0x03 {
                out = Some(d);
            }
        }
    }
    assert_eq!(out.expect("a check-out")[..5], [0x03, 1, 38, 1, 10]);
}
