//! What a range scanner detects, kept in a World Model Vector Knowledge Store
//! (implementation choice, not Part 1). Sans-IO: [`MapFeed`] takes sweeps and the
//! vehicle's pose and returns the Create / Delete VKS Objects messages to send.
//!
//! Each object of a sweep becomes a *track* in the local frame (a circle: the nearest
//! return pushed back by the radius its angular width implies). A detection within
//! [`MapFeedConfig::associate`] of a track refreshes it; a track is stored as a buffered
//! point object (buffer = its radius + [`MapFeedConfig::buffer`]) and stored again when
//! its estimate moves. A track is forgotten (and deleted from the store) only on
//! evidence: it has not been seen for [`MapFeedConfig::max_age`] while the sweep looked
//! through where it should be. Turning away from an object keeps it.

use std::time::{Duration, Instant};

use nalgebra::{Rotation2, Vector2};

use super::scan::{Beam, Detection};
use crate::messages::*;
use crate::stock::geo::{local_pose, LocalFrame};
use crate::Address;

/// Settings of the feed.
#[derive(Debug, Clone)]
pub struct MapFeedConfig {
    /// The World Model Vector Knowledge Store.
    pub world_model: Address,
    /// The Global Pose Sensor giving the scanner's vehicle pose (a service connection on
    /// Report Global Pose).
    pub pose_sensor: Address,
    /// The local frame positions are computed in (`None`: at the first pose).
    pub origin: Option<LocalFrame>,
    /// Where the scanner sits on the vehicle: forward and right of the pose's point, m.
    pub mount: Vector2<f64>,
    /// How often a sweep is taken into the map.
    pub period: Duration,
    /// Margin added to an object's estimated radius in its region buffer, m.
    pub buffer: f64,
    /// A detection within this distance of a track's centre is that track, m.
    pub associate: f64,
    /// A stored track whose estimate moved this far is stored again, m.
    pub moved: f64,
    /// A track unseen this long while the scanner looks through it is deleted.
    pub max_age: Duration,
    /// Poses older than this are not used.
    pub pose_timeout: Duration,
    /// Most tracks kept; detections beyond are dropped and counted.
    pub max_tracks: usize,
    /// Feature class of the stored objects.
    pub feature_class: u16,
}

impl MapFeedConfig {
    /// The defaults for a world model and a pose sensor: a sweep every 0.5 s, 0.3 m of
    /// margin, association within 1 m, re-stored after 0.5 m, deleted 3 s after it
    /// should have been seen, poses up to 0.5 s old, 64 tracks, feature class 2.
    pub fn new(world_model: Address, pose_sensor: Address) -> Self {
        Self {
            world_model,
            pose_sensor,
            origin: None,
            mount: Vector2::zeros(),
            period: Duration::from_millis(500),
            buffer: 0.3,
            associate: 1.0,
            moved: 0.5,
            max_age: Duration::from_secs(3),
            pose_timeout: Duration::from_millis(500),
            max_tracks: 64,
            feature_class: 2,
        }
    }
}

/// What the feed counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MapFeedStats {
    /// Sweeps taken into the map.
    pub sweeps: u64,
    /// Sweeps skipped for want of a fresh pose.
    pub no_pose: u64,
    /// Objects sent for creation.
    pub created: u64,
    /// Objects sent for deletion.
    pub deleted: u64,
    /// Detections dropped because `max_tracks` were kept.
    pub dropped: u64,
    /// Objects the world model did not create (id 0), or creation reports that
    /// matched no request.
    pub refused: u64,
}

/// A message for the world model.
#[derive(Debug, Clone, PartialEq)]
pub enum MapUpdate {
    /// Store an object.
    Create(CreateVksObjects),
    /// Delete stored objects.
    Delete(DeleteVksObjects),
}

/// An object the feed keeps, local frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Track {
    /// Centre, m.
    pub centre: Vector2<f64>,
    /// Estimated radius, m.
    pub radius: f64,
    /// When a detection last refreshed it.
    pub last_seen: Instant,
    stored: Stored,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Stored {
    /// Not stored (or stored and since moved: waiting to be stored again).
    No,
    /// Sent with this request id; the centre sent.
    Pending(u8, Vector2<f64>),
    /// Stored under this id at this centre.
    Yes(u32, Vector2<f64>),
}

/// The feed (see the module documentation).
#[derive(Debug)]
pub struct MapFeed {
    config: MapFeedConfig,
    frame: Option<LocalFrame>,
    pose: Option<(Instant, Vector2<f64>, f64)>,
    tracks: Vec<Track>,
    next_request: u8,
    next_sweep: Option<Instant>,
    stats: MapFeedStats,
}

