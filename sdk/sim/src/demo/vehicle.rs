//! The demo's vehicle and operator station as components: which stock cores, over which
//! simulated hardware, with which settings.

use std::time::Instant;

use nalgebra::Vector2;

use crate::camera::SimCamera;
use crate::scanner::{ScannerParams, SimScanner};
use crate::vehicle::{SimVehicle, VehicleParams};
use jaus::component::local::Endpoint;
use jaus::component::Config;
use jaus::components::system_commander::{self};
use jaus::components::{
    global_path_segment_driver, global_pose_sensor, global_waypoint_driver,
    local_path_segment_driver, local_pose_sensor, local_waypoint_driver, mission_spooler,
    primitive_driver, range_sensor, reflexive_driver, subsystem_commander, velocity_state_sensor,
    visual_sensor, world_model_vector_knowledge_store,
};
use jaus::stock::commander::{
    ControlKeeper, KeeperConfig, StockSubsystemCommander, SubsystemConfig,
};
use jaus::stock::drivers::{
    PrimitiveConfig, ReflexiveConfig, StockGlobalPathSegmentDriver, StockGlobalWaypointDriver,
    StockLocalPathSegmentDriver, StockLocalWaypointDriver, StockPrimitiveDriver,
    StockReflexiveDriver,
};
use jaus::stock::environment::camera::{StockVisualSensor, VisualConfig};
use jaus::stock::environment::map_feed::MapFeedConfig;
use jaus::stock::environment::range::{RangeConfig, StockRangeSensor};
use jaus::stock::geo::LocalFrame;
use jaus::stock::motion::DriverConfig;
use jaus::stock::sensors::{StockGlobalPoseSensor, StockLocalPoseSensor, StockVelocityStateSensor};
use jaus::stock::spooler::{SpoolerConfig, StockMissionSpooler};
use jaus::stock::world_model::{StockWorldModel, WorldModelConfig};
use jaus::Address;

use super::*;

pub(super) fn driver_config(pose_sensor: Address, ss: u8, node: u8) -> DriverConfig {
    DriverConfig {
        // Part 1 Figures 5-9 and 5-16: driving through the Reflexive Driver.
        output: addr::on(addr::RD, ss, node),
        pose_sensor,
        velocity_sensor: Some(addr::on(addr::VSS, ss, node)),
        origin: Some(LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2)),
        ..DriverConfig::default()
    }
}

/// The vehicle side of the demo (node 1.1): primitive and reflexive drivers, pose and
/// velocity sensors, the global waypoint and local path-segment drivers, over one
/// simulated vehicle.
pub fn vehicle(t0: Instant, opts: &Options) -> (Vec<Box<dyn Endpoint>>, SimVehicle) {
    vehicle_at(t0, opts, 1, 1)
}

/// [`vehicle`] on node `node` of subsystem `ss` (the components keep their ids and
/// instances of [`addr`]; the drivers' outputs and sensors follow them).
pub fn vehicle_at(
    t0: Instant,
    opts: &Options,
    ss: u8,
    node: u8,
) -> (Vec<Box<dyn Endpoint>>, SimVehicle) {
    let (parts, vehicle, _) = vehicle_with_scanner_at(t0, opts, ss, node);
    (parts, vehicle)
}

