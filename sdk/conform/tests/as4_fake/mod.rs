//! A small AS-4 vehicle for the judge's tests: one component (5.1.1) answering the IOP
//! scenario's messages from a little state (control, management state, pose, a list of
//! local waypoints it drives at the speed given), with faults to switch on.

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::net::as5669a::{As4Endpoint, As4Id, As4Message, As4Send};
use jaus::CommandCode;
use jaus_as4::messages::*;

/// The fake's id.
pub const VEHICLE: As4Id = As4Id::new(5, 1, 1);

/// What the fake does wrong.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Faults {
    /// Report Control names 42.1.2 instead of the controller.
    pub wrong_controller: bool,
    /// Resume changes nothing.
    pub ignore_resume: bool,
    /// Report Velocity State carries every field whatever is asked.
    pub all_velocity_fields: bool,
    /// Execute List is accepted but the vehicle never moves.
    pub stuck: bool,
}

/// The fake vehicle.
#[derive(Debug)]
pub struct FakeVehicle {
    faults: Faults,
    controller: Option<As4Id>,
    state: ComponentState,
    x: f64,
    y: f64,
    yaw: f64,
    /// UID, x, y in list order.
    list: Vec<(u16, f64, f64)>,
    active: Option<usize>,
    speed: f64,
    last: Option<Instant>,
    /// Messages handled, by name (for the tests to look at).
    pub seen: Vec<String>,
}

/// The tick of the motion model.
const TICK: Duration = Duration::from_millis(100);

impl FakeVehicle {
    /// A vehicle in Standby at 0, 0 with nobody in control.
    pub fn new(faults: Faults) -> Self {
        FakeVehicle {
            faults,
            controller: None,
            state: ComponentState::Standby,
            x: 0.0,
            y: 0.0,
            yaw: 0.0,
            list: Vec::new(),
            active: None,
            speed: 0.0,
            last: None,
            seen: Vec::new(),
        }
    }

    /// Its state.
    pub fn state(&self) -> ComponentState {
        self.state
    }

    /// Its position.
    pub fn position(&self) -> (f64, f64) {
        (self.x, self.y)
    }

    fn ready_from_controller(&self, from: As4Id) -> bool {
        self.controller == Some(from) && self.state == ComponentState::Ready
    }

