//! The behaviours of the proxy's sensors and Primitive Driver: RA 3.3 queries answered
//! from the latest AS-4 report ([`Shared`]), Set Wrench Effort passed
//! on; and what every proxy driver does when its core state changes
//! ([`state_to_as4`]).

use std::fmt;
use std::marker::PhantomData;

use jaus::codec::Encode;
use jaus::component::{Behaviour, Context, CoreState, Interface, Refused, StopReason};
use jaus::components::primitive_driver;
use jaus::messages::{self as ra, Message as Ra33Message};
use jaus::JausMessage;

use super::shared::{lock, Shared, SharedRef};
use super::Role;
use crate::messages::{self as as4, ComponentState, EmergencyCode, Message};
use crate::ra33::efforts;

/// An AS-4 time stamp as RA 3.3's (the same fields, [`jaus::clock::TimeOfDay`]).
fn time_stamp(t: &as4::TimeStamp) -> ra::TimeStamp {
    jaus::clock::TimeOfDay::from(t).into()
}

/// The RA 3.3 report of an AS-4 Report Velocity State (the same fields and units).
pub fn velocity_state(r: &as4::ReportVelocityState) -> ra::ReportVelocityState {
    ra::ReportVelocityState {
        velocity_x: r.velocity_x,
        velocity_y: r.velocity_y,
        velocity_z: r.velocity_z,
        velocity_rms: r.velocity_rms,
        roll_rate: r.roll_rate,
        pitch_rate: r.pitch_rate,
        yaw_rate: r.yaw_rate,
        rate_rms: r.rate_rms,
        time_stamp: r.time_stamp.as_ref().map(time_stamp),
    }
}

/// The RA 3.3 report of an AS-4 Report Global Pose (altitude → elevation).
pub fn global_pose(r: &as4::ReportGlobalPose) -> ra::ReportGlobalPose {
    ra::ReportGlobalPose {
        latitude: r.latitude,
        longitude: r.longitude,
        elevation: r.altitude,
        position_rms: r.position_rms,
        roll: r.roll,
        pitch: r.pitch,
        yaw: r.yaw,
        attitude_rms: r.attitude_rms,
        time_stamp: r.time_stamp.as_ref().map(time_stamp),
    }
}

/// The RA 3.3 report of an AS-4 Report Local Pose, its position and yaw moved from the
/// AS-4 local frame into the RA 3.3 one.
pub fn local_pose(r: &as4::ReportLocalPose, s: &Shared) -> ra::ReportLocalPose {
    let (x, y) = match (r.x, r.y) {
        (Some(x), Some(y)) => {
            let (rx, ry) = s.frame.to_ra33(x, y);
            (Some(rx), Some(ry))
        }
        _ => (None, None),
    };
    ra::ReportLocalPose {
        x,
        y,
        z: r.z,
        position_rms: r.position_rms,
        roll: r.roll,
        pitch: r.pitch,
        yaw: r.yaw.map(|a| s.frame.yaw_to_ra33(a)),
        attitude_rms: r.attitude_rms,
        time_stamp: r.time_stamp.as_ref().map(time_stamp),
    }
}

/// No report from the vehicle yet: the query is not answered (counted by the runtime).
fn not_yet() -> Refused {
    Refused::Unsupported
}

/// The answer to an RA 3.3 sensor query from the latest AS-4 report, the query's
/// presence vector applied.
fn sensor_answer(s: &Shared, role: Role, q: &Ra33Message) -> Result<Ra33Message, Refused> {
    let latest = |code| s.report(role, code).map(|(_, m)| m);
    match q {
        Ra33Message::QueryVelocityState(q) => {
            let Some(Message::ReportVelocityState(r)) = latest(as4::ReportVelocityState::CODE)
            else {
                return Err(not_yet());
            };
            let mut out = velocity_state(r);
            out.keep_present(u64::from(q.presence_vector));
            Ok(out.into())
        }
        Ra33Message::QueryGlobalPose(q) => {
            let Some(Message::ReportGlobalPose(r)) = latest(as4::ReportGlobalPose::CODE) else {
                return Err(not_yet());
            };
            let mut out = global_pose(r);
            out.keep_present(u64::from(q.presence_vector));
            Ok(out.into())
        }
        Ra33Message::QueryLocalPose(q) => {
            let Some(Message::ReportLocalPose(r)) = latest(as4::ReportLocalPose::CODE) else {
                return Err(not_yet());
            };
            let mut out = local_pose(r, s);
            out.keep_present(u64::from(q.presence_vector));
            Ok(out.into())
        }
        _ => Err(Refused::Unsupported),
    }
}

