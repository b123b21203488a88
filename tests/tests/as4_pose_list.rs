//! AS-4 Manipulator v2.0 End-Effector Pose List Driver through the gateway, over the
//! stock RA 3.3 End-Effector Pose Driver of the simulated 6-axis arm
//! (`jaus_as4::manipulator::pose_list`): a list of two reachable poses driven in order,
//! its Execute List a Core v1.1 command event that ends when the list is done; Execute
//! List refused without control and for a pose out of reach; Standby, or control
//! released, mid-list stops the arm. An AS-4 client (ours, on SimNet); the checks read
//! the AS-4 End-Effector Pose Sensor and the simulated arm itself.

use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;
use jaus::net::{Node, NodeConfig};
use jaus::stock::nalgebra::{Isometry3, Translation3, Vector3};
use jaus_as4::{
    embedded, CommandResult, CreateCommandEvent, Element, ManipulatorExecuteList, Message,
    QueryCommandedEndEffectorPose, QueryEndEffectorPose, QueryManipulatorActiveElement,
    QueryToolOffset, ReportEndEffectorPose, SetElement, SetEndEffectorPose, Standby,
};
use jaus_sim::arm::{ArmParams, SimArm};

mod common;
use common::as4::As4Rig;

const ARM: As4Id = As4Id::new(1, 1, 1);
const URI: &str = "urn:jaus:jss:manipulator:ManipulatorEndEffectorPoseListDriver";

/// The stock manipulator components over a fresh arm on node 1.1, the gateway in front
/// of them, an AS-4 client.
fn rig() -> (As4Rig, SimArm) {
    let t0 = Instant::now();
    let arm = SimArm::new(ArmParams::six_axis());
    let mut node = Node::new(NodeConfig::default(), t0);
    for c in jaus_sim::arm_demo::arm_components(&arm, 1, 1, t0) {
        node.add_boxed(c).unwrap();
    }
    let rig = As4Rig::new(t0, node, ARM, "arm", Duration::from_secs(2));
    (rig, arm)
}

/// Control taken and the component Ready.
fn ready(rig: &mut As4Rig) {
    rig.take_control();
    rig.ask(jaus_as4::Resume {}, Duration::from_millis(300));
}

/// The pose of the arm's tool point `tool` at joints `q` (vehicle frame), as an AS-4
/// Set End Effector Pose.
fn pose_at(arm: &SimArm, q: &[f64], tool: Vector3<f64>) -> SetEndEffectorPose {
    let t = arm.lock().chain().forward(q) * Translation3::from(tool);
    let (p, r) = (t.translation.vector, t.rotation);
    SetEndEffectorPose {
        tool_point_x: p.x,
        tool_point_y: p.y,
        tool_point_z: p.z,
        quaternion_d: r.w,
        quaternion_a: r.i,
        quaternion_b: r.j,
        quaternion_c: r.k,
    }
}

/// The tool point the RA 3.3 End-Effector Pose Driver uses (Report Tool Offset).
fn tool(rig: &mut As4Rig) -> Vector3<f64> {
    let Message::ReportToolOffset(t) = rig.one(QueryToolOffset {}) else {
        panic!("no Report Tool Offset");
    };
    Vector3::new(t.tool_point_x, t.tool_point_y, t.tool_point_z)
}

fn element(uid: u16, previous: u16, next: u16, p: &SetEndEffectorPose) -> Element {
    Element::holding(uid, previous, next, &p.clone().into()).unwrap()
}

/// Position (m) and orientation (rad) from `got` to `want`.
fn error(got: &ReportEndEffectorPose, want: &SetEndEffectorPose) -> (f64, f64) {
    let iso = |x, y, z, d, a, b, c| {
        jaus::stock::manipulator::pose_drivers::pose_of(x, y, z, d, a, b, c).unwrap()
    };
    let g: Isometry3<f64> = iso(
        got.tool_point_x,
        got.tool_point_y,
        got.tool_point_z,
        got.quaternion_d,
        got.quaternion_a,
        got.quaternion_b,
        got.quaternion_c,
    );
    let w = iso(
        want.tool_point_x,
        want.tool_point_y,
        want.tool_point_z,
        want.quaternion_d,
        want.quaternion_a,
        want.quaternion_b,
        want.quaternion_c,
    );
    (
        (g.translation.vector - w.translation.vector).norm(),
        (w.rotation * g.rotation.inverse()).angle(),
    )
}

/// The answer of type `pick` among `got`.
fn find<T>(got: &[Message], pick: impl Fn(&Message) -> Option<T>) -> Option<T> {
    got.iter().find_map(pick)
}

