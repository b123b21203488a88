//! Environment sensors over the simulated vehicle (issue 14, in part): the Range Sensor
//! answering Query Relative Object Position from a simulated scanner, the same scanner
//! feeding the Reflexive Driver, which stops the vehicle before an obstacle that no map
//! holds, and the Visual Sensor's camera messages and images.

use std::time::{Duration, Instant};

use jaus::component::local::{LocalBus, Probe};
use jaus::component::Config;
use jaus::components::{
    local_pose_sensor, local_vector_driver, primitive_driver, range_sensor, reflexive_driver,
    velocity_state_sensor, visual_sensor,
};
use jaus::messages::*;
use jaus::stock::drivers::{
    PrimitiveConfig, ReflexiveConfig, StockLocalVectorDriver, StockPrimitiveDriver,
    StockReflexiveDriver,
};
use jaus::stock::environment::camera::{StockVisualSensor, VisualConfig};
use jaus::stock::environment::range::{RangeConfig, ScanObstacles, StockRangeSensor};
use jaus::stock::motion::DriverConfig;
use jaus::stock::nalgebra::Vector2;
use jaus::stock::sensors::{StockLocalPoseSensor, StockVelocityStateSensor};
use jaus::wire::{AckNak, Header};
use jaus::Address;
use jaus_sim::camera::SimCamera;
use jaus_sim::scanner::{ScannerParams, Scene, SimScanner};
use jaus_sim::vehicle::{SimVehicle, VehicleParams};

const PD: Address = Address::new(1, 1, 33, 1);
const RD: Address = Address::new(1, 1, 43, 1);
const LPS: Address = Address::new(1, 1, 41, 1);
const VSS: Address = Address::new(1, 1, 42, 1);
const LVD: Address = Address::new(1, 1, 44, 1);
const RS: Address = Address::new(1, 1, 50, 1);
const VS: Address = Address::new(1, 1, 37, 1);
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

type Vs = jaus::component::Component<visual_sensor::Dispatch<StockVisualSensor<SimCamera>>>;

fn replies(bus: &mut LocalBus) -> Vec<Message> {
    let p = bus.get_mut::<Probe>(OCU).unwrap();
    let out = p.messages().cloned().collect();
    p.clear();
    out
}

fn with_ack(bus: &mut LocalBus, msg: impl Into<Message>) {
    let msg: Message = msg.into();
    let mut h = Header::new(msg.code(), VS, OCU);
    h.ack_nak = AckNak::Request;
    bus.send_with(h, Some(&msg));
}

fn naks(bus: &LocalBus) -> usize {
    bus.trace()
        .filter(|d| d.header.source == VS && d.header.ack_nak == AckNak::Nak)
        .count()
}

