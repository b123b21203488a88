//! The AS-4 Range Sensor hosted natively on the gateway's component over the simulated
//! scanner (`jaus_as4::environment::RangeSensorService` over the `RangeScanner` the
//! demo vehicle's RA 3.3 Range Sensor reads), as a node file with `host: [vehicle]`
//! and `as4:` builds it: an AS-4 client fetches a sweep and checks it against the
//! simulated scene (each beam ray-cast against its circular obstacles), reads the
//! capabilities, configuration and placement, the compressed data (no compression
//! only), and has a configuration refused without control and checked with it.

use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use jaus::stock::nalgebra::Vector2;

use jaus::net::as5669a::As4Id;
use jaus_as4::{
    ConfirmSensorConfigurationVariant as Confirmed,
    ConfirmSensorConfigurationVariantRangeSensorErrorRecCode as RangeCode, CoordinateSystemEnum,
    DataCompressionEnum, Message, QueryRangeSensorCapabilities, QueryRangeSensorCapabilitiesRec,
    QueryRangeSensorCompressedData, QueryRangeSensorCompressedDataRec,
    QueryRangeSensorConfiguration, QueryRangeSensorConfigurationRec, QueryRangeSensorData,
    QueryRangeSensorDataRec, QuerySensorGeometricProperties, RangeSensorConfigurationRec,
    RangeSensorDataErrorRecCode, ReportRangeSensorCapabilitiesRecCoordinateTransformationSupported,
    ReportRangeSensorCompressedDataVariant as Compressed, ReportRangeSensorDataVariant as Data,
    ReportRangeSensorDataVariantSeq, ReportRangeSensorDataVariantSeqPointRecRangeValidity as Valid,
    ReportSensorGeometricPropertiesSequenceVariant as Placement, RequestIdRec, SensorIdRec,
    SensorStateEnum, SetRangeSensorConfiguration,
};
use jaus_node::NodeFile;
use jaus_sim::scanner::ray_circle;

mod common;
use common::as4::As4Rig;

const VEHICLE: As4Id = As4Id::new(1, 1, 1);
const WAIT: Duration = Duration::from_millis(500);
/// The simulated scanner: 181 beams over 180°, 20 m, 1 cm of range noise.
const BEAMS: usize = 181;
const MAX_RANGE: f64 = 20.0;
/// A return within noise and this of the scene's geometry, m.
const TOLERANCE: f64 = 0.1;

struct Rig(As4Rig);