/// [`vehicle_at`], with the range scanner its Range Sensor reads (a handle on the same
/// scanner: another service may read the same sweeps, such as the AS-4 Range Sensor).
pub fn vehicle_with_scanner_at(
    t0: Instant,
    opts: &Options,
    ss: u8,
    node: u8,
) -> (Vec<Box<dyn Endpoint>>, SimVehicle, SimScanner) {
    let at = |a: Address| addr::on(a, ss, node);
    let vehicle = SimVehicle::new(VehicleParams {
        position_noise: opts.position_noise,
        heading_noise: opts.position_noise * 0.5,
        seed: opts.seed,
        origin: LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2),
        start: (Vector2::zeros(), 0.0),
        ..VehicleParams::default()
    });
    let cfg = config();
    let cfg_lwd = cfg.clone();
    let specifications = Some(vehicle.lock().params().specifications());
    let pd = StockPrimitiveDriver::new(
        vehicle.clone(),
        PrimitiveConfig {
            specifications,
            ..PrimitiveConfig::default()
        },
    );
    let rd = StockReflexiveDriver::new(
        (),
        ReflexiveConfig {
            output: at(addr::PD),
            ..Default::default()
        },
    );
    let scene = scene();
    let vs = StockVisualSensor::new(
        SimCamera::new(vehicle.clone(), scene.clone()),
        VisualConfig::default(),
    );
    let scanner = SimScanner::new(
        vehicle.clone(),
        scene,
        ScannerParams {
            noise: 0.01,
            seed: opts.seed,
            ..ScannerParams::default()
        },
    );
    let rs = StockRangeSensor::new(scanner.clone(), RangeConfig::default()).with_map_feed(
        MapFeedConfig {
            origin: Some(LocalFrame::new(ORIGIN.0, ORIGIN.1, ORIGIN.2)),
            ..MapFeedConfig::new(at(addr::WM), at(addr::GPS))
        },
    );
    let gwd = StockGlobalWaypointDriver::new(driver_config(at(addr::GPS), ss, node));
    let lpsd = StockLocalPathSegmentDriver::new(driver_config(at(addr::LPS), ss, node));
    let gpsd = StockGlobalPathSegmentDriver::new(driver_config(at(addr::GPS), ss, node));
    let parts: Vec<Box<dyn Endpoint>> = vec![
        Box::new(primitive_driver::component(
            at(addr::PD),
            pd,
            cfg.clone(),
            t0,
        )),
        Box::new(reflexive_driver::component(
            at(addr::RD),
            rd,
            cfg.clone(),
            t0,
        )),
        Box::new(global_pose_sensor::component(
            at(addr::GPS),
            StockGlobalPoseSensor(vehicle.clone()),
            cfg.clone(),
            t0,
        )),
        Box::new(local_pose_sensor::component(
            at(addr::LPS),
            StockLocalPoseSensor(vehicle.clone()),
            cfg.clone(),
            t0,
        )),
        Box::new(velocity_state_sensor::component(
            at(addr::VSS),
            StockVelocityStateSensor(vehicle.clone()),
            cfg.clone(),
            t0,
        )),
        Box::new(global_waypoint_driver::component(
            at(addr::GWD),
            gwd,
            cfg.clone(),
            t0,
        )),
        Box::new(local_path_segment_driver::component(
            at(addr::LPSD),
            lpsd,
            cfg.clone(),
            t0,
        )),
        Box::new(global_path_segment_driver::component(
            at(addr::GPSD),
            gpsd,
            cfg.clone(),
            t0,
        )),
        Box::new(range_sensor::component(at(addr::RS), rs, cfg.clone(), t0)),
        Box::new(visual_sensor::component(at(addr::VS), vs, cfg.clone(), t0)),
        Box::new(world_model_vector_knowledge_store::component(
            at(addr::WM),
            StockWorldModel::new(WorldModelConfig::default()),
            cfg.clone(),
            t0,
        )),
        // The Subsystem Commander takes the spooler's control with authority 150 (the
        // spooler accepts 100 and above; an operator station at 200 can still take it).
        Box::new(subsystem_commander::component(
            at(addr::SC),
            StockSubsystemCommander::new(SubsystemConfig::new(at(addr::MS))),
            Config {
                authority: 150,
                ..cfg.clone()
            },
            t0,
        )),
        // The spooler outranks the reflexive driver so that it can borrow the primitive
        // driver for the mission's payload action (the horn).
        Box::new(mission_spooler::component(
            at(addr::MS),
            StockMissionSpooler::new(SpoolerConfig::default()),
            Config {
                authority: 100,
                ..cfg
            },
            t0,
        )),
    ];
    let mut parts = parts;
    if opts.local_waypoint_driver {
        parts.push(Box::new(local_waypoint_driver::component(
            at(addr::LWD),
            StockLocalWaypointDriver::new(driver_config(at(addr::LPS), ss, node)),
            cfg_lwd,
            t0,
        )));
    }
    (parts, vehicle, scanner)
}

/// The demo's vehicle on a node of its own (`subsystem.node`, the node's other settings
/// from `config`), as `jaus node` with `host: [vehicle]` runs it: with the Local
/// Waypoint Driver ([`Options::local_waypoint_driver`]).
pub fn vehicle_node(
    t0: Instant,
    mut config: jaus::net::NodeConfig,
    subsystem: u8,
    node: u8,
) -> Result<jaus::net::Node, jaus::net::NetError> {
    config.subsystem = subsystem;
    config.node = node;
    let mut n = jaus::net::Node::new(config, t0);
    let opts = Options {
        local_waypoint_driver: true,
        ..Options::default()
    };
    for p in vehicle_at(t0, &opts, subsystem, node).0 {
        n.add_boxed(p)?;
    }
    Ok(n)
}

/// The operator side of the demo (1.2.40.1).
pub fn operator(t0: Instant, opts: &Options) -> Ocu {
    // The drivers are resumed by the operator once their orders are loaded.
    let mut keeper = ControlKeeper::new(KeeperConfig {
        resume: false,
        ..KeeperConfig::default()
    });
    keeper.keep(addr::GWD);
    keeper.keep(addr::LPSD);
    let ocu = Operator {
        waypoint_speed: opts.waypoint_speed,
        path_speed: opts.path_speed,
        keeper,
        ..Operator::default()
    };
    // The operator outranks everything it commands.
    system_commander::component(
        addr::OCU,
        ocu,
        Config {
            authority: 200,
            ..config()
        },
        t0,
    )
}
