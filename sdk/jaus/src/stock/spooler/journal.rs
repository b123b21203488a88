//! The Mission Spooler's persistence seam: [`MissionJournal`], through which
//! [`StockMissionSpooler`] commits every mission it accepts or changes, and
//! [`MissionRecord`], a mission as committed, from which a spooler is rebuilt after a
//! restart ([`StockMissionSpooler::restore`]).
//!
//! Without a journal missions are in memory only (the default). With one:
//!
//! * Spool Mission (new, replacing or appending), Remove Messages and Replace Messages
//!   are committed before the handler returns (before anything else is answered); if
//!   the commit fails the mission is put back as it was and the message is refused.
//! * Progress (Run, Pause, Resume, Abort, each message sent or reported finished, the
//!   spooler leaving Ready) is committed after the step that made it, once per mission
//!   per step; a failed commit is counted and tried again at the next step.
//!
//! A restored spooler holds every mission where it stood, those that were pending,
//! running or paused **paused**, so nothing moves on its own after a restart. Resume
//! Mission (task 0) or Run Mission runs such a mission again from the start of the
//! task it was in (the rule of a spooler leaving Ready: the destination may have lost
//! what it was told, and the blocking message it was executing may never report
//! finished).

use std::collections::BTreeSet;
use std::fmt;

use super::mission::{Item, ItemState, Mission, MissionState};
use super::StockMissionSpooler;
use crate::component::Refused;
use crate::messages::MissionCommand;
pub use crate::stock::journal::JournalError;
use crate::Address;

/// One message of a [`MissionRecord`].
#[derive(Debug, Clone, PartialEq)]
pub struct MissionMessage {
    /// Its task.
    pub task: u16,
    /// Where it stands.
    pub state: ItemState,
    /// The message, as spooled.
    pub command: MissionCommand,
}

/// A mission as committed: its messages in tree order and where it stands.
#[derive(Debug, Clone, PartialEq)]
pub struct MissionRecord {
    /// Its id.
    pub mission_id: u16,
    /// The component that spooled it (told when messages finish).
    pub owner: Address,
    /// Where it stands.
    pub state: MissionState,
    /// Position of the next message to send.
    pub cursor: u32,
    /// uid of the blocking message being waited for.
    pub waiting: Option<u16>,
    /// Tasks paused on their own.
    pub paused_tasks: Vec<u16>,
    /// Tasks aborted on their own.
    pub aborted_tasks: Vec<u16>,
    /// Each task and its parent.
    pub parents: Vec<(u16, u16)>,
    /// Other subsystems' spoolers already told to run it.
    pub remote_started: Vec<Address>,
    /// Its messages in tree order.
    pub messages: Vec<MissionMessage>,
}

/// Where the Mission Spooler commits its missions. `put` returns once the mission is
/// durable (it replaces the record of the same id).
pub trait MissionJournal: Send + fmt::Debug {
    /// Commits `mission`.
    fn put(&mut self, mission: &MissionRecord) -> Result<(), JournalError>;
}

impl Mission {
    fn to_record(&self, mission_id: u16) -> MissionRecord {
        let mut parents: Vec<(u16, u16)> = self.parents.iter().map(|(k, v)| (*k, *v)).collect();
        parents.sort_unstable();
        MissionRecord {
            mission_id,
            owner: self.owner,
            state: self.state,
            // Items never outnumber `max_messages`, far below 2³².
            cursor: u32::try_from(self.cursor).unwrap_or(u32::MAX),
            waiting: self.waiting,
            paused_tasks: self.paused_tasks.clone(),
            aborted_tasks: self.aborted_tasks.clone(),
            parents,
            remote_started: self.remote_started.clone(),
            messages: self
                .items
                .iter()
                .map(|i| MissionMessage {
                    task: i.task,
                    state: i.state,
                    command: i.cmd.clone(),
                })
                .collect(),
        }
    }

    fn from_record(r: MissionRecord) -> Result<Mission, String> {
        let id = r.mission_id;
        let cursor = r.cursor as usize;
        if cursor > r.messages.len() {
            return Err(format!(
                "mission {id}: cursor {cursor} is past its {} messages",
                r.messages.len()
            ));
        }
        if let Some(w) = r.waiting {
            if !r.messages.iter().any(|m| m.command.uid == w) {
                return Err(format!(
                    "mission {id}: waits for message {w}, which it lacks"
                ));
            }
        }
        Ok(Mission {
            owner: r.owner,
            items: r
                .messages
                .into_iter()
                .map(|m| Item {
                    task: m.task,
                    cmd: m.command,
                    state: m.state,
                })
                .collect(),
            cursor,
            waiting: r.waiting,
            state: r.state,
            paused_tasks: r.paused_tasks,
            aborted_tasks: r.aborted_tasks,
            parents: r.parents.into_iter().collect(),
            remote_started: r.remote_started,
        })
    }
}

