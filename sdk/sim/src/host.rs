//! Stock components à la carte: any of the SDK's stock components at any instance of a
//! node, those that need hardware over one simulated vehicle shared by the node. This
//! is what `jaus node` hosts from its configuration file (`host:`), and what a vendor's
//! own `main` can call in a few lines:
//!
//! ```
//! use std::time::Instant;
//! use jaus::net::{Node, NodeConfig};
//! use jaus_sim::host::{Host, Stock};
//!
//! let t0 = Instant::now();
//! let mut node = Node::new(NodeConfig { subsystem: 5, node: 2, ..NodeConfig::default() }, t0);
//! let mut host = Host::new(5, 2, t0);
//! for part in [Host::entry(Stock::GlobalPoseSensor), Host::entry(Stock::WorldModel).instance(2)] {
//!     node.add_boxed(host.build(&part).unwrap()).unwrap();
//! }
//! assert!(node.get::<jaus::component::Component<
//!     jaus::components::global_pose_sensor::Dispatch<
//!         jaus::stock::sensors::StockGlobalPoseSensor<jaus_sim::SimVehicle>>>>(
//!     jaus::Address::new(5, 2, 38, 1)).is_some());
//! ```
//!
//! The Communicator ([`Stock::Communicator`]) is real hardware rather than simulated:
//! its [`Entry::links`] are UDP data links ([`UdpLink`]) to the far communicators
//! (links of other kinds, such as `jaus-quic`'s authenticated QUIC link, are made by the
//! caller and handed to [`Host::build_communicator`]), and the node that hosts it must
//! name it as its gateway (`NodeConfig::communicator`, see [`Host::communicator_of`]):
//!
//! ```
//! use std::time::Instant;
//! use jaus::net::udp::link::UdpLinkConfig;
//! use jaus::net::{Node, NodeConfig};
//! use jaus_sim::host::{Host, Stock};
//!
//! let t0 = Instant::now();
//! let mut comm = Host::entry(Stock::Communicator);
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

use std::time::Instant;

use nalgebra::Vector2;

use crate::arm::{ArmParams, SimArm};
use crate::arm_demo::CONTROL_PERIOD;
use crate::demo::{OBSTACLE, ORIGIN};
use crate::scanner::{ScannerParams, Scene, SimScanner};
use crate::vehicle::{SimVehicle, VehicleParams};
use jaus::component::{Config, Endpoint};
use jaus::components::{
    global_path_segment_driver, global_pose_sensor, global_vector_driver, global_waypoint_driver,
    local_path_segment_driver, local_pose_sensor, local_vector_driver, local_waypoint_driver,
    mission_spooler, primitive_driver, reflexive_driver, velocity_state_sensor,
    world_model_vector_knowledge_store,
};
use jaus::components::{
    manipulator_end_effector_discrete_pose_driver, manipulator_end_effector_pose_driver,
    manipulator_end_effector_velocity_state_driver, manipulator_joint_force_torque_sensor,
    manipulator_joint_move_driver, manipulator_joint_position_sensor,
    manipulator_joint_positions_driver, manipulator_joint_velocities_driver,
    manipulator_joint_velocity_sensor, primitive_manipulator,
};
use jaus::components::{range_sensor, visual_sensor};
use jaus::net::udp::link::{UdpLink, UdpLinkConfig};
use jaus::stock::communicator::{
    CommunicatorConfig, CommunicatorEndpoint, CommunicatorError, DataLink, StockCommunicator,
};
use jaus::stock::drivers::{
    Navigator, PrimitiveConfig, ReflexiveConfig, StockPrimitiveDriver, StockReflexiveDriver,
    StockVectorDriver,
};
use jaus::stock::environment::camera::{StockVisualSensor, VisualConfig};
use jaus::stock::environment::range::{RangeConfig, ScanObstacles, StockRangeSensor};
use jaus::stock::geo::LocalFrame;
use jaus::stock::manipulator::link::ArmDriverConfig;
use jaus::stock::manipulator::{
    PrimitiveManipulatorConfig, StockEndEffectorDiscretePoseDriver, StockEndEffectorPoseDriver,
    StockEndEffectorVelocityStateDriver, StockJointMoveDriver, StockJointPositionsDriver,
    StockJointSensor, StockJointVelocitiesDriver, StockPrimitiveManipulator,
};
use jaus::stock::motion::DriverConfig;
use jaus::stock::sensors::{StockGlobalPoseSensor, StockLocalPoseSensor, StockVelocityStateSensor};
use jaus::stock::spooler::{SpoolerConfig, StockMissionSpooler};
use jaus::stock::world_model::{StockWorldModel, WorldModelConfig};
use jaus::Address;

