//! Units and frames between ROS 2 (REP-103/105: base x forward, y left, z up; world
//! frames east, north, up) and the SDK's JAUS conventions (local frame x north, y east,
//! z down; vehicle frame x forward, y right, z down; yaw 0 along +x, growing toward +y).
//!
//! Every function here is pure and refuses (returns `None` for) a message that is not
//! finite, so that nothing a ROS node sends can make a JAUS report fail to encode.

use jaus::stock::hardware::{GlobalPose, LocalPose, VelocityState, Wrench};
use jaus::stock::nalgebra::{Matrix3, Quaternion, Rotation3, UnitQuaternion, Vector3};

use crate::config::{EffortMapping, OdomAxes};
use crate::msg::{self, NavSatFix, NavSatStatus, Odometry, Twist};

/// The rotation taking ROS base-frame vectors (x forward, y left, z up) to the JAUS
/// vehicle frame (x forward, y right, z down): π about x.
pub(crate) fn flu_to_frd() -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
}

/// The rotation taking vectors of the ROS odometry frame to the JAUS local frame.
pub(crate) fn odom_to_local(axes: OdomAxes) -> UnitQuaternion<f64> {
    match axes {
        // x_n = y_e, y_e = x_e, z_d = −z_u: a proper rotation (det +1).
        OdomAxes::Enu => UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(
            Matrix3::new(0.0, 1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, -1.0),
        )),
        OdomAxes::Flu => flu_to_frd(),
    }
}

fn finite3(v: &Vector3<f64>) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// A ROS vector in REP-103 base axes as a JAUS vehicle-frame vector.
pub fn base_to_vehicle(v: &msg::Vector3) -> Vector3<f64> {
    Vector3::new(v.x, -v.y, -v.z)
}

/// The attitude of a ROS orientation (base frame in the odometry frame) as the SDK's
/// attitude (vehicle frame in the JAUS local frame), or `None` when it is not finite
/// or has no length.
pub fn attitude_of(q: &msg::Quaternion, axes: OdomAxes) -> Option<UnitQuaternion<f64>> {
    let raw = Quaternion::new(q.w, q.x, q.y, q.z);
    if !raw.coords.iter().all(|c| c.is_finite()) || raw.norm() < 1e-9 {
        return None;
    }
    let ros = UnitQuaternion::from_quaternion(raw);
    // local←vehicle = (local←odom) · (odom←base) · (base←vehicle); base←vehicle is its
    // own inverse.
    Some(odom_to_local(axes) * ros * flu_to_frd())
}

/// The local pose and velocity state of an odometry message, or `None` when any
/// number in them is not finite.
pub fn odometry_to_jaus(o: &Odometry, axes: OdomAxes) -> Option<(LocalPose, VelocityState)> {
    let p = &o.pose.pose.position;
    let position = odom_to_local(axes) * Vector3::new(p.x, p.y, p.z);
    let attitude = attitude_of(&o.pose.pose.orientation, axes)?;
    let velocity = VelocityState {
        linear: base_to_vehicle(&o.twist.twist.linear),
        angular: base_to_vehicle(&o.twist.twist.angular),
    };
    (finite3(&position) && finite3(&velocity.linear) && finite3(&velocity.angular))
        .then_some((LocalPose { position, attitude }, velocity))
}

/// Position RMS reported when the fix gives no covariance: the most Report Global Pose
/// can carry (its field saturates at 100 m).
pub const UNKNOWN_POSITION_RMS: f64 = 100.0;

