//! Scaled values out of range: an encode error naming the field, the value and the
//! limits, never silent clamping; clamping is an explicit call (`clamp_to_range`,
//! `clamped`) that reaches every scaled field; received values are never clamped.

use jaus::codec::{Decode, Encode, EncodeError};
use jaus::messages::{
    CreateVksObjects, Message, ReportGlobalPose, SetJointPositions, VksObject, VksObjectType,
    VksPoint,
};
use jaus::{JausMessage, JausRecord, JausUnion};

fn pose(latitude: f64) -> ReportGlobalPose {
    ReportGlobalPose {
        latitude: Some(latitude),
        longitude: Some(-82.3),
        ..Default::default()
    }
}

#[test]
fn latitude_129_5_is_an_error_naming_field_value_and_range() {
    let e = pose(129.5).to_bytes().unwrap_err();
    assert_eq!(
        e.to_string(),
        "ReportGlobalPose.latitude: 129.5 outside [-90, 90] deg"
    );
    let EncodeError::OutOfRange {
        scaled,
        value,
        message,
    } = e
    else {
        panic!("{e:?}");
    };
    assert_eq!(
        (scaled.field, scaled.lo, scaled.hi, scaled.unit),
        ("ReportGlobalPose.latitude", -90.0, 90.0, "deg")
    );
    assert_eq!(value, 129.5);
    assert_eq!(message, Some("ReportGlobalPose"));
    // Through the message enum and into a packet, the same error.
    let m = Message::from(pose(-129.5));
    assert_eq!(
        m.to_bytes().unwrap_err().to_string(),
        "ReportGlobalPose.latitude: -129.5 outside [-90, 90] deg"
    );
}

#[test]
fn the_clamp_api_gives_the_limit() {
    let clamped = pose(129.5).clamped();
    assert_eq!(clamped.latitude, Some(90.0));
    assert_eq!(clamped.longitude, Some(-82.3));
    assert_eq!(clamped.to_bytes().unwrap(), pose(90.0).to_bytes().unwrap());
    let mut p = pose(-1e9);
    p.elevation = Some(20_000.0); // in range: [-10000, 35000]
    p.position_rms = Some(250.0); // [0, 100]
    p.clamp_to_range();
    assert_eq!(
        (p.latitude, p.elevation, p.position_rms),
        (Some(-90.0), Some(20_000.0), Some(100.0))
    );
    // The message enum clamps the message it holds.
    let m = Message::from(pose(129.5)).clamped();
    assert_eq!(m, Message::from(pose(90.0)));
}

#[test]
fn nan_and_infinities_are_errors_and_nan_is_not_clamped() {
    let e = pose(f64::NAN).to_bytes().unwrap_err();
    assert!(matches!(e, EncodeError::OutOfRange { value, .. } if value.is_nan()));
    assert_eq!(
        e.to_string(),
        "ReportGlobalPose.latitude: NaN is not in [-90, 90] deg"
    );
    assert_eq!(
        pose(f64::INFINITY).to_bytes().unwrap_err().to_string(),
        "ReportGlobalPose.latitude: inf outside [-90, 90] deg"
    );
    assert_eq!(pose(f64::NEG_INFINITY).clamped().latitude, Some(-90.0));
    let p = pose(f64::NAN).clamped();
    assert!(p.latitude.unwrap().is_nan());
    assert!(p.to_bytes().is_err());
}

