//! Stock components à la carte: any of the SDK's stock components at any instance of a
//! node, those that need hardware over one simulated vehicle (and arm) shared by the
//! node. This is what `jaus node` hosts from its configuration file (`host:`), and what
//! a vendor's own `main` can call in a few lines:
//!
//! ```
//! use std::time::Instant;
//! use jaus::components::{global_pose_sensor, world_model_vector_knowledge_store};
//! use jaus::net::{Node, NodeConfig};
//! use jaus_node::host::{Host, Stock};
//!
//! let t0 = Instant::now();
//! let mut node = Node::new(NodeConfig { subsystem: 5, node: 2, ..NodeConfig::default() }, t0);
//! let mut host = Host::new(5, 2, t0);
//! let gps = Stock::by_id(global_pose_sensor::ID).unwrap();
//! let store = Stock::by_name("world_model").unwrap();
//! for part in [Host::entry(gps), Host::entry(store).instance(2)] {
//!     node.add_boxed(host.build(&part).unwrap()).unwrap();
//! }
//! assert!(node.get::<jaus::component::Component<
//!     global_pose_sensor::Dispatch<
//!         jaus::stock::sensors::StockGlobalPoseSensor<jaus_sim::SimVehicle>>>>(
//!     jaus::Address::new(5, 2, 38, 1)).is_some());
//! assert_eq!(store.id(), world_model_vector_knowledge_store::ID);
//! ```
//!
//! # Where the components come from
//!
//! Which components there are, their names in node files, their ids and the hardware
//! they run over are the definitions' (`stock:` of a component in `jaus-spec/defs`,
//! generated into [`jaus::components::COMPONENTS`]); the one thing written here per
//! component is the line of `registry.rs` that builds its stock core. A new stock
//! component needs its YAML entry, its core and that line.
//!
//! # The simulated world
//!
//! [`Host::new`] hosts over an empty world: the vehicle at the origin of the default
//! frame, no obstacles. [`Host::with_world`] takes the world to simulate
//! ([`World`]: the frame's origin, the obstacles the range sensor, reflexive
//! driver and camera see, the arm's control period); `jaus_sim::demo::world()`
//! is the demo's.
//!
//! # Durable world model and missions
//!
//! [`Host::use_store`] hands the host a [`jaus_store::Store`]: the World Models and
//! Mission Spoolers it builds from then on are rebuilt from what that store holds for
//! their instance (objects with their ids; missions where they stood, paused) and
//! commit every change they accept to it before confirming it (`jaus node`'s
//! `store: PATH`). Without one they keep everything in memory.
//!
//! # The Communicator
//!
//! The Communicator is real hardware rather than simulated: its [`Entry::links`] are
//! UDP data links ([`UdpLink`]) to the far communicators (links of other kinds, such as
//! `jaus-quic`'s authenticated QUIC link, are made by the caller and handed to
//! [`Host::build_communicator`]), and the node that hosts it must name it as its
//! gateway (`NodeConfig::communicator`, see [`Host::communicator_of`]):
//!
//! ```
//! use std::time::Instant;
//! use jaus::net::udp::link::UdpLinkConfig;
//! use jaus::net::{Node, NodeConfig};
//! use jaus_node::host::{Host, Stock};
//!
//! let t0 = Instant::now();
//! let mut comm = Host::entry(Stock::by_name("communicator").unwrap());
//! let any = "127.0.0.1:0".parse().unwrap();
//! comm.links.push(UdpLinkConfig::new(1, any, "127.0.0.1:4002".parse().unwrap()));
//! let config = NodeConfig {
//!     subsystem: 5,
//!     communicator: Host::communicator_of(5, 2, [&comm]),
//!     ..NodeConfig::default()
//! };
//! let mut node = Node::new(NodeConfig { node: 2, ..config }, t0);
//! node.add_boxed(Host::new(5, 2, t0).build(&comm).unwrap()).unwrap();
//! assert_eq!(node.stats().to_communicator, 0);
//! ```

mod build;
mod communicator;
mod registry;

use std::time::Instant;

use nalgebra::Vector2;

