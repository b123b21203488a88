//! Validation and code generation for each derive, one module per derive.
//!
//! Messages and records go through a model of their fields ([`model`], built by
//! [`classify`]) and the code of each kind of field ([`field`]); enumerations, bit
//! fields and unions are expanded directly. Every derive that found attribute errors
//! emits them through [`common::fallback`].

mod bits;
mod classify;
mod common;
mod enumeration;
mod field;
mod message;
mod model;
mod shape;
mod types;
mod union;

pub use bits::bits;
pub use enumeration::enumeration;
pub use message::message;
pub use union::union;
