//! The judge's side of the AS-4 IOP scenario (`jaus_conform::as4`) against a small
//! fake vehicle: in memory on a virtual clock, and over UDP on loopback; a vehicle
//! that gets a step wrong fails that step's check.

mod as4_fake;

use std::net::UdpSocket;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use as4_fake::{FakeVehicle, Faults, VEHICLE};
use jaus::net::Participant;
use jaus_conform::as4::udp::UdpAs4Session;
use jaus_conform::as4::{check_ids, run_as4, As4Host, As4Options, As4Session, MemoryAs4Session};
use jaus_conform::{report, RunReport, Verdict};

fn run_fake(faults: Faults, opts: As4Options) -> (RunReport, MemoryAs4Session) {
    let t0 = Instant::now();
    let mut session = MemoryAs4Session::new(As4Host::new(FakeVehicle::new(faults)), t0);
    session.record();
    let run = run_as4(&mut session, &opts);
    println!("{}", report::summary(&run));
    for o in &run.components[0].outcomes {
        println!("{} {:?}: {}", o.check.id, o.verdict, o.detail);
    }
    (run, session)
}

fn verdict(run: &RunReport, id: &str) -> (Verdict, String) {
    let o = run.components[0]
        .outcomes
        .iter()
        .find(|o| o.check.id == id)
        .unwrap_or_else(|| panic!("{id} not in the run"));
    (o.verdict, o.detail.clone())
}

fn with_motion() -> As4Options {
    As4Options {
        allow_motion: true,
        ..As4Options::default()
    }
}

fn fake(session: &mut MemoryAs4Session) -> &FakeVehicle {
    session
        .target()
        .as_any()
        .downcast_ref::<As4Host<FakeVehicle>>()
        .expect("the fake")
        .endpoint()
}

#[test]
fn the_whole_scenario_passes_against_a_vehicle_that_does_it_right() {
    let (run, mut session) = run_fake(Faults::default(), with_motion());
    let c = &run.components[0];
    assert_eq!(c.address, VEHICLE.to_string());
    assert_eq!(c.identification.as_deref(), Some("fake vehicle"));
    let ids: Vec<&str> = c.outcomes.iter().map(|o| o.check.id.as_str()).collect();
    assert_eq!(
        ids,
        check_ids(&with_motion()),
        "every check, in the scenario's order"
    );
    let not_passed: Vec<_> = c
        .outcomes
        .iter()
        .filter(|o| o.verdict != Verdict::Pass)
        .map(|o| (&o.check.id, &o.detail))
        .collect();
    assert!(not_passed.is_empty(), "{not_passed:?}");
    assert!(run.passed());
    // The list was driven to its end, and the time it took is said.
    let (_, detail) = verdict(&run, "as4.waypoints.active_element");
    assert!(detail.starts_with("[1, 2, 3"), "{detail}");
    assert!(detail.contains(" s"), "{detail}");
    // Query Identification every 5 s: the mission took several seconds.
    let (_, detail) = verdict(&run, "as4.discovery.periodic");
    let sent: u32 = detail.split(' ').next().unwrap().parse().unwrap();
    assert!(sent >= 2, "{detail}");
    // Each check keeps its messages; the judge gave control back last, leaving the
    // vehicle in Standby as it found it (no Shutdown unless asked).
    assert!(c.outcomes.iter().all(|o| !o.evidence.is_empty()));
    let v = fake(&mut session);
    assert_eq!(v.state(), jaus_as4::ComponentState::Standby);
    assert_eq!(v.seen.last().map(String::as_str), Some("QueryStatus"));
    let (x, y) = v.position();
    assert!((x - 3.0).abs() < 0.1 && (y - 0.0).abs() < 0.1, "{x}, {y}");
    // Every datagram was AS5669A, recorded for a pcap.
    let rec = session.take_recording();
    assert!(rec.datagrams.len() > 50, "{}", rec.datagrams.len());
    assert!(rec.datagrams.iter().all(|d| d.bytes.first() == Some(&2)));
    // The reports read the same way as the RA 3.3 ones.
    let junit = report::junit(&run);
    assert!(junit.contains("name=\"as4.waypoints.execute\""), "{junit}");
    assert_eq!(junit.matches("<failure ").count(), 0);
    assert!(report::html(&run).contains("as4.velocity.pv0140"));
}

#[test]
fn without_allow_motion_the_list_is_loaded_but_not_driven() {
    let (run, mut session) = run_fake(Faults::default(), As4Options::default());
    for id in [
        "as4.waypoints.execute",
        "as4.waypoints.active_element",
        "as4.waypoints.travel_speed",
        "as4.waypoints.local_waypoint",
    ] {
        let (v, detail) = verdict(&run, id);
        assert_eq!(v, Verdict::Inconclusive, "{id}: {detail}");
        assert!(detail.contains("--allow-motion"), "{detail}");
    }
    assert_eq!(
        verdict(&run, "as4.waypoints.element_count").0,
        Verdict::Pass
    );
    assert!(run.passed());
    let v = fake(&mut session);
    assert!(!v.seen.iter().any(|m| m == "ExecuteList"));
    let (x, y) = v.position();
    assert!(
        (x - 3.0).abs() < 1e-3 && (y + 2.0).abs() < 1e-3,
        "the pose set, never moved: {x}, {y}"
    );
}

