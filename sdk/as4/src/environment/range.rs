//! The Range Sensor service, hosted natively over a scanning range finder (any
//! [`RangeScanner`], the hardware trait the RA 3.3 stock Range Sensor runs over too: one
//! scanner, read by both generations). It is a [`GeneratedService`] on its generated
//! machines (`defs/environment_services.yaml`), so any AS-4 component hosts it
//! (`As4Component::with_service`, or beside a gateway's services with
//! [`crate::gateway::DualNode::with_service`]). The scanner is AS-4 sensor
//! [`SENSOR_ID`]; a query's records for other ids are left out of the answer, and
//! each query answers the sensor once however often it is listed.
//!
//! * Query Range Sensor Capabilities and Configuration: what [`RangeScanner::spec`]
//!   gives: the horizontal field of view (first and last beam's bearings), a vertical
//!   one of 0 (one plane), ranges from 0 to the farthest return, Active (its only
//!   state), no compression, and a coordinate transform when the mount is known. The
//!   update rate is left out (a sweep is read when asked), as is everything the spec
//!   would give for a scanner without one.
//! * Query Sensor Geometric Properties: the mount (forward and right of the vehicle's
//!   reference point, height 0) with the identity orientation (the unit quaternion's
//!   element 0 is the scalar part, as in the Manipulator set): a sweep's bearings are
//!   the vehicle's directions already; a scanner without a spec has no placement.
//! * Query Range Sensor Data: a fresh sweep ([`RangeScanner::scan`] when asked) as one
//!   point per beam, at most [`MAX_POINTS`]: range, bearing (0 forward, positive to the
//!   right, as the beam's) and inclination 0, in the sensor's native coordinate system:
//!   ranges from the mount point, bearings from the vehicle's forward axis. A record
//!   asking for the vehicle coordinate system is answered in it when the mount is
//!   known (each return moved to the vehicle's reference point), else in the native one,
//!   the report's coordinate system field saying which (the machine's
//!   `!isCoordinateTransformSupported` transition: "in each sensor's native coordinate
//!   system"). A beam that saw nothing reads the farthest range (0 when the scanner
//!   does not say), its range validity False; a beam whose bearing is not a number is
//!   left out. The point fields the record's query presence vector asks for (the point
//!   record's bits) are given when known: the point id (the beam's index), the range,
//!   bearing and inclination validities, the range error (the scanner's noise). No
//!   sweep: a Range Sensor Data Error (Unknown Error Failure).
//! * Query Range Sensor Compressed Data: only "no compression" (`DataCompressionEnum::None`),
//!   the data being the encoded point list of Report Range Sensor Data (its `u16`
//!   count, then the points); another compression is answered with a Range Sensor
//!   Data Error (Invalid Compression Format).
//! * Set Range Sensor Configuration: from the controlling client (the machine's
//!   `isControllingClient`; anyone else's is refused and nothing is answered), answered
//!   with Confirm Sensor Configuration sensor by sensor: accepted when it asks what the
//!   scanner does (its field of view, 0 vertical, ranges 0 to its farthest, Active),
//!   else refused with the range sensor error naming the field (Multiple Invalid
//!   Parameters for several); an unknown id is Unknown Sensor Id. Nothing of the
//!   scanner changes.

use std::f64::consts::PI;
use std::fmt;
use std::time::Instant;

use jaus::codec::{encode_list, Encode, Writer};
use jaus::stock::environment::range::{Beam, RangeScanner, ScannerSpec};
use jaus::CommandCode;

