//! [`StockWorldModel`]: the World Model Vector Knowledge Store component, the generated
//! trait implemented over a [`VectorStore`], with long answers paged out to their
//! requesters.
//!
//! # Long answers
//!
//! Query VKS Objects is answered by exactly one Report VKS Objects (the interface does
//! not let the component send that report on its own, and no message carries a
//! transfer identifier or a continuation). A report holds at most
//! [`WorldModelConfig::max_report_objects`] objects (at most 65,535: the count is a
//! u16) and about [`WorldModelConfig::max_report_bytes`] bytes of object data, taken in
//! ascending object ID order. When the answer is longer, [`StockWorldModel`] opens a
//! **data transfer** for the requester: sending the *same* query again (same request
//! ID, same filter) returns the next page, until the last page closes the transfer
//! (the next identical query starts over). A different query from the same requester
//! replaces its transfer; Terminate VKS Data Transfer ends the requester's transfer
//! and is answered with Report VKS Data Transfer Termination; a transfer not continued
//! within [`WorldModelConfig::transfer_timeout`] is dropped. A query whose response
//! presence vector leaves bit 0 clear gets only the number of matching objects (capped
//! at 65,535), which tells a requester how many pages to expect. Pages reflect the
//! store when they are built: objects deleted meanwhile are skipped, objects created
//! meanwhile with a higher ID are included.

use std::time::{Duration, Instant};

use super::error::StoreError;
use super::journal::{JournalError, RestoreError, VksChange, VksJournal, VksSnapshot};
use super::region::Filter;
use super::store::{Bounds, ObjectId, StoreConfig, VectorStore};
use crate::codec::Encode;
use crate::component::Refused;
use crate::components::world_model_vector_knowledge_store::{Ctx, WorldModelVectorKnowledgeStore};
use crate::messages::*;
use crate::Address;

/// Feature-class ID that Query VKS Bounds uses for "every object" (an SDK convention:
/// the message has no such value of its own).
pub const ALL_FEATURE_CLASSES: u16 = u16::MAX;

/// Settings of [`StockWorldModel`].
#[derive(Debug, Clone, PartialEq)]
pub struct WorldModelConfig {
    /// Limits of the store.
    pub store: StoreConfig,
    /// Most objects in one Report VKS Objects (at most 65,535).
    pub max_report_objects: usize,
    /// Most bytes of object data in one Report VKS Objects (a single object larger than
    /// this is still sent, alone).
    pub max_report_bytes: usize,
    /// Most data transfers open at once (the least recently used is dropped beyond).
    pub max_transfers: usize,
    /// A data transfer not continued for this long is dropped.
    pub transfer_timeout: Duration,
}

impl Default for WorldModelConfig {
    fn default() -> Self {
        Self {
            store: StoreConfig::default(),
            max_report_objects: 65_535,
            max_report_bytes: 1 << 20,
            max_transfers: 32,
            transfer_timeout: Duration::from_secs(30),
        }
    }
}

/// A long answer being paged out to a requester (module docs, "Long answers").
#[derive(Debug, Clone)]
struct Transfer {
    requester: Address,
    query: QueryVksObjects,
    /// Highest object ID sent so far.
    cursor: ObjectId,
    last: Instant,
}

/// The World Model Vector Knowledge Store: the generated trait over a [`VectorStore`].
///
/// * Create VKS Objects stores each object; Report VKS Objects Creation (when bit 0 of
///   the message properties asks for it) gives each object's ID, 0 for one refused. A
///   message with a refused object is counted as invalid although its valid objects
///   are stored.
/// * Delete VKS Objects deletes what its filter selects; a filter with no criterion is
///   refused.
/// * Query VKS Objects answers with the matching objects (module docs for long
///   answers); Query VKS Bounds with the box of a feature class's objects
///   ([`ALL_FEATURE_CLASSES`] for all), south-west (90, 180) and north-east (-90, -180)
///   when there is none; Query VKS Feature Class Metadata with the text (empty when
///   none).
/// * Terminate VKS Data Transfer ends the sender's transfer and is always answered with
///   Report VKS Data Transfer Termination.
///
/// With a journal ([`StockWorldModel::restore`]), every accepted create, delete and
/// metadata change is committed before it is confirmed ([`super::journal`]).
#[derive(Debug)]
pub struct StockWorldModel {
    store: VectorStore,
    config: WorldModelConfig,
    transfers: Vec<Transfer>,
    journal: Option<Box<dyn VksJournal>>,
    journal_failures: u64,
}

