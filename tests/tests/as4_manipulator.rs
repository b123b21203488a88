//! AS-4 Manipulator v2.0 through the gateway: an AS-4 client (ours: an `As4Client` on
//! SimNet) reads the simulated 6-axis arm's specification and joints and moves it, by
//! joint positions and by an end-effector pose, through the Manipulator services the
//! gateway presents over the stock RA 3.3 manipulator components
//! (`jaus_as4::manipulator`). The arm must actually get there: the check reads the
//! simulated arm, not the gateway.

use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;
use jaus::net::{Node, NodeConfig};
use jaus_as4::{
    ComponentState, ConfirmControl, ControlConfirmation, FirstJoint, JointPosition,
    JointPositionRadians, Message, NodeServicesQuery, QueryCommandedJointPositions,
    QueryEndEffectorPose, QueryJointPositions, QueryManipulatorSpecifications, QueryServices,
    QueryStatus, ReportEndEffectorPose, RequestControl, Resume, SetEndEffectorPose,
    SetJointPositions,
};
use jaus_sim::arm::{ArmParams, SimArm};

mod common;
use common::as4::As4Rig;

const ARM: As4Id = As4Id::new(1, 1, 1);
/// 0.1°.
const TENTH_DEGREE: f64 = 0.1 * std::f64::consts::PI / 180.0;

struct Rig {
    rig: As4Rig,
    arm: SimArm,
}

impl Rig {
    /// The stock manipulator components over a fresh arm on node 1.1, the gateway in
    /// front of them, an AS-4 client.
    fn new() -> Self {
        let t0 = Instant::now();
        let arm = SimArm::new(ArmParams::six_axis());
        let mut node = Node::new(NodeConfig::default(), t0);
        for c in jaus_sim::arm_demo::arm_components(&arm, 1, 1, t0) {
            node.add_boxed(c).unwrap();
        }
        let rig = As4Rig::new(t0, node, ARM, "arm", Duration::from_secs(2));
        Rig { rig, arm }
    }

    fn ask(&mut self, m: impl Into<Message>, wait: Duration) -> Vec<Message> {
        self.rig.ask(m, wait)
    }

    fn one(&mut self, m: impl Into<Message>) -> Message {
        self.rig.one(m)
    }

    fn take_control(&mut self) {
        let got = self.one(RequestControl { authority_code: 5 });
        assert!(
            matches!(
                got,
                Message::ConfirmControl(ConfirmControl {
                    response_code: ControlConfirmation::ControlAccepted,
                    ..
                })
            ),
            "{got:?}"
        );
        self.ask(Resume {}, Duration::from_millis(300));
        let Message::ReportStatus(s) = self.one(QueryStatus {}) else {
            panic!("no Report Status");
        };
        assert_eq!(s.status, ComponentState::Ready);
    }

    fn joints(&self) -> Vec<f64> {
        self.arm.lock().positions().to_vec()
    }

    fn pose(&mut self) -> ReportEndEffectorPose {
        match self.one(QueryEndEffectorPose {}) {
            Message::ReportEndEffectorPose(p) => p,
            other => panic!("{other:?}"),
        }
    }
}

fn radians(q: &[f64]) -> Vec<JointPosition> {
    q.iter()
        .map(|&value| JointPosition::Radians(JointPositionRadians { value }))
        .collect()
}

fn values(r: &[JointPosition]) -> Vec<f64> {
    r.iter()
        .map(|p| match p {
            JointPosition::Radians(r) => r.value,
            JointPosition::Metres(m) => m.value,
        })
        .collect()
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len(), "{a:?} vs {b:?}");
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn the_gateway_offers_the_manipulator_services_with_the_arms_specification() {
    let mut r = Rig::new();
    let Message::ReportServices(s) = r.one(QueryServices {
        nodes: vec![NodeServicesQuery {
            node_id: 255,
            component_ids: vec![255],
        }],
    }) else {
        panic!("no Report Services");
    };
    let uris: Vec<String> = s
        .nodes
        .iter()
        .flat_map(|n| &n.components)
        .flat_map(|c| &c.services)
        .map(|s| s.uri.clone())
        .collect();
    for name in [
        "ManipulatorJointPositionSensor",
        "ManipulatorJointVelocitySensor",
        "ManipulatorSpecificationService",
        "ManipulatorEndEffectorPoseSensor",
        "ManipulatorJointPositionDriver",
        "ManipulatorEndEffectorPoseDriver",
    ] {
        let uri = format!("urn:jaus:jss:manipulator:{name}");
        assert!(uris.contains(&uri), "{uri} not in {uris:?}");
    }
    // The specification is the simulated arm's chain.
    let Message::ReportManipulatorSpecifications(spec) =
        r.one(QueryManipulatorSpecifications { presence_vector: 1 })
    else {
        panic!("no Report Manipulator Specifications");
    };
    let chain = r.arm.lock().chain().clone();
    assert_eq!(spec.joints.len() + 1, chain.dof());
    assert!(spec.coordinate_system.is_some());
    let FirstJoint::Revolute(first) = &spec.first_joint else {
        panic!("{:?}", spec.first_joint);
    };
    assert!((first.joint1_max_value.unwrap() - chain.joints[0].max).abs() < 1e-6);
    // Joint positions as the arm holds them, each a revolute joint's angle.
    let Message::ReportJointPositions(q) = r.one(QueryJointPositions {}) else {
        panic!("no Report Joint Positions");
    };
    assert!(q
        .joint_positions
        .iter()
        .all(|p| matches!(p, JointPosition::Radians(_))));
    assert!(max_diff(&values(&q.joint_positions), &r.joints()) < 1e-3);
}

