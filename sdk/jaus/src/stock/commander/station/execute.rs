//! Carrying out a checked command: the JAUS messages it becomes, the route it draws.

use super::{id, send_std, Command, GeoPoint, MissionAction, Station, CREATE_REQUEST};
use crate::component::{Context, Interface};
use crate::messages::{
    AbortMission, ClearEmergency, ClearEmergencyCode, CreateVksObjects, EmergencyCode, Message,
    MissionCommand, PauseMission, Resume, ResumeMission, RunMission, SetEmergency,
    SetGlobalPathSegment, SetGlobalWaypoint, SetTravelSpeed, SpoolMission, Standby, VksAttribute,
    VksFeatureClass, VksObject, VksObjectType, VksPoint,
};
use crate::stock::commander::view::MissionView;
use crate::stock::spooler::{command, leaf_task, mission_of};
use crate::Address;

impl Station {
    pub(super) fn execute<I: Interface>(&mut self, ctx: &mut Context<'_, I>, cmd: Command) {
        let me = ctx.address();
        let send = send_std::<I>;
        match cmd {
            Command::TakeControl { target, authority } => {
                self.keeper.keep_with(target, authority);
                self.notice(
                    false,
                    format!("{target}: asking for control with authority {authority}"),
                );
            }
            Command::ReleaseControl { target } => {
                self.keeper.release(ctx, target);
                self.notice(false, format!("{target}: control released"));
            }
            Command::Emergency { subsystem } | Command::ClearEmergency { subsystem } => {
                let set = matches!(cmd, Command::Emergency { .. });
                let targets: Vec<Address> = self
                    .tree
                    .components
                    .keys()
                    .filter(|a| {
                        a.subsystem == subsystem && **a != me && a.component != id::NODE_MANAGER
                    })
                    .copied()
                    .collect();
                for a in &targets {
                    if set {
                        ctx.send_core(
                            *a,
                            SetEmergency {
                                emergency_code: EmergencyCode {
                                    transition_to_emergency: true,
                                    ..EmergencyCode::default()
                                },
                            },
                        );
                    } else {
                        ctx.send_core(
                            *a,
                            ClearEmergency {
                                emergency_code: ClearEmergencyCode {
                                    clear_emergency: true,
                                    ..ClearEmergencyCode::default()
                                },
                            },
                        );
                    }
                }
                // Ask at once how they are.
                self.next_status = None;
                self.notice(
                    set,
                    format!(
                        "subsystem {subsystem}: {} sent to {} component(s)",
                        if set {
                            "Set Emergency"
                        } else {
                            "Clear Emergency"
                        },
                        targets.len()
                    ),
                );
            }
            Command::Resume { target } => {
                ctx.send_core(target, Resume {});
                self.resume_sent(ctx.now(), target);
            }
            Command::Standby { target } => ctx.send_core(target, Standby {}),
            Command::Waypoints {
                driver,
                points,
                speed,
            } => {
                ctx.send_core(driver, Resume {});
                self.resume_sent(ctx.now(), driver);
                for (i, p) in points.iter().enumerate() {
                    send(
                        ctx,
                        driver,
                        SetGlobalWaypoint {
                            waypoint_number: i as u16,
                            latitude: p.latitude,
                            longitude: p.longitude,
                            ..SetGlobalWaypoint::default()
                        }
                        .into(),
                    );
                }
                self.route_sent(ctx, driver, &points, speed, "waypoint(s)");
            }
            Command::PathSegments {
                driver,
                points,
                speed,
            } => {
                ctx.send_core(driver, Resume {});
                self.resume_sent(ctx.now(), driver);
                let start = self
                    .vehicles
                    .get(&driver.subsystem)
                    .and_then(|v| v.pose.as_ref())
                    .map(|(p, _)| GeoPoint {
                        latitude: p.latitude,
                        longitude: p.longitude,
                    });
                let mut from = start.unwrap_or(points[0]);
                for (i, p) in points.iter().enumerate() {
                    let mid = GeoPoint {
                        latitude: (from.latitude + p.latitude) / 2.0,
                        longitude: (from.longitude + p.longitude) / 2.0,
                    };
                    send(
                        ctx,
                        driver,
                        SetGlobalPathSegment {
                            path_segment_number: i as u16,
                            p1_latitude: mid.latitude,
                            p1_longitude: mid.longitude,
                            p1_altitude: None,
                            p2_latitude: p.latitude,
                            p2_longitude: p.longitude,
                            p2_altitude: None,
                            weighting_factor: 0.0,
                        }
                        .into(),
                    );
                    from = *p;
                }
                self.route_sent(ctx, driver, &points, speed, "path segment(s)");
            }
            Command::SpoolMission {
                spooler,
                driver,
                points,
                speed,
            } => {
                if self.keeper.holds(driver) || self.keeper.kept().any(|(a, ..)| a == driver) {
                    self.keeper.release(ctx, driver);
                    self.notice(
                        false,
                        format!("{driver}: control released for the spooler {spooler}"),
                    );
                }
                let mission_id = self.next_mission_id;
                self.next_mission_id = self.next_mission_id.wrapping_add(1).max(1);
                match mission(spooler, driver, mission_id, &points, speed) {
                    Ok(m) => {
                        let tasks = m.root.children.len();
                        ctx.send_core(spooler, Resume {});
                        send(ctx, spooler, m.into());
                        self.set_route(driver.subsystem, &points);
                        if let Some(v) = self.vehicles.get_mut(&spooler.subsystem) {
                            v.mission = Some((
                                spooler,
                                MissionView {
                                    id: mission_id,
                                    status: None,
                                    tasks,
                                },
                            ));
                        }
                        self.notice(
                            false,
                            format!("{spooler}: mission {mission_id} spooled ({tasks} moves)"),
                        );
                    }
                    Err(e) => self.notice(true, format!("{spooler}: mission not spooled: {e}")),
                }
            }
            Command::StoreObstacle {
                world_model,
                point,
                radius,
                class,
            } => {
                let object = VksObject {
                    object_type: VksObjectType::Point,
                    buffer: Some(radius as f32),
                    feature_classes: vec![VksFeatureClass {
                        id: class,
                        attribute: VksAttribute::Default,
                    }],
                    points: vec![VksPoint {
                        latitude: point.latitude,
                        longitude: point.longitude,
                    }],
                };
                send(
                    ctx,
                    world_model,
                    CreateVksObjects {
                        buffered: true,
                        message_properties: 0,
                        request_id: CREATE_REQUEST,
                        objects: vec![object],
                    }
                    .into(),
                );
                // Drawn once the store lists it.
                self.next_world = None;
                self.notice(
                    false,
                    format!("{world_model}: obstacle of {radius} m stored (class {class})"),
                );
            }
            Command::Mission { spooler, action } => {
                let Some(id) = self
                    .vehicles
                    .get(&spooler.subsystem)
                    .and_then(|v| v.mission.as_ref())
                    .map(|(_, m)| m.id)
                else {
                    return;
                };
                let m: Message = match action {
                    MissionAction::Run => RunMission { mission_id: id }.into(),
                    MissionAction::Pause => PauseMission {
                        mission_id: id,
                        task_id: 0,
                    }
                    .into(),
                    MissionAction::Resume => ResumeMission {
                        mission_id: id,
                        task_id: 0,
                    }
                    .into(),
                    MissionAction::Abort => AbortMission {
                        mission_id: id,
                        task_id: 0,
                    }
                    .into(),
                };
                self.notice(false, format!("{spooler}: {} (mission {id})", m.name()));
                if matches!(action, MissionAction::Run | MissionAction::Resume) {
                    // The spooler runs missions only in Ready; after an emergency is
                    // cleared it is in Standby.
                    ctx.send_core(spooler, Resume {});
                }
                send(ctx, spooler, m);
                self.next_mission = None;
            }
        }
    }