/// The node file `yaml` (after `subsystem`, `node` and `bind`) in a directory of its own.
fn node_file(name: &str, yaml: &str) -> (PathBuf, PathBuf) {
    let dir = std::env::temp_dir().join(format!("jaus-as4-range-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("vehicle.yaml");
    std::fs::write(
        &path,
        format!(
            "subsystem: 1\nnode: 1\nbind: 127.0.0.1:3794\n{yaml}as4: {{ name: demo vehicle }}\n"
        ),
    )
    .unwrap();
    (dir, path)
}

impl Rig {
    /// What the node file at `path` hosts, behind its gateway; the native services'
    /// count.
    fn from_file(path: &Path) -> (Self, usize) {
        let file = NodeFile::load(path).unwrap();
        let t0 = Instant::now();
        let (node, native) = file.build_node_and_as4(path, t0).unwrap();
        let count = native.len();
        let rig = As4Rig::hosting(
            t0,
            node,
            native,
            VEHICLE,
            "demo vehicle",
            Duration::from_secs(3),
        );
        (Rig(rig), count)
    }

    fn one(&mut self, m: impl Into<Message>) -> Message {
        self.0.one_within(m, WAIT)
    }

    /// One sweep of sensor 1 in `system`, every point field asked.
    fn sweep(&mut self, system: CoordinateSystemEnum) -> ReportRangeSensorDataVariantSeq {
        let Message::ReportRangeSensorData(d) = self.one(QueryRangeSensorData {
            query_range_sensor_data_list: vec![QueryRangeSensorDataRec {
                sensor_id: 1,
                report_coordinate_system: system,
                query_presence_vector: 0x7f,
            }],
        }) else {
            panic!("no Report Range Sensor Data");
        };
        assert_eq!(d.range_sensor_data_list.len(), 1);
        match d.range_sensor_data_list.into_iter().next() {
            Some(Data::RangeSensorDataSeq(s)) => s,
            other => panic!("no sweep: {other:?}"),
        }
    }

    fn refused(&self) -> u64 {
        self.0
            .dual()
            .gateway()
            .component()
            .expect("the gateway's component")
            .stats()
            .refused
    }

    /// Sends Set Range Sensor Configuration (request 7), returns what came back.
    fn set(&mut self, list: Vec<RangeSensorConfigurationRec>) -> Vec<Message> {
        self.0.ask(
            SetRangeSensorConfiguration {
                request_id_rec: RequestIdRec { request_id: 7 },
                range_sensor_configuration_list: list,
            },
            WAIT,
        )
    }
}

/// The bearing of beam `i` of the simulated scanner (first on the left).
fn bearing_of(i: usize) -> f64 {
    -PI / 2.0 + PI * i as f64 / (BEAMS - 1) as f64
}

/// What beam `i` sees of the demo scene from the vehicle at the origin facing north
/// (local frame x north, y east; the beam's bearing positive to the right).
fn expected(i: usize) -> Option<f64> {
    let b = bearing_of(i);
    let d = Vector2::new(b.cos(), b.sin());
    jaus_sim::demo::scene()
        .circles
        .iter()
        .filter_map(|(c, r)| ray_circle(Vector2::zeros(), d, *c, *r))
        .min_by(f64::total_cmp)
        .filter(|t| *t <= MAX_RANGE)
}

fn config(f: impl FnOnce(&mut RangeSensorConfigurationRec)) -> RangeSensorConfigurationRec {
    let mut c = RangeSensorConfigurationRec {
        sensor_id: 1,
        ..Default::default()
    };
    f(&mut c);
    c
}

#[test]
fn an_as4_client_reads_the_simulated_scan_through_the_range_sensor() {
    let (dir, path) = node_file("vehicle", "host: [vehicle]\n");
    let (mut r, native) = Rig::from_file(&path);
    assert_eq!(native, 2, "Illumination and the Range Sensor");
    let uris = r.0.service_uris();
    assert_eq!(
        uris.iter()
            .filter(|u| *u == "urn:jaus:jss:environmentSensing:RangeSensor")
            .count(),
        1,
        "{uris:?}"
    );

    // A sweep, beam by beam against the scene.
    let s = r.sweep(CoordinateSystemEnum::NativeCoordinateSystem);
    assert_eq!(s.range_sensor_data_rec.sensor_id, 1);
    assert_eq!(
        s.range_sensor_data_rec.report_coordinate_system,
        CoordinateSystemEnum::NativeCoordinateSystem
    );
    let points = &s.range_sensor_data_point_list;
    assert_eq!(points.len(), BEAMS);
    let mut hits = 0;
    for (i, p) in points.iter().enumerate() {
        assert_eq!(p.point_id, Some(i as u32));
        assert!(
            (p.bearing - bearing_of(i)).abs() < 1e-6,
            "beam {i}: bearing {} vs {}",
            p.bearing,
            bearing_of(i)
        );
        assert_eq!(p.inclination, 0.0);
        match expected(i) {
            Some(t) => {
                hits += 1;
                assert_eq!(p.range_validity, Some(Valid::True), "beam {i}");
                assert!(
                    (p.range - t).abs() < TOLERANCE,
                    "beam {i}: {} m, the scene says {t} m",
                    p.range
                );
                assert!((p.range_error_rms.unwrap() - 0.01).abs() < 1e-4);
            }
            None => {
                assert_eq!(p.range_validity, Some(Valid::False), "beam {i}: {p:?}");
                assert!((p.range - MAX_RANGE).abs() < 1e-3, "beam {i}: {p:?}");
            }
        }
    }
    // Both obstacles seen; the one 1.5 m ahead and 2 m to the left (2.5 m to its
    // centre, 0.4 m radius) by the beam pointing at it, 53° left.
    assert!(hits >= 4, "{hits} returns");
    let (cx, cy) = jaus_sim::demo::UNKNOWN_OBSTACLE.0;
    let at = cy.atan2(cx);
    let i = ((at + PI / 2.0) / PI * (BEAMS - 1) as f64).round() as usize;
    assert_eq!(i, 37);
    let near = cx.hypot(cy) - jaus_sim::demo::UNKNOWN_OBSTACLE.1;
    assert!(
        (points[i].range - near).abs() < TOLERANCE,
        "{} vs {near}",
        points[i].range
    );
    // Nothing on the right.
    assert!(points[BEAMS - 1].range_validity == Some(Valid::False));

    // The vehicle's frame: the scanner is at the reference point, the same returns.
    let v = r.sweep(CoordinateSystemEnum::VehicleCoordinateSystem);
    assert_eq!(
        v.range_sensor_data_rec.report_coordinate_system,
        CoordinateSystemEnum::VehicleCoordinateSystem
    );
    assert!((v.range_sensor_data_point_list[i].range - near).abs() < TOLERANCE);

    // Another sensor id: nothing of it.
    let Message::ReportRangeSensorData(d) = r.one(QueryRangeSensorData {
        query_range_sensor_data_list: vec![QueryRangeSensorDataRec {
            sensor_id: 9,
            ..Default::default()
        }],
    }) else {
        panic!("no Report Range Sensor Data");
    };
    assert!(d.range_sensor_data_list.is_empty());

    // Capabilities, configuration and placement: what the scanner is.
    let Message::ReportRangeSensorCapabilities(c) = r.one(QueryRangeSensorCapabilities {
        range_sensor_capabilities_list: vec![QueryRangeSensorCapabilitiesRec {
            sensor_id: 1,
            query_presence_vector: 0xffff,
        }],
    }) else {
        panic!("no Report Range Sensor Capabilities");
    };
    let [c] = &c.range_sensor_capabilities_list[..] else {
        panic!("{c:?}");
    };
    assert_eq!(c.sensor_id, 1);
    assert!(c.supported_states.unwrap().active);
    assert!((c.minimum_horizontal_field_of_view_start_angle.unwrap() + PI / 2.0).abs() < 1e-6);
    assert!((c.maximum_horizontal_field_of_view_stop_angle.unwrap() - PI / 2.0).abs() < 1e-6);
    assert!((c.maximum_range.unwrap() - MAX_RANGE).abs() < 1e-3);
    assert!(c.supported_compression.unwrap().no_compression);
    assert!(!c.supported_compression.unwrap().deflate);
    assert_eq!(
        c.coordinate_transformation_supported,
        Some(ReportRangeSensorCapabilitiesRecCoordinateTransformationSupported::True)
    );
    let Message::ReportRangeSensorConfiguration(k) = r.one(QueryRangeSensorConfiguration {
        range_sensor_configuration_list: vec![QueryRangeSensorConfigurationRec {
            sensor_id: 1,
            query_presence_vector: 0xffff,
        }],
    }) else {
        panic!("no Report Range Sensor Configuration");
    };
    let [k] = &k.range_sensor_configuration_list[..] else {
        panic!("{k:?}");
    };
    assert_eq!(k.sensor_state, Some(SensorStateEnum::Active));
    assert!((k.maximum_range.unwrap() - MAX_RANGE).abs() < 1e-3);
    let have = k.clone();
    let Message::ReportSensorGeometricProperties(g) = r.one(QuerySensorGeometricProperties {
        sensor_id_list: vec![SensorIdRec { sensor_id: 1 }],
    }) else {
        panic!("no Report Sensor Geometric Properties");
    };
    match &g.geometric_properties_list[..] {
        [p] => match &p.geometric_properties_variant {
            Placement::StaticGeometricPropertiesRec(s) => {
                assert!(s.sensor_position.position_vector_element_0.abs() < 1e-6);
                assert!((s.unit_quaternion.unit_quaternion_element_0 - 1.0).abs() < 1e-6);
            }
            other => panic!("{other:?}"),
        },
        other => panic!("{other:?}"),
    }

    // Compressed data: no compression only, the data the encoded point list.
    let compressed = |r: &mut Rig, data_compression| {
        let Message::ReportRangeSensorCompressedData(c) = r.one(QueryRangeSensorCompressedData {
            query_range_sensor_compressed_data_list: vec![QueryRangeSensorCompressedDataRec {
                sensor_id: 1,
                report_coordinate_system: CoordinateSystemEnum::NativeCoordinateSystem,
                data_compression,
                query_presence_vector: 0,
            }],
        }) else {
            panic!("no Report Range Sensor Compressed Data");
        };
        c.range_sensor_compressed_data_list
    };
    match &compressed(&mut r, DataCompressionEnum::None)[..] {
        [Compressed::RangeSensorCompressedDataRec(c)] => {
            assert_eq!(c.data_compression, DataCompressionEnum::None);
            assert_eq!(
                u16::from_le_bytes([c.compressed_data[0], c.compressed_data[1]]),
                BEAMS as u16
            );
        }
        other => panic!("{other:?}"),
    }
    match &compressed(&mut r, DataCompressionEnum::Deflate)[..] {
        [Compressed::RangeSensorDataErrorRec(e)] => assert_eq!(
            e.data_error_code,
            RangeSensorDataErrorRecCode::InvalidCompressionFormat
        ),
        other => panic!("{other:?}"),
    }

    // A configuration without control: refused, nothing answered.
    let refused = r.refused();
    assert!(r.set(vec![have.clone()]).is_empty());
    assert_eq!(r.refused(), refused + 1);

    // With control: what the scanner does is accepted, the rest refused sensor by
    // sensor.
    r.0.take_control();
    let got = r.set(vec![
        have.clone(),
        config(|c| c.maximum_range = Some(50.0)),
        config(|c| c.sensor_state = Some(SensorStateEnum::Off)),
        config(|c| {
            c.update_rate = Some(10.0);
            c.vertical_field_of_view_stop_angle = Some(0.3);
        }),
        RangeSensorConfigurationRec {
            sensor_id: 4,
            ..Default::default()
        },
    ]);
    let [Message::ConfirmSensorConfiguration(c)] = &got[..] else {
        panic!("{got:?}");
    };
    assert_eq!(c.request_id_rec.request_id, 7);
    let codes: Vec<Option<RangeCode>> = c
        .confirm_sensor_list
        .iter()
        .map(|c| match c {
            Confirmed::SensorIdRec(s) => {
                assert_eq!(s.sensor_id, 1);
                None
            }
            Confirmed::RangeSensorErrorRec(e) => Some(e.range_sensor_error_code),
            other => panic!("{other:?}"),
        })
        .collect();
    assert_eq!(
        codes,
        vec![
            None,
            Some(RangeCode::InvalidSensorRange),
            Some(RangeCode::InvalidSensorState),
            Some(RangeCode::MultipleInvalidParameters),
            Some(RangeCode::UnknownSensorId),
        ]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_range_sensor_entry_offers_the_as4_range_sensor_over_its_scanner() {
    // The stock range sensor in the empty world of `host:` entries: no returns.
    let (dir, path) = node_file("stock", "host: [range_sensor]\n");
    let (mut r, native) = Rig::from_file(&path);
    assert_eq!(native, 1, "the Range Sensor alone");
    let s = r.sweep(CoordinateSystemEnum::NativeCoordinateSystem);
    assert_eq!(s.range_sensor_data_point_list.len(), BEAMS);
    assert!(s
        .range_sensor_data_point_list
        .iter()
        .all(|p| p.range_validity == Some(Valid::False) && (p.range - MAX_RANGE).abs() < 1e-3));
    let _ = std::fs::remove_dir_all(&dir);
}
