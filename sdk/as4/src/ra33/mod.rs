//! The RA 3.3 side of a gateway, sans-IO: the environment ([`Ra33Side`]) that the
//! Mobility services of [`crate::mobility`] read and command through, below both them
//! and the [`crate::gateway`] that hosts them.
//!
//! It keeps the latest report of each RA 3.3 component it polls, sends what the services
//! ask (bounded, counted when full), holds RA 3.3 control of the drivers while an AS-4
//! client holds control of the AS-4 component, and keeps the AS-4 local frame (Set Local
//! Pose moves it; RA 3.3 has no way to set a pose sensor) and the discrete devices'
//! bits it commands the Primitive Driver ([`discrete`]). A poll a component leaves
//! unanswered backs off and then stops ([`GIVE_UP_AFTER`]) until the component answers
//! it or is discovered again ([`Ra33Side::rediscovered`]). As an RA 3.3 component it
//! answers Query Identification and Query Services ([`Ra33Side::services`]).
//!
//! Commands that arrive (issue 48): on a node that makes them arrive
//! (`jaus::net::NodeConfig::reliable`), every command this side sends to an RA 3.3
//! component of another node (Request and Release Component Control, Resume, Standby,
//! the numbered Set Local/Global Waypoint and Path Segment uploads, Set Travel Speed)
//! goes with an acknowledgement requested and is resent until acknowledged; the node
//! hands the outcome back ([`Ra33Side::on_settled`]): counted ([`Ra33Stats`]), a
//! refusal or a give-up logged with the message and the driver, and a control request
//! given up asked again. The set-point streams ([`STREAMED`]) are the exception.

use std::collections::{BTreeSet, HashMap, VecDeque};
use std::time::{Duration, Instant};

use jaus::component::{Outcome, Settled};
use jaus::messages::{
    ConfirmComponentControl, ControlResponse, JausService, Message as Ra33Message, QueryLevel,
    ReleaseComponentControl, ReportIdentification, ReportServices, RequestComponentControl, Resume,
    ServiceCommand, Standby,
};
use jaus::stock::geo::LocalFrame;
use jaus::JausMessage;
use jaus::{Address, CommandCode};

pub mod discrete;
pub mod frame;
mod polls;
pub mod targets;

pub use discrete::DiscreteChange;
pub use frame::Frame;
pub use polls::{BACKOFF_AFTER, GIVE_UP_AFTER, MAX_POLL_PERIOD};
pub use targets::{Group, Targets};

use polls::Polls;

/// The gateway's name in RA 3.3 Report Identification.
pub const IDENTIFICATION: &str = "AS-4 gateway";

/// Most RA 3.3 messages waiting to leave (more are dropped and counted).
pub const MAX_OUTBOX: usize = 1024;

/// The commands this side streams, sent once and never asked for an acknowledgement
/// even on a node that makes commands arrive ([`jaus::net::Node::send_once`], which the
/// [`DualNode`](crate::gateway::DualNode) calls for them): Set Wrench Effort follows
/// each AS-4 Set Wrench Effort of the client at its rate, so the next one replaces a
/// lost one within a period, while a resent old one would arrive after (and undo) a
/// newer effort; and as the node sends a peer's tracked commands one at a time, a
/// stream waiting for each acknowledgement would fall behind the client. The
/// manipulator's velocity set-points (Set Joint Velocities, Set End Effector Velocity
/// State) are streams alike: the RA 3.3 drivers stop when they are not refreshed.
pub const STREAMED: &[CommandCode] = &[
    jaus::messages::SetWrenchEffort::CODE,
    jaus::messages::SetJointVelocities::CODE,
    jaus::messages::SetEndEffectorVelocityState::CODE,
];

/// Times a control request the node gave up on (no answer after every copy) is asked
/// again at once, to a driver known to acknowledge; after that it is asked again when
/// the client next commands the driver ([`Ra33Side::ensure_control`]).
pub const CONTROL_RETRIES: u32 = 3;