impl MapFeed {
    /// With `config`.
    pub fn new(config: MapFeedConfig) -> Self {
        Self {
            frame: config.origin,
            config,
            pose: None,
            tracks: Vec::new(),
            next_request: 0,
            next_sweep: None,
            stats: MapFeedStats::default(),
        }
    }

    /// The settings.
    pub fn config(&self) -> &MapFeedConfig {
        &self.config
    }

    /// What it counted.
    pub fn stats(&self) -> MapFeedStats {
        self.stats
    }

    /// The objects kept.
    pub fn tracks(&self) -> &[Track] {
        &self.tracks
    }

    /// Whether a sweep is due at `now` (then the next is one period later).
    pub fn due(&mut self, now: Instant) -> bool {
        if self.next_sweep.is_some_and(|t| now < t) {
            return false;
        }
        self.next_sweep = Some(now + self.config.period);
        true
    }

    /// Takes a global pose report.
    pub fn on_global_pose(&mut self, now: Instant, r: &ReportGlobalPose) {
        let last_yaw = self.pose.map(|p| p.2);
        if let Some((p, yaw)) = local_pose(&mut self.frame, r, last_yaw) {
            self.pose = Some((now, p, yaw));
        }
    }

    /// Takes a sweep (`beams` and the objects found in them) at `now`; returns what the
    /// world model must be told.
    pub fn observe(
        &mut self,
        now: Instant,
        beams: &[Beam],
        detections: &[Detection],
    ) -> Vec<MapUpdate> {
        let Some((position, yaw)) = self
            .pose
            .filter(|(t, ..)| now.saturating_duration_since(*t) <= self.config.pose_timeout)
            .map(|(_, p, y)| (p, y))
        else {
            self.stats.no_pose += 1;
            return Vec::new();
        };
        self.stats.sweeps += 1;
        let origin = position + Rotation2::new(yaw) * self.config.mount;
        for d in detections {
            let (centre, radius) = estimate(origin, yaw, d);
            self.refresh(now, centre, radius);
        }
        let mut out = Vec::new();
        // Forget what the sweep looked through without seeing.
        let mut gone = Vec::new();
        let max_age = self.config.max_age;
        self.tracks.retain(|t| {
            let stale = now.saturating_duration_since(t.last_seen) >= max_age;
            let keep = !(stale && looked_through(origin, yaw, beams, t));
            if !keep {
                if let Stored::Yes(id, _) = t.stored {
                    gone.push(id);
                }
            }
            keep
        });
        for t in &mut self.tracks {
            // Moved since stored: delete the old object, store the new estimate.
            if let Stored::Yes(id, at) = t.stored {
                if (t.centre - at).norm() >= self.config.moved {
                    gone.push(id);
                    t.stored = Stored::No;
                }
            }
        }
        if !gone.is_empty() {
            self.stats.deleted += gone.len() as u64;
            out.push(MapUpdate::Delete(delete(gone)));
        }
        if let Some(frame) = self.frame {
            for i in 0..self.tracks.len() {
                if self.tracks[i].stored != Stored::No {
                    continue;
                }
                let request = self.next_request;
                self.next_request = self.next_request.wrapping_add(1);
                let t = &mut self.tracks[i];
                t.stored = Stored::Pending(request, t.centre);
                let (latitude, longitude) = frame.to_global(t.centre);
                self.stats.created += 1;
                out.push(MapUpdate::Create(CreateVksObjects {
                    buffered: true,
                    // Bit 0: report the created object's id.
                    message_properties: 1,
                    request_id: request,
                    objects: vec![VksObject {
                        object_type: VksObjectType::Point,
                        buffer: Some((t.radius + self.config.buffer) as f32),
                        feature_classes: vec![VksFeatureClass {
                            id: self.config.feature_class,
                            attribute: VksAttribute::Default,
                        }],
                        points: vec![VksPoint {
                            latitude,
                            longitude,
                        }],
                    }],
                }));
            }
        }
        out
    }

    /// Takes the world model's answer to a creation; returns the ids to delete (an
    /// object created for a track that has since moved or gone).
    pub fn on_created(&mut self, r: &ReportVksObjectsCreation) -> Option<DeleteVksObjects> {
        let id = r.object_ids.first().copied().unwrap_or(0);
        let track = self
            .tracks
            .iter_mut()
            .find(|t| matches!(t.stored, Stored::Pending(q, _) if q == r.request_id));
        let Some(t) = track else {
            // The track went while its creation was on the way: delete the object.
            if id != 0 {
                self.stats.deleted += 1;
                return Some(delete(vec![id]));
            }
            self.stats.refused += 1;
            return None;
        };
        let Stored::Pending(_, at) = t.stored else {
            return None;
        };
        if id == 0 {
            self.stats.refused += 1;
            t.stored = Stored::No;
        } else {
            t.stored = Stored::Yes(id, at);
        }
        None
    }

