//! # jaus-spec — the JAUS RA 3.3 definition language
//!
//! YAML files describe message groups: shared types (records, enumerations, bit fields,
//! tagged unions), messages with their command codes and fields in wire order, and
//! component interfaces. This crate loads them with `serde_yaml` into a typed model
//! ([`model`]), validates the whole set, and reports every problem with
//! `file:line:column`, the message and field concerned, and what to fix.
//!
//! Validation also resolves the set, once: the [`Spec`] it returns holds every field
//! with its wire form ([`Field::wire`]), every named type in its resolved form
//! ([`TypeForm`]: record fields, enum and bit-field representations, bit-field members,
//! union variants) and every presence vector type. Consumers read those; there is no
//! resolution left to do, and nothing to fall back on.
//!
//! The language is documented, one example per feature, in this crate's README.md.
//! The RA 3.3 definitions themselves live in `defs/` ([`defs_dir`]).
//!
//! ```
//! let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).unwrap();
//! let pose = spec.message("ReportGlobalPose").unwrap();
//! assert_eq!(pose.def.code.0, 0x4402);
//! let latitude = &pose.fields[0];
//! assert_eq!(latitude.def.name, "latitude");
//! assert_eq!(
//!     latitude.wire,
//!     jaus_spec::Wire::Scaled { int: jaus_spec::Int::I32, lo: -90.0, hi: 90.0 }
//! );
//! ```
//!
//! ## Features
//!
//! - `yaml` (default): the definition language itself: the model, loading, validation
//!   and the validated [`Spec`]. Without it the crate is the [`count`] module alone,
//!   with no dependencies: the parser of a list's count expression that the derive
//!   macros share with validation.

pub mod count;
#[cfg(feature = "yaml")]
mod load;
#[cfg(feature = "yaml")]
pub mod location;
#[cfg(feature = "yaml")]
pub mod model;
#[cfg(feature = "yaml")]
mod resolved;
#[cfg(feature = "yaml")]
mod source;
#[cfg(feature = "yaml")]
mod validate;

pub use count::{CountRef, CountRefError};
#[cfg(feature = "yaml")]
pub use load::*;
#[cfg(feature = "yaml")]
pub use model::*;
#[cfg(feature = "yaml")]
pub use resolved::*;
#[cfg(feature = "yaml")]
pub use source::{Source, SpecError, SpecErrors};
