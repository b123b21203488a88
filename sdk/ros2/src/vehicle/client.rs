//! The JAUS side of vehicle mode: a System Commander component on the bridge's node
//! that finds the vehicle's components in the system tree by their Part 1 ids, follows
//! Local Pose, Velocity State and Global Pose through service connections (querying
//! them at the same rate where a connection is not granted), queries the components'
//! status and controller, takes and keeps control ([`ControlKeeper`]) of the Primitive
//! Driver for `cmd_vel` or of a waypoint driver for `goal_pose`, and sends what the
//! sans-IO core ([`super::core`]) decides.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use jaus::component::{CoreState, Refused};
use jaus::components::system_commander::{Ctx, SystemCommander};
use jaus::components::{
    global_pose_sensor, global_waypoint_driver, local_pose_sensor, local_waypoint_driver,
    primitive_driver, velocity_state_sensor,
};
use jaus::messages::{
    Message, QueryComponentControl, QueryComponentStatus, QueryGlobalPose, QueryLocalPose,
    QueryVelocityState, ReportGlobalPose, ReportLocalPose, ReportVelocityState, Resume,
    SetTravelSpeed, Standby,
};
use jaus::stock::commander::{ControlEvent, ControlKeeper, KeeperConfig};
use jaus::stock::geo::LocalFrame;
use jaus::{Address, JausMessage};

pub use super::core::role;
use super::core::{
    global_waypoint_of, local_waypoint_of, wrench_of_twist, zero_wrench, CmdGate, GateAction,
};
use super::shared::{vlock, Shared, VehicleEvent};
use crate::config::{EffortMapping, VehicleConfig};
use crate::msg::PoseStamped;

/// Report Local Pose fields asked for: x, y, z, position RMS, roll, pitch, yaw.
const LOCAL_PRESENCE: u16 = 0x7F;
/// Report Velocity State fields: velocity x, y, z, roll, pitch and yaw rates.
const VELOCITY_PRESENCE: u16 = 0x77;
/// Report Global Pose fields: latitude, longitude, elevation, position RMS, yaw.
const GLOBAL_PRESENCE: u16 = 0x4F;
/// A service connection not active this long after it was asked for: poll instead.
const POLL_AFTER: Duration = Duration::from_secs(2);
/// How often each component's status and controller are queried.
const STATUS_PERIOD: Duration = Duration::from_secs(1);
/// How often a command is refreshed (the stock Primitive Driver brakes after 300 ms).
const REFRESH: Duration = Duration::from_millis(100);

/// Which source drives the vehicle now.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Idle,
    Drive,
    Goal(Address),
}

/// The bridge's JAUS client (see the module documentation).
#[derive(Debug)]
pub struct VehicleClient {
    subsystem: u8,
    config: VehicleConfig,
    mapping: EffortMapping,
    shared: Shared,
    keeper: ControlKeeper,
    gate: CmdGate,
    mode: Mode,
    cmd_seq: u64,
    pending_goal: Option<PoseStamped>,
    origin: Option<LocalFrame>,
    subscribed: BTreeMap<(Address, u16), Instant>,
    next_poll: Option<Instant>,
    next_status: Option<Instant>,
    /// The arrival of the command the gate last sent for the first time.
    measured: Option<Instant>,
}

impl VehicleClient {
    pub(crate) fn new(
        subsystem: u8,
        config: VehicleConfig,
        mapping: EffortMapping,
        shared: Shared,
    ) -> Self {
        VehicleClient {
            subsystem,
            config,
            mapping,
            shared,
            keeper: ControlKeeper::new(KeeperConfig {
                retry: Duration::from_millis(500),
                status_period: Duration::from_millis(500),
                resume: true,
            }),
            gate: CmdGate::new(config.cmd_vel_timeout(), REFRESH),
            mode: Mode::Idle,
            cmd_seq: 0,
            pending_goal: None,
            origin: None,
            subscribed: BTreeMap::new(),
            next_poll: None,
            next_status: None,
            measured: None,
        }
    }

    fn find(tree: &[Address], id: u8) -> Option<Address> {
        tree.iter().filter(|a| a.component == id).min().copied()
    }

    /// Switches who drives: the Primitive Driver for `cmd_vel`, a waypoint driver for a
    /// goal (each source's driver released and, for a waypoint driver, put in Standby).
    fn switch(&mut self, ctx: &mut Ctx<'_>, to: Mode, pd: Option<Address>) {
        if self.mode == to {
            return;
        }
        match self.mode {
            Mode::Drive => {
                if let Some(pd) = pd {
                    if self.keeper.holds(pd) {
                        ctx.send(pd, zero_wrench());
                    }
                    self.keeper.release(ctx, pd);
                }
            }
            Mode::Goal(d) => {
                if self.keeper.holds(d) {
                    ctx.send_core(d, Standby {});
                }
                self.keeper.release(ctx, d);
            }
            Mode::Idle => {}
        }
        match to {
            Mode::Drive => {
                if let Some(pd) = pd {
                    self.keeper.keep(pd);
                }
            }
            Mode::Goal(d) => self.keeper.keep(d),
            Mode::Idle => {}
        }
        self.mode = to;
    }