    fn answer(&mut self, now: Instant, from: As4Id, m: &Message) -> Option<Message> {
        let controls = self.controller == Some(from);
        Some(match m {
            Message::QueryIdentification(q) => ReportIdentification {
                query_type: q.query_type,
                entity_type: EntityType::Vehicle,
                identification: "fake vehicle".into(),
            }
            .into(),
            Message::QueryServices(_) => {
                let uris = [
                    "urn:jaus:jss:core:Transport",
                    "urn:jaus:jss:core:Events",
                    "urn:jaus:jss:core:AccessControl",
                    "urn:jaus:jss:core:Management",
                    "urn:jaus:jss:core:Discovery",
                    "urn:jaus:jss:core:ListManager",
                    "urn:jaus:jss:mobility:VelocityStateSensor",
                    "urn:jaus:jss:mobility:LocalPoseSensor",
                    "urn:jaus:jss:mobility:LocalWaypointListDriver",
                ];
                ReportServices {
                    nodes: vec![NodeServices {
                        node_id: VEHICLE.node,
                        components: vec![ComponentServices {
                            component_id: VEHICLE.component,
                            instance_id: 0,
                            services: uris
                                .iter()
                                .map(|u| ServiceInfo {
                                    uri: (*u).into(),
                                    major_version: 1,
                                    minor_version: 0,
                                })
                                .collect(),
                        }],
                    }],
                }
                .into()
            }
            Message::QueryControl(_) => {
                let c = match (self.controller, self.faults.wrong_controller) {
                    (Some(_), true) => As4Id::new(42, 1, 2),
                    (Some(c), false) => c,
                    (None, _) => As4Id::default(),
                };
                ReportControl {
                    controller: ComponentAddress {
                        subsystem_id: c.subsystem,
                        node_id: c.node,
                        component_id: c.component,
                    },
                    authority_code: if self.controller.is_some() { 255 } else { 0 },
                }
                .into()
            }
            Message::RequestControl(_) => {
                let ok = self.controller.is_none() || controls;
                if ok {
                    self.controller = Some(from);
                }
                ConfirmControl {
                    response_code: if ok {
                        ControlConfirmation::ControlAccepted
                    } else {
                        ControlConfirmation::NotAvailable
                    },
                }
                .into()
            }
            Message::ReleaseControl(_) if controls => {
                self.controller = None;
                RejectControl {
                    response_code: ControlRejection::ControlReleased,
                }
                .into()
            }
            Message::QueryTimeout(_) => ReportTimeout { timeout: 3 }.into(),
            Message::QueryStatus(_) => ReportStatus {
                status: self.state,
                reserved: 0,
            }
            .into(),
            Message::Resume(_) if controls && !self.faults.ignore_resume => {
                if self.state == ComponentState::Standby {
                    self.state = ComponentState::Ready;
                }
                return None;
            }
            Message::Standby(_) if controls => {
                if self.state == ComponentState::Ready {
                    self.state = ComponentState::Standby;
                    self.active = None;
                }
                return None;
            }
            Message::Shutdown(_) if controls => {
                self.state = ComponentState::Shutdown;
                self.active = None;
                return None;
            }
            Message::QueryVelocityState(q) => {
                let pv = if self.faults.all_velocity_fields {
                    0x01FF
                } else {
                    q.presence_vector
                };
                let moving = self.active.is_some();
                let has = |b: u16| pv & (1 << b) != 0;
                ReportVelocityState {
                    velocity_x: has(0).then_some(if moving { self.speed } else { 0.0 }),
                    velocity_y: has(1).then_some(0.0),
                    velocity_z: has(2).then_some(0.0),
                    velocity_rms: has(3).then_some(0.1),
                    roll_rate: has(4).then_some(0.0),
                    pitch_rate: has(5).then_some(0.0),
                    yaw_rate: has(6).then_some(0.0),
                    rate_rms: has(7).then_some(0.1),
                    time_stamp: has(8).then(|| TimeStamp {
                        second: 7,
                        ..TimeStamp::default()
                    }),
                }
                .into()
            }
            Message::SetLocalPose(p) if self.ready_from_controller(from) => {
                self.x = p.x.unwrap_or(self.x);
                self.y = p.y.unwrap_or(self.y);
                self.yaw = p.yaw.unwrap_or(self.yaw);
                return None;
            }
            Message::QueryLocalPose(q) => {
                let has = |b: u16| q.presence_vector & (1 << b) != 0;
                ReportLocalPose {
                    x: has(0).then_some(self.x),
                    y: has(1).then_some(self.y),
                    yaw: has(6).then_some(self.yaw),
                    time_stamp: has(8).then(TimeStamp::default),
                    ..ReportLocalPose::default()
                }
                .into()
            }
            Message::SetElement(s) if self.ready_from_controller(from) => {
                for e in &s.elements {
                    match e.message() {
                        Some(Ok(Message::SetLocalWaypoint(w))) => self.list.push((e.uid, w.x, w.y)),
                        _ => {
                            return Some(
                                RejectElementRequest {
                                    request_id: s.request_id,
                                    response_code: ElementRejection::UnsupportedElementType,
                                }
                                .into(),
                            )
                        }
                    }
                }
                ConfirmElementRequest {
                    request_id: s.request_id,
                }
                .into()
            }
            Message::QueryElementList(_) => ReportElementList {
                element_uids: self.list.iter().map(|e| e.0).collect(),
            }
            .into(),
            Message::QueryElementCount(_) => ReportElementCount {
                element_count: self.list.len() as u16,
            }
            .into(),
            Message::ExecuteList(e) if self.ready_from_controller(from) => {
                let start = e
                    .element_uid
                    .unwrap_or(self.list.first().map_or(0, |l| l.0));
                self.active = self.list.iter().position(|l| l.0 == start);
                self.speed = e.speed;
                self.last = Some(now);
                return None;
            }
            Message::QueryActiveElement(_) => ReportActiveElement {
                element_uid: self.active.map_or(0, |i| self.list[i].0),
            }
            .into(),
            Message::QueryTravelSpeed(_) => ReportTravelSpeed {
                speed: if self.active.is_some() {
                    self.speed
                } else {
                    0.0
                },
            }
            .into(),
            Message::QueryLocalWaypoint(_) => {
                let (x, y) = self
                    .active
                    .map_or((0.0, 0.0), |i| (self.list[i].1, self.list[i].2));
                ReportLocalWaypoint {
                    x,
                    y,
                    ..ReportLocalWaypoint::default()
                }
                .into()
            }
            _ => return None,
        })
    }

    fn drive(&mut self, now: Instant) {
        let Some(i) = self.active else { return };
        let dt = self
            .last
            .map_or(0.0, |l| now.saturating_duration_since(l).as_secs_f64());
        self.last = Some(now);
        if self.faults.stuck {
            return;
        }
        let (_, tx, ty) = self.list[i];
        let (dx, dy) = (tx - self.x, ty - self.y);
        let d = dx.hypot(dy);
        let step = self.speed * dt;
        if d <= step.max(0.05) {
            self.x = tx;
            self.y = ty;
            self.active = (i + 1 < self.list.len()).then_some(i + 1);
        } else {
            self.x += dx / d * step;
            self.y += dy / d * step;
        }
    }
}

impl As4Endpoint<SocketAddr> for FakeVehicle {
    fn handle(
        &mut self,
        now: Instant,
        _from: SocketAddr,
        messages: Vec<As4Message>,
    ) -> Vec<As4Message> {
        let mut out = Vec::new();
        for m in messages {
            let for_me = m.destination == VEHICLE
                || m.destination == As4Id::new(0xFFFF, 0xFF, 0xFF)
                || m.destination == As4Id::new(VEHICLE.subsystem, 0xFF, 0xFF);
            if !for_me {
                continue;
            }
            let Ok(msg) = Message::decode(CommandCode(m.message_id), &m.body) else {
                continue;
            };
            // Shut down: it still tells its state, and nothing else.
            if self.state == ComponentState::Shutdown && !matches!(msg, Message::QueryStatus(_)) {
                continue;
            }
            self.seen.push(msg.name().to_string());
            self.drive(now);
            if let Some(reply) = self.answer(now, m.source, &msg) {
                if let Ok(body) = reply.to_bytes() {
                    let mut r = m.reply(reply.code().0, body);
                    r.source = VEHICLE;
                    out.push(r);
                }
            }
        }
        out
    }

    fn handle_timeout(&mut self, now: Instant) -> Vec<As4Send<SocketAddr>> {
        self.drive(now);
        Vec::new()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        self.active.and(self.last).map(|l| l + TICK)
    }
}
