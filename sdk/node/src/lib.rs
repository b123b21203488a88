//! # jaus-node — a JAUS node from its node file
//!
//! `jaus node --config FILE` in a library: the YAML node file ([`NodeFile`]: its
//! address, transport, peers, the components it hosts, its AS-4 side, ROS 2 robots,
//! data links, policy and durable store), what it builds, and the node's run loop.
//!
//! * [`host`]: the stock-component registry: any of the SDK's stock components at any
//!   instance of a node, those that need hardware over the simulators of `jaus-sim`
//!   (one vehicle, its scanner and camera, one arm), in one simulated
//!   [`jaus_sim::World`];
//! * [`NodeFile`] and [`node`]: the node file and running it;
//! * [`LinkFile`] and [`PolicyFile`]: a Communicator's data links and the node's
//!   policy, as the node file writes them;
//! * [`attach_openjaus`]: stock components as component processes of an OpenJAUS node
//!   manager.
//!
//! The simulators provide hardware only; which component runs over which hardware is
//! decided here.

mod attach;
mod file;
pub mod host;
mod links_file;
mod policy_file;
mod sim_lights;
pub mod video;

pub use attach::{attach_openjaus, OjNodeManager};
pub use file::run::node;
pub use file::{
    As4File, As4Native, As4VehicleFile, FrameFile, HostItem, Hosted, IoFile, MulticastFile,
    NodeFile, OjComponentsFile, ReliableFile, TransportFile,
};
pub use links_file::{LinkFile, QuicLinkFile};
pub use policy_file::{PolicyFile, RuleFile};
pub use sim_lights::SimLights;
