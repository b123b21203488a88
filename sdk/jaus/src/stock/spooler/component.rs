//! The Mission Spooler's messages: spooling, running, pausing, resuming and aborting
//! missions, changing their messages, and answering their status.

use std::collections::HashMap;

use super::delivery::self_route;
use super::mission::{walk, wire_status, Item, ItemState, Mission, MissionState};
use super::StockMissionSpooler;
use crate::component::{CoreState, Refused};
use crate::components::mission_spooler::{Ctx, MissionSpooler, Transition};
use crate::messages::*;
use crate::JausMessage;

impl MissionSpooler for StockMissionSpooler {
    fn on_spool_mission(&mut self, ctx: &mut Ctx<'_>, m: &SpoolMission) -> Result<(), Refused> {
        let owner = ctx.source().unwrap_or(ctx.address());
        // What to put back if the journal cannot commit the change.
        let before = self.saved(m.mission_id);
        let stored_before = self.stored;
        let mut items = Vec::new();
        let mut parents = HashMap::new();
        walk(
            &m.root,
            0,
            self.config.max_depth,
            &mut items,
            &mut parents,
            m.root.task_id,
        )
        .map_err(Refused::Invalid)?;
        let mut uids: Vec<u16> = items.iter().map(|i| i.cmd.uid).collect();
        uids.sort_unstable();
        if uids.windows(2).any(|w| w[0] == w[1]) {
            return Err(Refused::Invalid(
                "message uids repeat within the mission".into(),
            ));
        }
        let append = m.append_flag != 0 && self.missions.contains_key(&m.mission_id);
        let existing = if append {
            self.missions[&m.mission_id].items.len()
        } else {
            0
        };
        let replaced = if append {
            0
        } else {
            self.missions
                .get(&m.mission_id)
                .map_or(0, |x| x.items.len())
        };
        if self.stored - replaced + items.len() > self.config.max_messages {
            return Err(Refused::Invalid(format!(
                "more than {} messages spooled",
                self.config.max_messages
            )));
        }
        if !append
            && !self.missions.contains_key(&m.mission_id)
            && self.missions.len() >= self.config.max_missions
        {
            return Err(Refused::Invalid(format!(
                "{} missions already stored",
                self.config.max_missions
            )));
        }
        if self.running == Some(m.mission_id) && !append {
            return Err(Refused::Invalid(format!(
                "mission {} is running: abort it before replacing it",
                m.mission_id
            )));
        }
        self.stored = self.stored - replaced + items.len();
        if append {
            let mission = self.mission(m.mission_id)?;
            if mission
                .items
                .iter()
                .any(|i| uids.binary_search(&i.cmd.uid).is_ok())
            {
                self.stored -= items.len();
                return Err(Refused::Invalid(
                    "appended uids repeat uids of the mission".into(),
                ));
            }
            mission.items.extend(items);
            for (k, v) in parents {
                mission.parents.entry(k).or_insert(v);
            }
            if mission.state == MissionState::Finished {
                mission.state = MissionState::Pending;
            }
            let _ = existing;
        } else {
            self.missions.insert(
                m.mission_id,
                Mission {
                    owner,
                    items,
                    cursor: 0,
                    waiting: None,
                    state: MissionState::Pending,
                    paused_tasks: Vec::new(),
                    aborted_tasks: Vec::new(),
                    parents,
                    remote_started: Vec::new(),
                },
            );
            self.restored.remove(&m.mission_id);
        }
        self.persist(m.mission_id, before, stored_before)
    }