#[test]
fn report_control_naming_someone_else_fails_the_control_request() {
    let (run, _) = run_fake(
        Faults {
            wrong_controller: true,
            ..Faults::default()
        },
        As4Options::default(),
    );
    let (v, detail) = verdict(&run, "as4.control.request");
    assert_eq!(v, Verdict::Fail, "{detail}");
    assert!(detail.contains("42.1.2"), "{detail}");
    assert!(!run.passed());
}

#[test]
fn a_vehicle_ignoring_resume_fails_the_resume_check() {
    let (run, _) = run_fake(
        Faults {
            ignore_resume: true,
            ..Faults::default()
        },
        with_motion(),
    );
    let (v, detail) = verdict(&run, "as4.management.resume");
    assert_eq!(v, Verdict::Fail, "{detail}");
    assert!(detail.contains("Standby after Resume"), "{detail}");
    // Never Ready: the commands that need it are not judged on it.
    assert_eq!(verdict(&run, "as4.pose.set_local").0, Verdict::Inconclusive);
    assert!(!run.passed());
}

#[test]
fn extra_velocity_fields_fail_the_presence_vector_check() {
    let (run, _) = run_fake(
        Faults {
            all_velocity_fields: true,
            ..Faults::default()
        },
        As4Options::default(),
    );
    let (v, detail) = verdict(&run, "as4.velocity.pv0140");
    assert_eq!(v, Verdict::Fail);
    assert!(
        detail.contains("0x01FF") && detail.contains("velocity_x"),
        "{detail}"
    );
}

#[test]
fn a_list_never_finished_fails_after_the_mission_timeout_and_stops_the_vehicle() {
    let (run, mut session) = run_fake(
        Faults {
            stuck: true,
            ..Faults::default()
        },
        As4Options {
            mission_timeout: Duration::from_secs(8),
            ..with_motion()
        },
    );
    let (v, detail) = verdict(&run, "as4.waypoints.active_element");
    assert_eq!(v, Verdict::Fail, "{detail}");
    assert!(
        detail.contains("not done after") && detail.contains("Standby"),
        "{detail}"
    );
    assert!(fake(&mut session).seen.iter().any(|m| m == "Standby"));
}

#[test]
fn nothing_answering_leaves_every_later_check_not_run() {
    let t0 = Instant::now();
    let node = jaus::net::Node::new(Default::default(), t0);
    let mut session = MemoryAs4Session::new(node, t0);
    let run = run_as4(&mut session, &As4Options::default());
    let c = &run.components[0];
    assert_eq!(c.outcomes[0].verdict, Verdict::Fail);
    assert!(c.outcomes[1..]
        .iter()
        .all(|o| o.verdict == Verdict::Inconclusive));
    assert!(!run.passed());
}

/// The fake on a loopback socket, served by a thread until `stop`.
fn serve(socket: UdpSocket, stop: Arc<AtomicBool>) -> std::thread::JoinHandle<()> {
    std::thread::spawn(move || {
        let mut host = As4Host::new(FakeVehicle::new(Faults::default()));
        socket
            .set_read_timeout(Some(Duration::from_millis(5)))
            .expect("timeout");
        let mut buf = vec![0u8; 65_536];
        while !stop.load(Ordering::Relaxed) {
            if let Ok((n, from)) = socket.recv_from(&mut buf) {
                host.handle_datagram(Instant::now(), from, &buf[..n]);
            }
            host.handle_timeout(Instant::now());
            while let Some(d) = host.poll_transmit() {
                let _ = socket.send_to(&d.bytes, d.to);
            }
        }
    })
}

#[test]
fn the_scenario_runs_over_udp() {
    let vehicle = UdpSocket::bind("127.0.0.1:0").expect("bind");
    let addr = vehicle.local_addr().expect("addr");
    let stop = Arc::new(AtomicBool::new(false));
    let server = serve(vehicle, stop.clone());
    let judge = UdpSocket::bind("127.0.0.1:0").expect("bind");
    let mut session = UdpAs4Session::new(judge, addr).expect("session");
    session.record();
    let opts = As4Options {
        vehicle: Some(addr),
        allow_motion: true,
        // Quicker than the IOP's 5 s, so that the test takes seconds.
        periodic: Duration::from_millis(500),
        settle: Duration::from_millis(50),
        ..As4Options::default()
    };
    let run = run_as4(&mut session, &opts);
    stop.store(true, Ordering::Relaxed);
    server.join().expect("server");
    println!("{}", report::summary(&run));
    assert!(session.heard());
    assert_eq!(run.peer, addr.to_string());
    let failed: Vec<_> = run.components[0]
        .outcomes
        .iter()
        .filter(|o| o.verdict != Verdict::Pass)
        .map(|o| (&o.check.id, &o.detail))
        .collect();
    assert!(failed.is_empty(), "{failed:?}");
    let rec = session.take_recording();
    assert!(rec.datagrams.iter().any(|d| d.from == addr));
}
