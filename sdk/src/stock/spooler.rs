//! The Mission Spooler (Part 1 §5.6.2, component 36).
//!
//! A mission is an N-ary tree of tasks, each holding JAUS messages and child tasks; the
//! spooler keeps missions by id and, when one runs, parcels its messages out in tree
//! order (a task's messages, then its children, depth first). Rules:
//!
//! * It never sends past a **blocking** message until a Report Mission Status "finished"
//!   for that message's uid arrives.
//! * Delivery to each destination is chosen once, by asking it Query Spooling Preference
//!   and Query Services: a component that answers the preference gets Spool Mission
//!   with up to its message-count limit per batch; one that answers only its services
//!   and lists Spool Mission gets Spool Mission one message at a time (Part 1's fallback
//!   when the preference is not answered); one that lists no Spool Mission, or answers
//!   neither within [`SpoolerConfig::probe_timeout`], gets the raw messages one at a time.
//! * Messages for another subsystem whose Mission Spooler is known
//!   ([`SpoolerConfig::remote_spoolers`]) go to that spooler as Spool Mission + Run
//!   Mission (Part 1 Figure 5-31); its "finished" reports come back here.
//! * Every "finished" (message or mission) is reported to the component that spooled the
//!   mission.
//! * Control of a destination is requested (with the spooler's authority) before its
//!   first message and released once no mission has a message for it left to send or a
//!   blocking message it is still executing (a driver stops when it loses control), so
//!   the component's usual controller gets it back.
//! * Pause and abort apply to a whole mission (task 0) or one task; Remove and Replace
//!   Messages change only messages not yet sent.
//!
//! Only one mission runs at a time; the component modes follow it (Idle, Running,
//! Paused).

use std::collections::{BTreeMap, HashMap};
use std::time::{Duration, Instant};

use crate::component::{CoreState, Refused};
use crate::components::mission_spooler::{Ctx, MissionSpooler, Transition};
use crate::messages::*;
use crate::{Address, JausMessage};

/// Settings of the spooler.
#[derive(Debug, Clone)]
pub struct SpoolerConfig {
    /// How long to wait for a destination to answer Query Spooling Preference / Query
    /// Services.
    pub probe_timeout: Duration,
    /// How often control of a destination is asked for again while refused.
    pub control_retry: Duration,
    /// Mission Spoolers of other subsystems.
    pub remote_spoolers: Vec<Address>,
    /// Most missions stored.
    pub max_missions: usize,
    /// Most messages stored over all missions.
    pub max_messages: usize,
    /// Deepest task tree accepted.
    pub max_depth: usize,
    /// The message-count limit this spooler reports in Report Spooling Preference.
    pub preference: i32,
    /// Most messages sent per tick (keeps the component's outgoing queue from
    /// overflowing on long non-blocking stretches).
    pub max_per_tick: usize,
}

impl Default for SpoolerConfig {
    fn default() -> Self {
        Self {
            probe_timeout: Duration::from_secs(1),
            control_retry: Duration::from_secs(1),
            remote_spoolers: Vec::new(),
            max_missions: 64,
            max_messages: 1_000_000,
            max_depth: 64,
            preference: 1000,
            max_per_tick: 128,
        }
    }
}

/// How one destination receives mission messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Delivery {
    /// Being asked (since then).
    Probing(Instant),
    /// Spool Mission with up to this many messages at a time.
    Spool(usize),
    /// The raw messages, one at a time.
    Raw,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ItemState {
    Pending,
    Sent,
    Finished,
    Removed,
}

