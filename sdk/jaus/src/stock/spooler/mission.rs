//! The mission model: a spooled task tree flattened into its messages in tree order,
//! each with its state, and the mission's own state.

use std::collections::HashMap;

use crate::messages::*;
use crate::Address;

/// Where one message of a mission stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ItemState {
    /// Not sent yet.
    Pending,
    /// Sent (a blocking one not reported finished yet).
    Sent,
    /// Reported finished by its destination.
    Finished,
    /// Removed or replaced before it was sent.
    Removed,
}

#[derive(Debug, Clone)]
pub(super) struct Item {
    pub(super) task: u16,
    pub(super) cmd: MissionCommand,
    pub(super) state: ItemState,
}

/// Where a mission stands.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MissionState {
    /// Spooled, not running.
    Pending,
    /// Running: its messages are being sent.
    Running,
    /// Paused: nothing is sent until it is resumed.
    Paused,
    /// Aborted.
    Aborted,
    /// Every message sent and every blocking one finished.
    Finished,
}

#[derive(Debug, Clone)]
pub(super) struct Mission {
    pub(super) owner: Address,
    /// Every message in tree order.
    pub(super) items: Vec<Item>,
    /// Position of the next message to send.
    pub(super) cursor: usize,
    /// uid of the blocking message being waited for.
    pub(super) waiting: Option<u16>,
    pub(super) state: MissionState,
    pub(super) paused_tasks: Vec<u16>,
    pub(super) aborted_tasks: Vec<u16>,
    /// Parent of each task id.
    pub(super) parents: HashMap<u16, u16>,
    /// Remote spoolers already told to run this mission.
    pub(super) remote_started: Vec<Address>,
}

impl Mission {
    /// Puts the task being executed back to its first message, so that running the
    /// mission again sends the whole task again. A destination leaving Ready (Standby,
    /// Emergency, Clear Emergency) forgets what it was told: a driver's travel speed is
    /// zero after an emergency, and the blocking message it was executing will never
    /// finish, so carrying on from the message after it would wait forever. Messages
    /// for another subsystem's spooler are left alone: that spooler runs its own copy of
    /// the mission. `remote(dest)` says whether `dest` is reached through one.
    pub(super) fn rewind_task(&mut self, remote: impl Fn(Address) -> bool) {
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

    pub(super) fn task_blocked(&self, task: u16, list: &[u16]) -> bool {
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

pub(super) fn walk(
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

pub(super) fn wire_status(s: MissionState) -> MissionStatus {
    match s {
        MissionState::Pending => MissionStatus::Pending,
        MissionState::Running => MissionStatus::Spooling,
        MissionState::Paused => MissionStatus::Paused,
        MissionState::Aborted => MissionStatus::Aborted,
        MissionState::Finished => MissionStatus::Finished,
    }
}
