//! The Digital Video service (and the Visual Sensor it extends) over an RA 3.3 Visual
//! Sensor: while the controlling client has the stream playing, the service asks the
//! RA 3.3 sensor for an image at the configured frame rate (Query Image, one asked at a
//! time), makes each image a baseline JPEG frame (an RA 3.3 JPEG as it is; PNG and PPM
//! decoded and encoded) and publishes it to the node's [`VideoHub`], from which the
//! node's stream transport serves it (MJPEG: the only format offered). The standard
//! leaves the stream's transport to the implementation; this service only decides what
//! frames there are and when.
//!
//! Bounds: the frame rate within 1..=[`VideoLimits::max_frame_rate`] (a rate above is
//! refused, sensor by sensor, in Confirm Sensor Configuration); one image asked at a
//! time (a due frame while one is awaited is not asked again; the image is asked anew
//! after [`WAIT`]); frames over [`VideoLimits::max_frame_bytes`] dropped and counted;
//! the hub holds one frame per stream. The stream belongs to the client that started
//! it: when that client no longer holds control of the component, it stops.

use std::time::{Duration, Instant};

use jaus::messages as ra;
use jaus::net::as5669a::As4Id;
use jaus::stock::environment::image;
use jaus::{Address, JausMessage};

use super::visual::OverVisualSensor;
use super::{ServiceIds, SENSOR_ID};
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::digital_video as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{
    ConfirmSensorConfiguration, ConfirmSensorConfigurationVariant as Confirmed,
    ConfirmSensorConfigurationVariantDigitalVideoSensorErrorRec as VideoError,
    ConfirmSensorConfigurationVariantDigitalVideoSensorErrorRecErrorCode as VideoCode,
    ControlDigitalVideoSensorStream, ControlDigitalVideoSensorStreamStreamState as Wanted,
    DigitalFormatEnum, DigitalVideoSensorConfigurationRec, QueryDigitalVideoSensorCapabilities,
    QueryDigitalVideoSensorConfiguration, ReportDigitalVideoSensorCapabilities,
    ReportDigitalVideoSensorCapabilitiesRec,
    ReportDigitalVideoSensorCapabilitiesRecSupportedDigitalFormats as Formats,
    ReportDigitalVideoSensorConfiguration, SensorIdRec, SetDigitalVideoSensorConfiguration,
};
use crate::outgoing::sender_of;
use crate::ra33::Ra33Side;
use crate::service::Cx;

mod hub;

pub use hub::{Frame, Next, StreamState, StreamStats, VideoHub, Viewer, WatchError};

/// How long an asked image is awaited before it is asked again.
pub const WAIT: Duration = Duration::from_secs(2);

/// An image decoded for transcoding takes this many bytes as RGB at most.
const MAX_DECODED_BYTES: usize = 32 << 20;

/// A stream's bounds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct VideoLimits {
    /// The highest frame rate a client may ask for, frames/s (at least 1).
    pub max_frame_rate: u8,
    /// A frame larger than this is dropped (counted), bytes.
    pub max_frame_bytes: usize,
}

impl Default for VideoLimits {
    /// 10 frames/s, 1 MiB a frame.
    fn default() -> Self {
        Self {
            max_frame_rate: 10,
            max_frame_bytes: 1 << 20,
        }
    }
}

machined!(
    Video,
    digital_video,
    ServiceIds::DIGITAL_VIDEO,
    access_control {
        fn tick(&mut self, cx: &mut Cx<'_, Ra33Side>) {
            self.run(cx);
        }

        fn poll_timeout(&self) -> Option<Instant> {
            match self.state {
                StreamState::Playing => Some(self.next_due),
                _ => None,
            }
        }
    }
);

/// The Digital Video service over an RA 3.3 Visual Sensor.
pub type DigitalVideo = OnMachines<Video>;

/// The Digital Video service's data: the RA 3.3 sensor, the stream's settings and state.
#[derive(Debug)]
pub struct Video {
    sensor: Address,
    hub: VideoHub,
    limits: VideoLimits,
    frame_rate: u8,
    state: StreamState,
    /// The client that started the stream.
    owner: Option<As4Id>,
    /// When the next frame is due (while playing).
    next_due: Instant,
    /// When the image awaited was asked for.
    asked: Option<Instant>,
}

impl DigitalVideo {
    /// The service over the RA 3.3 Visual Sensor at `sensor`, its frames published to
    /// `hub` as sensor [`SENSOR_ID`]'s, within `limits`; the stream stopped, at half
    /// the highest rate.
    pub fn new(sensor: Address, hub: VideoHub, limits: VideoLimits) -> Self {
        hub.add_stream(SENSOR_ID);
        let max = limits.max_frame_rate.max(1);
        OnMachines::from_impl(Video {
            sensor,
            hub,
            limits: VideoLimits {
                max_frame_rate: max,
                ..limits
            },
            frame_rate: max.div_ceil(2),
            state: StreamState::Stopped,
            owner: None,
            next_due: Instant::now(),
            asked: None,
        })
    }
}

