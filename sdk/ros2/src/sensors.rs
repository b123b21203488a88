//! The robot's lidar and camera: `sensor_msgs/LaserScan` as the sweeps of the stock
//! Range Sensor (50, [`ScanSource`]) and `sensor_msgs/Image` (or a PNG
//! `sensor_msgs/CompressedImage`) as the frames of the stock Visual Sensor (37,
//! [`RosCamera`]).
//!
//! Frames: the laser's frame is taken as the platform's (no TF: a lidar mounted
//! upright, facing forward). ROS angles grow counter-clockwise (to the left, REP-103);
//! a JAUS bearing grows to the right, so bearing = −angle, wrapped to (−π, π]. A range
//! outside `[range_min, range_max]`, infinite or NaN is no return (`None`).
//!
//! Bounds: a sweep of more than [`MAX_BEAMS`] beams, an image wider or taller than
//! [`MAX_IMAGE_SIDE`] or larger than [`Sensors::max_image_bytes`], an encoding or format
//! not handled, a `step` shorter than a row or data shorter than the rows: the message
//! is dropped, counted ([`BridgeStats`](crate::BridgeStats)`::scans_refused`,
//! `images_refused`) and logged with the reason. Nothing a ROS node sends panics.

use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use jaus::stock::environment::camera::{CameraSettings, CameraSpec, Cameras};
use jaus::stock::environment::image::RgbImage;
use jaus::stock::environment::scan::{Beam, RangeScanner};
use jaus::stock::nalgebra::Vector3;

use crate::config::{Ros2Config, Sensors, MAX_BEAMS, MAX_IMAGE_SIDE};
use crate::msg::{CompressedImage, Image, LaserScan};
use crate::state::{lock, Frame, Shared, Tap};

/// Why a scan or an image was dropped.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SensorError {
    /// A sweep with more beams than [`MAX_BEAMS`].
    #[error("{beams} beams, more than {MAX_BEAMS}")]
    TooManyBeams {
        /// Beams in the message.
        beams: usize,
    },
    /// Angles or range limits a sweep cannot have.
    #[error("{0}")]
    BadScan(&'static str),
    /// A pixel encoding not handled (rgb8, bgr8, rgba8, bgra8, mono8, mono16 are).
    #[error("encoding {0:?} not handled (rgb8, bgr8, rgba8, bgra8, mono8, mono16 are)")]
    Encoding(String),
    /// A compressed format not handled (PNG is).
    #[error("compressed format {0:?} not handled (png is)")]
    Format(String),
    /// No pixels.
    #[error("an empty {width}×{height} image")]
    Empty {
        /// Width.
        width: u32,
        /// Height.
        height: u32,
    },
    /// Over [`MAX_IMAGE_SIDE`] or the configured byte limit.
    #[error("a {width}×{height} image of {bytes} bytes is over the limit ({MAX_IMAGE_SIDE} pixels a side, {limit} bytes)")]
    TooLarge {
        /// Width.
        width: u32,
        /// Height.
        height: u32,
        /// Bytes given, or the decoded RGB size when that is larger.
        bytes: usize,
        /// The configured limit.
        limit: usize,
    },
    /// `step` shorter than a row of pixels.
    #[error("step {step} is shorter than a row ({row} bytes)")]
    Step {
        /// The message's step.
        step: usize,
        /// Bytes of one row's pixels.
        row: usize,
    },
    /// Fewer bytes than the rows need.
    #[error("{len} bytes of data, {needed} needed")]
    Short {
        /// Bytes given.
        len: usize,
        /// Bytes needed.
        needed: usize,
    },
    /// The PNG did not decode.
    #[error("PNG: {0}")]
    Png(String),
}

/// `angle` wrapped to (−π, π].
fn wrap(angle: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let w = angle.rem_euclid(TAU);
    if w > PI {
        w - TAU
    } else {
        w
    }
}

