//! The sensors' checks: Report Velocity State with exactly the fields presence vector
//! 0x0140 asks for, and the local pose set by Set Local Pose and reported back.

use jaus_as4::messages::{Message, QueryLocalPose, QueryVelocityState, SetLocalPose};

use super::Scenario;
use crate::engine::{fail, inconclusive, pass, Found};

/// The presence vector of the velocity query: yaw rate (bit 6) and time stamp (bit 8).
const VELOCITY_PV: u16 = 0x0140;
/// The presence vector of Set Local Pose: x, y, yaw (bits 0, 1, 6).
const SET_POSE_PV: u16 = 0x0043;
/// The presence vector of the pose query: x, y, time stamp (bits 0, 1, 8).
const REPORT_POSE_PV: u16 = 0x0103;

/// The fields of Report Velocity State by presence bit.
const VELOCITY_FIELDS: [&str; 9] = [
    "velocity_x",
    "velocity_y",
    "velocity_z",
    "velocity_rms",
    "roll_rate",
    "pitch_rate",
    "yaw_rate",
    "rate_rms",
    "time_stamp",
];
/// The fields of Report Local Pose by presence bit.
const POSE_FIELDS: [&str; 9] = [
    "x",
    "y",
    "z",
    "position_rms",
    "roll",
    "pitch",
    "yaw",
    "attitude_rms",
    "time_stamp",
];

/// The presence vector at the start of a report's body (`None` when too short).
fn presence(body: &[u8]) -> Option<u16> {
    Some(u16::from_le_bytes([*body.first()?, *body.get(1)?]))
}

/// The names of the fields `bits` selects.
fn fields(bits: u16, names: &[&str; 9]) -> String {
    let v: Vec<&str> = (0..9)
        .filter(|b| bits & (1 << b) != 0)
        .map(|b| names[b])
        .collect();
    if v.is_empty() {
        "none".into()
    } else {
        v.join(", ")
    }
}

/// How a report's presence vector differs from the one asked for, or `None` when it
/// is the same.
fn presence_mismatch(asked: u16, got: u16, names: &[&str; 9]) -> Option<String> {
    if asked == got {
        return None;
    }
    let mut parts = Vec::new();
    if got & !asked != 0 {
        parts.push(format!(
            "fields not asked for: {}",
            fields(got & !asked, names)
        ));
    }
    if asked & !got != 0 {
        parts.push(format!("fields missing: {}", fields(asked & !got, names)));
    }
    Some(format!(
        "presence vector 0x{got:04X} instead of 0x{asked:04X} ({})",
        parts.join("; ")
    ))
}

impl Scenario<'_> {
    /// `as4.velocity.pv0140`.
    pub(super) fn velocity(&mut self) -> Found {
        let q = QueryVelocityState {
            presence_vector: VELOCITY_PV,
        };
        let (m, body, _) = match self.j.ask_raw(self.j.peer, q.into()) {
            Ok(r) => r,
            Err(e) => return fail(e),
        };
        let Message::ReportVelocityState(r) = m else {
            return fail("the answer is not Report Velocity State");
        };
        let Some(pv) = presence(&body) else {
            return fail("Report Velocity State without its presence vector");
        };
        match presence_mismatch(VELOCITY_PV, pv, &VELOCITY_FIELDS) {
            Some(why) => fail(why),
            None => pass(format!(
                "yaw rate {:.3} rad/s and a time stamp, nothing else",
                r.yaw_rate.unwrap_or_default()
            )),
        }
    }

    /// `as4.pose.set_local`: Set Local Pose, read back with the same presence vector.
    pub(super) fn set_local_pose(&mut self) -> Found {
        if let Some(f) = self.needs_control() {
            return f;
        }
        if let Err(e) = self.ensure_ready() {
            return inconclusive(e);
        }
        let (x, y, yaw) = self.j.opts.pose;
        self.j.command(
            SetLocalPose {
                x: Some(x),
                y: Some(y),
                yaw: Some(yaw),
                ..SetLocalPose::default()
            }
            .into(),
        );
        let q = QueryLocalPose {
            presence_vector: SET_POSE_PV,
        };
        let r = match self.j.ask(q.into()) {
            Ok(Message::ReportLocalPose(r)) => r,
            Ok(m) => return fail(format!("Query Local Pose answered by {}", m.name())),
            Err(e) => return fail(e),
        };
        let tol = self.j.opts.pose_tolerance;
        match (r.x, r.y, r.yaw) {
            (Some(rx), Some(ry), Some(ryaw))
                if (rx - x).abs() <= tol
                    && (ry - y).abs() <= tol
                    && angle_diff(ryaw, yaw) <= 0.05 =>
            {
                self.pose_set = true;
                pass(format!(
                    "set x {x} m, y {y} m, yaw {yaw} rad; read back x {rx:.3}, y {ry:.3}, yaw {ryaw:.3}"
                ))
            }
            (rx, ry, ryaw) => fail(format!(
                "set x {x} m, y {y} m, yaw {yaw} rad; read back x {rx:?}, y {ry:?}, yaw {ryaw:?} (tolerance {tol} m, 0.05 rad)"
            )),
        }
    }

    /// `as4.pose.report_local`.
    pub(super) fn report_local_pose(&mut self) -> Found {
        let q = QueryLocalPose {
            presence_vector: REPORT_POSE_PV,
        };
        let (m, body, _) = match self.j.ask_raw(self.j.peer, q.into()) {
            Ok(r) => r,
            Err(e) => return fail(e),
        };
        let Message::ReportLocalPose(r) = m else {
            return fail("the answer is not Report Local Pose");
        };
        let Some(pv) = presence(&body) else {
            return fail("Report Local Pose without its presence vector");
        };
        if let Some(why) = presence_mismatch(REPORT_POSE_PV, pv, &POSE_FIELDS) {
            return fail(why);
        }
        let (x, y, _) = self.j.opts.pose;
        let (rx, ry) = (r.x.unwrap_or(f64::NAN), r.y.unwrap_or(f64::NAN));
        if !self.pose_set {
            return pass(format!(
                "x {rx:.3} m, y {ry:.3} m and a time stamp (the pose was not set: not compared)"
            ));
        }
        let tol = self.j.opts.pose_tolerance;
        if (rx - x).abs() <= tol && (ry - y).abs() <= tol {
            pass(format!(
                "x {rx:.3} m, y {ry:.3} m (set {x}, {y}) and a time stamp"
            ))
        } else {
            fail(format!(
                "x {rx:.3} m, y {ry:.3} m, but {x}, {y} was set (tolerance {tol} m; the vehicle should not be moving)"
            ))
        }
    }
}

/// The difference of two angles, in [0, π].
pub(super) fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presence_vectors_name_what_differs() {
        assert_eq!(presence_mismatch(0x0140, 0x0140, &VELOCITY_FIELDS), None);
        let why = presence_mismatch(0x0140, 0x0141, &VELOCITY_FIELDS).unwrap();
        assert!(why.contains("not asked for: velocity_x"), "{why}");
        let why = presence_mismatch(0x0103, 0x0003, &POSE_FIELDS).unwrap();
        assert!(why.contains("missing: time_stamp"), "{why}");
    }

    #[test]
    fn angles_wrap() {
        assert!(angle_diff(3.1, -3.1) < 0.1);
        assert!((angle_diff(0.0, 1.0) - 1.0).abs() < 1e-12);
    }
}