/// A proxy sensor of interface `I` (Velocity State, Local or Global Pose Sensor).
pub struct Sensor<I> {
    role: Role,
    shared: SharedRef,
    _interface: PhantomData<fn() -> I>,
}

impl<I> fmt::Debug for Sensor<I> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Sensor").field("role", &self.role).finish()
    }
}

impl<I> Sensor<I> {
    /// The sensor presenting `role` from `shared`.
    pub fn new(role: Role, shared: SharedRef) -> Self {
        Self {
            role,
            shared,
            _interface: PhantomData,
        }
    }
}

impl<I: Interface<Messages = Ra33Message>> Behaviour for Sensor<I> {
    type Interface = I;

    fn handle(
        &mut self,
        _ctx: &mut Context<'_, I>,
        msg: &Ra33Message,
    ) -> Result<Option<Ra33Message>, Refused> {
        sensor_answer(&lock(&self.shared), self.role, msg).map(Some)
    }
}

/// A proxy driver's core state changed (`from` → `to`): the AS-4 Management command
/// that makes the vehicle's component follow. Resume and Standby only while the proxy
/// holds AS-4 control (they need it); Set Emergency unless the vehicle is in Emergency
/// already (its own, which the proxy followed), Clear Emergency only while it is.
pub fn state_to_as4(s: &mut Shared, role: Role, from: CoreState, to: CoreState) {
    let Some(at) = s.service(role) else {
        return;
    };
    let vehicle = s.status(at);
    let held = s.holds(role);
    match (from, to) {
        (_, CoreState::Emergency) if vehicle != Some(ComponentState::Emergency) => {
            s.send(
                at,
                as4::SetEmergency {
                    emergency_code: EmergencyCode::Stop,
                },
            );
        }
        (CoreState::Emergency, _) if vehicle == Some(ComponentState::Emergency) => {
            s.send(
                at,
                as4::ClearEmergency {
                    emergency_code: EmergencyCode::Stop,
                },
            );
        }
        (CoreState::Standby, CoreState::Ready) if held => s.send(at, as4::Resume {}),
        (CoreState::Ready, CoreState::Standby) if held => s.send(at, as4::Standby {}),
        _ => {}
    }
}

/// The proxy's Primitive Driver.
#[derive(Debug)]
pub struct Primitive {
    shared: SharedRef,
}

impl Primitive {
    /// The driver presenting the vehicle's Primitive Driver from `shared`.
    pub fn new(shared: SharedRef) -> Self {
        Self { shared }
    }
}

type PdCtx<'a> = Context<'a, primitive_driver::Interface>;

impl Behaviour for Primitive {
    type Interface = primitive_driver::Interface;

    fn handle(
        &mut self,
        _ctx: &mut PdCtx<'_>,
        msg: &Ra33Message,
    ) -> Result<Option<Ra33Message>, Refused> {
        let mut s = lock(&self.shared);
        let role = Role::PrimitiveDriver;
        match msg {
            Ra33Message::SetWrenchEffort(w) => {
                if !s.holds(role) {
                    return Err(Refused::Invalid(
                        "Set Wrench Effort: no AS-4 control of the vehicle's Primitive Driver"
                            .into(),
                    ));
                }
                s.send_to(role, efforts!(w => as4::SetWrenchEffort));
                Ok(None)
            }
            Ra33Message::QueryWrenchEffort(q) => {
                let Some((_, Message::ReportWrenchEffort(r))) =
                    s.report(role, as4::ReportWrenchEffort::CODE)
                else {
                    return Err(not_yet());
                };
                let mut out = efforts!(r => ra::ReportWrenchEffort);
                out.keep_present(u64::from(q.presence_vector));
                Ok(Some(out.into()))
            }
            _ => Err(Refused::Unsupported),
        }
    }

    fn state_changed(&mut self, _ctx: &mut PdCtx<'_>, from: CoreState, to: CoreState) {
        state_to_as4(&mut lock(&self.shared), Role::PrimitiveDriver, from, to);
    }

    fn stop(&mut self, _ctx: &mut PdCtx<'_>, reason: StopReason) {
        let mut s = lock(&self.shared);
        if s.holds(Role::PrimitiveDriver) {
            tracing::info!(%reason, "proxy Primitive Driver: efforts to zero");
            s.send_to(
                Role::PrimitiveDriver,
                as4::SetWrenchEffort {
                    propulsive_linear_effort_x: Some(0.0),
                    propulsive_rotational_effort_z: Some(0.0),
                    ..Default::default()
                },
            );
        }
    }
}