/// The beams of a sweep in the SDK's platform frame (bearing positive to the right),
/// into `out` (cleared first), ordered left to right.
pub fn scan_to_beams(s: &LaserScan, out: &mut Vec<Beam>) -> Result<(), SensorError> {
    out.clear();
    let n = s.ranges.len();
    if n > MAX_BEAMS {
        return Err(SensorError::TooManyBeams { beams: n });
    }
    let (a0, da) = (f64::from(s.angle_min), f64::from(s.angle_increment));
    let (lo, hi) = (f64::from(s.range_min), f64::from(s.range_max));
    if !(a0.is_finite() && da.is_finite()) {
        return Err(SensorError::BadScan(
            "angle_min or angle_increment is not finite",
        ));
    }
    if !(lo.is_finite() && hi.is_finite() && lo >= 0.0 && hi > lo) {
        return Err(SensorError::BadScan(
            "range_min and range_max are not finite with 0 ≤ range_min < range_max",
        ));
    }
    out.reserve(n);
    // ROS beams go counter-clockwise (right to left): reversed, they go left to right.
    for (i, r) in s.ranges.iter().enumerate().rev() {
        let r = f64::from(*r);
        out.push(Beam {
            bearing: wrap(-(a0 + da * i as f64)),
            range: (r.is_finite() && r >= lo && r <= hi).then_some(r),
        });
    }
    Ok(())
}

/// The pixel encodings of `sensor_msgs/Image` taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Encoding {
    Rgb8,
    Bgr8,
    Rgba8,
    Bgra8,
    Mono8,
    Mono16 { big_endian: bool },
}

impl Encoding {
    fn of(i: &Image) -> Result<Encoding, SensorError> {
        Ok(match i.encoding.as_str() {
            "rgb8" => Encoding::Rgb8,
            "bgr8" => Encoding::Bgr8,
            "rgba8" => Encoding::Rgba8,
            "bgra8" => Encoding::Bgra8,
            "mono8" | "8UC1" => Encoding::Mono8,
            "mono16" | "16UC1" => Encoding::Mono16 {
                big_endian: i.is_bigendian != 0,
            },
            other => return Err(SensorError::Encoding(other.into())),
        })
    }

    fn bytes_per_pixel(self) -> usize {
        match self {
            Encoding::Rgb8 | Encoding::Bgr8 => 3,
            Encoding::Rgba8 | Encoding::Bgra8 => 4,
            Encoding::Mono8 => 1,
            Encoding::Mono16 { .. } => 2,
        }
    }

    fn rgb(self, p: &[u8]) -> [u8; 3] {
        match self {
            Encoding::Rgb8 | Encoding::Rgba8 => [p[0], p[1], p[2]],
            Encoding::Bgr8 | Encoding::Bgra8 => [p[2], p[1], p[0]],
            Encoding::Mono8 => [p[0]; 3],
            // The high byte.
            Encoding::Mono16 { big_endian: true } => [p[0]; 3],
            Encoding::Mono16 { big_endian: false } => [p[1]; 3],
        }
    }
}

/// Checks the size of a `width` × `height` image of `bytes` bytes against the limits.
fn check_size(width: u32, height: u32, bytes: usize, limit: usize) -> Result<(), SensorError> {
    if width == 0 || height == 0 {
        return Err(SensorError::Empty { width, height });
    }
    let rgb = (width as usize) * (height as usize) * 3;
    if width > MAX_IMAGE_SIDE || height > MAX_IMAGE_SIDE || bytes.max(rgb) > limit {
        return Err(SensorError::TooLarge {
            width,
            height,
            bytes: bytes.max(rgb),
            limit,
        });
    }
    Ok(())
}

/// Checks that `i` can be converted (encoding, size, step, data), without converting.
pub fn check_image(i: &Image, max_bytes: usize) -> Result<(), SensorError> {
    let e = Encoding::of(i)?;
    check_size(i.width, i.height, i.data.len(), max_bytes)?;
    let (w, h, step) = (i.width as usize, i.height as usize, i.step as usize);
    let row = w * e.bytes_per_pixel();
    if step < row {
        return Err(SensorError::Step { step, row });
    }
    let needed = step.saturating_mul(h - 1).saturating_add(row);
    if i.data.len() < needed {
        return Err(SensorError::Short {
            len: i.data.len(),
            needed,
        });
    }
    Ok(())
}

/// `h` rows of `w` pixels, `step` bytes apart in `data`, as RGB.
fn rows_to_rgb(
    data: &[u8],
    (w, h, step): (usize, usize, usize),
    bpp: usize,
    pixel: impl Fn(&[u8]) -> [u8; 3],
) -> Result<Vec<u8>, SensorError> {
    let row = w * bpp;
    let mut out = Vec::with_capacity(w * h * 3);
    for y in 0..h {
        let start = y.saturating_mul(step);
        let end = start.saturating_add(row);
        let r = data.get(start..end).ok_or(SensorError::Short {
            len: data.len(),
            needed: end,
        })?;
        for p in r.chunks_exact(bpp) {
            out.extend_from_slice(&pixel(p));
        }
    }
    Ok(out)
}