#[test]
fn a_field_of_a_record_inside_a_message_names_the_message() {
    let object = |latitude: f64| VksObject {
        object_type: VksObjectType::Point,
        buffer: None,
        feature_classes: vec![],
        points: vec![
            VksPoint {
                latitude: 29.6,
                longitude: -82.3,
            },
            VksPoint {
                latitude,
                longitude: -82.3,
            },
        ],
    };
    let m = CreateVksObjects {
        buffered: false,
        message_properties: 0,
        request_id: 1,
        objects: vec![object(10.0), object(95.0)],
    };
    assert_eq!(
        m.to_bytes().unwrap_err().to_string(),
        "CreateVksObjects: VksPoint.latitude: 95 outside [-90, 90] deg"
    );
    let m = m.clamped();
    assert_eq!(m.objects[1].points[1].latitude, 90.0);
    assert_eq!(m.objects[0].points[1].latitude, 10.0);
    assert!(m.to_bytes().is_ok());

    // Lists of scaled values: each element.
    let j = SetJointPositions {
        joint_position: vec![0.5, 30.0, -30.0],
    };
    let e = j.to_bytes().unwrap_err();
    assert!(
        e.to_string()
            .starts_with("SetJointPositions.joint_position: 30 outside [-25.13"),
        "{e}"
    );
    let lim = 8.0 * std::f64::consts::PI;
    assert_eq!(j.clamped().joint_position, [0.5, lim, -lim]);
}

#[test]
fn values_within_one_count_of_a_limit_encode_as_the_limit() {
    // Latitude: one count is 180 / (2^32 - 2) degrees.
    let step = jaus::codec::scale_step::<i32>(-90.0, 90.0);
    for v in [90.0 + 1e-12, 90.0 + step, 90.0 + 1.4 * step] {
        assert_eq!(pose(v).to_bytes().unwrap(), pose(90.0).to_bytes().unwrap());
    }
    assert!(pose(90.0 + 1.6 * step).to_bytes().is_err());
    assert!(pose(-90.0 - 1.6 * step).to_bytes().is_err());
}

#[test]
fn received_values_are_never_clamped_and_the_spare_integer_re_encodes() {
    // i32::MIN is one count below -90°: it decodes as sent, below the limit...
    let mut body = vec![0x01, 0x00];
    body.extend_from_slice(&i32::MIN.to_le_bytes());
    let p = ReportGlobalPose::decode_body(&body).unwrap();
    let lat = p.latitude.unwrap();
    assert!(lat < -90.0, "{lat}");
    assert!((lat + 90.0 + jaus::codec::scale_step::<i32>(-90.0, 90.0)).abs() < 1e-12);
    // ... and re-encodes as the limit, -(2^31 - 1).
    let again = p.to_bytes().unwrap();
    assert_eq!(again[2..], (-i32::MAX).to_le_bytes());
    assert_eq!(
        ReportGlobalPose::from_bytes(&again).unwrap().latitude,
        Some(-90.0)
    );
}

// Clamping by hand-derived types: through options, lists, records and unions.

#[derive(Debug, Clone, PartialEq, JausRecord)]
struct Joint {
    #[jaus(scaled(i16, -3.0, 3.0), unit = "rad")]
    angle: f64,
    id: u8,
}

#[derive(Debug, Clone, PartialEq, JausUnion)]
#[jaus(tag = u8)]
enum Limit {
    #[jaus(tag = 0)]
    None,
    #[jaus(tag = 1)]
    Joint(Joint),
    #[jaus(tag = 2)]
    Raw(u16),
}

#[derive(Debug, Clone, PartialEq, JausMessage)]
#[jaus(code = 0xD710, presence = u8)]
struct Arm {
    #[jaus(scaled(u8, 0.0, 100.0), unit = "%")]
    grip: f64,
    #[jaus(bit = 0, scaled(u16, 0.0, 10.0))]
    reach: Option<f64>,
    #[jaus(bit = 1, count = u8)]
    joints: Option<Vec<Joint>>,
    #[jaus(count = u8, scaled(i16, -1.0, 1.0))]
    gains: Vec<f64>,
    limit: Limit,
}