    fn on_run_mission(&mut self, ctx: &mut Ctx<'_>, m: &RunMission) -> Result<(), Refused> {
        if let Some(r) = self.running.filter(|r| *r != m.mission_id) {
            return Err(Refused::Invalid(format!("mission {r} is running")));
        }
        if ctx.state() != CoreState::Ready {
            return Err(Refused::Invalid(
                "the spooler runs missions only in Ready".into(),
            ));
        }
        if self.restored.contains(&m.mission_id) {
            // Paused by a restart: runs again from the start of the task it was in.
            let me = ctx.address();
            let config = &self.config;
            if let Some(mission) = self.missions.get_mut(&m.mission_id) {
                if mission.state == MissionState::Paused {
                    mission.rewind_task(|dest| self_route(config, me, dest) != dest);
                    mission.state = MissionState::Pending;
                }
            }
            self.restored.remove(&m.mission_id);
        }
        let mission = self.mission(m.mission_id)?;
        if mission.state != MissionState::Pending {
            return Err(Refused::Invalid(format!(
                "mission {} is not pending",
                m.mission_id
            )));
        }
        mission.state = MissionState::Running;
        self.running = Some(m.mission_id);
        self.clear_reason(m.mission_id);
        self.touch(m.mission_id);
        ctx.transition(Transition::Run)
            .map_err(|e| Refused::Invalid(e.to_string()))?;
        self.pump(ctx);
        Ok(())
    }

    fn on_pause_mission(&mut self, ctx: &mut Ctx<'_>, m: &PauseMission) -> Result<(), Refused> {
        let mission = self.mission(m.mission_id)?;
        if m.task_id == 0 {
            if mission.state != MissionState::Running {
                return Err(Refused::Invalid(format!(
                    "mission {} is not running",
                    m.mission_id
                )));
            }
            mission.state = MissionState::Paused;
            ctx.transition(Transition::Pause)
                .map_err(|e| Refused::Invalid(e.to_string()))?;
        } else if !mission.paused_tasks.contains(&m.task_id) {
            mission.paused_tasks.push(m.task_id);
        }
        self.touch(m.mission_id);
        self.flush();
        Ok(())
    }

    fn on_resume_mission(&mut self, ctx: &mut Ctx<'_>, m: &ResumeMission) -> Result<(), Refused> {
        if m.task_id == 0 && self.restored.contains(&m.mission_id) {
            // Paused by a restart: the component is Idle, so this runs it.
            return self.on_run_mission(
                ctx,
                &RunMission {
                    mission_id: m.mission_id,
                },
            );
        }
        let mission = self.mission(m.mission_id)?;
        if m.task_id == 0 {
            if mission.state != MissionState::Paused {
                return Err(Refused::Invalid(format!(
                    "mission {} is not paused",
                    m.mission_id
                )));
            }
            mission.state = MissionState::Running;
            ctx.transition(Transition::Resume)
                .map_err(|e| Refused::Invalid(e.to_string()))?;
            self.clear_reason(m.mission_id);
        } else {
            mission.paused_tasks.retain(|t| *t != m.task_id);
        }
        self.touch(m.mission_id);
        self.pump(ctx);
        Ok(())
    }

    fn on_abort_mission(&mut self, ctx: &mut Ctx<'_>, m: &AbortMission) -> Result<(), Refused> {
        let mission = self.mission(m.mission_id)?;
        if m.task_id == 0 {
            let was = mission.state;
            mission.state = MissionState::Aborted;
            mission.waiting = None;
            if self.running == Some(m.mission_id) {
                self.running = None;
                if matches!(was, MissionState::Running | MissionState::Paused) {
                    let _ = ctx.transition(Transition::Abort);
                }
            }
            self.restored.remove(&m.mission_id);
            self.clear_reason(m.mission_id);
            self.touch(m.mission_id);
            self.flush();
        } else {
            if !mission.aborted_tasks.contains(&m.task_id) {
                mission.aborted_tasks.push(m.task_id);
            }
            // Waiting on a message of an aborted task ends the wait.
            let w = mission.waiting;
            let waiting_task = w
                .and_then(|u| mission.items.iter().find(|i| i.cmd.uid == u))
                .map(|i| i.task);
            if waiting_task.is_some_and(|t| mission.task_blocked(t, &mission.aborted_tasks)) {
                mission.waiting = None;
            }
            self.touch(m.mission_id);
            self.pump(ctx);
        }
        Ok(())
    }

