//! The RA 3.3 side of a gateway, sans-IO: the environment ([`Ra33Side`]) that the
//! Mobility services of [`crate::mobility`] read and command through.
//!
//! It keeps the latest report of each RA 3.3 component it polls, sends what the services
//! ask (bounded, counted when full), holds RA 3.3 control of the drivers while an AS-4
//! client holds control of the AS-4 component, and keeps the AS-4 local frame (Set Local
//! Pose moves it; RA 3.3 has no way to set a pose sensor).

use std::collections::{HashMap, VecDeque};
use std::time::{Duration, Instant};

use jaus::messages::{
    ConfirmComponentControl, ControlResponse, JausService, Message as Ra33Message, QueryLevel,
    ReleaseComponentControl, ReportIdentification, ReportServices, RequestComponentControl, Resume,
    ServiceCommand, Standby,
};
use jaus::stock::geo::LocalFrame;
use jaus::JausMessage;
use jaus::{Address, CommandCode};

/// The gateway's name in RA 3.3 Report Identification.
pub const IDENTIFICATION: &str = "AS-4 gateway";

/// Most RA 3.3 messages waiting to leave (more are dropped and counted).
pub const MAX_OUTBOX: usize = 1024;

/// A poll left unanswered this many times in a row starts backing off: each further
/// unanswered poll doubles its period, up to [`MAX_POLL_PERIOD`].
pub const BACKOFF_AFTER: u32 = 3;

/// The longest period a backed-off poll waits.
pub const MAX_POLL_PERIOD: Duration = Duration::from_secs(30);

/// A poll left unanswered this many times in a row stops (counted, logged): the
/// component never answers that query (OpenJAUS 3.3's primitive driver and Query Wrench
/// Effort). A report of its kind from the component starts it again.
pub const GIVE_UP_AFTER: u32 = 10;

/// The RA 3.3 components a gateway presents as AS-4 services (any may be missing: the
/// service that needs it is then not offered).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Targets {
    /// Velocity State Sensor.
    pub velocity_state_sensor: Option<Address>,
    /// Local Pose Sensor.
    pub local_pose_sensor: Option<Address>,
    /// Global Pose Sensor.
    pub global_pose_sensor: Option<Address>,
    /// Primitive Driver.
    pub primitive_driver: Option<Address>,
    /// Local Waypoint Driver.
    pub local_waypoint_driver: Option<Address>,
    /// Global Waypoint Driver.
    pub global_waypoint_driver: Option<Address>,
    /// Local Path Segment Driver.
    pub local_path_segment_driver: Option<Address>,
    /// Global Path Segment Driver.
    pub global_path_segment_driver: Option<Address>,
}

impl Targets {
    /// The drivers the gateway takes RA 3.3 control of as soon as an AS-4 client
    /// controls it: the waypoint and path segment drivers. The Primitive Driver is
    /// taken only when the AS-4 client commands efforts ([`Ra33Side::ensure_control`]):
    /// the other drivers reach it through the Reflexive Driver, which must hold it.
    pub fn drivers(&self) -> impl Iterator<Item = Address> {
        [
            self.local_waypoint_driver,
            self.global_waypoint_driver,
            self.local_path_segment_driver,
            self.global_path_segment_driver,
        ]
        .into_iter()
        .flatten()
    }

    /// The components of subsystem `ss` with the standard component ids of Part 1
    /// (instance 1), on any node: for a gateway in front of a whole subsystem, before
    /// discovery tells it more.
    pub fn of_tree(tree: &jaus::net::SystemTree, ss: u8) -> Targets {
        use jaus::components as c;
        let all = tree.components();
        let find = |id: u8| {
            all.iter()
                .copied()
                .find(|a| a.subsystem == ss && a.component == id)
        };
        Targets {
            velocity_state_sensor: find(c::velocity_state_sensor::ID),
            local_pose_sensor: find(c::local_pose_sensor::ID),
            global_pose_sensor: find(c::global_pose_sensor::ID),
            primitive_driver: find(c::primitive_driver::ID),
            local_waypoint_driver: find(c::local_waypoint_driver::ID),
            global_waypoint_driver: find(c::global_waypoint_driver::ID),
            local_path_segment_driver: find(c::local_path_segment_driver::ID),
            global_path_segment_driver: find(c::global_path_segment_driver::ID),
        }
    }
}

