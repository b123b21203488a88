//! The RA 3.3 side of a gateway, where it was first: it is [`crate::ra33`] now (below
//! the Mobility services as well as the gateway); everything public there is reachable
//! here too.

pub use crate::ra33::*;
