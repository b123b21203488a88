//! The Visual Sensor (Part 1 §5.5, id 37) over a set of cameras ([`Cameras`]): camera
//! count and selection, each camera's pose on its pan/tilt mount, capabilities and
//! format options, and Query Image answered with a frame of the selected camera
//! encoded as its chosen format (PNG or PPM, [`image`](super::image)), no more often
//! than its frame rate (a faster query gets the last frame again) and no larger than
//! [`VisualConfig::max_image_bytes`] (a larger message travels as a multi-packet
//! sequence on the network).
//!
//! Cameras are numbered from 1 (`camera_id` 0 is refused). Frames (platform): x
//! forward, y right, z down; a camera's pan turns its lens to the right, its tilt up.

use std::time::{Duration, Instant};

use nalgebra::Vector3;

use super::image::{encode, RgbImage, FORMATS};
use crate::codec::fit_latin1;
use crate::component::Refused;
use crate::components::visual_sensor as vs;
use crate::messages::*;

/// What a camera is and can do.
#[derive(Debug, Clone, PartialEq)]
pub struct CameraSpec {
    /// Name (Report Camera Pose carries 15 ISO-8859-1 characters; longer is cut).
    pub name: String,
    /// Description (Report Camera Capabilities carries 50 characters; longer is cut).
    pub description: String,
    /// Position of the camera's origin on the platform, m.
    pub origin: Vector3<f64>,
    /// The mount pans ±this far, rad (0: fixed).
    pub pan_limit: f64,
    /// The mount tilts ±this far, rad (0: fixed).
    pub tilt_limit: f64,
    /// Narrowest and widest horizontal field of view, rad.
    pub horizontal_fov: (f64, f64),
    /// Smallest and largest image, pixels (width, height).
    pub resolution: ((u16, u16), (u16, u16)),
    /// Highest frame rate, frames/s.
    pub max_frame_rate: u16,
}

/// How a camera is set.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraSettings {
    /// Image width, pixels.
    pub width: u16,
    /// Image height, pixels.
    pub height: u16,
    /// Horizontal field of view, rad.
    pub horizontal_fov: f64,
    /// Frames per second at most.
    pub frame_rate: u16,
    /// Encoding of Report Image.
    pub format: ImageFormat,
    /// Pan (to the right) and tilt (up) of the mount, rad.
    pub pan: f64,
    /// Tilt, rad.
    pub tilt: f64,
}

impl CameraSettings {
    /// The largest image, widest view, highest rate, PNG, looking straight ahead.
    pub fn defaults_for(spec: &CameraSpec) -> Self {
        Self {
            width: spec.resolution.1 .0,
            height: spec.resolution.1 .1,
            horizontal_fov: spec.horizontal_fov.1,
            frame_rate: spec.max_frame_rate.max(1),
            format: ImageFormat::Png,
            pan: 0.0,
            tilt: 0.0,
        }
    }

    /// The lens direction and the image's X axis (to the right) in the platform frame.
    pub fn axes(&self) -> (Vector3<f64>, Vector3<f64>) {
        let (sp, cp) = self.pan.sin_cos();
        let (st, ct) = self.tilt.sin_cos();
        (
            Vector3::new(ct * cp, ct * sp, -st),
            Vector3::new(-sp, cp, 0.0),
        )
    }
}

/// The cameras of a platform.
pub trait Cameras: Send + 'static {
    /// What each camera is (index 0 is camera 1).
    fn specs(&self) -> &[CameraSpec];
    /// A frame of camera `index` taken at `now` with `settings` (`None`: no frame).
    fn capture(
        &mut self,
        index: usize,
        now: Instant,
        settings: &CameraSettings,
    ) -> Option<RgbImage>;
}

/// Settings of the Visual Sensor.
#[derive(Debug, Clone)]
pub struct VisualConfig {
    /// Largest Report Image body, bytes (the network reassembles up to 1 MiB by default).
    pub max_image_bytes: usize,
}

/// 1 MiB − 2 bytes: a Report Image body whole, within the default reassembly limit.
impl Default for VisualConfig {
    fn default() -> Self {
        Self {
            max_image_bytes: (1 << 20) - 2,
        }
    }
}

/// What the Visual Sensor counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct VisualStats {
    /// Frames captured and encoded.
    pub frames: u64,
    /// Queries answered with the previous frame (faster than the frame rate).
    pub repeated: u64,
    /// Queries refused (no frame, encoding failed, image too large).
    pub refused: u64,
}

