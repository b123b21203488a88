//! The Local and Global Path Segment Drivers over RA 3.3 path segment drivers: list
//! drivers like the waypoint ones ([`super::lists`], whose machinery they use), their
//! List Manager elements holding Set Local (or Global) Path Segment messages.
//!
//! AS-4 and RA 3.3 define a segment alike: a curve from P0 (the vehicle's position for
//! the first segment, the previous segment's P2 after) through control point P1 to P2,
//! shaped by the weighting factor (0: a straight line to P2). Execute List sends the
//! elements as numbered RA 3.3 Set Path Segment messages (local ones with P1 and P2
//! moved from the AS-4 local frame into the RA 3.3 one) and the travel speed, and polls
//! Query Path Segment Count. An element is reached at its P2, within its path tolerance
//! when one above 0 is given ([`DEFAULT_TOLERANCE`] otherwise), or once passed along the
//! start of the next segment (toward its P1, or its P2 when straight). Query Local (or
//! Global) Path Segment answers the active element's segment.

use jaus::messages as ra;
use jaus::{CommandCode, JausMessage};

use super::lists::{self, list_machines, Goal, Kind, ListDriver, DEFAULT_TOLERANCE};
use super::ServiceIds;
use crate::machined::OnMachines;
use crate::messages::{
    QueryGlobalPathSegment, QueryLocalPathSegment, ReportGlobalPathSegment, ReportLocalPathSegment,
    SetGlobalPathSegment, SetLocalPathSegment,
};
use crate::ra33::Ra33Side;
use crate::service::ServiceId;
use crate::Message;

/// Path segments in the local frame.
#[derive(Debug)]
pub struct LocalSegments;

/// Path segments as latitude and longitude.
#[derive(Debug)]
pub struct GlobalSegments;

/// The Local Path Segment Driver.
pub type LocalPathSegmentDriver = OnMachines<ListDriver<LocalSegments>>;
/// The Global Path Segment Driver.
pub type GlobalPathSegmentDriver = OnMachines<ListDriver<GlobalSegments>>;

/// How close to P2 counts as reached: the path tolerance when one above 0 is given.
fn tolerance(path_tolerance: Option<f64>) -> f64 {
    path_tolerance
        .filter(|t| *t > 0.0)
        .unwrap_or(DEFAULT_TOLERANCE)
}

/// Where a segment with control point `p1`, end `p2` and weighting `w1` takes the
/// vehicle: P2, heading first for P1 (for P2 when the segment is straight).
fn goal(p1: [f64; 2], p2: [f64; 2], w1: f64, path_tolerance: Option<f64>) -> Goal {
    Goal {
        at: p2,
        toward: if w1 > 0.0 { p1 } else { p2 },
        tolerance: tolerance(path_tolerance),
    }
}

/// The count of an RA 3.3 Report Path Segment Count.
fn segment_count(report: &ra::Message) -> Option<u16> {
    match report {
        ra::Message::ReportPathSegmentCount(c) => Some(c.path_segment_count),
        _ => None,
    }
}

impl Kind for LocalSegments {
    type Element = SetLocalPathSegment;
    const ID: ServiceId = ServiceIds::LOCAL_PATH_SEGMENT_DRIVER;
    const QUERY: CommandCode = QueryLocalPathSegment::CODE;
    const COUNT: CommandCode = ra::ReportPathSegmentCount::CODE;
    list_machines!(local_path_segment_driver);

    fn element(m: &Message) -> Option<SetLocalPathSegment> {
        match m {
            Message::SetLocalPathSegment(s) => Some(s.clone()),
            _ => None,
        }
    }

