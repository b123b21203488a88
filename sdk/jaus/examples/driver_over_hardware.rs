//! A vendor's Primitive Driver: the SDK's stock driver over the vendor's own motor
//! controller. The vendor writes only the `Actuators` implementation (here it records
//! what it is told); control, the watchdog, emergency and the safe stop are the stock
//! component's and the runtime's. An operator takes control, sends a wrench effort, and
//! stops refreshing it: the driver brakes.
//!
//! Run: `cargo run -p jaus --example driver_over_hardware`

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use jaus::component::local::{LocalBus, Probe};
use jaus::component::Config;
use jaus::components::primitive_driver;
use jaus::messages::{RequestComponentControl, Resume, SetWrenchEffort};
use jaus::stock::drivers::{PrimitiveConfig, StockPrimitiveDriver};
use jaus::stock::hardware::{Actuators, Wrench};
use jaus::Address;

/// Stand-in for a motor controller on a CAN bus: remembers every effort it was given.
#[derive(Clone, Default)]
struct MotorController {
    applied: Arc<Mutex<Vec<(Duration, Wrench)>>>,
    start: Option<Instant>,
}

impl Actuators for MotorController {
    fn apply(&mut self, now: Instant, effort: &Wrench) {
        let start = *self.start.get_or_insert(now);
        // Send the frame to the controller here.
        if let Ok(mut log) = self.applied.lock() {
            log.push((now - start, *effort));
        }
    }
}

fn main() {
    const PD: Address = Address::new(1, 1, 33, 1);
    const OCU: Address = Address::new(1, 1, 200, 1);
    let hardware = MotorController::default();
    let log = hardware.applied.clone();
    let t0 = Instant::now();
    let mut bus = LocalBus::new(t0);
    bus.add(primitive_driver::component(
        PD,
        StockPrimitiveDriver::new(hardware, PrimitiveConfig::default()),
        Config::default(),
        t0,
    ));
    bus.add(Probe::new(OCU));
    bus.run_for(Duration::from_millis(100));

    // Without control the command is refused by the runtime: the motors never see it.
    let forward = SetWrenchEffort {
        propulsive_linear_effort_x: Some(40.0),
        propulsive_rotational_effort_z: Some(-10.0),
        ..Default::default()
    };
    bus.send(OCU, PD, forward.clone());
    bus.run_for(Duration::from_millis(100));

    // With control and Ready, the effort reaches the hardware; not refreshed, it is
    // replaced by brakes after the watchdog's 0.3 s.
    bus.send(OCU, PD, RequestComponentControl { authority_code: 10 });
    bus.send(OCU, PD, Resume {});
    bus.run_for(Duration::from_millis(100));
    bus.send(OCU, PD, forward);
    bus.run_for(Duration::from_secs(1));

    let log = log.lock().map(|l| l.clone()).unwrap_or_default();
    let mut last: Option<Wrench> = None;
    for (t, w) in &log {
        if last.as_ref() != Some(w) {
            println!(
                "t = {:5.2} s  linear x {:6.1} %  rotational z {:6.1} %  brake {:5.1} %",
                t.as_secs_f64(),
                w.linear.x,
                w.rotational.z,
                w.resistive_linear.x
            );
            last = Some(*w);
        }
    }
    let drove = log.iter().any(|(_, w)| (w.linear.x - 40.0).abs() < 0.01);
    let braked = log
        .last()
        .is_some_and(|(_, w)| w.resistive_linear.x > 0.0 && w.linear.x == 0.0);
    assert!(drove, "the controlled effort reached the motors");
    assert!(
        braked,
        "the watchdog braked when the effort was not refreshed"
    );
    println!("the effort reached the motors only under control, then the watchdog braked");
}
