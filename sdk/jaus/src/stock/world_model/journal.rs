//! The World Model's persistence seam: [`VksJournal`], through which
//! [`StockWorldModel`](super::StockWorldModel) commits every change it accepts before
//! confirming it, and [`VksSnapshot`], what it is rebuilt from after a restart
//! ([`StockWorldModel::restore`](super::StockWorldModel::restore)).
//!
//! Without a journal the store is in memory only (the default). With one:
//!
//! * Create VKS Objects: the objects admitted are committed (with the IDs they got)
//!   before Report VKS Objects Creation is sent; if the commit fails they are taken
//!   out again, the report gives 0 for every object and the message is refused.
//! * Delete VKS Objects: the IDs selected are committed as deleted before they are
//!   deleted; if the commit fails nothing is deleted and the message is refused.
//! * Set VKS Feature Class Metadata: the class's new text is committed; if the commit
//!   fails the old text is put back and the message is refused.
//!
//! Changes made through [`StockWorldModel::store_mut`](super::StockWorldModel::store_mut)
//! are not journalled.

use std::fmt;

use super::error::StoreError;
use super::store::ObjectId;
use crate::messages::VksStoredObject;
pub use crate::stock::journal::JournalError;

/// One change the World Model accepted, as committed.
#[derive(Debug, Clone, PartialEq)]
pub enum VksChange {
    /// An object was stored under its ID (its buffer is 0 when none was given).
    Created(VksStoredObject),
    /// The object with this ID was deleted.
    Deleted(ObjectId),
    /// The metadata text of a feature class is now `text` (empty: erased).
    Metadata {
        /// The feature class.
        class: u16,
        /// Its whole text after the change.
        text: String,
    },
}

/// Where the World Model commits what it accepts. `commit` returns once the changes
/// are durable (all of them or none): only then is the change confirmed.
pub trait VksJournal: Send + fmt::Debug {
    /// Commits `changes`, in order, as one atomic unit.
    fn commit(&mut self, changes: &[VksChange]) -> Result<(), JournalError>;
}

/// What a World Model is rebuilt from: every object with its ID, and the metadata
/// text of every feature class that has some.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct VksSnapshot {
    /// The objects (any order).
    pub objects: Vec<VksStoredObject>,
    /// Feature class and its metadata text.
    pub metadata: Vec<(u16, String)>,
}

/// Why a [`VksSnapshot`] cannot be restored under the store's limits.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RestoreError {
    /// An object the store refuses (its limits, its geometry, its ID).
    #[error("object {id}: {error}")]
    Object {
        /// The object's ID.
        id: ObjectId,
        /// Why.
        error: StoreError,
    },
    /// Metadata the store refuses (its limits).
    #[error("metadata of feature class {class}: {error}")]
    Metadata {
        /// The feature class.
        class: u16,
        /// Why.
        error: StoreError,
    },
}
