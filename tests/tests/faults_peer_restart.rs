//! A peer that restarts as a new process (issue 35): a `jaus node` hosting the demo
//! vehicle (`host: [vehicle]`) is driven by an operator station (the logic of `jaus
//! ocu`, `jaus::stock::commander::Station`, on a UDP node of the test) that holds
//! control of the Global Waypoint Driver and follows the vehicle's pose and velocity
//! through service connections. In the middle of a move the vehicle's process is
//! killed with SIGKILL and started again:
//!
//! * at once (faster than the operator's node can tell a node went away: its heartbeats
//!   barely pause), and
//! * after the operator's system tree dropped the node (its node timeout, 5 s).
//!
//! Either way the operator's tree lists the vehicle's components again, its service
//! connections are asked for again and deliver the new process's reports, control is
//! asked for again and granted (the new process reports the station as its
//! controller), and the vehicle stays still until the operator commands a move again,
//! which it then makes.

mod common;

use std::time::{Duration, Instant};

use common::process::{free_addr, node_file, test_dir, NodeProcess};
use common::station::{component, components_of, StationNode};
use jaus::stock::commander::{Command, GeoPoint, SystemView};
use jaus::Address;
use jaus_sim::demo::{addr, ORIGIN};

const ME: Address = Address::new(1, 2, 40, 1);
/// Components of the demo vehicle's node (its node manager among them).
const VEHICLE_COMPONENTS: usize = 14;

/// The vehicle subsystem's view.
fn vehicle(v: &SystemView) -> Option<&jaus::stock::commander::view::SubsystemView> {
    v.subsystems.iter().find(|s| s.id == 1)
}

/// Control of the waypoint driver held by the station and so reported by the driver.
fn in_control(v: &SystemView) -> bool {
    component(v, addr::GWD)
        .is_some_and(|c| c.held && c.controller.as_deref() == Some(&ME.to_string()[..]))
}

/// A pose received within the last 0.3 s, and the speed the station last heard.
fn fresh_pose(v: &SystemView) -> Option<((f64, f64), f64)> {
    let s = vehicle(v)?;
    let p = s.pose.as_ref().filter(|p| p.age_s < 0.3)?;
    Some(((p.x, p.y), s.velocity.as_ref().map_or(0.0, |v| v.speed)))
}

/// A point `north` metres north of the demo's origin.
fn north(metres: f64) -> GeoPoint {
    let f = jaus::stock::geo::LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2);
    // Local x is north, y east.
    let (latitude, longitude) = f.to_global(jaus::stock::nalgebra::Vector2::new(metres, 0.0));
    GeoPoint {
        latitude,
        longitude,
    }
}

fn drive(station: &StationNode) {
    station.submit(Command::Waypoints {
        driver: addr::GWD,
        points: vec![north(40.0)],
        speed: 1.0,
    });
    let moving = station.wait_for(Duration::from_secs(15), |v| {
        fresh_pose(v).is_some_and(|(_, speed)| speed > 0.3)
    });
    assert!(moving.is_ok(), "the vehicle did not move: {:#?}", moving);
}

/// Starts the vehicle and the station, takes control, and starts a move.
fn start(tag: &str) -> (std::path::PathBuf, NodeProcess, StationNode) {
    let dir = test_dir(tag);
    let at = free_addr();
    let cfg = node_file(&dir, "vehicle.yaml", (1, 1), at, "vehicle", "");
    let node = NodeProcess::start(&cfg);
    let station = StationNode::start(ME, 200, vec![at]);
    let found = station.wait_for(Duration::from_secs(20), |v| {
        components_of(v, 1, 1) >= VEHICLE_COMPONENTS
    });
    assert!(found.is_ok(), "vehicle not discovered: {found:#?}");
    station.submit(Command::TakeControl {
        target: addr::GWD,
        authority: 200,
    });
    let held = station.wait_for(Duration::from_secs(10), |v| {
        in_control(v) && fresh_pose(v).is_some()
    });
    assert!(held.is_ok(), "no control or no poses: {held:#?}");
    drive(&station);
    (cfg, node, station)
}

/// When control and poses came back after a restart.
struct Regained {
    control: Duration,
    poses: Duration,
}

