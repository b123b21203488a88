//! A Subsystem Commander core (Part 1 component 32: it "coordinates all activity within
//! a given subsystem"): the subsystem's missions go through it. A System Commander (or
//! any requester) hands it a mission with Spool Mission and runs, pauses, resumes or
//! aborts it with the mission messages, as it would a Mission Spooler; the Subsystem
//! Commander
//!
//! * takes and keeps control of the subsystem's Mission Spooler with its own authority
//!   ([`ControlKeeper`]), so requesters need no control of the spooler themselves;
//! * hands the mission over (Resume, then Spool Mission, as the mission's owner) and
//!   passes the requester's Run / Pause / Resume / Abort on, those sent before the hand-
//!   over once it is done;
//! * watches it: queries the mission's status every
//!   [`status_period`](SubsystemConfig::status_period) and passes every status the
//!   spooler reports on to the requester;
//! * reacts: a spooler that loses control to someone else is asked again; a spooler
//!   going through Emergency interrupts the mission (the spooler rewinds it to the task
//!   it was in); when the emergency is cleared the mission is run again if
//!   [`resume_after_emergency`](SubsystemConfig::resume_after_emergency) says so, else
//!   it waits for the requester's Run Mission;
//! * lets go of the spooler once the mission has finished or was aborted.
//!
//! One mission at a time: a Spool Mission for another mission while one is under way is
//! refused (NAK when asked for). Run it with
//! `subsystem_commander::component(address, StockSubsystemCommander::new(config), ..)`.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use super::{ControlEvent, ControlKeeper, KeeperConfig};
use crate::component::{CoreState, Refused};
use crate::components::subsystem_commander::{Ctx, SubsystemCommander};
use crate::messages::{
    Message, MissionStatus, MissionStatusType, QueryMissionStatus, ReportMissionStatus, Resume,
    RunMission, SpoolMission,
};
use crate::Address;

/// Mission messages a requester may send before the hand-over that are kept for it.
const MAX_QUEUED: usize = 16;

/// Settings of a [`StockSubsystemCommander`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SubsystemConfig {
    /// The subsystem's Mission Spooler.
    pub spooler: Address,
    /// Authority to ask the spooler's control with (`None`: the component's own).
    pub authority: Option<u8>,
    /// How often the running mission's status is queried.
    pub status_period: Duration,
    /// Run the mission again by itself once an emergency that interrupted it is cleared
    /// (the spooler carries on from the task it was in). Off by default: clearing an
    /// emergency then leaves the vehicle still until the requester runs the mission.
    pub resume_after_emergency: bool,
}

impl SubsystemConfig {
    /// For the spooler at `spooler`: the component's own authority, status every second,
    /// no resumption by itself after an emergency.
    pub fn new(spooler: Address) -> Self {
        Self {
            spooler,
            authority: None,
            status_period: Duration::from_secs(1),
            resume_after_emergency: false,
        }
    }
}

/// What the Subsystem Commander has done so far.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SubsystemStats {
    /// Missions accepted from requesters.
    pub missions: u64,
    /// Spool Missions refused (another mission under way).
    pub refused: u64,
    /// Mission statuses passed on to requesters.
    pub relayed: u64,
    /// Times the mission was interrupted by the spooler leaving Ready (an emergency).
    pub interruptions: u64,
    /// Times it ran the mission again after an emergency was cleared.
    pub resumed: u64,
    /// Requester messages dropped because the queue before the hand-over was full.
    pub dropped: u64,
}

/// The mission being coordinated, as the requester sees it.
#[derive(Debug, Clone, PartialEq)]
pub struct MissionOrder {
    /// Who handed the mission over (status reports go there).
    pub requester: Address,
    /// The mission.
    pub mission_id: u16,
    /// Handed to the spooler.
    pub handed: bool,
    /// The mission's last status the spooler reported.
    pub status: Option<MissionStatus>,
    /// Interrupted by an emergency and not run again yet.
    pub interrupted: bool,
    /// When the mission's status was last reported.
    pub heard: Option<Instant>,
}

#[derive(Debug)]
struct Order {
    view: MissionOrder,
    mission: SpoolMission,
    queued: VecDeque<Message>,
    /// Whether the requester ran the mission (and did not abort it since).
    running: bool,
    next_query: Option<Instant>,
}

/// The Subsystem Commander core.
#[derive(Debug)]
pub struct StockSubsystemCommander {
    config: SubsystemConfig,
    keeper: ControlKeeper,
    order: Option<Order>,
    last: Option<MissionOrder>,
    spooler_state: Option<CoreState>,
    stats: SubsystemStats,
}

impl StockSubsystemCommander {
    /// With `config`, no mission yet.
    pub fn new(config: SubsystemConfig) -> Self {
        Self {
            config,
            // The spooler is resumed when a mission is handed over, not on every grant.
            keeper: ControlKeeper::new(KeeperConfig {
                resume: false,
                status_period: Duration::from_millis(500),
                ..KeeperConfig::default()
            }),
            order: None,
            last: None,
            spooler_state: None,
            stats: SubsystemStats::default(),
        }
    }

