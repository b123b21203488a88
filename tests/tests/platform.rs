//! Platform stock components driving the simulated vehicle: the demo mission (Part 1 path
//! segments and a waypoint list), the Part 1 travel-speed and Standby rules, the
//! watchdog, the emergency stop, control, rejection of bad commands, the vector and
//! reflexive drivers.

mod plots;

use std::time::{Duration, Instant};

use jaus::component::local::{LocalBus, Probe};
use jaus::component::{Component, Config, CoreState};
use jaus::components::{
    local_pose_sensor, local_vector_driver, local_waypoint_driver, primitive_driver,
    reflexive_driver, velocity_state_sensor,
};
use jaus::messages::*;
use jaus::stock::drivers::{
    ObstacleSource, PrimitiveConfig, ReflexiveConfig, StockLocalVectorDriver,
    StockLocalWaypointDriver, StockPrimitiveDriver, StockReflexiveDriver,
};
use jaus::stock::motion::DriverConfig;
use jaus::stock::sensors::{StockLocalPoseSensor, StockVelocityStateSensor};
use jaus::Address;
use jaus_sim::demo;
use jaus_sim::vehicle::{SimVehicle, VehicleParams};

const PD: Address = Address::new(1, 1, 33, 1);
const RD: Address = Address::new(1, 1, 43, 1);
const LPS: Address = Address::new(1, 1, 41, 1);
const VSS: Address = Address::new(1, 1, 42, 1);
const LVD: Address = Address::new(1, 1, 44, 1);
const LWD: Address = Address::new(1, 1, 46, 1);
const OCU: Address = Address::new(1, 2, 40, 1);
const INTRUDER: Address = Address::new(1, 3, 40, 1);

#[test]
fn demo_drives_the_waypoint_mission_and_the_part1_path_segments() {
    let report = demo::run(&demo::Options::default(), |_| {}).expect("demo finishes");
    assert_eq!(
        report.legs.len(),
        11,
        "5 waypoint legs, 2 path segments, 4 spooled moves (a detour on each leg)"
    );
    for leg in &report.legs {
        assert!(leg.arrival.is_some(), "{} never reached", leg.name);
        let limit = if leg.name.starts_with("path") {
            0.10
        } else {
            0.35
        };
        assert!(
            leg.xte_max < limit,
            "{}: max cross-track {:.3} m",
            leg.name,
            leg.xte_max
        );
        assert!(
            leg.xte_rms < 0.12,
            "{}: RMS cross-track {:.3} m",
            leg.name,
            leg.xte_rms
        );
    }
    // Part 1: back to Standby at the final point, within the arrival tolerance (plus
    // the distance coasted while braking).
    assert!(report.waypoints_done.is_some() && report.path_done.is_some());
    // The spooled mission: blocking move, payload action, blocking move home.
    let (horn, done) = (
        report.horn_at.expect("payload action"),
        report.mission_done.expect("mission finished"),
    );
    let path_done = report.path_done.unwrap();
    assert!(
        horn > path_done && horn < done,
        "payload action during the mission: {horn} (path done {path_done}, mission done {done})"
    );
    assert!(
        report.final_errors[2] < 0.2,
        "home missed by {:.3} m",
        report.final_errors[2]
    );
    // The operator asked the world model what lies along the mission and found the
    // obstacle it stored and the one only the Range Sensor had detected (and stored); it
    // planned a detour round each: the vehicle never touched either buffer.
    assert_eq!(report.objects_found, (1, 1), "{:?}", report.planned);
    assert_eq!(report.planned.len(), 4, "{:?}", report.planned);
    for (clearance, radius) in [
        (report.obstacle_clearance, jaus_sim::demo::OBSTACLE.1),
        (report.unknown_clearance, jaus_sim::demo::UNKNOWN_OBSTACLE.1),
    ] {
        assert!(
            clearance > radius + 0.3,
            "closest approach {clearance:.2} m to an obstacle of radius {radius} m"
        );
    }
    for e in &report.final_errors {
        assert!(*e < 0.2, "final point missed by {e:.3} m");
    }
    assert!(report.duration < 120.0);
    // Deterministic for a seed.
    let again = demo::run(&demo::Options::default(), |_| {}).unwrap();
    assert_eq!(again.legs, report.legs);
    // Another seed: still on the path.
    let other = demo::run(
        &demo::Options {
            seed: 99,
            ..Default::default()
        },
        |_| {},
    )
    .unwrap();
    assert!(other.legs.iter().all(|l| l.xte_max < 0.4));
}