/// Where RA 3.3 control of one driver stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ra33Control {
    /// Not asked for.
    None,
    /// Requested; no answer yet.
    Requested,
    /// Granted.
    Granted,
    /// Refused (with the response code).
    Refused(ControlResponse),
}

/// A rigid 2-D transform: AS-4 local = rotate(yaw) · RA 3.3 local + (x, y).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Frame {
    /// Translation along X, metres.
    pub x: f64,
    /// Translation along Y, metres.
    pub y: f64,
    /// Rotation, radians.
    pub yaw: f64,
}

impl Frame {
    /// A point of the RA 3.3 local frame in the AS-4 one.
    pub fn to_as4(&self, x: f64, y: f64) -> (f64, f64) {
        let (s, c) = self.yaw.sin_cos();
        (c * x - s * y + self.x, s * x + c * y + self.y)
    }

    /// A point of the AS-4 local frame in the RA 3.3 one.
    pub fn to_ra33(&self, x: f64, y: f64) -> (f64, f64) {
        let (s, c) = self.yaw.sin_cos();
        let (dx, dy) = (x - self.x, y - self.y);
        (c * dx + s * dy, -s * dx + c * dy)
    }

    /// A heading of the RA 3.3 local frame in the AS-4 one, in (-π, π].
    pub fn yaw_to_as4(&self, yaw: f64) -> f64 {
        wrap(yaw + self.yaw)
    }

    /// A heading of the AS-4 local frame in the RA 3.3 one.
    pub fn yaw_to_ra33(&self, yaw: f64) -> f64 {
        wrap(yaw - self.yaw)
    }

    /// The frame in which the RA 3.3 pose (`x`, `y`, `yaw`) reads as the AS-4 pose
    /// (`ax`, `ay`, `ayaw`).
    pub fn placing(x: f64, y: f64, yaw: f64, ax: f64, ay: f64, ayaw: f64) -> Frame {
        let r = wrap(ayaw - yaw);
        let (s, c) = r.sin_cos();
        Frame {
            x: ax - (c * x - s * y),
            y: ay - (s * x + c * y),
            yaw: r,
        }
    }
}

fn wrap(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    let w = a.rem_euclid(t);
    if w > std::f64::consts::PI {
        w - t
    } else {
        w
    }
}

/// A query sent on a schedule, to keep a report fresh.
#[derive(Debug, Clone)]
struct Poll {
    to: Address,
    query: Ra33Message,
    every: Duration,
    due: Instant,
    /// Polls sent since the last report of the query's kind from `to`.
    unanswered: u32,
    /// Stopped after [`GIVE_UP_AFTER`] unanswered polls.
    given_up: bool,
}

/// Counters of the RA 3.3 side.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Ra33Stats {
    /// Messages queued for RA 3.3 components.
    pub sent: u64,
    /// Dropped: the outbox was full.
    pub outbox_full: u64,
    /// Reports received and kept.
    pub reports: u64,
    /// Messages received that the gateway has no use for.
    pub ignored: u64,
    /// Polls sent while the previous one of the same query was still unanswered.
    pub polls_unanswered: u64,
    /// Polls stopped: the component left [`GIVE_UP_AFTER`] of them unanswered in a row.
    pub polls_given_up: u64,
}

