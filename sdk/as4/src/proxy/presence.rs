//! The presence vectors of the proxy's queries. Each asks for every field the
//! definitions give the report that answers it, and for no other bit: a bit the
//! standard does not define asks for a field nobody knows, and a strict vehicle may
//! refuse the query for it (the JAUS Tool Set's components check the bits asked).
//!
//! The masks are computed from the reports' fields by one helper, [`of_full_report`]:
//! a report with every field set encodes the presence vector of every field its
//! definition has. Each report below is written with all its fields and no
//! `..Default::default()`, so a field added to the definitions does not compile until
//! it is added here, and the mask cannot fall behind the definitions.

use jaus::codec::Encode;

use crate::messages::{
    ReportGlobalPose, ReportLocalPose, ReportVelocityState, ReportWrenchEffort, TimeStamp,
};

/// The presence vector that `full` encodes: with every optional field of the report
/// set, the bits its definition defines. An AS-4 report's presence vector is the first
/// field of its body, a little-endian u16 for these reports; a report that does not
/// encode gives 0 (ask for nothing rather than for undefined bits; the tests show that
/// each report here encodes).
pub fn of_full_report(full: &impl Encode) -> u16 {
    match full.to_bytes().as_deref() {
        Ok([lo, hi, ..]) => u16::from_le_bytes([*lo, *hi]),
        _ => 0,
    }
}

/// Every field of Report Velocity State (Query Velocity State's presence vector).
pub fn velocity_state() -> u16 {
    of_full_report(&ReportVelocityState {
        velocity_x: Some(0.0),
        velocity_y: Some(0.0),
        velocity_z: Some(0.0),
        velocity_rms: Some(0.0),
        roll_rate: Some(0.0),
        pitch_rate: Some(0.0),
        yaw_rate: Some(0.0),
        rate_rms: Some(0.0),
        time_stamp: Some(TimeStamp::default()),
    })
}

/// Every field of Report Global Pose (Query Global Pose's presence vector).
pub fn global_pose() -> u16 {
    of_full_report(&ReportGlobalPose {
        latitude: Some(0.0),
        longitude: Some(0.0),
        altitude: Some(0.0),
        position_rms: Some(0.0),
        roll: Some(0.0),
        pitch: Some(0.0),
        yaw: Some(0.0),
        attitude_rms: Some(0.0),
        time_stamp: Some(TimeStamp::default()),
    })
}

/// Every field of Report Local Pose (Query Local Pose's presence vector).
pub fn local_pose() -> u16 {
    of_full_report(&ReportLocalPose {
        x: Some(0.0),
        y: Some(0.0),
        z: Some(0.0),
        position_rms: Some(0.0),
        roll: Some(0.0),
        pitch: Some(0.0),
        yaw: Some(0.0),
        attitude_rms: Some(0.0),
        time_stamp: Some(TimeStamp::default()),
    })
}

/// Every field of Report Wrench Effort (Query Wrench Effort's presence vector).
pub fn wrench_effort() -> u16 {
    of_full_report(&ReportWrenchEffort {
        propulsive_linear_effort_x: Some(0.0),
        propulsive_linear_effort_y: Some(0.0),
        propulsive_linear_effort_z: Some(0.0),
        propulsive_rotational_effort_x: Some(0.0),
        propulsive_rotational_effort_y: Some(0.0),
        propulsive_rotational_effort_z: Some(0.0),
        resistive_linear_effort_x: Some(0.0),
        resistive_linear_effort_y: Some(0.0),
        resistive_linear_effort_z: Some(0.0),
        resistive_rotational_effort_x: Some(0.0),
        resistive_rotational_effort_y: Some(0.0),
        resistive_rotational_effort_z: Some(0.0),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use jaus::codec::Decode;

    /// The masks are the bits AS6009 defines: 0-8 for the pose and velocity reports
    /// (eight values and the time stamp), 0-11 for the wrench effort (twelve efforts).
    #[test]
    fn the_masks_are_the_defined_bits_and_no_other() {
        assert_eq!(velocity_state(), 0x01FF);
        assert_eq!(global_pose(), 0x01FF);
        assert_eq!(local_pose(), 0x01FF);
        assert_eq!(wrench_effort(), 0x0FFF);
    }

    /// A report answering the query with every bit it asked for decodes and carries
    /// every field: the mask asks for all the report has.
    #[test]
    fn a_report_with_the_bits_asked_has_every_field() {
        // Three positions and their RMS (u32), three angles and their RMS (u16), the
        // time stamp (u32).
        let mut body = local_pose().to_le_bytes().to_vec();
        body.extend([0u8; 4 * 4 + 4 * 2 + 4]);
        let r = ReportLocalPose::from_bytes(&body).unwrap();
        assert!(r.x.is_some() && r.attitude_rms.is_some() && r.time_stamp.is_some());
        // One bit more is a bit the definition does not have.
        let mut body = (local_pose() << 1 | 1).to_le_bytes().to_vec();
        body.extend([0u8; 40]);
        let r = ReportLocalPose::from_bytes(&body).unwrap();
        assert_eq!(
            of_full_report(&r),
            local_pose(),
            "the undefined bit is dropped"
        );
    }
}
