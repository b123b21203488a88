//! The registry: one line per stock component saying how to build its core. Its name,
//! id and hardware are the definitions' (`stock:` in `jaus-spec/defs`, generated into
//! [`jaus::components::COMPONENTS`]); a line here whose component has no `stock:`
//! entry, or a `stock:` entry with no line here, fails the registry's test.

use std::fmt;
use std::hash::{Hash, Hasher};

use super::build::{BuildCx, Built};
use jaus::component::{ComponentInfo, Hardware, StockInfo};
use jaus::components::{self as c, COMPONENTS};
use jaus::stock::drivers::{
    Navigator, PrimitiveConfig, ReflexiveConfig, StockPrimitiveDriver, StockReflexiveDriver,
    StockVectorDriver,
};
use jaus::stock::environment::camera::{StockVisualSensor, VisualConfig};
use jaus::stock::environment::range::{RangeConfig, ScanObstacles, StockRangeSensor};
use jaus::stock::manipulator::{
    PrimitiveManipulatorConfig, StockEndEffectorDiscretePoseDriver, StockEndEffectorPoseDriver,
    StockEndEffectorVelocityStateDriver, StockJointMoveDriver, StockJointPositionsDriver,
    StockJointSensor, StockJointVelocitiesDriver, StockPrimitiveManipulator,
};
use jaus::stock::sensors::{StockGlobalPoseSensor, StockLocalPoseSensor, StockVelocityStateSensor};
use jaus::stock::spooler::{SpoolerConfig, StockMissionSpooler};
use jaus::stock::world_model::{StockWorldModel, WorldModelConfig};