use super::{ServiceIds, SENSOR_ID};
use crate::core::machine::Host;
use crate::messages::services::range_sensor as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::services::Arg;
use crate::messages::{
    ConfirmSensorConfiguration, ConfirmSensorConfigurationVariant as Confirmed,
    ConfirmSensorConfigurationVariantRangeSensorErrorRec as RangeError,
    ConfirmSensorConfigurationVariantRangeSensorErrorRecCode as RangeCode, CoordinateSystemEnum,
    DataCompressionEnum, Message, PositionVector, QueryRangeSensorCapabilities,
    QueryRangeSensorCompressedData, QueryRangeSensorConfiguration, QueryRangeSensorData,
    QuerySensorGeometricProperties, RangeSensorConfigurationRec, RangeSensorDataErrorRec,
    RangeSensorDataErrorRecCode as DataErrorCode, ReportRangeSensorCapabilities,
    ReportRangeSensorCapabilitiesRec,
    ReportRangeSensorCapabilitiesRecCoordinateTransformationSupported as Transform,
    ReportRangeSensorCapabilitiesRecSupportedCompression as Compression,
    ReportRangeSensorCompressedData, ReportRangeSensorCompressedDataVariant as CompressedVariant,
    ReportRangeSensorCompressedDataVariantRec as CompressedRec, ReportRangeSensorConfiguration,
    ReportRangeSensorData, ReportRangeSensorDataVariant as DataVariant,
    ReportRangeSensorDataVariantSeq as DataSeq, ReportRangeSensorDataVariantSeqPointRec as Point,
    ReportRangeSensorDataVariantSeqPointRecBearingValidity as BearingValidity,
    ReportRangeSensorDataVariantSeqPointRecInclinationValidity as InclinationValidity,
    ReportRangeSensorDataVariantSeqPointRecRangeValidity as RangeValidity,
    ReportRangeSensorDataVariantSeqRec as DataHeader, ReportSensorGeometricProperties,
    ReportSensorGeometricPropertiesSequence as Placement,
    ReportSensorGeometricPropertiesSequenceVariant as PlacementVariant,
    ReportSensorGeometricPropertiesSequenceVariantNoVariant as NoPlacement,
    ReportSensorGeometricPropertiesSequenceVariantStaticRec as StaticPlacement, SensorIdRec,
    SensorStateEnum, SetRangeSensorConfiguration, SupportedSensorStates, TimeStamp, UnitQuaternion,
};
use crate::service::{GeneratedService, Outbox, Outgoing, ServiceId, Taken};

/// Points in one report at most: what the point list's `u16` count holds.
pub const MAX_POINTS: usize = u16::MAX as usize;

/// Angles closer than this are the same (what a configuration asks is compared with
/// the scanner's), rad.
const ANGLE_TOLERANCE: f64 = 1e-6;
/// Ranges closer than this are the same, m.
const RANGE_TOLERANCE: f64 = 1e-3;
/// The farthest range the messages carry, m.
const MAX_WIRE_RANGE: f64 = 1_000_000.0;
/// The farthest mount offset the geometric properties carry, m.
const MAX_MOUNT: f64 = 30.0;

/// The Range Sensor service's own guards and actions over the scanner `S`.
struct Ranges<S> {
    scanner: S,
    name: String,
    /// The time of the message being handled.
    now: Option<Instant>,
    /// The component's time stamp at `now`, when its clock is set.
    stamp: Option<TimeStamp>,
    beams: Vec<Beam>,
    outbox: Outbox,
}

impl<S> fmt::Debug for Ranges<S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Ranges")
            .field("name", &self.name)
            .finish_non_exhaustive()
    }
}

/// `a` within `[-π, π]` (0 for a value that is not a number).
fn wrap(a: f64) -> f64 {
    if !a.is_finite() {
        return 0.0;
    }
    let w = (a + PI).rem_euclid(2.0 * PI) - PI;
    w.clamp(-PI, PI)
}

/// A range as the messages carry it: finite, within `[0, 1e6]` m, else 0.
fn wire_range(r: f64) -> f64 {
    if r.is_finite() {
        r.clamp(0.0, MAX_WIRE_RANGE)
    } else {
        0.0
    }
}

/// The point fields of the query presence vector `pv` that this service fills.
#[derive(Debug, Clone, Copy)]
struct Asked(u16);

impl Asked {
    fn bit(self, b: u16) -> bool {
        self.0 & (1 << b) != 0
    }
}