impl StockMissionSpooler {
    /// A spooler holding `missions` (as committed to a journal) where each stood, those
    /// that were pending, running or paused now paused (module docs), committing every
    /// change from now on to `journal`. Refused when the missions break the limits of
    /// `config` (missions, messages) or one is inconsistent.
    pub fn restore(
        config: super::SpoolerConfig,
        missions: Vec<MissionRecord>,
        journal: Box<dyn MissionJournal>,
    ) -> Result<Self, String> {
        if missions.len() > config.max_missions {
            return Err(format!(
                "{} missions, more than the maximum of {} (max_missions)",
                missions.len(),
                config.max_missions
            ));
        }
        let mut s = Self::new(config);
        for r in missions {
            let id = r.mission_id;
            let mut m = Mission::from_record(r)?;
            if matches!(
                m.state,
                MissionState::Pending | MissionState::Running | MissionState::Paused
            ) {
                m.state = MissionState::Paused;
                s.restored.insert(id);
            }
            s.stored += m
                .items
                .iter()
                .filter(|i| i.state != ItemState::Removed)
                .count();
            if s.missions.insert(id, m).is_some() {
                return Err(format!("mission {id} is given twice"));
            }
        }
        if s.stored > s.config.max_messages {
            return Err(format!(
                "{} messages, more than the maximum of {} (max_messages)",
                s.stored, s.config.max_messages
            ));
        }
        s.journal = Some(journal);
        Ok(s)
    }

    /// Whether missions are committed to a journal.
    pub fn is_durable(&self) -> bool {
        self.journal.is_some()
    }

    /// Commits that failed (changes refused, progress tried again).
    pub fn journal_failures(&self) -> u64 {
        self.journal_failures
    }

    /// A mission as it would be committed.
    pub fn record(&self, id: u16) -> Option<MissionRecord> {
        self.missions.get(&id).map(|m| m.to_record(id))
    }

    /// A copy of mission `id` to put back if a change cannot be committed (only with a
    /// journal: without one nothing is copied).
    pub(super) fn saved(&self, id: u16) -> Option<Mission> {
        self.journal.as_ref()?;
        self.missions.get(&id).cloned()
    }

    /// Mission `id` changed: commit it at the next [`flush`](Self::flush).
    pub(super) fn touch(&mut self, id: u16) {
        if self.journal.is_some() {
            self.dirty.insert(id);
        }
    }

    /// Commits every mission touched since the last flush (progress; a failure is
    /// counted and tried again next time).
    pub(super) fn flush(&mut self) {
        let Some(j) = self.journal.as_mut() else {
            return;
        };
        let dirty = std::mem::take(&mut self.dirty);
        let mut again = BTreeSet::new();
        for id in dirty {
            let Some(m) = self.missions.get(&id) else {
                continue;
            };
            if let Err(e) = j.put(&m.to_record(id)) {
                self.journal_failures += 1;
                tracing::warn!(mission = id, "mission progress not committed: {e}");
                again.insert(id);
            }
        }
        self.dirty = again;
    }

    /// Commits mission `id` after an accepted change; if that fails, puts back
    /// `before` (the mission before the change, `None`: there was none) and `stored`,
    /// and refuses the change.
    pub(super) fn persist(
        &mut self,
        id: u16,
        before: Option<Mission>,
        stored: usize,
    ) -> Result<(), Refused> {
        let Some(j) = self.journal.as_mut() else {
            return Ok(());
        };
        let Some(m) = self.missions.get(&id) else {
            return Ok(());
        };
        match j.put(&m.to_record(id)) {
            Ok(()) => {
                self.dirty.remove(&id);
                Ok(())
            }
            Err(e) => {
                self.journal_failures += 1;
                match before {
                    Some(b) => self.missions.insert(id, b),
                    None => self.missions.remove(&id),
                };
                self.stored = stored;
                Err(Refused::Invalid(format!(
                    "mission {id} not changed: the journal did not commit it: {e}"
                )))
            }
        }
    }
}