/// The Visual Sensor over [`Cameras`].
#[derive(Debug)]
pub struct StockVisualSensor<C> {
    cameras: C,
    config: VisualConfig,
    settings: Vec<CameraSettings>,
    selected: usize,
    /// Per camera: when the last frame was taken and its encoding.
    last: Vec<Option<(Instant, ImageFormat, Vec<u8>)>>,
    stats: VisualStats,
}

impl<C: Cameras> StockVisualSensor<C> {
    /// Over `cameras`, camera 1 selected.
    pub fn new(cameras: C, config: VisualConfig) -> Self {
        let settings: Vec<_> = cameras
            .specs()
            .iter()
            .map(CameraSettings::defaults_for)
            .collect();
        Self {
            last: vec![None; settings.len()],
            settings,
            cameras,
            config,
            selected: 0,
            stats: VisualStats::default(),
        }
    }

    /// The settings of camera `id` (from 1).
    pub fn settings(&self, id: u8) -> Option<&CameraSettings> {
        self.settings.get(usize::from(id).checked_sub(1)?)
    }

    /// What it counted.
    pub fn stats(&self) -> VisualStats {
        self.stats
    }

    fn index(&self, id: u8) -> Result<usize, Refused> {
        usize::from(id)
            .checked_sub(1)
            .filter(|i| *i < self.settings.len())
            .ok_or_else(|| {
                Refused::Invalid(format!(
                    "no camera {id}: cameras are numbered 1 to {}",
                    self.settings.len()
                ))
            })
    }

    fn frame(&mut self, now: Instant) -> Result<ReportImage, Refused> {
        let i = self.selected;
        let s = self.settings[i];
        let period = Duration::from_secs_f64(1.0 / f64::from(s.frame_rate.max(1)));
        if let Some((t, format, data)) = &self.last[i] {
            if now.saturating_duration_since(*t) < period && *format == s.format {
                self.stats.repeated += 1;
                return Ok(report(i, *format, data.clone()));
            }
        }
        let refuse = |stats: &mut VisualStats, why: String| {
            stats.refused += 1;
            Refused::Invalid(why)
        };
        let Some(image) = self.cameras.capture(i, now, &s) else {
            return Err(refuse(
                &mut self.stats,
                format!("camera {} gave no frame", i + 1),
            ));
        };
        let data = encode(&image, s.format).map_err(|e| refuse(&mut self.stats, e.to_string()))?;
        if data.len() > self.config.max_image_bytes {
            return Err(refuse(
                &mut self.stats,
                format!(
                    "a {}×{} {:?} image is {} bytes, over the {}-byte limit: lower the resolution (Set Camera Capabilities)",
                    s.width,
                    s.height,
                    s.format,
                    data.len(),
                    self.config.max_image_bytes
                ),
            ));
        }
        self.stats.frames += 1;
        self.last[i] = Some((now, s.format, data.clone()));
        Ok(report(i, s.format, data))
    }
}

fn report(index: usize, format: ImageFormat, data: Vec<u8>) -> ReportImage {
    ReportImage {
        camera_id: (index + 1) as u8,
        video_format: format,
        data,
    }
}

impl<C: Cameras> vs::VisualSensor for StockVisualSensor<C> {
    fn on_select_camera(
        &mut self,
        _ctx: &mut vs::Ctx<'_>,
        msg: &SelectCamera,
    ) -> Result<(), Refused> {
        self.selected = self.index(msg.camera_id)?;
        Ok(())
    }

