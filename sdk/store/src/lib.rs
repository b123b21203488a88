//! Durable World Model objects and Mission Spooler missions: the journals of the SDK's
//! stock cores ([`VksJournal`], [`MissionJournal`]) over an embedded database, and the
//! cores rebuilt from it after a restart.
//!
//! ```no_run
//! use jaus::stock::spooler::SpoolerConfig;
//! use jaus::stock::world_model::WorldModelConfig;
//! use jaus_store::Store;
//!
//! let store = Store::open("vehicle.jstore")?;
//! // Instance 1 of each: objects with their ids, missions paused where they stood.
//! let world_model = store.world_model(1, WorldModelConfig::default())?;
//! let spooler = store.mission_spooler(1, SpoolerConfig::default())?;
//! # Ok::<(), jaus_store::StoreError>(())
//! ```
//!
//! # The database
//!
//! [`redb`]: a pure-Rust embedded key-value store (no C toolchain), ACID, crash-safe by
//! copy-on-write B-trees with a checksummed commit, one writer at a time. Every
//! [`VksJournal::commit`] and [`MissionJournal::put`] is one write transaction
//! committed with fsync ([`redb::Durability::Immediate`]) before it returns, so a core
//! confirms nothing that a `kill -9` or a power cut could lose, and a transaction cut
//! short is never seen (the database opens at the last complete commit). SQLite's
//! R*Tree was the other candidate: the World Model already keeps its own R*-tree in
//! memory and rebuilds it at load by bulk loading, so the store only needs keys and
//! values, and redb gives those without a C library.
//!
//! # Tables
//!
//! | table | key | value |
//! |---|---|---|
//! | `vks_objects` | (component instance, object id) | a [`record`] holding the object's `VksStoredObject` wire bytes |
//! | `vks_metadata` | (component instance, feature class) | a [`record`] holding the text |
//! | `missions` | (component instance, mission id) | a [`record`] holding the mission, its messages as `MissionCommand` wire bytes |
//!
//! A record that does not decode at load is a [`StoreError::Corrupt`] naming the file,
//! the table and the key: the core is not built from half of what was committed.

pub mod record;

use std::fmt;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use jaus::stock::spooler::{
    JournalError, MissionJournal, MissionRecord, SpoolerConfig, StockMissionSpooler,
};
use jaus::stock::world_model::{
    StockWorldModel, VksChange, VksJournal, VksSnapshot, WorldModelConfig,
};
use redb::{Database, TableDefinition};

const OBJECTS: TableDefinition<'_, (u8, u32), &[u8]> = TableDefinition::new("vks_objects");
const METADATA: TableDefinition<'_, (u8, u16), &[u8]> = TableDefinition::new("vks_metadata");
const MISSIONS: TableDefinition<'_, (u8, u16), &[u8]> = TableDefinition::new("missions");

/// Largest record written or read by default (a mission of many messages is the
/// largest; an object is at most about 530 KB).
pub const MAX_RECORD_BYTES: usize = 64 << 20;

/// Why the store cannot be opened, read or written.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum StoreError {
    /// The database file cannot be opened or created (in use by another process, not
    /// a store, unreadable).
    #[error("store {}: cannot open: {error}", file.display())]
    Open {
        /// The file.
        file: PathBuf,
        /// Why.
        error: String,
    },
    /// A read or write of the database failed.
    #[error("store {}: {error}", file.display())]
    Database {
        /// The file.
        file: PathBuf,
        /// Why.
        error: String,
    },
    /// A record that does not decode: nothing is loaded.
    #[error("store {}: table `{table}`, key {key}: record does not decode: {error}", file.display())]
    Corrupt {
        /// The file.
        file: PathBuf,
        /// The table.
        table: &'static str,
        /// The key, as (instance, id).
        key: String,
        /// Why.
        error: String,
    },
    /// What was loaded breaks the limits of the core's configuration.
    #[error("store {}: {what}: cannot restore: {error}", file.display())]
    Restore {
        /// The file.
        file: PathBuf,
        /// What was restored (`world model instance 1`).
        what: String,
        /// Why.
        error: String,
    },
}

/// A database error as text (inside a write transaction).
fn db_text(e: impl Into<redb::Error>) -> String {
    e.into().to_string()
}

