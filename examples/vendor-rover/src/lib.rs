//! Vendor Rover: experimental JAUS messages and the Tank Monitor component, generated from
//! `defs/vendor_rover.yaml` at build time, implemented here, and hosted with the SDK's
//! stock Global Pose Sensor on one JAUS node.
//!
//! Struct literals of generated messages end with `..Default::default()`: a later
//! revision of the definitions may add an optional field (a compatible change), and a
//! literal listing every field would then stop compiling (docs/spec-revisions.md of the
//! SDK). Clippy's `needless_update` flags the form while no field is left out.
#![allow(clippy::needless_update)]

use std::time::Instant;

use jaus::component::{Config, Endpoint, Refused};
use jaus::components::global_pose_sensor;
use jaus::net::{NetError, Node, NodeConfig};
use jaus::stock::hardware::{GlobalPose, GlobalPoseSource};
use jaus::stock::nalgebra::UnitQuaternion;
use jaus::stock::sensors::StockGlobalPoseSensor;
use jaus::Address;

/// The generated messages: this crate's own and, wrapped in `Message::Jaus`, the SDK's.
pub mod messages {
    include!(concat!(env!("OUT_DIR"), "/messages.rs"));

    /// The generated component skeletons.
    pub mod components {
        include!(concat!(env!("OUT_DIR"), "/components.rs"));
    }
}

use messages::components::tank_monitor::{self, Ctx, TankMonitor, Transition};
use messages::{
    QueryDrainValve, QueryTankLevels, ReportDrainValve, ReportTankLevels, SetDrainValve,
};

/// The Tank Monitor's implementation: simulated tanks that drain 1 % per tick while
/// their valve is open. Replace the level model with your hardware.
#[derive(Debug, Clone, PartialEq)]
pub struct Tanks {
    /// Fill levels, %.
    pub levels: Vec<f64>,
    /// The tank whose valve is open.
    pub open: Option<u8>,
}

impl Tanks {
    fn report(&self, ctx: &Ctx<'_>) -> ReportTankLevels {
        ReportTankLevels {
            time_stamp: ctx.time_stamps().map(|s| s.0).unwrap_or_default(),
            levels: self.levels.clone(),
            ..Default::default()
        }
    }
}

impl TankMonitor for Tanks {
    fn on_set_drain_valve(
        &mut self,
        ctx: &mut Ctx<'_>,
        msg: &SetDrainValve,
    ) -> Result<(), Refused> {
        if usize::from(msg.tank) >= self.levels.len() {
            return Err(Refused::Invalid(format!("no tank {}", msg.tank)));
        }
        let t = match msg.open {
            1 => {
                self.open = Some(msg.tank);
                Transition::Open
            }
            0 => {
                self.open = None;
                Transition::Close
            }
            n => return Err(Refused::Invalid(format!("open must be 0 or 1, not {n}"))),
        };
        ctx.transition(t)
            .map(|_| ())
            .map_err(|e| Refused::Invalid(e.to_string()))
    }

    fn on_query_tank_levels(
        &mut self,
        ctx: &mut Ctx<'_>,
        _: &QueryTankLevels,
    ) -> Result<ReportTankLevels, Refused> {
        Ok(self.report(ctx))
    }

    fn on_query_drain_valve(
        &mut self,
        _: &mut Ctx<'_>,
        msg: &QueryDrainValve,
    ) -> Result<ReportDrainValve, Refused> {
        if usize::from(msg.tank) >= self.levels.len() {
            return Err(Refused::Invalid(format!("no tank {}", msg.tank)));
        }
        Ok(ReportDrainValve {
            tank: msg.tank,
            open: u8::from(self.open == Some(msg.tank)),
        })
    }

    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        let (Some(tank), Some(controller)) = (self.open, ctx.controller()) else {
            return;
        };
        let level = &mut self.levels[usize::from(tank)];
        *level = (*level - 1.0).max(0.0);
        let report = self.report(ctx);
        ctx.send(controller, report);
    }
}

/// A GPS fixed at one place: replace with your receiver's driver.
#[derive(Debug, Clone, Copy)]
pub struct FixedGps {
    /// Latitude, degrees.
    pub latitude: f64,
    /// Longitude, degrees.
    pub longitude: f64,
}

impl GlobalPoseSource for FixedGps {
    fn global_pose(&mut self, _now: Instant) -> Option<GlobalPose> {
        Some(GlobalPose {
            latitude: self.latitude,
            longitude: self.longitude,
            elevation: 0.0,
            attitude: UnitQuaternion::identity(),
            position_rms: 1.0,
        })
    }
}

/// The Tank Monitor at `subsystem`.`node`.210.1.
pub fn tank_monitor_at(
    subsystem: u8,
    node: u8,
    t0: Instant,
) -> jaus::component::Component<tank_monitor::Dispatch<Tanks>> {
    tank_monitor::component(
        Address::new(subsystem, node, 210, 1),
        Tanks {
            levels: vec![80.0, 40.0],
            open: None,
        },
        Config::default(),
        t0,
    )
}

/// The components of this node: the Tank Monitor (210.1) and the SDK's stock Global
/// Pose Sensor (38.1) over [`FixedGps`].
pub fn components(subsystem: u8, node: u8, t0: Instant) -> Vec<Box<dyn Endpoint>> {
    vec![
        Box::new(tank_monitor_at(subsystem, node, t0)),
        Box::new(global_pose_sensor::component(
            Address::new(subsystem, node, 38, 1),
            StockGlobalPoseSensor(FixedGps {
                latitude: 29.65,
                longitude: -82.32,
            }),
            Config::default(),
            t0,
        )),
    ]
}

/// A node hosting [`components`].
pub fn node(config: NodeConfig, t0: Instant) -> Result<Node, NetError> {
    let (ss, n) = (config.subsystem, config.node);
    let mut node = Node::new(config, t0);
    for c in components(ss, n, t0) {
        node.add_boxed(c)?;
    }
    Ok(node)
}