/// The global pose of a fix, with `attitude` (the latest odometry's, when its frame is
/// earth-aligned; the identity otherwise), or `None` without a fix (status −1) or with
/// a position that is not a WGS 84 latitude and longitude. An unknown (NaN) altitude
/// is reported as 0.
pub fn fix_to_jaus(f: &NavSatFix, attitude: UnitQuaternion<f64>) -> Option<GlobalPose> {
    let in_range = f.latitude.is_finite()
        && f.longitude.is_finite()
        && f.latitude.abs() <= 90.0
        && f.longitude.abs() <= 180.0;
    if f.status.status <= NavSatStatus::NO_FIX || !in_range {
        return None;
    }
    let c = &f.position_covariance;
    let var = c[0] + c[4] + c[8];
    let position_rms = if f.position_covariance_type == NavSatFix::COVARIANCE_UNKNOWN
        || !var.is_finite()
        || var < 0.0
    {
        UNKNOWN_POSITION_RMS
    } else {
        var.sqrt()
    };
    Some(GlobalPose {
        latitude: f.latitude,
        longitude: f.longitude,
        elevation: if f.altitude.is_finite() {
            f.altitude
        } else {
            0.0
        },
        attitude,
        position_rms,
    })
}

/// The `cmd_vel` for a wrench effort: each propulsive effort (%) scaled to
/// `max_linear`/`max_angular`, times what its axis' resistive effort leaves
/// (100 % brakes: 0), turned from the JAUS vehicle frame into ROS base axes. Anything
/// not finite gives a zero twist.
pub fn twist_of(w: &Wrench, m: &EffortMapping) -> Twist {
    let left = |r: f64| 1.0 - r.clamp(0.0, 100.0) / 100.0;
    let axis =
        |effort: f64, brake: f64, max: f64| effort.clamp(-100.0, 100.0) / 100.0 * max * left(brake);
    let lin = |i: usize| axis(w.linear[i], w.resistive_linear[i], m.max_linear);
    let rot = |i: usize| axis(w.rotational[i], w.resistive_rotational[i], m.max_angular);
    // JAUS vehicle (forward, right, down) → ROS base (forward, left, up). `+ 0.0` turns
    // a −0 into 0, so that a stop is an all-zero message.
    let t = Twist {
        linear: msg::Vector3 {
            x: lin(0) + 0.0,
            y: -lin(1) + 0.0,
            z: -lin(2) + 0.0,
        },
        angular: msg::Vector3 {
            x: rot(0) + 0.0,
            y: -rot(1) + 0.0,
            z: -rot(2) + 0.0,
        },
    };
    let all = [
        t.linear.x,
        t.linear.y,
        t.linear.z,
        t.angular.x,
        t.angular.y,
        t.angular.z,
    ];
    if all.iter().all(|v| v.is_finite()) {
        t
    } else {
        Twist::ZERO
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn yaw_quat(yaw: f64) -> msg::Quaternion {
        msg::Quaternion {
            x: 0.0,
            y: 0.0,
            z: (yaw / 2.0).sin(),
            w: (yaw / 2.0).cos(),
        }
    }

    fn odom(x: f64, y: f64, yaw: f64) -> Odometry {
        let mut o = Odometry::default();
        o.pose.pose.position = msg::Point { x, y, z: 1.0 };
        o.pose.pose.orientation = yaw_quat(yaw);
        o.twist.twist.linear.x = 0.5;
        o.twist.twist.linear.y = 0.1;
        o.twist.twist.angular.z = 0.2;
        o
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn enu_odometry_becomes_ned() {
        // 3 m east, 2 m north, 1 m up, facing north (ENU yaw π/2).
        let (p, v) = odometry_to_jaus(&odom(3.0, 2.0, FRAC_PI_2), OdomAxes::Enu).unwrap();
        assert!(close(p.position.x, 2.0) && close(p.position.y, 3.0) && close(p.position.z, -1.0));
        // Facing north is JAUS yaw 0; facing east (ENU yaw 0) is JAUS π/2.
        assert!(close(p.yaw(), 0.0), "{}", p.yaw());
        let (east, _) = odometry_to_jaus(&odom(0.0, 0.0, 0.0), OdomAxes::Enu).unwrap();
        assert!(close(east.yaw(), FRAC_PI_2), "{}", east.yaw());
        let (roll, pitch, _) = east.attitude.euler_angles();
        assert!(close(roll, 0.0) && close(pitch, 0.0));
        // Twist in the base frame: forward stays, left becomes −right, CCW becomes −CW.
        assert!(close(v.linear.x, 0.5) && close(v.linear.y, -0.1));
        assert!(close(v.angular.z, -0.2));
    }

    #[test]
    fn flu_odometry_mirrors_y() {
        let (p, _) = odometry_to_jaus(&odom(3.0, 2.0, 0.3), OdomAxes::Flu).unwrap();
        assert!(close(p.position.x, 3.0) && close(p.position.y, -2.0) && close(p.position.z, -1.0));
        assert!(close(p.yaw(), -0.3), "{}", p.yaw());
    }

    #[test]
    fn pitch_and_roll_keep_their_sense() {
        // Nose up in ROS (negative pitch about y-left) is nose up in JAUS (positive
        // pitch about y-right).
        let q = UnitQuaternion::from_euler_angles(0.1, -0.2, 0.0);
        let m = msg::Quaternion {
            x: q.i,
            y: q.j,
            z: q.k,
            w: q.w,
        };
        let a = attitude_of(&m, OdomAxes::Flu).unwrap();
        let (r, p, y) = a.euler_angles();
        assert!(
            close(r, 0.1) && close(p, 0.2) && close(y, 0.0),
            "{r} {p} {y}"
        );
    }

    #[test]
    fn garbage_odometry_is_refused() {
        let mut o = odom(f64::NAN, 0.0, 0.0);
        assert!(odometry_to_jaus(&o, OdomAxes::Enu).is_none());
        o = odom(0.0, 0.0, 0.0);
        o.pose.pose.orientation = msg::Quaternion {
            x: 0.0,
            y: 0.0,
            z: 0.0,
            w: 0.0,
        };
        assert!(odometry_to_jaus(&o, OdomAxes::Enu).is_none());
        o = odom(0.0, 0.0, 0.0);
        o.twist.twist.angular.x = f64::INFINITY;
        assert!(odometry_to_jaus(&o, OdomAxes::Enu).is_none());
    }

    #[test]
    fn efforts_scale_and_brake() {
        let m = EffortMapping {
            max_linear: 2.0,
            max_angular: 0.5,
        };
        let mut w = Wrench::ZERO;
        w.linear.x = 50.0;
        w.rotational.z = 100.0; // JAUS: turn right
        let t = twist_of(&w, &m);
        assert!(close(t.linear.x, 1.0) && close(t.angular.z, -0.5));
        w.resistive_linear.x = 50.0;
        assert!(close(twist_of(&w, &m).linear.x, 0.5));
        let stop = twist_of(&Wrench::brake(), &m);
        assert!(stop.is_zero(), "{stop:?}");
        assert!(twist_of(&Wrench::ZERO, &m).is_zero());
        w.linear.y = f64::NAN;
        assert!(twist_of(&w, &m).is_zero());
    }

    #[test]
    fn fixes_map_or_are_refused() {
        let mut f = NavSatFix {
            latitude: 29.65,
            longitude: -82.32,
            altitude: f64::NAN,
            ..NavSatFix::default()
        };
        let g = fix_to_jaus(&f, UnitQuaternion::identity()).unwrap();
        assert_eq!((g.elevation, g.position_rms), (0.0, UNKNOWN_POSITION_RMS));
        f.position_covariance = [4.0, 0.0, 0.0, 0.0, 4.0, 0.0, 0.0, 0.0, 1.0];
        f.position_covariance_type = 2;
        assert!(close(
            fix_to_jaus(&f, UnitQuaternion::identity())
                .unwrap()
                .position_rms,
            3.0
        ));
        f.status.status = NavSatStatus::NO_FIX;
        assert!(fix_to_jaus(&f, UnitQuaternion::identity()).is_none());
        f.status.status = 0;
        f.latitude = 91.0;
        assert!(fix_to_jaus(&f, UnitQuaternion::identity()).is_none());
    }
}