/// What the store has done since it was opened.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct StoreStats {
    /// Write transactions committed.
    pub commits: u64,
    /// Records written (inserted or replaced).
    pub written: u64,
    /// Records deleted.
    pub deleted: u64,
    /// Commits refused or failed (the core refused the change).
    pub failed: u64,
    /// Of those, refused because a record was larger than the limit.
    pub too_large: u64,
}

#[derive(Debug, Default)]
struct Counters {
    commits: AtomicU64,
    written: AtomicU64,
    deleted: AtomicU64,
    failed: AtomicU64,
    too_large: AtomicU64,
}

#[derive(Debug)]
struct Inner {
    db: Database,
    file: PathBuf,
    max_record: usize,
    counters: Counters,
}

/// A durable store in one file: the journals of any number of World Model and Mission
/// Spooler instances of a node. Cheap to clone (shared).
#[derive(Clone)]
pub struct Store {
    inner: Arc<Inner>,
}

impl fmt::Debug for Store {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Store({})", self.inner.file.display())
    }
}

impl Store {
    /// Opens the store at `path`, creating it if there is none (a store left by a
    /// killed process opens at its last complete commit).
    pub fn open(path: impl AsRef<Path>) -> Result<Store, StoreError> {
        Self::open_with_limit(path, MAX_RECORD_BYTES)
    }

    /// [`open`](Self::open) with the largest record written or read.
    pub fn open_with_limit(path: impl AsRef<Path>, max_record: usize) -> Result<Store, StoreError> {
        let file = path.as_ref().to_path_buf();
        let db = Database::create(&file).map_err(|e| StoreError::Open {
            file: file.clone(),
            error: e.to_string(),
        })?;
        let store = Store {
            inner: Arc::new(Inner {
                db,
                file,
                max_record,
                counters: Counters::default(),
            }),
        };
        // Every table exists from now on, so reading never meets a missing one.
        store.write(|tx| {
            tx.open_table(OBJECTS).map_err(db_text)?;
            tx.open_table(METADATA).map_err(db_text)?;
            tx.open_table(MISSIONS).map_err(db_text)?;
            Ok(())
        })?;
        Ok(store)
    }

    /// The file.
    pub fn path(&self) -> &Path {
        &self.inner.file
    }

    /// What the store has done since it was opened.
    pub fn stats(&self) -> StoreStats {
        let c = &self.inner.counters;
        let get = |a: &AtomicU64| a.load(Ordering::Relaxed);
        StoreStats {
            commits: get(&c.commits),
            written: get(&c.written),
            deleted: get(&c.deleted),
            failed: get(&c.failed),
            too_large: get(&c.too_large),
        }
    }

    fn db_error(&self, e: impl fmt::Display) -> StoreError {
        StoreError::Database {
            file: self.inner.file.clone(),
            error: e.to_string(),
        }
    }

    /// Runs `f` in one write transaction and commits it durably.
    fn write(
        &self,
        f: impl FnOnce(&redb::WriteTransaction) -> Result<(), String>,
    ) -> Result<(), StoreError> {
        let tx = self.inner.db.begin_write().map_err(|e| self.db_error(e))?;
        f(&tx).map_err(|e| self.db_error(e))?;
        tx.commit().map_err(|e| self.db_error(e))?;
        self.inner.counters.commits.fetch_add(1, Ordering::Relaxed);
        Ok(())
    }

    fn corrupt(&self, table: &'static str, key: String, error: String) -> StoreError {
        StoreError::Corrupt {
            file: self.inner.file.clone(),
            table,
            key,
            error,
        }
    }

    fn check_size(&self, table: &'static str, key: String, len: usize) -> Result<(), String> {
        if len > self.inner.max_record {
            return Err(format!(
                "table `{table}`, key {key}: record of {len} bytes, more than the limit of {}",
                self.inner.max_record
            ));
        }
        Ok(())
    }