#[derive(Debug, Clone)]
struct Item {
    task: u16,
    cmd: MissionCommand,
    state: ItemState,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum MissionState {
    Pending,
    Running,
    Paused,
    Aborted,
    Finished,
}

#[derive(Debug, Clone)]
struct Mission {
    owner: Address,
    /// Every message in tree order.
    items: Vec<Item>,
    /// Position of the next message to send.
    cursor: usize,
    /// uid of the blocking message being waited for.
    waiting: Option<u16>,
    state: MissionState,
    paused_tasks: Vec<u16>,
    aborted_tasks: Vec<u16>,
    /// Parent of each task id.
    parents: HashMap<u16, u16>,
    /// Remote spoolers already told to run this mission.
    remote_started: Vec<Address>,
}

impl Mission {
    /// Puts the task being executed back to its first message, so that running the
    /// mission again sends the whole task again. A destination leaving Ready (Standby,
    /// Emergency, Clear Emergency) forgets what it was told: a driver's travel speed is
    /// zero after an emergency, and the blocking message it was executing will never
    /// finish, so carrying on from the message after it would wait forever. Messages
    /// for another subsystem's spooler are left alone: that spooler runs its own copy of
    /// the mission. `remote(dest)` says whether `dest` is reached through one.
    fn rewind_task(&mut self, remote: impl Fn(Address) -> bool) {
        let Some(last) = self.cursor.checked_sub(1) else {
            return;
        };
        let task = self.items[last].task;
        let in_progress =
            self.waiting.is_some() || self.items.get(self.cursor).is_some_and(|i| i.task == task);
        if !in_progress {
            return;
        }
        let mut first = last;
        while first > 0 && self.items[first - 1].task == task {
            first -= 1;
        }
        if self.items[first..=last]
            .iter()
            .any(|i| remote(i.cmd.message.header.destination))
        {
            return;
        }
        for it in &mut self.items[first..=last] {
            if it.state != ItemState::Removed {
                it.state = ItemState::Pending;
            }
        }
        self.cursor = first;
        self.waiting = None;
    }

    fn task_blocked(&self, task: u16, list: &[u16]) -> bool {
        let mut t = Some(task);
        let mut guard = 0;
        while let Some(id) = t {
            if list.contains(&id) {
                return true;
            }
            t = self.parents.get(&id).copied().filter(|p| *p != id);
            guard += 1;
            if guard > 1024 {
                break;
            }
        }
        false
    }
}

/// The Mission Spooler.
#[derive(Debug)]
pub struct StockMissionSpooler {
    config: SpoolerConfig,
    missions: BTreeMap<u16, Mission>,
    running: Option<u16>,
    delivery: HashMap<Address, Delivery>,
    preferences: HashMap<Address, i32>,
    spool_capable: HashMap<Address, bool>,
    control_asked: HashMap<Address, (Instant, Instant)>,
    refused_control: Vec<Address>,
    stored: usize,
    sent: u64,
}

fn walk(
    t: &MissionTask,
    depth: usize,
    max: usize,
    items: &mut Vec<Item>,
    parents: &mut HashMap<u16, u16>,
    parent: u16,
) -> Result<(), String> {
    if depth > max {
        return Err(format!("task tree deeper than {max}"));
    }
    if parents.insert(t.task_id, parent).is_some() && t.task_id != 0 {
        return Err(format!("task id {} is used twice", t.task_id));
    }
    for c in &t.messages {
        items.push(Item {
            task: t.task_id,
            cmd: c.clone(),
            state: ItemState::Pending,
        });
    }
    for c in &t.children {
        walk(c, depth + 1, max, items, parents, t.task_id)?;
    }
    Ok(())
}

impl StockMissionSpooler {
    /// With `config`.
    pub fn new(config: SpoolerConfig) -> Self {
        Self {
            config,
            missions: BTreeMap::new(),
            running: None,
            delivery: HashMap::new(),
            preferences: HashMap::new(),
            spool_capable: HashMap::new(),
            control_asked: HashMap::new(),
            refused_control: Vec::new(),
            stored: 0,
            sent: 0,
        }
    }

    /// Number of missions stored.
    pub fn missions(&self) -> usize {
        self.missions.len()
    }

    /// The delivery chosen for `dest`, if any.
    pub fn delivery(&self, dest: Address) -> Option<Delivery> {
        self.delivery.get(&dest).copied()
    }

    /// Messages sent to destinations so far.
    pub fn sent(&self) -> u64 {
        self.sent
    }

    /// The status of mission `id`: (status, messages finished or sent, total).
    pub fn status(&self, id: u16) -> Option<(MissionStatus, usize, usize)> {
        let m = self.missions.get(&id)?;
        let done = m
            .items
            .iter()
            .filter(|i| matches!(i.state, ItemState::Sent | ItemState::Finished))
            .count();
        Some((wire_status(m.state), done, m.items.len()))
    }