/// The RA 3.3 side of a gateway: its own address, the components it presents, their
/// latest reports, control of the drivers, and its outbox.
#[derive(Debug)]
pub struct Ra33Side {
    me: Address,
    targets: Targets,
    authority: u8,
    poll_period: Duration,
    outbox: VecDeque<(Address, Ra33Message)>,
    latest: HashMap<(Address, CommandCode), (Instant, Ra33Message)>,
    polls: Vec<Poll>,
    control: HashMap<Address, Ra33Control>,
    want_control: bool,
    ready: bool,
    active: Option<Address>,
    /// The AS-4 local frame relative to the RA 3.3 one (Set Local Pose moves it).
    pub frame: Frame,
    /// A local frame (x north, y east) at the first global position the Global Pose
    /// Sensor reported: the RA 3.3 local frame of a subsystem without a Local Pose
    /// Sensor ([`crate::mobility::derived`]).
    tangent: Option<LocalFrame>,
    stats: Ra33Stats,
}

impl Ra33Side {
    /// The RA 3.3 side of a gateway at RA 3.3 address `me` in front of `targets`,
    /// requesting control with `authority` and polling each sensor every `poll_period`.
    pub fn new(me: Address, targets: Targets, authority: u8, poll_period: Duration) -> Self {
        Self {
            me,
            targets,
            authority,
            poll_period,
            outbox: VecDeque::new(),
            latest: HashMap::new(),
            polls: Vec::new(),
            control: HashMap::new(),
            want_control: false,
            ready: false,
            active: None,
            frame: Frame::default(),
            tangent: None,
            stats: Ra33Stats::default(),
        }
    }

    /// Its RA 3.3 address.
    pub fn address(&self) -> Address {
        self.me
    }

    /// The components it presents.
    pub fn targets(&self) -> &Targets {
        &self.targets
    }

    /// The components it presents, once found (control follows: drivers found while an
    /// AS-4 client holds control are asked for at once).
    pub fn set_targets(&mut self, targets: Targets) {
        let before: Vec<Address> = self.targets.drivers().collect();
        self.targets = targets;
        if self.want_control {
            let new: Vec<Address> = targets.drivers().filter(|d| !before.contains(d)).collect();
            for d in new {
                self.control.insert(d, Ra33Control::Requested);
                self.send(
                    d,
                    RequestComponentControl {
                        authority_code: self.authority,
                    },
                );
            }
        }
    }

    /// Counters.
    pub fn stats(&self) -> Ra33Stats {
        self.stats
    }

    /// Queues `message` for `to` (dropped and counted when the outbox is full).
    pub fn send(&mut self, to: Address, message: impl Into<Ra33Message>) {
        if self.outbox.len() >= MAX_OUTBOX {
            self.stats.outbox_full += 1;
            tracing::warn!(gateway = %self.me, %to, "RA 3.3 outbox full: message dropped");
            return;
        }
        self.stats.sent += 1;
        self.outbox.push_back((to, message.into()));
    }

    /// The next message for an RA 3.3 component.
    pub fn poll_transmit(&mut self) -> Option<(Address, Ra33Message)> {
        self.outbox.pop_front()
    }

    /// Keeps `query` to `to` going every poll period, from `now` on (once per pair).
    pub fn keep_polling(&mut self, now: Instant, to: Address, query: impl Into<Ra33Message>) {
        let query = query.into();
        if self
            .polls
            .iter()
            .any(|p| p.to == to && p.query.code() == query.code())
        {
            return;
        }
        self.polls.push(Poll {
            to,
            query,
            every: self.poll_period,
            due: now,
            unanswered: 0,
            given_up: false,
        });
    }

    /// The latest report with code `code` from `from`, with when it came.
    pub fn latest(&self, from: Address, code: CommandCode) -> Option<(Instant, &Ra33Message)> {
        self.latest.get(&(from, code)).map(|(t, m)| (*t, m))
    }

    /// The local frame placed at the first global position reported (`None` until the
    /// Global Pose Sensor has reported one).
    pub fn tangent(&self) -> Option<&LocalFrame> {
        self.tangent.as_ref()
    }

    /// RA 3.3 control of `driver`.
    pub fn control_of(&self, driver: Address) -> Ra33Control {
        self.control
            .get(&driver)
            .copied()
            .unwrap_or(Ra33Control::None)
    }

