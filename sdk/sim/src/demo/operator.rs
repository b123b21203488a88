//! The demo's operator: the System Commander that drives the scripted run (waypoints, path
//! segments, the spooled mission, the obstacle round) and keeps its trail.

use std::time::{Duration, Instant};

use nalgebra::Vector2;

use jaus::component::{CoreState, Refused};
use jaus::components::system_commander::{Ctx, SystemCommander};
use jaus::messages::*;
use jaus::stock::commander::{ControlEvent, ControlKeeper};
use jaus::stock::geo::LocalFrame;
use jaus::stock::spooler::{command, leaf_task, mission_of};
use jaus::Address;

use super::plan::{merge_overlapping, plan_round, Found};
use super::*;

/// The scripted operator.
#[derive(Debug, Default)]
pub struct Operator {
    pub(super) step: Step,
    pub(super) waypoint_speed: f64,
    pub(super) path_speed: f64,
    pub(super) seen_ready: bool,
    pub(super) started: Option<Instant>,
    pub(super) waypoints_done: Option<Instant>,
    pub(super) path_done: Option<Instant>,
    pub(super) mission_done: Option<Instant>,
    pub(super) horn_at: Option<Instant>,
    /// The mission's move targets as planned (a detour first if an obstacle is in the way).
    pub(super) planned: Vec<(f64, f64)>,
    /// Positions received from the Local Pose Sensor (at most `TRAIL_MAX`).
    pub(super) trail: Vec<(Instant, Vector2<f64>)>,
    /// Objects along the mission the world model returned: (stored by the operator,
    /// detected by the range sensor).
    pub(super) objects_found: (usize, usize),
    pub(super) path_started: Option<Instant>,
    pub(super) next_query: Option<Instant>,
    /// When to ask the Subsystem Commander for the mission's status next.
    pub(super) next_status: Option<Instant>,
    /// When the world model was first asked what lies along the mission.
    pub(super) world_asked: Option<Instant>,
    /// The Visual Sensor's image, and how often it was asked for.
    pub(super) image: Option<ReportImage>,
    pub(super) image_queries: u32,
    pub(super) next_image: Option<Instant>,
    /// Control of the drivers, then of the spooler (`jaus::stock::commander`).
    pub(super) keeper: ControlKeeper,
}

#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub(super) enum Step {
    #[default]
    TakeControl,
    StartWaypoints,
    Waypoints,
    StartPath,
    Path,
    StartMission,
    StoreObstacle,
    PlanMission,
    Mission,
    Done,
}

impl Operator {
    /// Asks the world model what lies along the mission (a line region with the
    /// clearance as its buffer).
    fn ask_along_mission(&mut self, ctx: &mut Ctx<'_>, frame: &LocalFrame) {
        self.world_asked.get_or_insert(ctx.now());
        self.next_query = Some(ctx.now() + Duration::from_secs(1));
        let region_points = mission_route()
            .iter()
            .map(|p| {
                let (latitude, longitude) = frame.to_global(*p);
                VksPoint {
                    latitude,
                    longitude,
                }
            })
            .collect();
        ctx.send(
            addr::WM,
            QueryVksObjects {
                filter_by_class_ids: false,
                filter_by_attributes: false,
                response_presence_vector: 1,
                request_id: 2,
                object_ids: None,
                region_type: Some(VksObjectType::Line),
                region_buffer: Some(CLEARANCE as f32),
                feature_classes: None,
                region_points: Some(region_points),
            },
        );
    }

    fn watch(&mut self, ctx: &mut Ctx<'_>, driver: Address) {
        let now = ctx.now();
        if self.next_query.is_none_or(|t| now >= t) {
            self.next_query = Some(now + Duration::from_millis(100));
            ctx.send(driver, QueryComponentStatus {});
        }
    }
}

/// Most positions the operator keeps (an hour at 10 Hz).
pub(super) const TRAIL_MAX: usize = 36_000;