impl Default for StockWorldModel {
    fn default() -> Self {
        Self::new(WorldModelConfig::default())
    }
}

fn invalid(e: StoreError) -> Refused {
    Refused::Invalid(e.to_string())
}

/// Commits the changes `changes` makes to `journal`, if there is one (counting a
/// failure in `failures`).
fn commit(
    journal: &mut Option<Box<dyn VksJournal>>,
    failures: &mut u64,
    changes: impl FnOnce() -> Vec<VksChange>,
) -> Result<(), JournalError> {
    let Some(j) = journal.as_mut() else {
        return Ok(());
    };
    let changes = changes();
    if changes.is_empty() {
        return Ok(());
    }
    j.commit(&changes).inspect_err(|e| {
        *failures += 1;
        tracing::warn!("world model: change not committed, refused: {e}");
    })
}

impl StockWorldModel {
    /// An empty store.
    pub fn new(mut config: WorldModelConfig) -> Self {
        config.max_report_objects = config.max_report_objects.clamp(1, 65_535);
        Self {
            store: VectorStore::new(config.store.clone()),
            config,
            transfers: Vec::new(),
            journal: None,
            journal_failures: 0,
        }
    }

    /// The store rebuilt from `snapshot` (objects keep their IDs; new IDs continue
    /// after the highest), committing every change it accepts from now on to
    /// `journal` before confirming it. Refused (nothing restored) when an object or a
    /// metadata text of the snapshot breaks the limits of `config`.
    pub fn restore(
        mut config: WorldModelConfig,
        snapshot: VksSnapshot,
        journal: Box<dyn VksJournal>,
    ) -> Result<Self, RestoreError> {
        config.max_report_objects = config.max_report_objects.clamp(1, 65_535);
        let mut store = VectorStore::restore(config.store.clone(), snapshot.objects)
            .map_err(|(id, error)| RestoreError::Object { id, error })?;
        for (class, text) in &snapshot.metadata {
            store
                .set_metadata(*class, VksMetadataOption::Overwrite, text)
                .map_err(|error| RestoreError::Metadata {
                    class: *class,
                    error,
                })?;
        }
        Ok(Self {
            store,
            config,
            transfers: Vec::new(),
            journal: Some(journal),
            journal_failures: 0,
        })
    }

    /// Whether changes are committed to a journal.
    pub fn is_durable(&self) -> bool {
        self.journal.is_some()
    }

    /// Changes refused because the journal could not commit them.
    pub fn journal_failures(&self) -> u64 {
        self.journal_failures
    }

    /// The store.
    pub fn store(&self) -> &VectorStore {
        &self.store
    }

    /// The store, to fill or change it locally.
    pub fn store_mut(&mut self) -> &mut VectorStore {
        &mut self.store
    }

    /// Number of data transfers open.
    pub fn open_transfers(&self) -> usize {
        self.transfers.len()
    }