    fn refresh(&mut self, now: Instant, centre: Vector2<f64>, radius: f64) {
        let near = self
            .tracks
            .iter_mut()
            .map(|t| ((t.centre - centre).norm(), t))
            .filter(|(d, _)| *d <= self.config.associate)
            .min_by(|a, b| a.0.total_cmp(&b.0));
        if let Some((_, t)) = near {
            // Smooth the estimate: noise does not move a stored object every sweep.
            t.centre += (centre - t.centre) * 0.3;
            t.radius += (radius - t.radius) * 0.3;
            t.last_seen = now;
            return;
        }
        if self.tracks.len() >= self.config.max_tracks {
            self.stats.dropped += 1;
            return;
        }
        self.tracks.push(Track {
            centre,
            radius,
            last_seen: now,
            stored: Stored::No,
        });
    }
}

/// Delete VKS Objects for these ids.
fn delete(ids: Vec<u32>) -> DeleteVksObjects {
    DeleteVksObjects {
        filter_by_class_ids: false,
        filter_by_attributes: false,
        request_id: 0,
        object_ids: Some(ids),
        region_type: None,
        region_buffer: None,
        feature_classes: None,
        region_points: None,
    }
}

/// The circle a detection implies, seen from `origin` with the vehicle at `yaw`: an
/// object of radius R whose nearest return is at range d subtends a half-angle α with
/// sin α = R / (d + R), so R = d sin α / (1 − sin α); its centre lies R beyond the
/// nearest return along the beam.
pub fn estimate(origin: Vector2<f64>, yaw: f64, d: &Detection) -> (Vector2<f64>, f64) {
    let s = (d.span / 2.0).sin().clamp(0.0, 0.9);
    let radius = d.range * s / (1.0 - s);
    let a = yaw + d.bearing;
    let dir = Vector2::new(a.cos(), a.sin());
    (origin + dir * (d.range + radius), radius)
}

