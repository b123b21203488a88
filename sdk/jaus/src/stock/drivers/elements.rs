//! The report of a stored navigation element: what Query Global/Local Waypoint and
//! Query Global/Local Path Segment answer from the Set message that stored it. The stock
//! waypoint and path segment drivers answer with these, and so does anything else that
//! keeps the Set messages (the AS-4 proxy's drivers in `jaus-as4`).

use crate::messages::{
    ReportGlobalPathSegment, ReportGlobalWaypoint, ReportLocalPathSegment, ReportLocalWaypoint,
    SetGlobalPathSegment, SetGlobalWaypoint, SetLocalPathSegment, SetLocalWaypoint,
};

/// Report Global Waypoint of a stored Set Global Waypoint.
pub fn global_waypoint_report(w: &SetGlobalWaypoint) -> ReportGlobalWaypoint {
    ReportGlobalWaypoint {
        waypoint_number: w.waypoint_number,
        latitude: w.latitude,
        longitude: w.longitude,
        elevation: w.elevation,
        roll: w.roll,
        pitch: w.pitch,
        yaw: w.yaw,
    }
}

/// Report Local Waypoint of a stored Set Local Waypoint.
pub fn local_waypoint_report(w: &SetLocalWaypoint) -> ReportLocalWaypoint {
    ReportLocalWaypoint {
        waypoint_number: w.waypoint_number,
        x: w.x,
        y: w.y,
        z: w.z,
        roll: w.roll,
        pitch: w.pitch,
        yaw: w.yaw,
    }
}

/// Report Global Path Segment of a stored Set Global Path Segment, with the optional
/// altitudes the query's presence vector asks for (bit 0: P1's, bit 1: P2's).
pub fn global_path_segment_report(
    s: &SetGlobalPathSegment,
    presence_vector: u8,
) -> ReportGlobalPathSegment {
    ReportGlobalPathSegment {
        path_segment_number: s.path_segment_number,
        p1_latitude: s.p1_latitude,
        p1_longitude: s.p1_longitude,
        p1_altitude: s.p1_altitude.filter(|_| presence_vector & 1 != 0),
        p2_latitude: s.p2_latitude,
        p2_longitude: s.p2_longitude,
        p2_altitude: s.p2_altitude.filter(|_| presence_vector & 2 != 0),
        weighting_factor: s.weighting_factor,
    }
}

/// Report Local Path Segment of a stored Set Local Path Segment, with the optional
/// z coordinates the query's presence vector asks for (bit 0: P1's, bit 1: P2's).
pub fn local_path_segment_report(
    s: &SetLocalPathSegment,
    presence_vector: u8,
) -> ReportLocalPathSegment {
    ReportLocalPathSegment {
        path_segment_number: s.path_segment_number,
        p1_x: s.p1_x,
        p1_y: s.p1_y,
        p1_z: s.p1_z.filter(|_| presence_vector & 1 != 0),
        p2_x: s.p2_x,
        p2_y: s.p2_y,
        p2_z: s.p2_z.filter(|_| presence_vector & 2 != 0),
        weighting_factor: s.weighting_factor,
    }
}