#[test]
fn an_as4_client_moves_the_arm_to_a_joint_set_and_a_pose_through_the_gateway() {
    let mut r = Rig::new();
    // Without control the command is refused and the arm stays.
    let before = r.joints();
    let target = [0.2, -0.5, 1.2, 0.1, 0.7, 0.2];
    r.ask(
        SetJointPositions {
            joint_positions: radians(&target),
        },
        Duration::from_secs(1),
    );
    assert!(
        max_diff(&r.joints(), &before) < 2e-3,
        "moved without control"
    );

    r.take_control();
    // A wrong joint count is refused; the arm stays.
    r.ask(
        SetJointPositions {
            joint_positions: radians(&target[..5]),
        },
        Duration::from_secs(1),
    );
    assert!(max_diff(&r.joints(), &before) < 2e-3);

    // Joint positions: every joint within 0.1°.
    r.ask(
        SetJointPositions {
            joint_positions: radians(&target),
        },
        Duration::from_secs(6),
    );
    let q = r.joints();
    eprintln!(
        "joints: moved {:.4} rad, {:.5}° from the target",
        max_diff(&q, &before),
        max_diff(&q, &target).to_degrees()
    );
    assert!(
        max_diff(&q, &target) < TENTH_DEGREE,
        "joints {q:?}, asked {target:?}"
    );
    let Message::ReportCommandedJointPositions(c) = r.one(QueryCommandedJointPositions {}) else {
        panic!("no Report Commanded Joint Positions");
    };
    assert!(max_diff(&values(&c.joint_positions), &target) < 1e-6);
    let Message::ReportJointPositions(m) = r.one(QueryJointPositions {}) else {
        panic!("no Report Joint Positions");
    };
    assert!(max_diff(&values(&m.joint_positions), &target) < TENTH_DEGREE);

    // The reported pose is the arm's (forward kinematics of the true joints).
    let here = r.pose();
    let truth = r.arm.lock().tool_pose(&[0.0, 0.0, 0.0].into());
    let p = truth.translation.vector;
    let err = (here.tool_point_x - p.x)
        .hypot(here.tool_point_y - p.y)
        .hypot(here.tool_point_z - p.z);
    assert!(err < 1e-3, "reported pose {here:?}, true {p:?}");

    // An end-effector pose 5 cm aside, same orientation: within 1 mm.
    let goal = SetEndEffectorPose {
        tool_point_x: here.tool_point_x,
        tool_point_y: here.tool_point_y + 0.05,
        tool_point_z: here.tool_point_z - 0.03,
        quaternion_d: here.quaternion_d,
        quaternion_a: here.quaternion_a,
        quaternion_b: here.quaternion_b,
        quaternion_c: here.quaternion_c,
    };
    r.ask(goal.clone(), Duration::from_secs(6));
    let truth = r.arm.lock().tool_pose(&[0.0, 0.0, 0.0].into());
    let p = truth.translation.vector;
    let err = (goal.tool_point_x - p.x)
        .hypot(goal.tool_point_y - p.y)
        .hypot(goal.tool_point_z - p.z);
    eprintln!("pose: {:.3} mm from the goal", err * 1e3);
    assert!(err < 1e-3, "tool point {p:?}, asked {goal:?}: {err} m off");
    let q = truth.rotation;
    let dot = (q.w * goal.quaternion_d
        + q.i * goal.quaternion_a
        + q.j * goal.quaternion_b
        + q.k * goal.quaternion_c)
        .abs();
    assert!(dot > 0.9999, "orientation off: |<q, goal>| = {dot}");
    let after = r.pose();
    assert!(
        (after.tool_point_y - goal.tool_point_y).abs() < 1e-3,
        "{after:?}"
    );
}