impl OverVisualSensor for Video {
    fn visual_sensor(&self) -> Address {
        self.sensor
    }
}

impl Video {
    fn set_state(&mut self, state: StreamState, why: &str) {
        if state != self.state {
            tracing::info!(sensor = SENSOR_ID, ra33 = %self.sensor, from = ?self.state, to = ?state,
                "Digital Video stream: {why}");
        }
        self.state = state;
        if state == StreamState::Stopped {
            self.owner = None;
            self.asked = None;
        }
        self.hub.set_state(SENSOR_ID, state);
    }

    fn period(&self) -> Duration {
        Duration::from_secs(1) / u32::from(self.frame_rate.max(1))
    }

    /// While playing: the stream stops if its client lost control; an image asked for
    /// that came is published; a frame due is asked for.
    fn run(&mut self, cx: &mut Cx<'_, Ra33Side>) {
        if self.state == StreamState::Stopped {
            return;
        }
        if self.owner.is_some() && cx.controller != self.owner {
            return self.set_state(
                StreamState::Stopped,
                "the client that started it no longer controls the component",
            );
        }
        let now = cx.now;
        if let Some(asked) = self.asked {
            if let Some((at, ra::Message::ReportImage(r))) =
                cx.env.latest(self.sensor, ra::ReportImage::CODE)
            {
                if at >= asked {
                    self.asked = None;
                    if self.state == StreamState::Playing {
                        let frame = self.frame_of(r);
                        match frame {
                            Ok(jpeg) => self.hub.publish(SENSOR_ID, at, jpeg),
                            Err(why) => {
                                self.hub.dropped(SENSOR_ID);
                                tracing::warn!(ra33 = %self.sensor, "Digital Video: an RA 3.3 Report Image dropped: {why}");
                            }
                        }
                    }
                }
            }
            if self
                .asked
                .is_some_and(|t| now.saturating_duration_since(t) >= WAIT)
            {
                tracing::warn!(ra33 = %self.sensor, "Digital Video: no Report Image within {WAIT:?}; asking again");
                self.asked = None;
            }
        }
        if self.state == StreamState::Playing && now >= self.next_due {
            if self.asked.is_none() {
                cx.env.send(self.sensor, ra::QueryImage {});
                self.asked = Some(now);
            }
            self.next_due += self.period();
            if self.next_due <= now {
                // Late (a slow tick): no burst to catch up.
                self.next_due = now + self.period();
            }
        }
    }

    /// An RA 3.3 image as a JPEG frame within the limits.
    fn frame_of(&self, r: &ra::ReportImage) -> Result<Vec<u8>, String> {
        let jpeg = match r.video_format {
            ra::ImageFormat::Jpeg => r.data.clone(),
            f @ (ra::ImageFormat::Png | ra::ImageFormat::Ppm) => {
                let rgb =
                    image::decode(f, &r.data, MAX_DECODED_BYTES).map_err(|e| e.to_string())?;
                image::encode(&rgb, ra::ImageFormat::Jpeg).map_err(|e| e.to_string())?
            }
            other => {
                return Err(format!(
                    "{other:?} images are not made JPEG frames (JPEG, PNG and PPM are)"
                ))
            }
        };
        if jpeg.len() > self.limits.max_frame_bytes {
            return Err(format!(
                "a {}-byte frame is over the {}-byte limit",
                jpeg.len(),
                self.limits.max_frame_bytes
            ));
        }
        Ok(jpeg)
    }

    /// The configuration of sensor [`SENSOR_ID`].
    fn configuration(&self) -> DigitalVideoSensorConfigurationRec {
        DigitalVideoSensorConfigurationRec {
            sensor_id: SENSOR_ID,
            frame_rate: Some(self.frame_rate),
            digital_format: Some(DigitalFormatEnum::Mjpeg),
            ..Default::default()
        }
    }