    /// The settings.
    pub fn config(&self) -> &SubsystemConfig {
        &self.config
    }

    /// The mission under way, if any.
    pub fn order(&self) -> Option<&MissionOrder> {
        self.order.as_ref().map(|o| &o.view)
    }

    /// The last mission that ended (finished or aborted).
    pub fn last(&self) -> Option<&MissionOrder> {
        self.last.as_ref()
    }

    /// Whether it holds control of the spooler.
    pub fn holds_spooler(&self) -> bool {
        self.keeper.holds(self.config.spooler)
    }

    /// Counters.
    pub fn stats(&self) -> SubsystemStats {
        self.stats
    }

    fn on_spool(
        &mut self,
        ctx: &mut Ctx<'_>,
        source: Address,
        m: &SpoolMission,
    ) -> Result<(), Refused> {
        if let Some(o) = &mut self.order {
            let under_way = !matches!(
                o.view.status,
                Some(MissionStatus::Finished | MissionStatus::Aborted)
            );
            if o.view.mission_id != m.mission_id && under_way {
                self.stats.refused += 1;
                return Err(Refused::Invalid(format!(
                    "mission {} from {} is under way: abort it first",
                    o.view.mission_id, o.view.requester
                )));
            }
            if m.append_flag != 0 && o.view.mission_id == m.mission_id {
                // More of the same mission: passed on as it is.
                let msg: Message = m.clone().into();
                if o.view.handed {
                    ctx.forward(self.config.spooler, msg);
                } else if o.queued.len() < MAX_QUEUED {
                    o.queued.push_back(msg);
                } else {
                    self.stats.dropped += 1;
                    return Err(Refused::Invalid(format!(
                        "{MAX_QUEUED} mission messages already wait for the spooler"
                    )));
                }
                return Ok(());
            }
        }
        if m.append_flag != 0 {
            self.stats.refused += 1;
            return Err(Refused::Invalid(format!(
                "mission {} is not here to append to",
                m.mission_id
            )));
        }
        self.stats.missions += 1;
        tracing::info!(
            address = %ctx.address(),
            requester = %source,
            mission = m.mission_id,
            spooler = %self.config.spooler,
            "mission accepted; handing it to the spooler"
        );
        match self.config.authority {
            Some(a) => self.keeper.keep_with(self.config.spooler, a),
            None => self.keeper.keep(self.config.spooler),
        }
        self.order = Some(Order {
            view: MissionOrder {
                requester: source,
                mission_id: m.mission_id,
                handed: false,
                status: None,
                interrupted: false,
                heard: None,
            },
            mission: m.clone(),
            queued: VecDeque::new(),
            running: false,
            next_query: None,
        });
        self.hand_over(ctx);
        Ok(())
    }

    /// A requester's Run / Pause / Resume / Abort Mission for mission `id`.
    fn on_command(&mut self, ctx: &mut Ctx<'_>, id: u16, msg: &Message) -> Result<(), Refused> {
        let Some(o) = self.order.as_mut().filter(|o| o.view.mission_id == id) else {
            return Err(Refused::Invalid(format!("no mission {id} here")));
        };
        match msg {
            Message::RunMission(_) | Message::ResumeMission(_) => {
                o.running = true;
                o.view.interrupted = false;
            }
            Message::AbortMission(a) if a.task_id == 0 => o.running = false,
            _ => {}
        }
        if o.view.handed {
            if matches!(msg, Message::RunMission(_) | Message::ResumeMission(_)) {
                // The spooler runs missions only in Ready (Standby after an emergency).
                ctx.send_core(self.config.spooler, Resume {});
            }
            ctx.forward(self.config.spooler, msg.clone());
        } else if o.queued.len() < MAX_QUEUED {
            o.queued.push_back(msg.clone());
        } else {
            self.stats.dropped += 1;
            return Err(Refused::Invalid(format!(
                "{MAX_QUEUED} mission messages already wait for the spooler"
            )));
        }
        Ok(())
    }

    /// Hands the mission to the spooler once control of it is held.
    fn hand_over(&mut self, ctx: &mut Ctx<'_>) {
        let spooler = self.config.spooler;
        if !self.keeper.holds(spooler) {
            return;
        }
        let Some(o) = self.order.as_mut().filter(|o| !o.view.handed) else {
            return;
        };
        ctx.send_core(spooler, Resume {});
        ctx.send(spooler, o.mission.clone());
        o.view.handed = true;
        o.next_query = None;
        while let Some(m) = o.queued.pop_front() {
            if matches!(m, Message::RunMission(_) | Message::ResumeMission(_)) {
                ctx.send_core(spooler, Resume {});
            }
            ctx.forward(spooler, m);
        }
    }