/// The points of `beams` in `system` (the vehicle's when the mount is known and it is
/// asked, else native), with the fields `asked`; the system the points are in.
fn points_of(
    beams: &[Beam],
    spec: Option<&ScannerSpec>,
    system: CoordinateSystemEnum,
    asked: Asked,
) -> (Vec<Point>, CoordinateSystemEnum) {
    let mount = spec
        .map(|s| s.mount)
        .filter(|_| system == CoordinateSystemEnum::VehicleCoordinateSystem)
        .filter(|(x, y)| x.is_finite() && y.is_finite());
    let farthest = spec.map_or(0.0, |s| wire_range(s.max_range));
    let noise = spec.map(|s| s.range_noise).filter(|n| n.is_finite());
    let points = beams
        .iter()
        .enumerate()
        .filter(|(_, b)| b.bearing.is_finite())
        .take(MAX_POINTS)
        .map(|(i, b)| {
            let hit = b.range.filter(|r| r.is_finite() && *r >= 0.0);
            let (range, bearing) = match (hit, mount) {
                (Some(r), Some((x, y))) => {
                    let (px, py) = (x + r * b.bearing.cos(), y + r * b.bearing.sin());
                    (px.hypot(py), py.atan2(px))
                }
                (Some(r), None) => (r, b.bearing),
                (None, _) => (farthest, b.bearing),
            };
            Point {
                point_id: u32::try_from(i).ok().filter(|_| asked.bit(0)),
                range: wire_range(range),
                range_validity: asked.bit(1).then_some(if hit.is_some() {
                    RangeValidity::True
                } else {
                    RangeValidity::False
                }),
                range_error_rms: noise
                    .filter(|_| asked.bit(2) && hit.is_some())
                    .map(|n| n.clamp(0.0, 100_000.0)),
                bearing: wrap(bearing),
                bearing_validity: asked.bit(3).then_some(BearingValidity::True),
                bearing_error_rms: None,
                inclination: 0.0,
                inclination_validity: asked.bit(5).then_some(InclinationValidity::True),
                inclination_error_rms: None,
            }
        })
        .collect();
    let system = if mount.is_some() {
        CoordinateSystemEnum::VehicleCoordinateSystem
    } else {
        CoordinateSystemEnum::NativeCoordinateSystem
    };
    (points, system)
}

/// The point list as Report Range Sensor Data carries it: its `u16` count, the points.
fn encoded_points(points: &[Point]) -> Option<Vec<u8>> {
    let len = 2 + points.iter().map(Encode::encoded_len).sum::<usize>();
    let mut out = vec![0u8; len];
    let mut w = Writer::new(&mut out);
    match encode_list::<u16, _>(&mut w, points, "range_sensor_data_point_list") {
        Ok(()) => Some(out),
        Err(e) => {
            tracing::warn!("Range Sensor compressed data: points not encoded: {e}");
            None
        }
    }
}

impl<S: RangeScanner> Ranges<S> {
    /// A fresh sweep into `self.beams` at the Core's time of the message being
    /// handled, or `false` without one (sans-IO: no time of its own).
    fn sweep(&mut self) -> bool {
        let Some(now) = self.now else {
            return false;
        };
        self.scanner.scan(now, &mut self.beams)
    }

    /// The configuration the scanner has.
    fn configuration(&self) -> RangeSensorConfigurationRec {
        let spec = self.scanner.spec();
        RangeSensorConfigurationRec {
            sensor_id: SENSOR_ID,
            horizontal_field_of_view_start_angle: spec.map(|s| wrap(s.first_bearing)),
            horizontal_field_of_view_stop_angle: spec.map(|s| wrap(s.last_bearing)),
            vertical_field_of_view_start_angle: spec.map(|_| 0.0),
            vertical_field_of_view_stop_angle: spec.map(|_| 0.0),
            update_rate: None,
            minimum_range: spec.map(|_| 0.0),
            maximum_range: spec.map(|s| wire_range(s.max_range)),
            sensor_state: Some(SensorStateEnum::Active),
        }
    }

    /// The first record of `list` naming our sensor (`id` reads a record's), if any.
    fn ours<T>(list: &[T], id: impl Fn(&T) -> u16) -> Option<&T> {
        list.iter().find(|r| id(r) == SENSOR_ID)
    }