#[test]
fn demo_writes_a_plot_of_path_and_trajectory() {
    let dir = std::env::temp_dir().join(format!("jaus-demo-{}", std::process::id()));
    let report = demo::run(&demo::Options::default(), |_| {}).unwrap();
    let path = jaus_cli::report::write_svg(&report, &dir).expect("plot written");
    let svg = std::fs::read_to_string(path).unwrap();
    plots::check_trajectory_plot(&svg);
    let _ = std::fs::remove_dir_all(dir);
}

/// A local subsystem: primitive driver, local pose and velocity sensors, a local
/// waypoint driver and a local vector driver over one vehicle, plus two probes.
fn subsystem(params: VehicleParams) -> (LocalBus, SimVehicle, Instant) {
    let t0 = Instant::now();
    let vehicle = SimVehicle::new(params);
    let cfg = Config::default();
    let mut bus = LocalBus::new(t0).with_trace(200_000);
    let pd = StockPrimitiveDriver::new(vehicle.clone(), PrimitiveConfig::default());
    bus.add(primitive_driver::component(PD, pd, cfg.clone(), t0));
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
        StockLocalWaypointDriver::new(dc.clone()),
        cfg.clone(),
        t0,
    ));
    bus.add(local_vector_driver::component(
        LVD,
        StockLocalVectorDriver::new(dc),
        cfg,
        t0,
    ));
    bus.add(Probe::new(OCU));
    bus.add(Probe::new(INTRUDER));
    (bus, vehicle, t0)
}

type Lwd = Component<local_waypoint_driver::Dispatch<StockLocalWaypointDriver>>;
type Lvd = Component<local_vector_driver::Dispatch<StockLocalVectorDriver>>;
type Pd = Component<primitive_driver::Dispatch<StockPrimitiveDriver<SimVehicle>>>;

fn lwd(bus: &LocalBus) -> &Lwd {
    bus.get::<Lwd>(LWD).unwrap()
}

fn waypoint(n: u16, x: f64, y: f64) -> SetLocalWaypoint {
    SetLocalWaypoint {
        waypoint_number: n,
        x,
        y,
        ..Default::default()
    }
}

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

/// Takes control of the waypoint driver, resumes it, loads a 20 m straight leg.
fn start_mission(bus: &mut LocalBus, speed: f64) {
    bus.send(OCU, LWD, RequestComponentControl { authority_code: 10 });
    bus.run_for(ms(50));
    bus.send(OCU, LWD, Resume {});
    bus.send(OCU, LWD, waypoint(0, 10.0, 0.0));
    bus.send(OCU, LWD, waypoint(1, 20.0, 0.0));
    bus.send(OCU, LWD, SetTravelSpeed { speed });
    bus.run_for(ms(50));
}

#[test]
fn waypoint_driver_follows_part1_rules_for_travel_speed_and_standby() {
    let (mut bus, vehicle, _) = subsystem(VehicleParams::default());
    start_mission(&mut bus, 1.0);
    assert_eq!(lwd(&bus).state(), CoreState::Ready);
    assert_eq!(lwd(&bus).mode(), local_waypoint_driver::Mode::Navigating);
    // Standby -> Ready resets the travel speed to zero: the vehicle waits.
    bus.run_for(Duration::from_secs(3));
    bus.send(OCU, LWD, Standby {});
    bus.run_for(ms(100));
    bus.send(OCU, LWD, Resume {});
    bus.run_for(ms(100));
    assert_eq!(lwd(&bus).behaviour().0.travel_speed(), 0.0);
    bus.run_for(Duration::from_secs(2));
    assert!(
        vehicle.lock().speed().abs() < 0.05,
        "no travel speed, no motion"
    );
    let waiting_at = vehicle.lock().position();
    // A new travel speed resumes the mission; at the final waypoint: Standby.
    bus.send(OCU, LWD, SetTravelSpeed { speed: 1.5 });
    bus.run_for(Duration::from_secs(25));
    let w = lwd(&bus);
    assert_eq!(
        w.state(),
        CoreState::Standby,
        "back to Standby at the final waypoint"
    );
    assert_eq!(w.mode(), local_waypoint_driver::Mode::Idle);
    assert_eq!(w.behaviour().0.arrivals(), 1);
    let end = vehicle.lock().position();
    assert!(
        (end - jaus::stock::nalgebra::Vector2::new(20.0, 0.0)).norm() < 0.2,
        "{end}"
    );
    assert!(waiting_at.x < 19.0);
    // The list is consumed.
    bus.send(OCU, LWD, QueryWaypointCount {});
    bus.run_for(ms(20));
    let count = bus
        .get::<Probe>(OCU)
        .unwrap()
        .messages()
        .find_map(|m| match m {
            Message::ReportWaypointCount(c) => Some(c.waypoint_count),
            _ => None,
        });
    assert_eq!(count, Some(0));
}