/// After the new process started: waits for control and fresh poses from it, checking
/// that the vehicle stays at the origin (where a new process starts it) meanwhile and
/// for `still` after.
fn regain(station: &StationNode, restarted: Instant, still: Duration) -> Regained {
    let (mut control, mut poses) = (None::<Instant>, None::<Instant>);
    let mut samples = 0;
    let deadline = restarted + Duration::from_secs(25);
    loop {
        let now = Instant::now();
        let (at, v) = station.view();
        // Poses of the new process (the last ones of the old one are older than that).
        let new = at > restarted + Duration::from_millis(300);
        if let Some(((x, y), speed)) = fresh_pose(&v).filter(|_| new) {
            samples += 1;
            poses.get_or_insert(at);
            assert!(
                x.hypot(y) < 0.5,
                "the restarted vehicle moved without a command: at ({x:.2}, {y:.2})"
            );
            // The speed the station shows is the new process's a little after its
            // first pose.
            if poses.is_some_and(|p| at > p + Duration::from_millis(300)) {
                assert!(speed < 0.05, "moving at {speed} m/s without a command");
            }
        }
        if new && in_control(&v) {
            control.get_or_insert(at);
        }
        if let (Some(c), Some(p)) = (control, poses) {
            if now >= c.max(p) + still {
                break;
            }
        }
        assert!(
            now < deadline,
            "control or service connections not regained {:?} after the restart (poses back: {}): {:#?}",
            now - restarted,
            poses.is_some(),
            component(&v, addr::GWD)
        );
        std::thread::sleep(Duration::from_millis(20));
    }
    assert!(samples > 20, "only {samples} fresh poses sampled");
    let since = |t: Option<Instant>| t.map_or(Duration::ZERO, |t| t - restarted);
    Regained {
        control: since(control),
        poses: since(poses),
    }
}

#[test]
fn a_vehicle_restarted_at_once_is_controlled_again_and_stays_still() {
    let (cfg, node, station) = start("restart-fast");
    node.kill();
    let restarted = Instant::now();
    let node = NodeProcess::start(&cfg);
    let took = regain(&station, restarted, Duration::from_secs(2));
    let (_, v) = station.view();
    assert!(components_of(&v, 1, 1) >= VEHICLE_COMPONENTS);
    // The station saw control go and come back.
    let said = |text: &str| v.notices.iter().filter(|n| n.text.contains(text)).count();
    assert_eq!(said("control lost"), 1, "{:#?}", v.notices);
    assert_eq!(said("control gained"), 2, "{:#?}", v.notices);
    println!(
        "restart at once: control back {:.2} s, poses {:.2} s after the new process started",
        took.control.as_secs_f64(),
        took.poses.as_secs_f64()
    );
    // Commanded again, it moves again.
    drive(&station);
    drop(node);
    let _ = std::fs::remove_dir_all(cfg.parent().unwrap());
}

#[test]
fn a_vehicle_restarted_after_the_tree_dropped_it_comes_back_whole() {
    let (cfg, node, station) = start("restart-slow");
    node.kill();
    let killed = Instant::now();
    let gone = station.wait_for(Duration::from_secs(15), |v| components_of(v, 1, 1) == 0);
    assert!(gone.is_ok(), "the killed node stayed in the tree");
    let dropped_after = killed.elapsed();
    let restarted = Instant::now();
    let node = NodeProcess::start(&cfg);
    let back = station.wait_for(Duration::from_secs(20), |v| {
        components_of(v, 1, 1) >= VEHICLE_COMPONENTS
    });
    assert!(back.is_ok(), "the tree did not converge: {back:#?}");
    let converged = restarted.elapsed();
    let took = regain(&station, restarted, Duration::from_secs(1));
    println!(
        "restart after the tree dropped the node ({:.1} s after the kill): tree whole again {:.2} s, control back {:.2} s, poses {:.2} s after the new process started",
        dropped_after.as_secs_f64(),
        converged.as_secs_f64(),
        took.control.as_secs_f64(),
        took.poses.as_secs_f64()
    );
    drive(&station);
    drop(node);
    let _ = std::fs::remove_dir_all(cfg.parent().unwrap());
}
