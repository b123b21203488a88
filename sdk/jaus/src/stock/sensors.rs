//! Global Pose, Local Pose and Velocity State Sensors over the hardware traits. The
//! runtime turns the query handlers into service connections and events as well.
//!
//! A reading beyond what its report can carry (a speed above 65.534 m/s, a position RMS
//! above 100 m, a latitude a hair beyond ±90° after noise) is reported at the limit of
//! the field: the sensors clamp their reports explicitly
//! ([`Encode::clamped`]), since the encoder refuses
//! values out of range. A reading that is not a number still fails to encode.

use nalgebra::UnitQuaternion;

use super::hardware::{GlobalPoseSource, LocalPoseSource, VelocitySource};
use crate::codec::Encode;
use crate::component::Refused;
use crate::components::global_pose_sensor::{self, GlobalPoseSensor};
use crate::components::local_pose_sensor::{self, LocalPoseSensor};
use crate::components::velocity_state_sensor::{self, VelocityStateSensor};
use crate::messages::*;

/// Roll, pitch, yaw of an attitude, each wrapped to (-π, π].
fn rpy(q: &UnitQuaternion<f64>) -> (f64, f64, f64) {
    q.euler_angles()
}

fn bit(pv: u16, b: u16) -> bool {
    pv & (1 << b) != 0
}

fn time_stamp<I: crate::component::Interface>(
    ctx: &crate::component::Context<'_, I>,
) -> Option<TimeStamp> {
    ctx.time_stamps().map(|(t, _)| t)
}

/// A Global Pose Sensor reading a [`GlobalPoseSource`].
#[derive(Debug)]
pub struct StockGlobalPoseSensor<S>(pub S);

impl<S: GlobalPoseSource> GlobalPoseSensor for StockGlobalPoseSensor<S> {
    fn on_query_global_pose(
        &mut self,
        ctx: &mut global_pose_sensor::Ctx<'_>,
        q: &QueryGlobalPose,
    ) -> Result<ReportGlobalPose, Refused> {
        let f = self
            .0
            .global_pose(ctx.now())
            .ok_or_else(|| Refused::Invalid("no global pose fix".into()))?;
        let (roll, pitch, yaw) = rpy(&f.attitude);
        let pv = q.presence_vector;
        Ok(ReportGlobalPose {
            latitude: bit(pv, 0).then_some(f.latitude),
            longitude: bit(pv, 1).then_some(f.longitude),
            elevation: bit(pv, 2).then_some(f.elevation),
            position_rms: bit(pv, 3).then_some(f.position_rms),
            roll: bit(pv, 4).then_some(roll),
            pitch: bit(pv, 5).then_some(pitch),
            yaw: bit(pv, 6).then_some(yaw),
            attitude_rms: None,
            time_stamp: if bit(pv, 8) { time_stamp(ctx) } else { None },
        }
        .clamped())
    }
}

/// A Local Pose Sensor reading a [`LocalPoseSource`].
#[derive(Debug)]
pub struct StockLocalPoseSensor<S>(pub S);

impl<S: LocalPoseSource> LocalPoseSensor for StockLocalPoseSensor<S> {
    fn on_query_local_pose(
        &mut self,
        ctx: &mut local_pose_sensor::Ctx<'_>,
        q: &QueryLocalPose,
    ) -> Result<ReportLocalPose, Refused> {
        let p = self
            .0
            .local_pose(ctx.now())
            .ok_or_else(|| Refused::Invalid("no local pose".into()))?;
        let (roll, pitch, yaw) = rpy(&p.attitude);
        let pv = q.presence_vector;
        Ok(ReportLocalPose {
            x: bit(pv, 0).then_some(p.position.x),
            y: bit(pv, 1).then_some(p.position.y),
            z: bit(pv, 2).then_some(p.position.z),
            position_rms: None,
            roll: bit(pv, 4).then_some(roll),
            pitch: bit(pv, 5).then_some(pitch),
            yaw: bit(pv, 6).then_some(yaw),
            attitude_rms: None,
            time_stamp: if bit(pv, 8) { time_stamp(ctx) } else { None },
        }
        .clamped())
    }
}

/// A Velocity State Sensor reading a [`VelocitySource`].
#[derive(Debug)]
pub struct StockVelocityStateSensor<S>(pub S);

impl<S: VelocitySource> VelocityStateSensor for StockVelocityStateSensor<S> {
    fn on_query_velocity_state(
        &mut self,
        ctx: &mut velocity_state_sensor::Ctx<'_>,
        q: &QueryVelocityState,
    ) -> Result<ReportVelocityState, Refused> {
        let v = self
            .0
            .velocity(ctx.now())
            .ok_or_else(|| Refused::Invalid("no velocity state".into()))?;
        let pv = q.presence_vector;
        Ok(ReportVelocityState {
            velocity_x: bit(pv, 0).then_some(v.linear.x),
            velocity_y: bit(pv, 1).then_some(v.linear.y),
            velocity_z: bit(pv, 2).then_some(v.linear.z),
            velocity_rms: None,
            roll_rate: bit(pv, 4).then_some(v.angular.x),
            pitch_rate: bit(pv, 5).then_some(v.angular.y),
            yaw_rate: bit(pv, 6).then_some(v.angular.z),
            rate_rms: None,
            time_stamp: if bit(pv, 8) { time_stamp(ctx) } else { None },
        }
        .clamped())
    }
}
