//! AS-4 Manipulator v2.0 pan-tilt services through the gateway, over the pan/tilt mount
//! of the demo vehicle's RA 3.3 Visual Sensor camera (±90° pan, ±30° tilt): the Pan Tilt
//! Specification Service, Joint Position Sensor and Joint Position Driver
//! (`jaus_as4::manipulator::pan_tilt`). An AS-4 client (ours, on SimNet) reads and
//! commands the mount; the checks also read the camera's pose as the RA 3.3 Visual
//! Sensor reports it to the gateway.

use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;
use jaus::net::NodeConfig;
use jaus::Address;
use jaus::JausMessage;
use jaus_as4::gateway::GatewayConfig;
use jaus_as4::manipulator::pan_tilt::pan_tilt_of;
use jaus_as4::manipulator::PanTiltMount;
use jaus_as4::ra33::Ra33Control;
use jaus_as4::{
    ComponentState, Message, QueryCommandedPanTiltJointPositions, QueryPanTiltJointPositions,
    QueryPanTiltSpecifications, QueryStatus, ReleaseControl, Resume, SetPanTiltJointPositions,
};

mod common;
use common::as4::As4Rig;

const VEHICLE: As4Id = As4Id::new(1, 1, 1);
/// The demo camera's mount (`jaus_sim::camera::SimCamera`).
const PAN_LIMIT_DEG: f64 = 90.0;
const TILT_LIMIT_DEG: f64 = 30.0;
/// How close a reached angle must be, degrees.
const TOLERANCE_DEG: f64 = 0.1;

struct Rig(As4Rig);

impl Rig {
    /// The demo vehicle behind a gateway told of its camera's mount.
    fn new() -> Self {
        let t0 = Instant::now();
        let node = jaus_sim::demo::vehicle_node(t0, NodeConfig::default(), 1, 1).unwrap();
        let mut config = GatewayConfig::new(VEHICLE, Address::new(1, 1, 60, 1), 1, "demo vehicle");
        config.pan_tilt = Some(PanTiltMount::new(
            1,
            PAN_LIMIT_DEG.to_radians(),
            TILT_LIMIT_DEG.to_radians(),
        ));
        Rig(As4Rig::configured(
            t0,
            node,
            Vec::new(),
            config,
            Duration::from_secs(3),
        ))
    }

    fn one(&mut self, m: impl Into<Message>) -> Message {
        self.0.one_within(m, Duration::from_millis(500))
    }

    /// Sends a command: no answer comes.
    fn command(&mut self, m: impl Into<Message>) {
        let got = self.0.ask(m, Duration::from_millis(300));
        assert!(got.is_empty(), "a command is not answered: {got:?}");
    }

    fn set(&mut self, pan_deg: f64, tilt_deg: f64) {
        self.command(SetPanTiltJointPositions {
            joint1_position: pan_deg.to_radians(),
            joint2_position: tilt_deg.to_radians(),
        });
    }

    /// The measured pan and tilt (AS-4 Pan Tilt Joint Position Sensor), degrees.
    fn measured(&mut self) -> (f64, f64) {
        match self.one(QueryPanTiltJointPositions {}) {
            Message::ReportPanTiltJointPositions(r) => (
                r.joint1_position.to_degrees(),
                r.joint2_position.to_degrees(),
            ),
            other => panic!("no Report Pan Tilt Joint Positions: {other:?}"),
        }
    }

    fn visual_sensor(&self) -> Address {
        let env = self.0.dual().gateway().node().env();
        env.targets().visual_sensor.expect("the camera found")
    }

    /// The pan and tilt of the latest RA 3.3 Report Camera Pose the gateway holds,
    /// degrees (from its lens axis).
    fn ra33_pose(&self) -> (f64, f64) {
        let vs = self.visual_sensor();
        let env = self.0.dual().gateway().node().env();
        match env.latest(vs, jaus::messages::ReportCameraPose::CODE) {
            Some((_, jaus::messages::Message::ReportCameraPose(p))) => {
                let z = [
                    p.z_camera_axis_direction_cosine_x.expect("z·x"),
                    p.z_camera_axis_direction_cosine_y.expect("z·y"),
                    p.z_camera_axis_direction_cosine_z.expect("z·z"),
                ];
                let (pan, tilt) = pan_tilt_of(z);
                (pan.to_degrees(), tilt.to_degrees())
            }
            other => panic!("no RA 3.3 Report Camera Pose: {other:?}"),
        }
    }

    fn ra33_control(&self) -> Ra33Control {
        let vs = self.visual_sensor();
        self.0.dual().gateway().node().env().control_of(vs)
    }
}

fn assert_near(got: (f64, f64), want: (f64, f64), what: &str) {
    let err = ((got.0 - want.0).abs(), (got.1 - want.1).abs());
    assert!(
        err.0 < TOLERANCE_DEG && err.1 < TOLERANCE_DEG,
        "{what}: {got:?}° for {want:?}° (errors {err:?}°)"
    );
}

#[test]
fn the_gateway_offers_the_pan_tilt_position_services_only() {
    let mut r = Rig::new();
    let uris = r.0.service_uris();
    for name in [
        "PanTiltSpecificationService",
        "PanTiltJointPositionSensor",
        "PanTiltJointPositionDriver",
    ] {
        let uri = format!("urn:jaus:jss:manipulator:{name}");
        assert!(uris.contains(&uri), "{uri} not in {uris:?}");
    }
    // The stock camera's mount takes no rates; RA 3.3 gives no speed limits.
    for name in [
        "PanTiltJointVelocityDriver",
        "PanTiltJointVelocitySensor",
        "PanTiltMotionProfileService",
    ] {
        let uri = format!("urn:jaus:jss:manipulator:{name}");
        assert!(!uris.contains(&uri), "{uri} offered");
    }
}