    /// Why `asked` is refused (the fields the scanner does not do), if it is.
    fn refusal(&self, asked: &RangeSensorConfigurationRec) -> Option<(RangeCode, &'static str)> {
        let have = self.configuration();
        let angle = |a: Option<f64>, h: Option<f64>| match (a, h) {
            (None, _) => true,
            (Some(a), Some(h)) => (a - h).abs() <= ANGLE_TOLERANCE,
            (Some(_), None) => false,
        };
        let range = |a: Option<f64>, h: Option<f64>| match (a, h) {
            (None, _) => true,
            (Some(a), Some(h)) => (a - h).abs() <= RANGE_TOLERANCE,
            (Some(_), None) => false,
        };
        let mut wrong: Vec<(RangeCode, &'static str)> = Vec::new();
        if !(angle(
            asked.horizontal_field_of_view_start_angle,
            have.horizontal_field_of_view_start_angle,
        ) && angle(
            asked.horizontal_field_of_view_stop_angle,
            have.horizontal_field_of_view_stop_angle,
        )) {
            wrong.push((
                RangeCode::InvalidHorizontalFieldOfView,
                "the scanner's field of view is fixed",
            ));
        }
        if !(angle(
            asked.vertical_field_of_view_start_angle,
            have.vertical_field_of_view_start_angle,
        ) && angle(
            asked.vertical_field_of_view_stop_angle,
            have.vertical_field_of_view_stop_angle,
        )) {
            wrong.push((
                RangeCode::InvalidVerticalFieldOfView,
                "the scanner scans one plane",
            ));
        }
        if asked.update_rate.is_some() {
            wrong.push((
                RangeCode::InvalidUpdateRate,
                "the scanner is read when asked",
            ));
        }
        if !(range(asked.minimum_range, have.minimum_range)
            && range(asked.maximum_range, have.maximum_range))
        {
            wrong.push((
                RangeCode::InvalidSensorRange,
                "the scanner's range is fixed",
            ));
        }
        if asked
            .sensor_state
            .is_some_and(|s| s != SensorStateEnum::Active)
        {
            wrong.push((
                RangeCode::InvalidSensorState,
                "the scanner is always active",
            ));
        }
        match wrong.len() {
            0 => None,
            1 => wrong.pop(),
            _ => Some((
                RangeCode::MultipleInvalidParameters,
                "the scanner has none of these settings",
            )),
        }
    }
}

impl<S: RangeScanner> generated::RangeSensor for Ranges<S> {
    fn is_coordinate_transform_supported(&self, args: &[Arg<'_>]) -> bool {
        let known = self.scanner.spec().is_some();
        let vehicle_ok =
            |c: CoordinateSystemEnum| c == CoordinateSystemEnum::NativeCoordinateSystem || known;
        args.iter().all(|a| match a {
            Arg::QueryRangeSensorData(q) => q
                .query_range_sensor_data_list
                .iter()
                .all(|r| vehicle_ok(r.report_coordinate_system)),
            Arg::QueryRangeSensorCompressedData(q) => q
                .query_range_sensor_compressed_data_list
                .iter()
                .all(|r| vehicle_ok(r.report_coordinate_system)),
            _ => true,
        })
    }

    fn send_report_range_sensor_capabilities(
        &mut self,
        msg: &QueryRangeSensorCapabilities,
        transport_data: &Receive,
    ) {
        let spec = self.scanner.spec();
        let list = Self::ours(&msg.range_sensor_capabilities_list, |r| r.sensor_id)
            .map(|_| ReportRangeSensorCapabilitiesRec {
                sensor_id: SENSOR_ID,
                sensor_name: self.name.clone(),
                supported_states: Some(SupportedSensorStates {
                    active: true,
                    ..Default::default()
                }),
                minimum_horizontal_field_of_view_start_angle: spec.map(|s| wrap(s.first_bearing)),
                maximum_horizontal_field_of_view_stop_angle: spec.map(|s| wrap(s.last_bearing)),
                minimum_vertical_field_of_view_start_angle: spec.map(|_| 0.0),
                maximum_vertical_field_of_view_stop_angle: spec.map(|_| 0.0),
                miniumum_update_rate: None,
                maximum_update_rate: None,
                minimum_range: spec.map(|_| 0.0),
                maximum_range: spec.map(|s| wire_range(s.max_range)),
                supported_compression: Some(Compression {
                    no_compression: true,
                    ..Default::default()
                }),
                coordinate_transformation_supported: Some(if spec.is_some() {
                    Transform::True
                } else {
                    Transform::False
                }),
            })
            .into_iter()
            .collect();
        self.outbox.reply(
            transport_data,
            &ReportRangeSensorCapabilities {
                range_sensor_capabilities_list: list,
            },
        );
    }

    fn send_report_range_sensor_compressed_data(
        &mut self,
        msg: &QueryRangeSensorCompressedData,
        transport_data: &Receive,
    ) {
        let mut list = Vec::new();
        if let Some(q) = Self::ours(&msg.query_range_sensor_compressed_data_list, |r| {
            r.sensor_id
        }) {
            let error = |code, why: &str| {
                CompressedVariant::RangeSensorDataErrorRec(RangeSensorDataErrorRec {
                    sensor_id: SENSOR_ID,
                    data_error_code: code,
                    error_message: why.into(),
                })
            };
            let q = q.clone();
            let item = if q.data_compression != DataCompressionEnum::None {
                error(
                    DataErrorCode::InvalidCompressionFormat,
                    "only no compression is served",
                )
            } else if !self.sweep() {
                error(
                    DataErrorCode::UnknownErrorFailure,
                    "no sweep from the range scanner",
                )
            } else {
                let spec = self.scanner.spec();
                let (points, system) = points_of(
                    &self.beams,
                    spec.as_ref(),
                    q.report_coordinate_system,
                    Asked(q.query_presence_vector),
                );
                match encoded_points(&points) {
                    Some(compressed_data) => {
                        CompressedVariant::RangeSensorCompressedDataRec(CompressedRec {
                            sensor_id: SENSOR_ID,
                            report_coordinate_system: system,
                            time_stamp: self.stamp.unwrap_or_default(),
                            data_compression: DataCompressionEnum::None,
                            compressed_data,
                        })
                    }
                    None => error(
                        DataErrorCode::UnknownErrorFailure,
                        "the sweep could not be encoded",
                    ),
                }
            };
            list.push(item);
        }
        self.outbox.reply(
            transport_data,
            &ReportRangeSensorCompressedData {
                range_sensor_compressed_data_list: list,
            },
        );
    }

    fn send_report_range_sensor_configuration(
        &mut self,
        msg: &QueryRangeSensorConfiguration,
        transport_data: &Receive,
    ) {
        let list = Self::ours(&msg.range_sensor_configuration_list, |r| r.sensor_id)
            .map(|_| self.configuration())
            .into_iter()
            .collect();
        self.outbox.reply(
            transport_data,
            &ReportRangeSensorConfiguration {
                range_sensor_configuration_list: list,
            },
        );
    }

    fn send_report_range_sensor_data(
        &mut self,
        msg: &QueryRangeSensorData,
        transport_data: &Receive,
    ) {
        let mut list = Vec::new();
        if let Some(q) = Self::ours(&msg.query_range_sensor_data_list, |r| r.sensor_id) {
            let q = q.clone();
            let item = if self.sweep() {
                let spec = self.scanner.spec();
                let (points, system) = points_of(
                    &self.beams,
                    spec.as_ref(),
                    q.report_coordinate_system,
                    Asked(q.query_presence_vector),
                );
                DataVariant::RangeSensorDataSeq(DataSeq {
                    range_sensor_data_rec: DataHeader {
                        sensor_id: SENSOR_ID,
                        report_coordinate_system: system,
                        time_stamp: self.stamp.unwrap_or_default(),
                    },
                    range_sensor_data_point_list: points,
                })
            } else {
                DataVariant::RangeSensorDataErrorRec(RangeSensorDataErrorRec {
                    sensor_id: SENSOR_ID,
                    data_error_code: DataErrorCode::UnknownErrorFailure,
                    error_message: "no sweep from the range scanner".into(),
                })
            };
            list.push(item);
        }
        self.outbox.reply(
            transport_data,
            &ReportRangeSensorData {
                range_sensor_data_list: list,
            },
        );
    }

    fn send_report_sensor_geometric_properties(
        &mut self,
        msg: &QuerySensorGeometricProperties,
        transport_data: &Receive,
    ) {
        let spec = self.scanner.spec();
        let list = Self::ours(&msg.sensor_id_list, |r| r.sensor_id)
            .map(|_| {
                let variant = match spec {
                    Some(s) if s.mount.0.is_finite() && s.mount.1.is_finite() => {
                        PlacementVariant::StaticGeometricPropertiesRec(StaticPlacement {
                            sensor_position: PositionVector {
                                position_vector_element_0: s.mount.0.clamp(-MAX_MOUNT, MAX_MOUNT),
                                position_vector_element_1: s.mount.1.clamp(-MAX_MOUNT, MAX_MOUNT),
                                position_vector_element_2: 0.0,
                            },
                            unit_quaternion: UnitQuaternion {
                                unit_quaternion_element_0: 1.0,
                                unit_quaternion_element_1: 0.0,
                                unit_quaternion_element_2: 0.0,
                                unit_quaternion_element_3: 0.0,
                            },
                        })
                    }
                    _ => PlacementVariant::NoGeometricPropertiesVariant(NoPlacement::default()),
                };
                Placement {
                    sensor_id_rec: SensorIdRec {
                        sensor_id: SENSOR_ID,
                    },
                    geometric_properties_variant: variant,
                }
            })
            .into_iter()
            .collect();
        self.outbox.reply(
            transport_data,
            &ReportSensorGeometricProperties {
                geometric_properties_list: list,
            },
        );
    }

    fn update_range_sensor_configuration(
        &mut self,
        msg: &SetRangeSensorConfiguration,
        transport_data: &Receive,
    ) {
        // One answer per record asked (the list's count bounds it); nothing changes.
        let confirm_sensor_list = msg
            .range_sensor_configuration_list
            .iter()
            .map(|r| {
                let refused = if r.sensor_id != SENSOR_ID {
                    Some((RangeCode::UnknownSensorId, "no such sensor"))
                } else {
                    self.refusal(r)
                };
                match refused {
                    None => Confirmed::SensorIdRec(SensorIdRec {
                        sensor_id: r.sensor_id,
                    }),
                    Some((code, why)) => Confirmed::RangeSensorErrorRec(RangeError {
                        sensor_id: r.sensor_id,
                        range_sensor_error_code: code,
                        error_message: why.into(),
                    }),
                }
            })
            .collect();
        self.outbox.reply(
            transport_data,
            &ConfirmSensorConfiguration {
                request_id_rec: msg.request_id_rec.clone(),
                confirm_sensor_list,
            },
        );
    }
}

/// The Range Sensor service over the scanner `S`, on its generated machines: a
/// [`GeneratedService`], hosted by any AS-4 component. Written out rather than the
/// generated `Hosted` adapter because each message first reads the Core's clock (the
/// time stamp of the data reports), which `Hosted` does not hand to the service.
pub struct RangeSensorService<S> {
    imp: Ranges<S>,
    machines: generated::Machines,
}

impl<S> fmt::Debug for RangeSensorService<S> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("RangeSensorService")
            .field("imp", &self.imp)
            .field("machines", &self.machines)
            .finish()
    }
}

