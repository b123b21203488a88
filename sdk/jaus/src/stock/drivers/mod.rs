//! The platform drivers of Part 1 §5.3: primitive, reflexive, global/local vector,
//! global/local waypoint and global/local path segment. Each is the generated trait of
//! its component implemented over the hardware traits and [`Motion`](crate::stock::motion::Motion).
//!
//! Common safety rules: only the controlling component commands them (the runtime);
//! NaN, infinite and out-of-range commands are refused ([`Refused::Invalid`], a NAK when
//! one was asked for); the vehicle stops on leaving Ready (Standby, Emergency, ...), when
//! pose feedback goes stale, and when a vector or wrench command is not refreshed.

pub mod elements;
mod navigator;
mod primitive;
mod reflexive;
mod vector;

pub use navigator::*;
pub use primitive::*;
pub use reflexive::*;
pub use vector::*;

use crate::component::Refused;

fn finite(v: f64, what: &str) -> Result<f64, Refused> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Refused::Invalid(format!("{what} is not a finite number")))
    }
}