/// A stock component of the SDK.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stock {
    /// Primitive Driver (33) over the simulated vehicle's actuators.
    PrimitiveDriver,
    /// Reflexive Driver (43), in front of a Primitive Driver.
    ReflexiveDriver,
    /// Global Pose Sensor (38) of the simulated vehicle.
    GlobalPoseSensor,
    /// Local Pose Sensor (41) of the simulated vehicle.
    LocalPoseSensor,
    /// Velocity State Sensor (42) of the simulated vehicle.
    VelocityStateSensor,
    /// Global Vector Driver (34).
    GlobalVectorDriver,
    /// Local Vector Driver (44).
    LocalVectorDriver,
    /// Global Waypoint Driver (45).
    GlobalWaypointDriver,
    /// Local Waypoint Driver (46).
    LocalWaypointDriver,
    /// Global Path Segment Driver (47).
    GlobalPathSegmentDriver,
    /// Local Path Segment Driver (48).
    LocalPathSegmentDriver,
    /// Mission Spooler (36).
    MissionSpooler,
    /// World Model Vector Knowledge Store (61).
    WorldModel,
    /// Range Sensor (50): a scanner on the simulated vehicle, looking at the demo's
    /// obstacle (the Reflexive Driver's obstacle source uses the same scanner).
    RangeSensor,
    /// Visual Sensor (37): a pan/tilt camera on the simulated vehicle drawing the demo's
    /// obstacle from above.
    VisualSensor,
    /// Primitive Manipulator (49) over the simulated arm.
    PrimitiveManipulator,
    /// Manipulator Joint Position Sensor (51) of the simulated arm.
    JointPositionSensor,
    /// Manipulator Joint Velocity Sensor (52) of the simulated arm.
    JointVelocitySensor,
    /// Manipulator Joint Force/Torque Sensor (53) of the simulated arm.
    JointForceTorqueSensor,
    /// Manipulator Joint Positions Driver (54).
    JointPositionsDriver,
    /// Manipulator End-Effector Pose Driver (55).
    EndEffectorPoseDriver,
    /// Manipulator Joint Velocities Driver (56).
    JointVelocitiesDriver,
    /// Manipulator End-Effector Velocity State Driver (57).
    EndEffectorVelocityStateDriver,
    /// Manipulator Joint Move Driver (58).
    JointMoveDriver,
    /// Manipulator End-Effector Discrete Pose Driver (59).
    EndEffectorDiscretePoseDriver,
    /// Communicator (35): the subsystem's gateway to other subsystems over the UDP data
    /// links of its [`Entry::links`] (at least one). The node hosting it must have it
    /// as `NodeConfig::communicator` ([`Host::communicator_of`]).
    Communicator,
}