impl SystemCommander for Operator {
    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        let now = ctx.now();
        if self.started.is_none() {
            // The vehicle's position as the operator sees it (x, y).
            if let Err(e) = ctx.create_service_connection(
                addr::LPS,
                <ReportLocalPose as jaus::JausMessage>::CODE,
                10.0,
                0x03,
            ) {
                tracing::warn!("no position feedback: {e}");
            }
        }
        self.started.get_or_insert(now);
        // Control of what the operator commands, taken and kept by the commander logic.
        for e in self.keeper.tick(ctx) {
            if let ControlEvent::Lost(a) = e {
                tracing::warn!(component = %a, "control lost; asking again");
            }
        }
        // A picture of the scene before the run (a query a second, five at most: a
        // lost image does not hold anything up).
        if self.image.is_none()
            && self.image_queries < 5
            && self.next_image.is_none_or(|t| now >= t)
        {
            self.image_queries += 1;
            self.next_image = Some(now + Duration::from_secs(1));
            ctx.send(addr::VS, QueryImage {});
        }
        let frame = LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2);
        match self.step {
            Step::TakeControl => {
                if self.keeper.holds(addr::GWD) && self.keeper.holds(addr::LPSD) {
                    self.step = Step::StartWaypoints;
                }
            }
            Step::StartWaypoints => {
                ctx.send_core(addr::GWD, Resume {});
                for (i, (x, y)) in WAYPOINTS.iter().enumerate() {
                    let (latitude, longitude) = frame.to_global(Vector2::new(*x, *y));
                    ctx.send(
                        addr::GWD,
                        SetGlobalWaypoint {
                            waypoint_number: i as u16,
                            latitude,
                            longitude,
                            ..Default::default()
                        },
                    );
                }
                // After Resume: Part 1 resets the travel speed on Standby -> Ready.
                ctx.send(
                    addr::GWD,
                    SetTravelSpeed {
                        speed: self.waypoint_speed,
                    },
                );
                self.seen_ready = false;
                self.step = Step::Waypoints;
            }
            Step::Waypoints => self.watch(ctx, addr::GWD),
            Step::StartPath => {
                ctx.send_core(addr::LPSD, Resume {});
                for (i, (p1, p2, w1)) in SEGMENTS.iter().enumerate() {
                    ctx.send(
                        addr::LPSD,
                        SetLocalPathSegment {
                            path_segment_number: i as u16,
                            p1_x: p1.0,
                            p1_y: p1.1,
                            p1_z: None,
                            p2_x: p2.0,
                            p2_y: p2.1,
                            p2_z: None,
                            weighting_factor: *w1,
                        },
                    );
                }
                ctx.send(
                    addr::LPSD,
                    SetTravelSpeed {
                        speed: self.path_speed,
                    },
                );
                self.path_started = Some(now);
                self.seen_ready = false;
                self.step = Step::Path;
            }
            Step::Path => self.watch(ctx, addr::LPSD),
            Step::StartMission => {
                // Let go of the drivers: the spooler drives them in the mission, handed
                // to it by the Subsystem Commander.
                for d in [addr::GWD, addr::LPSD] {
                    self.keeper.release(ctx, d);
                }
                self.step = Step::StoreObstacle;
            }
            Step::StoreObstacle => {
                // Store the obstacle in the world model, then ask it what lies along the
                // first leg of the mission.
                let ((x, y), r) = OBSTACLE;
                let (latitude, longitude) = frame.to_global(Vector2::new(x, y));
                ctx.send(
                    addr::WM,
                    CreateVksObjects {
                        buffered: true,
                        message_properties: 0,
                        request_id: 1,
                        objects: vec![VksObject {
                            object_type: VksObjectType::Point,
                            buffer: Some(r as f32),
                            feature_classes: vec![VksFeatureClass {
                                id: OPERATOR_CLASS,
                                attribute: VksAttribute::Default,
                            }],
                            points: vec![VksPoint {
                                latitude,
                                longitude,
                            }],
                        }],
                    },
                );
                self.ask_along_mission(ctx, &frame);
                self.step = Step::PlanMission;
            }
            // A query or its report may be lost: asked again every second until
            // answered.
            Step::PlanMission => {
                if self.next_query.is_none_or(|t| now >= t) {
                    self.ask_along_mission(ctx, &frame);
                }
            }
            Step::Mission => {
                let now = ctx.now();
                if self.horn_at.is_none() && self.next_query.is_none_or(|t| now >= t) {
                    self.next_query = Some(now + Duration::from_millis(100));
                    ctx.send(addr::PD, QueryDiscreteDevices { presence_vector: 2 });
                }
                // The Subsystem Commander reports the mission's end once; asked for it
                // every second too, in case that report is lost.
                if self.next_status.is_none_or(|t| now >= t) {
                    self.next_status = Some(now + Duration::from_secs(1));
                    ctx.send(
                        addr::SC,
                        QueryMissionStatus {
                            presence_vector: 1,
                            status_type: MissionStatusType::Mission,
                            mission_id: 1,
                            task_id: 0,
                            task_msg_id: 0,
                        },
                    );
                }
            }
            Step::Done => {}
        }
    }

    fn on_other_message(
        &mut self,
        ctx: &mut Ctx<'_>,
        msg: &Message,
    ) -> Result<Option<Message>, Refused> {
        match msg {
            Message::ReportLocalPose(p) => {
                if let (Some(x), Some(y)) = (p.x, p.y) {
                    if self.trail.len() < TRAIL_MAX {
                        self.trail.push((ctx.now(), Vector2::new(x, y)));
                    }
                }
            }
            Message::ReportVksObjects(r) if self.step == Step::PlanMission && r.request_id == 2 => {
                let frame = LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2);
                let objects: Vec<Found> = r
                    .objects
                    .iter()
                    .flatten()
                    .filter_map(|o| {
                        let p = o.points.first()?;
                        Some(Found {
                            centre: frame.to_local(p.latitude, p.longitude),
                            buffer: f64::from(o.buffer),
                            operator: o.feature_classes.iter().any(|c| c.id == OPERATOR_CLASS),
                        })
                    })
                    .collect();
                // The query may overtake the obstacle it is to find (a query is not
                // held behind a command): until 5 s have passed, an answer without the
                // operator's own obstacle waits for the next one.
                let asked = *self.world_asked.get_or_insert(ctx.now());
                if !objects.iter().any(|o| o.operator)
                    && ctx.now().saturating_duration_since(asked) < Duration::from_secs(5)
                {
                    return Ok(None);
                }
                let objects = merge_overlapping(objects);
                self.objects_found = (
                    objects.iter().filter(|o| o.operator).count(),
                    objects.iter().filter(|o| !o.operator).count(),
                );
                let plan = plan_round(&mission_route(), &objects);
                self.planned = plan.clone();
                // The subsystem's missions go through its Subsystem Commander, which
                // holds the spooler, hands the mission over and reports back.
                ctx.send(
                    addr::SC,
                    mission_message(&frame, self.waypoint_speed, &plan),
                );
                ctx.send(addr::SC, RunMission { mission_id: 1 });
                self.step = Step::Mission;
            }
            Message::ReportMissionStatus(r)
                if self.step == Step::Mission
                    && r.status_type == MissionStatusType::Mission
                    && r.status == MissionStatus::Finished =>
            {
                self.mission_done = Some(ctx.now());
                self.step = Step::Done;
            }
            Message::ReportImage(r) if self.image.is_none() => {
                self.image = Some(r.clone());
            }
            Message::ReportDiscreteDevices(d)
                if self.horn_at.is_none() && d.parking_brake_and_horn.is_some_and(|p| p.horn) =>
            {
                self.horn_at = Some(ctx.now());
            }
            _ => {}
        }
        if let (Message::ReportComponentStatus(s), Some(from)) = (msg, ctx.source()) {
            self.keeper.on_status(from, s);
        }
        if let Message::ReportComponentStatus(s) = msg {
            let state = CoreState::from_wire(s.primary_status_code);
            let from = ctx.source();
            let (driver, next) = match self.step {
                Step::Waypoints => (addr::GWD, Step::StartPath),
                Step::Path => (addr::LPSD, Step::StartMission),
                _ => return Ok(None),
            };
            if from != Some(driver) {
                return Ok(None);
            }
            match state {
                Some(CoreState::Ready) => self.seen_ready = true,
                Some(CoreState::Standby) if self.seen_ready => {
                    match self.step {
                        Step::Waypoints => self.waypoints_done = Some(ctx.now()),
                        _ => self.path_done = Some(ctx.now()),
                    }
                    self.step = next;
                }
                _ => {}
            }
        }
        Ok(None)
    }
}