use jaus::component::Endpoint;
use jaus::components::{communicator as comm, reflexive_driver};
use jaus::net::udp::link::UdpLinkConfig;
use jaus::stock::communicator::CommunicatorError;
use jaus::Address;
use jaus_sim::arm::{ArmParams, SimArm};
use jaus_sim::scanner::{ScannerParams, SimScanner};
use jaus_sim::vehicle::{SimVehicle, VehicleParams};
use jaus_sim::World;

use build::BuildCx;
pub use registry::Stock;

#[cfg(doc)]
use jaus::net::udp::link::UdpLink;

/// One component to host: which, at which instance, and where its commands and
/// feedback go when it is a driver.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// The component.
    pub stock: Stock,
    /// Its instance id (default 1).
    pub instance: u8,
    /// For a driver above the Primitive Driver: where its wrench efforts go (default:
    /// this node's Reflexive Driver 43.1 if the node hosts one, else its Primitive
    /// Driver 33.1). For the Reflexive Driver: its Primitive Driver (default 33.1). For
    /// a manipulator driver: its Primitive Manipulator (default 49.1; its joint sensors
    /// are this node's 51.1 and 52.1).
    pub output: Option<Address>,
    /// For a vector, waypoint or path driver: its pose sensor (default: this node's
    /// Global Pose Sensor 38.1 for global drivers, Local Pose Sensor 41.1 for local
    /// ones).
    pub pose: Option<Address>,
    /// Its authority (default 0; the demo gives the spooler 100).
    pub authority: u8,
    /// For the Communicator: its data links, each a UDP socket and the far
    /// communicator's link socket (at least one; distinct ids; the first is selected).
    /// Ignored by the other components.
    pub links: Vec<UdpLinkConfig>,
}

impl Entry {
    /// At instance `i`.
    pub fn instance(mut self, i: u8) -> Self {
        self.instance = i;
        self
    }
}

/// Why a component cannot be hosted.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum HostError {
    /// Instance 0 or 255.
    #[error("{component}: instance {instance} is not in 1..=254")]
    Instance {
        /// The component's name.
        component: &'static str,
        /// The instance asked for.
        instance: u8,
    },
    /// Hosted twice at the same address.
    #[error("{component}: {address} is already hosted")]
    Duplicate {
        /// The component's name.
        component: &'static str,
        /// The address.
        address: Address,
    },
    /// The Communicator's links: none, or two with the same id.
    #[error("{component}: {error} (give its data links in `links:`; only a node hosts a communicator, as its gateway)")]
    Links {
        /// The component's name.
        component: &'static str,
        /// What is wrong.
        error: CommunicatorError,
    },
    /// What the durable store holds for the component cannot be loaded (a record
    /// that does not decode, the limits of the component).
    #[error("{component}: {error}")]
    Store {
        /// The component's name.
        component: &'static str,
        /// What is wrong (`jaus_store::StoreError`, as text: it names the file, table
        /// and key).
        error: String,
    },
    /// A data link of the Communicator could not be set up (its socket, its MTU).
    #[error("{component}: {error}")]
    Link {
        /// The component's name.
        component: &'static str,
        /// The link's id.
        link: u8,
        /// What went wrong (`jaus::net::udp::link::UdpLinkError`, as text).
        error: String,
    },
}

/// Builds stock components for node `node` of subsystem `subsystem`; those that need
/// hardware share one simulated vehicle (with its scanner and camera looking at the
/// configured scene), and the manipulator components one simulated 6-axis arm
/// ([`ArmParams::six_axis`]).
#[derive(Debug)]
pub struct Host {
    subsystem: u8,
    node: u8,
    t0: Instant,
    world: World,
    vehicle: SimVehicle,
    scanner: SimScanner,
    arm: SimArm,
    built: Vec<Address>,
    reflexive: bool,
    store: Option<jaus_store::Store>,
}

impl Host {
    /// A host for `subsystem`.`node`, its components starting at `t0`, over an empty
    /// world ([`World::default`]).
    pub fn new(subsystem: u8, node: u8, t0: Instant) -> Self {
        Self::with_world(subsystem, node, t0, World::default())
    }