    /// What World Model instance `instance` committed.
    pub fn load_vks(&self, instance: u8) -> Result<VksSnapshot, StoreError> {
        let tx = self.inner.db.begin_read().map_err(|e| self.db_error(e))?;
        let objects_table = tx.open_table(OBJECTS).map_err(|e| self.db_error(e))?;
        let mut snapshot = VksSnapshot::default();
        let range = objects_table
            .range((instance, 0)..=(instance, u32::MAX))
            .map_err(|e| self.db_error(e))?;
        for row in range {
            let (k, v) = row.map_err(|e| self.db_error(e))?;
            let (i, id) = k.value();
            let key = format!("({i}, {id})");
            let bytes = v.value();
            self.check_size("vks_objects", key.clone(), bytes.len())
                .map_err(|e| self.corrupt("vks_objects", key.clone(), e))?;
            let o = record::decode_object(bytes)
                .map_err(|e| self.corrupt("vks_objects", key.clone(), e))?;
            if o.object_id != id {
                return Err(self.corrupt(
                    "vks_objects",
                    key,
                    format!("holds object {}", o.object_id),
                ));
            }
            snapshot.objects.push(o);
        }
        let metadata_table = tx.open_table(METADATA).map_err(|e| self.db_error(e))?;
        let range = metadata_table
            .range((instance, 0)..=(instance, u16::MAX))
            .map_err(|e| self.db_error(e))?;
        for row in range {
            let (k, v) = row.map_err(|e| self.db_error(e))?;
            let (i, class) = k.value();
            let text = record::decode_metadata(v.value())
                .map_err(|e| self.corrupt("vks_metadata", format!("({i}, {class})"), e))?;
            snapshot.metadata.push((class, text));
        }
        Ok(snapshot)
    }

    /// What Mission Spooler instance `instance` committed.
    pub fn load_missions(&self, instance: u8) -> Result<Vec<MissionRecord>, StoreError> {
        let tx = self.inner.db.begin_read().map_err(|e| self.db_error(e))?;
        let table = tx.open_table(MISSIONS).map_err(|e| self.db_error(e))?;
        let range = table
            .range((instance, 0)..=(instance, u16::MAX))
            .map_err(|e| self.db_error(e))?;
        let mut out = Vec::new();
        for row in range {
            let (k, v) = row.map_err(|e| self.db_error(e))?;
            let (i, id) = k.value();
            let key = format!("({i}, {id})");
            let bytes = v.value();
            self.check_size("missions", key.clone(), bytes.len())
                .map_err(|e| self.corrupt("missions", key.clone(), e))?;
            out.push(
                record::decode_mission(id, bytes).map_err(|e| self.corrupt("missions", key, e))?,
            );
        }
        Ok(out)
    }

    /// The journal of World Model instance `instance`.
    pub fn vks_journal(&self, instance: u8) -> StoreVksJournal {
        StoreVksJournal {
            store: self.clone(),
            instance,
        }
    }

    /// The journal of Mission Spooler instance `instance`.
    pub fn mission_journal(&self, instance: u8) -> StoreMissionJournal {
        StoreMissionJournal {
            store: self.clone(),
            instance,
        }
    }

    /// World Model instance `instance` rebuilt from what it committed, committing here
    /// from now on.
    pub fn world_model(
        &self,
        instance: u8,
        config: WorldModelConfig,
    ) -> Result<StockWorldModel, StoreError> {
        let snapshot = self.load_vks(instance)?;
        let (objects, classes) = (snapshot.objects.len(), snapshot.metadata.len());
        let wm = StockWorldModel::restore(config, snapshot, Box::new(self.vks_journal(instance)))
            .map_err(|e| StoreError::Restore {
            file: self.inner.file.clone(),
            what: format!("world model instance {instance}"),
            error: e.to_string(),
        })?;
        tracing::info!(
            store = %self.inner.file.display(),
            "world model instance {instance}: {objects} objects, metadata of {classes} feature classes restored"
        );
        Ok(wm)
    }

    /// Mission Spooler instance `instance` rebuilt from what it committed (missions
    /// that were pending, running or paused now paused), committing here from now on.
    pub fn mission_spooler(
        &self,
        instance: u8,
        config: SpoolerConfig,
    ) -> Result<StockMissionSpooler, StoreError> {
        let missions = self.load_missions(instance)?;
        let n = missions.len();
        let s = StockMissionSpooler::restore(
            config,
            missions,
            Box::new(self.mission_journal(instance)),
        )
        .map_err(|error| StoreError::Restore {
            file: self.inner.file.clone(),
            what: format!("mission spooler instance {instance}"),
            error,
        })?;
        tracing::info!(
            store = %self.inner.file.display(),
            "mission spooler instance {instance}: {n} missions restored"
        );
        Ok(s)
    }