/// The Spool Mission of the third phase.
pub(super) fn mission_message(
    frame: &LocalFrame,
    speed: f64,
    moves: &[(f64, f64)],
) -> SpoolMission {
    // Every message here encodes (fixed fields in range); an encoding error would be a
    // bug of this function, so fall back to an empty body rather than panic.
    let cmd = |uid: u16, to: Address, m: Message, blocking: bool| {
        command(uid, addr::MS, to, &m, blocking).unwrap_or(MissionCommand {
            uid,
            message: jaus::Packet::new(jaus::Header::new(m.code(), to, addr::MS), Vec::new()),
            blocking: u8::from(blocking),
        })
    };
    let goto = |uid: u16, (x, y): (f64, f64)| {
        let (latitude, longitude) = frame.to_global(Vector2::new(x, y));
        let w = SetGlobalWaypoint {
            waypoint_number: 0,
            latitude,
            longitude,
            ..Default::default()
        };
        vec![
            cmd(uid, addr::GWD, Resume {}.into(), false),
            cmd(uid + 1, addr::GWD, SetTravelSpeed { speed }.into(), false),
            cmd(uid + 2, addr::GWD, w.into(), true),
        ]
    };
    let leaf = leaf_task;
    let horn = SetDiscreteDevices {
        parking_brake_and_horn: Some(ParkingBrakeHorn {
            parking_brake: false,
            horn: true,
            reserved: 0,
        }),
        ..Default::default()
    };
    // Every move but the last, then the payload action, then the move home.
    let (home, outbound) = moves
        .split_last()
        .map_or((MISSION[1], &[][..]), |(h, o)| (*h, o));
    let mut children: Vec<MissionTask> = outbound
        .iter()
        .enumerate()
        .map(|(i, m)| leaf(i as u16 + 1, goto(10 * (i as u16 + 1), *m)))
        .collect();
    let n = children.len() as u16;
    children.push(leaf(n + 1, vec![cmd(500, addr::PD, horn.into(), false)]));
    children.push(leaf(n + 2, goto(600, home)));
    mission_of(1, children)
}

/// The mission as driven: from P4 (where the path segments end) through the moves.
pub(super) fn mission_route() -> Vec<Vector2<f64>> {
    let mut route = vec![Vector2::new(SEGMENTS[1].1 .0, SEGMENTS[1].1 .1)];
    route.extend(MISSION.iter().map(|(x, y)| Vector2::new(*x, *y)));
    route
}
