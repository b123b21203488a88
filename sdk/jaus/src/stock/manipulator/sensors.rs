//! The joint sensors (Part 1 §5.4.3–§5.4.5): joint positions, velocities and
//! forces/torques read from [`JointSensors`] when queried (and so by service connection
//! and event, which the runtime answers through the same query).

use std::time::Instant;

use super::hardware::{JointSensors, JointState};
use crate::component::Refused;
use crate::components::{
    manipulator_joint_force_torque_sensor as fts, manipulator_joint_position_sensor as jps,
    manipulator_joint_velocity_sensor as jvs,
};
use crate::messages::*;

/// Largest joint position the report carries, ±8π (rad or m).
const POSITION_LIMIT: f64 = 8.0 * std::f64::consts::PI;
/// Largest joint velocity the report carries, ±10π (rad/s or m/s).
const VELOCITY_LIMIT: f64 = 10.0 * std::f64::consts::PI;
/// Largest force/torque the report carries, ±1000 (N or N·m).
const EFFORT_LIMIT: f64 = 1000.0;

/// A joint sensor over [`JointSensors`]: the same type serves as the Joint Position
/// Sensor (51), the Joint Velocity Sensor (52) and the Joint Force/Torque Sensor (53);
/// run one instance per component. Readings beyond what the report carries are sent
/// saturated at its limit and counted.
#[derive(Debug)]
pub struct StockJointSensor<S> {
    sensors: S,
    reading: JointState,
    saturated: u64,
}

impl<S: JointSensors> StockJointSensor<S> {
    /// Over `sensors`.
    pub fn new(sensors: S) -> Self {
        Self {
            sensors,
            reading: JointState::default(),
            saturated: 0,
        }
    }

    /// Values sent saturated at the report's limit.
    pub fn saturated(&self) -> u64 {
        self.saturated
    }

    fn read(
        &mut self,
        now: Instant,
        pick: fn(&JointState) -> &[f64],
        limit: f64,
    ) -> Result<Vec<f64>, Refused> {
        if !self.sensors.read_joints(now, &mut self.reading) || !self.reading.is_valid() {
            return Err(Refused::Invalid("no valid joint reading".into()));
        }
        let values = pick(&self.reading);
        Ok(values
            .iter()
            .map(|&v| {
                if v.abs() > limit {
                    self.saturated += 1;
                }
                v.clamp(-limit, limit)
            })
            .collect())
    }
}

impl<S: JointSensors> jps::ManipulatorJointPositionSensor for StockJointSensor<S> {
    fn on_query_joint_positions(
        &mut self,
        ctx: &mut jps::Ctx<'_>,
        _q: &QueryJointPositions,
    ) -> Result<ReportJointPositions, Refused> {
        Ok(ReportJointPositions {
            joint_position: self.read(ctx.now(), |s| &s.positions, POSITION_LIMIT)?,
        })
    }
}

impl<S: JointSensors> jvs::ManipulatorJointVelocitySensor for StockJointSensor<S> {
    fn on_query_joint_velocities(
        &mut self,
        ctx: &mut jvs::Ctx<'_>,
        _q: &QueryJointVelocities,
    ) -> Result<ReportJointVelocities, Refused> {
        Ok(ReportJointVelocities {
            joint_velocity: self.read(ctx.now(), |s| &s.velocities, VELOCITY_LIMIT)?,
        })
    }
}

impl<S: JointSensors> fts::ManipulatorJointForceTorqueSensor for StockJointSensor<S> {
    fn on_query_joint_force_torques(
        &mut self,
        ctx: &mut fts::Ctx<'_>,
        _q: &QueryJointForceTorques,
    ) -> Result<ReportJointForceTorques, Refused> {
        Ok(ReportJointForceTorques {
            joint_force_torque: self.read(ctx.now(), |s| &s.efforts, EFFORT_LIMIT)?,
        })
    }
}
