//! The sans-IO core of vehicle mode: JAUS reports → ROS 2 messages, ROS 2 commands →
//! JAUS messages, the `cmd_vel` watchdog's decisions and the roles of the vehicle's
//! components ([`role`]). Pure functions and a small state machine ([`CmdGate`]) fed
//! with the times the shell reads; nothing here reads a clock, a socket or a DDS
//! reader, and nothing panics on what the network sent.

use std::time::{Duration, Instant};

use jaus::components::{
    global_pose_sensor, global_waypoint_driver, local_pose_sensor, local_waypoint_driver,
    primitive_driver, velocity_state_sensor,
};
use jaus::messages::{
    ReportGlobalPose, ReportLocalPose, ReportVelocityState, SetGlobalWaypoint, SetLocalWaypoint,
    SetWrenchEffort,
};
use jaus::stock::geo::LocalFrame;
use jaus::stock::hardware::Wrench;
use jaus::stock::motion::wrench_message;
use jaus::stock::nalgebra::{UnitQuaternion, Vector2};

use crate::config::{EffortMapping, OdomAxes};
use crate::convert::{flu_to_frd, odom_to_local};
use crate::msg::{
    self, Header, NavSatFix, NavSatStatus, Odometry, Point, PoseStamped, Time, Twist,
};

fn finite(v: &[f64]) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// The short name of a component id the bridge gives a role (`PD`, `LPS`, ...).
pub fn role(id: u8) -> &'static str {
    match id {
        primitive_driver::ID => "PD",
        global_pose_sensor::ID => "GPS",
        local_pose_sensor::ID => "LPS",
        velocity_state_sensor::ID => "VSS",
        global_waypoint_driver::ID => "GWD",
        local_waypoint_driver::ID => "LWD",
        _ => "component",
    }
}

/// The ROS orientation (base_link in the ENU `odom` frame) of a JAUS attitude (vehicle
/// frame in the local north-east-down frame): R(NED→ENU) · q · R(FRD→FLU), both
/// rotations their own inverses.
pub fn ros_orientation(attitude: &UnitQuaternion<f64>) -> msg::Quaternion {
    let q = odom_to_local(OdomAxes::Enu) * attitude * flu_to_frd();
    msg::Quaternion {
        x: q.i,
        y: q.j,
        z: q.k,
        w: q.w,
    }
}

/// `nav_msgs/Odometry` of a Report Local Pose (and the latest Report Velocity State, if
/// any) in frames `frame`/`child`: position ENU = (JAUS y, JAUS x, −JAUS z), the
/// attitude by [`ros_orientation`], the twist in the base frame = (vx, −vy, −vz), rates
/// (p, −q, −r). Absent fields are 0; `None` when a present one is not finite or the
/// report has no position.
pub fn odometry_of(
    pose: &ReportLocalPose,
    velocity: Option<&ReportVelocityState>,
    stamp: Time,
    frame: &str,
    child: &str,
) -> Option<Odometry> {
    let g = |v: Option<f64>| v.unwrap_or(0.0);
    let (x, y) = (pose.x?, pose.y?);
    let (z, roll, pitch, yaw) = (g(pose.z), g(pose.roll), g(pose.pitch), g(pose.yaw));
    if !finite(&[x, y, z, roll, pitch, yaw]) {
        return None;
    }
    let mut o = Odometry {
        header: Header {
            stamp,
            frame_id: frame.to_string(),
        },
        child_frame_id: child.to_string(),
        ..Odometry::default()
    };
    o.pose.pose.position = Point { x: y, y: x, z: -z };
    o.pose.pose.orientation = ros_orientation(&UnitQuaternion::from_euler_angles(roll, pitch, yaw));
    if let Some(v) = velocity {
        let lin = [g(v.velocity_x), g(v.velocity_y), g(v.velocity_z)];
        let rot = [g(v.roll_rate), g(v.pitch_rate), g(v.yaw_rate)];
        if !finite(&lin) || !finite(&rot) {
            return None;
        }
        // `+ 0.0`: no −0 on the wire.
        o.twist.twist.linear = msg::Vector3 {
            x: lin[0],
            y: -lin[1] + 0.0,
            z: -lin[2] + 0.0,
        };
        o.twist.twist.angular = msg::Vector3 {
            x: rot[0],
            y: -rot[1] + 0.0,
            z: -rot[2] + 0.0,
        };
    }
    // Unknown covariances: −1 on the diagonal's first element is REP-145's "ignore";
    // here the RMS, when reported, on the diagonal.
    if let Some(rms) = pose.position_rms.filter(|r| r.is_finite()) {
        for i in [0, 7, 14] {
            o.pose.covariance.0[i] = rms * rms / 3.0;
        }
    }
    if let Some(rms) = pose.attitude_rms.filter(|r| r.is_finite()) {
        for i in [21, 28, 35] {
            o.pose.covariance.0[i] = rms * rms / 3.0;
        }
    }
    Some(o)
}