/// Width and height from a PNG's IHDR chunk.
fn png_size(data: &[u8]) -> (u32, u32) {
    assert_eq!(&data[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(&data[12..16], b"IHDR");
    let be = |b: &[u8]| u32::from_be_bytes([b[0], b[1], b[2], b[3]]);
    (be(&data[16..20]), be(&data[20..24]))
}

#[test]
fn the_visual_sensor_reports_its_camera_and_images_within_its_limits() {
    let t0 = Instant::now();
    let vehicle = SimVehicle::new(VehicleParams::default());
    let scene = Scene {
        circles: vec![(Vector2::new(5.0, 0.0), 1.0)],
    };
    let mut bus = LocalBus::new(t0).with_trace(10_000);
    bus.add(visual_sensor::component(
        VS,
        StockVisualSensor::new(SimCamera::new(vehicle, scene), VisualConfig::default()),
        Config::default(),
        t0,
    ));
    bus.add(Probe::new(OCU));
    bus.run_for(Duration::from_millis(100));

    // What the camera is.
    bus.send(OCU, VS, QueryCameraCount {});
    bus.send(OCU, VS, QuerySelectedCamera {});
    bus.send(
        OCU,
        VS,
        QueryCameraCapabilities {
            presence_vector: 0x7FFF,
            camera_id: 1,
        },
    );
    bus.send(
        OCU,
        VS,
        QueryCameraFormatOptions {
            presence_vector: 0x7F,
            camera_id: 1,
        },
    );
    bus.send(
        OCU,
        VS,
        QueryCameraPose {
            presence_vector: 0x3FF,
            camera_id: 1,
        },
    );
    bus.send(OCU, VS, QueryImage {});
    bus.run_for(Duration::from_millis(20));
    let got = replies(&mut bus);
    let find = |f: &dyn Fn(&Message) -> bool| got.iter().find(|m| f(m)).cloned();
    assert!(matches!(
        find(&|m| matches!(m, Message::ReportCameraCount(_))),
        Some(Message::ReportCameraCount(ReportCameraCount {
            camera_count: 1
        }))
    ));
    assert!(matches!(
        find(&|m| matches!(m, Message::ReportSelectedCamera(_))),
        Some(Message::ReportSelectedCamera(ReportSelectedCamera {
            camera_id: 1
        }))
    ));
    let Some(Message::ReportCameraCapabilities(c)) =
        find(&|m| matches!(m, Message::ReportCameraCapabilities(_)))
    else {
        panic!("no capabilities: {got:?}")
    };
    assert_eq!(
        (
            c.max_horizontal_resolution,
            c.max_vertical_resolution,
            c.min_horizontal_resolution,
            c.min_vertical_resolution,
            c.max_frame_rate
        ),
        (Some(640), Some(480), Some(16), Some(12), Some(10))
    );
    // 90° wide; 4:3 makes the vertical view 2·atan(tan 45° · 3/4) = 73.7°.
    assert!((c.max_horizontal_fov.unwrap().to_degrees() - 90.0).abs() < 0.01);
    assert!((c.max_vertical_fov.unwrap().to_degrees() - 73.74).abs() < 0.01);
    assert!(c
        .camera_description
        .unwrap()
        .starts_with("simulated pan/tilt camera"));
    let Some(Message::ReportCameraFormatOptions(f)) =
        find(&|m| matches!(m, Message::ReportCameraFormatOptions(_)))
    else {
        panic!("no format options")
    };
    assert_eq!(
        (
            f.image_format_1,
            f.image_format_2,
            f.image_format_3,
            f.audio_format_1
        ),
        (Some(ImageFormat::Png), Some(ImageFormat::Ppm), None, None)
    );
    let Some(Message::ReportCameraPose(p)) = find(&|m| matches!(m, Message::ReportCameraPose(_)))
    else {
        panic!("no pose")
    };
    assert_eq!(p.camera_name.as_deref(), Some("front camera"));
    assert_eq!(
        (
            p.x_camera_origin,
            p.z_camera_origin,
            p.z_camera_axis_direction_cosine_x,
            p.x_camera_axis_direction_cosine_y
        ),
        (Some(0.5), Some(-1.0), Some(1.0), Some(1.0))
    );
    let Some(Message::ReportImage(first)) = find(&|m| matches!(m, Message::ReportImage(_))) else {
        panic!("no image")
    };
    assert_eq!((first.camera_id, first.video_format), (1, ImageFormat::Png));
    assert_eq!(png_size(&first.data), (640, 480));

    // Faster than 10 frames/s: the same frame again, not a new one.
    bus.send(OCU, VS, QueryImage {});
    bus.run_for(Duration::from_millis(20));
    assert!(replies(&mut bus)
        .iter()
        .any(|m| matches!(m, Message::ReportImage(r) if r.data == first.data)));
    let stats = bus.get::<Vs>(VS).unwrap().behaviour().0.stats();
    assert_eq!((stats.frames, stats.repeated), (1, 1));

    // Commands need control.
    with_ack(
        &mut bus,
        SetCameraFormatOptions {
            camera_id: 1,
            image_format: Some(ImageFormat::Ppm),
            ..Default::default()
        },
    );
    bus.run_for(Duration::from_millis(20));
    assert_eq!(naks(&bus), 1);
    bus.send(OCU, VS, RequestComponentControl { authority_code: 10 });
    bus.run_for(Duration::from_millis(50));
    bus.send(OCU, VS, Resume {});
    bus.run_for(Duration::from_millis(50));

    // A smaller PPM, the mount panned half right (45°).
    for m in [
        Message::from(SetCameraCapabilities {
            camera_id: 1,
            horizontal_resolution: Some(160),
            vertical_resolution: Some(120),
            ..Default::default()
        }),
        Message::from(SetCameraFormatOptions {
            camera_id: 1,
            image_format: Some(ImageFormat::Ppm),
            ..Default::default()
        }),
        Message::from(SetCameraPose {
            camera_id: 1,
            y_angular_position_or_rate: Some(50.0),
            ..Default::default()
        }),
    ] {
        with_ack(&mut bus, m);
    }
    bus.run_for(Duration::from_millis(200));
    assert_eq!(naks(&bus), 1, "the three commands were acknowledged");
    bus.send(OCU, VS, QueryImage {});
    bus.send(
        OCU,
        VS,
        QueryCameraPose {
            presence_vector: 0x380,
            camera_id: 1,
        },
    );
    bus.run_for(Duration::from_millis(20));
    let got = replies(&mut bus);
    let Some(Message::ReportImage(small)) = got
        .iter()
        .find(|m| matches!(m, Message::ReportImage(_)))
        .cloned()
    else {
        panic!("no image: {got:?}")
    };
    assert_eq!(small.video_format, ImageFormat::Ppm);
    assert!(small.data.starts_with(b"P6\n160 120\n255\n"));
    assert_eq!(small.data.len(), 15 + 160 * 120 * 3);
    let Some(Message::ReportCameraPose(p)) = got
        .iter()
        .find(|m| matches!(m, Message::ReportCameraPose(_)))
        .cloned()
    else {
        panic!("no pose")
    };
    let h = std::f64::consts::FRAC_1_SQRT_2;
    assert!((p.z_camera_axis_direction_cosine_x.unwrap() - h).abs() < 1e-4);
    assert!((p.z_camera_axis_direction_cosine_y.unwrap() - h).abs() < 1e-4);

    // Bad values are refused (NAK) and change nothing.
    for m in [
        Message::from(SetCameraCapabilities {
            camera_id: 1,
            horizontal_resolution: Some(1000),
            ..Default::default()
        }),
        Message::from(SetCameraCapabilities {
            camera_id: 1,
            frame_rate: Some(60),
            ..Default::default()
        }),
        Message::from(SelectCamera { camera_id: 2 }),
        Message::from(SetCameraFormatOptions {
            camera_id: 1,
            image_format: Some(ImageFormat::Jpeg),
            ..Default::default()
        }),
        Message::from(SetCameraPose {
            camera_id: 1,
            mode: CameraPoseMode {
                y_angular_mode: 1,
                ..Default::default()
            },
            y_angular_position_or_rate: Some(10.0),
            ..Default::default()
        }),
    ] {
        with_ack(&mut bus, m);
    }
    bus.run_for(Duration::from_millis(50));
    assert_eq!(naks(&bus), 6);
    let vs = bus.get::<Vs>(VS).unwrap();
    let s = vs.behaviour().0.settings(1).unwrap();
    assert_eq!(
        (s.width, s.height, s.format, s.frame_rate),
        (160, 120, ImageFormat::Ppm, 10)
    );
    assert!((s.pan.to_degrees() - 45.0).abs() < 0.01);
}
