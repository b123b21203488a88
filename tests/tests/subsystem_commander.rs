//! The Subsystem Commander core (`jaus::stock::commander::StockSubsystemCommander`,
//! issue 14 item 4) on the demo's simulated vehicle: a requester hands it a mission and
//! runs it; it takes control of the Mission Spooler with its own authority, hands the
//! mission over, passes every status on, and lets go of the spooler at the end. It
//! refuses a second mission while one is under way, takes the spooler back after a
//! higher authority lets go, and after an emergency that interrupts the mission either
//! waits for the requester's Run Mission or runs the mission again by itself.

use std::time::Duration;

use jaus::component::local::{LocalBus, Probe};
use jaus::component::{Component, Config};
use jaus::components::{mission_spooler, subsystem_commander};
use jaus::messages::*;
use jaus::stock::commander::{StockSubsystemCommander, SubsystemConfig};
use jaus::stock::geo::LocalFrame;
use jaus::stock::nalgebra::Vector2;
use jaus::stock::spooler::{command, leaf_task, mission_of, StockMissionSpooler};
use jaus::Address;
use jaus_sim::demo::{addr, ORIGIN};
use jaus_sim::vehicle::SimVehicle;

const OCU: Address = Address::new(1, 2, 40, 1);
const INTRUDER: Address = Address::new(1, 3, 40, 1);

type Sc = Component<subsystem_commander::Dispatch<StockSubsystemCommander>>;
type Ms = Component<mission_spooler::Dispatch<StockMissionSpooler>>;

struct Rig {
    bus: LocalBus,
    vehicle: SimVehicle,
    parts: Vec<Address>,
}

fn rig(resume_after_emergency: bool) -> Rig {
    let t0 = std::time::Instant::now();
    let mut bus = LocalBus::new(t0);
    let (parts, vehicle) = jaus_sim::demo::vehicle(t0, &jaus_sim::demo::Options::default());
    let mut addresses = Vec::new();
    for p in parts {
        addresses.push(bus.add_boxed(p));
    }
    // The demo's Subsystem Commander, with the setting under test.
    assert!(bus.remove(addr::SC));
    bus.add(subsystem_commander::component(
        addr::SC,
        StockSubsystemCommander::new(SubsystemConfig {
            resume_after_emergency,
            ..SubsystemConfig::new(addr::MS)
        }),
        Config {
            authority: 150,
            ..Config::default()
        },
        t0,
    ));
    bus.add(Probe::new(OCU));
    bus.add(Probe::new(INTRUDER));
    bus.run_for(Duration::from_millis(500));
    Rig {
        bus,
        vehicle,
        parts: addresses,
    }
}

/// Mission `id`: blocking moves of the Global Waypoint Driver to each point (local m).
fn mission(id: u16, points: &[(f64, f64)]) -> SpoolMission {
    let frame = LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2);
    let tasks = points
        .iter()
        .enumerate()
        .map(|(i, (x, y))| {
            let (latitude, longitude) = frame.to_global(Vector2::new(*x, *y));
            let uid = 10 * (i as u16 + 1);
            let goto = SetGlobalWaypoint {
                latitude,
                longitude,
                ..SetGlobalWaypoint::default()
            };
            let msgs: [(Message, bool); 3] = [
                (Resume {}.into(), false),
                (SetTravelSpeed { speed: 2.0 }.into(), false),
                (goto.into(), true),
            ];
            let cmds = msgs
                .iter()
                .enumerate()
                .map(|(j, (m, b))| command(uid + j as u16, addr::MS, addr::GWD, m, *b).unwrap())
                .collect();
            leaf_task(i as u16 + 1, cmds)
        })
        .collect();
    mission_of(id, tasks)
}

fn sc(bus: &LocalBus) -> &StockSubsystemCommander {
    &bus.get::<Sc>(addr::SC).unwrap().behaviour().0
}

fn spooler_controller(bus: &LocalBus) -> Option<(Address, u8)> {
    bus.get::<Ms>(addr::MS).unwrap().controller()
}

/// Mission-level statuses the requester received from the Subsystem Commander.
fn statuses(bus: &LocalBus, id: u16) -> Vec<MissionStatus> {
    bus.get::<Probe>(OCU)
        .unwrap()
        .received()
        .iter()
        .filter(|r| r.header.source == addr::SC)
        .filter_map(|r| match &r.message {
            Message::ReportMissionStatus(s)
                if s.mission_id == id && s.status_type == MissionStatusType::Mission =>
            {
                Some(s.status)
            }
            _ => None,
        })
        .collect()
}

fn position(r: &Rig) -> Vector2<f64> {
    r.vehicle.lock().position()
}

/// Runs up to `secs` seconds until mission `id` is reported finished; returns the
/// farthest x the vehicle reached.
fn run_to_finish(r: &mut Rig, id: u16, secs: u64) -> f64 {
    let mut far = f64::MIN;
    for _ in 0..secs {
        r.bus.run_for(Duration::from_secs(1));
        far = far.max(position(r).x);
        if statuses(&r.bus, id).contains(&MissionStatus::Finished) {
            break;
        }
    }
    far
}

fn emergency(r: &mut Rig, set: bool) {
    for a in r.parts.clone() {
        if set {
            r.bus.send(
                INTRUDER,
                a,
                SetEmergency {
                    emergency_code: EmergencyCode {
                        transition_to_emergency: true,
                        ..Default::default()
                    },
                },
            );
        } else {
            r.bus.send(
                INTRUDER,
                a,
                ClearEmergency {
                    emergency_code: ClearEmergencyCode {
                        clear_emergency: true,
                        ..Default::default()
                    },
                },
            );
        }
    }
}