/// `sensor_msgs/NavSatFix` of a Report Global Pose: latitude, longitude, altitude =
/// elevation (0 when absent); the position RMS spread over the three axes as an
/// approximated diagonal covariance (type UNKNOWN without one); status FIX, service
/// GPS. `None` without a finite latitude and longitude in range.
pub fn nav_sat_fix_of(g: &ReportGlobalPose, stamp: Time, frame: &str) -> Option<NavSatFix> {
    let (lat, lon) = (g.latitude?, g.longitude?);
    if !finite(&[lat, lon]) || lat.abs() > 90.0 || lon.abs() > 180.0 {
        return None;
    }
    let mut f = NavSatFix {
        header: Header {
            stamp,
            frame_id: frame.to_string(),
        },
        status: NavSatStatus {
            status: 0,
            service: 1,
        },
        latitude: lat,
        longitude: lon,
        altitude: g.elevation.filter(|e| e.is_finite()).unwrap_or(0.0),
        ..NavSatFix::default()
    };
    if let Some(rms) = g.position_rms.filter(|r| r.is_finite() && *r >= 0.0) {
        let var = rms * rms / 3.0;
        f.position_covariance = [var, 0.0, 0.0, 0.0, var, 0.0, 0.0, 0.0, var];
        f.position_covariance_type = 1;
    }
    Some(f)
}

/// The Set Wrench Effort for a `cmd_vel`: `linear.x / max_linear` → propulsive linear
/// effort x (%), `−angular.z / max_angular` → propulsive rotational effort z (% : JAUS
/// +z is down, so + turns right), each clamped to ±100 %; a twist that is not finite is
/// zero effort. The other axes of a ground vehicle are not sent.
pub fn wrench_of_twist(t: &Twist, m: &EffortMapping) -> SetWrenchEffort {
    let pct = |v: f64, max: f64| {
        let p = v / max * 100.0;
        if p.is_finite() {
            p.clamp(-100.0, 100.0) + 0.0
        } else {
            0.0
        }
    };
    let mut w = Wrench::ZERO;
    if finite(&[t.linear.x, t.angular.z]) {
        w.linear.x = pct(t.linear.x, m.max_linear);
        w.rotational.z = pct(-t.angular.z, m.max_angular);
    }
    wrench_message(&w)
}

/// Zero efforts (the vehicle coasts to a stop; the stock driver brakes at once).
pub fn zero_wrench() -> SetWrenchEffort {
    wrench_message(&Wrench::ZERO)
}

/// A `goal_pose` as a Local Waypoint: the goal is in the `odom` frame this bridge
/// publishes, which is the vehicle's local frame turned ENU, so x north = goal y,
/// y east = goal x. `None` when not finite.
pub fn local_waypoint_of(goal: &PoseStamped) -> Option<SetLocalWaypoint> {
    let p = goal.pose.position;
    finite(&[p.x, p.y]).then(|| SetLocalWaypoint {
        waypoint_number: 0,
        x: p.y,
        y: p.x,
        ..SetLocalWaypoint::default()
    })
}

/// A `goal_pose` as a Global Waypoint: the goal in an ENU frame anchored at `origin`
/// (the first fix), east x and north y metres from it. `None` when not finite.
pub fn global_waypoint_of(goal: &PoseStamped, origin: &LocalFrame) -> Option<SetGlobalWaypoint> {
    let p = goal.pose.position;
    if !finite(&[p.x, p.y]) {
        return None;
    }
    let (latitude, longitude) = origin.to_global(Vector2::new(p.y, p.x));
    (finite(&[latitude, longitude]) && latitude.abs() <= 90.0).then_some(SetGlobalWaypoint {
        waypoint_number: 0,
        latitude,
        longitude,
        ..SetGlobalWaypoint::default()
    })
}