/// Whether the sweep looked through the track: the beam nearest its bearing (within
/// the sweep's field) returned nothing, or a return beyond the track's far side.
fn looked_through(origin: Vector2<f64>, yaw: f64, beams: &[Beam], t: &Track) -> bool {
    let to = t.centre - origin;
    let distance = to.norm();
    let bearing = crate::stock::geo::wrap_angle(to.y.atan2(to.x) - yaw);
    let (lo, hi) = beams
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), b| {
            (lo.min(b.bearing), hi.max(b.bearing))
        });
    if !(lo..=hi).contains(&bearing) {
        return false;
    }
    beams
        .iter()
        .min_by(|a, b| {
            (a.bearing - bearing)
                .abs()
                .total_cmp(&(b.bearing - bearing).abs())
        })
        .is_some_and(|b| b.range.is_none_or(|r| r > distance + t.radius))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pose(lat: f64, lon: f64, yaw: f64) -> ReportGlobalPose {
        ReportGlobalPose {
            latitude: Some(lat),
            longitude: Some(lon),
            yaw: Some(yaw),
            ..Default::default()
        }
    }

    /// A sweep of `n` beams over 180° seeing circles (local frame) from `origin`, yaw.
    fn sweep(origin: Vector2<f64>, yaw: f64, circles: &[(Vector2<f64>, f64)]) -> Vec<Beam> {
        let n = 181;
        (0..n)
            .map(|i| {
                let bearing =
                    -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * i as f64 / (n - 1) as f64;
                let a = yaw + bearing;
                let d = Vector2::new(a.cos(), a.sin());
                let range = circles
                    .iter()
                    .filter_map(|(c, r)| {
                        let oc = c - origin;
                        let along = oc.dot(&d);
                        let disc = along * along - (oc.norm_squared() - r * r);
                        (disc >= 0.0 && along - disc.sqrt() > 0.0).then(|| along - disc.sqrt())
                    })
                    .min_by(f64::total_cmp);
                Beam { bearing, range }
            })
            .collect()
    }

    fn feed() -> (MapFeed, LocalFrame) {
        let frame = LocalFrame::new(29.6436, -82.3549, 40.0);
        let mut c = MapFeedConfig::new(Address::new(1, 1, 61, 1), Address::new(1, 1, 38, 1));
        c.origin = Some(frame);
        (MapFeed::new(c), frame)
    }

    #[test]
    fn a_circle_is_estimated_where_it_is() {
        // 1 m circle whose centre is 5 m ahead: nearest return 4 m, half-angle
        // asin(1/5) = 11.5°.
        let d = Detection {
            range: 4.0,
            bearing: 0.0,
            beams: 23,
            span: 2.0 * (0.2f64).asin(),
        };
        let (c, r) = estimate(Vector2::zeros(), 0.0, &d);
        assert!((r - 1.0).abs() < 1e-9, "{r}");
        assert!((c - Vector2::new(5.0, 0.0)).norm() < 1e-9);
        // Facing east, the same detection is 5 m east.
        let (c, _) = estimate(Vector2::zeros(), std::f64::consts::FRAC_PI_2, &d);
        assert!((c - Vector2::new(0.0, 5.0)).norm() < 1e-9, "{c}");
    }

    #[test]
    fn a_detected_object_is_stored_refreshed_and_deleted_only_when_seen_through() {
        let (mut f, frame) = feed();
        let t0 = Instant::now();
        let (lat, lon) = frame.to_global(Vector2::zeros());
        let obstacle = (Vector2::new(6.0, 1.0), 0.5);
        f.on_global_pose(t0, &pose(lat, lon, 0.0));
        let beams = sweep(Vector2::zeros(), 0.0, &[obstacle]);
        let found = super::super::scan::detections(&beams, 0.3);
        let out = f.observe(t0, &beams, &found);
        assert_eq!(out.len(), 1);
        let MapUpdate::Create(c) = &out[0] else {
            panic!("{out:?}")
        };
        assert_eq!((c.request_id, c.message_properties), (0, 1));
        let o = &c.objects[0];
        let at = frame.to_local(o.points[0].latitude, o.points[0].longitude);
        // Within a beam's width of the truth (181 beams over 180°).
        assert!((at - obstacle.0).norm() < 0.15, "{at}");
        let buffer = f64::from(o.buffer.unwrap());
        assert!((buffer - 0.8).abs() < 0.1, "{buffer}");
        // The same object again: nothing new while its creation is pending or done.
        assert!(f.observe(t0, &beams, &found).is_empty());
        assert_eq!(
            f.on_created(&ReportVksObjectsCreation {
                request_id: 0,
                object_ids: vec![41],
            }),
            None
        );
        // Turned away (facing south): not seen, not looked through, kept however old.
        let later = t0 + Duration::from_secs(10);
        f.on_global_pose(later, &pose(lat, lon, std::f64::consts::PI));
        let away = sweep(Vector2::zeros(), std::f64::consts::PI, &[obstacle]);
        assert!(f.observe(later, &away, &[]).is_empty());
        assert_eq!(f.tracks().len(), 1);
        // Facing it again and it is gone: deleted, by its id.
        let later = later + Duration::from_secs(1);
        f.on_global_pose(later, &pose(lat, lon, 0.0));
        let empty = sweep(Vector2::zeros(), 0.0, &[]);
        let out = f.observe(later, &empty, &[]);
        assert_eq!(out.len(), 1);
        let MapUpdate::Delete(d) = &out[0] else {
            panic!("{out:?}")
        };
        assert_eq!(d.object_ids, Some(vec![41]));
        assert!(f.tracks().is_empty());
        let s = f.stats();
        assert_eq!((s.sweeps, s.created, s.deleted, s.refused), (4, 1, 1, 0));
    }

    #[test]
    fn without_a_fresh_pose_nothing_is_stored() {
        let (mut f, frame) = feed();
        let t0 = Instant::now();
        let beams = sweep(Vector2::zeros(), 0.0, &[(Vector2::new(4.0, 0.0), 0.5)]);
        let found = super::super::scan::detections(&beams, 0.3);
        assert!(f.observe(t0, &beams, &found).is_empty());
        let (lat, lon) = frame.to_global(Vector2::zeros());
        f.on_global_pose(t0, &pose(lat, lon, 0.0));
        assert!(f
            .observe(t0 + Duration::from_secs(2), &beams, &found)
            .is_empty());
        assert_eq!(f.stats().no_pose, 2);
    }

    #[test]
    fn tracks_are_bounded_and_refusals_counted() {
        let (mut f, frame) = feed();
        f.config.max_tracks = 2;
        let t0 = Instant::now();
        let (lat, lon) = frame.to_global(Vector2::zeros());
        f.on_global_pose(t0, &pose(lat, lon, 0.0));
        let circles: Vec<_> = (0..4)
            .map(|i| (Vector2::new(5.0, -6.0 + 4.0 * i as f64), 0.4))
            .collect();
        let beams = sweep(Vector2::zeros(), 0.0, &circles);
        let found = super::super::scan::detections(&beams, 0.3);
        assert_eq!(found.len(), 4);
        let out = f.observe(t0, &beams, &found);
        assert_eq!((out.len(), f.tracks().len(), f.stats().dropped), (2, 2, 2));
        // The world model refused one: it is stored again at the next sweep.
        f.on_created(&ReportVksObjectsCreation {
            request_id: 1,
            object_ids: vec![0],
        });
        assert_eq!(f.stats().refused, 1);
        let out = f.observe(t0, &beams, &found);
        assert!(matches!(&out[..], [MapUpdate::Create(c)] if c.request_id == 2));
    }
}
