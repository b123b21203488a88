//! AS-4 UGV services through the gateway (`jaus_as4::ugv`): an AS-4 client sets the
//! demo vehicle's parking brake through the Parking Brake Driver the gateway presents
//! over the RA 3.3 Primitive Driver's discrete devices, and reads it back from the RA
//! 3.3 driver's report; only the controlling client may, and only while Ready but to
//! apply it harder. The Platform Specifications service is offered over a Primitive
//! Driver that answers Query Platform Specifications. The Odometry service reads the
//! demo vehicle's odometer (RA 3.3 Report Platform Operational Data) as it drives, and
//! keeps trip odometers the controlling client resets. The Annunciator sounds the demo
//! vehicle's RA 3.3 horn bit for the controlling client, a siren refused, the parking
//! brake bit of the same RA 3.3 message left as it was by the horn and the reverse, even
//! when both commands come together.

use std::time::{Duration, Instant};

use jaus::component::Config;
use jaus::components::primitive_driver as pd;
use jaus::messages as ra;
use jaus::net::as5669a::{As4Client, As4Id, As4Message};
use jaus::net::Node;
use jaus::stock::drivers::{PrimitiveConfig, StockPrimitiveDriver};
use jaus::JausMessage;
use jaus_as4::{
    AnnunciatorState, ComponentState, Message, Odometer, QueryAnnunciatorConfiguration,
    QueryAnnunciatorState, QueryOdometry, QueryParkingBrake, QueryPlatformSpecifications,
    QueryStatus, ReleaseControl, ReportParkingBrake, ResetOdometry, Resume, SetAnnunciatorState,
    SetParkingBrake, SetWrenchEffort, Standby, SteeringSpecifics, TripOdometer,
};
use jaus_sim::network::SimNet;

mod common;
use common::as4::As4Rig;

const VEHICLE: As4Id = As4Id::new(1, 1, 1);
const WAIT: Duration = Duration::from_millis(500);

struct Rig(As4Rig);

impl Rig {
    /// The demo vehicle behind the gateway.
    fn demo() -> Self {
        Rig(As4Rig::demo_vehicle())
    }

    fn over(t0: Instant, node: Node) -> Self {
        Rig(As4Rig::new(
            t0,
            node,
            VEHICLE,
            "demo vehicle",
            Duration::from_secs(3),
        ))
    }

    fn one(&mut self, m: impl Into<Message>) -> Message {
        self.0.one_within(m, WAIT)
    }

    fn uris(&mut self) -> Vec<String> {
        self.0.service_uris()
    }

    fn take_control(&mut self) {
        self.0.take_control();
    }

    fn status(&mut self) -> ComponentState {
        let Message::ReportStatus(s) = self.one(QueryStatus {}) else {
            panic!("no Report Status");
        };
        s.status
    }

    /// Sends Set Parking Brake; what came back (nothing: it was taken or refused).
    fn set(&mut self, level: f64) {
        let got = self.0.ask(
            SetParkingBrake {
                parking_brake: level,
            },
            WAIT,
        );
        assert!(got.is_empty(), "{got:?}");
    }

    fn brake(&mut self) -> ReportParkingBrake {
        match self.one(QueryParkingBrake {}) {
            Message::ReportParkingBrake(r) => r,
            other => panic!("{other:?}"),
        }
    }

    /// The parking brake bit of the RA 3.3 Primitive Driver's latest Report Discrete
    /// Devices, as the gateway holds it.
    fn ra33_bit(&self) -> bool {
        self.ra33_bits().0
    }

    /// The parking brake and horn bits of the RA 3.3 Primitive Driver's latest Report
    /// Discrete Devices, as the gateway holds it.
    fn ra33_bits(&self) -> (bool, bool) {
        let env = self.0.dual().gateway().node().env();
        let pd = env.targets().primitive_driver.expect("the driver found");
        match env.latest(pd, ra::ReportDiscreteDevices::CODE) {
            // Without the field: never set.
            Some((_, ra::Message::ReportDiscreteDevices(r))) => r
                .parking_brake_and_horn
                .map_or((false, false), |d| (d.parking_brake, d.horn)),
            other => panic!("no RA 3.3 discrete devices: {other:?}"),
        }
    }
}