    /// Counts a failed commit and turns it into the journal's error.
    fn failed(&self, e: impl fmt::Display, too_large: bool) -> JournalError {
        let c = &self.inner.counters;
        c.failed.fetch_add(1, Ordering::Relaxed);
        if too_large {
            c.too_large.fetch_add(1, Ordering::Relaxed);
        }
        JournalError(format!("store {}: {e}", self.inner.file.display()))
    }
}

/// [`VksJournal`] of one World Model instance in a [`Store`]: each commit one durable
/// write transaction.
#[derive(Debug, Clone)]
pub struct StoreVksJournal {
    store: Store,
    instance: u8,
}

impl VksJournal for StoreVksJournal {
    fn commit(&mut self, changes: &[VksChange]) -> Result<(), JournalError> {
        let s = &self.store;
        let i = self.instance;
        // Encoded (and checked) before the transaction: a refused record writes nothing.
        let mut rows = Vec::with_capacity(changes.len());
        for c in changes {
            let row = match c {
                VksChange::Created(o) => {
                    let bytes = record::encode_object(o).map_err(|e| s.failed(e, false))?;
                    let key = format!("({i}, {})", o.object_id);
                    s.check_size("vks_objects", key, bytes.len())
                        .map_err(|e| s.failed(e, true))?;
                    (c, Some(bytes))
                }
                VksChange::Metadata { text, .. } if !text.is_empty() => {
                    (c, Some(record::encode_metadata(text)))
                }
                _ => (c, None),
            };
            rows.push(row);
        }
        let (mut written, mut deleted) = (0, 0);
        s.write(|tx| {
            let mut objects = tx.open_table(OBJECTS).map_err(db_text)?;
            let mut metadata = tx.open_table(METADATA).map_err(db_text)?;
            for (c, bytes) in &rows {
                match (c, bytes) {
                    (VksChange::Created(o), Some(b)) => {
                        objects
                            .insert((i, o.object_id), b.as_slice())
                            .map_err(db_text)?;
                        written += 1;
                    }
                    (VksChange::Deleted(id), _) => {
                        objects.remove((i, *id)).map_err(db_text)?;
                        deleted += 1;
                    }
                    (VksChange::Metadata { class, .. }, Some(b)) => {
                        metadata
                            .insert((i, *class), b.as_slice())
                            .map_err(db_text)?;
                        written += 1;
                    }
                    (VksChange::Metadata { class, .. }, None) => {
                        metadata.remove((i, *class)).map_err(db_text)?;
                        deleted += 1;
                    }
                    (VksChange::Created(_), None) => {}
                }
            }
            Ok(())
        })
        .map_err(|e| s.failed(e, false))?;
        let c = &s.inner.counters;
        c.written.fetch_add(written, Ordering::Relaxed);
        c.deleted.fetch_add(deleted, Ordering::Relaxed);
        Ok(())
    }
}

/// [`MissionJournal`] of one Mission Spooler instance in a [`Store`]: each put one
/// durable write transaction.
#[derive(Debug, Clone)]
pub struct StoreMissionJournal {
    store: Store,
    instance: u8,
}

impl MissionJournal for StoreMissionJournal {
    fn put(&mut self, mission: &MissionRecord) -> Result<(), JournalError> {
        let s = &self.store;
        let key = (self.instance, mission.mission_id);
        let bytes = record::encode_mission(mission).map_err(|e| s.failed(e, false))?;
        s.check_size("missions", format!("{key:?}"), bytes.len())
            .map_err(|e| s.failed(e, true))?;
        s.write(|tx| {
            tx.open_table(MISSIONS)
                .map_err(db_text)?
                .insert(key, bytes.as_slice())
                .map_err(db_text)?;
            Ok(())
        })
        .map_err(|e| s.failed(e, false))?;
        s.inner.counters.written.fetch_add(1, Ordering::Relaxed);
        Ok(())
    }
}
