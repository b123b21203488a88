//! The Still Image service (and the Visual Sensor it extends) over an RA 3.3 Visual
//! Sensor: an image is the RA 3.3 sensor's Report Image, asked for when an AS-4 client
//! asks (rendering or grabbing a frame costs; nothing is polled). A query finds an image
//! younger than [`FRESH`] answered at once; else the RA 3.3 sensor is asked and the
//! query waits for its image ([`MAX_WAITING`] queries at most, each [`WAIT`] at most:
//! then refused, logged).

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use jaus::messages as ra;
use jaus::net::as5669a::As4Id;
use jaus::{Address, JausMessage};

use super::{ServiceIds, SENSOR_ID};
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::still_image as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{
    ConfirmSensorConfiguration, ConfirmSensorConfigurationVariant as Confirmed,
    ConfirmSensorConfigurationVariantStillImageSensorErrorRec as StillImageError,
    ConfirmSensorConfigurationVariantStillImageSensorErrorRecErrorCode as StillImageCode,
    CoordinateSystemEnum, QueryStillImageData, QueryStillImageSensorCapabilities,
    QueryStillImageSensorConfiguration, ReportStillImageData, ReportStillImageDataRec,
    ReportStillImageSensorCapabilities, ReportStillImageSensorCapabilitiesRec,
    ReportStillImageSensorCapabilitiesRecSupportedImageFormats as ImageFormats,
    ReportStillImageSensorConfiguration, SensorIdRec, SetStillImageSensorConfiguration,
    StillImageFormatEnum, StillImageSensorConfigurationRec,
};
use crate::outgoing::sender_of;
use crate::ra33::Ra33Side;
use crate::service::{Cx, Outgoing};

/// An image at most this old answers a query at once.
pub const FRESH: Duration = Duration::from_millis(500);
/// How long a query waits for the RA 3.3 sensor's image.
pub const WAIT: Duration = Duration::from_secs(3);
/// Queries waiting for an image at most (more are refused).
pub const MAX_WAITING: usize = 16;

machined!(
    Images,
    still_image,
    ServiceIds::STILL_IMAGE,
    access_control {
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            self.answer_waiting(cx);
        }
    }
);

/// The Still Image service over an RA 3.3 Visual Sensor.
pub type StillImage = OnMachines<Images>;

/// The Still Image service's data: the RA 3.3 sensor, the queries waiting for its image.
#[derive(Debug)]
pub struct Images {
    sensor: Address,
    /// Who asked, since when.
    waiting: VecDeque<(As4Id, Instant)>,
}

impl StillImage {
    /// The service over the RA 3.3 Visual Sensor at `sensor`.
    pub fn new(sensor: Address) -> Self {
        OnMachines::from_impl(Images {
            sensor,
            waiting: VecDeque::new(),
        })
    }
}

impl Images {
    /// Answers the queries waiting once the RA 3.3 image asked for them came; refuses
    /// (logs) those waiting longer than [`WAIT`].
    fn answer_waiting(&mut self, cx: &mut Cx<'_, Ra33Side>) {
        let Some(&(_, first)) = self.waiting.front() else {
            return;
        };
        let now = cx.now;
        match latest_image(cx.env, self.sensor) {
            Some((at, format, data)) if at >= first => {
                let report = report_of(format, data);
                for (to, _) in self.waiting.drain(..) {
                    cx.send(Outgoing::new(to, report.clone()));
                }
            }
            _ => {
                while let Some(&(to, since)) = self.waiting.front() {
                    if now.saturating_duration_since(since) < WAIT {
                        break;
                    }
                    self.waiting.pop_front();
                    tracing::warn!(client = %to, sensor = %self.sensor,
                        "Query Still Image Data: no image from the RA 3.3 visual sensor within {WAIT:?}");
                }
            }
        }
    }
}

/// The RA 3.3 sensor's latest image: when it came, its AS-4 format, the bytes.
fn latest_image(env: &Ra33Side, sensor: Address) -> Option<(Instant, StillImageFormatEnum, &[u8])> {
    match env.latest(sensor, ra::ReportImage::CODE) {
        Some((at, ra::Message::ReportImage(r))) => {
            still_format(r.video_format).map(|f| (at, f, r.data.as_slice()))
        }
        _ => None,
    }
}

/// Report Still Image Data of one image of [`SENSOR_ID`], in its native frame.
fn report_of(format: StillImageFormatEnum, data: &[u8]) -> ReportStillImageData {
    ReportStillImageData {
        still_image_data_list: vec![ReportStillImageDataRec {
            sensor_id: SENSOR_ID,
            report_coordinate_system: CoordinateSystemEnum::NativeCoordinateSystem,
            time_stamp: None,
            image_frame_format: format.to_repr(),
            image_frame: data.to_vec(),
        }],
    }
}

/// The AS-4 still image format of an RA 3.3 image format, if it has one.
fn still_format(f: ra::ImageFormat) -> Option<StillImageFormatEnum> {
    Some(match f {
        ra::ImageFormat::Jpeg => StillImageFormatEnum::Jpeg,
        ra::ImageFormat::Gif => StillImageFormatEnum::Gif,
        ra::ImageFormat::Png => StillImageFormatEnum::Png,
        ra::ImageFormat::Bmp => StillImageFormatEnum::Bmp,
        ra::ImageFormat::Tiff => StillImageFormatEnum::Tiff,
        ra::ImageFormat::Ppm => StillImageFormatEnum::Ppm,
        ra::ImageFormat::Pgm => StillImageFormatEnum::Pgm,
        _ => return None,
    })
}