#[test]
fn the_controlling_client_sets_the_parking_brake_of_the_ra33_driver() {
    let mut r = Rig::demo();
    let uris = r.uris();
    assert!(
        uris.iter()
            .any(|u| u == "urn:jaus:jss:ugv:ParkingBrakeDriver"),
        "{uris:?}"
    );
    // The demo vehicle's stock RA 3.3 Primitive Driver answers Query Platform
    // Specifications with what the simulation's model says.
    assert!(
        uris.iter()
            .any(|u| u == "urn:jaus:jss:ugv:PlatformSpecifications"),
        "{uris:?}"
    );
    let Message::ReportPlatformSpecifications(s) = r.one(QueryPlatformSpecifications {}) else {
        panic!("no Report Platform Specifications");
    };
    assert_eq!(s.platform_spec.mobility_platform_name, "jaus sim");
    let top = s
        .platform_inertial
        .maximum_forward_speed
        .expect("top speed");
    assert!((top - 2.0).abs() < 0.01, "{top}");
    let released = r.brake();
    assert_eq!(released.actual_parking_brake, 0.0);
    assert!(!r.ra33_bit());

    // Without control: refused, nothing changes.
    r.set(100.0);
    assert_eq!(r.brake().actual_parking_brake, 0.0);
    assert!(!r.ra33_bit());

    // The controller, Ready: applied, read back from the RA 3.3 report.
    r.take_control();
    r.0.ask(Resume {}, WAIT);
    assert_eq!(r.status(), ComponentState::Ready);
    r.set(100.0);
    let b = r.brake();
    assert_eq!(
        (b.commanded_parking_brake, b.actual_parking_brake),
        (100.0, 100.0)
    );
    assert!(r.ra33_bit());
    // Released again.
    r.set(0.0);
    let b = r.brake();
    assert_eq!(
        (b.commanded_parking_brake, b.actual_parking_brake),
        (0.0, 0.0)
    );
    assert!(!r.ra33_bit());
    // A partial level applies the RA 3.3 brake (on or off only).
    r.set(30.0);
    let b = r.brake();
    assert!((b.commanded_parking_brake - 30.0).abs() < 0.5, "{b:?}");
    assert_eq!(b.actual_parking_brake, 100.0);
    r.set(0.0);
    assert_eq!(r.brake().actual_parking_brake, 0.0);
}

#[test]
fn leaving_ready_applies_the_brake_and_outside_ready_it_is_only_applied_harder() {
    let mut r = Rig::demo();
    r.take_control();
    r.0.ask(Resume {}, WAIT);
    assert_eq!(r.status(), ComponentState::Ready);
    assert_eq!(r.brake().actual_parking_brake, 0.0);
    // Standby: the exit action of Ready applies the brake.
    r.0.ask(Standby {}, WAIT);
    assert_eq!(r.status(), ComponentState::Standby);
    assert_eq!(r.brake().actual_parking_brake, 100.0);
    assert!(r.ra33_bit());
    // Controlled, not Ready: releasing is refused (not harder than applied).
    r.set(0.0);
    assert_eq!(r.brake().actual_parking_brake, 100.0);
    assert!(r.ra33_bit());
}

/// The RA 3.3 specifications a vendor's platform gives its Primitive Driver.
fn ra33_specifications() -> ra::ReportPlatformSpecifications {
    ra::ReportPlatformSpecifications {
        platform_name: Some("demo rover".into()),
        front: Some(0.6),
        back: Some(0.4),
        right: Some(0.35),
        left: Some(0.35),
        bottom: Some(0.1),
        top: Some(0.5),
        x_cg: Some(0.1),
        y_cg: Some(0.0),
        z_cg: Some(0.2),
        turning_radius: Some(0.0),
        wheel_base: Some(0.55),
        track_width: Some(0.6),
        pitch_over: Some(0.7),
        roll_over: Some(0.6),
        maximum_velocity_x: Some(2.0),
        maximum_yaw_rate: Some(1.5),
        ..Default::default()
    }
}

