//! The Communicator (Part 1 §5.2.1, id 35): the data links between its subsystem and
//! the other subsystems of the system, and the single point of entry into the subsystem
//! (Figure 5-1).
//!
//! * [`DataLink`] is the hardware: a channel carrying JAUS packets, sans-IO (`jaus-sim`
//!   implements it with a simulated radio).
//! * [`StockCommunicator`] keeps the links: their states (Off, On, Standby, and Loss Of
//!   Command when a link that is On loses the far side), the selected link, the
//!   communications messages, bounded per-link queues and per-link counters.
//! * [`CommunicatorEndpoint`] hosts it in a node as the node's gateway: with
//!   `NodeConfig::communicator` naming it, the node hands it every packet for another
//!   subsystem and routes every packet its links receive, so traffic between subsystems
//!   crosses the links and nothing else.

mod component;
mod gateway;

pub use crate::link::{DataLink, LinkError};
pub use component::{CommunicatorConfig, CommunicatorError, LinkStats, StockCommunicator};
pub use gateway::{CommunicatorComponent, CommunicatorEndpoint};
