//! AS-4 UGV Skid Steer Driver and Power Plant Manager through the gateway
//! (`jaus_as4::ugv::skid_steer`, `jaus_as4::ugv::power_plant`), over the demo vehicle's
//! RA 3.3 Primitive Driver.
//!
//! Skid steer: efforts of the two sides from the controlling client drive the simulated
//! vehicle: equal ones straight ahead, a faster left side turns it right (its heading
//! increases), a faster right side left; the Mobility Primitive Driver's efforts to the
//! same RA 3.3 driver win when they come later; refused without control; Query Skid
//! Steer Effort reads back what was commanded, 0 and 0 after leaving Ready.
//!
//! Power plant: the engine switched on and off by the controlling client through AS-4
//! is the RA 3.3 driver's main propulsion bit, read back through AS-4 and from the
//! driver's discrete devices, the parking brake bit of the same message untouched (also
//! when both commands come together); what RA 3.3 cannot do (standby, a throttle,
//! another power plant) refused; the engine's gauges of RA 3.3 Report Platform
//! Operational Data in its status.

use std::time::{Duration, Instant};

use jaus::component::Config;
use jaus::components::primitive_driver as pd;
use jaus::messages as ra;
use jaus::net::as5669a::{As4Client, As4Id, As4Message};
use jaus::stock::drivers::{PrimitiveConfig, StockPrimitiveDriver};
use jaus::stock::hardware::{Actuators, OperationalData, Wrench};
use jaus::JausMessage;
use jaus_as4::{
    ComponentState, GasEngineSettings, Message, PowerPlantCondition, PowerPlantConfiguration,
    PowerPlantLimits, PowerPlantSettings, PowerState, QueryPowerPlantCapabilities,
    QueryPowerPlantConfiguration, QueryPowerPlantStatus, QuerySkidSteerEffort, QueryStatus, Resume,
    SetParkingBrake, SetPowerPlantConfiguration, SetSkidSteerEffort, SetWrenchEffort, Standby,
};
use jaus_sim::network::SimNet;
use jaus_sim::vehicle::SimVehicle;

mod common;
use common::as4::As4Rig;

const VEHICLE: As4Id = As4Id::new(1, 1, 1);
const WAIT: Duration = Duration::from_millis(500);

/// The demo vehicle's hardware with engine gauges: what a vendor's platform gives its
/// RA 3.3 Primitive Driver as operational data.
struct Gauged(SimVehicle);

impl Actuators for Gauged {
    fn apply(&mut self, now: Instant, effort: &Wrench) {
        self.0.apply(now, effort);
    }

    fn operational_data(&mut self, now: Instant) -> Option<OperationalData> {
        let odometer = self.0.operational_data(now).and_then(|d| d.odometer);
        Some(OperationalData {
            engine_temperature: Some(88.0),
            odometer,
            battery_voltage: Some(97.0),
            fuel_level: Some(62.5),
            oil_pressure: Some(104.0),
        })
    }
}

struct Rig {
    rig: As4Rig,
    vehicle: SimVehicle,
}

impl Rig {
    /// The demo vehicle behind the gateway, its stock RA 3.3 Primitive Driver over
    /// [`Gauged`] hardware.
    fn demo() -> Self {
        let t0 = Instant::now();
        let at = jaus::Address::new(1, 1, pd::ID, 1);
        let (mut node, vehicle) = As4Rig::demo_vehicle_node(t0, Some(at));
        let specifications = Some(vehicle.lock().params().specifications());
        let driver = StockPrimitiveDriver::new(
            Gauged(vehicle.clone()),
            PrimitiveConfig {
                specifications,
                ..PrimitiveConfig::default()
            },
        );
        node.add_boxed(Box::new(pd::component(at, driver, Config::default(), t0)))
            .expect("added");
        let rig = As4Rig::new(t0, node, VEHICLE, "demo vehicle", Duration::from_secs(3));
        Rig { rig, vehicle }
    }

    fn one(&mut self, m: impl Into<Message>) -> Message {
        self.rig.one_within(m, WAIT)
    }

    fn status(&mut self) -> ComponentState {
        let Message::ReportStatus(s) = self.one(QueryStatus {}) else {
            panic!("no Report Status");
        };
        s.status
    }