    fn mission(&mut self, id: u16) -> Result<&mut Mission, Refused> {
        self.missions
            .get_mut(&id)
            .ok_or_else(|| Refused::Invalid(format!("no mission {id}")))
    }

    fn report(
        ctx: &mut Ctx<'_>,
        to: Address,
        kind: MissionStatusType,
        status: MissionStatus,
        mission: u16,
        task: u16,
        uid: u16,
    ) {
        ctx.send(
            to,
            ReportMissionStatus {
                status_type: kind,
                status,
                secondary_status: MissionSecondaryStatus::NoError,
                mission_id: mission,
                task_id: task,
                task_msg_id: uid,
            },
        );
    }

    /// The address messages for `dest` go to (a remote spooler for another subsystem).
    fn route(&self, me: Address, dest: Address) -> Address {
        if dest.subsystem != me.subsystem {
            if let Some(s) = self
                .config
                .remote_spoolers
                .iter()
                .find(|s| s.subsystem == dest.subsystem)
            {
                return *s;
            }
        }
        dest
    }

    fn decide(&mut self, dest: Address, now: Instant) -> Option<Delivery> {
        let d = *self.delivery.get(&dest)?;
        let Delivery::Probing(since) = d else {
            return Some(d);
        };
        if let Some(n) = self.preferences.get(&dest) {
            let d = Delivery::Spool((*n).clamp(1, 4096) as usize);
            self.delivery.insert(dest, d);
            return Some(d);
        }
        if now.saturating_duration_since(since) < self.config.probe_timeout {
            return None;
        }
        let d = match self.spool_capable.get(&dest) {
            Some(true) => Delivery::Spool(1),
            _ => Delivery::Raw,
        };
        tracing::info!(destination = %dest, "mission delivery: {d:?}");
        self.delivery.insert(dest, d);
        Some(d)
    }