    /// A host for `subsystem`.`node`, its components starting at `t0`, over `world`.
    pub fn with_world(subsystem: u8, node: u8, t0: Instant, world: World) -> Self {
        let vehicle = SimVehicle::new(VehicleParams {
            origin: world.origin,
            start: (Vector2::zeros(), 0.0),
            ..VehicleParams::default()
        });
        Self {
            subsystem,
            node,
            t0,
            scanner: SimScanner::new(
                vehicle.clone(),
                world.scene.clone(),
                ScannerParams::default(),
            ),
            vehicle,
            arm: SimArm::new(ArmParams::six_axis()),
            world,
            built: Vec::new(),
            reflexive: false,
            store: None,
        }
    }

    /// Makes the World Models and Mission Spoolers built from now on durable in
    /// `store` (module docs).
    pub fn use_store(&mut self, store: jaus_store::Store) {
        self.store = Some(store);
    }

    /// The durable store, if the host was given one.
    pub fn store(&self) -> Option<&jaus_store::Store> {
        self.store.as_ref()
    }

    /// An entry with the defaults (instance 1, default output and pose sensor).
    pub fn entry(stock: Stock) -> Entry {
        Entry {
            stock,
            instance: 1,
            output: None,
            pose: None,
            authority: 0,
            links: Vec::new(),
        }
    }

    /// The Communicator among `entries`, at `subsystem`.`node`, if one is there: what
    /// the hosting node's `NodeConfig::communicator` must be.
    pub fn communicator_of<'a>(
        subsystem: u8,
        node: u8,
        entries: impl IntoIterator<Item = &'a Entry>,
    ) -> Option<Address> {
        entries
            .into_iter()
            .find(|e| e.stock.id() == comm::ID)
            .map(|e| Address::new(subsystem, node, comm::ID, e.instance))
    }

    /// Tells the host the node will also host a Reflexive Driver, so that drivers
    /// entered before it default their output to it.
    pub fn expect_reflexive_driver(&mut self) {
        self.reflexive = true;
    }

    /// The simulated vehicle behind the hardware of every component built.
    pub fn vehicle(&self) -> &SimVehicle {
        &self.vehicle
    }

    /// The range scanner on the simulated vehicle behind the range sensors built (clone
    /// it to read the same sweeps elsewhere, such as the AS-4 Range Sensor).
    pub fn scanner(&self) -> &SimScanner {
        &self.scanner
    }

    /// The simulated arm behind the manipulator components built.
    pub fn arm(&self) -> &SimArm {
        &self.arm
    }

    /// The world the components are built over.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// Where `e` goes on this node, checked: its instance in 1..=254, not hosted yet.
    fn address_of(&self, e: &Entry) -> Result<Address, HostError> {
        let name = e.stock.name();
        if e.instance == 0 || e.instance == 255 {
            return Err(HostError::Instance {
                component: name,
                instance: e.instance,
            });
        }
        let at = Address::new(self.subsystem, self.node, e.stock.id(), e.instance);
        if self.built.contains(&at) {
            return Err(HostError::Duplicate {
                component: name,
                address: at,
            });
        }
        Ok(at)
    }

    /// Builds one component.
    pub fn build(&mut self, e: &Entry) -> Result<Box<dyn Endpoint>, HostError> {
        self.build_used(e).map(|(built, _)| built)
    }

    /// Builds one component, and says which simulated hardware its core was given.
    fn build_used(
        &mut self,
        e: &Entry,
    ) -> Result<(Box<dyn Endpoint>, Vec<jaus::component::Hardware>), HostError> {
        let at = self.address_of(e)?;
        if e.stock.id() == reflexive_driver::ID {
            self.reflexive = true;
        }
        let cx = BuildCx::new(self, e, at);
        // (A communicator whose links failed is not hosted: it may be entered again.)
        let built = e.stock.build(&cx)?;
        let used = cx.used();
        self.built.push(at);
        Ok((built, used))
    }
}

#[cfg(test)]
mod tests;