/// Asks `m` (answers within 100 ms), noting the result of command event `event_id` if
/// its Command Event came meanwhile.
fn noting(
    rig: &mut As4Rig,
    m: impl Into<Message>,
    event_id: u8,
    result: &mut Option<CommandResult>,
) -> Vec<Message> {
    let got = rig.ask(m, Duration::from_millis(100));
    if let Some(r) = find(&got, |m| match m {
        Message::CommandEvent(e) if e.event_id == event_id => Some(e.command_result),
        _ => None,
    }) {
        *result = Some(r);
    }
    got
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn a_list_of_two_poses_is_driven_through_and_its_command_event_ends_when_done() {
    let (mut r, arm) = rig();
    let uris = r.service_uris();
    assert!(uris.contains(&URI.to_string()), "{URI} not in {uris:?}");
    let tool = tool(&mut r);
    let a = pose_at(&arm, &[0.3, -0.4, 1.2, 0.0, 0.6, 0.0], tool);
    let b = pose_at(&arm, &[-0.2, -0.5, 1.0, 0.2, 0.5, 0.3], tool);
    let start = arm.lock().positions().to_vec();

    // Without control, Execute List is refused; nothing moves.
    let refused = r.refused();
    r.ask(
        ManipulatorExecuteList { element_uid: None },
        Duration::from_millis(500),
    );
    assert!(r.refused() > refused, "Execute List taken without control");
    assert!(max_diff(arm.lock().positions(), &start) < 2e-3);

    ready(&mut r);
    let Message::ConfirmElementRequest(ok) = r.one(SetElement {
        request_id: 4,
        elements: vec![element(1, 0, 2, &a), element(2, 1, 0, &b)],
    }) else {
        panic!("Confirm Element Request expected");
    };
    assert_eq!(ok.request_id, 4);

    // Execute List inside a command event: confirmed, not done yet.
    let got = r.ask(
        CreateCommandEvent {
            request_id: 5,
            maximum_allowed_duration: 60,
            command_message: embedded::encode(&ManipulatorExecuteList { element_uid: None }.into())
                .expect("encodes"),
        },
        Duration::from_millis(300),
    );
    let event_id = find(&got, |m| match m {
        Message::ConfirmEventRequest(c) if c.request_id == 5 => Some(c.event_id),
        _ => None,
    })
    .unwrap_or_else(|| panic!("no Confirm Event Request in {got:?}"));
    assert!(
        !got.iter().any(|m| matches!(m, Message::CommandEvent(_))),
        "done at once: {got:?}"
    );

    // The active element goes 1, then 2, then 0 (done); the commanded pose is the
    // active element's; the command event ends Successful once the list is done.
    let (mut active, mut nearest_a, mut result) = (Vec::new(), f64::INFINITY, None);
    let mut commanded_ok = true;
    let mut end = None;
    for _ in 0..200 {
        let got = noting(
            &mut r,
            QueryManipulatorActiveElement {},
            event_id,
            &mut result,
        );
        let Some(uid) = find(&got, |m| match m {
            Message::ReportManipulatorActiveElement(e) => Some(e.element_uid),
            _ => None,
        }) else {
            panic!("Report Manipulator Active Element expected in {got:?}");
        };
        if active.last() != Some(&uid) {
            active.push(uid);
        }
        let got = noting(&mut r, QueryEndEffectorPose {}, event_id, &mut result);
        let Some(here) = find(&got, |m| match m {
            Message::ReportEndEffectorPose(p) => Some(p.clone()),
            _ => None,
        }) else {
            panic!("Report End Effector Pose expected in {got:?}");
        };
        nearest_a = nearest_a.min(error(&here, &a).0);
        if uid == 0 {
            end = Some(here);
            break;
        }
        let got = noting(
            &mut r,
            QueryCommandedEndEffectorPose {},
            event_id,
            &mut result,
        );
        if let Some(c) = find(&got, |m| match m {
            Message::ReportCommandedEndEffectorPose(c) => Some(c.clone()),
            _ => None,
        }) {
            let want = if uid == 1 { &a } else { &b };
            commanded_ok &= (c.tool_point_x - want.tool_point_x).abs() < 1e-6
                && (c.tool_point_z - want.tool_point_z).abs() < 1e-6;
        }
    }
    noting(
        &mut r,
        QueryManipulatorActiveElement {},
        event_id,
        &mut result,
    );
    let end = end.expect("the list never done");
    let (dp, da) = error(&end, &b);
    let truth = arm.lock().tool_pose(&tool).translation.vector;
    let true_dp = (truth - Vector3::new(b.tool_point_x, b.tool_point_y, b.tool_point_z)).norm();
    eprintln!(
        "active elements {active:?}; passed within {:.3} mm of a; ended {:.3} mm, {:.4}° from b \
         (AS-4 End-Effector Pose Sensor; {:.3} mm by the simulated arm); command event {result:?}",
        nearest_a * 1e3,
        dp * 1e3,
        da.to_degrees(),
        true_dp * 1e3
    );
    assert_eq!(active, vec![1, 2, 0]);
    assert!(
        commanded_ok,
        "Query Commanded End Effector Pose not the active element's"
    );
    assert!(nearest_a < 0.03, "did not pass by a: {nearest_a} m");
    assert!(dp < 1e-3, "ended {dp} m from b");
    assert!(da < 0.01, "ended {da} rad from b's orientation");
    assert!(true_dp < 1e-3, "the arm ended {true_dp} m from b");
    assert_eq!(result, Some(CommandResult::Successful));

    // The RA 3.3 driver holds b: 2 s on, the pose is still within 1 mm of it.
    r.net.run_for(Duration::from_secs(2));
    let Message::ReportEndEffectorPose(held) = r.one(QueryEndEffectorPose {}) else {
        panic!("Report End Effector Pose expected");
    };
    let (dp, da) = error(&held, &b);
    eprintln!(
        "2 s later: {:.3} mm, {:.4}° from b",
        dp * 1e3,
        da.to_degrees()
    );
    assert!(dp < 1e-3 && da < 0.01, "left b: {dp} m, {da} rad");
}

#[test]
fn a_pose_out_of_reach_is_refused_and_standby_or_release_mid_list_stops_the_arm() {
    let (mut r, arm) = rig();
    let tool = tool(&mut r);
    ready(&mut r);
    let start = arm.lock().positions().to_vec();
    let a = pose_at(&arm, &[1.5, -0.4, 1.2, 0.0, 0.6, 0.0], tool);
    let far = SetEndEffectorPose {
        tool_point_x: 2.0,
        ..a.clone()
    };
    // A list whose second pose is 2 m out: refused as a whole, nothing moves.
    let Message::ConfirmElementRequest(_) = r.one(SetElement {
        request_id: 1,
        elements: vec![element(1, 0, 2, &a), element(2, 1, 0, &far)],
    }) else {
        panic!("Confirm Element Request expected");
    };
    let refused = r.refused();
    r.ask(
        ManipulatorExecuteList { element_uid: None },
        Duration::from_millis(500),
    );
    assert!(r.refused() > refused, "a pose out of reach taken");
    assert!(max_diff(arm.lock().positions(), &start) < 2e-3, "moved");

    // The second pose replaced by a reachable one; the first is far from here (the base
    // joint 1.5 rad round): Standby on the way to it stops the arm, which stays, and the
    // list ends (no active element).
    let b = pose_at(&arm, &[-1.5, -0.5, 1.0, 0.2, 0.5, 0.3], tool);
    let Message::ConfirmElementRequest(_) = r.one(SetElement {
        request_id: 2,
        elements: vec![element(2, 1, 0, &b)],
    }) else {
        panic!("Confirm Element Request expected");
    };
    r.ask(
        ManipulatorExecuteList { element_uid: None },
        Duration::from_millis(600),
    );
    let Message::ReportManipulatorActiveElement(e) = r.one(QueryManipulatorActiveElement {}) else {
        panic!("Report Manipulator Active Element expected");
    };
    assert_eq!(e.element_uid, 1);
    let moving = max_diff(arm.lock().positions(), &start);
    assert!(moving > 0.05, "not moving: {moving} rad");
    r.ask(Standby {}, Duration::from_millis(500));
    let stopped = arm.lock().positions().to_vec();
    r.net.run_for(Duration::from_secs(2));
    let drift = max_diff(arm.lock().positions(), &stopped);
    let Message::ReportManipulatorActiveElement(e) = r.one(QueryManipulatorActiveElement {}) else {
        panic!("Report Manipulator Active Element expected");
    };
    let Message::ReportEndEffectorPose(here) = r.one(QueryEndEffectorPose {}) else {
        panic!("Report End Effector Pose expected");
    };
    eprintln!(
        "stopped {moving:.3} rad into the list, {:.0} mm from a; drifted {drift:.5} rad in 2 s of Standby",
        error(&here, &a).0 * 1e3
    );
    assert_eq!(e.element_uid, 0, "the list still runs in Standby");
    assert!(drift < 5e-3, "moving in Standby: {drift} rad");
    assert!(error(&here, &a).0 > 0.05, "reached a anyway");

    // Again from Ready, then control released on the way: the same.
    r.ask(jaus_as4::Resume {}, Duration::from_millis(300));
    r.ask(
        ManipulatorExecuteList { element_uid: None },
        Duration::from_millis(600),
    );
    let moved = max_diff(arm.lock().positions(), &stopped);
    assert!(moved > 0.05, "not moving again: {moved} rad");
    r.ask(jaus_as4::ReleaseControl {}, Duration::from_millis(500));
    let released = arm.lock().positions().to_vec();
    r.net.run_for(Duration::from_secs(2));
    let drift = max_diff(arm.lock().positions(), &released);
    let Message::ReportManipulatorActiveElement(e) = r.one(QueryManipulatorActiveElement {}) else {
        panic!("Report Manipulator Active Element expected");
    };
    eprintln!("control released {moved:.3} rad on; drifted {drift:.5} rad in 2 s");
    assert_eq!(e.element_uid, 0, "the list still runs without control");
    assert!(drift < 5e-3, "moving without control: {drift} rad");
}