    fn on_remove_messages(
        &mut self,
        _ctx: &mut Ctx<'_>,
        m: &RemoveMessages,
    ) -> Result<(), Refused> {
        let (before, stored_before) = (self.saved(m.mission_id), self.stored);
        let mission = self.mission(m.mission_id)?;
        for uid in &m.uids {
            let Some(item) = mission.items.iter().find(|i| i.cmd.uid == *uid) else {
                return Err(Refused::Invalid(format!(
                    "mission {} has no message {uid}",
                    m.mission_id
                )));
            };
            if item.state != ItemState::Pending {
                return Err(Refused::Invalid(format!(
                    "message {uid} was already spooled"
                )));
            }
        }
        let mut n = 0;
        for item in mission
            .items
            .iter_mut()
            .filter(|i| m.uids.contains(&i.cmd.uid))
        {
            item.state = ItemState::Removed;
            n += 1;
        }
        self.stored -= n.min(self.stored);
        self.persist(m.mission_id, before, stored_before)
    }

    fn on_replace_messages(
        &mut self,
        _ctx: &mut Ctx<'_>,
        m: &ReplaceMessages,
    ) -> Result<(), Refused> {
        let max = self.config.max_messages;
        let stored = self.stored;
        let before = self.saved(m.mission_id);
        let mission = self.mission(m.mission_id)?;
        for uid in &m.uids {
            match mission.items.iter().find(|i| i.cmd.uid == *uid) {
                None => {
                    return Err(Refused::Invalid(format!(
                        "mission {} has no message {uid}",
                        m.mission_id
                    )))
                }
                Some(i) if i.state != ItemState::Pending => {
                    return Err(Refused::Invalid(format!(
                        "message {uid} was already spooled"
                    )))
                }
                Some(_) => {}
            }
        }
        for c in &m.commands {
            if !m.uids.contains(&c.uid)
                && mission
                    .items
                    .iter()
                    .any(|i| i.cmd.uid == c.uid && i.state != ItemState::Removed)
            {
                return Err(Refused::Invalid(format!(
                    "uid {} is already in the mission",
                    c.uid
                )));
            }
        }
        if stored + m.commands.len() > max {
            return Err(Refused::Invalid(format!(
                "more than {max} messages spooled"
            )));
        }
        // New messages go where the first removed one was (or at the end of the task).
        let at = mission
            .items
            .iter()
            .position(|i| m.uids.contains(&i.cmd.uid))
            .or_else(|| {
                mission
                    .items
                    .iter()
                    .rposition(|i| i.task == m.task_id)
                    .map(|p| p + 1)
            })
            .unwrap_or(mission.items.len())
            .max(mission.cursor);
        for item in mission
            .items
            .iter_mut()
            .filter(|i| m.uids.contains(&i.cmd.uid))
        {
            item.state = ItemState::Removed;
        }
        let new: Vec<Item> = m
            .commands
            .iter()
            .map(|c| Item {
                task: m.task_id,
                cmd: c.clone(),
                state: ItemState::Pending,
            })
            .collect();
        let added = new.len();
        mission.items.splice(at..at, new);
        self.stored = stored + added - m.uids.len().min(stored + added);
        self.persist(m.mission_id, before, stored)
    }