    /// A status of the mission from the spooler: passed on, and the end of the order
    /// when the mission finished or was aborted.
    fn on_report(&mut self, ctx: &mut Ctx<'_>, r: &ReportMissionStatus) {
        let Some(o) = self
            .order
            .as_mut()
            .filter(|o| o.view.mission_id == r.mission_id)
        else {
            return;
        };
        ctx.send(o.view.requester, r.clone());
        self.stats.relayed += 1;
        if r.status_type != MissionStatusType::Mission {
            return;
        }
        o.view.status = Some(r.status);
        o.view.heard = Some(ctx.now());
        if matches!(r.status, MissionStatus::Finished | MissionStatus::Aborted) {
            tracing::info!(
                address = %ctx.address(),
                mission = r.mission_id,
                "mission {:?}; control of the spooler given back",
                r.status
            );
            let done = self.order.take().map(|o| o.view);
            self.last = done;
            self.keeper.release(ctx, self.config.spooler);
        }
    }

    /// The spooler's core state changed.
    fn on_spooler_state(&mut self, ctx: &mut Ctx<'_>, state: CoreState) {
        let before = self.spooler_state.replace(state);
        let Some(o) = self.order.as_mut().filter(|o| o.view.handed) else {
            return;
        };
        if state == CoreState::Emergency && o.running && !o.view.interrupted {
            o.view.interrupted = true;
            self.stats.interruptions += 1;
            tracing::warn!(
                address = %ctx.address(),
                spooler = %self.config.spooler,
                mission = o.view.mission_id,
                "the spooler is in Emergency: mission interrupted"
            );
        }
        let cleared = before == Some(CoreState::Emergency) && state == CoreState::Standby;
        if cleared && o.view.interrupted && o.running {
            if self.config.resume_after_emergency {
                ctx.send_core(self.config.spooler, Resume {});
                ctx.send(
                    self.config.spooler,
                    RunMission {
                        mission_id: o.view.mission_id,
                    },
                );
                o.view.interrupted = false;
                self.stats.resumed += 1;
                tracing::info!(
                    address = %ctx.address(),
                    mission = o.view.mission_id,
                    "emergency cleared: mission run again"
                );
            } else {
                tracing::info!(
                    address = %ctx.address(),
                    mission = o.view.mission_id,
                    "emergency cleared: the mission waits for Run Mission"
                );
            }
        }
    }
}

impl SubsystemCommander for StockSubsystemCommander {
    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        for e in self.keeper.tick(ctx) {
            match e {
                ControlEvent::Gained(_) => self.hand_over(ctx),
                ControlEvent::Lost(a) => {
                    tracing::warn!(address = %ctx.address(), spooler = %a, "control of the spooler lost; asking again");
                }
                ControlEvent::State(_, s) => self.on_spooler_state(ctx, s),
            }
        }
        let now = ctx.now();
        let period = self.config.status_period;
        if let Some(o) = self.order.as_mut().filter(|o| o.view.handed) {
            if o.next_query.is_none_or(|t| now >= t) {
                o.next_query = Some(now + period);
                ctx.send(
                    self.config.spooler,
                    QueryMissionStatus {
                        presence_vector: 1,
                        status_type: MissionStatusType::Mission,
                        mission_id: o.view.mission_id,
                        task_id: 0,
                        task_msg_id: 0,
                    },
                );
            }
        }
    }

    fn on_other_message(
        &mut self,
        ctx: &mut Ctx<'_>,
        msg: &Message,
    ) -> Result<Option<Message>, Refused> {
        let Some(source) = ctx.source() else {
            return Ok(None);
        };
        if source == self.config.spooler {
            match msg {
                Message::ReportMissionStatus(r) => self.on_report(ctx, r),
                Message::ReportComponentStatus(s) => {
                    if let Some(ControlEvent::State(_, st)) = self.keeper.on_status(source, s) {
                        self.on_spooler_state(ctx, st);
                    }
                }
                _ => {}
            }
            return Ok(None);
        }
        match msg {
            Message::SpoolMission(m) => self.on_spool(ctx, source, m).map(|()| None),
            Message::RunMission(m) => self.on_command(ctx, m.mission_id, msg).map(|()| None),
            Message::PauseMission(m) => self.on_command(ctx, m.mission_id, msg).map(|()| None),
            Message::ResumeMission(m) => self.on_command(ctx, m.mission_id, msg).map(|()| None),
            Message::AbortMission(m) => self.on_command(ctx, m.mission_id, msg).map(|()| None),
            Message::QueryMissionStatus(q) => {
                let known = self
                    .order
                    .as_ref()
                    .map(|o| &o.view)
                    .or(self.last.as_ref())
                    .filter(|v| v.mission_id == q.mission_id);
                let Some(v) = known else {
                    return Err(Refused::Invalid(format!(
                        "no mission {} here",
                        q.mission_id
                    )));
                };
                Ok(Some(
                    ReportMissionStatus {
                        status_type: MissionStatusType::Mission,
                        status: v.status.unwrap_or(MissionStatus::Pending),
                        secondary_status: crate::messages::MissionSecondaryStatus::NoError,
                        mission_id: v.mission_id,
                        task_id: 0,
                        task_msg_id: 0,
                    }
                    .into(),
                ))
            }
            _ => Err(Refused::Unsupported),
        }
    }
}
