//! Delivery: how each destination receives mission messages (probed once), control of
//! the destinations, sending what can be sent of the running mission, and the
//! "finished" reports that let it go on.

use std::time::Instant;

use super::mission::{Item, ItemState, MissionState};
use super::{SpoolerConfig, StockMissionSpooler};
use crate::components::mission_spooler::{Ctx, Transition};
use crate::messages::*;
use crate::Address;

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

impl StockMissionSpooler {
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

    /// Sends what can be sent of the running mission, and commits the missions that
    /// changed (with a journal).
    pub(super) fn pump(&mut self, ctx: &mut Ctx<'_>) {
        let (id, sent) = (self.running, self.sent);
        self.pump_messages(ctx);
        if let Some(id) = id {
            if self.sent != sent || self.running != Some(id) {
                self.touch(id);
            }
        }
        self.flush();
    }

    /// Sends what can be sent of the running mission.
    fn pump_messages(&mut self, ctx: &mut Ctx<'_>) {
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
                if self.unsettled(id) {
                    // Finished once every delivery to a destination that answers is
                    // acknowledged (a refused one is sent again or pauses it).
                    return;
                }
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
                            Ok(msg) => self.deliver(ctx, id, target, vec![c.uid], msg),
                            Err(e) => tracing::warn!(
                                uid = c.uid,
                                destination = %target,
                                "mission message does not decode; skipped: {e}"
                            ),
                        }
                    }
                }
                _ => {
                    let uids = cmds.iter().map(|c| c.uid).collect();
                    let batch = SpoolMission {
                        mission_id: id,
                        append_flag: 1,
                        root: MissionTask {
                            task_id: first_task,
                            child_count: 0,
                            child_offsets: Vec::new(),
                            messages: cmds,
                            children: Vec::new(),
                        },
                    };
                    self.deliver(ctx, id, target, uids, batch.into());
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

    pub(super) fn finished(&mut self, ctx: &mut Ctx<'_>, r: &ReportMissionStatus) {
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
        if self.journal.is_some() {
            self.dirty.insert(r.mission_id);
        }
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

pub(super) fn self_route(config: &SpoolerConfig, me: Address, dest: Address) -> Address {
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