    fn follow(&mut self, ctx: &mut Ctx<'_>, tree: &[Address]) {
        let now = ctx.now();
        let sensors = [
            (local_pose_sensor::ID, ReportLocalPose::CODE, LOCAL_PRESENCE),
            (
                velocity_state_sensor::ID,
                ReportVelocityState::CODE,
                VELOCITY_PRESENCE,
            ),
            (
                global_pose_sensor::ID,
                ReportGlobalPose::CODE,
                GLOBAL_PRESENCE,
            ),
        ];
        let mut poll = Vec::new();
        for (id, code, pv) in sensors {
            let Some(a) = Self::find(tree, id) else {
                continue;
            };
            match self.subscribed.get(&(a, code.0)) {
                None => {
                    if let Err(e) =
                        ctx.create_service_connection(a, code, self.config.rate_hz, u32::from(pv))
                    {
                        tracing::warn!(provider = %a, report = %code, "jaus-ros2 vehicle: no service connection, polling: {e}");
                    }
                    self.subscribed.insert((a, code.0), now);
                }
                Some(at) => {
                    if now.saturating_duration_since(*at) > POLL_AFTER
                        && !ctx.service_connection_active(a, code)
                    {
                        poll.push((a, code));
                    }
                }
            }
        }
        if !poll.is_empty() && self.next_poll.is_none_or(|t| now >= t) {
            self.next_poll = Some(now + self.config.period());
            for (a, code) in poll {
                if code == ReportLocalPose::CODE {
                    ctx.send(
                        a,
                        QueryLocalPose {
                            presence_vector: LOCAL_PRESENCE,
                        },
                    );
                } else if code == ReportVelocityState::CODE {
                    ctx.send(
                        a,
                        QueryVelocityState {
                            presence_vector: VELOCITY_PRESENCE,
                        },
                    );
                } else {
                    ctx.send(
                        a,
                        QueryGlobalPose {
                            presence_vector: GLOBAL_PRESENCE,
                        },
                    );
                }
            }
        }
        if self.next_status.is_none_or(|t| now >= t) {
            self.next_status = Some(now + STATUS_PERIOD);
            for a in tree.iter().filter(|a| role(a.component) != "component") {
                ctx.send_core(*a, QueryComponentStatus {});
                ctx.send_core(*a, QueryComponentControl {});
            }
        }
    }

    fn send_goal(&mut self, ctx: &mut Ctx<'_>, driver: Address, goal: &PoseStamped) {
        let now = ctx.now();
        let waypoint: Result<Message, &'static str> =
            if driver.component == local_waypoint_driver::ID {
                local_waypoint_of(goal)
                    .map(Message::from)
                    .ok_or("goal not finite")
            } else {
                match &self.origin {
                    None => Err("no fix yet: the goal's ENU frame is anchored at the first fix"),
                    Some(o) => global_waypoint_of(goal, o)
                        .map(Message::from)
                        .ok_or("goal not finite"),
                }
            };
        let mut s = vlock(&self.shared);
        match waypoint {
            Ok(w) => {
                // Part 1 resets the travel speed on Standby → Ready: Resume first.
                ctx.send_core(driver, Resume {});
                ctx.send(
                    driver,
                    SetTravelSpeed {
                        speed: self.config.waypoint_speed,
                    },
                );
                ctx.forward(driver, w);
                tracing::info!(%driver, x = goal.pose.position.x, y = goal.pose.position.y, "jaus-ros2 vehicle: goal_pose sent as a waypoint");
                s.event(VehicleEvent::GoalSent { at: now, driver });
            }
            Err(reason) => {
                tracing::warn!(%driver, "jaus-ros2 vehicle: goal_pose refused: {reason}");
                s.event(VehicleEvent::GoalRefused { at: now, reason });
            }
        }
    }
}