    fn page(
        &mut self,
        requester: Address,
        now: Instant,
        q: &QueryVksObjects,
        ids: &[ObjectId],
    ) -> Vec<VksStoredObject> {
        let pos = self.transfers.iter().position(|t| t.requester == requester);
        let mut cursor = 0;
        if let Some(i) = pos {
            if self.transfers[i].query == *q {
                cursor = self.transfers[i].cursor;
            } else {
                self.transfers.remove(i);
            }
        }
        let start = ids.partition_point(|&id| id <= cursor);
        let mut page = Vec::new();
        let mut bytes = 0usize;
        for id in &ids[start..] {
            let Some(o) = self.store.get(*id) else {
                continue;
            };
            let len = o.encoded_len();
            if page.len() >= self.config.max_report_objects
                || (!page.is_empty() && bytes + len > self.config.max_report_bytes)
            {
                break;
            }
            bytes += len;
            page.push(o.clone());
        }
        let done = start + page.len() >= ids.len();
        let at = self.transfers.iter().position(|t| t.requester == requester);
        match (done, at) {
            (true, Some(i)) => {
                self.transfers.remove(i);
            }
            (true, None) => {}
            (false, _) => {
                let cursor = page.last().map_or(cursor, |o| o.object_id);
                if let Some(i) = at {
                    self.transfers.remove(i);
                }
                if self.transfers.len() >= self.config.max_transfers.max(1) {
                    // The least recently used transfer goes.
                    if let Some(i) =
                        (0..self.transfers.len()).min_by_key(|&i| self.transfers[i].last)
                    {
                        self.transfers.remove(i);
                    }
                }
                self.transfers.push(Transfer {
                    requester,
                    query: q.clone(),
                    cursor,
                    last: now,
                });
            }
        }
        page
    }
}

impl WorldModelVectorKnowledgeStore for StockWorldModel {
    fn on_create_vks_objects(
        &mut self,
        ctx: &mut Ctx<'_>,
        msg: &CreateVksObjects,
    ) -> Result<(), Refused> {
        let mut ids = Vec::with_capacity(msg.objects.len());
        let mut refused = 0usize;
        let mut first_error = None;
        // One batch, so that a large one is indexed by bulk loading.
        let results = if msg.buffered {
            self.store.create_all(&msg.objects)
        } else {
            let unbuffered: Vec<VksObject> = msg
                .objects
                .iter()
                .map(|o| VksObject {
                    buffer: None,
                    ..o.clone()
                })
                .collect();
            self.store.create_all(&unbuffered)
        };
        for (i, r) in results.into_iter().enumerate() {
            match r {
                Ok(id) => ids.push(id),
                Err(e) => {
                    ids.push(0);
                    refused += 1;
                    first_error.get_or_insert((i, e));
                }
            }
        }
        // Committed before the report: what is confirmed survives a restart.
        let store = &self.store;
        let created = || {
            ids.iter()
                .filter_map(|id| store.get(*id))
                .map(|o| VksChange::Created(o.clone()))
                .collect()
        };
        let mut not_committed = None;
        if let Err(e) = commit(&mut self.journal, &mut self.journal_failures, created) {
            let stored: Vec<ObjectId> = ids.iter().copied().filter(|id| *id != 0).collect();
            self.store.delete(&stored);
            ids.iter_mut().for_each(|id| *id = 0);
            not_committed = Some(e);
        }
        if msg.message_properties & 1 != 0 {
            if let Some(src) = ctx.source() {
                ctx.send(
                    src,
                    ReportVksObjectsCreation {
                        request_id: msg.request_id,
                        object_ids: ids,
                    },
                );
            }
        }
        if let Some(e) = not_committed {
            return Err(Refused::Invalid(format!(
                "none of {} objects stored: the journal did not commit them: {e}",
                msg.objects.len()
            )));
        }
        match first_error {
            None => Ok(()),
            Some((i, e)) => Err(Refused::Invalid(format!(
                "{refused} of {} objects refused; object {i}: {e}",
                msg.objects.len()
            ))),
        }
    }

    fn on_set_vks_feature_class_metadata(
        &mut self,
        _ctx: &mut Ctx<'_>,
        msg: &SetVksFeatureClassMetadata,
    ) -> Result<(), Refused> {
        let class = msg.feature_class_id;
        let old = self.store.metadata(class).to_string();
        self.store
            .set_metadata(class, msg.metadata_option, &msg.metadata)
            .map_err(invalid)?;
        let text = self.store.metadata(class).to_string();
        let metadata = || vec![VksChange::Metadata { class, text }];
        if let Err(e) = commit(&mut self.journal, &mut self.journal_failures, metadata) {
            // Puts back what was there (it fitted the limits before).
            let _ = self
                .store
                .set_metadata(class, VksMetadataOption::Overwrite, &old);
            return Err(Refused::Invalid(format!(
                "metadata of feature class {class} not changed: the journal did not commit it: {e}"
            )));
        }
        Ok(())
    }