/// How long after its latest command a driver's reports are not kept while that
/// command is unsettled ([`Ra33Side::on_message`]); longer than the node's retries.
pub const UNSETTLED_MAX: Duration = Duration::from_secs(10);

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
    /// Polls sent (queries on a schedule, [`Ra33Side::keep_polling`]).
    pub polls_sent: u64,
    /// Polls left unanswered: no report of their kind had come from the component when
    /// the next one fell due (or when polling it stopped).
    pub polls_unanswered: u64,
    /// (component, query) pairs no longer polled: the component left [`GIVE_UP_AFTER`]
    /// polls of that query unanswered in a row.
    pub polls_given_up: u64,
    /// (component, query) pairs polled again after they were given up: the component
    /// answered after all, or was discovered again.
    pub polls_resumed: u64,
    /// Commands the RA 3.3 component acknowledged (the node making commands arrive).
    pub acknowledged: u64,
    /// Commands it refused (NAK).
    pub refused: u64,
    /// Commands the node gave up on: no answer after every copy.
    pub given_up: u64,
    /// Control requests asked again after the node gave up on them.
    pub control_retried: u64,
    /// Reports of a driver not kept because a command to it was still unsettled (the
    /// query overtook the command's retransmission: the report may predate it).
    pub stale_reports: u64,
}