/// An image as RGB (row padding of `step` dropped, BGR swapped, grey replicated, alpha
/// dropped, 16-bit grey to its high byte).
pub fn image_to_rgb(i: &Image, max_bytes: usize) -> Result<RgbImage, SensorError> {
    check_image(i, max_bytes)?;
    let e = Encoding::of(i)?;
    let pixels = rows_to_rgb(
        &i.data,
        (i.width as usize, i.height as usize, i.step as usize),
        e.bytes_per_pixel(),
        |p| e.rgb(p),
    )?;
    // check_size bounded both sides by MAX_IMAGE_SIDE, within u16.
    Ok(RgbImage {
        width: i.width as u16,
        height: i.height as u16,
        pixels,
    })
}

/// Checks a compressed image's format (PNG: `png`, or image_transport's
/// `<encoding>; png compressed <encoding>`) and size, without decoding.
pub fn check_compressed(c: &CompressedImage, max_bytes: usize) -> Result<(), SensorError> {
    if !c.format.to_ascii_lowercase().contains("png") {
        return Err(SensorError::Format(c.format.clone()));
    }
    if c.data.len() > max_bytes {
        return Err(SensorError::TooLarge {
            width: 0,
            height: 0,
            bytes: c.data.len(),
            limit: max_bytes,
        });
    }
    Ok(())
}

/// A PNG file as RGB (palette and low bit depths expanded, 16 bits to 8, alpha dropped),
/// refused when it would be over the limits before any pixel is decoded
/// (`jaus::stock::environment::image::decode`, then this bridge's own side limit).
pub fn png_to_rgb(data: &[u8], max_bytes: usize) -> Result<RgbImage, SensorError> {
    use jaus::stock::environment::image::{decode, ImageError};
    let img = decode(jaus::messages::ImageFormat::Png, data, max_bytes).map_err(|e| match e {
        ImageError::TooLarge {
            width,
            height,
            bytes,
            limit,
        } => SensorError::TooLarge {
            width,
            height,
            bytes,
            limit,
        },
        other => SensorError::Png(other.to_string()),
    })?;
    check_size(img.width.into(), img.height.into(), data.len(), max_bytes)?;
    Ok(img)
}

/// `img` at `width` × `height` (nearest pixel); as it is when already that size.
pub fn resample(img: RgbImage, width: u16, height: u16) -> RgbImage {
    if (img.width, img.height) == (width, height) || img.width == 0 || img.height == 0 {
        return img;
    }
    let (sw, sh) = (usize::from(img.width), usize::from(img.height));
    let (w, h) = (usize::from(width), usize::from(height));
    let mut pixels = Vec::with_capacity(w * h * 3);
    for y in 0..h {
        let sy = (y * sh / h.max(1)).min(sh - 1);
        for x in 0..w {
            let sx = (x * sw / w.max(1)).min(sw - 1);
            let at = (sy * sw + sx) * 3;
            pixels.extend_from_slice(img.pixels.get(at..at + 3).unwrap_or(&[0; 3]));
        }
    }
    RgbImage {
        width,
        height,
        pixels,
    }
}

/// Logs a dropped scan or image: the first and every 100th of each kind.
fn log_drop(kind: &str, topic: &str, count: u64, e: &SensorError) {
    if count % 100 == 1 {
        tracing::warn!(dropped = count, "jaus-ros2: {kind} on {topic} dropped: {e}");
    }
}

/// A `LaserScan` taken from DDS: converted and kept as the latest sweep, or dropped and
/// counted.
pub(crate) fn on_scan(shared: &Mutex<Shared>, scan: &LaserScan, topic: &str) {
    let mut beams = Vec::new();
    let r = scan_to_beams(scan, &mut beams);
    let mut s = lock(shared);
    match r {
        Ok(()) => {
            s.stats.scans += 1;
            s.scan = Some((beams, Instant::now()));
        }
        Err(e) => {
            s.stats.scans_refused += 1;
            log_drop("scan", topic, s.stats.scans_refused, &e);
        }
    }
}