/// What the `cmd_vel` gate wants sent at a tick.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GateAction {
    /// Nothing.
    Idle,
    /// Send this command (a new `cmd_vel`, or its refresh).
    Drive(Twist),
    /// The watchdog fired: send zero efforts once.
    Stop,
}

/// The `cmd_vel` watchdog and refresh, sans IO: the latest twist and when it arrived in,
/// what to send out. A command is refreshed every `refresh` (the Primitive Driver's own
/// command timeout is shorter than a silent ROS node's), and `timeout` after the last
/// `cmd_vel` zero efforts go once.
#[derive(Debug, Clone)]
pub struct CmdGate {
    timeout: Duration,
    refresh: Duration,
    latest: Option<(Twist, Instant)>,
    sent_at: Option<Instant>,
    stopped: bool,
}

impl CmdGate {
    /// A gate stopping `timeout` after the last command, refreshing every `refresh`.
    pub fn new(timeout: Duration, refresh: Duration) -> Self {
        CmdGate {
            timeout,
            refresh,
            latest: None,
            sent_at: None,
            stopped: true,
        }
    }

    /// A `cmd_vel` arrived at `at`.
    pub fn command(&mut self, t: Twist, at: Instant) {
        self.latest = Some((t, at));
        self.sent_at = None;
        self.stopped = false;
    }

    /// The command [`tick`](Self::tick) gave could not be sent (control not held yet):
    /// give it again at the next tick instead of a refresh period later.
    pub fn unsent(&mut self) {
        self.sent_at = None;
    }

    /// Whether commands are flowing (a `cmd_vel` within the timeout).
    pub fn active(&self) -> bool {
        !self.stopped
    }