/// The RA 3.3 side of a gateway: its own address, the components it presents, their
/// latest reports, control of the drivers, and its outbox.
#[derive(Debug)]
pub struct Ra33Side {
    me: Address,
    targets: Targets,
    authority: u8,
    outbox: VecDeque<(Address, Ra33Message)>,
    latest: HashMap<(Address, CommandCode), (Instant, Ra33Message)>,
    polls: Polls,
    /// The codes of the messages it has sent (for Report Services; bounded by the
    /// catalogue, and only this side's own messages land here).
    sent_codes: BTreeSet<CommandCode>,
    control: HashMap<Address, Ra33Control>,
    want_control: bool,
    ready: bool,
    /// The driver of each group that moves its hardware ([`Ra33Side::activate`]).
    active: HashMap<Group, Address>,
    /// How many commands each group's drivers were given ([`Ra33Side::activations`]).
    activations: HashMap<Group, u64>,
    /// The AS-4 local frame relative to the RA 3.3 one (Set Local Pose moves it).
    pub frame: Frame,
    /// A local frame (x north, y east) at the first global position the Global Pose
    /// Sensor reported: the RA 3.3 local frame of a subsystem without a Local Pose
    /// Sensor ([`crate::mobility::derived`]).
    tangent: Option<LocalFrame>,
    /// The parking brake, horn and propulsion bits commanded to each driver ([`discrete`]).
    discrete: discrete::DiscreteDevices,
    /// Control requests asked again in a row, per driver ([`CONTROL_RETRIES`]).
    control_retries: HashMap<Address, u32>,
    /// Components whose commands the node reports the outcome of (it tracks them).
    answering: BTreeSet<Address>,
    /// Commands to each of those not settled yet, and when the latest was sent.
    unsettled: HashMap<Address, (u32, Instant)>,
    /// The latest time this side was told.
    now: Option<Instant>,
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
            outbox: VecDeque::new(),
            latest: HashMap::new(),
            polls: Polls::new(poll_period),
            sent_codes: BTreeSet::new(),
            control: HashMap::new(),
            want_control: false,
            ready: false,
            active: HashMap::new(),
            activations: HashMap::new(),
            frame: Frame::default(),
            tangent: None,
            discrete: discrete::DiscreteDevices::default(),
            control_retries: HashMap::new(),
            answering: BTreeSet::new(),
            unsettled: HashMap::new(),
            now: None,
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
        let message: Ra33Message = message.into();
        let code = message.code();
        if let Some(now) = self.now.filter(|_| {
            self.answering.contains(&to)
                && code.class() == jaus::wire::MessageClass::Command
                && !STREAMED.contains(&code)
        }) {
            let u = self.unsettled.entry(to).or_insert((0, now));
            *u = (u.0 + 1, now);
        }
        self.stats.sent += 1;
        self.sent_codes.insert(message.code());
        self.outbox.push_back((to, message));
    }

    /// The next message for an RA 3.3 component.
    pub fn poll_transmit(&mut self) -> Option<(Address, Ra33Message)> {
        self.outbox.pop_front()
    }

    /// Keeps `query` to `to` going every poll period, from `now` on (once per pair).
    pub fn keep_polling(&mut self, now: Instant, to: Address, query: impl Into<Ra33Message>) {
        self.polls.keep(now, to, query.into());
    }

    /// `component` was discovered again (it left the system tree and came back, or
    /// announced itself anew): its polls start again at the poll period, from `now`,
    /// those given up included.
    pub fn rediscovered(&mut self, now: Instant, component: Address) {
        self.polls.rediscovered(now, component, &mut self.stats);
    }

    /// The (component, query code) pairs no longer polled: the component never answered
    /// them ([`GIVE_UP_AFTER`]).
    pub fn polls_given_up(&self) -> Vec<(Address, CommandCode)> {
        self.polls.given_up().collect()
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
        self.now = Some(now);
        match &message {
            Ra33Message::ConfirmComponentControl(ConfirmComponentControl { response_code }) => {
                let state = if *response_code == ControlResponse::ControlAccepted {
                    Ra33Control::Granted
                } else {
                    tracing::warn!(gateway = %self.me, driver = %from, ?response_code, "RA 3.3 control refused");
                    Ra33Control::Refused(*response_code)
                };
                self.control.insert(from, state);
                if state == Ra33Control::Granted && self.ready && self.is_active(from) {
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
                self.send(from, self.services());
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
                self.polls.answered(now, from, m.code(), &mut self.stats);
                if self.unsettled.get(&from).is_some_and(|(n, at)| {
                    *n > 0 && now.saturating_duration_since(*at) < UNSETTLED_MAX
                }) {
                    // Asked before a command the node is still resending arrived: it
                    // may show the driver without it (a waypoint count of 0 would end
                    // the list). The next poll asks again.
                    self.stats.stale_reports += 1;
                    return;
                }
                self.stats.reports += 1;
                self.latest.insert((from, m.code()), (now, message));
            }
            _ => self.stats.ignored += 1,
        }
    }

    /// How a command this side sent ended, as the node learnt it (acknowledged,
    /// refused, given up; see the module's documentation). A control request refused
    /// leaves control refused; one given up while still unanswered is asked again, at
    /// once to a driver known to acknowledge ([`CONTROL_RETRIES`] times), else when
    /// the driver is next commanded.
    pub fn on_settled(&mut self, now: Instant, s: Settled) {
        self.now = Some(now);
        if s.peer_known {
            self.answering.insert(s.to);
        }
        if let Some(u) = self.unsettled.get_mut(&s.to) {
            u.0 = u.0.saturating_sub(1);
            if u.0 == 0 {
                self.unsettled.remove(&s.to);
            }
        }
        let name = jaus::MessageInfo::of(s.code).map_or("(unknown message)", |i| i.name);
        let control = s.code == RequestComponentControl::CODE;
        match s.outcome {
            Outcome::Acknowledged => {
                self.stats.acknowledged += 1;
                if control {
                    self.control_retries.remove(&s.to);
                }
                return;
            }
            Outcome::Refused => {
                self.stats.refused += 1;
                tracing::warn!(gateway = %self.me, driver = %s.to, message = name, "RA 3.3 command refused (NAK)");
                if control && self.control_of(s.to) == Ra33Control::Requested {
                    self.control
                        .insert(s.to, Ra33Control::Refused(ControlResponse::NotAvailable));
                }
                return;
            }
            Outcome::GaveUp => self.stats.given_up += 1,
        }
        tracing::warn!(gateway = %self.me, driver = %s.to, message = name, attempts = s.attempts,
            "RA 3.3 command not acknowledged after every copy");
        if !control || self.control_of(s.to) != Ra33Control::Requested {
            return;
        }
        let tries = self.control_retries.entry(s.to).or_insert(0);
        if self.want_control && s.peer_known && *tries < CONTROL_RETRIES {
            *tries += 1;
            self.stats.control_retried += 1;
            tracing::info!(gateway = %self.me, driver = %s.to, "RA 3.3 control asked for again");
            self.send(
                s.to,
                RequestComponentControl {
                    authority_code: self.authority,
                },
            );
        } else {
            // Asked again when the client next commands the driver.
            self.control_retries.remove(&s.to);
            self.control.insert(s.to, Ra33Control::None);
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

    /// Whether an AS-4 client controls the AS-4 component ([`Self::set_controlled`]).
    pub fn controlled(&self) -> bool {
        self.want_control
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
            let mut active: Vec<Address> = self.active.values().copied().collect();
            active.sort();
            for d in active {
                if self.control_of(d) == Ra33Control::Granted {
                    self.send(d, Resume {});
                }
            }
            return;
        }
        self.active.clear();
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

    /// Whether `driver` is the active one of its group (the one the AS-4 client
    /// commanded last, while the component is Ready; [`activate`](Self::activate)).
    pub fn is_active(&self, driver: Address) -> bool {
        self.active.get(&self.targets.group(driver)) == Some(&driver)
    }

    /// How many times a driver of `driver`'s group was made the active one
    /// ([`activate`](Self::activate), once per command an AS-4 service passes on): a
    /// service that drove the group last knows another command came when it changes,
    /// even one to the same RA 3.3 driver.
    pub fn activations(&self, driver: Address) -> u64 {
        self.activations
            .get(&self.targets.group(driver))
            .copied()
            .unwrap_or(0)
    }

    /// Makes `driver` the one that moves its group's hardware ([`Group`]): it is resumed
    /// (control asked for first if needed) and every other driver of its group the
    /// gateway controls goes to standby, so that two drivers never contend for the
    /// vehicle (two waypoint drivers in Ready would both take the Reflexive Driver) or
    /// for the arm; the other group's drivers are left as they are.
    pub fn activate(&mut self, driver: Address) {
        self.ensure_control(driver);
        let group = self.targets.group(driver);
        let mut others: Vec<Address> = self
            .control
            .iter()
            .filter(|(a, c)| {
                **a != driver && **c == Ra33Control::Granted && self.targets.group(**a) == group
            })
            .map(|(a, _)| *a)
            .collect();
        others.sort();
        if !self.is_active(driver) {
            for d in others {
                self.send(d, Standby {});
            }
        }
        self.active.insert(group, driver);
        *self.activations.entry(group).or_default() += 1;
        if self.ready && self.control_of(driver) == Ra33Control::Granted {
            self.send(driver, Resume {});
        }
    }

    /// Sends the polls that are due; a poll left unanswered backs off, then stops.
    pub fn handle_timeout(&mut self, now: Instant) {
        self.now = Some(now);
        for (to, q) in self.polls.due(now, self.me, &mut self.stats) {
            self.send(to, q);
        }
    }

    /// When the next poll is due.
    pub fn poll_timeout(&self) -> Option<Instant> {
        self.polls.next_due()
    }

    /// Its Report Services, as an RA 3.3 component answers Query Services: the core
    /// service (type 0), as the SDK's stock components list it, with what this side
    /// really takes (the queries it answers, the control answers, the reports of the
    /// queries it polls) and sends (its reports, control of the drivers, and every
    /// message it has sent so far). It has no service of its own component id: what it
    /// presents is offered on the AS-4 side.
    pub fn services(&self) -> ReportServices {
        let entry = |code: CommandCode| ServiceCommand {
            command_code: code.0,
            presence_vector: 0,
        };
        let mut inputs: BTreeSet<CommandCode> = [
            jaus::messages::QueryIdentification::CODE,
            jaus::messages::QueryServices::CODE,
            ConfirmComponentControl::CODE,
            jaus::messages::RejectComponentControl::CODE,
        ]
        .into_iter()
        .collect();
        inputs.extend(self.polls.reports());
        let mut outputs: BTreeSet<CommandCode> = [
            ReportIdentification::CODE,
            ReportServices::CODE,
            RequestComponentControl::CODE,
            ReleaseComponentControl::CODE,
            Standby::CODE,
            Resume::CODE,
        ]
        .into_iter()
        .collect();
        outputs.extend(self.sent_codes.iter().copied());
        ReportServices {
            services: vec![JausService {
                service_type: 0,
                input_commands: inputs.into_iter().map(entry).collect(),
                output_commands: outputs.into_iter().map(entry).collect(),
            }],
        }
    }
}

/// Copies the twelve same-named efforts of one wrench-effort message into another type
/// (RA 3.3's and AS-4's share names and units): the gateway's Primitive Driver and the
/// proxy's use it, each way.
macro_rules! efforts {
    ($src:expr => $dst:path) => {{
        let s = $src;
        $dst {
            propulsive_linear_effort_x: s.propulsive_linear_effort_x,
            propulsive_linear_effort_y: s.propulsive_linear_effort_y,
            propulsive_linear_effort_z: s.propulsive_linear_effort_z,
            propulsive_rotational_effort_x: s.propulsive_rotational_effort_x,
            propulsive_rotational_effort_y: s.propulsive_rotational_effort_y,
            propulsive_rotational_effort_z: s.propulsive_rotational_effort_z,
            resistive_linear_effort_x: s.resistive_linear_effort_x,
            resistive_linear_effort_y: s.resistive_linear_effort_y,
            resistive_linear_effort_z: s.resistive_linear_effort_z,
            resistive_rotational_effort_x: s.resistive_rotational_effort_x,
            resistive_rotational_effort_y: s.resistive_rotational_effort_y,
            resistive_rotational_effort_z: s.resistive_rotational_effort_z,
        }
    }};
}
pub(crate) use efforts;

#[cfg(test)]
mod tests {
    use super::*;

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
        assert_eq!(s.stats().polls_sent, u64::from(GIVE_UP_AFTER));
        assert_eq!(s.stats().polls_unanswered, u64::from(GIVE_UP_AFTER));
        assert_eq!(s.polls_given_up(), vec![(driver, QueryWrenchEffort::CODE)]);
        assert_eq!(s.poll_timeout(), None);
        // A report of its kind (an event, or an answer after all) restarts it.
        s.on_message(now, driver, ReportWrenchEffort::default().into());
        assert_eq!(s.stats().polls_resumed, 1);
        assert!(s.polls_given_up().is_empty());
        assert_eq!(s.poll_timeout(), Some(now + period));
        s.handle_timeout(now + period);
        assert!(s.poll_transmit().is_some());
        assert_eq!(s.stats().polls_sent, u64::from(GIVE_UP_AFTER) + 1);
    }

    #[test]
    fn a_component_discovered_again_is_polled_again_at_once() {
        use jaus::messages::{QueryGlobalPose, QueryWrenchEffort};
        let me = Address::new(1, 1, 200, 1);
        let (driver, gps) = (Address::new(1, 1, 33, 1), Address::new(1, 1, 38, 1));
        let period = Duration::from_millis(100);
        let mut s = Ra33Side::new(me, Targets::default(), 200, period);
        let t0 = Instant::now();
        s.keep_polling(t0, driver, QueryWrenchEffort::default());
        s.keep_polling(t0, gps, QueryGlobalPose::default());
        let mut now = t0;
        while let Some(due) = s.poll_timeout() {
            now = due;
            s.handle_timeout(now);
            while s.poll_transmit().is_some() {}
        }
        assert_eq!(s.stats().polls_given_up, 2);
        // Another component coming back changes nothing for the driver.
        let later = now + Duration::from_secs(5);
        s.rediscovered(later, gps);
        assert_eq!(s.polls_given_up(), vec![(driver, QueryWrenchEffort::CODE)]);
        assert_eq!(s.poll_timeout(), Some(later));
        s.handle_timeout(later);
        assert!(matches!(
            s.poll_transmit(),
            Some((to, Ra33Message::QueryGlobalPose(_))) if to == gps
        ));
        assert!(s.poll_transmit().is_none());
        s.rediscovered(later, driver);
        assert!(s.polls_given_up().is_empty());
        assert_eq!(s.stats().polls_resumed, 2);
        s.handle_timeout(later);
        assert!(matches!(
            s.poll_transmit(),
            Some((to, Ra33Message::QueryWrenchEffort(_))) if to == driver
        ));
    }

    #[test]
    fn query_services_is_answered() {
        let me = Address::new(1, 1, 200, 1);
        let asker = Address::new(1, 1, 1, 1);
        let mut s = Ra33Side::new(me, Targets::default(), 200, Duration::from_millis(100));
        let gps = Address::new(1, 1, 38, 1);
        s.keep_polling(
            Instant::now(),
            gps,
            jaus::messages::QueryGlobalPose::default(),
        );
        s.on_message(
            Instant::now(),
            asker,
            jaus::messages::QueryServices {}.into(),
        );
        match s.poll_transmit() {
            Some((to, Ra33Message::ReportServices(r))) => {
                assert_eq!(to, asker);
                assert_eq!(r.services.len(), 1);
                let codes = |l: &[ServiceCommand]| -> Vec<u16> {
                    l.iter().map(|c| c.command_code).collect()
                };
                let (inputs, outputs) = (
                    codes(&r.services[0].input_commands),
                    codes(&r.services[0].output_commands),
                );
                assert_eq!(r.services[0].service_type, 0);
                assert!(inputs.contains(&jaus::messages::QueryServices::CODE.0));
                // The reports of what it polls, what it sends.
                assert!(inputs.contains(&jaus::messages::ReportGlobalPose::CODE.0));
                assert!(outputs.contains(&ReportServices::CODE.0));
                assert!(outputs.contains(&Resume::CODE.0));
                assert!(inputs.windows(2).all(|w| w[0] < w[1]), "{inputs:?}");
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