#[test]
fn watchdog_stops_the_vehicle_when_pose_goes_stale() {
    let (mut bus, vehicle, _) = subsystem(VehicleParams::default());
    start_mission(&mut bus, 1.0);
    bus.run_for(Duration::from_secs(4));
    assert!(vehicle.lock().speed() > 0.8);
    // The pose sensor falls silent: brakes within 0.5 s (docs/performance.md).
    bus.set_filter(|h| h.source != LPS);
    let mut braked_after = None;
    for i in 1..=40 {
        bus.run_for(ms(25));
        let pd = bus.get::<Pd>(PD).unwrap();
        if pd.behaviour().0.applied().resistive_linear.x > 0.0 {
            braked_after = Some(i * 25);
            break;
        }
    }
    let braked_after = braked_after.expect("the driver braked");
    assert!(
        braked_after <= 500,
        "braked {braked_after} ms after the pose stopped"
    );
    bus.run_for(Duration::from_secs(2));
    assert!(
        vehicle.lock().speed().abs() < 0.02,
        "stopped: {}",
        vehicle.lock().speed()
    );
    assert!(lwd(&bus).behaviour().0.motion.watchdog_trips() >= 1);
    // Pose back: the mission continues to the end.
    bus.clear_filter();
    bus.run_for(Duration::from_secs(25));
    assert_eq!(lwd(&bus).state(), CoreState::Standby);
}

#[test]
fn emergency_stops_the_vehicle_and_holds_it() {
    let (mut bus, vehicle, _) = subsystem(VehicleParams::default());
    start_mission(&mut bus, 1.5);
    bus.run_for(Duration::from_secs(4));
    assert!(vehicle.lock().speed() > 1.0);
    // Anyone may stop it: the intruder (not in control) sets the emergency.
    let e = SetEmergency {
        emergency_code: EmergencyCode {
            transition_to_emergency: true,
            reserved: 0,
        },
    };
    bus.send(INTRUDER, LWD, e.clone());
    bus.send(INTRUDER, PD, e);
    bus.run_for(Duration::from_secs(2));
    assert_eq!(lwd(&bus).state(), CoreState::Emergency);
    assert_eq!(bus.get::<Pd>(PD).unwrap().state(), CoreState::Emergency);
    assert!(vehicle.lock().speed().abs() < 0.01);
    // Commands change nothing while the emergency holds.
    bus.send(OCU, LWD, SetTravelSpeed { speed: 2.0 });
    bus.send(OCU, LWD, Resume {});
    bus.run_for(Duration::from_secs(2));
    assert!(vehicle.lock().speed().abs() < 0.01);
    assert_eq!(lwd(&bus).state(), CoreState::Emergency);
}

/// An emergency on the output alone, cleared by whoever set it, leaves the Primitive
/// Driver in Standby (Clear Emergency → Standby); the waypoint driver, still Ready and
/// still in control of it, sees it report Standby and resumes it, and the vehicle goes on
/// (the emergency of a whole vehicle ends the same way once its drivers are resumed).
#[test]
fn a_driver_resumes_its_output_after_an_emergency_on_the_output_is_cleared() {
    let (mut bus, vehicle, _) = subsystem(VehicleParams::default());
    start_mission(&mut bus, 1.5);
    bus.run_for(Duration::from_secs(3));
    assert!(vehicle.lock().speed() > 1.0);
    bus.send(
        INTRUDER,
        PD,
        SetEmergency {
            emergency_code: EmergencyCode {
                transition_to_emergency: true,
                reserved: 0,
            },
        },
    );
    bus.run_for(Duration::from_secs(2));
    assert_eq!(bus.get::<Pd>(PD).unwrap().state(), CoreState::Emergency);
    assert!(vehicle.lock().speed().abs() < 0.01);
    // Still Emergency after more than one status period: nothing resumes an emergency.
    bus.run_for(Duration::from_secs(2));
    assert_eq!(bus.get::<Pd>(PD).unwrap().state(), CoreState::Emergency);
    assert_eq!(lwd(&bus).state(), CoreState::Ready);
    let x0 = vehicle.lock().position().x;
    bus.send(
        INTRUDER,
        PD,
        ClearEmergency {
            emergency_code: ClearEmergencyCode {
                clear_emergency: true,
                reserved: 0,
            },
        },
    );
    bus.run_for(ms(20));
    assert_eq!(bus.get::<Pd>(PD).unwrap().state(), CoreState::Standby);
    // Resumed within one status period (1 s) and a round trip.
    bus.run_for(ms(1_100));
    assert_eq!(bus.get::<Pd>(PD).unwrap().state(), CoreState::Ready);
    bus.run_for(Duration::from_secs(3));
    assert!(vehicle.lock().position().x > x0 + 1.0, "on its way again");
}

