//! Local services of an RA 3.3 subsystem that has only global ones: a Local Pose Sensor
//! over its Global Pose Sensor and a Local Waypoint List Driver over its Global Waypoint
//! Driver (OpenJAUS 3.3's vehicle simulator has no local pose sensor and no local
//! waypoint driver, and the IOP scenario asks for both).
//!
//! The RA 3.3 local frame of such a subsystem is a tangent plane (x north, y east, the
//! SDK's [`LocalFrame`]) placed at the first global position its Global Pose Sensor
//! reports ([`Ra33Side::tangent`]); the AS-4 local frame sits on it as on a real RA 3.3
//! local frame (Set Local Pose moves it, [`Ra33Side::frame`]). A local waypoint goes to
//! the Global Waypoint Driver as the latitude and longitude of its point in that plane.

use jaus::messages as ra;
use jaus::stock::geo::LocalFrame;
use jaus::stock::nalgebra::Vector2;
use jaus::{CommandCode, JausMessage};

use super::lists::{self, list_machines, Goal, Kind, ListDriver, DEFAULT_TOLERANCE};
use super::ServiceIds;
use crate::machined::OnMachines;
use crate::messages::{QueryLocalWaypoint, SetLocalWaypoint};
use crate::ra33::Ra33Side;
use crate::service::ServiceId;
use crate::Message;

/// Why a local position cannot be had yet.
const NO_FIX: &str =
    "no global position from the RA 3.3 Global Pose Sensor yet (the local frame is placed at the first one)";

/// The vehicle's pose in the tangent plane, as the Local Pose Sensor it lacks would
/// report it: x and y from its latitude and longitude, its attitude and time as they
/// are. `None` before the first global position.
pub fn local_pose(side: &Ra33Side) -> Option<ra::ReportLocalPose> {
    let plane = side.tangent()?;
    let gps = side.targets().global_pose_sensor?;
    let Some((_, ra::Message::ReportGlobalPose(g))) = side.latest(gps, ra::ReportGlobalPose::CODE)
    else {
        return None;
    };
    let p = plane.to_local(g.latitude?, g.longitude?);
    Some(ra::ReportLocalPose {
        x: Some(p.x),
        y: Some(p.y),
        z: None,
        position_rms: g.position_rms,
        roll: g.roll,
        pitch: g.pitch,
        yaw: g.yaw,
        attitude_rms: g.attitude_rms,
        time_stamp: g.time_stamp,
    })
}

/// Local waypoints driven by a Global Waypoint Driver.
#[derive(Debug)]
pub struct LocalOnGlobal;

/// The Local Waypoint List Driver over an RA 3.3 Global Waypoint Driver.
pub type LocalWaypointListDriverOnGlobal = OnMachines<ListDriver<LocalOnGlobal>>;

impl LocalOnGlobal {
    fn plane(side: &Ra33Side) -> Result<&LocalFrame, String> {
        side.tangent().ok_or_else(|| NO_FIX.to_string())
    }
}

impl Kind for LocalOnGlobal {
    type Element = SetLocalWaypoint;
    const ID: ServiceId = ServiceIds::LOCAL_WAYPOINT_LIST_DRIVER;
    const QUERY: CommandCode = QueryLocalWaypoint::CODE;
    const COUNT: CommandCode = ra::ReportWaypointCount::CODE;
    list_machines!(local_waypoint_list_driver);

    fn element(m: &Message) -> Option<SetLocalWaypoint> {
        lists::Local::element(m)
    }

    fn to_ra33(
        w: &SetLocalWaypoint,
        number: u16,
        side: &Ra33Side,
    ) -> Result<(ra::Message, Goal), String> {
        let plane = Self::plane(side)?;
        let (x, y) = side.frame.to_ra33(w.x, w.y);
        let (latitude, longitude) = plane.to_global(Vector2::new(x, y));
        let m = ra::SetGlobalWaypoint {
            waypoint_number: number,
            latitude,
            longitude,
            elevation: None,
            roll: w.roll,
            pitch: w.pitch,
            yaw: w.yaw.map(|a| side.frame.yaw_to_ra33(a)),
        };
        Ok((
            m.into(),
            Goal::point([x, y], w.waypoint_tolerance.unwrap_or(DEFAULT_TOLERANCE)),
        ))
    }