    fn ready(&mut self) {
        self.rig.take_control();
        assert!(self.rig.ask(Resume {}, WAIT).is_empty());
        assert_eq!(self.status(), ComponentState::Ready);
    }

    /// The simulated vehicle's true position (north, east; m) and heading (rad,
    /// clockwise from north).
    fn pose(&self) -> (f64, f64, f64) {
        let v = self.vehicle.lock();
        let p = v.position();
        (p.x, p.y, v.yaw())
    }

    /// Streams Set Skid Steer Effort `left`, `right` every 100 ms for `secs` seconds
    /// (the RA 3.3 driver's watchdog brakes a stale effort).
    fn drive(&mut self, left: f64, right: f64, secs: u32) {
        for _ in 0..secs * 10 {
            let got = self.rig.ask(
                SetSkidSteerEffort {
                    left_side_propulsive_effort: left,
                    right_side_propulsive_effort: right,
                },
                Duration::from_millis(100),
            );
            assert!(got.is_empty(), "{got:?}");
        }
    }

    /// Streams the Mobility Primitive Driver's Set Wrench Effort, linear x alone, every
    /// 100 ms for `secs` seconds.
    fn wrench(&mut self, x: f64, secs: u32) {
        for _ in 0..secs * 10 {
            let got = self.rig.ask(
                SetWrenchEffort {
                    propulsive_linear_effort_x: Some(x),
                    propulsive_rotational_effort_z: Some(0.0),
                    ..Default::default()
                },
                Duration::from_millis(100),
            );
            assert!(got.is_empty(), "{got:?}");
        }
    }

    /// Asserts Query Skid Steer Effort reads `left`, `right` (within the wire's
    /// resolution: 0 is carried as 0.0015).
    fn efforts(&mut self, left: f64, right: f64) {
        let Message::ReportSkidSteerEffort(r) = self.one(QuerySkidSteerEffort {}) else {
            panic!("no Report Skid Steer Effort");
        };
        let got = (
            r.left_side_propulsive_effort,
            r.right_side_propulsive_effort,
        );
        assert!(close(got.0, left) && close(got.1, right), "{got:?}");
    }

    /// The main propulsion and parking brake bits of the RA 3.3 Primitive Driver's
    /// latest Report Discrete Devices, as the gateway holds it (a field left out: never
    /// set, off).
    fn ra33_bits(&self) -> (bool, bool) {
        let env = self.rig.dual().gateway().node().env();
        let at = env.targets().primitive_driver.expect("the driver found");
        match env.latest(at, ra::ReportDiscreteDevices::CODE) {
            Some((_, ra::Message::ReportDiscreteDevices(r))) => (
                r.propulsion.is_some_and(|p| p.main_propulsion),
                r.parking_brake_and_horn.is_some_and(|b| b.parking_brake),
            ),
            other => panic!("no RA 3.3 discrete devices: {other:?}"),
        }
    }
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 0.01
}

