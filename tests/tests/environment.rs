//! Environment sensors over the simulated vehicle (issue 14, in part): the Range Sensor
//! answering Query Relative Object Position from a simulated scanner, and the same
//! scanner feeding the Reflexive Driver, which stops the vehicle before an obstacle that
//! no map holds.

use std::time::{Duration, Instant};

use jaus::component::local::{LocalBus, Probe};
use jaus::component::Config;
use jaus::components::{
    local_pose_sensor, local_vector_driver, primitive_driver, range_sensor, reflexive_driver,
    velocity_state_sensor,
};
use jaus::messages::*;
use jaus::stock::drivers::{
    PrimitiveConfig, ReflexiveConfig, StockLocalVectorDriver, StockPrimitiveDriver,
    StockReflexiveDriver,
};
use jaus::stock::environment::range::{RangeConfig, ScanObstacles, StockRangeSensor};
use jaus::stock::motion::DriverConfig;
use jaus::stock::nalgebra::Vector2;
use jaus::stock::sensors::{StockLocalPoseSensor, StockVelocityStateSensor};
use jaus::Address;
use jaus_sim::scanner::{ScannerParams, Scene, SimScanner};
use jaus_sim::vehicle::{SimVehicle, VehicleParams};

const PD: Address = Address::new(1, 1, 33, 1);
const RD: Address = Address::new(1, 1, 43, 1);
const LPS: Address = Address::new(1, 1, 41, 1);
const VSS: Address = Address::new(1, 1, 42, 1);
const LVD: Address = Address::new(1, 1, 44, 1);
const RS: Address = Address::new(1, 1, 50, 1);
const OCU: Address = Address::new(1, 2, 40, 1);

#[test]
fn the_range_sensor_reports_the_nearest_object() {
    let t0 = Instant::now();
    let vehicle = SimVehicle::new(VehicleParams::default());
    let scanner = SimScanner::new(
        vehicle,
        Scene {
            circles: vec![(Vector2::new(4.0, 0.0), 0.5), (Vector2::new(0.0, 7.0), 1.0)],
        },
        ScannerParams::default(),
    );
    let mut bus = LocalBus::new(t0);
    bus.add(range_sensor::component(
        RS,
        StockRangeSensor::new(scanner, RangeConfig::default()),
        Config::default(),
        t0,
    ));
    bus.add(Probe::new(OCU));
    // Range, bearing and confidence/object id.
    bus.send(
        OCU,
        RS,
        QueryRelativeObjectPosition {
            presence_vector: 0x45,
        },
    );
    bus.run_for(Duration::from_millis(20));
    let r = bus
        .get::<Probe>(OCU)
        .unwrap()
        .messages()
        .find_map(|m| match m {
            Message::ReportRelativeObjectPosition(r) => Some(r.clone()),
            _ => None,
        })
        .expect("a report");
    // 0.5 m circle 4 m ahead: 3.5 m straight ahead (scaled i32 over ±10 km: 5 µm steps).
    assert!((r.range.unwrap() - 3.5).abs() < 1e-5, "{r:?}");
    assert!(r.bearing.unwrap().abs() < 1e-6);
    assert!(r.range_error.is_none() && r.confidence_and_object_id);
    assert!(r.confidence.unwrap() > 1, "seen by several beams");
}

#[test]
fn the_reflexive_driver_stops_before_an_obstacle_no_map_holds() {
    let t0 = Instant::now();
    let vehicle = SimVehicle::new(VehicleParams::default());
    let scanner = SimScanner::new(vehicle.clone(), Scene::default(), ScannerParams::default());
    // Not in any world model: only the scanner can see it.
    scanner.add_obstacle(Vector2::new(8.0, 0.0), 0.5);
    let cfg = Config::default();
    let mut bus = LocalBus::new(t0);
    bus.add(primitive_driver::component(
        PD,
        StockPrimitiveDriver::new(vehicle.clone(), PrimitiveConfig::default()),
        cfg.clone(),
        t0,
    ));
    bus.add(reflexive_driver::component(
        RD,
        StockReflexiveDriver::new(
            ScanObstacles::new(scanner.clone(), 1.0),
            ReflexiveConfig {
                output: PD,
                ..ReflexiveConfig::default()
            },
        ),
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
        output: RD,
        pose_sensor: LPS,
        velocity_sensor: Some(VSS),
        ..DriverConfig::default()
    };
    bus.add(local_vector_driver::component(
        LVD,
        StockLocalVectorDriver::new(dc),
        cfg.clone(),
        t0,
    ));
    bus.add(range_sensor::component(
        RS,
        StockRangeSensor::new(scanner, RangeConfig::default()),
        cfg,
        t0,
    ));
    bus.add(Probe::new(OCU));
    bus.send(OCU, LVD, RequestComponentControl { authority_code: 1 });
    bus.run_for(Duration::from_millis(50));
    bus.send(OCU, LVD, Resume {});
    // Straight north at 1.5 m/s, refreshed, for 15 s: far enough to hit it.
    for _ in 0..75 {
        bus.send(
            OCU,
            LVD,
            SetLocalVector {
                speed: 1.5,
                heading: 0.0,
            },
        );
        bus.run_for(Duration::from_millis(200));
    }
    let x = vehicle.lock().position().x;
    assert!(
        x < 8.0 - 0.5 - 0.3,
        "stopped short of the obstacle's edge at 7.5 m: x = {x:.2}"
    );
    assert!(x > 5.0, "it did drive: x = {x:.2}");
    assert!(vehicle.lock().speed().abs() < 0.05);
    // The range sensor sees it too, as the vehicle stands now.
    bus.send(
        OCU,
        RS,
        QueryRelativeObjectPosition {
            presence_vector: 0x05,
        },
    );
    bus.run_for(Duration::from_millis(20));
    let r = bus
        .get::<Probe>(OCU)
        .unwrap()
        .messages()
        .filter_map(|m| match m {
            Message::ReportRelativeObjectPosition(r) => Some(r.clone()),
            _ => None,
        })
        .last()
        .expect("a report");
    assert!(
        (r.range.unwrap() - (7.5 - x)).abs() < 0.05,
        "{r:?} at x = {x}"
    );
}
