//! The Platform Specifications service over an RA 3.3 Primitive Driver's Report
//! Platform Specifications (asked once, [`super::ask`]): the fields both generations have, each within the
//! AS-4 field's range; what RA 3.3 lacks is absent (presence vector), what AS-4 lacks
//! (maximum velocity along y and z, maximum roll and pitch rates) is dropped.
//!
//! | AS-4 (`ReportPlatformSpecifications`) | RA 3.3 |
//! |---|---|
//! | `platform_spec.mobility_platform_name` | `platform_name` (empty when absent) |
//! | `front`, `back`, `right`, `left`, `bottom`, `top` | the same, m |
//! | `cg_x`, `cg_y`, `cg_z` | `x_cg`, `y_cg`, `z_cg`, m |
//! | `wheel_base` | `wheel_base`, m |
//! | `static_pitch_over`, `static_roll_over` | `pitch_over`, `roll_over`, rad |
//! | `platform_inertial.maximum_forward_speed` | `maximum_velocity_x`, m/s |
//! | `maximum_rotational_speed` | `maximum_yaw_rate`, rad/s |
//! | `platform_specifics`: Ackermann `min_turn_radius`, `wheel_separation` | `turning_radius` (above 0), `track_width` |
//! | `platform_specifics`: skid steer `track_separation` | `track_width` (turning radius 0 or absent) |
//!
//! Absent, RA 3.3 has no such field: maximum reverse speed, accelerations and
//! decelerations, vehicle weight, approach, departure and breakover angles, drive wheel
//! radius, steering angle range.

use jaus::messages as ra;
use jaus::Address;

use super::{specifications, ServiceIds};
use crate::machined::{machined, On, OnMachines};
use crate::messages::services::platform_specifications_service as generated;
use crate::messages::services::transport::event::Receive;
use crate::messages::{
    AckermannSpecifics, PlatformGeometry, PlatformPerformance, QueryPlatformSpecifications,
    ReportPlatformSpecifications, SkidSteerSpecifics, SteeringSpecifics,
};

/// The Platform Specifications service over the RA 3.3 Primitive Driver at an address,
/// on its generated machines.
pub type PlatformSpecificationsService = OnMachines<Platform>;

/// The Platform Specifications service's data: the RA 3.3 Primitive Driver.
#[derive(Debug)]
pub struct Platform {
    driver: Address,
}

impl PlatformSpecificationsService {
    /// The service over the RA 3.3 Primitive Driver at `driver` (whose specifications
    /// the gateway asked for, [`super::ask`]).
    pub fn new(driver: Address) -> Self {
        OnMachines::from_impl(Platform { driver })
    }
}

machined!(
    Platform,
    platform_specifications_service,
    ServiceIds::PLATFORM_SPECIFICATIONS,
    events
);

/// The top of AS-4's maximum rotational speed field, rad/s: the definition's `[0, 6.28]`
/// (not 2π).
#[allow(clippy::approx_constant)]
const MAX_ROTATIONAL_SPEED: f64 = 6.28;

/// `v` within `[lo, hi]` (a scaled field cannot carry more).
fn within(v: Option<f64>, lo: f64, hi: f64) -> Option<f64> {
    v.map(|v| v.clamp(lo, hi))
}

/// The AS-4 report of an RA 3.3 Report Platform Specifications (see the module's
/// table).
pub fn report(r: &ra::ReportPlatformSpecifications) -> ReportPlatformSpecifications {
    use std::f64::consts::PI;
    let metres = |v| within(v, 0.0, 30.0);
    let ackermann = r.turning_radius.is_some_and(|t| t > 0.0);
    let platform_specifics = if ackermann {
        SteeringSpecifics::Ackermann(AckermannSpecifics {
            min_turn_radius: within(r.turning_radius, 0.0, 25.0),
            wheel_separation: metres(r.track_width),
            ..Default::default()
        })
    } else {
        SteeringSpecifics::SkidSteer(SkidSteerSpecifics {
            track_separation: metres(r.track_width),
            ..Default::default()
        })
    };
    ReportPlatformSpecifications {
        platform_specifics,
        platform_inertial: PlatformPerformance {
            maximum_forward_speed: within(r.maximum_velocity_x, 0.0, 90.0),
            maximum_rotational_speed: within(r.maximum_yaw_rate, 0.0, MAX_ROTATIONAL_SPEED),
            ..Default::default()
        },
        platform_spec: PlatformGeometry {
            mobility_platform_name: r.platform_name.clone().unwrap_or_default(),
            front: metres(r.front),
            back: metres(r.back),
            right: metres(r.right),
            left: metres(r.left),
            bottom: metres(r.bottom),
            top: metres(r.top),
            cg_x: within(r.x_cg, -30.0, 30.0),
            cg_y: within(r.y_cg, -30.0, 30.0),
            cg_z: within(r.z_cg, -30.0, 30.0),
            wheel_base: within(r.wheel_base, 0.0, 60.0),
            static_pitch_over: within(r.pitch_over, -PI, PI),
            static_roll_over: within(r.roll_over, -PI, PI),
            ..Default::default()
        },
    }
}

impl generated::PlatformSpecificationsService for On<'_, Platform> {
    fn send_report_platform_specifications(
        &mut self,
        _msg: &QueryPlatformSpecifications,
        transport: &Receive,
    ) {
        match specifications(self.env, self.svc.driver) {
            Some(r) => {
                let report = report(r);
                self.reply(transport, report);
            }
            None => self.refuse(format!(
                "Query Platform Specifications: no Report Platform Specifications from the RA 3.3 Primitive Driver {} yet",
                self.svc.driver
            )),
        }
    }
}
