//! The World Model Vector Knowledge Store of Part 1 §5.5.3 (component 61): a
//! [`VectorStore`] of points, lines/polylines and polygons in WGS 84 with region
//! buffers, feature classes and feature-class metadata, indexed with an R*-tree, and
//! [`StockWorldModel`], the generated
//! [`WorldModelVectorKnowledgeStore`](crate::components::world_model_vector_knowledge_store::WorldModelVectorKnowledgeStore)
//! trait implemented over it.
//!
//! | module | holds |
//! |---|---|
//! | [`geometry`] | what shapes, edges and buffers mean; distances in a local equirectangular frame and their error; the antimeridian |
//! | [`region`] | [`Geometry`], the buffered region of a query or deletion, and the [`Filter`] that selects objects |
//! | [`store`] | [`VectorStore`] and its limits ([`StoreConfig`]): the objects, the spatial index, the bounds on memory |
//! | [`error`] | [`StoreError`]: why the store refused something |
//! | [`journal`] | [`VksJournal`]: the persistence seam (every accepted change committed before it is confirmed) and [`VksSnapshot`], what a restart restores |
//! | [`component`] | [`StockWorldModel`]: the component over the store, and how long answers are paged |
//!
//! Every public item is re-exported here (`jaus::stock::world_model::VectorStore`).

pub mod component;
mod coords;
pub mod error;
pub mod geometry;
mod index;
pub mod journal;
pub mod region;
pub mod store;

pub use component::{StockWorldModel, WorldModelConfig, ALL_FEATURE_CLASSES};
pub use error::StoreError;
pub use geometry::{
    point_in_polygon, point_segment_distance, segments_intersect, Shape, MAX_VERTICES,
};
pub use journal::{JournalError, RestoreError, VksChange, VksJournal, VksSnapshot};
pub use region::{Filter, Geometry, MAX_REGION_BUFFER};
pub use store::{Bounds, ObjectId, StoreConfig, VectorStore};
