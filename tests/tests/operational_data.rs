//! Query Platform Operational Data on the demo vehicle: the stock Primitive Driver
//! answers with the simulated vehicle's odometer (the distance it has driven, whole
//! metres), which grows as the vehicle drives and never goes back, with only the fields
//! the query asks for.

use std::time::Duration;

use jaus::component::local::{LocalBus, Probe};
use jaus::messages::*;
use jaus::Address;
use jaus_sim::demo::{self, addr};
use jaus_sim::vehicle::SimVehicle;

const OCU: Address = Address::new(1, 5, 40, 1);

fn ms(n: u64) -> Duration {
    Duration::from_millis(n)
}

/// The demo vehicle on a bus, noise-free, with a probe as the operator.
fn rig() -> (LocalBus, SimVehicle) {
    let t0 = std::time::Instant::now();
    let mut bus = LocalBus::new(t0);
    let opts = demo::Options {
        position_noise: 0.0,
        ..demo::Options::default()
    };
    let (parts, vehicle) = demo::vehicle(t0, &opts);
    for p in parts {
        bus.add_boxed(p);
    }
    bus.add(Probe::new(OCU));
    bus.run_for(ms(500));
    (bus, vehicle)
}

fn probe(bus: &mut LocalBus) -> &mut Probe {
    bus.get_mut::<Probe>(OCU).unwrap()
}

/// The answers to Query Platform Operational Data with `presence_vector`.
fn query(bus: &mut LocalBus, presence_vector: u8) -> Vec<ReportPlatformOperationalData> {
    probe(bus).clear();
    bus.send(
        OCU,
        addr::PD,
        QueryPlatformOperationalData { presence_vector },
    );
    bus.run_for(ms(20));
    probe(bus)
        .messages()
        .filter_map(|m| match m {
            Message::ReportPlatformOperationalData(r) => Some(r.clone()),
            _ => None,
        })
        .collect()
}

/// The odometer the driver reports, m.
fn odometer(bus: &mut LocalBus) -> u32 {
    let r = query(bus, 0xFF);
    assert_eq!(r.len(), 1, "one answer: {r:?}");
    r[0].odometer
        .expect("the demo vehicle reports its odometer")
}

/// The position in the latest Report Local Pose from the Local Pose Sensor.
fn pose(bus: &mut LocalBus) -> (f64, f64) {
    probe(bus).clear();
    bus.send(
        OCU,
        addr::LPS,
        QueryLocalPose {
            presence_vector: 0b11,
        },
    );
    bus.run_for(ms(10));
    probe(bus)
        .messages()
        .find_map(|m| match m {
            Message::ReportLocalPose(p) => Some((p.x?, p.y?)),
            _ => None,
        })
        .expect("a local pose")
}

#[test]
fn the_odometer_grows_with_the_distance_driven_and_never_goes_back() {
    let (mut bus, vehicle) = rig();
    let start = odometer(&mut bus);
    assert_eq!(start, 0, "at rest since start");
    bus.send(
        OCU,
        addr::PD,
        RequestComponentControl {
            authority_code: 200,
        },
    );
    bus.run_for(ms(50));
    bus.send(OCU, addr::PD, Resume {});
    bus.run_for(ms(50));
    // Drive an arc, forward then back, adding up the distance between poses.
    let mut last = pose(&mut bus);
    let mut moved = 0.0;
    let mut reading = start;
    for i in 0..300 {
        let forward = if i < 200 { 60.0 } else { -60.0 };
        bus.send(
            OCU,
            addr::PD,
            SetWrenchEffort {
                propulsive_linear_effort_x: Some(forward),
                propulsive_rotational_effort_z: Some(15.0),
                ..Default::default()
            },
        );
        bus.run_for(ms(70));
        let p = pose(&mut bus);
        moved += ((p.0 - last.0).powi(2) + (p.1 - last.1).powi(2)).sqrt();
        last = p;
        if i % 25 == 24 {
            let now = odometer(&mut bus);
            assert!(now >= reading, "the odometer went back: {reading} → {now}");
            reading = now;
        }
    }
    let driven = f64::from(odometer(&mut bus) - start);
    assert!(moved > 20.0, "moved {moved:.1} m");
    assert!(
        (driven - moved).abs() <= 0.1 * moved,
        "odometer {driven} m, poses {moved:.2} m"
    );
    // Whole metres of the model's distance, rounded down.
    assert_eq!(driven, vehicle.lock().odometer().floor());
    // More than the displacement: it came back part of the way.
    let (x, y) = last;
    assert!(driven > (x * x + y * y).sqrt() + 5.0);
}

#[test]
fn the_query_presence_vector_is_honoured() {
    let (mut bus, _) = rig();
    // The odometer only (bit 1).
    assert_eq!(
        query(&mut bus, 1 << 1),
        [ReportPlatformOperationalData {
            odometer: Some(0),
            ..Default::default()
        }]
    );
    // Fields the model does not have (engine temperature, battery, fuel, oil): an
    // answer with none of them.
    assert_eq!(
        query(&mut bus, 0b1_1101),
        [ReportPlatformOperationalData::default()]
    );
}
