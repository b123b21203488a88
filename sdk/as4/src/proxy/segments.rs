//! The proxy's Global and Local Path Segment Drivers (RA 3.3 components 47 and 48) over
//! the vehicle's AS-4 Global and Local Path Segment Drivers: the waypoint drivers'
//! machinery ([`super::waypoints`]) with path segments for elements.
//!
//! Numbered Set Global (Local) Path Segment and Set Travel Speed, once Ready with a
//! speed above 0 and AS-4 control, replace the vehicle's list with AS-4 Set Global
//! (Local) Path Segment elements (the same P1, P2 and weighting factor; local points
//! moved into the AS-4 frame) and execute it; Query Path Segment Count answers the
//! elements not yet passed, Query Global (Local) Path Segment what was set; the list
//! done, the driver returns to Standby.

use jaus::component::Context;
use jaus::components::{global_path_segment_driver as gpsd, local_path_segment_driver as lpsd};
use jaus::messages::{self as ra, Message as Ra33Message};
use jaus::stock::drivers::elements;

use super::shared::Shared;
use super::waypoints::{Kind, WaypointDriver};
use super::Role;
use crate::messages::{self as as4, Message};

/// Global path segments (RA 3.3 Global Path Segment Driver, AS-4 Global Path Segment
/// Driver).
#[derive(Debug)]
pub struct GlobalSegments;

/// Local path segments (RA 3.3 Local Path Segment Driver, AS-4 Local Path Segment
/// Driver).
#[derive(Debug)]
pub struct LocalSegments;

/// A proxy path segment driver of kind `K`.
pub type PathSegmentDriver<K> = WaypointDriver<K>;

/// Report Path Segment Count with `remaining` if `m` is Query Path Segment Count.
fn segment_count(m: &Ra33Message, remaining: u16) -> Option<Ra33Message> {
    match m {
        Ra33Message::QueryPathSegmentCount(_) => Some(
            ra::ReportPathSegmentCount {
                path_segment_count: remaining,
            }
            .into(),
        ),
        _ => None,
    }
}

impl Kind for GlobalSegments {
    type Iface = gpsd::Interface;
    const ROLE: Role = Role::GlobalPathSegmentDriver;
    const ELEMENT: &'static str = "path segment";

    fn set_number(m: &Ra33Message) -> Option<u16> {
        match m {
            Ra33Message::SetGlobalPathSegment(s) => Some(s.path_segment_number),
            _ => None,
        }
    }

    fn query_number(m: &Ra33Message) -> Option<u16> {
        match m {
            Ra33Message::QueryGlobalPathSegment(q) => Some(q.path_segment_number),
            _ => None,
        }
    }

    fn report(set: &Ra33Message, query: &Ra33Message) -> Option<Ra33Message> {
        let Ra33Message::SetGlobalPathSegment(s) = set else {
            return None;
        };
        let pv = match query {
            Ra33Message::QueryGlobalPathSegment(q) => q.presence_vector,
            _ => u8::MAX,
        };
        Some(elements::global_path_segment_report(s, pv).into())
    }

    fn count(m: &Ra33Message, remaining: u16) -> Option<Ra33Message> {
        segment_count(m, remaining)
    }

    fn as4(set: &Ra33Message, _s: &Shared) -> Option<Message> {
        let Ra33Message::SetGlobalPathSegment(s) = set else {
            return None;
        };
        Some(
            as4::SetGlobalPathSegment {
                p1_latitude: s.p1_latitude,
                p1_longitude: s.p1_longitude,
                p1_altitude: s.p1_altitude,
                p2_latitude: s.p2_latitude,
                p2_longitude: s.p2_longitude,
                p2_altitude: s.p2_altitude,
                weighting_factor: s.weighting_factor,
                path_tolerance: None,
            }
            .into(),
        )
    }

    fn start(ctx: &mut Context<'_, gpsd::Interface>) {
        let _ = ctx.transition(gpsd::Transition::Start);
    }

    fn arrive(ctx: &mut Context<'_, gpsd::Interface>) {
        let _ = ctx.transition(gpsd::Transition::Arrive);
    }
}

impl Kind for LocalSegments {
    type Iface = lpsd::Interface;
    const ROLE: Role = Role::LocalPathSegmentDriver;
    const ELEMENT: &'static str = "path segment";