#[test]
fn commands_without_control_and_bad_values_are_refused() {
    let (mut bus, _vehicle, _) = subsystem(VehicleParams::default());
    start_mission(&mut bus, 1.0);
    // Not in control: ignored.
    bus.send(INTRUDER, LWD, waypoint(0, -50.0, 0.0));
    bus.send(INTRUDER, LWD, SetTravelSpeed { speed: 0.1 });
    bus.run_for(ms(50));
    let w = lwd(&bus);
    assert_eq!(w.stats().not_controller, 2);
    assert_eq!(w.behaviour().0.elements().len(), 2);
    // 1.0 m/s on the wire: scaled u16 over 0..10000 m/s, one step is 0.153 m/s.
    let speed = w.behaviour().0.travel_speed();
    assert!((speed - 1.0).abs() < 0.08, "{speed}");
    // In control but out of range / leaving a gap: refused, with a NAK when asked.
    let mut h = jaus::Header::new(SetTravelSpeed::CODE, LWD, OCU);
    h.ack_nak = jaus::wire::AckNak::Request;
    bus.send_with(h, Some(&SetTravelSpeed { speed: 9.0 }.into()));
    bus.send(OCU, LWD, waypoint(7, 1.0, 1.0));
    bus.run_for(ms(50));
    let w = lwd(&bus);
    assert_eq!(w.stats().invalid, 2);
    assert_eq!(w.behaviour().0.travel_speed(), speed);
    assert!(bus
        .trace()
        .any(|d| d.header.source == LWD && d.header.ack_nak == jaus::wire::AckNak::Nak));
}

#[test]
fn local_vector_driver_holds_heading_and_speed_and_stops_on_stale_commands() {
    let (mut bus, vehicle, _) = subsystem(VehicleParams::default());
    bus.send(OCU, LVD, RequestComponentControl { authority_code: 1 });
    bus.run_for(ms(50));
    bus.send(OCU, LVD, Resume {});
    let heading = std::f64::consts::FRAC_PI_2;
    for _ in 0..30 {
        bus.send(
            OCU,
            LVD,
            SetLocalVector {
                speed: 1.0,
                heading,
            },
        );
        bus.run_for(ms(200));
    }
    {
        let v = vehicle.lock();
        assert!((v.yaw() - heading).abs() < 0.05, "heading {}", v.yaw());
        assert!((v.speed() - 1.0).abs() < 0.1, "speed {}", v.speed());
    }
    // No refresh for the command timeout (2 s): the driver stops the vehicle.
    bus.run_for(Duration::from_secs(4));
    assert!(vehicle.lock().speed().abs() < 0.02);
    let lvd = bus.get::<Lvd>(LVD).unwrap();
    assert_eq!(lvd.state(), CoreState::Ready);
}

/// An obstacle a fixed distance ahead of the start, on the +x axis.
struct Wall {
    vehicle: SimVehicle,
    at: f64,
}

impl ObstacleSource for Wall {
    fn obstacle_distance(&mut self, _now: Instant) -> Option<f64> {
        Some(self.at - self.vehicle.lock().position().x)
    }
}

#[test]
fn reflexive_driver_slows_and_stops_before_an_obstacle() {
    let (mut bus, vehicle, t0) = subsystem(VehicleParams::default());
    let wall = Wall {
        vehicle: vehicle.clone(),
        at: 8.0,
    };
    let rd = StockReflexiveDriver::new(wall, ReflexiveConfig::default());
    bus.add(reflexive_driver::component(RD, rd, Config::default(), t0));
    // Drive the reflexive driver directly with full forward effort.
    bus.send(OCU, RD, RequestComponentControl { authority_code: 1 });
    bus.run_for(ms(50));
    bus.send(OCU, RD, Resume {});
    for _ in 0..100 {
        bus.send(
            OCU,
            RD,
            SetWrenchEffort {
                propulsive_linear_effort_x: Some(80.0),
                ..Default::default()
            },
        );
        bus.run_for(ms(100));
    }
    let x = vehicle.lock().position().x;
    assert!(
        x > 5.0 && x < 8.0 - 0.5,
        "stopped short of the wall: x = {x}"
    );
    assert!(vehicle.lock().speed().abs() < 0.05);
}

use jaus::JausMessage;