impl Stock {
    /// Every stock component, with the name used in configuration files.
    pub const ALL: &'static [(&'static str, Stock)] = &[
        ("primitive_driver", Stock::PrimitiveDriver),
        ("reflexive_driver", Stock::ReflexiveDriver),
        ("global_pose_sensor", Stock::GlobalPoseSensor),
        ("local_pose_sensor", Stock::LocalPoseSensor),
        ("velocity_state_sensor", Stock::VelocityStateSensor),
        ("global_vector_driver", Stock::GlobalVectorDriver),
        ("local_vector_driver", Stock::LocalVectorDriver),
        ("global_waypoint_driver", Stock::GlobalWaypointDriver),
        ("local_waypoint_driver", Stock::LocalWaypointDriver),
        ("global_path_segment_driver", Stock::GlobalPathSegmentDriver),
        ("local_path_segment_driver", Stock::LocalPathSegmentDriver),
        ("mission_spooler", Stock::MissionSpooler),
        ("world_model", Stock::WorldModel),
        ("range_sensor", Stock::RangeSensor),
        ("visual_sensor", Stock::VisualSensor),
        ("primitive_manipulator", Stock::PrimitiveManipulator),
        ("joint_position_sensor", Stock::JointPositionSensor),
        ("joint_velocity_sensor", Stock::JointVelocitySensor),
        ("joint_force_torque_sensor", Stock::JointForceTorqueSensor),
        ("joint_positions_driver", Stock::JointPositionsDriver),
        ("end_effector_pose_driver", Stock::EndEffectorPoseDriver),
        ("joint_velocities_driver", Stock::JointVelocitiesDriver),
        (
            "end_effector_velocity_state_driver",
            Stock::EndEffectorVelocityStateDriver,
        ),
        ("joint_move_driver", Stock::JointMoveDriver),
        (
            "end_effector_discrete_pose_driver",
            Stock::EndEffectorDiscretePoseDriver,
        ),
        ("communicator", Stock::Communicator),
    ];

    /// The component by its configuration name.
    pub fn by_name(name: &str) -> Option<Stock> {
        Self::ALL.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
    }

    /// The configuration name.
    pub fn name(self) -> &'static str {
        Self::ALL
            .iter()
            .find(|(_, s)| *s == self)
            .map_or("?", |(n, _)| n)
    }

    /// The Part 1 component id.
    pub fn id(self) -> u8 {
        match self {
            Stock::PrimitiveDriver => 33,
            Stock::ReflexiveDriver => 43,
            Stock::GlobalPoseSensor => 38,
            Stock::LocalPoseSensor => 41,
            Stock::VelocityStateSensor => 42,
            Stock::GlobalVectorDriver => 34,
            Stock::LocalVectorDriver => 44,
            Stock::GlobalWaypointDriver => 45,
            Stock::LocalWaypointDriver => 46,
            Stock::GlobalPathSegmentDriver => 47,
            Stock::LocalPathSegmentDriver => 48,
            Stock::MissionSpooler => 36,
            Stock::WorldModel => 61,
            Stock::RangeSensor => 50,
            Stock::VisualSensor => 37,
            Stock::PrimitiveManipulator => 49,
            Stock::JointPositionSensor => 51,
            Stock::JointVelocitySensor => 52,
            Stock::JointForceTorqueSensor => 53,
            Stock::JointPositionsDriver => 54,
            Stock::EndEffectorPoseDriver => 55,
            Stock::JointVelocitiesDriver => 56,
            Stock::EndEffectorVelocityStateDriver => 57,
            Stock::JointMoveDriver => 58,
            Stock::EndEffectorDiscretePoseDriver => 59,
            Stock::Communicator => 35,
        }
    }
}

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
/// hardware share one simulated vehicle, and the manipulator components one simulated
/// 6-axis arm ([`ArmParams::six_axis`]).
#[derive(Debug)]
pub struct Host {
    subsystem: u8,
    node: u8,
    t0: Instant,
    vehicle: SimVehicle,
    scanner: SimScanner,
    arm: SimArm,
    built: Vec<Address>,
    reflexive: bool,
}

impl Host {
    /// A host for `subsystem`.`node`, its components starting at `t0`.
    pub fn new(subsystem: u8, node: u8, t0: Instant) -> Self {
        let vehicle = SimVehicle::new(VehicleParams {
            origin: LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2),
            start: (Vector2::zeros(), 0.0),
            ..VehicleParams::default()
        });
        Self {
            subsystem,
            node,
            t0,
            scanner: SimScanner::new(
                vehicle.clone(),
                Scene {
                    circles: vec![(Vector2::new(OBSTACLE.0 .0, OBSTACLE.0 .1), OBSTACLE.1)],
                },
                ScannerParams::default(),
            ),
            vehicle,
            arm: SimArm::new(ArmParams::six_axis()),
            built: Vec::new(),
            reflexive: false,
        }
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
            .find(|e| e.stock == Stock::Communicator)
            .map(|e| Address::new(subsystem, node, Stock::Communicator.id(), e.instance))
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

    /// The simulated arm behind the manipulator components built.
    pub fn arm(&self) -> &SimArm {
        &self.arm
    }

