//! The stock manipulator components one rule at a time, over the simulated arm on the
//! in-process bus: control and authority, refusals that leave the arm still, emergency,
//! the feedback and command watchdogs, Joint Move timing, determinism.

use std::time::{Duration, Instant};

use jaus::component::local::{LocalBus, Probe};
use jaus::component::{Component, CoreState};
use jaus::components::{
    manipulator_joint_move_driver as jmd, manipulator_joint_positions_driver as jpd,
    primitive_manipulator as pm,
};
use jaus::messages::*;
use jaus::stock::manipulator::{
    StockJointMoveDriver, StockJointPositionsDriver, StockPrimitiveManipulator,
};
use jaus::wire::AckNak;
use jaus::{Address, Header, JausMessage};
use jaus_sim::arm::{ArmParams, SimArm};
use jaus_sim::arm_demo::{self, addr, ArmOptions};

const OCU: Address = Address::new(1, 2, 40, 1);
const INTRUDER: Address = Address::new(1, 4, 40, 1);

type Pm = Component<pm::Dispatch<StockPrimitiveManipulator<SimArm>>>;
type Jpd = Component<jpd::Dispatch<StockJointPositionsDriver>>;
type Jmd = Component<jmd::Dispatch<StockJointMoveDriver>>;

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

/// The ten components over a fresh arm, the operator and an intruder as probes.
fn arm_node() -> (LocalBus, SimArm) {
    let t0 = Instant::now();
    let arm = SimArm::new(ArmParams::six_axis());
    let mut bus = LocalBus::new(t0).with_trace(1_000_000);
    for c in arm_demo::arm_components(&arm, 1, 3, t0) {
        bus.add_boxed(c);
    }
    bus.add(Probe::new(OCU));
    bus.add(Probe::new(INTRUDER));
    (bus, arm)
}

/// The operator takes control of `driver` with authority 200, resumes it, and waits
/// until the driver holds the arm.
fn take(bus: &mut LocalBus, driver: Address) {
    bus.send(
        OCU,
        driver,
        RequestComponentControl {
            authority_code: 200,
        },
    );
    bus.run_for(ms(50));
    bus.send(OCU, driver, Resume {});
    bus.run_for(Duration::from_secs(2));
}

fn with_ack(bus: &mut LocalBus, from: Address, to: Address, msg: impl Into<Message>) {
    let msg: Message = msg.into();
    let mut h = Header::new(msg.code(), to, from);
    h.ack_nak = AckNak::Request;
    bus.send_with(h, Some(&msg));
}

