//! The reports the station follows: component status and control, poses, velocities,
//! world-model objects, mission status.

use std::time::{Duration, Instant};

use nalgebra::Vector2;

use super::{id, Station, VKS_REQUEST};
use crate::component::CoreState;
use crate::messages::{ControlResponse, Message, MissionStatusType};
use crate::stock::commander::view::{ObjectView, PoseView, VelocityView};
use crate::stock::geo::LocalFrame;
use crate::Address;

/// How long after the station's Resume a component may still report Standby before the
/// station says it did not obey (a driver whose controller is someone else refuses it;
/// one that cannot take its output stays; OpenJAUS 3.3's drivers pass through Standby
/// for a few milliseconds on their way to Ready).
const RESUME_GRACE: Duration = Duration::from_millis(1500);

impl Station {
    /// The station sent `target` Resume at `now`: its next status reports say whether
    /// it obeyed (asked for at once).
    pub(super) fn resume_sent(&mut self, now: Instant, target: Address) {
        if let Some(k) = self.known.get_mut(&target) {
            k.resumed = Some(now);
        }
        self.next_status = None;
    }

    /// A status report from `source` that has been sent Resume: Ready ends the watch;
    /// still Standby after [`RESUME_GRACE`] is reported (an error notice naming the
    /// controller the station knows), once.
    fn check_resumed(&mut self, now: Instant, source: Address, state: Option<CoreState>) {
        let Some(k) = self.known.get_mut(&source) else {
            return;
        };
        let Some(sent) = k.resumed else {
            return;
        };
        match state {
            Some(CoreState::Standby) => {
                let waited = now.saturating_duration_since(sent);
                if waited < RESUME_GRACE {
                    return;
                }
                k.resumed = None;
                let controller = match k.controller {
                    Some((c, authority)) => format!("its controller: {c}, authority {authority}"),
                    None => "no controller known".to_string(),
                };
                self.notice(
                    true,
                    format!(
                        "{source}: still in Standby {:.1} s after Resume: it did not obey ({controller})",
                        waited.as_secs_f64()
                    ),
                );
            }
            // Ready: obeyed. Emergency, Failure, Shutdown: reported as such elsewhere.
            Some(_) => k.resumed = None,
            None => {}
        }
    }