impl On<'_, Images> {
    /// The format the images come in (PNG until the first image says otherwise).
    fn format(&self) -> StillImageFormatEnum {
        latest_image(self.env, self.svc.sensor).map_or(StillImageFormatEnum::Png, |(_, f, _)| f)
    }
}

impl super::visual::OverVisualSensor for Images {
    fn visual_sensor(&self) -> Address {
        self.sensor
    }
}

impl generated::StillImage for On<'_, Images> {
    fn is_coordinate_transform_supported(&self, msg: &QueryStillImageData) -> bool {
        // Images are only in the sensor's own frame.
        msg.query_still_image_data_list
            .iter()
            .all(|r| r.report_coordinate_system == CoordinateSystemEnum::NativeCoordinateSystem)
    }

    fn send_report_still_image_data(&mut self, msg: &QueryStillImageData, transport: &Receive) {
        if !msg
            .query_still_image_data_list
            .iter()
            .any(|r| r.sensor_id == SENSOR_ID)
        {
            // No sensor of ours asked: no image, as the other queries answer an empty
            // list for ids they do not know.
            let none = ReportStillImageData {
                still_image_data_list: Vec::new(),
            };
            return self.reply(transport, none);
        }
        let now = self.now;
        if let Some((at, format, data)) = latest_image(self.env, self.svc.sensor) {
            if now.saturating_duration_since(at) <= FRESH {
                let report = report_of(format, data);
                return self.reply(transport, report);
            }
        }
        if self.svc.waiting.len() >= MAX_WAITING {
            return self.refuse(format!(
                "{MAX_WAITING} queries already wait for the RA 3.3 visual sensor's image"
            ));
        }
        // Asked once for every query waiting.
        if self.svc.waiting.is_empty() {
            let sensor = self.svc.sensor;
            self.env.send(sensor, ra::QueryImage {});
        }
        self.svc.waiting.push_back((sender_of(transport), now));
    }

    fn send_report_still_image_sensor_capabilities(
        &mut self,
        msg: &QueryStillImageSensorCapabilities,
        transport: &Receive,
    ) {
        let format = self.format();
        let list = msg
            .query_still_image_sensor_capabilities_list
            .iter()
            .filter(|r| r.sensor_id == SENSOR_ID)
            .map(|_| {
                let mut formats = ImageFormats::default();
                match format {
                    StillImageFormatEnum::Jpeg => formats.jpeg = true,
                    StillImageFormatEnum::Gif => formats.gif = true,
                    StillImageFormatEnum::Bmp => formats.bmp = true,
                    StillImageFormatEnum::Tiff => formats.tiff = true,
                    StillImageFormatEnum::Ppm => formats.ppm = true,
                    StillImageFormatEnum::Pgm => formats.pgm = true,
                    _ => formats.png = true,
                }
                ReportStillImageSensorCapabilitiesRec {
                    sensor_id: SENSOR_ID,
                    supported_frame_sizes: None,
                    supported_image_formats: Some(formats),
                }
            })
            .collect();
        self.reply(
            transport,
            ReportStillImageSensorCapabilities {
                still_image_sensor_list: list,
            },
        );
    }

    fn send_report_still_image_sensor_configuration(
        &mut self,
        msg: &QueryStillImageSensorConfiguration,
        transport: &Receive,
    ) {
        let format = self.format();
        let list = msg
            .query_still_image_sensor_configuration_list
            .iter()
            .filter(|r| r.sensor_id == SENSOR_ID)
            .map(|_| StillImageSensorConfigurationRec {
                sensor_id: SENSOR_ID,
                frame_size: None,
                still_image_format: Some(format),
            })
            .collect();
        self.reply(
            transport,
            ReportStillImageSensorConfiguration {
                still_image_sensor_configuration_list: list,
            },
        );
    }

    fn update_still_image_sensor_configuration(
        &mut self,
        msg: &SetStillImageSensorConfiguration,
        transport: &Receive,
    ) {
        // The RA 3.3 sensor's format is the only one: asked for, it is accepted.
        let format = self.format();
        let confirm_sensor_list = msg
            .still_image_sensor_list
            .iter()
            .map(|r| {
                let refuse = |code, why: String| {
                    Confirmed::StillImageSensorErrorRec(StillImageError {
                        sensor_id: r.sensor_id,
                        still_image_error_code: code,
                        error_message: why,
                    })
                };
                if r.sensor_id != SENSOR_ID {
                    refuse(StillImageCode::UnknownSensorId, "no such sensor".into())
                } else if r.frame_size.is_some() {
                    refuse(
                        StillImageCode::InvalidFrameSize,
                        "the RA 3.3 visual sensor's frame size is fixed".into(),
                    )
                } else if r.still_image_format.is_some_and(|f| f != format) {
                    refuse(
                        StillImageCode::InvalidFormat,
                        format!("the RA 3.3 visual sensor gives {format:?} only"),
                    )
                } else {
                    Confirmed::SensorIdRec(SensorIdRec {
                        sensor_id: r.sensor_id,
                    })
                }
            })
            .collect();
        self.reply(
            transport,
            ConfirmSensorConfiguration {
                request_id_rec: msg.request_id_rec.clone(),
                confirm_sensor_list,
            },
        );
    }
}