    fn local(&self, component: u8) -> Address {
        Address::new(self.subsystem, self.node, component, 1)
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
        let at = self.address_of(e)?;
        if e.stock == Stock::ReflexiveDriver {
            self.reflexive = true;
        }
        let cfg = Config {
            authority: e.authority,
            ..Config::default()
        };
        let t0 = self.t0;
        let v = self.vehicle.clone();
        let output = e.output.unwrap_or_else(|| {
            if self.reflexive && e.stock != Stock::ReflexiveDriver {
                self.local(43)
            } else {
                self.local(33)
            }
        });
        let drive = |pose: u8| DriverConfig {
            output,
            pose_sensor: e.pose.unwrap_or_else(|| self.local(pose)),
            velocity_sensor: Some(self.local(42)),
            origin: Some(LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2)),
            ..DriverConfig::default()
        };
        // The manipulator components run at the arm's control period.
        let arm_cfg = || Config {
            tick: CONTROL_PERIOD,
            ..cfg.clone()
        };
        let arm_driver = ArmDriverConfig {
            output: e.output.unwrap_or_else(|| self.local(49)),
            position_sensor: self.local(51),
            velocity_sensor: Some(self.local(52)),
            ..ArmDriverConfig::default()
        };
        let a = self.arm.clone();
        let built: Box<dyn Endpoint> = match e.stock {
            Stock::Communicator => self.communicator(at, e)?,
            Stock::RangeSensor => Box::new(range_sensor::component(
                at,
                StockRangeSensor::new(self.scanner.clone(), RangeConfig::default()),
                cfg,
                t0,
            )),
            Stock::VisualSensor => Box::new(visual_sensor::component(
                at,
                StockVisualSensor::new(
                    crate::camera::SimCamera::new(self.vehicle.clone(), self.scanner.scene()),
                    VisualConfig::default(),
                ),
                cfg,
                t0,
            )),
            Stock::PrimitiveManipulator => {
                let chain = a.lock().chain().clone();
                Box::new(primitive_manipulator::component(
                    at,
                    StockPrimitiveManipulator::new(a, chain, PrimitiveManipulatorConfig::default()),
                    arm_cfg(),
                    t0,
                ))
            }
            Stock::JointPositionSensor => Box::new(manipulator_joint_position_sensor::component(
                at,
                StockJointSensor::new(a),
                arm_cfg(),
                t0,
            )),
            Stock::JointVelocitySensor => Box::new(manipulator_joint_velocity_sensor::component(
                at,
                StockJointSensor::new(a),
                arm_cfg(),
                t0,
            )),
            Stock::JointForceTorqueSensor => {
                Box::new(manipulator_joint_force_torque_sensor::component(
                    at,
                    StockJointSensor::new(a),
                    arm_cfg(),
                    t0,
                ))
            }
            Stock::JointPositionsDriver => Box::new(manipulator_joint_positions_driver::component(
                at,
                StockJointPositionsDriver::new(arm_driver),
                arm_cfg(),
                t0,
            )),
            Stock::EndEffectorPoseDriver => {
                Box::new(manipulator_end_effector_pose_driver::component(
                    at,
                    StockEndEffectorPoseDriver::new(arm_driver),
                    arm_cfg(),
                    t0,
                ))
            }
            Stock::JointVelocitiesDriver => {
                Box::new(manipulator_joint_velocities_driver::component(
                    at,
                    StockJointVelocitiesDriver::new(arm_driver),
                    arm_cfg(),
                    t0,
                ))
            }
            Stock::EndEffectorVelocityStateDriver => {
                Box::new(manipulator_end_effector_velocity_state_driver::component(
                    at,
                    StockEndEffectorVelocityStateDriver::new(arm_driver),
                    arm_cfg(),
                    t0,
                ))
            }
            Stock::JointMoveDriver => Box::new(manipulator_joint_move_driver::component(
                at,
                StockJointMoveDriver::new(arm_driver),
                arm_cfg(),
                t0,
            )),
            Stock::EndEffectorDiscretePoseDriver => {
                Box::new(manipulator_end_effector_discrete_pose_driver::component(
                    at,
                    StockEndEffectorDiscretePoseDriver::new(arm_driver),
                    arm_cfg(),
                    t0,
                ))
            }
            Stock::PrimitiveDriver => Box::new(primitive_driver::component(
                at,
                StockPrimitiveDriver::new(v, PrimitiveConfig::default()),
                cfg,
                t0,
            )),
            Stock::ReflexiveDriver => Box::new(reflexive_driver::component(
                at,
                StockReflexiveDriver::new(
                    ScanObstacles::new(self.scanner.clone(), 1.0),
                    ReflexiveConfig {
                        output,
                        ..ReflexiveConfig::default()
                    },
                ),
                cfg,
                t0,
            )),
            Stock::GlobalPoseSensor => Box::new(global_pose_sensor::component(
                at,
                StockGlobalPoseSensor(v),
                cfg,
                t0,
            )),
            Stock::LocalPoseSensor => Box::new(local_pose_sensor::component(
                at,
                StockLocalPoseSensor(v),
                cfg,
                t0,
            )),
            Stock::VelocityStateSensor => Box::new(velocity_state_sensor::component(
                at,
                StockVelocityStateSensor(v),
                cfg,
                t0,
            )),
            Stock::GlobalVectorDriver => Box::new(global_vector_driver::component(
                at,
                StockVectorDriver::new(drive(38)),
                cfg,
                t0,
            )),
            Stock::LocalVectorDriver => Box::new(local_vector_driver::component(
                at,
                StockVectorDriver::new(drive(41)),
                cfg,
                t0,
            )),
            Stock::GlobalWaypointDriver => Box::new(global_waypoint_driver::component(
                at,
                Navigator::new(drive(38)),
                cfg,
                t0,
            )),
            Stock::LocalWaypointDriver => Box::new(local_waypoint_driver::component(
                at,
                Navigator::new(drive(41)),
                cfg,
                t0,
            )),
            Stock::GlobalPathSegmentDriver => Box::new(global_path_segment_driver::component(
                at,
                Navigator::new(drive(38)),
                cfg,
                t0,
            )),
            Stock::LocalPathSegmentDriver => Box::new(local_path_segment_driver::component(
                at,
                Navigator::new(drive(41)),
                cfg,
                t0,
            )),
            Stock::MissionSpooler => Box::new(mission_spooler::component(
                at,
                StockMissionSpooler::new(SpoolerConfig::default()),
                cfg,
                t0,
            )),
            Stock::WorldModel => Box::new(world_model_vector_knowledge_store::component(
                at,
                StockWorldModel::new(WorldModelConfig::default()),
                cfg,
                t0,
            )),
        };
        // (A communicator whose links failed is not hosted: it may be entered again.)
        self.built.push(at);
        Ok(built)
    }
}