#[test]
fn skid_steer_efforts_drive_the_ra33_vehicle_straight_and_turn_it() {
    let mut r = Rig::demo();
    let uris = r.rig.service_uris();
    for want in [
        "urn:jaus:jss:ugv:SkidSteerDriver",
        "urn:jaus:jss:mobility:PrimitiveDriver",
    ] {
        assert_eq!(
            uris.iter().filter(|u| *u == want).count(),
            1,
            "{want} once in {uris:?}"
        );
    }
    r.efforts(0.0, 0.0);

    // Without control: refused, the vehicle stays.
    let refused = r.rig.refused();
    r.drive(60.0, 60.0, 1);
    assert!(r.rig.refused() >= refused + 10, "every effort refused");
    r.efforts(0.0, 0.0);
    let (n0, e0, yaw0) = r.pose();
    assert!(n0.abs() < 0.01 && e0.abs() < 0.01, "moved to {n0}, {e0}");

    // Equal efforts: straight ahead (north, its heading at the start).
    r.ready();
    r.drive(60.0, 60.0, 3);
    r.efforts(60.0, 60.0);
    let (n1, e1, yaw1) = r.pose();
    eprintln!("straight: {n1:.2} m north, {e1:.3} m east, heading {yaw1:.4} rad");
    assert!(n1 > 2.0, "only {n1} m forward");
    assert!(e1.abs() < 0.05, "drifted {e1} m sideways");
    assert!((yaw1 - yaw0).abs() < 0.01, "turned {} rad", yaw1 - yaw0);

    // The left side faster: it turns right, its heading increasing.
    r.drive(80.0, 20.0, 2);
    let (_, _, yaw2) = r.pose();
    eprintln!("left faster: heading {yaw1:.3} -> {yaw2:.3} rad");
    assert!(yaw2 - yaw1 > 0.5, "heading {yaw1} -> {yaw2}");
    r.efforts(80.0, 20.0);

    // The right side faster: back to the left.
    r.drive(20.0, 80.0, 2);
    let (_, _, yaw3) = r.pose();
    eprintln!("right faster: heading {yaw2:.3} -> {yaw3:.3} rad");
    assert!(yaw2 - yaw3 > 0.5, "heading {yaw2} -> {yaw3}");

    // The Mobility Primitive Driver commands the same RA 3.3 driver: its latest effort
    // wins (straight on), Query Skid Steer Effort still reads the skid-steer command.
    r.wrench(60.0, 1);
    let (_, _, yaw4) = r.pose();
    r.wrench(60.0, 1);
    let (_, _, yaw5) = r.pose();
    assert!((yaw5 - yaw4).abs() < 0.01, "heading {yaw4} -> {yaw5}");
    r.efforts(20.0, 80.0);

    // Leaving Ready stops it: the efforts read 0, and sets are refused.
    assert!(r.rig.ask(Standby {}, WAIT).is_empty());
    r.efforts(0.0, 0.0);
    r.rig.net.run_for(Duration::from_secs(2));
    let (n4, e4, _) = r.pose();
    let refused = r.rig.refused();
    r.drive(60.0, 60.0, 1);
    assert!(r.rig.refused() >= refused + 10, "refused outside Ready");
    let (n5, e5, _) = r.pose();
    assert!(
        (n5 - n4).abs() < 0.05 && (e5 - e4).abs() < 0.05,
        "moved from {n4}, {e4} to {n5}, {e5} in Standby"
    );
}

fn engine(power: PowerState) -> PowerPlantConfiguration {
    PowerPlantConfiguration {
        power_plant_id: 1,
        settings: PowerPlantSettings::GasEngine(GasEngineSettings {
            power,
            ..Default::default()
        }),
    }
}

fn set_engine(power: PowerState) -> SetPowerPlantConfiguration {
    SetPowerPlantConfiguration {
        power_plants: vec![engine(power)],
    }
}

impl Rig {
    /// Sends `m`, a command: nothing comes back (taken or refused).
    fn command(&mut self, m: impl Into<Message>) {
        let got = self.rig.ask(m, WAIT);
        assert!(got.is_empty(), "{got:?}");
    }

    fn power(&mut self) -> PowerState {
        let Message::ReportPowerPlantConfiguration(c) =
            self.one(QueryPowerPlantConfiguration::default())
        else {
            panic!("no Report Power Plant Configuration");
        };
        assert_eq!(c.power_plants.len(), 1, "{c:?}");
        let p = &c.power_plants[0];
        assert_eq!(p.power_plant_id, 1);
        let PowerPlantSettings::GasEngine(g) = &p.settings else {
            panic!("{p:?}");
        };
        assert_eq!((g.rpm, g.throttle), (None, None));
        g.power
    }

    /// Sends `messages` in one datagram (the gateway takes them in the same instant,
    /// before any RA 3.3 report), then lets `WAIT` pass.
    fn together(&mut self, messages: Vec<Message>) {
        let to = SimNet::addr(self.rig.node);
        let batch: Vec<As4Message> = messages
            .iter()
            .map(|m| {
                let body = m.body().to_bytes().expect("encodes");
                As4Message::new(m.code().0, self.rig.target, common::as4::ME, body)
            })
            .collect();
        let c = self
            .rig
            .net
            .get_mut::<As4Client>(self.rig.client)
            .expect("client");
        c.send(to, &batch);
        self.rig.net.run_for(WAIT);
        let c = self
            .rig
            .net
            .get_mut::<As4Client>(self.rig.client)
            .expect("client");
        let got = c.take();
        assert!(got.is_empty(), "{got:?}");
    }
}