    fn on_delete_vks_objects(
        &mut self,
        _ctx: &mut Ctx<'_>,
        msg: &DeleteVksObjects,
    ) -> Result<(), Refused> {
        let filter = Filter::from_delete(msg).map_err(invalid)?;
        if self.journal.is_none() {
            self.store.delete_matching(&filter).map_err(invalid)?;
            return Ok(());
        }
        if filter.is_empty() {
            return Err(invalid(StoreError::EmptyFilter));
        }
        // Committed before the objects go: a failed commit deletes nothing.
        let ids = self.store.query(&filter);
        let deleted = || ids.iter().map(|id| VksChange::Deleted(*id)).collect();
        commit(&mut self.journal, &mut self.journal_failures, deleted).map_err(|e| {
            Refused::Invalid(format!(
                "nothing deleted: the journal did not commit the deletion: {e}"
            ))
        })?;
        self.store.delete(&ids);
        Ok(())
    }

    fn on_terminate_vks_data_transfer(
        &mut self,
        ctx: &mut Ctx<'_>,
        _msg: &TerminateVksDataTransfer,
    ) -> Result<(), Refused> {
        if let Some(src) = ctx.source() {
            self.transfers.retain(|t| t.requester != src);
            ctx.send(src, ReportVksDataTransferTermination {});
        }
        Ok(())
    }

    fn on_query_vks_objects(
        &mut self,
        ctx: &mut Ctx<'_>,
        q: &QueryVksObjects,
    ) -> Result<ReportVksObjects, Refused> {
        let filter = Filter::from_query(q).map_err(invalid)?;
        let ids = self.store.query(&filter);
        if q.response_presence_vector & 1 == 0 {
            return Ok(ReportVksObjects {
                request_id: q.request_id,
                object_count: u16::try_from(ids.len()).unwrap_or(u16::MAX),
                objects: None,
            });
        }
        let requester = ctx.source().unwrap_or_default();
        let page = self.page(requester, ctx.now(), q, &ids);
        Ok(ReportVksObjects {
            request_id: q.request_id,
            // The page never exceeds `max_report_objects` <= 65,535.
            object_count: u16::try_from(page.len()).unwrap_or(u16::MAX),
            objects: Some(page),
        })
    }

    fn on_query_vks_feature_class_metadata(
        &mut self,
        _ctx: &mut Ctx<'_>,
        msg: &QueryVksFeatureClassMetadata,
    ) -> Result<ReportVksFeatureClassMetadata, Refused> {
        Ok(ReportVksFeatureClassMetadata {
            feature_class_id: msg.feature_class_id,
            metadata: self.store.metadata(msg.feature_class_id).to_string(),
        })
    }

    fn on_query_vks_bounds(
        &mut self,
        _ctx: &mut Ctx<'_>,
        msg: &QueryVksBounds,
    ) -> Result<ReportVksBounds, Refused> {
        let class = (msg.feature_class_id != ALL_FEATURE_CLASSES).then_some(msg.feature_class_id);
        let b = self.store.bounds(class).unwrap_or(Bounds {
            south: 90.0,
            west: 180.0,
            north: -90.0,
            east: -180.0,
        });
        Ok(ReportVksBounds {
            request_id: msg.request_id,
            feature_class: msg.feature_class_id,
            south_west_latitude: b.south,
            south_west_longitude: b.west,
            north_east_latitude: b.north,
            north_east_longitude: b.east,
        })
    }

    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        let now = ctx.now();
        let timeout = self.config.transfer_timeout;
        self.transfers
            .retain(|t| now.saturating_duration_since(t.last) < timeout);
    }
}