impl<S: RangeScanner> RangeSensorService<S> {
    /// The service over `scanner`, its machines not started (they follow the Core's at
    /// the first message).
    pub fn new(scanner: S) -> Self {
        Self {
            imp: Ranges {
                scanner,
                name: "range scanner".into(),
                now: None,
                stamp: None,
                beams: Vec::new(),
                outbox: Outbox::new(),
            },
            machines: generated::Machines::new(),
        }
    }

    /// Named `name` in Report Range Sensor Capabilities (at most 255 bytes kept; default
    /// "range scanner").
    pub fn with_name(mut self, name: &str) -> Self {
        let mut end = name.len().min(255);
        while !name.is_char_boundary(end) {
            end -= 1;
        }
        self.imp.name = name[..end].to_string();
        self
    }

    /// The scanner.
    pub fn scanner(&self) -> &S {
        &self.imp.scanner
    }
}

impl<S: RangeScanner> GeneratedService for RangeSensorService<S> {
    fn id(&self) -> ServiceId {
        ServiceIds::RANGE_SENSOR
    }

    fn receives(&self, code: CommandCode) -> bool {
        generated::RECEIVES.contains(&code)
    }

    fn follow(&mut self, core_state: &'static str) {
        self.machines.follow(&mut self.imp, core_state);
    }

