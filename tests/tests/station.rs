//! The System Commander's operator logic (`jaus::stock::commander::Station`, issue 14
//! item 4; the console of issue 16 is its user interface) against the demo's simulated
//! vehicle on a virtual clock: it follows the vehicle's pose and every component's state,
//! refuses commands it cannot carry out (no control, bad coordinates, bad speed), takes
//! control with an authority, drives waypoints to arrival, loses control to a higher
//! authority and takes it back, sets and clears an emergency, and spools and runs a
//! mission on the spooler until the spooler reports it finished.

use std::time::Duration;

use jaus::component::local::{LocalBus, Probe};
use jaus::component::Config;
use jaus::components::system_commander;
use jaus::messages::*;
use jaus::stock::commander::view::ComponentView;
use jaus::stock::commander::{
    Command, GeoPoint, MissionAction, Station, StationConfig, StationError, SystemView, TreeInput,
};
use jaus::stock::nalgebra::Vector2;
use jaus::{Address, JausMessage};

const ME: Address = Address::new(200, 1, 40, 1);
const GWD: Address = Address::new(1, 1, 45, 1);
const MS: Address = Address::new(1, 1, 36, 1);
const GPS: Address = Address::new(1, 1, 38, 1);
const GPSD: Address = Address::new(1, 1, 47, 1);
const LPS: Address = Address::new(1, 1, 41, 1);
const VSS: Address = Address::new(1, 1, 42, 1);
const INTRUDER: Address = Address::new(1, 3, 40, 1);

type Ocu = jaus::component::Component<system_commander::Dispatch<Station>>;

fn station(bus: &mut LocalBus) -> &mut Station {
    &mut bus.get_mut::<Ocu>(ME).unwrap().behaviour_mut().0
}

fn view(bus: &mut LocalBus) -> SystemView {
    let now = bus.now();
    // Any wall-clock time: it only dates the notices.
    station(bus).view(now, Duration::from_secs(1_800_000_000), true)
}

fn vehicle_xy(v: &SystemView) -> (f64, f64) {
    let p = v
        .subsystems
        .iter()
        .find(|s| s.id == 1)
        .unwrap()
        .pose
        .unwrap();
    (p.x, p.y)
}

fn component(v: &SystemView, a: Address) -> Option<&ComponentView> {
    v.subsystems
        .iter()
        .flat_map(|s| &s.nodes)
        .flat_map(|n| &n.components)
        .find(|c| c.address == a.to_string())
}

fn state(v: &SystemView, a: Address) -> Option<String> {
    component(v, a).and_then(|c| c.state.clone())
}

/// Spools a mission of moves of the waypoint driver to `points` at 2 m/s on the
/// spooler, then runs it.
fn spool_and_run(bus: &mut LocalBus, points: Vec<GeoPoint>) {
    station(bus)
        .submit(Command::SpoolMission {
            spooler: MS,
            driver: GWD,
            points,
            speed: 2.0,
        })
        .unwrap();
    bus.run_for(Duration::from_secs(1));
    station(bus)
        .submit(Command::Mission {
            spooler: MS,
            action: MissionAction::Run,
        })
        .unwrap();
}

fn errors(v: &SystemView) -> Vec<String> {
    v.notices
        .iter()
        .filter(|n| n.error)
        .map(|n| n.text.clone())
        .collect()
}

/// The demo's simulated vehicle (subsystem 1) and a station (`ME`) that knows its
/// components, with a probe at `INTRUDER`, on a bus with a virtual clock.
fn rig() -> LocalBus {
    let t0 = std::time::Instant::now();
    let mut bus = LocalBus::new(t0);
    let (parts, _) = jaus_sim::demo::vehicle_at(t0, &jaus_sim::demo::Options::default(), 1, 1);
    let mut tree = TreeInput::default();
    for p in parts {
        let a = bus.add_boxed(p);
        tree.components.insert(a, None);
    }
    bus.add(system_commander::component(
        ME,
        Station::new(StationConfig::default()),
        Config::default(),
        t0,
    ));
    bus.add(Probe::new(INTRUDER));
    station(&mut bus).set_tree(tree);
    bus
}

