//! The standard's first revisions as jaus-as4 holds them (`sdk/as4/revisions/`: Core
//! v1.0 and Manipulator v1.0) are code a vendor could build: `tests/build.rs` generates
//! them, this file compiles them, and what `revisions/*.txt` says of the wire holds for
//! the generated codecs: a message v2.0 renamed keeps its bytes, the one report v2.0
//! changed on the wire does not decode alike.

use jaus::codec::Encode;
use jaus::{CommandCode, JausMessage};

/// The first revisions, generated.
#[allow(clippy::all, clippy::pedantic, dead_code, unused_imports, missing_docs)]
mod v1 {
    include!(concat!(env!("OUT_DIR"), "/as4-v1.0/messages.rs"));
    pub mod services {
        include!(concat!(env!("OUT_DIR"), "/as4-v1.0/services.rs"));
    }
}

#[test]
fn the_first_revisions_generate_their_messages_and_services() {
    // 41 of Core v1.0, 72 of Manipulator v1.0.
    assert_eq!(v1::MESSAGES.len(), 113);
    assert!(v1::MESSAGES.iter().any(|m| m.name == "SetMotionProfile"));
    assert!(!jaus_as4::MESSAGES
        .iter()
        .any(|m| m.name == "SetMotionProfile"));
}

#[test]
fn a_renamed_message_keeps_its_bytes_and_the_changed_report_does_not_go_back() {
    // Set Motion Profile (v1.0) is v2.0's Set Joint Motion Profile: same code, same bytes.
    let profile = |speed: f64| {
        v1::JointMotionProfile::Revolute(v1::RevoluteMotionProfile {
            joint_max_speed: speed,
            joint_max_acceleration_rate: 2.0,
            joint_max_deceleration_rate: 3.0,
        })
    };
    let old = v1::SetMotionProfile {
        joint_motion_profiles: vec![profile(0.5), profile(1.5)],
    };
    let bytes = old.to_bytes().expect("encodes");
    let code = <v1::SetMotionProfile as JausMessage>::CODE;
    let new = jaus_as4::Message::decode(code, &bytes).expect("v2.0 decodes v1.0's bytes");
    let jaus_as4::Message::SetJointMotionProfile(p) = &new else {
        panic!("{new:?}");
    };
    assert_eq!(p.joint_motion_profiles.len(), 2);
    assert_eq!(new.body().to_bytes().unwrap(), bytes);

    // Report Manipulator Specifications: a v2.0 joint record with its bounding-cylinder
    // radius (presence bit 5) is not what a v1.0 decoder reads.
    let spec = jaus_as4::Message::decode(
        CommandCode(0x4600),
        &v1::ReportManipulatorSpecifications {
            first_joint: v1::FirstJoint::Revolute(Default::default()),
            joints: vec![v1::JointSpecification::Revolute(Default::default())],
            coordinate_system: None,
        }
        .to_bytes()
        .unwrap(),
    )
    .expect("v2.0 decodes a v1.0 report without the new fields");
    let jaus_as4::Message::ReportManipulatorSpecifications(mut spec) = spec else {
        panic!("{spec:?}");
    };
    let jaus_as4::JointSpecification::Revolute(r) = &mut spec.joints[0] else {
        panic!("a revolute joint");
    };
    r.link_length_bounding_cylinder_radius = Some(0.25);
    let v2_bytes = spec.to_bytes().unwrap();
    let e = v1::Message::decode(CommandCode(0x4600), &v2_bytes)
        .expect_err("v1.0 cannot read v2.0's radius");
    assert!(e.to_string().contains("presence bit 5"), "{e}");
    // Without the radius, the bytes are v1.0's again.
    let jaus_as4::JointSpecification::Revolute(r) = &mut spec.joints[0] else {
        unreachable!()
    };
    r.link_length_bounding_cylinder_radius = None;
    assert!(v1::Message::decode(CommandCode(0x4600), &spec.to_bytes().unwrap()).is_ok());
}