    fn receive(&mut self, core: &mut Host<'_>, message: &Message, transport: &Receive) -> Taken {
        let Some(trigger) = generated::Trigger::received(message, transport) else {
            return Taken::NotMine;
        };
        let now = core.now();
        self.imp.now = Some(now);
        self.imp.stamp = core
            .others_ref()
            .and_then(|o| o.time.stamps(now))
            .map(|(t, _)| t);
        if self.machines.handle(&mut self.imp, core, &trigger) {
            Taken::Taken
        } else {
            Taken::NoTransition(self.machines.0.iter().next().map_or("", |m| m.path()))
        }
    }

    fn take_output(&mut self) -> Vec<Outgoing> {
        self.imp.outbox.take()
    }

    fn states(&self) -> Vec<(&'static str, &'static str)> {
        self.machines
            .0
            .iter()
            .map(|m| (m.def().name, m.path()))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> ScannerSpec {
        ScannerSpec {
            first_bearing: -PI / 2.0,
            last_bearing: PI / 2.0,
            beams: 3,
            max_range: 20.0,
            range_noise: 0.01,
            mount: (1.0, 0.0),
        }
    }

    fn beams() -> Vec<Beam> {
        vec![
            Beam {
                bearing: -PI / 2.0,
                range: None,
            },
            Beam {
                bearing: 0.0,
                range: Some(4.0),
            },
            Beam {
                bearing: f64::NAN,
                range: Some(1.0),
            },
            Beam {
                bearing: 0.5,
                range: Some(f64::INFINITY),
            },
        ]
    }

    #[test]
    fn beams_become_points_native_or_moved_to_the_vehicle() {
        let s = spec();
        let (p, system) = points_of(
            &beams(),
            Some(&s),
            CoordinateSystemEnum::NativeCoordinateSystem,
            Asked(0x7f),
        );
        assert_eq!(system, CoordinateSystemEnum::NativeCoordinateSystem);
        // The beam without a bearing is left out; no return reads the farthest range.
        assert_eq!(p.len(), 3);
        assert_eq!(
            (p[0].range, p[0].range_validity),
            (20.0, Some(RangeValidity::False))
        );
        assert_eq!(
            (p[1].range, p[1].range_validity),
            (4.0, Some(RangeValidity::True))
        );
        assert_eq!((p[1].point_id, p[2].point_id), (Some(1), Some(3)));
        assert_eq!(p[2].range_validity, Some(RangeValidity::False));
        assert_eq!(p[1].range_error_rms, Some(0.01));
        // In the vehicle's frame: 1 m further forward.
        let (p, system) = points_of(
            &beams(),
            Some(&s),
            CoordinateSystemEnum::VehicleCoordinateSystem,
            Asked(0),
        );
        assert_eq!(system, CoordinateSystemEnum::VehicleCoordinateSystem);
        assert!((p[1].range - 5.0).abs() < 1e-12 && p[1].bearing.abs() < 1e-12);
        assert_eq!((p[1].point_id, p[1].range_validity), (None, None));
        // Without a spec: native, a beam without a return reads 0.
        let (p, system) = points_of(
            &beams(),
            None,
            CoordinateSystemEnum::VehicleCoordinateSystem,
            Asked(0),
        );
        assert_eq!(system, CoordinateSystemEnum::NativeCoordinateSystem);
        assert_eq!(p[0].range, 0.0);
        // Every point encodes, counted.
        let bytes = encoded_points(&p).unwrap();
        assert_eq!(&bytes[..2], &[3, 0]);
    }

    #[test]
    fn angles_wrap_into_the_fields_range() {
        assert!((wrap(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-12);
        assert!((wrap(-PI) + PI).abs() < 1e-12 || (wrap(-PI) - PI).abs() < 1e-12);
        assert_eq!(wrap(f64::NAN), 0.0);
        assert_eq!(wire_range(-1.0), 0.0);
        assert_eq!(wire_range(f64::NAN), 0.0);
    }
}