impl Host {
    /// A Communicator with the instance and authority of `e` (a [`Stock::Communicator`]
    /// entry) over `links` that the caller made (any [`DataLink`]: a link of its own
    /// hardware, a QUIC link, `Box<dyn DataLink>` for a mix), all On, the first
    /// selected; `e.links` is not used. The UDP links of `e.links` are what
    /// [`Host::build`] makes itself.
    pub fn build_communicator<L: DataLink>(
        &mut self,
        e: &Entry,
        links: Vec<L>,
    ) -> Result<Box<dyn Endpoint>, HostError> {
        let e = Entry {
            stock: Stock::Communicator,
            ..e.clone()
        };
        let at = self.address_of(&e)?;
        let built = self.communicator_over(at, &e, links)?;
        self.built.push(at);
        Ok(built)
    }

    /// The Communicator of `e` at `at` over `links`, all On, the first selected.
    fn communicator_over<L: DataLink>(
        &self,
        at: Address,
        e: &Entry,
        links: Vec<L>,
    ) -> Result<Box<dyn Endpoint>, HostError> {
        let component = Stock::Communicator.name();
        let stock = StockCommunicator::new(links, CommunicatorConfig::default(), self.t0)
            .map_err(|error| HostError::Links { component, error })?;
        let cfg = Config {
            authority: e.authority,
            ..Config::default()
        };
        Ok(Box::new(CommunicatorEndpoint::new(at, stock, cfg, self.t0)))
    }