#[test]
fn missions_go_through_the_subsystem_commander_to_the_spooler_and_back() {
    let mut r = rig(false);
    assert_eq!(spooler_controller(&r.bus), None);
    r.bus
        .send(OCU, addr::SC, mission(7, &[(8.0, 0.0), (0.0, 0.0)]));
    r.bus.send(OCU, addr::SC, RunMission { mission_id: 7 });
    r.bus.run_for(Duration::from_secs(1));
    // It holds the spooler with its own authority; the requester holds nothing.
    assert_eq!(spooler_controller(&r.bus), Some((addr::SC, 150)));
    let o = sc(&r.bus).order().unwrap().clone();
    assert_eq!((o.requester, o.mission_id, o.handed), (OCU, 7, true));

    // A second mission while the first is under way is refused; the spooler never
    // sees it.
    r.bus.send(INTRUDER, addr::SC, mission(8, &[(1.0, 1.0)]));
    r.bus.run_for(Duration::from_millis(100));
    assert_eq!(sc(&r.bus).stats().refused, 1);
    assert_eq!(
        r.bus.get::<Ms>(addr::MS).unwrap().behaviour().0.status(8),
        None
    );

    let far = run_to_finish(&mut r, 7, 40);
    let s = statuses(&r.bus, 7);
    assert!(s.contains(&MissionStatus::Spooling), "{s:?}");
    assert_eq!(s.last(), Some(&MissionStatus::Finished), "{s:?}");
    assert!(far > 7.5, "reached (8, 0): {far:.2}");
    assert!(position(&r).norm() < 1.0, "home: {:?}", position(&r));
    // Over: the spooler is let go, the order is the last one.
    r.bus.run_for(Duration::from_millis(200));
    assert_eq!(spooler_controller(&r.bus), None);
    assert!(sc(&r.bus).order().is_none());
    assert_eq!(sc(&r.bus).last().unwrap().mission_id, 7);
    let st = sc(&r.bus).stats();
    assert_eq!((st.missions, st.interruptions), (1, 0));
    assert!(st.relayed >= 3, "{st:?}");
}

#[test]
fn control_of_the_spooler_taken_away_is_taken_back() {
    let mut r = rig(false);
    r.bus
        .send(OCU, addr::SC, mission(3, &[(6.0, 0.0), (0.0, 0.0)]));
    r.bus.run_for(Duration::from_secs(1));
    assert_eq!(spooler_controller(&r.bus), Some((addr::SC, 150)));
    r.bus.send(
        INTRUDER,
        addr::MS,
        RequestComponentControl {
            authority_code: 200,
        },
    );
    r.bus.run_for(Duration::from_secs(2));
    assert_eq!(spooler_controller(&r.bus), Some((INTRUDER, 200)));
    r.bus.send(INTRUDER, addr::MS, ReleaseComponentControl {});
    r.bus.run_for(Duration::from_secs(1));
    assert_eq!(spooler_controller(&r.bus), Some((addr::SC, 150)));
    // And the mission still runs to the end.
    r.bus.send(OCU, addr::SC, RunMission { mission_id: 3 });
    let far = run_to_finish(&mut r, 3, 40);
    assert!(far > 5.5, "{far:.2}");
    assert_eq!(statuses(&r.bus, 3).last(), Some(&MissionStatus::Finished));
}

/// Emergency on the whole vehicle in the middle of the first move; returns where the
/// vehicle stood once the emergency was cleared.
fn interrupt(r: &mut Rig, id: u16) -> Vector2<f64> {
    r.bus
        .send(OCU, addr::SC, mission(id, &[(8.0, 0.0), (0.0, 0.0)]));
    r.bus.send(OCU, addr::SC, RunMission { mission_id: id });
    r.bus.run_for(Duration::from_secs(3));
    assert!(position(r).x > 1.0, "under way: {:?}", position(r));
    emergency(r, true);
    r.bus.run_for(Duration::from_secs(2));
    assert!(r.vehicle.lock().speed().abs() < 0.01);
    let o = sc(&r.bus).order().unwrap();
    assert!(o.interrupted, "{o:?}");
    emergency(r, false);
    r.bus.run_for(Duration::from_millis(600));
    position(r)
}

#[test]
fn after_an_emergency_the_mission_waits_for_the_requester_to_run_it() {
    let mut r = rig(false);
    let stood = interrupt(&mut r, 4);
    r.bus.run_for(Duration::from_secs(3));
    assert!(
        (position(&r) - stood).norm() < 0.05,
        "still: {stood:?} -> {:?}",
        position(&r)
    );
    assert!(sc(&r.bus).order().unwrap().interrupted);
    r.bus.send(OCU, addr::SC, RunMission { mission_id: 4 });
    let far = run_to_finish(&mut r, 4, 40);
    assert!(far > 7.5, "went on to (8, 0): {far:.2}");
    assert_eq!(statuses(&r.bus, 4).last(), Some(&MissionStatus::Finished));
    let st = sc(&r.bus).stats();
    assert_eq!((st.interruptions, st.resumed), (1, 0));
}

#[test]
fn after_an_emergency_it_can_run_the_mission_again_by_itself() {
    let mut r = rig(true);
    interrupt(&mut r, 5);
    let far = run_to_finish(&mut r, 5, 40);
    assert!(far > 7.5, "went on to (8, 0): {far:.2}");
    assert_eq!(statuses(&r.bus, 5).last(), Some(&MissionStatus::Finished));
    assert!(position(&r).norm() < 1.0);
    let st = sc(&r.bus).stats();
    assert_eq!((st.interruptions, st.resumed), (1, 1));
}