    /// A message from an RA 3.3 component.
    pub fn on_message(&mut self, now: Instant, from: Address, message: Ra33Message) {
        match &message {
            Ra33Message::ConfirmComponentControl(ConfirmComponentControl { response_code }) => {
                let state = if *response_code == ControlResponse::ControlAccepted {
                    Ra33Control::Granted
                } else {
                    tracing::warn!(gateway = %self.me, driver = %from, ?response_code, "RA 3.3 control refused");
                    Ra33Control::Refused(*response_code)
                };
                self.control.insert(from, state);
                if state == Ra33Control::Granted && self.ready && self.active == Some(from) {
                    self.send(from, Resume {});
                }
            }
            Ra33Message::RejectComponentControl(_) => {
                tracing::info!(gateway = %self.me, driver = %from, "RA 3.3 control taken away");
                self.control.insert(from, Ra33Control::None);
            }
            Ra33Message::QueryServices(_) => {
                // An RA 3.3 component answers Query Services (OpenJAUS's node manager
                // asks every component it finds): what this side takes and sends.
                self.send(from, services());
            }
            Ra33Message::QueryIdentification(q) if q.query_field == QueryLevel::Component => {
                // Who this component is, for the node managers' system trees.
                self.send(
                    from,
                    ReportIdentification {
                        query_type: QueryLevel::Component,
                        authority: self.authority,
                        identification_type: 0,
                        identification: IDENTIFICATION.to_string(),
                    },
                );
            }
            m if m.code().class() == jaus::wire::MessageClass::Inform => {
                if let (None, Ra33Message::ReportGlobalPose(g)) = (&self.tangent, m) {
                    if let (Some(lat), Some(lon)) = (g.latitude, g.longitude) {
                        if Some(from) == self.targets.global_pose_sensor {
                            tracing::info!(gateway = %self.me, latitude = lat, longitude = lon, "local frame placed at the first global position");
                            self.tangent = Some(LocalFrame::new(lat, lon, 0.0));
                        }
                    }
                }
                self.stats.reports += 1;
                self.answered(now, from, m.code());
                self.latest.insert((from, m.code()), (now, message));
            }
            _ => self.stats.ignored += 1,
        }
    }

    /// Whether an AS-4 client controls the AS-4 component: RA 3.3 control of the drivers
    /// is asked for, or given up.
    pub fn set_controlled(&mut self, controlled: bool) {
        if controlled == self.want_control {
            return;
        }
        self.want_control = controlled;
        let drivers: Vec<Address> = self.targets.drivers().collect();
        for d in drivers {
            if controlled {
                self.control.insert(d, Ra33Control::Requested);
                self.send(
                    d,
                    RequestComponentControl {
                        authority_code: self.authority,
                    },
                );
            }
        }
        if !controlled {
            let held: Vec<Address> = self
                .control
                .iter()
                .filter(|(_, c)| matches!(c, Ra33Control::Granted | Ra33Control::Requested))
                .map(|(a, _)| *a)
                .collect();
            for d in held {
                self.release(d);
            }
        }
    }

    /// Asks for RA 3.3 control of `driver` now (the AS-4 client commands it directly),
    /// unless it is held or asked for already; nothing without an AS-4 controller.
    pub fn ensure_control(&mut self, driver: Address) {
        if !self.want_control
            || matches!(
                self.control_of(driver),
                Ra33Control::Granted | Ra33Control::Requested
            )
        {
            return;
        }
        self.control.insert(driver, Ra33Control::Requested);
        self.send(
            driver,
            RequestComponentControl {
                authority_code: self.authority,
            },
        );
    }

    /// Gives up RA 3.3 control of `driver` (put in standby first) if held.
    pub fn release(&mut self, driver: Address) {
        if self.control_of(driver) == Ra33Control::Granted {
            self.send(driver, Standby {});
            self.send(driver, ReleaseComponentControl {});
        }
        self.control.insert(driver, Ra33Control::None);
    }