/// How a stock core is built.
type Build = fn(&BuildCx<'_>) -> Built;

/// Every stock component `jaus node` hosts, by component id, with how to build it; in
/// the order `jaus node` lists them.
const REGISTRY: &[(u8, Build)] = &[
    (c::primitive_driver::ID, |cx| {
        cx.run(c::primitive_driver::component, {
            let vehicle = cx.vehicle();
            let specifications = Some(vehicle.lock().params().specifications());
            StockPrimitiveDriver::new(
                vehicle,
                PrimitiveConfig {
                    specifications,
                    ..PrimitiveConfig::default()
                },
            )
        })
    }),
    (c::reflexive_driver::ID, |cx| {
        cx.run(
            c::reflexive_driver::component,
            StockReflexiveDriver::new(
                ScanObstacles::new(cx.scanner(), 1.0),
                ReflexiveConfig {
                    output: cx.output(),
                    ..ReflexiveConfig::default()
                },
            ),
        )
    }),
    (c::global_pose_sensor::ID, |cx| {
        cx.run(
            c::global_pose_sensor::component,
            StockGlobalPoseSensor(cx.vehicle()),
        )
    }),
    (c::local_pose_sensor::ID, |cx| {
        cx.run(
            c::local_pose_sensor::component,
            StockLocalPoseSensor(cx.vehicle()),
        )
    }),
    (c::velocity_state_sensor::ID, |cx| {
        cx.run(
            c::velocity_state_sensor::component,
            StockVelocityStateSensor(cx.vehicle()),
        )
    }),
    (c::global_vector_driver::ID, |cx| {
        cx.run(
            c::global_vector_driver::component,
            StockVectorDriver::new(cx.drive(c::global_pose_sensor::ID)),
        )
    }),
    (c::local_vector_driver::ID, |cx| {
        cx.run(
            c::local_vector_driver::component,
            StockVectorDriver::new(cx.drive(c::local_pose_sensor::ID)),
        )
    }),
    (c::global_waypoint_driver::ID, |cx| {
        cx.run(
            c::global_waypoint_driver::component,
            Navigator::new(cx.drive(c::global_pose_sensor::ID)),
        )
    }),
    (c::local_waypoint_driver::ID, |cx| {
        cx.run(
            c::local_waypoint_driver::component,
            Navigator::new(cx.drive(c::local_pose_sensor::ID)),
        )
    }),
    (c::global_path_segment_driver::ID, |cx| {
        cx.run(
            c::global_path_segment_driver::component,
            Navigator::new(cx.drive(c::global_pose_sensor::ID)),
        )
    }),
    (c::local_path_segment_driver::ID, |cx| {
        cx.run(
            c::local_path_segment_driver::component,
            Navigator::new(cx.drive(c::local_pose_sensor::ID)),
        )
    }),
    (c::mission_spooler::ID, |cx| {
        let config = SpoolerConfig::default();
        let core = match cx.store() {
            Some(s) => s
                .mission_spooler(cx.at.instance, config)
                .map_err(|e| cx.store_error(e))?,
            None => StockMissionSpooler::new(config),
        };
        cx.run(c::mission_spooler::component, core)
    }),
    (c::world_model_vector_knowledge_store::ID, |cx| {
        let config = WorldModelConfig::default();
        let core = match cx.store() {
            Some(s) => s
                .world_model(cx.at.instance, config)
                .map_err(|e| cx.store_error(e))?,
            None => StockWorldModel::new(config),
        };
        cx.run(c::world_model_vector_knowledge_store::component, core)
    }),
    (c::range_sensor::ID, |cx| {
        cx.run(
            c::range_sensor::component,
            StockRangeSensor::new(cx.scanner(), RangeConfig::default()),
        )
    }),
    (c::visual_sensor::ID, |cx| {
        cx.run(
            c::visual_sensor::component,
            StockVisualSensor::new(cx.camera(), VisualConfig::default()),
        )
    }),
    (c::primitive_manipulator::ID, |cx| {
        let arm = cx.arm();
        let chain = arm.lock().chain().clone();
        cx.run_arm(
            c::primitive_manipulator::component,
            StockPrimitiveManipulator::new(
                arm.clone(),
                chain,
                PrimitiveManipulatorConfig::default(),
            )
            .with_hold(arm.holding_controller()),
        )
    }),
    (c::manipulator_joint_position_sensor::ID, |cx| {
        cx.run_arm(
            c::manipulator_joint_position_sensor::component,
            StockJointSensor::new(cx.arm()),
        )
    }),
    (c::manipulator_joint_velocity_sensor::ID, |cx| {
        cx.run_arm(
            c::manipulator_joint_velocity_sensor::component,
            StockJointSensor::new(cx.arm()),
        )
    }),
    (c::manipulator_joint_force_torque_sensor::ID, |cx| {
        cx.run_arm(
            c::manipulator_joint_force_torque_sensor::component,
            StockJointSensor::new(cx.arm()),
        )
    }),
    (c::manipulator_joint_positions_driver::ID, |cx| {
        cx.run_arm(
            c::manipulator_joint_positions_driver::component,
            StockJointPositionsDriver::new(cx.arm_driver()),
        )
    }),
    (c::manipulator_end_effector_pose_driver::ID, |cx| {
        cx.run_arm(
            c::manipulator_end_effector_pose_driver::component,
            StockEndEffectorPoseDriver::new(cx.arm_driver()),
        )
    }),
    (c::manipulator_joint_velocities_driver::ID, |cx| {
        cx.run_arm(
            c::manipulator_joint_velocities_driver::component,
            StockJointVelocitiesDriver::new(cx.arm_driver()),
        )
    }),
    (
        c::manipulator_end_effector_velocity_state_driver::ID,
        |cx| {
            cx.run_arm(
                c::manipulator_end_effector_velocity_state_driver::component,
                StockEndEffectorVelocityStateDriver::new(cx.arm_driver()),
            )
        },
    ),
    (c::manipulator_joint_move_driver::ID, |cx| {
        cx.run_arm(
            c::manipulator_joint_move_driver::component,
            StockJointMoveDriver::new(cx.arm_driver()),
        )
    }),
    (c::manipulator_end_effector_discrete_pose_driver::ID, |cx| {
        cx.run_arm(
            c::manipulator_end_effector_discrete_pose_driver::component,
            StockEndEffectorDiscretePoseDriver::new(cx.arm_driver()),
        )
    }),
    (c::communicator::ID, |cx| cx.communicator()),
];

/// A stock component a [`Host`](super::Host) builds: its row of the component table
/// (name in node files, id, hardware) and its registry line. Compared by id.
#[derive(Clone, Copy)]
pub struct Stock {
    info: &'static ComponentInfo,
    stock: StockInfo,
    build: Build,
}

impl Stock {
    /// Every stock component, in the order of the registry.
    pub fn all() -> impl Iterator<Item = Stock> {
        REGISTRY.iter().filter_map(|&(id, build)| {
            let info = COMPONENTS.iter().find(|c| c.id == id)?;
            Some(Stock {
                info,
                stock: info.stock?,
                build,
            })
        })
    }

    /// The names of every stock component, as node files give them.
    pub fn names() -> impl Iterator<Item = &'static str> {
        Self::all().map(Stock::name)
    }

    /// The component by its name in node files (`world_model`).
    pub fn by_name(name: &str) -> Option<Stock> {
        Self::all().find(|s| s.name() == name)
    }

    /// The component by its id (`jaus::components::world_model_vector_knowledge_store::ID`).
    pub fn by_id(id: u8) -> Option<Stock> {
        Self::all().find(|s| s.id() == id)
    }

    /// Its name in node files.
    pub fn name(self) -> &'static str {
        self.stock.name
    }

    /// Its component id (Part 1).
    pub fn id(self) -> u8 {
        self.info.id
    }

    /// The hardware it runs over.
    pub fn needs(self) -> Hardware {
        self.stock.needs
    }

    /// Its row of the component table.
    pub fn info(self) -> &'static ComponentInfo {
        self.info
    }

    /// Builds its core.
    pub(super) fn build(self, cx: &BuildCx<'_>) -> Built {
        (self.build)(cx)
    }
}