#[test]
fn a_station_follows_commands_and_recovers_the_vehicle() {
    let mut bus = rig();

    // It follows the pose (service connection) and every component's state.
    bus.run_for(Duration::from_secs(2));
    let v = view(&mut bus);
    let s1 = v.subsystems.iter().find(|s| s.id == 1).unwrap();
    assert!(s1.pose.is_some() && !s1.stale, "{s1:?}");
    assert!(s1.trail.len() >= 10, "{} positions in 2 s", s1.trail.len());
    assert_eq!(s1.roles.waypoint_driver.as_deref(), Some("1.1.45.1"));
    assert_eq!(state(&v, GWD).as_deref(), Some("Standby"));
    let frame = *station(&mut bus).frame().unwrap();
    // A point of the view: x metres east, y metres north of the station's origin (the
    // frame counts north, east).
    let at = |x: f64, y: f64| {
        let (latitude, longitude) = frame.to_global(Vector2::new(y, x));
        GeoPoint {
            latitude,
            longitude,
        }
    };

    // Refused before anything is sent: no control, bad coordinates, bad speed, unknown.
    let drive = |points: Vec<GeoPoint>, speed: f64| Command::Waypoints {
        driver: GWD,
        points,
        speed,
    };
    let st = station(&mut bus);
    assert!(matches!(
        st.submit(drive(vec![at(8.0, 0.0)], 2.0)),
        Err(StationError::NotInControl { target: GWD, .. })
    ));
    let bad = GeoPoint {
        latitude: 95.0,
        longitude: 0.0,
    };
    assert!(matches!(
        st.submit(drive(vec![bad], 2.0)),
        Err(StationError::Coordinate {
            field: "latitude",
            ..
        })
    ));
    assert!(matches!(
        st.submit(drive(vec![at(8.0, 0.0)], f64::NAN)),
        Err(StationError::Speed { .. })
    ));
    assert!(matches!(
        st.submit(Command::TakeControl {
            target: Address::new(1, 1, 49, 1),
            authority: 5
        }),
        Err(StationError::Unknown(_))
    ));
    // Path segments need a Global Path Segment Driver (47), not a waypoint driver.
    assert!(matches!(
        st.submit(Command::PathSegments {
            driver: GWD,
            points: vec![at(1.0, 1.0)],
            speed: 1.0
        }),
        Err(StationError::WrongComponent { id: 47, .. })
    ));
    // An obstacle for the world model: a bad radius or the wrong component is refused;
    // a good one is stored and drawn once the store lists it.
    const WM: Address = Address::new(1, 1, 61, 1);
    let obstacle = |world_model: Address, radius: f64| Command::StoreObstacle {
        world_model,
        point: at(20.0, 20.0),
        radius,
        class: 9,
    };
    let st = station(&mut bus);
    assert!(matches!(
        st.submit(obstacle(WM, -1.0)),
        Err(StationError::Radius { .. })
    ));
    assert!(matches!(
        st.submit(obstacle(GWD, 0.7)),
        Err(StationError::WrongComponent { id: 61, .. })
    ));
    st.submit(obstacle(WM, 0.7)).unwrap();
    assert_eq!(errors(&view(&mut bus)).len(), 7);
    bus.run_for(Duration::from_secs(3));
    let v = view(&mut bus);
    let stored = v.subsystems[0].objects.iter().find(|o| {
        let (x, y) = o.points[0];
        (x - 20.0).hypot(y - 20.0) < 0.05 && (o.buffer - 0.7).abs() < 1e-3
    });
    assert!(stored.is_some(), "{:?}", v.subsystems[0].objects);

    // Control with authority 5, then two waypoints driven to arrival.
    station(&mut bus)
        .submit(Command::TakeControl {
            target: GWD,
            authority: 5,
        })
        .unwrap();
    // Granted, then seen in the next status round (every second).
    bus.run_for(Duration::from_millis(2500));
    let v = view(&mut bus);
    let gwd = component(&v, GWD).unwrap().clone();
    assert!(gwd.held, "{gwd:?}");
    assert_eq!(gwd.controller.as_deref(), Some("200.1.40.1"));
    assert_eq!(gwd.controller_authority, Some(5));
    station(&mut bus)
        .submit(drive(vec![at(6.0, 4.0), at(10.0, 0.0)], 2.0))
        .unwrap();
    bus.run_for(Duration::from_secs(20));
    let v = view(&mut bus);
    let (x, y) = vehicle_xy(&v);
    assert!((x - 10.0).hypot(y) < 1.0, "arrived at ({x:.2}, {y:.2})");
    assert_eq!(v.subsystems[0].route.len(), 2);

    // A higher authority takes the driver: the station says so, asks again, and takes it
    // back once released.
    bus.send(
        INTRUDER,
        GWD,
        RequestComponentControl {
            authority_code: 100,
        },
    );
    bus.run_for(Duration::from_secs(1));
    let v = view(&mut bus);
    assert!(
        errors(&v)
            .iter()
            .any(|e| e.contains("1.1.45.1: control lost")),
        "{:?}",
        errors(&v)
    );
    assert!(matches!(
        station(&mut bus).submit(drive(vec![at(0.0, 0.0)], 2.0)),
        Err(StationError::NotInControl { .. })
    ));
    bus.send(INTRUDER, GWD, ReleaseComponentControl {});
    bus.run_for(Duration::from_secs(2));
    let v = view(&mut bus);
    assert!(
        v.notices
            .iter()
            .filter(|n| n.text == "1.1.45.1: control gained")
            .count()
            >= 2
    );

    // Path segments (straight, weighting 0) through the Global Path Segment Driver,
    // driven to the end of the last one.
    station(&mut bus)
        .submit(Command::TakeControl {
            target: GPSD,
            authority: 5,
        })
        .unwrap();
    bus.run_for(Duration::from_secs(1));
    station(&mut bus)
        .submit(Command::PathSegments {
            driver: GPSD,
            points: vec![at(10.0, 6.0), at(4.0, 6.0)],
            speed: 2.0,
        })
        .unwrap();
    let mut near_corner = f64::INFINITY;
    for _ in 0..20 {
        bus.run_for(Duration::from_secs(1));
        let (x, y) = vehicle_xy(&view(&mut bus));
        near_corner = near_corner.min((x - 10.0).hypot(y - 6.0));
    }
    let v = view(&mut bus);
    let (x, y) = vehicle_xy(&v);
    assert!(
        (x - 4.0).hypot(y - 6.0) < 1.0,
        "arrived at ({x:.2}, {y:.2})"
    );
    assert!(
        near_corner < 1.0,
        "passed the first end: {near_corner:.2} m"
    );
    assert_eq!(
        state(&v, GPSD).as_deref(),
        Some("Standby"),
        "back to Standby"
    );
    station(&mut bus)
        .submit(Command::ReleaseControl { target: GPSD })
        .unwrap();

    // A mission on the spooler (authority 100): refused at authority 5, visibly; taken
    // at 200; two blocking moves back, run to the end.
    station(&mut bus)
        .submit(Command::TakeControl {
            target: MS,
            authority: 5,
        })
        .unwrap();
    bus.run_for(Duration::from_secs(1));
    let v = view(&mut bus);
    assert!(
        errors(&v)
            .iter()
            .any(|e| e == "1.1.36.1: control refused (InsufficientAuthority)"),
        "{:?}",
        errors(&v)
    );
    station(&mut bus)
        .submit(Command::TakeControl {
            target: MS,
            authority: 200,
        })
        .unwrap();
    bus.run_for(Duration::from_secs(1));
    let r = station(&mut bus).submit(Command::Mission {
        spooler: MS,
        action: MissionAction::Run,
    });
    assert!(
        matches!(r, Err(StationError::NoMission(MS))),
        "{r:?} {:?}",
        errors(&view(&mut bus))
    );
    spool_and_run(&mut bus, vec![at(5.0, -3.0), at(0.0, 0.0)]);
    bus.run_for(Duration::from_secs(30));
    let v = view(&mut bus);
    let m = v.subsystems[0].mission.clone().unwrap();
    assert_eq!(m.tasks, 2);
    assert_eq!(m.status.as_deref(), Some("Finished"), "{:?}", v.notices);
    let (x, y) = vehicle_xy(&v);
    assert!(x.hypot(y) < 1.0, "home at ({x:.2}, {y:.2})");

    // Emergency on the whole subsystem, then cleared.
    station(&mut bus)
        .submit(Command::Emergency { subsystem: 1 })
        .unwrap();
    bus.run_for(Duration::from_secs(2));
    let v = view(&mut bus);
    assert!(v.subsystems[0].emergency);
    assert_eq!(state(&v, GWD).as_deref(), Some("Emergency"));
    station(&mut bus)
        .submit(Command::ClearEmergency { subsystem: 1 })
        .unwrap();
    bus.run_for(Duration::from_secs(2));
    let v = view(&mut bus);
    assert!(!v.subsystems[0].emergency, "{:?}", state(&v, GWD));
    // The pose and velocity sensors it follows (nobody controls them) are resumed:
    // Clear Emergency leaves them in Standby, where OpenJAUS's stop reporting.
    for sensor in [GPS, LPS, VSS] {
        assert_eq!(state(&v, sensor).as_deref(), Some("Ready"), "{sensor}");
        let resumed = format!("{sensor}: sensor resumed after the emergency");
        assert!(v.notices.iter().any(|n| n.text == resumed), "{resumed}");
    }
    // ... and control of them given back.
    bus.run_for(Duration::from_secs(2));
    let v = view(&mut bus);
    for sensor in [GPS, LPS, VSS] {
        let c = component(&v, sensor).unwrap();
        assert!(c.controller.is_none() && !c.held, "{c:?}");
    }
    assert_eq!(state(&v, GWD).as_deref(), Some("Standby"));

    // An emergency in the middle of a mission stops the vehicle; once it is cleared,
    // running the mission again carries on from the move it was in, to the end.
    spool_and_run(&mut bus, vec![at(8.0, 0.0), at(0.0, 0.0)]);
    bus.run_for(Duration::from_secs(3));
    let v = view(&mut bus);
    let (x, _) = vehicle_xy(&v);
    assert!(x > 1.0, "under way: x = {x:.2}");
    station(&mut bus)
        .submit(Command::Emergency { subsystem: 1 })
        .unwrap();
    bus.run_for(Duration::from_secs(2));
    let (x1, y1) = vehicle_xy(&view(&mut bus));
    bus.run_for(Duration::from_secs(2));
    let (x2, y2) = vehicle_xy(&view(&mut bus));
    assert!(
        (x2 - x1).hypot(y2 - y1) < 0.2,
        "stopped: ({x1:.2}, {y1:.2}) -> ({x2:.2}, {y2:.2})"
    );
    assert!(x2 < 7.0, "stopped short of the first point: x = {x2:.2}");
    station(&mut bus)
        .submit(Command::ClearEmergency { subsystem: 1 })
        .unwrap();
    bus.run_for(Duration::from_secs(2));
    let v = view(&mut bus);
    assert_eq!(state(&v, GWD).as_deref(), Some("Standby"));
    let (x3, y3) = vehicle_xy(&v);
    assert!(
        (x3 - x2).hypot(y3 - y2) < 0.2,
        "clearing does not move it: ({x2:.2}, {y2:.2}) -> ({x3:.2}, {y3:.2})"
    );
    station(&mut bus)
        .submit(Command::Mission {
            spooler: MS,
            action: MissionAction::Run,
        })
        .unwrap();
    // The far point first (the vehicle must pass x = 7.5), then home.
    let mut far = x3;
    for _ in 0..40 {
        bus.run_for(Duration::from_secs(1));
        far = far.max(vehicle_xy(&view(&mut bus)).0);
    }
    let v = view(&mut bus);
    let m = v.subsystems[0].mission.clone().unwrap();
    assert_eq!(m.status.as_deref(), Some("Finished"), "{:?}", v.notices);
    assert!(
        far > 7.5,
        "reached the first point after the emergency: {far:.2}"
    );
    let (x, y) = vehicle_xy(&v);
    assert!(x.hypot(y) < 1.0, "home at ({x:.2}, {y:.2})");
}