    /// The Communicator of `e` at `at`: its links bound, all On, the first selected.
    fn communicator(&self, at: Address, e: &Entry) -> Result<Box<dyn Endpoint>, HostError> {
        let component = Stock::Communicator.name();
        // Checked before any socket is bound (StockCommunicator::new checks again).
        let ids: Vec<u8> = e.links.iter().map(|l| l.id).collect();
        let error = if ids.is_empty() {
            Some(CommunicatorError::NoLinks)
        } else {
            (1..ids.len())
                .find(|&i| ids[..i].contains(&ids[i]))
                .map(|i| CommunicatorError::DuplicateId(ids[i]))
        };
        if let Some(error) = error {
            return Err(HostError::Links { component, error });
        }
        let links = e
            .links
            .iter()
            .map(|l| {
                UdpLink::bind(l.clone()).map_err(|err| HostError::Link {
                    component,
                    link: l.id,
                    error: err.to_string(),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        self.communicator_over(at, e, links)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_stock_component_is_hosted_at_its_id_and_instance() {
        let t0 = Instant::now();
        let mut host = Host::new(7, 3, t0);
        let any: std::net::SocketAddr = "127.0.0.1:0".parse().unwrap();
        for (name, s) in Stock::ALL {
            assert_eq!(Stock::by_name(name), Some(*s));
            let mut entry = Host::entry(*s).instance(4);
            if *s == Stock::Communicator {
                entry.links.push(UdpLinkConfig::new(1, any, any));
            }
            let e = host.build(&entry).unwrap();
            assert_eq!(e.address(), Address::new(7, 3, s.id(), 4), "{name}");
        }
        let again = host.build(&Host::entry(Stock::WorldModel).instance(4));
        assert!(matches!(again, Err(HostError::Duplicate { .. })));
        let zero = host.build(&Host::entry(Stock::WorldModel).instance(0));
        assert!(matches!(zero, Err(HostError::Instance { .. })));
    }

    #[test]
    fn a_communicator_needs_its_links_and_is_the_nodes_gateway() {
        let t0 = Instant::now();
        let mut host = Host::new(2, 1, t0);
        let any: std::net::SocketAddr = "127.0.0.1:0".parse().unwrap();
        let mut e = Host::entry(Stock::Communicator);
        let none = host.build(&e).err().unwrap();
        assert_eq!(
            none.to_string(),
            "communicator: a communicator needs at least one data link (give its data links in `links:`; only a node hosts a communicator, as its gateway)"
        );
        e.links = vec![
            UdpLinkConfig::new(3, any, any),
            UdpLinkConfig::new(3, any, any),
        ];
        assert!(matches!(
            host.build(&e),
            Err(HostError::Links {
                error: CommunicatorError::DuplicateId(3),
                ..
            })
        ));
        // A socket that cannot be bound names the link.
        let taken = std::net::UdpSocket::bind(any).unwrap();
        e.links = vec![UdpLinkConfig::new(4, taken.local_addr().unwrap(), any)];
        let busy = host.build(&e).err().unwrap();
        assert!(matches!(busy, HostError::Link { link: 4, .. }), "{busy}");
        assert!(
            busy.to_string()
                .starts_with("communicator: data link 4: cannot use 127.0.0.1:"),
            "{busy}"
        );
        // Failed attempts hosted nothing: the same address takes a good entry.
        e.links = vec![
            UdpLinkConfig::new(1, any, any),
            UdpLinkConfig::new(2, any, any),
        ];
        let c = host.build(&e).unwrap();
        assert_eq!(c.address(), Address::new(2, 1, 35, 1));
        let gw = c
            .as_any()
            .downcast_ref::<CommunicatorEndpoint<UdpLink>>()
            .unwrap();
        assert_eq!(gw.communicator().link_ids().collect::<Vec<_>>(), [1, 2]);
        let other = Host::entry(Stock::GlobalPoseSensor);
        assert_eq!(
            Host::communicator_of(2, 1, [&other, &e.clone().instance(3)]),
            Some(Address::new(2, 1, 35, 3))
        );
        assert_eq!(Host::communicator_of(2, 1, [&other]), None);
    }

    #[test]
    fn a_communicator_over_links_the_caller_made() {
        let t0 = Instant::now();
        let mut host = Host::new(2, 1, t0);
        let any: std::net::SocketAddr = "127.0.0.1:0".parse().unwrap();
        let e = Host::entry(Stock::Communicator).instance(2);
        let none: Vec<Box<dyn DataLink>> = Vec::new();
        assert!(matches!(
            host.build_communicator(&e, none),
            Err(HostError::Links {
                error: CommunicatorError::NoLinks,
                ..
            })
        ));
        let links: Vec<Box<dyn DataLink>> = [7, 3]
            .into_iter()
            .map(|id| Box::new(UdpLink::bind(UdpLinkConfig::new(id, any, any)).unwrap()) as _)
            .collect();
        let c = host.build_communicator(&e, links).unwrap();
        assert_eq!(c.address(), Address::new(2, 1, 35, 2));
        let gw = c
            .as_any()
            .downcast_ref::<CommunicatorEndpoint<Box<dyn DataLink>>>()
            .unwrap();
        assert_eq!(gw.communicator().link_ids().collect::<Vec<_>>(), [7, 3]);
        // Hosted: the address is taken.
        let again = vec![UdpLink::bind(UdpLinkConfig::new(1, any, any)).unwrap()];
        assert!(matches!(
            host.build_communicator(&e, again),
            Err(HostError::Duplicate { .. })
        ));
    }
}