impl PartialEq for Stock {
    fn eq(&self, other: &Self) -> bool {
        self.id() == other.id()
    }
}

impl Eq for Stock {}

impl Hash for Stock {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.id().hash(state);
    }
}

impl fmt::Debug for Stock {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Stock({} {})", self.name(), self.id())
    }
}

impl fmt::Display for Stock {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_registry_and_the_definitions_name_the_same_components() {
        // Every line builds a component the definitions give a `stock:` entry...
        for &(id, _) in REGISTRY {
            let row = COMPONENTS.iter().find(|c| c.id == id);
            assert!(
                row.is_some_and(|r| r.stock.is_some()),
                "registry line for component {id}: no `stock:` entry in jaus-spec/defs ({row:?})"
            );
        }
        // ... and every `stock:` entry has exactly one line.
        for info in COMPONENTS.iter().filter(|c| c.stock.is_some()) {
            let lines = REGISTRY.iter().filter(|(id, _)| *id == info.id).count();
            assert_eq!(lines, 1, "{}: {lines} registry lines", info.name);
        }
        assert_eq!(Stock::all().count(), REGISTRY.len());
    }

    #[test]
    fn names_and_ids_are_the_definitions() {
        let wm = Stock::by_name("world_model").unwrap();
        assert_eq!(wm.id(), c::world_model_vector_knowledge_store::ID);
        assert_eq!(wm.info().name, "WorldModelVectorKnowledgeStore");
        assert_eq!(wm.needs(), Hardware::None);
        assert_eq!(
            Stock::by_id(c::range_sensor::ID).unwrap().needs(),
            Hardware::Scanner
        );
        assert_eq!(
            Stock::by_name("communicator").unwrap().needs(),
            Hardware::Links
        );
        assert_eq!(Stock::by_name("world_model_vector_knowledge_store"), None);
        assert_eq!(Stock::by_id(c::system_commander::ID), None);
        assert_eq!(format!("{wm} {wm:?}"), "world_model Stock(world_model 61)");
    }
}
