//! The Range Sensor (Part 1 §5.5, id 50) over a scanning range finder
//! ([`RangeScanner`]): each sweep's returns are grouped into objects (neighbouring beams
//! whose ranges agree), and Query Relative Object Position is answered with the nearest
//! object, in the platform frame at the time of the sweep. [`ScanObstacles`] gives the
//! same sweeps to the Reflexive Driver as its obstacle source.

use std::time::Instant;

use super::map_feed::{MapFeed, MapFeedConfig, MapFeedStats, MapUpdate};
pub use super::scan::{detections, Beam, Detection, RangeScanner, ScannerSpec};
use crate::component::Refused;
use crate::components::range_sensor as rs;
use crate::messages::*;
use crate::stock::drivers::ObstacleSource;
use crate::JausMessage;

/// Settings of the Range Sensor.
#[derive(Debug, Clone)]
pub struct RangeConfig {
    /// Neighbouring returns farther apart than this are different objects, m.
    pub gap: f64,
    /// Range error reported, m.
    pub range_error: f64,
    /// Bearing error reported, rad.
    pub bearing_error: f64,
}

/// The defaults: objects split at 0.3 m, errors 0.05 m and 0.5°.
///
/// ```
/// let c = jaus::stock::environment::range::RangeConfig::default();
/// assert_eq!((c.gap, c.range_error), (0.3, 0.05));
/// ```
impl Default for RangeConfig {
    fn default() -> Self {
        Self {
            gap: 0.3,
            range_error: 0.05,
            bearing_error: 0.5f64.to_radians(),
        }
    }
}

/// The Range Sensor over a [`RangeScanner`]; with [`with_map_feed`](Self::with_map_feed)
/// it also keeps what it detects in a world model ([`map_feed`](super::map_feed)).
#[derive(Debug)]
pub struct StockRangeSensor<S> {
    scanner: S,
    config: RangeConfig,
    beams: Vec<Beam>,
    sweeps: u64,
    feed: Option<MapFeed>,
    subscribed: bool,
}

impl<S: RangeScanner> StockRangeSensor<S> {
    /// Over `scanner`.
    pub fn new(scanner: S, config: RangeConfig) -> Self {
        Self {
            scanner,
            config,
            beams: Vec::new(),
            sweeps: 0,
            feed: None,
            subscribed: false,
        }
    }

    /// Also keeps its detections in the world model of `feed`.
    pub fn with_map_feed(mut self, feed: MapFeedConfig) -> Self {
        self.feed = Some(MapFeed::new(feed));
        self
    }

    /// The world-model feed's counters, when it has one.
    pub fn map_feed_stats(&self) -> Option<MapFeedStats> {
        self.feed.as_ref().map(MapFeed::stats)
    }

    /// Sweeps read so far.
    pub fn sweeps(&self) -> u64 {
        self.sweeps
    }

    /// The objects of the latest sweep, nearest first.
    pub fn detect(&mut self, now: Instant) -> Option<Vec<Detection>> {
        if !self.scanner.scan(now, &mut self.beams) {
            return None;
        }
        self.sweeps += 1;
        let mut d = detections(&self.beams, self.config.gap);
        d.sort_by(|a, b| a.range.total_cmp(&b.range));
        Some(d)
    }
}

impl<S: RangeScanner> rs::RangeSensor for StockRangeSensor<S> {
    fn tick(&mut self, ctx: &mut rs::Ctx<'_>) {
        let Some(feed) = self.feed.as_mut() else {
            return;
        };
        let now = ctx.now();
        if !self.subscribed {
            self.subscribed = true;
            // Latitude, longitude, elevation and yaw (bits 0-2 and 6), at 10 Hz.
            let pose = feed.config().pose_sensor;
            if let Err(e) = ctx.create_service_connection(pose, ReportGlobalPose::CODE, 10.0, 0x47)
            {
                tracing::warn!(address = %ctx.address(), %pose, "no pose for the world-model feed: {e}");
            }
        }
        if !feed.due(now) || !self.scanner.scan(now, &mut self.beams) {
            return;
        }
        self.sweeps += 1;
        let found = detections(&self.beams, self.config.gap);
        let to = feed.config().world_model;
        for update in feed.observe(now, &self.beams, &found) {
            match update {
                MapUpdate::Create(m) => ctx.send(to, m),
                MapUpdate::Delete(m) => ctx.send(to, m),
            }
        }
    }

    fn on_report_global_pose(
        &mut self,
        ctx: &mut rs::Ctx<'_>,
        msg: &ReportGlobalPose,
    ) -> Result<(), Refused> {
        if let Some(feed) = self.feed.as_mut() {
            feed.on_global_pose(ctx.now(), msg);
        }
        Ok(())
    }

    fn on_report_vks_objects_creation(
        &mut self,
        ctx: &mut rs::Ctx<'_>,
        msg: &ReportVksObjectsCreation,
    ) -> Result<(), Refused> {
        if let Some(feed) = self.feed.as_mut() {
            if let Some(delete) = feed.on_created(msg) {
                ctx.send(feed.config().world_model, delete);
            }
        }
        Ok(())
    }

    fn on_query_relative_object_position(
        &mut self,
        ctx: &mut rs::Ctx<'_>,
        q: &QueryRelativeObjectPosition,
    ) -> Result<ReportRelativeObjectPosition, Refused> {
        let objects = self
            .detect(ctx.now())
            .ok_or_else(|| Refused::Invalid("no sweep from the range scanner".into()))?;
        let time_stamp = ctx.time_stamps().map(|t| t.0).unwrap_or_default();
        let want = |bit: u8| q.presence_vector & (1 << bit) != 0;
        // Nothing in range: a report with the time stamp only.
        let Some(near) = objects.first() else {
            return Ok(ReportRelativeObjectPosition {
                time_stamp,
                ..Default::default()
            });
        };
        let c = &self.config;
        Ok(ReportRelativeObjectPosition {
            time_stamp,
            range: want(0).then_some(near.range.min(10_000.0)),
            range_error: want(1).then_some(c.range_error),
            bearing: want(2).then_some(near.bearing),
            bearing_error: want(3).then_some(c.bearing_error),
            inclination: want(4).then_some(0.0),
            inclination_error: want(5).then_some(0.0),
            confidence_and_object_id: want(6),
            confidence: want(6).then_some((near.beams.min(255)) as u8),
            object_id: want(6).then_some(0),
        })
    }
}

/// The Reflexive Driver's obstacle source from a [`RangeScanner`]: the free distance
/// ahead is the nearest return inside a corridor as wide as the platform.
#[derive(Debug)]
pub struct ScanObstacles<S> {
    scanner: S,
    /// Half the corridor's width, m.
    pub half_width: f64,
    beams: Vec<Beam>,
}

impl<S: RangeScanner> ScanObstacles<S> {
    /// Over `scanner`, for a corridor `width` metres wide.
    pub fn new(scanner: S, width: f64) -> Self {
        Self {
            scanner,
            half_width: width / 2.0,
            beams: Vec::new(),
        }
    }
}

impl<S: RangeScanner> ObstacleSource for ScanObstacles<S> {
    fn obstacle_distance(&mut self, now: Instant) -> Option<f64> {
        if !self.scanner.scan(now, &mut self.beams) {
            return None;
        }
        self.beams
            .iter()
            .filter_map(|b| {
                let r = b.range?;
                let (ahead, side) = (r * b.bearing.cos(), r * b.bearing.sin());
                (ahead > 0.0 && side.abs() <= self.half_width).then_some(ahead)
            })
            .min_by(f64::total_cmp)
    }
}
