//! Mission Spooler rules on the virtual-clock bus: blocking messages (a spooled move
//! really drives the simulated vehicle), pause/resume, abort, remove/replace of
//! messages not yet spooled, the two Part 1 fallbacks, forwarding to another
//! subsystem's spooler.

use std::time::{Duration, Instant};

use jaus::component::local::{LocalBus, Probe};
use jaus::component::{Component, Config, Refused, StopReason};
use jaus::components::global_waypoint_driver::{self, GlobalWaypointDriver};
use jaus::components::{
    local_pose_sensor, local_waypoint_driver, mission_spooler, primitive_driver,
    velocity_state_sensor,
};
use jaus::messages::*;
use jaus::stock::drivers::{PrimitiveConfig, StockLocalWaypointDriver, StockPrimitiveDriver};
use jaus::stock::motion::DriverConfig;
use jaus::stock::sensors::{StockLocalPoseSensor, StockVelocityStateSensor};
use jaus::stock::spooler::{command, Delivery, SpoolerConfig, StockMissionSpooler};
use jaus::Address;
use jaus_sim::vehicle::{SimVehicle, VehicleParams};

const MS: Address = Address::new(1, 1, 36, 1);
const PD: Address = Address::new(1, 1, 33, 1);
const LPS: Address = Address::new(1, 1, 41, 1);
const VSS: Address = Address::new(1, 1, 42, 1);
const LWD: Address = Address::new(1, 1, 46, 1);
const GWD: Address = Address::new(1, 1, 45, 1);
const PAYLOAD: Address = Address::new(1, 1, 200, 1);
const OCU: Address = Address::new(1, 2, 40, 1);
const REMOTE_MS: Address = Address::new(2, 1, 36, 1);
const REMOTE_PAYLOAD: Address = Address::new(2, 1, 200, 1);

type Spooler = Component<mission_spooler::Dispatch<StockMissionSpooler>>;

/// A waypoint driver that takes Spool Mission but does not answer Query Spooling
/// Preference (so the spooler falls back to one message at a time).
#[derive(Debug, Default)]
struct OneAtATime {
    spooled: Vec<usize>,
}

