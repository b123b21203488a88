//! What a registry line builds a stock core from: the entry, its address, the shared
//! simulated hardware and the default wiring of the node.

use std::cell::RefCell;
use std::time::Instant;

use super::{Entry, Host, HostError};
use jaus::component::{Config, Endpoint, Hardware};
use jaus::components::{
    manipulator_joint_position_sensor as joint_positions,
    manipulator_joint_velocity_sensor as joint_velocities, primitive_driver, primitive_manipulator,
    reflexive_driver, velocity_state_sensor,
};
use jaus::stock::manipulator::link::ArmDriverConfig;
use jaus::stock::motion::DriverConfig;
use jaus::Address;
use jaus_sim::arm::SimArm;
use jaus_sim::camera::SimCamera;
use jaus_sim::scanner::SimScanner;
use jaus_sim::vehicle::SimVehicle;

/// A built component, or why not.
pub(super) type Built = Result<Box<dyn Endpoint>, HostError>;

/// The build context of one entry.
pub(super) struct BuildCx<'a> {
    host: &'a Host,
    /// The entry being built.
    pub entry: &'a Entry,
    /// Its address.
    pub at: Address,
    /// The simulated hardware handed out.
    used: RefCell<Vec<Hardware>>,
}

impl<'a> BuildCx<'a> {
    pub(super) fn new(host: &'a Host, entry: &'a Entry, at: Address) -> Self {
        Self {
            host,
            entry,
            at,
            used: RefCell::new(Vec::new()),
        }
    }

    /// The host.
    pub(super) fn host(&self) -> &'a Host {
        self.host
    }

    /// The hardware handed out so far.
    pub(super) fn used(&self) -> Vec<Hardware> {
        self.used.borrow().clone()
    }

    fn uses(&self, h: Hardware) {
        let mut used = self.used.borrow_mut();
        if !used.contains(&h) {
            used.push(h);
        }
    }

    /// When the components start.
    pub(super) fn t0(&self) -> Instant {
        self.host.t0
    }

    /// The component's configuration: its authority, the runtime's defaults.
    pub(super) fn config(&self) -> Config {
        Config {
            authority: self.entry.authority,
            ..Config::default()
        }
    }

    /// `make` (a generated `component` function) at this entry's address running
    /// `core`, with [`BuildCx::config`].
    pub(super) fn run<T, C: Endpoint + 'static>(
        &self,
        make: impl FnOnce(Address, T, Config, Instant) -> C,
        core: T,
    ) -> Built {
        Ok(Box::new(make(self.at, core, self.config(), self.t0())))
    }

    /// As [`BuildCx::run`], ticking at the arm's control period (the manipulator
    /// components).
    pub(super) fn run_arm<T, C: Endpoint + 'static>(
        &self,
        make: impl FnOnce(Address, T, Config, Instant) -> C,
        core: T,
    ) -> Built {
        let config = Config {
            tick: self.host.world.arm_control_period,
            ..self.config()
        };
        Ok(Box::new(make(self.at, core, config, self.t0())))
    }

    /// The host's durable store, if it has one.
    pub(super) fn store(&self) -> Option<&'a jaus_store::Store> {
        self.host.store.as_ref()
    }

    /// Why this entry's core cannot be loaded from the store.
    pub(super) fn store_error(&self, e: jaus_store::StoreError) -> HostError {
        HostError::Store {
            component: self.entry.stock.name(),
            error: e.to_string(),
        }
    }

    /// The simulated vehicle (its actuators, pose and velocity).
    pub(super) fn vehicle(&self) -> SimVehicle {
        self.uses(Hardware::Vehicle);
        self.host.vehicle.clone()
    }

    /// The range scanner on the simulated vehicle, looking at the configured scene.
    pub(super) fn scanner(&self) -> SimScanner {
        self.uses(Hardware::Scanner);
        self.host.scanner.clone()
    }

    /// A pan/tilt camera on the simulated vehicle, looking at the configured scene.
    pub(super) fn camera(&self) -> SimCamera {
        self.uses(Hardware::Camera);
        SimCamera::new(self.host.vehicle.clone(), self.host.scanner.scene())
    }

    /// The simulated arm.
    pub(super) fn arm(&self) -> SimArm {
        self.uses(Hardware::Arm);
        self.host.arm.clone()
    }

    /// The entry's data links are used (the Communicator).
    pub(super) fn links(&self) -> &'a Entry {
        self.uses(Hardware::Links);
        self.entry
    }

    /// Component `id`, instance 1, on this node.
    pub(super) fn local(&self, id: u8) -> Address {
        Address::new(self.host.subsystem, self.host.node, id, 1)
    }

    /// Where a driver's efforts go: the entry's output, else this node's Reflexive
    /// Driver if it hosts one (but not for the Reflexive Driver itself), else its
    /// Primitive Driver.
    pub(super) fn output(&self) -> Address {
        self.entry.output.unwrap_or_else(|| {
            if self.host.reflexive && self.entry.stock.id() != reflexive_driver::ID {
                self.local(reflexive_driver::ID)
            } else {
                self.local(primitive_driver::ID)
            }
        })
    }

    /// A motion driver's configuration following the pose sensor `pose` of this node
    /// (unless the entry names one), in the configured frame.
    pub(super) fn drive(&self, pose: u8) -> DriverConfig {
        DriverConfig {
            output: self.output(),
            pose_sensor: self.entry.pose.unwrap_or_else(|| self.local(pose)),
            velocity_sensor: Some(self.local(velocity_state_sensor::ID)),
            origin: Some(self.host.world.origin),
            ..DriverConfig::default()
        }
    }

    /// A manipulator driver's configuration: the entry's output, else this node's
    /// Primitive Manipulator, and this node's joint sensors.
    pub(super) fn arm_driver(&self) -> ArmDriverConfig {
        ArmDriverConfig {
            output: self
                .entry
                .output
                .unwrap_or_else(|| self.local(primitive_manipulator::ID)),
            position_sensor: self.local(joint_positions::ID),
            velocity_sensor: Some(self.local(joint_velocities::ID)),
            ..ArmDriverConfig::default()
        }
    }
}