    fn on_set_camera_pose(
        &mut self,
        _ctx: &mut vs::Ctx<'_>,
        msg: &SetCameraPose,
    ) -> Result<(), Refused> {
        let i = self.index(msg.camera_id)?;
        let spec = &self.cameras.specs()[i];
        let m = &msg.mode;
        if m.x_angular_mode != 0 || m.y_angular_mode != 0 {
            return Err(Refused::Invalid(format!(
                "camera {}: its mount takes positions, not rates (mode bits 3 and 4 must be 0)",
                msg.camera_id
            )));
        }
        let fixed = [
            (
                "SetCameraPose.x_linear_position_or_rate",
                msg.x_linear_position_or_rate,
            ),
            (
                "SetCameraPose.y_linear_position_or_rate",
                msg.y_linear_position_or_rate,
            ),
            (
                "SetCameraPose.z_linear_position_or_rate",
                msg.z_linear_position_or_rate,
            ),
            (
                "SetCameraPose.z_angular_position_or_rate",
                msg.z_angular_position_or_rate,
            ),
        ];
        for (field, v) in fixed {
            if let Some(v) = v {
                Refused::check_range(field, v, 0.0, 0.0, "%")?;
            }
        }
        // X angular: tilt (about the image's horizontal axis); Y angular: pan. Each a
        // percentage of the mount's limit.
        let tilt = msg
            .x_angular_position_or_rate
            .map(|p| p / 100.0 * spec.tilt_limit);
        let pan = msg
            .y_angular_position_or_rate
            .map(|p| p / 100.0 * spec.pan_limit);
        let s = &mut self.settings[i];
        if let Some(t) = tilt {
            s.tilt = t;
        }
        if let Some(p) = pan {
            s.pan = p;
        }
        Ok(())
    }

    fn on_set_camera_capabilities(
        &mut self,
        _ctx: &mut vs::Ctx<'_>,
        msg: &SetCameraCapabilities,
    ) -> Result<(), Refused> {
        let i = self.index(msg.camera_id)?;
        let spec = self.cameras.specs()[i].clone();
        let mut s = self.settings[i];
        if let Some(f) = msg.horizontal_fov {
            s.horizontal_fov = Refused::check_range(
                "SetCameraCapabilities.horizontal_fov",
                f,
                spec.horizontal_fov.0,
                spec.horizontal_fov.1,
                "rad",
            )?;
        }
        let ((w0, h0), (w1, h1)) = spec.resolution;
        if let Some(w) = msg.horizontal_resolution {
            Refused::check_range(
                "SetCameraCapabilities.horizontal_resolution",
                w.into(),
                w0.into(),
                w1.into(),
                "px",
            )?;
            s.width = w;
        }
        if let Some(h) = msg.vertical_resolution {
            Refused::check_range(
                "SetCameraCapabilities.vertical_resolution",
                h.into(),
                h0.into(),
                h1.into(),
                "px",
            )?;
            s.height = h;
        }
        if let Some(r) = msg.frame_rate {
            Refused::check_range(
                "SetCameraCapabilities.frame_rate",
                r.into(),
                1.0,
                spec.max_frame_rate.into(),
                "frames/s",
            )?;
            s.frame_rate = r;
        }
        let unsupported = [
            ("vertical_fov", msg.vertical_fov.is_some()),
            ("focus", msg.focus.is_some()),
            ("iris", msg.iris.is_some()),
            ("gain", msg.gain.is_some()),
            ("shutter_speed", msg.shutter_speed.is_some()),
            (
                "image_control",
                msg.image_control.is_some_and(|c| c != Default::default()),
            ),
            (
                "audio_control",
                msg.audio_control.is_some_and(|c| c != Default::default()),
            ),
        ];
        if let Some((field, _)) = unsupported.iter().find(|(_, set)| *set) {
            return Err(Refused::Invalid(format!(
                "camera {}: `{field}` cannot be set (the vertical field of view follows from the horizontal one and the image's shape; no focus, iris, gain, shutter, image or audio controls)",
                msg.camera_id
            )));
        }
        self.settings[i] = s;
        Ok(())
    }

    fn on_set_camera_format_options(
        &mut self,
        _ctx: &mut vs::Ctx<'_>,
        msg: &SetCameraFormatOptions,
    ) -> Result<(), Refused> {
        let i = self.index(msg.camera_id)?;
        if msg.audio_format.is_some_and(|a| a != AudioFormat::Unused) {
            return Err(Refused::Invalid(format!(
                "camera {}: no audio",
                msg.camera_id
            )));
        }
        if msg.format_option.is_some() {
            return Err(Refused::Invalid(format!(
                "camera {}: PNG and PPM take no format option",
                msg.camera_id
            )));
        }
        if let Some(f) = msg.image_format {
            if !FORMATS.contains(&f) {
                return Err(Refused::Invalid(format!(
                    "camera {}: image format {f:?} is not offered (PNG, PPM)",
                    msg.camera_id
                )));
            }
            self.settings[i].format = f;
        }
        Ok(())
    }

