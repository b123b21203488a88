//! Issue 29: a component run on a real network carries the system's time in its time
//! stamps without anyone sending Set Time (the UDP shell gives the wall clock to every
//! component whose clock nobody set; the sans-IO runtime reads no clock itself).

use std::net::UdpSocket;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

use jaus::codec::{Decode, Encode};
use jaus::messages::{QueryTime, ReportTime};
use jaus::net::{udp, Framing, NodeConfig};
use jaus::{Address, Header, JausMessage, Packet};

#[test]
fn a_node_on_udp_reports_the_system_time_without_set_time() {
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let at = socket.local_addr().unwrap();
    let stop = Arc::new(AtomicBool::new(false));
    let s = stop.clone();
    let node = std::thread::spawn(move || {
        // A component with the default settings: no clock set (the demo's vehicle sets a
        // fixed one of its own, for its simulated day).
        struct Gps;
        impl jaus::components::global_pose_sensor::GlobalPoseSensor for Gps {}
        let t0 = Instant::now();
        let mut node = jaus::net::Node::new(NodeConfig::default(), t0);
        node.add(jaus::components::global_pose_sensor::component(
            Address::new(1, 1, 38, 1),
            Gps,
            jaus::component::Config::default(),
            t0,
        ))
        .unwrap();
        udp::run_on(&mut node, &socket, &s, None, |_| {}).unwrap();
    });
    let me = UdpSocket::bind("127.0.0.1:0").unwrap();
    me.set_read_timeout(Some(Duration::from_millis(100)))
        .unwrap();
    let header = Header::new(
        QueryTime::CODE,
        Address::new(1, 1, 38, 1),
        Address::new(9, 1, 40, 1),
    );
    let query = QueryTime {
        presence_vector: 0b11,
    };
    let bytes = Packet::new(header, query.to_bytes().unwrap())
        .to_bytes()
        .unwrap();
    let until = Instant::now() + Duration::from_secs(5);
    let report = loop {
        assert!(Instant::now() < until, "no Report Time");
        me.send_to(&Framing::Judp.encode(&bytes), at).unwrap();
        let mut buf = [0u8; 4096];
        let Ok((n, _)) = me.recv_from(&mut buf) else {
            continue;
        };
        let Ok((h, body)) = Framing::Judp.packet(&buf[..n]) else {
            continue;
        };
        if h.command_code == ReportTime::CODE {
            break ReportTime::from_bytes(body).unwrap();
        }
    };
    stop.store(true, Ordering::Relaxed);
    node.join().unwrap();
    let t = report.time_stamp.expect("a time stamp");
    let secs = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .unwrap()
        .as_secs();
    let (hour, minute) = ((secs / 3600) % 24, (secs / 60) % 60);
    let reported = u64::from(t.hour) * 60 + u64::from(t.minute);
    let now = hour * 60 + minute;
    // Within a minute of the system's clock (across midnight too).
    assert!(
        (reported + 1440 - now) % 1440 <= 1 || (now + 1440 - reported) % 1440 <= 1,
        "reported {}:{:02}, system {hour}:{minute:02}",
        t.hour,
        t.minute
    );
    assert!(report.date_stamp.is_some(), "a date stamp");
}