#[test]
fn platform_specifications_are_those_of_the_ra33_primitive_driver() {
    let t0 = Instant::now();
    let at = jaus::Address::new(1, 1, jaus::components::primitive_driver::ID, 1);
    let (mut node, vehicle) = As4Rig::demo_vehicle_node(t0, Some(at));
    let driver = StockPrimitiveDriver::new(
        vehicle,
        PrimitiveConfig {
            specifications: Some(ra33_specifications()),
            ..PrimitiveConfig::default()
        },
    );
    node.add_boxed(Box::new(pd::component(at, driver, Config::default(), t0)))
        .unwrap();
    let mut r = Rig::over(t0, node);
    let uris = r.uris();
    for want in [
        "urn:jaus:jss:ugv:PlatformSpecifications",
        "urn:jaus:jss:ugv:ParkingBrakeDriver",
    ] {
        assert_eq!(
            uris.iter().filter(|u| *u == want).count(),
            1,
            "{want} once in {uris:?}"
        );
    }
    let Message::ReportPlatformSpecifications(s) = r.one(QueryPlatformSpecifications {}) else {
        panic!("no Report Platform Specifications");
    };
    let want = ra33_specifications();
    let close = |a: Option<f64>, b: Option<f64>| {
        let (a, b) = (a.expect("present"), b.expect("present"));
        assert!((a - b).abs() < 0.01, "{a} vs {b}");
    };
    let g = &s.platform_spec;
    assert_eq!(g.mobility_platform_name, "demo rover");
    close(g.front, want.front);
    close(g.back, want.back);
    close(g.right, want.right);
    close(g.left, want.left);
    close(g.bottom, want.bottom);
    close(g.top, want.top);
    close(g.cg_x, want.x_cg);
    close(g.cg_y, want.y_cg);
    close(g.cg_z, want.z_cg);
    close(g.wheel_base, want.wheel_base);
    close(g.static_pitch_over, want.pitch_over);
    close(g.static_roll_over, want.roll_over);
    // RA 3.3 has no weight, no approach, departure or breakover angle.
    assert_eq!(g.vehicle_weight, None);
    assert_eq!(g.approach_angle, None);
    let p = &s.platform_inertial;
    close(p.maximum_forward_speed, want.maximum_velocity_x);
    close(p.maximum_rotational_speed, want.maximum_yaw_rate);
    assert_eq!(p.maximum_reverse_speed, None);
    assert_eq!(p.maximum_forward_acceleration, None);
    // A turning radius of 0: skid steer, the track width its track separation.
    let SteeringSpecifics::SkidSteer(k) = &s.platform_specifics else {
        panic!("{:?}", s.platform_specifics);
    };
    close(k.track_separation, want.track_width);
    assert_eq!(k.drive_wheel_radius, None);
}

impl Rig {
    fn odometry(&mut self, odometer: Odometer) -> u32 {
        let Message::ReportOdometry(r) = self.one(QueryOdometry { odometer }) else {
            panic!("no Report Odometry");
        };
        assert_eq!(r.odometer, odometer);
        r.odometry
    }

    /// Drives forward at 60 % effort for `secs` seconds, the effort refreshed every
    /// 100 ms (the driver's command timeout brakes a stale one), then stops.
    fn drive(&mut self, secs: u32) {
        let effort = |x: f64| SetWrenchEffort {
            propulsive_linear_effort_x: Some(x),
            ..Default::default()
        };
        for _ in 0..secs * 10 {
            self.0.ask(effort(60.0), Duration::from_millis(100));
        }
        self.0.ask(effort(0.0), Duration::from_secs(2));
    }
}

#[test]
fn the_odometry_service_reads_the_ra33_odometer_and_keeps_trips() {
    let mut r = Rig::demo();
    let uris = r.uris();
    assert!(
        uris.iter().any(|u| u == "urn:jaus:jss:ugv:OdometryService"),
        "{uris:?}"
    );
    let start = r.odometry(Odometer::Platform);
    assert_eq!(r.odometry(Odometer::TripA), 0);

    r.take_control();
    assert!(r.0.ask(Resume {}, WAIT).is_empty());
    r.drive(6);
    let first = r.odometry(Odometer::Platform) - start;
    assert!(first >= 2, "the odometer moved {first} m in 6 s at 60 %");
    assert_eq!(r.odometry(Odometer::TripA), first);
    assert_eq!(r.odometry(Odometer::TripB), first);

    // Resetting a trip needs control: released, the reset is refused.
    r.0.ask(ReleaseControl {}, WAIT);
    r.0.ask(reset_a(), WAIT);
    assert_eq!(r.odometry(Odometer::TripA), first);
    // The controller resets trip A: it counts the second leg alone; trip B both.
    r.take_control();
    r.0.ask(reset_a(), WAIT);
    assert_eq!(r.odometry(Odometer::TripA), 0);
    assert!(r.0.ask(Resume {}, WAIT).is_empty());
    r.drive(4);
    let total = r.odometry(Odometer::Platform) - start;
    let second = r.odometry(Odometer::TripA);
    assert!(second >= 1 && second < total, "leg {second} m of {total} m");
    assert_eq!(r.odometry(Odometer::TripB), total);
    eprintln!("odometer: {first} m, then {second} m more ({total} m)");
}

fn reset_a() -> ResetOdometry {
    ResetOdometry {
        odometer: TripOdometer::TripA,
    }
}