#[test]
fn a_driver_that_stays_in_standby_after_resume_is_reported() {
    let mut bus = rig();
    bus.run_for(Duration::from_secs(2));
    station(&mut bus)
        .submit(Command::TakeControl {
            target: GWD,
            authority: 10,
        })
        .unwrap();
    bus.run_for(Duration::from_secs(2));
    // The Resume is lost on its way: the driver stays in Standby, and the station says so.
    bus.set_filter(|h| !(h.command_code == Resume::CODE && h.destination == GWD));
    station(&mut bus)
        .submit(Command::Resume { target: GWD })
        .unwrap();
    bus.run_for(Duration::from_secs(4));
    let v = view(&mut bus);
    assert_eq!(state(&v, GWD).as_deref(), Some("Standby"));
    let stayed: Vec<String> = errors(&v)
        .into_iter()
        .filter(|e| e.contains("still in Standby") && e.contains("1.1.45.1"))
        .collect();
    assert_eq!(stayed.len(), 1, "{:?}", errors(&v));
    assert!(
        stayed[0].contains("its controller: 200.1.40.1"),
        "{stayed:?}"
    );
    // Delivered, it is obeyed and nothing more is said.
    bus.clear_filter();
    station(&mut bus)
        .submit(Command::Resume { target: GWD })
        .unwrap();
    bus.run_for(Duration::from_secs(4));
    let v = view(&mut bus);
    assert_eq!(state(&v, GWD).as_deref(), Some("Ready"));
    let stayed = errors(&v)
        .into_iter()
        .filter(|e| e.contains("still in Standby"))
        .count();
    assert_eq!(stayed, 1, "{:?}", errors(&v));
}
