//! The persistence seam of the stock cores that keep state worth keeping across a
//! restart (the World Model's objects, the Mission Spooler's missions): each core
//! commits every change it accepts through a small journal trait of its own
//! ([`VksJournal`](super::world_model::VksJournal),
//! [`MissionJournal`](super::spooler::MissionJournal)) *before* it confirms the change,
//! and is rebuilt from what was committed by a `restore` constructor. The cores know
//! no database: without a journal they keep everything in memory, as always; the
//! `jaus-store` crate implements the journals over an embedded database.

/// Why a journal could not commit a change. The core then undoes the change in memory
/// and refuses it, so nothing is confirmed that was not committed.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct JournalError(pub String);