    fn to_ra33(
        s: &SetLocalPathSegment,
        number: u16,
        side: &Ra33Side,
    ) -> Result<(ra::Message, Goal), String> {
        let (p1_x, p1_y) = side.frame.to_ra33(s.p1_x, s.p1_y);
        let (p2_x, p2_y) = side.frame.to_ra33(s.p2_x, s.p2_y);
        let m = ra::SetLocalPathSegment {
            path_segment_number: number,
            p1_x,
            p1_y,
            p1_z: s.p1_z,
            p2_x,
            p2_y,
            p2_z: s.p2_z,
            weighting_factor: s.weighting_factor,
        };
        let g = goal(
            [p1_x, p1_y],
            [p2_x, p2_y],
            s.weighting_factor,
            s.path_tolerance,
        );
        Ok((m.into(), g))
    }

    fn count_query() -> ra::Message {
        ra::QueryPathSegmentCount {}.into()
    }

    fn count(report: &ra::Message) -> Option<u16> {
        segment_count(report)
    }

    fn position(side: &Ra33Side) -> Option<[f64; 2]> {
        lists::Local::position(side)
    }

    fn offset(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
        lists::Local::offset(a, b)
    }

    fn report(s: &SetLocalPathSegment, query: &Message) -> Message {
        let mut r = ReportLocalPathSegment {
            p1_x: s.p1_x,
            p1_y: s.p1_y,
            p1_z: s.p1_z,
            p2_x: s.p2_x,
            p2_y: s.p2_y,
            p2_z: s.p2_z,
            weighting_factor: s.weighting_factor,
            path_tolerance: s.path_tolerance,
        };
        if let Message::QueryLocalPathSegment(q) = query {
            jaus::codec::Encode::keep_present(&mut r, u64::from(q.presence_vector));
        }
        r.into()
    }
}

impl Kind for GlobalSegments {
    type Element = SetGlobalPathSegment;
    const ID: ServiceId = ServiceIds::GLOBAL_PATH_SEGMENT_DRIVER;
    const QUERY: CommandCode = QueryGlobalPathSegment::CODE;
    const COUNT: CommandCode = ra::ReportPathSegmentCount::CODE;
    list_machines!(global_path_segment_driver);

    fn element(m: &Message) -> Option<SetGlobalPathSegment> {
        match m {
            Message::SetGlobalPathSegment(s) => Some(s.clone()),
            _ => None,
        }
    }

    fn to_ra33(
        s: &SetGlobalPathSegment,
        number: u16,
        _side: &Ra33Side,
    ) -> Result<(ra::Message, Goal), String> {
        let m = ra::SetGlobalPathSegment {
            path_segment_number: number,
            p1_latitude: s.p1_latitude,
            p1_longitude: s.p1_longitude,
            p1_altitude: s.p1_altitude,
            p2_latitude: s.p2_latitude,
            p2_longitude: s.p2_longitude,
            p2_altitude: s.p2_altitude,
            weighting_factor: s.weighting_factor,
        };
        let g = goal(
            [s.p1_latitude, s.p1_longitude],
            [s.p2_latitude, s.p2_longitude],
            s.weighting_factor,
            s.path_tolerance,
        );
        Ok((m.into(), g))
    }

    fn count_query() -> ra::Message {
        ra::QueryPathSegmentCount {}.into()
    }

    fn count(report: &ra::Message) -> Option<u16> {
        segment_count(report)
    }

    fn position(side: &Ra33Side) -> Option<[f64; 2]> {
        lists::Global::position(side)
    }

    fn offset(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
        lists::Global::offset(a, b)
    }

    fn report(s: &SetGlobalPathSegment, query: &Message) -> Message {
        let mut r = ReportGlobalPathSegment {
            p1_latitude: s.p1_latitude,
            p1_longitude: s.p1_longitude,
            p1_altitude: s.p1_altitude,
            p2_latitude: s.p2_latitude,
            p2_longitude: s.p2_longitude,
            p2_altitude: s.p2_altitude,
            weighting_factor: s.weighting_factor,
            path_tolerance: s.path_tolerance,
        };
        if let Message::QueryGlobalPathSegment(q) = query {
            jaus::codec::Encode::keep_present(&mut r, u64::from(q.presence_vector));
        }
        r.into()
    }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use jaus::Address;