#[test]
fn hand_derived_types_clamp_every_scaled_field() {
    let joint = |angle: f64| Joint { angle, id: 1 };
    let arm = Arm {
        grip: 150.0,
        reach: Some(-2.0),
        joints: Some(vec![joint(1.0), joint(-7.0)]),
        gains: vec![2.0, 0.5, -2.0],
        limit: Limit::Joint(joint(4.0)),
    };
    let e = arm.to_bytes().unwrap_err();
    assert_eq!(e.to_string(), "Arm.grip: 150 outside [0, 100] %");
    let Arm {
        grip,
        reach,
        joints,
        gains,
        limit,
    } = arm.clamped();
    assert_eq!((grip, reach), (100.0, Some(0.0)));
    assert_eq!(joints, Some(vec![joint(1.0), joint(-3.0)]));
    assert_eq!(gains, [1.0, 0.5, -1.0]);
    assert_eq!(limit, Limit::Joint(joint(3.0)));

    // An error in a record names the message it is in.
    let arm = Arm {
        grip: 50.0,
        reach: None,
        joints: None,
        gains: vec![],
        limit: Limit::Joint(joint(-4.0)),
    };
    assert_eq!(
        arm.to_bytes().unwrap_err().to_string(),
        "Arm: Joint.angle: -4 outside [-3, 3] rad"
    );
    let mut raw = Limit::Raw(7);
    raw.clamp_to_range();
    assert_eq!(raw, Limit::Raw(7));
    let mut none = Limit::None;
    none.clamp_to_range();
    assert_eq!(none, Limit::None);
}

// The stock sensors report a reading beyond what the message can carry at the limit.

use jaus::component::local::{LocalBus, Probe};
use jaus::component::Config;
use jaus::components::{global_pose_sensor, velocity_state_sensor};
use jaus::messages::{QueryGlobalPose, QueryVelocityState};
use jaus::stock::hardware::{GlobalPose, GlobalPoseSource, VelocitySource, VelocityState};
use jaus::stock::nalgebra::{UnitQuaternion, Vector3};
use jaus::stock::sensors::{StockGlobalPoseSensor, StockVelocityStateSensor};
use jaus::Address;
use std::time::{Duration, Instant};

struct FastPlane;

impl GlobalPoseSource for FastPlane {
    fn global_pose(&mut self, _now: Instant) -> Option<GlobalPose> {
        Some(GlobalPose {
            latitude: 90.0 + 1e-7, // noise past the pole
            longitude: 10.0,
            elevation: 40_000.0, // above the 35,000 m of the field
            attitude: UnitQuaternion::identity(),
            position_rms: 250.0, // above 100 m
        })
    }
}

impl VelocitySource for FastPlane {
    fn velocity(&mut self, _now: Instant) -> Option<VelocityState> {
        Some(VelocityState {
            linear: Vector3::new(70.0, 0.0, 0.0), // above 65.534 m/s
            angular: Vector3::zeros(),
        })
    }
}

#[test]
fn sensor_cores_report_readings_beyond_the_message_at_its_limits() {
    const GPS: Address = Address::new(1, 1, 38, 1);
    const VSS: Address = Address::new(1, 1, 42, 1);
    const OCU: Address = Address::new(1, 2, 40, 1);
    let t0 = Instant::now();
    let mut bus = LocalBus::new(t0);
    let cfg = Config::default();
    bus.add(global_pose_sensor::component(
        GPS,
        StockGlobalPoseSensor(FastPlane),
        cfg.clone(),
        t0,
    ));
    bus.add(velocity_state_sensor::component(
        VSS,
        StockVelocityStateSensor(FastPlane),
        cfg,
        t0,
    ));
    bus.add(Probe::new(OCU));
    bus.send(
        OCU,
        GPS,
        QueryGlobalPose {
            presence_vector: 0x0F,
        },
    );
    bus.send(
        OCU,
        VSS,
        QueryVelocityState {
            presence_vector: 0x01,
        },
    );
    bus.run_for(Duration::from_millis(50));
    assert_eq!(bus.stats().encode_errors, 0);
    let probe = bus.get::<Probe>(OCU).unwrap();
    let pose = probe
        .messages()
        .find_map(|m| match m {
            Message::ReportGlobalPose(p) => Some(p.clone()),
            _ => None,
        })
        .expect("a pose report");
    assert_eq!(
        (pose.latitude, pose.elevation, pose.position_rms),
        (Some(90.0), Some(35_000.0), Some(100.0))
    );
    let v = probe
        .messages()
        .find_map(|m| match m {
            Message::ReportVelocityState(v) => v.velocity_x,
            _ => None,
        })
        .expect("a velocity report");
    assert!((v - 65.534).abs() < 1e-3, "{v}");
}