    /// Whether the AS-4 component is Ready. Leaving Ready puts every driver the gateway
    /// controls in standby; entering it resumes the active one, if any
    /// ([`activate`](Self::activate)).
    pub fn set_ready(&mut self, ready: bool) {
        if ready == self.ready {
            return;
        }
        self.ready = ready;
        if ready {
            if let Some(d) = self.active {
                if self.control_of(d) == Ra33Control::Granted {
                    self.send(d, Resume {});
                }
            }
            return;
        }
        self.active = None;
        let granted: Vec<Address> = self
            .control
            .iter()
            .filter(|(_, c)| **c == Ra33Control::Granted)
            .map(|(a, _)| *a)
            .collect();
        for d in granted {
            self.send(d, Standby {});
        }
    }

    /// Makes `driver` the one that moves the vehicle: it is resumed (control asked for
    /// first if needed) and every other driver the gateway controls goes to standby, so
    /// that two drivers never contend for the vehicle (two waypoint drivers in Ready
    /// would both take the Reflexive Driver).
    pub fn activate(&mut self, driver: Address) {
        self.ensure_control(driver);
        let others: Vec<Address> = self
            .control
            .iter()
            .filter(|(a, c)| **a != driver && **c == Ra33Control::Granted)
            .map(|(a, _)| *a)
            .collect();
        if self.active != Some(driver) {
            for d in others {
                self.send(d, Standby {});
            }
        }
        self.active = Some(driver);
        if self.ready && self.control_of(driver) == Ra33Control::Granted {
            self.send(driver, Resume {});
        }
    }

    /// A report with code `report` came from `from`: the polls it answers start again
    /// at the poll period.
    fn answered(&mut self, now: Instant, from: Address, report: CommandCode) {
        for p in &mut self.polls {
            if p.to == from && p.query.code().complement() == Some(report) {
                if p.given_up {
                    tracing::info!(gateway = %self.me, to = %p.to, query = p.query.name(), "answered again: polling resumes");
                    p.due = now + self.poll_period;
                }
                p.unanswered = 0;
                p.given_up = false;
                p.every = self.poll_period;
            }
        }
    }

    /// Sends the polls that are due; a poll left unanswered backs off, then stops.
    pub fn handle_timeout(&mut self, now: Instant) {
        let mut due = Vec::new();
        for p in self.polls.iter_mut().filter(|p| !p.given_up) {
            if p.due > now {
                continue;
            }
            if p.unanswered > 0 {
                self.stats.polls_unanswered += 1;
            }
            if p.unanswered >= GIVE_UP_AFTER {
                p.given_up = true;
                self.stats.polls_given_up += 1;
                tracing::warn!(gateway = %self.me, to = %p.to, query = p.query.name(), unanswered = p.unanswered, "the component never answers this query: polling stopped");
                continue;
            }
            if p.unanswered >= BACKOFF_AFTER {
                p.every = (p.every * 2).min(MAX_POLL_PERIOD);
            }
            p.unanswered += 1;
            p.due = now + p.every;
            due.push((p.to, p.query.clone()));
        }
        for (to, q) in due {
            self.send(to, q);
        }
    }

    /// When the next poll is due.
    pub fn poll_timeout(&self) -> Option<Instant> {
        self.polls
            .iter()
            .filter(|p| !p.given_up)
            .map(|p| p.due)
            .min()
    }
}