    use super::*;
    use crate::ra33::{Frame, Targets};

    fn side(frame: Frame) -> Ra33Side {
        let me = Address::new(1, 1, 60, 1);
        let mut s = Ra33Side::new(me, Targets::default(), 200, Duration::from_millis(100));
        s.frame = frame;
        s
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn a_local_segment_moves_into_the_ra33_frame() {
        // The AS-4 frame: the RA 3.3 origin at AS-4 (10, 20), turned a quarter left.
        let frame = Frame {
            x: 10.0,
            y: 20.0,
            yaw: std::f64::consts::FRAC_PI_2,
        };
        let s = SetLocalPathSegment {
            p1_x: 10.0,
            p1_y: 22.0,
            p1_z: Some(1.5),
            p2_x: 7.0,
            p2_y: 20.0,
            p2_z: None,
            weighting_factor: 0.5,
            path_tolerance: Some(0.3),
        };
        let (m, g) = LocalSegments::to_ra33(&s, 3, &side(frame)).expect("a local segment");
        let ra::Message::SetLocalPathSegment(r) = m else {
            panic!("Set Local Path Segment expected, got {m:?}")
        };
        // AS-4 (10, 22) is 2 m along the RA 3.3 X axis; (7, 20) 3 m along its -Y.
        assert_eq!(r.path_segment_number, 3);
        assert!(close(r.p1_x, 2.0) && close(r.p1_y, 0.0), "{r:?}");
        assert!(close(r.p2_x, 0.0) && close(r.p2_y, 3.0), "{r:?}");
        assert_eq!((r.p1_z, r.p2_z), (Some(1.5), None));
        assert!(close(r.weighting_factor, 0.5));
        // Back again: the same points.
        let (x, y) = frame.to_as4(r.p2_x, r.p2_y);
        assert!(close(x, 7.0) && close(y, 20.0));
        // Reached at P2 (RA 3.3 terms), heading first for P1, within the path tolerance.
        assert!(close(g.at[0], 0.0) && close(g.at[1], 3.0), "{g:?}");
        assert!(close(g.toward[0], 2.0) && close(g.toward[1], 0.0), "{g:?}");
        assert!(close(g.tolerance, 0.3));
    }

    #[test]
    fn a_straight_segment_heads_for_p2_and_no_tolerance_is_the_default() {
        let s = SetLocalPathSegment {
            p1_x: 1.0,
            p1_y: 1.0,
            p2_x: 4.0,
            p2_y: 0.0,
            weighting_factor: 0.0,
            path_tolerance: Some(0.0),
            ..Default::default()
        };
        let (_, g) =
            LocalSegments::to_ra33(&s, 0, &side(Frame::default())).expect("a local segment");
        assert_eq!(g.toward, g.at);
        assert!(close(g.at[0], 4.0) && close(g.at[1], 0.0));
        assert!(close(g.tolerance, DEFAULT_TOLERANCE));
        let g = GlobalSegments::to_ra33(
            &SetGlobalPathSegment {
                p2_latitude: 29.6,
                p2_longitude: -82.3,
                ..Default::default()
            },
            0,
            &side(Frame::default()),
        )
        .expect("a global segment")
        .1;
        assert!(close(g.at[0], 29.6) && close(g.at[1], -82.3));
        assert!(close(g.tolerance, DEFAULT_TOLERANCE));
    }

    #[test]
    fn the_report_keeps_what_the_query_asks_for() {
        let s = SetLocalPathSegment {
            p1_z: Some(2.0),
            p2_z: Some(3.0),
            path_tolerance: Some(0.5),
            ..Default::default()
        };
        let q: Message = QueryLocalPathSegment {
            presence_vector: 0b100,
        }
        .into();
        let Message::ReportLocalPathSegment(r) = LocalSegments::report(&s, &q) else {
            panic!("Report Local Path Segment expected")
        };
        assert_eq!((r.p1_z, r.p2_z, r.path_tolerance), (None, None, Some(0.5)));
    }
}