    /// What to send at `now`.
    pub fn tick(&mut self, now: Instant) -> GateAction {
        let Some((t, at)) = self.latest else {
            return GateAction::Idle;
        };
        if self.stopped {
            return GateAction::Idle;
        }
        if now.saturating_duration_since(at) > self.timeout {
            self.stopped = true;
            return GateAction::Stop;
        }
        if self
            .sent_at
            .is_none_or(|s| now.saturating_duration_since(s) >= self.refresh)
        {
            self.sent_at = Some(now);
            return GateAction::Drive(t);
        }
        GateAction::Idle
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn local_pose_becomes_enu_odometry_and_back() {
        // 2 m north, 3 m east, 1 m up, facing east (JAUS yaw π/2).
        let pose = ReportLocalPose {
            x: Some(2.0),
            y: Some(3.0),
            z: Some(-1.0),
            yaw: Some(FRAC_PI_2),
            ..ReportLocalPose::default()
        };
        let vel = ReportVelocityState {
            velocity_x: Some(0.5),
            velocity_y: Some(0.1),
            yaw_rate: Some(0.2),
            ..ReportVelocityState::default()
        };
        let o = odometry_of(&pose, Some(&vel), Time::default(), "odom", "base_link").unwrap();
        let p = o.pose.pose.position;
        assert!(
            close(p.x, 3.0) && close(p.y, 2.0) && close(p.z, 1.0),
            "{p:?}"
        );
        // Facing east is ENU yaw 0: the identity.
        let q = o.pose.pose.orientation;
        assert!(close(q.w.abs(), 1.0), "{q:?}");
        assert!(close(o.twist.twist.linear.x, 0.5) && close(o.twist.twist.linear.y, -0.1));
        assert!(close(o.twist.twist.angular.z, -0.2));
        // The robot mode's conversion inverts it.
        let (back, v) = crate::convert::odometry_to_jaus(&o, OdomAxes::Enu).unwrap();
        assert!(close(back.position.x, 2.0) && close(back.position.y, 3.0));
        assert!(close(back.yaw(), FRAC_PI_2), "{}", back.yaw());
        assert!(close(v.angular.z, 0.2));
        assert_eq!(
            (o.header.frame_id.as_str(), o.child_frame_id.as_str()),
            ("odom", "base_link")
        );
    }

    #[test]
    fn garbage_reports_are_refused() {
        let mut pose = ReportLocalPose {
            x: Some(f64::NAN),
            y: Some(0.0),
            ..ReportLocalPose::default()
        };
        assert!(odometry_of(&pose, None, Time::default(), "odom", "base_link").is_none());
        pose.x = None;
        assert!(odometry_of(&pose, None, Time::default(), "odom", "base_link").is_none());
        let g = ReportGlobalPose {
            latitude: Some(95.0),
            longitude: Some(0.0),
            ..ReportGlobalPose::default()
        };
        assert!(nav_sat_fix_of(&g, Time::default(), "gps").is_none());
        let g = ReportGlobalPose {
            latitude: Some(29.6),
            longitude: Some(-82.3),
            position_rms: Some(3.0),
            ..ReportGlobalPose::default()
        };
        let f = nav_sat_fix_of(&g, Time::default(), "gps").unwrap();
        assert!(close(f.position_covariance[0], 3.0) && f.position_covariance_type == 1);
        assert_eq!(f.altitude, 0.0);
    }

    #[test]
    fn twists_become_clamped_efforts() {
        let m = EffortMapping {
            max_linear: 2.0,
            max_angular: 0.5,
        };
        let mut t = Twist::ZERO;
        t.linear.x = 1.0;
        t.angular.z = 0.25; // ROS: turn left
        let w = wrench_of_twist(&t, &m);
        assert_eq!(w.propulsive_linear_effort_x, Some(50.0));
        assert_eq!(w.propulsive_rotational_effort_z, Some(-50.0));
        t.linear.x = -9.0;
        assert_eq!(
            wrench_of_twist(&t, &m).propulsive_linear_effort_x,
            Some(-100.0)
        );
        t.angular.z = f64::NAN;
        let w = wrench_of_twist(&t, &m);
        assert_eq!(w.propulsive_linear_effort_x, Some(0.0));
        // Round trip through the robot mode's mapping.
        let mut t = Twist::ZERO;
        t.linear.x = 0.6;
        t.angular.z = -0.1;
        let back = crate::convert::twist_of(
            &jaus::stock::motion::wrench_of(&wrench_of_twist(&t, &m)),
            &m,
        );
        assert!(
            close(back.linear.x, 0.6) && close(back.angular.z, -0.1),
            "{back:?}"
        );
    }

    #[test]
    fn goals_become_waypoints() {
        let mut g = PoseStamped::default();
        g.pose.position.x = 10.0; // east
        g.pose.position.y = 5.0; // north
        let l = local_waypoint_of(&g).unwrap();
        assert_eq!((l.x, l.y), (5.0, 10.0));
        let origin = LocalFrame::new(29.6436, -82.3549, 0.0);
        let w = global_waypoint_of(&g, &origin).unwrap();
        let back = origin.to_local(w.latitude, w.longitude);
        assert!((back.x - 5.0).abs() < 1e-6 && (back.y - 10.0).abs() < 1e-6);
        g.pose.position.x = f64::INFINITY;
        assert!(local_waypoint_of(&g).is_none() && global_waypoint_of(&g, &origin).is_none());
    }

    #[test]
    fn the_gate_refreshes_then_stops_once() {
        let t0 = Instant::now();
        let ms = Duration::from_millis;
        let mut gate = CmdGate::new(ms(500), ms(100));
        assert_eq!(gate.tick(t0), GateAction::Idle);
        let mut t = Twist::ZERO;
        t.linear.x = 0.5;
        gate.command(t, t0);
        assert_eq!(gate.tick(t0), GateAction::Drive(t));
        assert_eq!(gate.tick(t0 + ms(50)), GateAction::Idle);
        assert_eq!(gate.tick(t0 + ms(100)), GateAction::Drive(t));
        assert!(gate.active());
        assert_eq!(gate.tick(t0 + ms(501)), GateAction::Stop);
        assert!(!gate.active());
        assert_eq!(gate.tick(t0 + ms(700)), GateAction::Idle);
        gate.command(t, t0 + ms(800));
        assert_eq!(gate.tick(t0 + ms(800)), GateAction::Drive(t));
    }
}