    /// Sends what can be sent of the running mission.
    fn pump(&mut self, ctx: &mut Ctx<'_>) {
        let Some(id) = self.running else { return };
        let now = ctx.now();
        let me = ctx.address();
        let mut budget = self.config.max_per_tick.max(1);
        while budget > 0 {
            let Some(m) = self.missions.get(&id) else {
                return;
            };
            if m.state != MissionState::Running || m.waiting.is_some() {
                return;
            }
            // Skip what was removed or aborted.
            let mut cursor = m.cursor;
            while cursor < m.items.len()
                && (m.items[cursor].state != ItemState::Pending
                    || m.task_blocked(m.items[cursor].task, &m.aborted_tasks))
            {
                cursor += 1;
            }
            if cursor >= m.items.len() {
                let owner = m.owner;
                if let Some(m) = self.missions.get_mut(&id) {
                    m.cursor = cursor;
                    m.state = MissionState::Finished;
                }
                self.running = None;
                let _ = ctx.transition(Transition::Finish);
                Self::report(
                    ctx,
                    owner,
                    MissionStatusType::Mission,
                    MissionStatus::Finished,
                    id,
                    0,
                    0,
                );
                return;
            }
            if m.task_blocked(m.items[cursor].task, &m.paused_tasks) {
                if let Some(m) = self.missions.get_mut(&id) {
                    m.cursor = cursor;
                }
                return;
            }
            let dest = m.items[cursor].cmd.message.header.destination;
            let target = self.route(me, dest);
            let remote = target != dest;
            // Ask how it wants its messages, at the same time as asking for control.
            if !remote && !self.delivery.contains_key(&target) {
                self.delivery.insert(target, Delivery::Probing(now));
                ctx.send(target, QuerySpoolingPreference {});
                ctx.send_core(target, QueryServices {});
            }
            // Control of the target. A destination that answers nothing within the probe
            // timeout (one without component control) gets the messages anyway; one
            // controlled by someone else is asked again and waited for.
            if !ctx.has_control_of(target) {
                let retry = self.config.control_retry;
                let (first, last) = *self
                    .control_asked
                    .entry(target)
                    .or_insert((now, now.checked_sub(retry).unwrap_or(now)));
                if now.saturating_duration_since(first) < self.config.probe_timeout
                    || self.refused_control.contains(&target)
                {
                    if first == last || now.saturating_duration_since(last) >= retry {
                        self.control_asked.insert(target, (first, now));
                        ctx.request_control(target);
                    }
                    return;
                }
            }
            // Core commands (Resume, Standby, ...) always go as they are: the
            // destination's runtime executes them, not its mission handling.
            let core = m.items[cursor].cmd.message.header.command_code.0 <= 0x0011;
            let delivery = if core {
                Delivery::Raw
            } else if remote {
                Delivery::Spool(usize::MAX)
            } else {
                match self.decide(target, now) {
                    Some(d) => d,
                    None => return,
                }
            };
            let Some(m) = self.missions.get_mut(&id) else {
                return;
            };
            // The batch: consecutive pending messages for the same destination, ending
            // at a blocking one.
            let max = match delivery {
                Delivery::Spool(n) => n,
                _ => 1,
            };
            let mut batch = Vec::new();
            let mut i = cursor;
            while i < m.items.len() && batch.len() < max {
                let it = &m.items[i];
                let it_core = it.cmd.message.header.command_code.0 <= 0x0011;
                if it.state != ItemState::Pending
                    || it.cmd.message.header.destination != dest
                    || (it_core && !batch.is_empty())
                    || (!it_core && core)
                {
                    break;
                }
                batch.push(i);
                i += 1;
                if it.cmd.blocking != 0 {
                    break;
                }
            }
            for &b in &batch {
                m.items[b].state = ItemState::Sent;
            }
            m.cursor = i;
            let last = &m.items[*batch.last().unwrap_or(&cursor)];
            if last.cmd.blocking != 0 {
                m.waiting = Some(last.cmd.uid);
            }
            let first_task = m.items[cursor].task;
            let cmds: Vec<MissionCommand> = batch.iter().map(|b| m.items[*b].cmd.clone()).collect();
            let start_remote = remote && !m.remote_started.contains(&target);
            if start_remote {
                m.remote_started.push(target);
            }
            // Control is held only while the mission has messages for that component, or
            // a blocking one it is still executing (losing control stops a driver).
            let more_for_target = m
                .items
                .iter()
                .any(|it| Self::holds(&self.config, me, it, target));
            self.sent += cmds.len() as u64;
            budget = budget.saturating_sub(cmds.len().max(1));
            match delivery {
                Delivery::Raw | Delivery::Probing(_) => {
                    for c in &cmds {
                        match Message::decode(c.message.header.command_code, &c.message.body) {
                            Ok(msg) => ctx.forward(target, msg),
                            Err(e) => tracing::warn!(
                                uid = c.uid,
                                "mission message does not decode; skipped: {e}"
                            ),
                        }
                    }
                }
                _ => {
                    ctx.send(
                        target,
                        SpoolMission {
                            mission_id: id,
                            append_flag: 1,
                            root: MissionTask {
                                task_id: first_task,
                                child_count: 0,
                                child_offsets: Vec::new(),
                                messages: cmds,
                                children: Vec::new(),
                            },
                        },
                    );
                    if start_remote {
                        ctx.send(target, RunMission { mission_id: id });
                    }
                }
            }
            if !more_for_target && ctx.has_control_of(target) {
                ctx.release_control(target);
                self.control_asked.remove(&target);
            }
        }
    }

    /// Whether `it` needs control of `target` kept: not sent yet, or a blocking message
    /// being executed.
    fn holds(config: &SpoolerConfig, me: Address, it: &Item, target: Address) -> bool {
        (it.state == ItemState::Pending || (it.state == ItemState::Sent && it.cmd.blocking != 0))
            && self_route(config, me, it.cmd.message.header.destination) == target
    }