    fn set_number(m: &Ra33Message) -> Option<u16> {
        match m {
            Ra33Message::SetLocalPathSegment(s) => Some(s.path_segment_number),
            _ => None,
        }
    }

    fn query_number(m: &Ra33Message) -> Option<u16> {
        match m {
            Ra33Message::QueryLocalPathSegment(q) => Some(q.path_segment_number),
            _ => None,
        }
    }

    fn report(set: &Ra33Message, query: &Ra33Message) -> Option<Ra33Message> {
        let Ra33Message::SetLocalPathSegment(s) = set else {
            return None;
        };
        let pv = match query {
            Ra33Message::QueryLocalPathSegment(q) => q.presence_vector,
            _ => u8::MAX,
        };
        Some(elements::local_path_segment_report(s, pv).into())
    }

    fn count(m: &Ra33Message, remaining: u16) -> Option<Ra33Message> {
        segment_count(m, remaining)
    }

    fn as4(set: &Ra33Message, sh: &Shared) -> Option<Message> {
        let Ra33Message::SetLocalPathSegment(s) = set else {
            return None;
        };
        let (p1_x, p1_y) = sh.frame.to_as4(s.p1_x, s.p1_y);
        let (p2_x, p2_y) = sh.frame.to_as4(s.p2_x, s.p2_y);
        Some(
            as4::SetLocalPathSegment {
                p1_x,
                p1_y,
                p1_z: s.p1_z,
                p2_x,
                p2_y,
                p2_z: s.p2_z,
                weighting_factor: s.weighting_factor,
                path_tolerance: None,
            }
            .into(),
        )
    }

    fn start(ctx: &mut Context<'_, lpsd::Interface>) {
        let _ = ctx.transition(lpsd::Transition::Start);
    }

    fn arrive(ctx: &mut Context<'_, lpsd::Interface>) {
        let _ = ctx.transition(lpsd::Transition::Arrive);
    }
}

#[cfg(test)]
mod tests {
    use jaus::net::as5669a::As4Id;

    use super::*;
    use crate::ra33::Frame;

    #[test]
    fn a_local_segment_moves_into_the_as4_frame() {
        // The RA 3.3 frame sits at AS-4 (5, -2), turned half a turn.
        let frame = Frame {
            x: 5.0,
            y: -2.0,
            yaw: std::f64::consts::PI,
        };
        let shared = Shared::new(As4Id::new(2, 1, 200), frame);
        let set: Ra33Message = ra::SetLocalPathSegment {
            path_segment_number: 1,
            p1_x: 1.0,
            p1_y: 0.0,
            p1_z: None,
            p2_x: 0.0,
            p2_y: 3.0,
            p2_z: Some(2.0),
            weighting_factor: 1.5,
        }
        .into();
        let Some(Message::SetLocalPathSegment(m)) = LocalSegments::as4(&set, &shared) else {
            panic!("AS-4 Set Local Path Segment expected")
        };
        let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
        // RA 3.3 (1, 0) → AS-4 (-1, 0) + (5, -2); (0, 3) → (0, -3) + (5, -2).
        assert!(close(m.p1_x, 4.0) && close(m.p1_y, -2.0), "{m:?}");
        assert!(close(m.p2_x, 5.0) && close(m.p2_y, -5.0), "{m:?}");
        assert_eq!((m.p1_z, m.p2_z), (None, Some(2.0)));
        assert!(close(m.weighting_factor, 1.5));
        // The numbered query answers what was set, as the query's presence vector asks.
        let q: Ra33Message = ra::QueryLocalPathSegment {
            path_segment_number: 1,
            presence_vector: 0,
        }
        .into();
        let Some(Ra33Message::ReportLocalPathSegment(r)) = LocalSegments::report(&set, &q) else {
            panic!("Report Local Path Segment expected")
        };
        assert_eq!((r.path_segment_number, r.p2_z), (1, None));
        assert!(
            LocalSegments::count(&ra::QueryPathSegmentCount {}.into(), 2).is_some()
                && LocalSegments::count(&ra::QueryWaypointCount {}.into(), 2).is_none()
        );
    }
}