impl SystemCommander for VehicleClient {
    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        let now = ctx.now();
        let (tree, cmd, goal) = {
            let mut s = vlock(&self.shared);
            s.me = Some(ctx.address());
            let subsystem = self.subsystem;
            let tree: Vec<Address> = s
                .tree
                .iter()
                .filter(|a| a.subsystem == subsystem)
                .copied()
                .collect();
            let cmd = (s.cmd_seq != self.cmd_seq).then_some(s.cmd).flatten();
            self.cmd_seq = s.cmd_seq;
            (tree, cmd, s.goal.take())
        };
        let pd = Self::find(&tree, primitive_driver::ID);
        if let Some((t, at)) = cmd {
            self.gate.command(t, at);
            self.measured = None;
            self.switch(ctx, Mode::Drive, pd);
        }
        if let Some(g) = goal {
            let driver = Self::find(&tree, local_waypoint_driver::ID)
                .or_else(|| Self::find(&tree, global_waypoint_driver::ID));
            match driver {
                Some(d) => {
                    self.switch(ctx, Mode::Goal(d), pd);
                    self.pending_goal = Some(g);
                }
                None => vlock(&self.shared).event(VehicleEvent::GoalRefused {
                    at: now,
                    reason: "no Local or Global Waypoint Driver on the vehicle",
                }),
            }
        }
        for e in self.keeper.tick(ctx) {
            let mut s = vlock(&self.shared);
            match e {
                ControlEvent::Gained(a) => {
                    tracing::info!(component = %a, "jaus-ros2 vehicle: control gained");
                    s.event(VehicleEvent::ControlGained {
                        at: now,
                        component: a,
                    });
                }
                ControlEvent::Lost(a) => {
                    tracing::warn!(component = %a, "jaus-ros2 vehicle: control lost; no more commands until a new cmd_vel or goal_pose");
                    s.event(VehicleEvent::ControlLost {
                        at: now,
                        component: a,
                    });
                    drop(s);
                    self.keeper.release(ctx, a);
                    // Learn who holds it now rather than at the next status round.
                    ctx.send_core(a, QueryComponentControl {});
                    self.mode = Mode::Idle;
                    self.pending_goal = None;
                }
                ControlEvent::State(..) => {}
            }
        }
        vlock(&self.shared).held = self.keeper.kept().filter(|k| k.2).map(|k| k.0).collect();
        // cmd_vel: only while driving and in control of the Primitive Driver.
        let action = self.gate.tick(now);
        if let (Mode::Drive, Some(pd)) = (self.mode, pd) {
            let held = self.keeper.holds(pd);
            let mut s = vlock(&self.shared);
            match action {
                GateAction::Drive(t) if held => {
                    ctx.send(pd, wrench_of_twist(&t, &self.mapping));
                    s.stats.wrench_sent += 1;
                    if let (None, Some((_, at))) = (self.measured, s.cmd) {
                        self.measured = Some(at);
                        s.latency(now.saturating_duration_since(at));
                    }
                }
                GateAction::Stop => {
                    tracing::info!(%pd, "jaus-ros2 vehicle: no cmd_vel for {:?}: zero efforts", self.config.cmd_vel_timeout());
                    s.event(VehicleEvent::CmdVelSilent { at: now });
                    if held {
                        ctx.send(pd, zero_wrench());
                        s.stats.watchdog_stops += 1;
                    }
                }
                GateAction::Drive(_) => {
                    s.stats.not_in_control += 1;
                    self.gate.unsent();
                }
                GateAction::Idle => {}
            }
        }
        if let (Mode::Goal(d), Some(g)) = (self.mode, self.pending_goal.clone()) {
            if self.keeper.holds(d) {
                self.pending_goal = None;
                self.send_goal(ctx, d, &g);
            }
        }
        self.follow(ctx, &tree);
    }

    fn on_other_message(
        &mut self,
        ctx: &mut Ctx<'_>,
        msg: &Message,
    ) -> Result<Option<Message>, Refused> {
        let Some(source) = ctx.source().filter(|a| a.subsystem == self.subsystem) else {
            return Ok(None);
        };
        let now = ctx.now();
        let mut s = vlock(&self.shared);
        match msg {
            Message::ReportLocalPose(r) => {
                s.stats.local_pose += 1;
                s.local = Some(r.clone());
                s.local_seq += 1;
            }
            Message::ReportVelocityState(r) => {
                s.stats.velocity += 1;
                s.velocity = Some((r.clone(), now));
            }
            Message::ReportGlobalPose(r) => {
                s.stats.global_pose += 1;
                if let (None, Some(lat), Some(lon)) = (&self.origin, r.latitude, r.longitude) {
                    if lat.is_finite() && lon.is_finite() && lat.abs() <= 90.0 {
                        self.origin = Some(LocalFrame::new(lat, lon, 0.0));
                    }
                }
                s.global = Some(r.clone());
                s.global_seq += 1;
            }
            Message::ReportComponentStatus(r) => {
                drop(s);
                let _ = self.keeper.on_status(source, r);
                let mut s = vlock(&self.shared);
                let state = CoreState::from_wire(r.primary_status_code);
                let e = s.status.entry(source).or_default();
                if e.state != state {
                    e.state = state;
                    s.status_seq += 1;
                }
            }
            Message::ReportComponentControl(r) => {
                let c = Address::new(r.subsystem_id, r.node_id, r.component_id, r.instance_id);
                let controller =
                    (r.subsystem_id != 0 && c.is_valid()).then_some((c, r.authority_code));
                let e = s.status.entry(source).or_default();
                if e.controller != controller {
                    e.controller = controller;
                    s.status_seq += 1;
                }
            }
            _ => {}
        }
        Ok(None)
    }
}