    fn finished(&mut self, ctx: &mut Ctx<'_>, r: &ReportMissionStatus) {
        if r.status != MissionStatus::Finished || r.status_type != MissionStatusType::Message {
            return;
        }
        let Some(m) = self.missions.get_mut(&r.mission_id) else {
            return;
        };
        let Some(item) = m.items.iter_mut().find(|i| i.cmd.uid == r.task_msg_id) else {
            return;
        };
        item.state = ItemState::Finished;
        let task = item.task;
        let me = ctx.address();
        let target = self_route(&self.config, me, item.cmd.message.header.destination);
        if m.waiting == Some(r.task_msg_id) {
            m.waiting = None;
        }
        let owner = m.owner;
        let still_needed = self.missions.values().any(|m| {
            m.items
                .iter()
                .any(|it| Self::holds(&self.config, me, it, target))
        });
        if !still_needed && ctx.has_control_of(target) {
            ctx.release_control(target);
            self.control_asked.remove(&target);
        }
        Self::report(
            ctx,
            owner,
            MissionStatusType::Message,
            MissionStatus::Finished,
            r.mission_id,
            task,
            r.task_msg_id,
        );
        self.pump(ctx);
    }
}

fn self_route(config: &SpoolerConfig, me: Address, dest: Address) -> Address {
    if dest.subsystem != me.subsystem {
        if let Some(s) = config
            .remote_spoolers
            .iter()
            .find(|s| s.subsystem == dest.subsystem)
        {
            return *s;
        }
    }
    dest
}

fn wire_status(s: MissionState) -> MissionStatus {
    match s {
        MissionState::Pending => MissionStatus::Pending,
        MissionState::Running => MissionStatus::Spooling,
        MissionState::Paused => MissionStatus::Paused,
        MissionState::Aborted => MissionStatus::Aborted,
        MissionState::Finished => MissionStatus::Finished,
    }
}

impl MissionSpooler for StockMissionSpooler {
    fn on_spool_mission(&mut self, ctx: &mut Ctx<'_>, m: &SpoolMission) -> Result<(), Refused> {
        let owner = ctx.source().unwrap_or(ctx.address());
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
        }
        Ok(())
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
        let mission = self.mission(m.mission_id)?;
        if mission.state != MissionState::Pending {
            return Err(Refused::Invalid(format!(
                "mission {} is not pending",
                m.mission_id
            )));
        }
        mission.state = MissionState::Running;
        self.running = Some(m.mission_id);
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
        Ok(())
    }

    fn on_resume_mission(&mut self, ctx: &mut Ctx<'_>, m: &ResumeMission) -> Result<(), Refused> {
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
        } else {
            mission.paused_tasks.retain(|t| *t != m.task_id);
        }
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
            self.pump(ctx);
        }
        Ok(())
    }

    fn on_remove_messages(
        &mut self,
        _ctx: &mut Ctx<'_>,
        m: &RemoveMessages,
    ) -> Result<(), Refused> {
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
        Ok(())
    }

    fn on_replace_messages(
        &mut self,
        _ctx: &mut Ctx<'_>,
        m: &ReplaceMessages,
    ) -> Result<(), Refused> {
        let max = self.config.max_messages;
        let stored = self.stored;
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
        Ok(())
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
            }
        }
    }

    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        if ctx.state() == CoreState::Ready {
            self.pump(ctx);
        }
    }
}

/// Builds a Mission Command record around `msg` addressed to `to` from `from`.
pub fn command(
    uid: u16,
    from: Address,
    to: Address,
    msg: &Message,
    blocking: bool,
) -> Result<MissionCommand, crate::codec::EncodeError> {
    use crate::codec::Encode;
    let body = msg.to_bytes()?;
    let header = crate::Header::new(msg.code(), to, from);
    Ok(MissionCommand {
        uid,
        message: crate::Packet::new(header, body),
        blocking: u8::from(blocking),
    })
}

/// A task without child tasks: `messages` in spooling order.
pub fn leaf_task(task_id: u16, messages: Vec<MissionCommand>) -> MissionTask {
    MissionTask {
        task_id,
        child_count: 0,
        child_offsets: Vec::new(),
        messages,
        children: Vec::new(),
    }
}

/// A Spool Mission replacing the current mission: a root task 0 without messages whose
/// children are `tasks`, run in order (child counts and offsets are computed on encode).
pub fn mission_of(mission_id: u16, tasks: Vec<MissionTask>) -> SpoolMission {
    let count = tasks.len();
    SpoolMission {
        mission_id,
        append_flag: 0,
        root: MissionTask {
            task_id: 0,
            child_count: count as u16,
            child_offsets: vec![0; count],
            messages: Vec::new(),
            children: tasks,
        },
    }
}