    /// Applies `r` (all of it, or nothing) or says why not.
    fn configure(&mut self, r: &DigitalVideoSensorConfigurationRec) -> Confirmed {
        let mut refused: Vec<(VideoCode, String)> = Vec::new();
        if r.sensor_id != SENSOR_ID {
            refused.push((VideoCode::UnknownSensorId, "no such sensor".into()));
        }
        if r.minimum_bit_rate.is_some() {
            refused.push((
                VideoCode::InvalidMinimumBitRate,
                "the bit rate follows from the frame rate (MJPEG)".into(),
            ));
        }
        if r.maximum_bit_rate.is_some() {
            refused.push((
                VideoCode::InvalidMaximumBitRate,
                "the bit rate follows from the frame rate (MJPEG)".into(),
            ));
        }
        let max = self.limits.max_frame_rate;
        match r.frame_rate {
            Some(0) => refused.push((
                VideoCode::InvalidMinimumFrameRate,
                "frame rate 0; Pause or Stop the stream instead".into(),
            )),
            Some(f) if f > max => refused.push((
                VideoCode::InvalidMaximumFrameRate,
                format!("frame rate {f} over the highest, {max} frames/s"),
            )),
            _ => {}
        }
        if r.frame_size.is_some() {
            refused.push((
                VideoCode::InvalidFrameSize,
                "the RA 3.3 visual sensor's frame size is its own".into(),
            ));
        }
        if r.digital_format
            .is_some_and(|f| f != DigitalFormatEnum::Mjpeg)
        {
            refused.push((VideoCode::InvalidFormat, "MJPEG only".into()));
        }
        let sensor_id = r.sensor_id;
        match refused.len() {
            0 => {
                if let Some(f) = r.frame_rate {
                    self.frame_rate = f;
                }
                Confirmed::SensorIdRec(SensorIdRec { sensor_id })
            }
            1 => {
                let (code, why) = refused.remove(0);
                Confirmed::DigitalVideoSensorErrorRec(VideoError {
                    sensor_id,
                    digital_video_error_code: code,
                    error_message: why,
                })
            }
            _ => {
                let why: Vec<String> = refused.into_iter().map(|(_, w)| w).collect();
                let mut error_message = why.join("; ");
                // The message's string is counted by a u8.
                let mut end = error_message.len().min(255);
                while !error_message.is_char_boundary(end) {
                    end -= 1;
                }
                error_message.truncate(end);
                Confirmed::DigitalVideoSensorErrorRec(VideoError {
                    sensor_id,
                    digital_video_error_code: VideoCode::MultipleInvalidParameters,
                    error_message,
                })
            }
        }
    }
}

impl generated::DigitalVideo for On<'_, Video> {
    fn send_report_digital_video_sensor_capabilities(
        &mut self,
        msg: &QueryDigitalVideoSensorCapabilities,
        transport: &Receive,
    ) {
        let max = self.svc.limits.max_frame_rate;
        let list = msg
            .query_digital_video_sensor_capabilities_list
            .iter()
            .filter(|r| r.sensor_id == SENSOR_ID)
            .map(|_| ReportDigitalVideoSensorCapabilitiesRec {
                sensor_id: SENSOR_ID,
                minimum_frame_rate: Some(1),
                maximum_frame_rate: Some(max),
                supported_digital_formats: Some(Formats {
                    mjpeg: true,
                    ..Default::default()
                }),
                ..Default::default()
            })
            .collect();
        self.reply(
            transport,
            ReportDigitalVideoSensorCapabilities {
                digital_video_sensor_list: list,
            },
        );
    }

    fn send_report_digital_video_sensor_configuration(
        &mut self,
        msg: &QueryDigitalVideoSensorConfiguration,
        transport: &Receive,
    ) {
        let list = msg
            .query_digital_video_configuration_list
            .iter()
            .filter(|r| r.sensor_id == SENSOR_ID)
            .map(|_| self.svc.configuration())
            .collect();
        self.reply(
            transport,
            ReportDigitalVideoSensorConfiguration {
                digital_video_sensor_configuration_list: list,
            },
        );
    }

    fn update_digital_video_sensor_configuration(
        &mut self,
        msg: &SetDigitalVideoSensorConfiguration,
        transport: &Receive,
    ) {
        let confirm_sensor_list = msg
            .digital_video_sensor_list
            .iter()
            .map(|r| self.svc.configure(r))
            .collect();
        self.reply(
            transport,
            ConfirmSensorConfiguration {
                request_id_rec: msg.request_id_rec.clone(),
                confirm_sensor_list,
            },
        );
    }

    fn modify_digital_video_sensor_stream(
        &mut self,
        msg: &ControlDigitalVideoSensorStream,
        transport: &Receive,
    ) {
        if msg.sensor_id != SENSOR_ID {
            return self.refuse(format!("no video sensor {}", msg.sensor_id));
        }
        let v = &mut *self.svc;
        match msg.stream_state {
            Wanted::Play => {
                if v.state != StreamState::Playing {
                    v.next_due = self.now;
                }
                v.owner = Some(sender_of(transport));
                v.set_state(StreamState::Playing, "played by its controlling client");
            }
            Wanted::Pause => v.set_state(StreamState::Paused, "paused by its controlling client"),
            Wanted::Stop => v.set_state(StreamState::Stopped, "stopped by its controlling client"),
            Wanted::Unknown(x) => {
                self.refuse(format!("stream state {x} is none of Play, Pause, Stop"))
            }
        }
    }
}