    fn on_query_mission_status(
        &mut self,
        _ctx: &mut Ctx<'_>,
        q: &QueryMissionStatus,
    ) -> Result<ReportMissionStatus, Refused> {
        let mission = self
            .missions
            .get(&q.mission_id)
            .ok_or_else(|| Refused::Invalid(format!("no mission {}", q.mission_id)))?;
        let status = match q.status_type {
            MissionStatusType::Message => {
                let item = mission
                    .items
                    .iter()
                    .find(|i| i.cmd.uid == q.task_msg_id)
                    .ok_or_else(|| Refused::Invalid(format!("no message {}", q.task_msg_id)))?;
                match item.state {
                    ItemState::Pending if mission.state == MissionState::Paused => {
                        MissionStatus::Paused
                    }
                    ItemState::Pending => MissionStatus::Pending,
                    ItemState::Sent => MissionStatus::Spooling,
                    ItemState::Finished => MissionStatus::Finished,
                    ItemState::Removed => MissionStatus::Aborted,
                }
            }
            MissionStatusType::Task if mission.aborted_tasks.contains(&q.task_id) => {
                MissionStatus::Aborted
            }
            MissionStatusType::Task if mission.paused_tasks.contains(&q.task_id) => {
                MissionStatus::Paused
            }
            MissionStatusType::Task => {
                let mine: Vec<&Item> = mission
                    .items
                    .iter()
                    .filter(|i| i.task == q.task_id)
                    .collect();
                if mine
                    .iter()
                    .all(|i| matches!(i.state, ItemState::Finished | ItemState::Removed))
                {
                    MissionStatus::Finished
                } else if mine.iter().any(|i| i.state == ItemState::Sent) {
                    MissionStatus::Spooling
                } else {
                    MissionStatus::Pending
                }
            }
            _ => wire_status(mission.state),
        };
        Ok(ReportMissionStatus {
            status_type: q.status_type,
            status,
            secondary_status: MissionSecondaryStatus::NoError,
            mission_id: q.mission_id,
            task_id: q.task_id,
            task_msg_id: q.task_msg_id,
        })
    }

    fn on_query_spooling_preference(
        &mut self,
        _ctx: &mut Ctx<'_>,
        _q: &QuerySpoolingPreference,
    ) -> Result<ReportSpoolingPreference, Refused> {
        Ok(ReportSpoolingPreference {
            spool_type: SpoolingLimitType::MessageCount,
            data: self.config.preference,
        })
    }

    fn on_report_mission_status(
        &mut self,
        ctx: &mut Ctx<'_>,
        r: &ReportMissionStatus,
    ) -> Result<(), Refused> {
        self.finished(ctx, r);
        Ok(())
    }

    fn on_report_spooling_preference(
        &mut self,
        ctx: &mut Ctx<'_>,
        r: &ReportSpoolingPreference,
    ) -> Result<(), Refused> {
        if let Some(src) = ctx.source() {
            let n = if r.spool_type == SpoolingLimitType::MessageCount {
                r.data
            } else {
                1
            };
            self.preferences.insert(src, n);
            self.pump(ctx);
        }
        Ok(())
    }

    fn on_other_message(
        &mut self,
        ctx: &mut Ctx<'_>,
        msg: &Message,
    ) -> Result<Option<Message>, Refused> {
        match (msg, ctx.source()) {
            (Message::RejectComponentControl(_), Some(src)) => {
                // Someone else holds it: keep asking, do not send past it.
                if !self.refused_control.contains(&src) {
                    self.refused_control.push(src);
                }
                return Ok(None);
            }
            (Message::ConfirmComponentControl(_), Some(src)) => {
                self.refused_control.retain(|a| *a != src);
                return Ok(None);
            }
            _ => {}
        }
        if let (Message::ReportServices(s), Some(src)) = (msg, ctx.source()) {
            let spool = s.services.iter().any(|sv| {
                sv.input_commands
                    .iter()
                    .any(|c| c.command_code == SpoolMission::CODE.0)
            });
            self.spool_capable.insert(src, spool);
            return Ok(None);
        }
        Err(Refused::Unsupported)
    }

    fn state_changed(&mut self, ctx: &mut Ctx<'_>, _from: CoreState, to: CoreState) {
        // Leaving Ready stops the running mission (the modes return to Idle); Run Mission
        // starts it again from the beginning of the task it was in.
        if to != CoreState::Ready {
            if let Some(id) = self.running.take() {
                let me = ctx.address();
                let config = &self.config;
                if let Some(m) = self.missions.get_mut(&id) {
                    m.state = MissionState::Pending;
                    m.rewind_task(|dest| self_route(config, me, dest) != dest);
                }
                self.touch(id);
                self.flush();
            }
        }
    }

    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        // What became of the deliveries (refused ones pause their mission).
        self.take_outcomes(ctx);
        if ctx.state() == CoreState::Ready {
            self.pump(ctx);
        }
    }
}