#[test]
fn without_a_mount_configured_no_pan_tilt_service_is_offered() {
    let mut r = As4Rig::demo_vehicle();
    let uris = r.service_uris();
    assert!(
        !uris.iter().any(|u| u.contains(":PanTilt")),
        "pan-tilt offered without its limits: {uris:?}"
    );
}

#[test]
fn the_specifications_give_the_mount_limits_and_the_camera_origin() {
    let mut r = Rig::new();
    let Message::ReportPanTiltSpecifications(s) = r.one(QueryPanTiltSpecifications {
        presence_vector: 0x7f,
    }) else {
        panic!("no Report Pan Tilt Specifications");
    };
    let deg = |v: f64| v.to_degrees();
    assert!(
        (deg(s.joint1_min_value) + PAN_LIMIT_DEG).abs() < 1e-3,
        "{s:?}"
    );
    assert!(
        (deg(s.joint1_max_value) - PAN_LIMIT_DEG).abs() < 1e-3,
        "{s:?}"
    );
    assert!(
        (deg(s.joint2_min_value) + TILT_LIMIT_DEG).abs() < 1e-3,
        "{s:?}"
    );
    assert!(
        (deg(s.joint2_max_value) - TILT_LIMIT_DEG).abs() < 1e-3,
        "{s:?}"
    );
    // The camera 0.5 m ahead and 1 m up (z down); the mount's orientation is not known.
    let o = [s.origin_x, s.origin_y, s.origin_z].map(|v| v.expect("origin asked"));
    for (got, want) in o.iter().zip([0.5, 0.0, -1.0]) {
        assert!((got - want).abs() < 1e-3, "origin {o:?}");
    }
    assert_eq!(
        (
            s.quaternion_d,
            s.quaternion_a,
            s.quaternion_b,
            s.quaternion_c
        ),
        (None, None, None, None)
    );
    // Only what is asked.
    let Message::ReportPanTiltSpecifications(s) =
        r.one(QueryPanTiltSpecifications { presence_vector: 0 })
    else {
        panic!("no Report Pan Tilt Specifications");
    };
    assert_eq!((s.origin_x, s.origin_y, s.origin_z), (None, None, None));
}

#[test]
fn the_controlling_client_turns_the_camera_and_the_sensor_reads_it_back() {
    let mut r = Rig::new();
    assert_near(r.measured(), (0.0, 0.0), "at rest");

    // Without control: refused, nothing moves, no RA 3.3 control asked for.
    let refused = r.0.refused();
    r.set(30.0, -10.0);
    r.0.net.run_for(Duration::from_millis(500));
    assert_eq!(
        r.0.refused(),
        refused + 1,
        "a Set without control is refused"
    );
    assert_near(r.measured(), (0.0, 0.0), "without control");
    assert_near(r.ra33_pose(), (0.0, 0.0), "RA 3.3 pose without control");
    assert_eq!(r.ra33_control(), Ra33Control::None);

    // Control, Ready: the mount turns.
    r.0.take_control();
    r.command(Resume {});
    let Message::ReportStatus(s) = r.one(QueryStatus {}) else {
        panic!("no Report Status");
    };
    assert_eq!(s.status, ComponentState::Ready);
    r.set(30.0, -10.0);
    r.0.net.run_for(Duration::from_millis(500));
    assert_eq!(r.ra33_control(), Ra33Control::Granted);
    let got = r.measured();
    assert_near(got, (30.0, -10.0), "AS-4 sensor");
    let ra33 = r.ra33_pose();
    assert_near(ra33, (30.0, -10.0), "RA 3.3 Report Camera Pose");
    eprintln!(
        "reached: AS-4 {got:?}°, RA 3.3 {ra33:?}°, errors {:.5}° / {:.5}°",
        got.0 - 30.0,
        got.1 + 10.0
    );
    let Message::ReportCommandedPanTiltJointPositions(c) =
        r.one(QueryCommandedPanTiltJointPositions {})
    else {
        panic!("no Report Commanded Pan Tilt Joint Positions");
    };
    assert_near(
        (
            c.joint1_position.to_degrees(),
            c.joint2_position.to_degrees(),
        ),
        (30.0, -10.0),
        "commanded",
    );

    // Beyond the limits: refused, the mount stays.
    let refused = r.0.refused();
    r.set(100.0, 0.0);
    r.set(0.0, -35.0);
    r.0.net.run_for(Duration::from_millis(500));
    assert_eq!(
        r.0.refused(),
        refused + 2,
        "targets beyond the limits refused"
    );
    assert_near(r.measured(), (30.0, -10.0), "after the refused targets");

    // The limits themselves are taken.
    r.set(-90.0, 30.0);
    r.0.net.run_for(Duration::from_millis(500));
    assert_near(r.measured(), (-90.0, 30.0), "at the limits");
    assert_near(r.ra33_pose(), (-90.0, 30.0), "RA 3.3 pose at the limits");

    // Control ends: RA 3.3 control of the Visual Sensor is given back, a Set refused.
    r.0.ask(ReleaseControl {}, Duration::from_millis(300));
    r.0.net.run_for(Duration::from_millis(500));
    assert_eq!(r.ra33_control(), Ra33Control::None);
    let refused = r.0.refused();
    r.set(0.0, 0.0);
    r.0.net.run_for(Duration::from_millis(500));
    assert_eq!(
        r.0.refused(),
        refused + 1,
        "a Set after control ended is refused"
    );
    assert_near(r.measured(), (-90.0, 30.0), "after control ended");
    assert_near(
        r.ra33_pose(),
        (-90.0, 30.0),
        "RA 3.3 pose after control ended",
    );
}