/// Report Services of the gateway's RA 3.3 side: the core service (type 0) with what it
/// answers and handles, and what it sends.
fn services() -> ReportServices {
    let entry = |code: CommandCode| ServiceCommand {
        command_code: code.0,
        presence_vector: 0,
    };
    ReportServices {
        services: vec![JausService {
            service_type: 0,
            input_commands: [
                jaus::messages::QueryIdentification::CODE,
                jaus::messages::QueryServices::CODE,
                ConfirmComponentControl::CODE,
                jaus::messages::RejectComponentControl::CODE,
            ]
            .into_iter()
            .map(entry)
            .collect(),
            output_commands: [
                ReportIdentification::CODE,
                ReportServices::CODE,
                RequestComponentControl::CODE,
                ReleaseComponentControl::CODE,
            ]
            .into_iter()
            .map(entry)
            .collect(),
        }],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_round_trip_and_placing() {
        let f = Frame::placing(3.0, 4.0, 0.5, -1.0, 2.0, 2.0);
        let (ax, ay) = f.to_as4(3.0, 4.0);
        assert!((ax + 1.0).abs() < 1e-9 && (ay - 2.0).abs() < 1e-9);
        assert!((f.yaw_to_as4(0.5) - 2.0).abs() < 1e-9);
        let (x, y) = f.to_ra33(10.0, -7.0);
        let (bx, by) = f.to_as4(x, y);
        assert!((bx - 10.0).abs() < 1e-9 && (by + 7.0).abs() < 1e-9);
        assert!((f.yaw_to_ra33(f.yaw_to_as4(3.0)) - 3.0).abs() < 1e-9);
    }

    #[test]
    fn an_unanswered_poll_backs_off_then_stops_and_an_answer_restarts_it() {
        use jaus::messages::{QueryWrenchEffort, ReportWrenchEffort};
        let me = Address::new(1, 1, 200, 1);
        let driver = Address::new(1, 1, 33, 1);
        let period = Duration::from_millis(100);
        let mut s = Ra33Side::new(me, Targets::default(), 200, period);
        let t0 = Instant::now();
        s.keep_polling(t0, driver, QueryWrenchEffort::default());
        // Run 60 s of virtual time, waking when due; count what was sent.
        let mut now = t0;
        let mut sent = Vec::new();
        while let Some(due) = s.poll_timeout() {
            if due > t0 + Duration::from_secs(60) {
                break;
            }
            now = due;
            s.handle_timeout(now);
            while s.poll_transmit().is_some() {
                sent.push(now - t0);
            }
        }
        assert_eq!(sent.len(), GIVE_UP_AFTER as usize, "{sent:?}");
        // At the period until BACKOFF_AFTER polls are unanswered, then doubling.
        assert_eq!(sent[1] - sent[0], period);
        assert_eq!(sent[3] - sent[2], period);
        assert_eq!(sent[4] - sent[3], period * 2);
        assert_eq!(sent[5] - sent[4], period * 4);
        assert_eq!(s.stats().polls_given_up, 1);
        assert_eq!(s.stats().polls_unanswered, GIVE_UP_AFTER as u64);
        assert_eq!(s.poll_timeout(), None);
        // A report of its kind (an event, or an answer after all) restarts it.
        s.on_message(now, driver, ReportWrenchEffort::default().into());
        assert_eq!(s.poll_timeout(), Some(now + period));
        s.handle_timeout(now + period);
        assert!(s.poll_transmit().is_some());
    }

    #[test]
    fn query_services_is_answered() {
        let me = Address::new(1, 1, 200, 1);
        let asker = Address::new(1, 1, 1, 1);
        let mut s = Ra33Side::new(me, Targets::default(), 200, Duration::from_millis(100));
        s.on_message(
            Instant::now(),
            asker,
            jaus::messages::QueryServices {}.into(),
        );
        match s.poll_transmit() {
            Some((to, Ra33Message::ReportServices(r))) => {
                assert_eq!(to, asker);
                assert_eq!(r.services.len(), 1);
                assert!(r.services[0]
                    .input_commands
                    .iter()
                    .any(|c| c.command_code == jaus::messages::QueryServices::CODE.0));
            }
            other => panic!("expected Report Services, got {other:?}"),
        }
    }

    #[test]
    fn outbox_is_bounded() {
        let me = Address::new(1, 1, 200, 1);
        let mut s = Ra33Side::new(me, Targets::default(), 200, Duration::from_millis(100));
        for _ in 0..MAX_OUTBOX + 5 {
            s.send(me, Resume {});
        }
        assert_eq!(s.stats().outbox_full, 5);
    }
}