fn naks_from(bus: &LocalBus, source: Address) -> usize {
    bus.trace()
        .filter(|d| d.header.source == source && d.header.ack_nak == AckNak::Nak)
        .count()
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn only_the_controller_commands_and_a_lower_authority_cannot_take_over() {
    let (mut bus, arm) = arm_node();
    take(&mut bus, addr::JPD);
    assert_eq!(bus.get::<Jpd>(addr::JPD).unwrap().state(), CoreState::Ready);
    let before = arm.lock().positions().to_vec();
    // The intruder is not in control: ignored, counted.
    bus.send(
        INTRUDER,
        addr::JPD,
        SetJointPositions {
            joint_position: vec![0.5; 6],
        },
    );
    // And cannot take control with a lower authority.
    bus.send(
        INTRUDER,
        addr::JPD,
        RequestComponentControl { authority_code: 10 },
    );
    bus.run_for(Duration::from_secs(1));
    let d = bus.get::<Jpd>(addr::JPD).unwrap();
    assert_eq!(d.stats().not_controller, 1);
    assert_eq!(d.controller().map(|c| c.0), Some(OCU));
    assert!(bus
        .get::<Probe>(INTRUDER)
        .unwrap()
        .messages()
        .any(|m| matches!(m, Message::RejectComponentControl(_))));
    let moved = max_diff(arm.lock().positions(), &before);
    assert!(moved < 2e-3, "the arm held still: moved {moved} rad");
    // The controller is obeyed.
    let target = [0.2, -0.5, 1.2, 0.1, 0.7, 0.2];
    bus.send(
        OCU,
        addr::JPD,
        SetJointPositions {
            joint_position: target.to_vec(),
        },
    );
    bus.run_for(Duration::from_secs(4));
    let q = arm.lock().positions().to_vec();
    assert!(max_diff(&q, &target) < 2e-3, "{q:?}");
}

#[test]
fn refused_commands_are_naked_and_leave_the_arm_still() {
    let (mut bus, arm) = arm_node();
    take(&mut bus, addr::JPD);
    take(&mut bus, addr::EPD);
    let before = arm.lock().positions().to_vec();
    // Wrong joint count, beyond a joint's limit, an unreachable pose, a zero quaternion.
    with_ack(
        &mut bus,
        OCU,
        addr::JPD,
        SetJointPositions {
            joint_position: vec![0.1; 5],
        },
    );
    with_ack(
        &mut bus,
        OCU,
        addr::JPD,
        SetJointPositions {
            joint_position: vec![0.0, 2.0, 0.0, 0.0, 0.0, 0.0],
        },
    );
    with_ack(
        &mut bus,
        OCU,
        addr::EPD,
        SetEndEffectorPose {
            x: 2.5,
            y: 0.0,
            z: 0.0,
            d: 1.0,
            a: 0.0,
            b: 0.0,
            c: 0.0,
        },
    );
    with_ack(
        &mut bus,
        OCU,
        addr::EPD,
        SetEndEffectorPose {
            x: 0.4,
            y: 0.0,
            z: 0.0,
            d: 0.0,
            a: 0.0,
            b: 0.0,
            c: 0.0,
        },
    );
    bus.run_for(Duration::from_secs(1));
    assert_eq!(bus.get::<Jpd>(addr::JPD).unwrap().stats().invalid, 2);
    assert_eq!(naks_from(&bus, addr::JPD), 2);
    assert_eq!(naks_from(&bus, addr::EPD), 2);
    // Nothing moved (the drivers hold the arm where it was).
    assert!(max_diff(arm.lock().positions(), &before) < 2e-3);
}

#[test]
fn emergency_zeroes_every_effort_within_one_control_period() {
    let (mut bus, arm) = arm_node();
    take(&mut bus, addr::JPD);
    bus.send(
        OCU,
        addr::JPD,
        SetJointPositions {
            joint_position: vec![1.0, -1.0, 1.5, 0.5, 1.0, 0.5],
        },
    );
    bus.run_for(ms(500));
    assert!(arm.lock().efforts().iter().any(|e| e.abs() > 5.0), "moving");
    // Anyone may set the emergency.
    let e = SetEmergency {
        emergency_code: EmergencyCode {
            transition_to_emergency: true,
            reserved: 0,
        },
    };
    bus.send(INTRUDER, addr::PM, e.clone());
    bus.send(INTRUDER, addr::JPD, e);
    bus.run_for(arm_demo::CONTROL_PERIOD);
    assert!(
        arm.lock().efforts().iter().all(|e| *e == 0.0),
        "{:?}",
        arm.lock().efforts()
    );
    assert!(bus
        .get::<Pm>(addr::PM)
        .unwrap()
        .behaviour()
        .0
        .applied()
        .iter()
        .all(|e| *e == 0.0));
    assert_eq!(
        bus.get::<Jpd>(addr::JPD).unwrap().state(),
        CoreState::Emergency
    );
    // Commands change nothing while it holds.
    bus.send(
        OCU,
        addr::JPD,
        SetJointPositions {
            joint_position: vec![0.0; 6],
        },
    );
    bus.run_for(ms(500));
    assert!(arm.lock().efforts().iter().all(|e| *e == 0.0));
}

#[test]
fn stale_joint_feedback_zeroes_the_efforts_and_the_driver_recovers() {
    let (mut bus, arm) = arm_node();
    take(&mut bus, addr::JPD);
    let target = [0.4, -0.6, 1.3, 0.0, 0.9, 0.0];
    bus.send(
        OCU,
        addr::JPD,
        SetJointPositions {
            joint_position: target.to_vec(),
        },
    );
    bus.run_for(ms(500));
    // The position sensor falls silent: zero effort within the 100 ms feedback timeout
    // and one control period.
    bus.set_filter(|h| h.source != addr::JPS);
    let mut zeroed_after = None;
    for i in 1..=30 {
        bus.run_for(ms(10));
        if arm.lock().efforts().iter().all(|e| *e == 0.0) {
            zeroed_after = Some(i * 10);
            break;
        }
    }
    let zeroed_after = zeroed_after.unwrap_or_else(|| {
        let d = &bus.get::<Jpd>(addr::JPD).unwrap().behaviour().0;
        panic!(
            "the watchdog did not zero the efforts: arm {:?}, driver sent {:?}, {:?}",
            arm.lock().efforts(),
            d.link.last_efforts(),
            d.link.counters()
        )
    });
    assert!(
        zeroed_after <= 130,
        "zeroed {zeroed_after} ms after the feedback stopped"
    );
    assert!(
        bus.get::<Jpd>(addr::JPD)
            .unwrap()
            .behaviour()
            .0
            .link
            .counters()
            .watchdog_trips
            >= 1
    );
    // Feedback back: the driver takes the arm to the target again.
    bus.clear_filter();
    bus.run_for(Duration::from_secs(5));
    assert!(
        max_diff(arm.lock().positions(), &target) < 2e-3,
        "{:?}",
        arm.lock().positions()
    );
}

#[test]
fn the_primitive_manipulator_applies_checked_efforts_and_holds_the_arm_when_they_go_stale() {
    let (mut bus, arm) = arm_node();
    take(&mut bus, addr::PM);
    bus.send(
        OCU,
        addr::PM,
        SetJointEfforts {
            joint_effort: vec![10.0, -5.0, 0.0, 0.0, 0.0, 0.0],
        },
    );
    bus.run_for(ms(20));
    // Scaled integers on the wire: 200 % over 65,535 steps.
    let e = arm.lock().efforts().to_vec();
    assert!(
        (e[0] - 10.0).abs() < 0.01 && (e[1] + 5.0).abs() < 0.01,
        "{e:?}"
    );
    // Wrong joint count: refused with a NAK; the efforts stay.
    with_ack(
        &mut bus,
        OCU,
        addr::PM,
        SetJointEfforts {
            joint_effort: vec![50.0; 3],
        },
    );
    bus.run_for(ms(20));
    assert_eq!(naks_from(&bus, addr::PM), 1);
    assert!((arm.lock().efforts()[0] - 10.0).abs() < 0.01);
    // Not refreshed for 300 ms: the command ends and the holding controller holds the
    // arm where it is (issue 51; it used to be zero effort, and the arm fell).
    bus.run_for(ms(400));
    let p = bus.get::<Pm>(addr::PM).unwrap();
    assert_eq!(p.behaviour().0.watchdog_trips(), 1);
    assert!(p.behaviour().0.holding());
    let held = p.behaviour().0.hold_target().map(<[f64]>::to_vec);
    let held = held.expect("the positions held");
    bus.run_for(ms(2000));
    let q = arm.lock().positions().to_vec();
    assert!(max_diff(&q, &held) < 2e-3, "{q:?} vs {held:?}");
    // Zero effort commanded on every joint stands, past the watchdog too.
    bus.send(
        OCU,
        addr::PM,
        SetJointEfforts {
            joint_effort: vec![0.0; 6],
        },
    );
    bus.run_for(ms(1000));
    assert!(arm.lock().efforts().iter().all(|e| *e == 0.0));
    assert!(!bus.get::<Pm>(addr::PM).unwrap().behaviour().0.holding());
    // The specifications describe the simulated arm.
    bus.send(OCU, addr::PM, QueryManipulatorSpecifications {});
    bus.run_for(ms(20));
    let spec = bus
        .get::<Probe>(OCU)
        .unwrap()
        .messages()
        .find_map(|m| match m {
            Message::ReportManipulatorSpecifications(r) => Some(r.clone()),
            _ => None,
        })
        .expect("specifications");
    assert_eq!(spec.num_joints, 6);
    let chain = jaus::stock::manipulator::kinematics::Chain::from_specifications(&spec).unwrap();
    let q = [0.3, -0.7, 1.1, 0.4, -0.9, 2.0];
    let d =
        chain.forward(&q).translation.vector - arm.lock().chain().forward(&q).translation.vector;
    assert!(d.norm() < 2e-3, "{d}");
}

#[test]
fn a_joint_move_reaches_each_set_at_its_time() {
    let (mut bus, arm) = arm_node();
    take(&mut bus, addr::JMD);
    let sets = [
        (2.0, [0.3, -0.5, 0.9, 0.0, 0.9, 0.0]),
        (4.0, [0.8, -0.6, 1.1, 0.1, 1.0, 0.2]),
    ];
    let poses = sets
        .iter()
        .map(|(t, q)| JointMotionPose {
            pose_time: *t,
            joints: q
                .iter()
                .map(|&position| JointMotionLimits {
                    position,
                    max_velocity: 1.0,
                    max_acceleration: 2.0,
                    max_deceleration: 2.0,
                })
                .collect(),
        })
        .collect::<Vec<_>>();
    let start = bus.now();
    bus.send(
        OCU,
        addr::JMD,
        SetJointMotion {
            num_joints: 6,
            num_poses: 2,
            poses,
        },
    );
    bus.run_for(ms(20));
    assert_eq!(bus.get::<Jmd>(addr::JMD).unwrap().mode(), jmd::Mode::Moving);
    for (t, q) in &sets {
        // One control period after the set's time.
        bus.run_until(start + Duration::from_secs_f64(*t) + arm_demo::CONTROL_PERIOD);
        let err = max_diff(arm.lock().positions(), q);
        println!("set at {t} s: largest joint error {:.4} rad", err);
        assert!(
            err < 0.02,
            "set at {t} s: {:?} vs {q:?}",
            arm.lock().positions()
        );
    }
    bus.run_for(Duration::from_secs(1));
    assert_eq!(bus.get::<Jmd>(addr::JMD).unwrap().mode(), jmd::Mode::Idle);
    // A set the joints cannot reach in time is refused and nothing moves.
    let before = arm.lock().positions().to_vec();
    with_ack(
        &mut bus,
        OCU,
        addr::JMD,
        SetJointMotion {
            num_joints: 6,
            num_poses: 1,
            poses: vec![JointMotionPose {
                pose_time: 0.5,
                joints: (0..6)
                    .map(|_| JointMotionLimits {
                        position: -2.0,
                        max_velocity: 1.0,
                        max_acceleration: 2.0,
                        max_deceleration: 2.0,
                    })
                    .collect(),
            }],
        },
    );
    bus.run_for(Duration::from_secs(1));
    assert_eq!(naks_from(&bus, addr::JMD), 1);
    let moved = max_diff(arm.lock().positions(), &before);
    assert!(moved < 2e-3, "moved {moved} rad");
    let _ = SetJointMotion::CODE;
}

#[test]
fn the_arm_demo_is_deterministic_per_seed() {
    let run = |seed| {
        arm_demo::run(
            &ArmOptions {
                seed,
                progress: None,
                ..ArmOptions::default()
            },
            |_| {},
        )
        .expect("finishes")
        .moves
    };
    assert_eq!(run(3), run(3));
}

/// Every driver, while merely holding the arm against gravity: emergency zeroes the
/// efforts within one control period, and silencing its joint feedback zeroes them
/// within the feedback timeout and one period.
#[test]
fn every_driver_obeys_emergency_and_its_feedback_watchdog() {
    for driver in [
        addr::JPD,
        addr::EPD,
        addr::JVD,
        addr::EVD,
        addr::JMD,
        addr::DPD,
    ] {
        let (mut bus, arm) = arm_node();
        take(&mut bus, driver);
        let holding = arm.lock().efforts().iter().any(|e| e.abs() > 1.0);
        assert!(holding, "{driver}: holds the arm against gravity");
        bus.send(
            INTRUDER,
            driver,
            SetEmergency {
                emergency_code: EmergencyCode {
                    transition_to_emergency: true,
                    reserved: 0,
                },
            },
        );
        bus.run_for(arm_demo::CONTROL_PERIOD);
        assert!(
            arm.lock().efforts().iter().all(|e| *e == 0.0),
            "{driver}: efforts after emergency {:?}",
            arm.lock().efforts()
        );

        let (mut bus, arm) = arm_node();
        take(&mut bus, driver);
        // The sensors this driver follows fall silent.
        bus.set_filter(|h| h.source != addr::JPS && h.source != addr::JVS);
        bus.run_for(ms(130));
        assert!(
            arm.lock().efforts().iter().all(|e| *e == 0.0),
            "{driver}: efforts without feedback {:?}",
            arm.lock().efforts()
        );
    }
}
