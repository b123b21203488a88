//! AS-4 Manipulator v2.0 through the gateway, the services beyond positions: the Joint
//! Velocity and End-Effector Velocity State Drivers over the stock RA 3.3 Joint
//! Velocities and End-Effector Velocity State Drivers, the Joint Force/Torque Sensor,
//! the End-Effector Velocity State Sensor, the Tool Offset Service and the Joint
//! Position List Driver over the RA 3.3 Joint Move Driver (`jaus_as4::manipulator`).
//! An AS-4 client (ours, on SimNet) streams its rates as a client of the velocity
//! drivers must; the checks read the simulated arm itself.

use std::time::{Duration, Instant};

use jaus::net::as5669a::As4Id;
use jaus::net::{Node, NodeConfig};
use jaus::stock::manipulator::hardware::{JointSensors, JointState};
use jaus::stock::nalgebra::{DVector, Dyn, OMatrix, Vector3, U6};
use jaus_as4::{
    ComponentState, ConfirmControl, ControlConfirmation, Element, ForceTorque, JointPosition,
    JointPositionRadians, JointVelocity, JointVelocityRadiansPerSecond, ManipulatorExecuteList,
    Message, QueryCommandedEndEffectorVelocityState, QueryCommandedJointPositions,
    QueryCommandedJointVelocity, QueryEndEffectorPose, QueryEndEffectorVelocityState,
    QueryJointForceTorques, QueryManipulatorActiveElement, QueryStatus, QueryToolOffset,
    ReleaseControl, ReportEndEffectorPose, RequestControl, Resume, SetElement,
    SetEndEffectorVelocityState, SetJointPositions, SetJointVelocity, SetToolOffset, Standby,
};
use jaus_sim::arm::{ArmParams, SimArm};

mod common;
use common::as4::As4Rig;

const ARM: As4Id = As4Id::new(1, 1, 1);
/// How often the client sends its rates (the RA 3.3 drivers stop after 500 ms without).
const STREAM: Duration = Duration::from_millis(100);

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
        self.rig.ask(Resume {}, Duration::from_millis(300));
        let Message::ReportStatus(s) = self.one(QueryStatus {}) else {
            panic!("no Report Status");
        };
        assert_eq!(s.status, ComponentState::Ready);
    }

    /// Sends `m` every [`STREAM`] for `d`.
    fn stream(&mut self, m: impl Into<Message> + Clone, d: Duration) {
        let n = (d.as_millis() / STREAM.as_millis()).max(1);
        for _ in 0..n {
            let got = self.rig.ask(m.clone(), STREAM);
            assert!(got.is_empty(), "a command is not answered: {got:?}");
        }
    }

    fn joints(&self) -> Vec<f64> {
        self.arm.lock().positions().to_vec()
    }

    fn rates(&self) -> Vec<f64> {
        self.arm.lock().velocities().to_vec()
    }

    /// What the RA 3.3 joint sensors read now: positions, velocities, forces/torques.
    fn reading(&mut self) -> JointState {
        let mut s = JointState::default();
        let now = self.rig.net.now();
        assert!(self.arm.read_joints(now, &mut s));
        s
    }

    fn pose(&mut self) -> ReportEndEffectorPose {
        match self.one(QueryEndEffectorPose {}) {
            Message::ReportEndEffectorPose(p) => p,
            other => panic!("{other:?}"),
        }
    }
}