/// A camera message taken from DDS: checked and kept as the latest frame, or dropped
/// and counted.
pub(crate) fn on_frame(shared: &Mutex<Shared>, frame: Frame, max_bytes: usize, topic: &str) {
    let r = match &frame {
        Frame::Raw(i) => check_image(i, max_bytes),
        Frame::Png(_) => Ok(()),
    };
    let mut s = lock(shared);
    match r {
        Ok(()) => {
            s.stats.images += 1;
            s.image = Some((Arc::new(frame), Instant::now()));
        }
        Err(e) => {
            s.stats.images_refused += 1;
            log_drop("image", topic, s.stats.images_refused, &e);
        }
    }
}

/// A `CompressedImage` taken from DDS.
pub(crate) fn on_compressed(
    shared: &Mutex<Shared>,
    c: CompressedImage,
    max_bytes: usize,
    topic: &str,
) {
    match check_compressed(&c, max_bytes) {
        Ok(()) => on_frame(shared, Frame::Png(c.data), max_bytes, topic),
        Err(e) => {
            let mut s = lock(shared);
            s.stats.images_refused += 1;
            log_drop("image", topic, s.stats.images_refused, &e);
        }
    }
}

/// The Range Sensor's scanner: the latest `scan`, none when older than
/// [`Sensors::max_age_ms`].
#[derive(Debug)]
pub struct ScanSource {
    tap: Tap,
    max_age: Duration,
}

impl ScanSource {
    pub(crate) fn new(tap: Tap, sensors: &Sensors) -> Self {
        ScanSource {
            tap,
            max_age: sensors.max_age(),
        }
    }
}

impl RangeScanner for ScanSource {
    fn scan(&mut self, now: Instant, out: &mut Vec<Beam>) -> bool {
        out.clear();
        let s = lock(&self.tap.shared);
        match &s.scan {
            Some((beams, at)) if now.saturating_duration_since(*at) <= self.max_age => {
                out.extend_from_slice(beams);
                true
            }
            _ => false,
        }
    }
}

/// The Visual Sensor's one camera: the latest image of `image_raw` (or
/// `image_raw/compressed`), none when older than [`Sensors::max_age_ms`], at the size
/// of the camera settings.
#[derive(Debug)]
pub struct RosCamera {
    tap: Tap,
    specs: Vec<CameraSpec>,
    max_age: Duration,
    max_bytes: usize,
    topic: String,
}

impl RosCamera {
    /// The camera of `config` (its spec: [`crate::config::CameraConfig`]) reading
    /// `topic` (its DDS name, for the description and the logs).
    pub(crate) fn new(tap: Tap, config: &Ros2Config, topic: String) -> Self {
        let c = &config.camera;
        let fov = c.horizontal_fov_deg.to_radians();
        RosCamera {
            tap,
            specs: vec![CameraSpec {
                name: c.name.clone(),
                description: format!("ROS 2 {topic}"),
                origin: Vector3::zeros(),
                pan_limit: 0.0,
                tilt_limit: 0.0,
                horizontal_fov: (fov, fov),
                resolution: ((1, 1), (c.width, c.height)),
                max_frame_rate: c.frame_rate,
            }],
            max_age: config.sensors.max_age(),
            max_bytes: config.sensors.max_image_bytes,
            topic,
        }
    }
}

impl Cameras for RosCamera {
    fn specs(&self) -> &[CameraSpec] {
        &self.specs
    }

    fn capture(&mut self, index: usize, now: Instant, s: &CameraSettings) -> Option<RgbImage> {
        if index != 0 {
            return None;
        }
        let frame = {
            let sh = lock(&self.tap.shared);
            let (f, at) = sh.image.as_ref()?;
            if now.saturating_duration_since(*at) > self.max_age {
                return None;
            }
            f.clone()
        };
        let r = match &*frame {
            Frame::Raw(i) => image_to_rgb(i, self.max_bytes),
            Frame::Png(data) => png_to_rgb(data, self.max_bytes),
        };
        match r {
            Ok(img) => Some(resample(img, s.width, s.height)),
            Err(e) => {
                let mut sh = lock(&self.tap.shared);
                sh.stats.images_refused += 1;
                log_drop("image", &self.topic, sh.stats.images_refused, &e);
                // Not again for every query.
                if sh
                    .image
                    .as_ref()
                    .is_some_and(|(f, _)| Arc::ptr_eq(f, &frame))
                {
                    sh.image = None;
                }
                None
            }
        }
    }
}

#[cfg(test)]
#[path = "sensors_tests.rs"]
mod tests;