impl Rig {
    fn annunciator(&mut self) -> AnnunciatorState {
        match self.one(QueryAnnunciatorState {}) {
            Message::ReportAnnunciatorState(r) => r.annunciator,
            other => panic!("{other:?}"),
        }
    }

    /// Sends Set Annunciator State; nothing comes back (taken or refused).
    fn sound(&mut self, annunciator: AnnunciatorState) {
        let got = self.0.ask(SetAnnunciatorState { annunciator }, WAIT);
        assert!(got.is_empty(), "{got:?}");
    }

    fn refused(&self) -> u64 {
        self.0.refused()
    }

    /// Sends `messages` in one datagram (the gateway takes them in the same instant,
    /// before any RA 3.3 report), then lets `WAIT` pass.
    fn together(&mut self, messages: Vec<Message>) {
        let to = SimNet::addr(self.0.node);
        let batch: Vec<As4Message> = messages
            .iter()
            .map(|m| {
                let body = m.body().to_bytes().expect("encodes");
                As4Message::new(m.code().0, self.0.target, common::as4::ME, body)
            })
            .collect();
        let c = self
            .0
            .net
            .get_mut::<As4Client>(self.0.client)
            .expect("client");
        c.send(to, &batch);
        self.0.net.run_for(WAIT);
        let c = self
            .0
            .net
            .get_mut::<As4Client>(self.0.client)
            .expect("client");
        let got = c.take();
        assert!(got.is_empty(), "{got:?}");
    }
}

fn horn(level: u8) -> AnnunciatorState {
    AnnunciatorState {
        horn: level,
        ..Default::default()
    }
}

#[test]
fn the_annunciator_sounds_the_ra33_horn_and_leaves_the_parking_brake_alone() {
    let mut r = Rig::demo();
    let uris = r.uris();
    assert!(
        uris.iter()
            .any(|u| u == "urn:jaus:jss:ugv:AnnunciatorService"),
        "{uris:?}"
    );
    // The horn is the one annunciator.
    let Message::ReportAnnunciatorConfiguration(c) = r.one(QueryAnnunciatorConfiguration {}) else {
        panic!("no Report Annunciator Configuration");
    };
    assert!(c.supported.horn);
    assert!(!(c.supported.siren || c.supported.backup));
    assert!(!(c.supported.variable1 || c.supported.variable2));
    assert_eq!(r.annunciator(), horn(0));
    assert_eq!(r.ra33_bits(), (false, false));

    // Without control: refused, silent.
    let refused = r.refused();
    r.sound(horn(15));
    assert_eq!(r.refused(), refused + 1);
    assert_eq!(r.annunciator(), horn(0));
    assert_eq!(r.ra33_bits(), (false, false));

    // The controller (Standby will do): any level sounds RA 3.3's horn, read 15.
    r.take_control();
    r.sound(horn(4));
    assert_eq!(r.annunciator(), horn(15));
    assert_eq!(r.ra33_bits(), (false, true));
    // A siren RA 3.3 does not have: refused, the horn as it was.
    let refused = r.refused();
    r.sound(AnnunciatorState {
        siren: 8,
        ..horn(0)
    });
    assert_eq!(r.refused(), refused + 1);
    assert_eq!(r.annunciator(), horn(15));
    assert_eq!(r.ra33_bits(), (false, true));

    // The parking brake keeps the horn, the horn keeps the parking brake.
    r.0.ask(Resume {}, WAIT);
    assert_eq!(r.status(), ComponentState::Ready);
    r.set(100.0);
    assert_eq!(r.ra33_bits(), (true, true));
    assert_eq!(r.annunciator(), horn(15));
    r.sound(horn(0));
    assert_eq!(r.ra33_bits(), (true, false));
    assert_eq!(r.brake().actual_parking_brake, 100.0);
    assert_eq!(r.annunciator(), horn(0));

    // Both in the same instant, before the driver reports either: neither clobbers the
    // other, in either order.
    r.together(vec![
        SetParkingBrake { parking_brake: 0.0 }.into(),
        SetAnnunciatorState {
            annunciator: horn(9),
        }
        .into(),
    ]);
    assert_eq!(r.ra33_bits(), (false, true));
    r.together(vec![
        SetAnnunciatorState {
            annunciator: horn(0),
        }
        .into(),
        SetParkingBrake {
            parking_brake: 100.0,
        }
        .into(),
    ]);
    assert_eq!(r.ra33_bits(), (true, false));
    assert_eq!(r.brake().actual_parking_brake, 100.0);
    assert_eq!(r.annunciator(), horn(0));
}