#[test]
fn the_power_plant_manager_switches_the_ra33_main_propulsion_bit() {
    let mut r = Rig::demo();
    let uris = r.rig.service_uris();
    assert!(
        uris.iter()
            .any(|u| u == "urn:jaus:jss:ugv:PowerPlantManager"),
        "{uris:?}"
    );
    // One power plant, an engine with no limits RA 3.3 could give.
    let Message::ReportPowerPlantCapabilities(c) = r.one(QueryPowerPlantCapabilities::default())
    else {
        panic!("no Report Power Plant Capabilities");
    };
    assert_eq!(c.power_plants.len(), 1, "{c:?}");
    assert_eq!(c.power_plants[0].power_plant_id, 1);
    assert!(matches!(
        c.power_plants[0].limits,
        PowerPlantLimits::GasEngine(_)
    ));
    // Its gauges: RA 3.3's operational data of the same meaning.
    let Message::ReportPowerPlantStatus(s) = r.one(QueryPowerPlantStatus::default()) else {
        panic!("no Report Power Plant Status");
    };
    let PowerPlantCondition::GasEngine(g) = &s.power_plants[0].condition else {
        panic!("{s:?}");
    };
    let near = |v: Option<f64>, want: f64| v.is_some_and(|v| (v - want).abs() < 0.5);
    assert!(near(g.engine_temp, 88.0), "{g:?}");
    assert!(near(g.percent_remaining_fuel, 62.5), "{g:?}");
    assert!(near(g.percent_oil_pressure, 104.0), "{g:?}");
    assert_eq!(g.tachometer, None);
    // Another power plant asked about: no entry.
    let Message::ReportPowerPlantStatus(s) = r.one(QueryPowerPlantStatus {
        power_plant_ids: vec![7],
    }) else {
        panic!("no Report Power Plant Status");
    };
    assert!(s.power_plants.is_empty(), "{s:?}");

    // The engine off before any command (the stock driver reports no propulsion).
    assert_eq!(r.power(), PowerState::Off);
    assert_eq!(r.ra33_bits(), (false, false));

    // Without control: refused.
    let refused = r.rig.refused();
    r.command(set_engine(PowerState::On));
    assert_eq!(r.rig.refused(), refused + 1);
    assert_eq!(r.power(), PowerState::Off);
    assert_eq!(r.ra33_bits(), (false, false));

    // The controller (Standby will do): the parking brake applied, then the engine on
    // and off; the brake bit stays.
    r.rig.take_control();
    r.command(SetParkingBrake {
        parking_brake: 100.0,
    });
    assert_eq!(r.ra33_bits(), (false, true));
    r.command(set_engine(PowerState::On));
    assert_eq!(r.power(), PowerState::On);
    assert_eq!(r.ra33_bits(), (true, true));
    r.command(set_engine(PowerState::Off));
    assert_eq!(r.power(), PowerState::Off);
    assert_eq!(r.ra33_bits(), (false, true));

    // What RA 3.3 cannot do: refused, nothing changes.
    let throttle = SetPowerPlantConfiguration {
        power_plants: vec![PowerPlantConfiguration {
            settings: PowerPlantSettings::GasEngine(GasEngineSettings {
                power: PowerState::On,
                throttle: Some(30.0),
                ..Default::default()
            }),
            ..engine(PowerState::On)
        }],
    };
    let other = SetPowerPlantConfiguration {
        power_plants: vec![PowerPlantConfiguration {
            power_plant_id: 2,
            ..engine(PowerState::On)
        }],
    };
    let refused = r.rig.refused();
    for m in [set_engine(PowerState::Standby), throttle, other] {
        r.command(m);
    }
    assert_eq!(r.rig.refused(), refused + 3);
    assert_eq!(r.power(), PowerState::Off);
    assert_eq!(r.ra33_bits(), (false, true));

    // Brake released and engine on in the same instant, before the driver reports
    // either: neither clobbers the other, in either order.
    r.ready();
    r.together(vec![
        SetParkingBrake { parking_brake: 0.0 }.into(),
        set_engine(PowerState::On).into(),
    ]);
    assert_eq!(r.ra33_bits(), (true, false));
    r.together(vec![
        set_engine(PowerState::Off).into(),
        SetParkingBrake {
            parking_brake: 100.0,
        }
        .into(),
    ]);
    assert_eq!(r.ra33_bits(), (false, true));
    assert_eq!(r.power(), PowerState::Off);
}