impl GlobalWaypointDriver for OneAtATime {
    /// A test stand-in that never moves anything.
    fn stop(&mut self, _c: &mut global_waypoint_driver::Ctx<'_>, _r: StopReason) {}

    fn on_spool_mission(
        &mut self,
        _c: &mut global_waypoint_driver::Ctx<'_>,
        m: &SpoolMission,
    ) -> Result<(), Refused> {
        self.spooled.push(m.root.messages.len());
        Ok(())
    }
}

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

fn bus() -> (LocalBus, SimVehicle) {
    let t0 = Instant::now();
    let cfg = Config::default();
    let vehicle = SimVehicle::new(VehicleParams::default());
    let mut bus = LocalBus::new(t0);
    let spooler = StockMissionSpooler::new(SpoolerConfig {
        remote_spoolers: vec![REMOTE_MS],
        ..SpoolerConfig::default()
    });
    bus.add(mission_spooler::component(MS, spooler, cfg.clone(), t0));
    bus.add(mission_spooler::component(
        REMOTE_MS,
        StockMissionSpooler::new(SpoolerConfig::default()),
        cfg.clone(),
        t0,
    ));
    bus.add(primitive_driver::component(
        PD,
        StockPrimitiveDriver::new(vehicle.clone(), PrimitiveConfig::default()),
        cfg.clone(),
        t0,
    ));
    bus.add(local_pose_sensor::component(
        LPS,
        StockLocalPoseSensor(vehicle.clone()),
        cfg.clone(),
        t0,
    ));
    bus.add(velocity_state_sensor::component(
        VSS,
        StockVelocityStateSensor(vehicle.clone()),
        cfg.clone(),
        t0,
    ));
    let dc = DriverConfig {
        output: PD,
        pose_sensor: LPS,
        velocity_sensor: Some(VSS),
        ..DriverConfig::default()
    };
    bus.add(local_waypoint_driver::component(
        LWD,
        StockLocalWaypointDriver::new(dc),
        cfg.clone(),
        t0,
    ));
    bus.add(global_waypoint_driver::component(
        GWD,
        OneAtATime::default(),
        cfg,
        t0,
    ));
    for a in [PAYLOAD, OCU, REMOTE_PAYLOAD] {
        bus.add(Probe::new(a));
    }
    // The operator controls both spoolers and puts them (and the waypoint driver) in
    // Ready, then hands the driver over to the spooler.
    for a in [MS, REMOTE_MS, LWD] {
        bus.send(OCU, a, RequestComponentControl { authority_code: 10 });
    }
    bus.run_for(ms(50));
    for a in [MS, REMOTE_MS, LWD] {
        bus.send(OCU, a, Resume {});
    }
    bus.send(OCU, LWD, ReleaseComponentControl {});
    bus.send(OCU, REMOTE_MS, ReleaseComponentControl {});
    bus.run_for(ms(50));
    (bus, vehicle)
}

fn cmd(uid: u16, to: Address, msg: impl Into<Message>, blocking: bool) -> MissionCommand {
    command(uid, MS, to, &msg.into(), blocking).unwrap()
}

fn task(id: u16, messages: Vec<MissionCommand>, children: Vec<MissionTask>) -> MissionTask {
    MissionTask {
        task_id: id,
        child_count: children.len() as u16,
        child_offsets: vec![0; children.len()],
        messages,
        children,
    }
}

fn spool(bus: &mut LocalBus, id: u16, root: MissionTask) {
    bus.send(
        OCU,
        MS,
        SpoolMission {
            mission_id: id,
            append_flag: 0,
            root,
        },
    );
    bus.send(OCU, MS, RunMission { mission_id: id });
    bus.run_for(ms(20));
}

fn payload_uids(bus: &LocalBus, at: Address) -> Vec<u8> {
    // Each raw payload message is a Set Discrete Devices whose gear is the uid.
    bus.get::<Probe>(at)
        .unwrap()
        .messages()
        .filter_map(|m| match m {
            Message::SetDiscreteDevices(d) => d.gear,
            _ => None,
        })
        .collect()
}

fn gear(uid: u16) -> SetDiscreteDevices {
    SetDiscreteDevices {
        gear: Some(uid as u8),
        ..Default::default()
    }
}

fn finish(bus: &mut LocalBus, mission: u16, uid: u16) {
    bus.send(
        PAYLOAD,
        MS,
        ReportMissionStatus {
            status_type: MissionStatusType::Message,
            status: MissionStatus::Finished,
            secondary_status: MissionSecondaryStatus::NoError,
            mission_id: mission,
            task_id: 0,
            task_msg_id: uid,
        },
    );
    bus.run_for(ms(20));
}

fn spooler(bus: &LocalBus) -> &StockMissionSpooler {
    &bus.get::<Spooler>(MS).unwrap().behaviour().0
}

fn mission_finished(bus: &LocalBus, id: u16) -> bool {
    bus.get::<Probe>(OCU).unwrap().messages().any(|m| {
        matches!(m, Message::ReportMissionStatus(r) if r.mission_id == id
            && r.status_type == MissionStatusType::Mission && r.status == MissionStatus::Finished)
    })
}

#[test]
fn blocking_moves_drive_the_vehicle_before_the_next_message_is_spooled() {
    let (mut bus, vehicle) = bus();
    let root = task(
        1,
        vec![
            cmd(1, LWD, SetTravelSpeed { speed: 1.5 }, false),
            cmd(
                2,
                LWD,
                SetLocalWaypoint {
                    waypoint_number: 0,
                    x: 6.0,
                    y: 0.0,
                    ..Default::default()
                },
                true,
            ),
            cmd(3, PAYLOAD, gear(3), false),
        ],
        // Part 1: back in Standby after the first move, so resume and set the speed again.
        vec![task(
            2,
            vec![
                cmd(4, LWD, Resume {}, false),
                cmd(5, LWD, SetTravelSpeed { speed: 1.5 }, false),
                cmd(
                    6,
                    LWD,
                    SetLocalWaypoint {
                        waypoint_number: 0,
                        x: 6.0,
                        y: 4.0,
                        ..Default::default()
                    },
                    true,
                ),
            ],
            vec![],
        )],
    );
    spool(&mut bus, 7, root);
    bus.run_for(Duration::from_secs(2));
    // The driver answered its spooling preference: both messages in one Spool Mission.
    assert_eq!(spooler(&bus).delivery(LWD), Some(Delivery::Spool(4096)));
    assert!(
        payload_uids(&bus, PAYLOAD).is_empty(),
        "blocked behind the move"
    );
    bus.run_for(Duration::from_secs(10));
    let p = vehicle.lock().position();
    assert!(
        (p - jaus::stock::nalgebra::Vector2::new(6.0, 0.0)).norm() < 1.5 || p.y > 1.0,
        "{p}"
    );
    assert_eq!(
        payload_uids(&bus, PAYLOAD),
        [3],
        "sent after the first move finished"
    );
    bus.run_for(Duration::from_secs(15));
    let p = vehicle.lock().position();
    assert!(
        (p - jaus::stock::nalgebra::Vector2::new(6.0, 4.0)).norm() < 0.25,
        "{p}"
    );
    assert!(mission_finished(&bus, 7));
    // The payload probe answered nothing: raw delivery after the probe timeout.
    assert_eq!(spooler(&bus).delivery(PAYLOAD), Some(Delivery::Raw));
}

#[test]
fn pause_and_resume_mid_task() {
    let (mut bus, _) = bus();
    let root = task(
        1,
        vec![
            cmd(1, PAYLOAD, gear(1), true),
            cmd(2, PAYLOAD, gear(2), false),
            cmd(3, PAYLOAD, gear(3), false),
        ],
        vec![],
    );
    spool(&mut bus, 1, root);
    bus.run_for(Duration::from_secs(2));
    assert_eq!(payload_uids(&bus, PAYLOAD), [1]);
    bus.send(
        OCU,
        MS,
        PauseMission {
            mission_id: 1,
            task_id: 0,
        },
    );
    bus.run_for(ms(20));
    finish(&mut bus, 1, 1);
    bus.run_for(Duration::from_secs(1));
    assert_eq!(payload_uids(&bus, PAYLOAD), [1], "paused");
    assert_eq!(
        bus.get::<Spooler>(MS).unwrap().mode(),
        mission_spooler::Mode::Paused
    );
    bus.send(
        OCU,
        MS,
        ResumeMission {
            mission_id: 1,
            task_id: 0,
        },
    );
    bus.run_for(ms(100));
    assert_eq!(payload_uids(&bus, PAYLOAD), [1, 2, 3]);
    assert!(mission_finished(&bus, 1));
    assert_eq!(
        bus.get::<Spooler>(MS).unwrap().mode(),
        mission_spooler::Mode::Idle
    );
}

#[test]
fn abort_a_task_or_the_whole_mission() {
    let (mut bus, _) = bus();
    // Abort one task: its blocking wait ends and the next task goes on.
    let root = task(
        1,
        vec![],
        vec![
            task(
                2,
                vec![
                    cmd(1, PAYLOAD, gear(1), true),
                    cmd(2, PAYLOAD, gear(2), false),
                ],
                vec![],
            ),
            task(3, vec![cmd(3, PAYLOAD, gear(3), false)], vec![]),
        ],
    );
    spool(&mut bus, 1, root);
    bus.run_for(Duration::from_secs(2));
    assert_eq!(payload_uids(&bus, PAYLOAD), [1]);
    bus.send(
        OCU,
        MS,
        AbortMission {
            mission_id: 1,
            task_id: 2,
        },
    );
    bus.run_for(ms(100));
    assert_eq!(
        payload_uids(&bus, PAYLOAD),
        [1, 3],
        "message 2 of the aborted task never sent"
    );
    // Abort the whole mission: nothing more is sent.
    let root = task(
        1,
        vec![
            cmd(1, PAYLOAD, gear(11), true),
            cmd(2, PAYLOAD, gear(12), false),
        ],
        vec![],
    );
    spool(&mut bus, 2, root);
    bus.run_for(ms(100));
    bus.send(
        OCU,
        MS,
        AbortMission {
            mission_id: 2,
            task_id: 0,
        },
    );
    bus.run_for(ms(20));
    finish(&mut bus, 2, 1);
    bus.run_for(ms(500));
    assert_eq!(payload_uids(&bus, PAYLOAD), [1, 3, 11]);
    bus.send(
        OCU,
        MS,
        QueryMissionStatus {
            presence_vector: 1,
            status_type: MissionStatusType::Mission,
            mission_id: 2,
            task_id: 0,
            task_msg_id: 0,
        },
    );
    bus.run_for(ms(20));
    assert!(bus.get::<Probe>(OCU).unwrap().messages().any(|m| matches!(m, Message::ReportMissionStatus(r) if r.mission_id == 2 && r.status == MissionStatus::Aborted)));
}

#[test]
fn remove_and_replace_only_what_is_not_yet_spooled() {
    let (mut bus, _) = bus();
    let root = task(
        1,
        vec![
            cmd(1, PAYLOAD, gear(1), true),
            cmd(2, PAYLOAD, gear(2), false),
            cmd(3, PAYLOAD, gear(3), false),
        ],
        vec![],
    );
    spool(&mut bus, 1, root);
    bus.run_for(Duration::from_secs(2));
    let invalid_before = bus.get::<Spooler>(MS).unwrap().stats().invalid;
    // Message 1 is already out: refused. Message 2 can go.
    bus.send(
        OCU,
        MS,
        RemoveMessages {
            mission_id: 1,
            task_id: 1,
            uids: vec![1],
        },
    );
    bus.send(
        OCU,
        MS,
        RemoveMessages {
            mission_id: 1,
            task_id: 1,
            uids: vec![2],
        },
    );
    bus.send(
        OCU,
        MS,
        ReplaceMessages {
            mission_id: 1,
            task_id: 1,
            uids: vec![3],
            commands: vec![
                cmd(4, PAYLOAD, gear(4), false),
                cmd(5, PAYLOAD, gear(5), false),
            ],
        },
    );
    bus.run_for(ms(20));
    assert_eq!(
        bus.get::<Spooler>(MS).unwrap().stats().invalid,
        invalid_before + 1
    );
    finish(&mut bus, 1, 1);
    bus.run_for(ms(100));
    assert_eq!(payload_uids(&bus, PAYLOAD), [1, 4, 5]);
    assert!(mission_finished(&bus, 1));
}

#[test]
fn a_component_without_spooling_preference_gets_one_message_at_a_time() {
    let (mut bus, _) = bus();
    bus.send(OCU, GWD, RequestComponentControl { authority_code: 1 });
    bus.run_for(ms(20));
    bus.send(OCU, GWD, Resume {});
    bus.send(OCU, GWD, ReleaseComponentControl {});
    bus.run_for(ms(20));
    let wp = |n| SetGlobalWaypoint {
        waypoint_number: n,
        latitude: 29.0,
        longitude: -82.0,
        ..Default::default()
    };
    let root = task(
        1,
        vec![
            cmd(1, GWD, wp(0), false),
            cmd(2, GWD, wp(1), false),
            cmd(3, GWD, wp(2), false),
        ],
        vec![],
    );
    spool(&mut bus, 3, root);
    bus.run_for(Duration::from_secs(3));
    assert_eq!(spooler(&bus).delivery(GWD), Some(Delivery::Spool(1)));
    type Gwd = Component<global_waypoint_driver::Dispatch<OneAtATime>>;
    assert_eq!(
        bus.get::<Gwd>(GWD).unwrap().behaviour().0.spooled,
        [1, 1, 1]
    );
    assert!(mission_finished(&bus, 3));
}

#[test]
fn messages_for_another_subsystem_go_through_its_spooler() {
    let (mut bus, _) = bus();
    let root = task(
        1,
        vec![
            cmd(1, REMOTE_PAYLOAD, gear(9), false),
            cmd(2, PAYLOAD, gear(2), false),
        ],
        vec![],
    );
    spool(&mut bus, 5, root);
    bus.run_for(Duration::from_secs(3));
    // The remote spooler got the mission and parcelled it out on its subsystem.
    let remote = &bus.get::<Spooler>(REMOTE_MS).unwrap().behaviour().0;
    assert_eq!(remote.missions(), 1);
    assert_eq!(payload_uids(&bus, REMOTE_PAYLOAD), [9]);
    assert_eq!(payload_uids(&bus, PAYLOAD), [2]);
    assert!(mission_finished(&bus, 5));
}

#[test]
fn bad_missions_are_refused() {
    let (mut bus, _) = bus();
    let dup = task(
        1,
        vec![
            cmd(1, PAYLOAD, gear(1), false),
            cmd(1, PAYLOAD, gear(2), false),
        ],
        vec![],
    );
    bus.send(
        OCU,
        MS,
        SpoolMission {
            mission_id: 1,
            append_flag: 0,
            root: dup,
        },
    );
    bus.send(OCU, MS, RunMission { mission_id: 99 });
    bus.send(PAYLOAD, MS, RunMission { mission_id: 1 });
    bus.run_for(ms(50));
    let s = bus.get::<Spooler>(MS).unwrap().stats();
    assert_eq!(s.invalid, 2, "duplicate uids, unknown mission");
    assert_eq!(s.not_controller, 1);
}

#[test]
fn a_long_mission_is_paced_and_nothing_is_dropped() {
    let (mut bus, _) = bus();
    let msgs: Vec<MissionCommand> = (1..=3000u16)
        .map(|u| cmd(u, PAYLOAD, gear(u % 250), false))
        .collect();
    spool(&mut bus, 9, task(1, msgs, vec![]));
    bus.run_for(Duration::from_secs(6));
    assert_eq!(payload_uids(&bus, PAYLOAD).len(), 3000);
    assert!(mission_finished(&bus, 9));
    assert_eq!(bus.get::<Spooler>(MS).unwrap().stats().outbox_dropped, 0);
}