fn rates(v: &[f64]) -> Vec<JointVelocity> {
    v.iter()
        .map(|&value| JointVelocity::RadiansPerSecond(JointVelocityRadiansPerSecond { value }))
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
fn the_gateway_offers_the_velocity_force_torque_and_tool_offset_services() {
    let mut r = Rig::new();
    let uris = r.rig.service_uris();
    for name in [
        "ManipulatorJointVelocityDriver",
        "ManipulatorEndEffectorVelocityStateDriver",
        "ManipulatorEndEffectorVelocityStateSensor",
        "ManipulatorJointForceTorqueSensor",
        "ManipulatorToolOffsetService",
    ] {
        let uri = format!("urn:jaus:jss:manipulator:{name}");
        assert!(uris.contains(&uri), "{uri} not in {uris:?}");
    }
}

#[test]
fn a_joint_velocity_moves_the_joint_its_way_and_stops_on_zero_and_on_release() {
    let mut r = Rig::new();
    let dof = r.joints().len();
    let mut v = vec![0.0; dof];
    v[0] = 0.3;
    let go = SetJointVelocity {
        joint_velocities: rates(&v),
    };

    // Without control: refused, counted; the arm stays.
    let before = r.joints();
    let refused = r.rig.refused();
    r.stream(go.clone(), Duration::from_millis(800));
    assert!(r.rig.refused() > refused, "not refused without control");
    assert!(
        max_diff(&r.joints(), &before) < 2e-3,
        "moved without control"
    );

    r.take_control();
    // A wrong joint count, a rate beyond the joint's limit: refused, nothing moves.
    let refused = r.rig.refused();
    r.stream(
        SetJointVelocity {
            joint_velocities: rates(&v[..dof - 1]),
        },
        Duration::from_millis(300),
    );
    let limit = r.arm.lock().chain().joints[0].max_rate;
    let mut fast = vec![0.0; dof];
    fast[0] = limit * 1.5;
    r.stream(
        SetJointVelocity {
            joint_velocities: rates(&fast),
        },
        Duration::from_millis(300),
    );
    assert!(r.rig.refused() >= refused + 2, "bad commands not refused");
    assert!(max_diff(&r.joints(), &before) < 2e-3);

    // +0.3 rad/s on the base joint for 2 s: it turns that way, the others stay.
    let start = r.joints();
    r.stream(go.clone(), Duration::from_secs(2));
    let q = r.joints();
    let turned = q[0] - start[0];
    eprintln!(
        "base joint turned {turned:.3} rad in 2 s at 0.3 rad/s; rate now {:.3}",
        r.rates()[0]
    );
    assert!(turned > 0.3, "the base joint turned {turned} rad");
    assert!(
        max_diff(&q[1..], &start[1..]) < 0.02,
        "{q:?} from {start:?}"
    );
    assert!((r.rates()[0] - 0.3).abs() < 0.05, "rate {:?}", r.rates());
    let Message::ReportCommandedJointVelocity(c) = r.one(QueryCommandedJointVelocity {}) else {
        panic!("no Report Commanded Joint Velocity");
    };
    assert_eq!(c.joint_velocities.len(), dof);
    let JointVelocity::RadiansPerSecond(first) = &c.joint_velocities[0] else {
        panic!("{c:?}");
    };
    assert!((first.value - 0.3).abs() < 1e-6);

    // Zero: the joint stops and stays.
    r.stream(
        SetJointVelocity {
            joint_velocities: rates(&vec![0.0; dof]),
        },
        Duration::from_secs(1),
    );
    let stopped = r.joints();
    r.stream(
        SetJointVelocity {
            joint_velocities: rates(&vec![0.0; dof]),
        },
        Duration::from_secs(1),
    );
    assert!(
        max_diff(&r.joints(), &stopped) < 5e-3,
        "drifted after zero: {:?} from {stopped:?}",
        r.joints()
    );

    // At rest, the force/torque sensor reads what the arm's RA 3.3 sensor reads (the
    // torques holding it against gravity).
    let Message::ReportJointForceTorques(f) = r.one(QueryJointForceTorques {}) else {
        panic!("no Report Joint Force Torques");
    };
    let truth = r.reading();
    let reported: Vec<f64> = f
        .actuator_force_torques
        .iter()
        .map(|t| match t {
            ForceTorque::NewtonMetres(t) => t.value,
            ForceTorque::Newtons(f) => f.value,
        })
        .collect();
    assert!(f
        .actuator_force_torques
        .iter()
        .all(|t| matches!(t, ForceTorque::NewtonMetres(_))));
    let scale = truth.efforts.iter().fold(1.0, |m: f64, v| m.max(v.abs()));
    eprintln!(
        "torques: AS-4 {reported:.2?}, RA 3.3 sensor {:.2?}",
        truth.efforts
    );
    assert!(
        max_diff(&reported, &truth.efforts) < 0.1 * scale,
        "{reported:?} vs {:?}",
        truth.efforts
    );

    // The other way, then control released mid-stream: the joint turns back, then
    // stops, the client's further rates refused.
    v[0] = -0.3;
    let back = SetJointVelocity {
        joint_velocities: rates(&v),
    };
    r.stream(back.clone(), Duration::from_secs(1));
    assert!(r.joints()[0] < stopped[0] - 0.1, "did not turn back");
    r.rig.ask(ReleaseControl {}, Duration::from_millis(100));
    let refused = r.rig.refused();
    r.stream(back.clone(), Duration::from_secs(1));
    let released = r.joints();
    r.stream(back, Duration::from_secs(1));
    assert!(r.rig.refused() > refused, "rates taken after release");
    assert!(
        max_diff(&r.joints(), &released) < 5e-3,
        "moving after release: {:?} from {released:?}",
        r.joints()
    );
}

#[test]
fn an_end_effector_velocity_moves_the_tool_point_and_the_sensor_reports_it() {
    let mut r = Rig::new();
    r.take_control();
    // At rest, the tool's velocity is zero.
    let Message::ReportEndEffectorVelocityState(rest) = r.one(QueryEndEffectorVelocityState {})
    else {
        panic!("no Report End Effector Velocity State");
    };
    assert!(
        rest.linear_velocity_x.abs() + rest.linear_velocity_y.abs() + rest.linear_velocity_z.abs()
            < 0.01,
        "{rest:?}"
    );
    let here = r.pose();
    // 5 cm/s up (vehicle z points down), streamed for 2 s; each query between lets the
    // driver run on the last command for its 300 ms.
    let up = SetEndEffectorVelocityState {
        linear_velocity_z: -0.05,
        ..Default::default()
    };
    r.stream(up.clone(), Duration::from_millis(1500));
    // Moving: the sensor's velocity is the Jacobian of the true joints times their rates.
    let Message::ReportEndEffectorVelocityState(moving) = r.one(QueryEndEffectorVelocityState {})
    else {
        panic!("no Report End Effector Velocity State");
    };
    let truth = {
        let a = r.arm.lock();
        let chain = a.chain().clone();
        let mut jac = OMatrix::<f64, U6, Dyn>::zeros(chain.dof());
        chain.jacobian(a.positions(), &mut jac);
        jac * DVector::from_column_slice(a.velocities())
    };
    eprintln!(
        "tool velocity: AS-4 z {:.4} m/s, true {:.4} m/s",
        moving.linear_velocity_z, truth[2]
    );
    assert!(
        (moving.linear_velocity_z - truth[2]).abs() < 0.015,
        "{moving:?} vs {truth:?}"
    );
    assert!(moving.linear_velocity_z < -0.03, "{moving:?}");
    r.stream(up.clone(), Duration::from_millis(500));
    let Message::ReportCommandedEndEffectorVelocityState(c) =
        r.one(QueryCommandedEndEffectorVelocityState {})
    else {
        panic!("no Report Commanded End Effector Velocity State");
    };
    assert!((c.linear_velocity_z + 0.05).abs() < 1e-6, "{c:?}");
    // Stop, and see where it went: up 10 to 15 cm, barely aside.
    r.stream(
        SetEndEffectorVelocityState::default(),
        Duration::from_secs(1),
    );
    let there = r.pose();
    let dz = there.tool_point_z - here.tool_point_z;
    let aside =
        (there.tool_point_x - here.tool_point_x).hypot(there.tool_point_y - here.tool_point_y);
    eprintln!("tool point: {dz:.4} m along z, {aside:.4} m aside");
    assert!(dz < -0.08 && dz > -0.16, "moved {dz} m along z");
    assert!(aside < 0.01, "{aside} m aside");
}

#[test]
fn the_tool_offset_is_the_ra33_tool_point_and_moves_the_reported_pose() {
    let mut r = Rig::new();
    let Message::ReportToolOffset(t0) = r.one(QueryToolOffset {}) else {
        panic!("no Report Tool Offset");
    };
    let before = r.pose();
    let offset = SetToolOffset {
        tool_point_x: t0.tool_point_x,
        tool_point_y: t0.tool_point_y,
        tool_point_z: t0.tool_point_z + 0.1,
    };
    // Without control: refused, nothing changes.
    let refused = r.rig.refused();
    r.rig.ask(offset.clone(), Duration::from_millis(500));
    assert!(r.rig.refused() > refused);
    let Message::ReportToolOffset(same) = r.one(QueryToolOffset {}) else {
        panic!("no Report Tool Offset");
    };
    assert!((same.tool_point_z - t0.tool_point_z).abs() < 1e-6);

    r.take_control();
    r.rig.ask(offset.clone(), Duration::from_secs(1));
    let Message::ReportToolOffset(t1) = r.one(QueryToolOffset {}) else {
        panic!("no Report Tool Offset");
    };
    assert!(
        (t1.tool_point_z - offset.tool_point_z).abs() < 1e-6,
        "{t1:?}"
    );
    // The pose sensor now places the new tool point: 10 cm along the last link's z.
    let after = r.pose();
    let q = r.arm.lock().tool_pose(&Vector3::zeros()).rotation;
    let shift = q * Vector3::new(0.0, 0.0, 0.1);
    let moved = Vector3::new(
        after.tool_point_x - before.tool_point_x,
        after.tool_point_y - before.tool_point_y,
        after.tool_point_z - before.tool_point_z,
    );
    eprintln!("pose moved {moved:?}, expected {shift:?}");
    assert!((moved - shift).norm() < 2e-3, "{moved:?} vs {shift:?}");
}

fn radians(q: &[f64]) -> Vec<JointPosition> {
    q.iter()
        .map(|&value| JointPosition::Radians(JointPositionRadians { value }))
        .collect()
}

#[test]
fn a_list_of_joint_positions_is_driven_through_over_the_joint_move_driver() {
    let mut r = Rig::new();
    let uris = r.rig.service_uris();
    let uri = "urn:jaus:jss:manipulator:ManipulatorJointPositionListDriver".to_string();
    assert!(uris.contains(&uri), "{uri} not in {uris:?}");
    let start = r.joints();
    let a = [0.3, -0.4, 1.2, 0.0, 0.6, 0.0];
    let b = [-0.2, -0.5, 1.0, 0.2, 0.5, 0.3];
    let element = |uid, previous, next, q: &[f64]| {
        Element::holding(
            uid,
            previous,
            next,
            &SetJointPositions {
                joint_positions: radians(q),
            }
            .into(),
        )
        .unwrap()
    };

    // Without control, Execute List is refused; nothing moves.
    let refused = r.rig.refused();
    r.rig.ask(
        ManipulatorExecuteList { element_uid: None },
        Duration::from_millis(500),
    );
    assert!(r.rig.refused() > refused);

    r.take_control();
    let Message::ConfirmElementRequest(ok) = r.one(SetElement {
        request_id: 3,
        elements: vec![element(1, 0, 2, &a), element(2, 1, 0, &b)],
    }) else {
        panic!("Confirm Element Request expected");
    };
    assert_eq!(ok.request_id, 3);
    r.rig.ask(QueryStatus {}, Duration::from_secs(1));
    assert!(
        max_diff(&r.joints(), &start) < 2e-3,
        "moved before Execute List"
    );

    r.rig.ask(
        ManipulatorExecuteList { element_uid: None },
        Duration::from_millis(300),
    );
    // The active element goes 1, then 2, then 0 (done); the arm passes through a on
    // its way and ends at b.
    let mut active = Vec::new();
    let mut nearest_a = f64::INFINITY;
    let mut targets = Vec::new();
    for _ in 0..100 {
        let Message::ReportManipulatorActiveElement(e) = r.one(QueryManipulatorActiveElement {})
        else {
            panic!("Report Manipulator Active Element expected");
        };
        if active.last() != Some(&e.element_uid) {
            active.push(e.element_uid);
        }
        nearest_a = nearest_a.min(max_diff(&r.joints(), &a));
        if e.element_uid == 0 {
            break;
        }
        // The target being driven to (the active element may have moved on since).
        let Message::ReportCommandedJointPositions(c) = r.one(QueryCommandedJointPositions {})
        else {
            panic!("Report Commanded Joint Positions expected");
        };
        let got: Vec<f64> = c
            .joint_positions
            .iter()
            .map(|p| match p {
                JointPosition::Radians(r) => r.value,
                JointPosition::Metres(m) => m.value,
            })
            .collect();
        let target = if max_diff(&got, &a) < 1e-6 {
            'a'
        } else if max_diff(&got, &b) < 1e-6 {
            'b'
        } else {
            // Done: the Joint Position Driver answers (the joints measured).
            '-'
        };
        if targets.last() != Some(&target) {
            targets.push(target);
        }
        for _ in 0..10 {
            r.rig.net.run_for(Duration::from_millis(20));
            nearest_a = nearest_a.min(max_diff(&r.joints(), &a));
        }
    }
    let end = r.joints();
    eprintln!(
        "active elements {active:?}, targets {targets:?}; passed within {:.4} rad of a, ended {:.5} rad from b",
        nearest_a,
        max_diff(&end, &b)
    );
    assert_eq!(active, vec![1, 2, 0]);
    assert_eq!(&targets[..2], &['a', 'b'], "{targets:?}");
    assert!(nearest_a < 0.02, "did not pass through a: {nearest_a} rad");
    assert!(max_diff(&end, &b) < 0.005, "ended at {end:?}, not {b:?}");
}

#[test]
fn standby_stops_the_rates_and_another_driver_ends_a_list() {
    let mut r = Rig::new();
    r.take_control();
    let dof = r.joints().len();
    let mut v = vec![0.0; dof];
    v[0] = 0.3;
    let go = SetJointVelocity {
        joint_velocities: rates(&v),
    };
    r.stream(go.clone(), Duration::from_secs(1));
    assert!(r.rates()[0] > 0.2, "not moving: {:?}", r.rates());
    // Standby (the JSIDL's stopMotion on leaving Ready): the joint stops, the commanded
    // rates read zero, and rates are refused until Resume.
    r.rig.ask(Standby {}, Duration::from_millis(100));
    let refused = r.rig.refused();
    r.stream(go.clone(), Duration::from_secs(1));
    let still = r.joints();
    r.stream(go, Duration::from_millis(500));
    assert!(r.rig.refused() > refused, "rates taken in Standby");
    assert!(max_diff(&r.joints(), &still) < 5e-3, "moving in Standby");
    let Message::ReportCommandedJointVelocity(c) = r.one(QueryCommandedJointVelocity {}) else {
        panic!("no Report Commanded Joint Velocity");
    };
    assert!(c.joint_velocities.iter().all(|v| match v {
        JointVelocity::RadiansPerSecond(r) => r.value == 0.0,
        JointVelocity::MetresPerSecond(m) => m.value == 0.0,
    }));

    // A list under way ends when the Joint Position Driver takes the arm.
    r.rig.ask(Resume {}, Duration::from_millis(300));
    let q = r.joints();
    let (mut a, mut b) = (q.clone(), q.clone());
    a[0] -= 0.5;
    b[0] -= 1.0;
    let element = |uid, previous, next, q: &[f64]| {
        Element::holding(
            uid,
            previous,
            next,
            &SetJointPositions {
                joint_positions: radians(q),
            }
            .into(),
        )
        .unwrap()
    };
    let Message::ConfirmElementRequest(_) = r.one(SetElement {
        request_id: 1,
        elements: vec![element(1, 0, 2, &a), element(2, 1, 0, &b)],
    }) else {
        panic!("Confirm Element Request expected");
    };
    r.rig.ask(
        ManipulatorExecuteList { element_uid: None },
        Duration::from_millis(500),
    );
    let Message::ReportManipulatorActiveElement(e) = r.one(QueryManipulatorActiveElement {}) else {
        panic!("Report Manipulator Active Element expected");
    };
    assert_eq!(e.element_uid, 1);
    let here = r.joints();
    r.rig.ask(
        SetJointPositions {
            joint_positions: radians(&here),
        },
        Duration::from_millis(300),
    );
    let Message::ReportManipulatorActiveElement(e) = r.one(QueryManipulatorActiveElement {}) else {
        panic!("Report Manipulator Active Element expected");
    };
    assert_eq!(e.element_uid, 0, "the list still runs");
    r.rig.net.run_for(Duration::from_secs(3));
    let end = r.joints();
    eprintln!(
        "list cut short {:.3} rad into the first element; {:.4} rad from where the joint driver held it",
        q[0] - here[0],
        max_diff(&end, &here)
    );
    assert!(max_diff(&end, &here) < 0.05, "the list went on: {end:?}");
    assert!(end[0] > b[0] + 0.3, "the list went on: {end:?}");
}