    /// Takes a message addressed to the station; returns whether it was one the
    /// station follows.
    pub fn on_message(&mut self, now: Instant, source: Address, msg: &Message) -> bool {
        self.clock = Some(now);
        let Some(k) = self.known.get_mut(&source) else {
            return false;
        };
        match msg {
            Message::ReportComponentStatus(r) => {
                let state = CoreState::from_wire(r.primary_status_code);
                let before = k.state.map(|s| s.0);
                if let Some(s) = state {
                    k.state = Some((s, now));
                }
                self.keeper.on_status(source, r);
                self.check_resumed(now, source, state);
                let emergency = self
                    .known
                    .iter()
                    .filter(|(a, _)| a.subsystem == source.subsystem)
                    .any(|(_, k)| k.state.is_some_and(|s| s.0 == CoreState::Emergency));
                if let Some(v) = self.vehicles.get_mut(&source.subsystem) {
                    v.emergency = emergency;
                }
                if state == Some(CoreState::Emergency) && before != Some(CoreState::Emergency) {
                    self.notice(true, format!("{source}: Emergency"));
                } else if before == Some(CoreState::Emergency) && state != before {
                    if let Some(s) = state {
                        self.notice(false, format!("{source}: left Emergency ({s:?})"));
                    }
                    // A pose or velocity sensor nobody controls is resumed: Clear
                    // Emergency leaves it in Standby, where some stop reporting
                    // (OpenJAUS 3.3's do), and the station and the drivers need it.
                    let sensor = matches!(
                        source.component,
                        id::GLOBAL_POSE | id::LOCAL_POSE | id::VELOCITY
                    );
                    let free = self
                        .known
                        .get(&source)
                        .is_some_and(|k| k.controller.is_none());
                    if sensor
                        && free
                        && state == Some(CoreState::Standby)
                        && !self.wake.contains(&source)
                        && self.wake.len() < 64
                    {
                        self.wake.push(source);
                    }
                }
            }
            Message::ReportComponentControl(r) => {
                let c = Address::new(r.subsystem_id, r.node_id, r.component_id, r.instance_id);
                k.controller = (c.subsystem != 0).then_some((c, r.authority_code));
            }
            Message::ConfirmComponentControl(c) => {
                if c.response_code != ControlResponse::ControlAccepted {
                    self.notice(
                        true,
                        format!("{source}: control refused ({:?})", c.response_code),
                    );
                }
            }
            Message::RejectComponentControl(_) => {
                self.notice(
                    true,
                    format!("{source}: control taken away (Reject Component Control)"),
                );
            }
            Message::ReportGlobalPose(p) => {
                let (Some(lat), Some(lon)) = (p.latitude, p.longitude) else {
                    return true;
                };
                let frame = *self
                    .frame
                    .get_or_insert_with(|| LocalFrame::new(lat, lon, 0.0));
                // The frame's (north, east) as the view's (east, north).
                let ne = frame.to_local(lat, lon);
                let l = Vector2::new(ne.y, ne.x);
                self.pose(now, source.subsystem, lat, lon, l, p.yaw);
            }
            Message::ReportLocalPose(p) => {
                let has_global = self.find(source.subsystem, id::GLOBAL_POSE).is_some();
                if let (false, Some(x), Some(y), Some(frame)) = (has_global, p.x, p.y, self.frame) {
                    // Local x is north, y east (Part 1's vehicle frames); the map's x east.
                    let l = Vector2::new(y, x);
                    let (lat, lon) = frame.to_global(Vector2::new(x, y));
                    self.pose(now, source.subsystem, lat, lon, l, p.yaw);
                }
            }
            Message::ReportVelocityState(r) => {
                let speed = r
                    .velocity_x
                    .unwrap_or(0.0)
                    .hypot(r.velocity_y.unwrap_or(0.0));
                if let Some(v) = self.vehicles.get_mut(&source.subsystem) {
                    v.velocity = Some((
                        VelocityView {
                            speed,
                            yaw_rate: r.yaw_rate,
                        },
                        now,
                    ));
                }
            }
            Message::ReportVksObjects(r) if r.request_id == VKS_REQUEST => {
                let Some(frame) = self.frame else {
                    return true;
                };
                if let Some(v) = self.vehicles.get_mut(&source.subsystem) {
                    v.objects = r
                        .objects
                        .iter()
                        .flatten()
                        .map(|o| ObjectView {
                            id: o.object_id,
                            buffer: f64::from(o.buffer),
                            points: o
                                .points
                                .iter()
                                .map(|p| {
                                    let l = frame.to_local(p.latitude, p.longitude);
                                    (l.y, l.x)
                                })
                                .collect(),
                        })
                        .collect();
                }
            }
            Message::ReportMissionStatus(r) => {
                if let Some((_, m)) = self
                    .vehicles
                    .get_mut(&source.subsystem)
                    .and_then(|v| v.mission.as_mut())
                    .filter(|(s, m)| *s == source && m.id == r.mission_id)
                {
                    if r.status_type == MissionStatusType::Mission {
                        let s = format!("{:?}", r.status);
                        if m.status.as_deref() != Some(&s) {
                            m.status = Some(s.clone());
                            let text = format!("{source}: mission {} {s}", r.mission_id);
                            self.notice(false, text);
                        }
                    }
                }
            }
            _ => return false,
        }
        true
    }

    fn pose(
        &mut self,
        now: Instant,
        subsystem: u8,
        latitude: f64,
        longitude: f64,
        l: Vector2<f64>,
        yaw: Option<f64>,
    ) {
        let max = self.config.trail_max;
        let v = self.vehicles.entry(subsystem).or_default();
        v.pose = Some((
            PoseView {
                latitude,
                longitude,
                x: l.x,
                y: l.y,
                yaw,
                age_s: 0.0,
                received_unix_ms: 0.0,
            },
            now,
        ));
        if v.trail.len() >= max {
            v.trail.pop_front();
        }
        v.trail.push_back((l.x, l.y));
        v.pose_count += 1;
        self.poses += 1;
    }
}