    /// After a route's elements: the travel speed (after Resume: Part 1 resets it on
    /// Standby → Ready), the route drawn, a notice.
    fn route_sent<I: Interface>(
        &mut self,
        ctx: &mut Context<'_, I>,
        driver: Address,
        points: &[GeoPoint],
        speed: f64,
        what: &str,
    ) {
        send_std(ctx, driver, SetTravelSpeed { speed }.into());
        self.set_route(driver.subsystem, points);
        self.notice(
            false,
            format!("{driver}: {} {what} at {speed} m/s", points.len()),
        );
    }

    fn set_route(&mut self, subsystem: u8, points: &[GeoPoint]) {
        let Some(frame) = self.frame else { return };
        if let Some(v) = self.vehicles.get_mut(&subsystem) {
            v.route = points
                .iter()
                .map(|p| {
                    let l = frame.to_local(p.latitude, p.longitude);
                    (l.y, l.x)
                })
                .collect();
        }
    }
}

/// A mission of blocking moves of `driver`, one task per point, as `spooler` sends it.
fn mission(
    spooler: Address,
    driver: Address,
    mission_id: u16,
    points: &[GeoPoint],
    speed: f64,
) -> Result<SpoolMission, crate::codec::EncodeError> {
    let mut children = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        let uid = 10 * (i as u16 + 1);
        let moves: [(Message, bool); 3] = [
            (Resume {}.into(), false),
            (SetTravelSpeed { speed }.into(), false),
            (
                SetGlobalWaypoint {
                    waypoint_number: 0,
                    latitude: p.latitude,
                    longitude: p.longitude,
                    ..SetGlobalWaypoint::default()
                }
                .into(),
                true,
            ),
        ];
        let messages = moves
            .iter()
            .enumerate()
            .map(|(j, (m, blocking))| command(uid + j as u16, spooler, driver, m, *blocking))
            .collect::<Result<Vec<MissionCommand>, _>>()?;
        children.push(leaf_task(i as u16 + 1, messages));
    }
    Ok(mission_of(mission_id, children))
}