    fn on_query_camera_pose(
        &mut self,
        _ctx: &mut vs::Ctx<'_>,
        msg: &QueryCameraPose,
    ) -> Result<ReportCameraPose, Refused> {
        let i = self.index(msg.camera_id)?;
        let spec = &self.cameras.specs()[i];
        let (z, x) = self.settings[i].axes();
        let want = |bit: u8| msg.presence_vector & (1 << bit) != 0;
        let o = spec.origin;
        Ok(ReportCameraPose {
            camera_id: msg.camera_id,
            camera_name: want(0).then(|| fit_latin1(&spec.name, 15)),
            x_camera_origin: want(1).then_some(o.x),
            y_camera_origin: want(2).then_some(o.y),
            z_camera_origin: want(3).then_some(o.z),
            x_camera_axis_direction_cosine_x: want(4).then_some(x.x),
            x_camera_axis_direction_cosine_y: want(5).then_some(x.y),
            x_camera_axis_direction_cosine_z: want(6).then_some(x.z),
            z_camera_axis_direction_cosine_x: want(7).then_some(z.x),
            z_camera_axis_direction_cosine_y: want(8).then_some(z.y),
            z_camera_axis_direction_cosine_z: want(9).then_some(z.z),
        })
    }

    fn on_query_camera_count(
        &mut self,
        _ctx: &mut vs::Ctx<'_>,
        _msg: &QueryCameraCount,
    ) -> Result<ReportCameraCount, Refused> {
        Ok(ReportCameraCount {
            camera_count: self.settings.len().min(255) as u8,
        })
    }

    fn on_query_selected_camera(
        &mut self,
        _ctx: &mut vs::Ctx<'_>,
        _msg: &QuerySelectedCamera,
    ) -> Result<ReportSelectedCamera, Refused> {
        Ok(ReportSelectedCamera {
            camera_id: (self.selected + 1) as u8,
        })
    }

    fn on_query_camera_capabilities(
        &mut self,
        _ctx: &mut vs::Ctx<'_>,
        msg: &QueryCameraCapabilities,
    ) -> Result<ReportCameraCapabilities, Refused> {
        let i = self.index(msg.camera_id)?;
        let spec = &self.cameras.specs()[i];
        let want = |bit: u8| msg.presence_vector & (1 << bit) != 0;
        let ((w0, h0), (w1, h1)) = spec.resolution;
        // The vertical field of view of an image of the same shape.
        let vfov = |h: f64, w: f64, hfov: f64| 2.0 * ((hfov / 2.0).tan() * h / w).atan();
        Ok(ReportCameraCapabilities {
            camera_id: msg.camera_id,
            camera_description: want(0).then(|| fit_latin1(&spec.description, 50)),
            max_horizontal_fov: want(1).then_some(spec.horizontal_fov.1),
            min_horizontal_fov: want(2).then_some(spec.horizontal_fov.0),
            max_vertical_fov: want(3).then(|| vfov(h1.into(), w1.into(), spec.horizontal_fov.1)),
            min_vertical_fov: want(4).then(|| vfov(h0.into(), w0.into(), spec.horizontal_fov.0)),
            max_horizontal_resolution: want(5).then_some(w1),
            min_horizontal_resolution: want(6).then_some(w0),
            max_vertical_resolution: want(7).then_some(h1),
            min_vertical_resolution: want(8).then_some(h0),
            max_frame_rate: want(9).then_some(spec.max_frame_rate),
            min_frame_rate: want(10).then_some(1),
            max_shutter_speed: None,
            min_shutter_speed: None,
            image_control: want(13).then(Default::default),
            audio_control: want(14).then(Default::default),
        })
    }

    fn on_query_camera_format_options(
        &mut self,
        _ctx: &mut vs::Ctx<'_>,
        msg: &QueryCameraFormatOptions,
    ) -> Result<ReportCameraFormatOptions, Refused> {
        self.index(msg.camera_id)?;
        let want = |bit: u8| msg.presence_vector & (1 << bit) != 0;
        Ok(ReportCameraFormatOptions {
            camera_id: msg.camera_id,
            audio_format_1: None,
            audio_format_2: None,
            image_format_1: want(2).then_some(FORMATS[0]),
            image_format_2: want(3).then_some(FORMATS[1]),
            image_format_3: None,
            image_format_4: None,
            format_option: None,
        })
    }

    fn on_query_image(
        &mut self,
        ctx: &mut vs::Ctx<'_>,
        _msg: &QueryImage,
    ) -> Result<ReportImage, Refused> {
        self.frame(ctx.now())
    }
}