    fn count_query() -> ra::Message {
        lists::Local::count_query()
    }

    fn count(report: &ra::Message) -> Option<u16> {
        lists::Local::count(report)
    }

    fn position(side: &Ra33Side) -> Option<[f64; 2]> {
        let p = local_pose(side)?;
        Some([p.x?, p.y?])
    }

    fn offset(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
        lists::Local::offset(a, b)
    }

    fn report(w: &SetLocalWaypoint, query: &Message) -> Message {
        lists::Local::report(w, query)
    }
}

#[cfg(test)]
mod tests {
    use std::time::{Duration, Instant};

    use jaus::Address;

    use super::*;
    use crate::ra33::{Frame, Targets};

    fn side_with_fix(lat: f64, lon: f64) -> Ra33Side {
        let gps = Address::new(10, 1, 38, 1);
        let targets = Targets {
            global_pose_sensor: Some(gps),
            ..Targets::default()
        };
        let mut side = Ra33Side::new(
            Address::new(30, 1, 60, 1),
            targets,
            200,
            Duration::from_millis(100),
        );
        side.on_message(
            Instant::now(),
            gps,
            ra::ReportGlobalPose {
                latitude: Some(lat),
                longitude: Some(lon),
                yaw: Some(0.5),
                ..Default::default()
            }
            .into(),
        );
        side
    }

    #[test]
    fn the_frame_is_placed_at_the_first_fix_and_waypoints_become_global() {
        let none = Ra33Side::new(
            Address::new(30, 1, 60, 1),
            Targets::default(),
            200,
            Duration::from_millis(100),
        );
        let w = SetLocalWaypoint {
            x: 20.0,
            y: 0.0,
            ..Default::default()
        };
        assert!(LocalOnGlobal::to_ra33(&w, 0, &none)
            .unwrap_err()
            .contains("no global position"));

        let mut side = side_with_fix(37.2136, -80.4376);
        let p = local_pose(&side).expect("a local pose from the fix");
        assert!(p.x.unwrap().abs() < 1e-6 && p.y.unwrap().abs() < 1e-6);
        assert_eq!(p.yaw, Some(0.5));
        // 20 m north in the AS-4 frame that Set Local Pose placed a quarter turn round.
        side.frame = Frame::placing(0.0, 0.0, 0.0, 0.0, 0.0, std::f64::consts::FRAC_PI_2);
        let (m, goal) = LocalOnGlobal::to_ra33(&w, 2, &side).expect("a global waypoint");
        let ra::Message::SetGlobalWaypoint(g) = m else {
            panic!("Set Global Waypoint expected, got {m:?}")
        };
        assert_eq!(g.waypoint_number, 2);
        let back = side.tangent().unwrap().to_local(g.latitude, g.longitude);
        assert!((back.x - goal.at[0]).abs() < 1e-6 && (back.y - goal.at[1]).abs() < 1e-6);
        assert!((back.norm() - 20.0).abs() < 1e-6, "{back:?}");
        assert_eq!(goal.tolerance, DEFAULT_TOLERANCE);
        // A second fix does not move the plane.
        let moved = side.tangent().copied();
        side.on_message(
            Instant::now(),
            Address::new(10, 1, 38, 1),
            ra::ReportGlobalPose {
                latitude: Some(37.2137),
                longitude: Some(-80.4376),
                ..Default::default()
            }
            .into(),
        );
        assert_eq!(side.tangent().copied(), moved);
        let p = local_pose(&side).unwrap();
        assert!((p.x.unwrap() - 11.1).abs() < 0.1, "{p:?}");
    }
}
