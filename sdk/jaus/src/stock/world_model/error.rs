//! [`StoreError`]: why the store refused an object, a region, a filter or a metadata
//! change, naming the limit of [`StoreConfig`](super::StoreConfig) that was reached.

use super::coords::Shape;

/// Why the store refused an object, a region, a filter or a metadata change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StoreError {
    /// The store holds [`StoreConfig::max_objects`](super::StoreConfig::max_objects) objects.
    #[error("the store is full: it holds the maximum of {max} objects (max_objects)")]
    TooManyObjects {
        /// The limit.
        max: usize,
    },
    /// More vertices than [`StoreConfig::max_vertices`](super::StoreConfig::max_vertices).
    #[error("{count} vertices exceed the maximum of {max} per object (max_vertices)")]
    TooManyVertices {
        /// Vertices given.
        count: usize,
        /// The limit.
        max: usize,
    },
    /// The store would hold more than
    /// [`StoreConfig::max_total_vertices`](super::StoreConfig::max_total_vertices) vertices.
    #[error("{count} more vertices would exceed the store's maximum of {max} vertices (max_total_vertices)")]
    TotalVertices {
        /// Vertices of the object.
        count: usize,
        /// The limit.
        max: usize,
    },
    /// More feature classes than
    /// [`StoreConfig::max_feature_classes`](super::StoreConfig::max_feature_classes).
    #[error(
        "{count} feature classes exceed the maximum of {max} per object (max_feature_classes)"
    )]
    TooManyFeatureClasses {
        /// Feature classes given.
        count: usize,
        /// The limit.
        max: usize,
    },
    /// An object type other than point, line or polygon.
    #[error("unknown object type {0} (0 point, 1 line, 2 polygon)")]
    UnknownType(u8),
    /// Too few (or, for a point, too many) vertices for the shape.
    #[error("a {shape:?} needs {need} vertices, {count} given")]
    VertexCount {
        /// The shape.
        shape: Shape,
        /// Vertices given.
        count: usize,
        /// What the shape needs ("exactly 1", "at least 2", "at least 3").
        need: &'static str,
    },
    /// A latitude or longitude that is NaN or infinite.
    #[error("vertex {index}: {what} is not a finite number")]
    NotFinite {
        /// Index of the vertex.
        index: usize,
        /// "latitude" or "longitude".
        what: &'static str,
    },
    /// A latitude outside [-90, 90].
    #[error("vertex {index}: latitude {value} is outside [-90, 90] degrees")]
    Latitude {
        /// Index of the vertex.
        index: usize,
        /// The latitude.
        value: f64,
    },
    /// A longitude outside [-180, 180].
    #[error("vertex {index}: longitude {value} is outside [-180, 180] degrees")]
    Longitude {
        /// Index of the vertex.
        index: usize,
        /// The longitude.
        value: f64,
    },
    /// A buffer that is NaN, negative or above the limit.
    #[error("region buffer {value} m is not a number in [0, {max}] m (max_buffer)")]
    Buffer {
        /// The buffer.
        value: f64,
        /// The limit.
        max: f64,
    },
    /// Edges that go all the way round the Earth (or a polygon around a pole).
    #[error("the object goes all the way round the Earth in longitude (a polygon around a pole, or a line spanning 360 degrees or more); split it")]
    WrapsAround,
    /// A delete filter with no criterion (it would delete everything).
    #[error("the delete filter has no criterion (object IDs, region or feature classes); it would delete every object")]
    EmptyFilter,
    /// A region given only in part.
    #[error("incomplete region: {0}")]
    Region(&'static str),
    /// Feature-class criteria with neither IDs nor attributes.
    #[error("feature-class criteria carry neither class IDs nor attributes")]
    EmptyCriteria,
    /// A metadata option other than append, prepend, overwrite and erase.
    #[error("unknown metadata option {0} (0 append, 1 prepend, 2 overwrite, 255 erase)")]
    MetadataOption(u8),
    /// Metadata of one class longer than 65,535 bytes.
    #[error("metadata of feature class {class} would be {len} bytes, more than 65535")]
    MetadataTooLong {
        /// The feature class.
        class: u16,
        /// The resulting length.
        len: usize,
    },
    /// Metadata of all classes above
    /// [`StoreConfig::max_metadata_bytes`](super::StoreConfig::max_metadata_bytes).
    #[error(
        "metadata would total {total} bytes, more than the maximum of {max} (max_metadata_bytes)"
    )]
    MetadataFull {
        /// The resulting total.
        total: usize,
        /// The limit.
        max: usize,
    },
    /// An object of a snapshot being restored that no store could hold as given.
    #[error("cannot restore the object: {0}")]
    Restore(&'static str),
}
