//! `jaus conform --as4 --plan` (`jaus_conform::as4::planned`): checks planned from the
//! AS-4 service definitions of whatever component answers. Against the SDK's own
//! vehicle (the demo vehicle behind the node's gateway: Core + Mobility, in memory on a
//! virtual clock) and its own arm (Core + Manipulator v2.0) every required planned check
//! passes; a vendor service known only
//! from a YAML fixture (tests/as4_vendor/beacon.yaml) is planned and checked; a broken
//! one fails exactly the checks it breaks.

use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Instant;

use jaus::net::as5669a::As4Id;
use jaus::net::NodeConfig;
use jaus::{Address, CommandCode, RawMessage};
use jaus_as4::component::As4Component;
use jaus_as4::core::CoreConfig;
use jaus_as4::gateway::{DualNode, GatewayConfig};
use jaus_as4::node::As4Node;
use jaus_as4::service::{Cx, Handled, Request, Service, ServiceId};
use jaus_as4::Message;
use jaus_conform::as4::planned::{plan, run_planned, Definitions, PlanOptions};
use jaus_conform::as4::{As4Host, As4Options, MemoryAs4Session};
use jaus_conform::{report, Level, RunReport, Verdict};

const VEHICLE: As4Id = As4Id::new(1, 1, 1);
const BEACON: As4Id = As4Id::new(7, 1, 3);

const QUERY_RATE: CommandCode = CommandCode(0xF020);
const REPORT_RATE: CommandCode = CommandCode(0xF021);
const SET_RATE: CommandCode = CommandCode(0xF022);

fn vendor_defs() -> Definitions {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/as4_vendor");
    Definitions::load(&[dir], &[]).expect("the fixture loads")
}

fn print(run: &RunReport) {
    println!("{}", report::summary(run));
    for o in &run.components[0].outcomes {
        println!(
            "{} [{:?}] {:?}: {}",
            o.check.id, o.check.level, o.verdict, o.detail
        );
    }
}

fn outcome<'r>(run: &'r RunReport, id: &str) -> &'r jaus_conform::Outcome {
    run.components[0]
        .outcomes
        .iter()
        .find(|o| o.check.id == id)
        .unwrap_or_else(|| panic!("{id} not planned"))
}

fn failed(run: &RunReport) -> Vec<String> {
    let mut v: Vec<String> = run.components[0]
        .outcomes
        .iter()
        .filter(|o| o.verdict == Verdict::Fail)
        .map(|o| o.check.id.clone())
        .collect();
    v.sort();
    v
}

#[test]
fn every_required_check_planned_for_core_and_mobility_passes_on_our_vehicle() {
    let t0 = Instant::now();
    let node = jaus_sim::demo::vehicle_node(t0, NodeConfig::default(), 1, 1).expect("vehicle");
    let config = GatewayConfig::new(VEHICLE, Address::new(1, 1, 60, 1), 1, "demo vehicle");
    let mut session = MemoryAs4Session::new(DualNode::new(node, config).expect("gateway"), t0);
    let defs = Definitions::as4().expect("jaus-as4's definitions");
    // With motion allowed: a Driver's commands are sent too (from a client without
    // control; from the controller only while Ready, which the plan does not change).
    let opts = As4Options {
        allow_motion: true,
        ..As4Options::default()
    };
    let run = run_planned(&mut session, &defs, &opts);
    print(&run);
    let c = &run.components[0];
    assert_eq!(c.address, VEHICLE.to_string());
    assert_eq!(outcome(&run, "as4.planned.services").verdict, Verdict::Pass);
    let bad: Vec<String> = c
        .outcomes
        .iter()
        .filter(|o| o.check.level == Level::Required && o.verdict != Verdict::Pass)
        .map(|o| format!("{} {:?}: {}", o.check.id, o.verdict, o.detail))
        .collect();
    assert!(bad.is_empty(), "{bad:#?}");
    assert!(run.passed());
    // Queries, commands and subscriptions, of the Core and of Mobility.
    for id in [
        "as4.management.query.QueryStatus",
        "as4.discovery.query.QueryIdentification",
        "as4.velocity_state_sensor.query.QueryVelocityState",
        "as4.velocity_state_sensor.event.QueryVelocityState",
        "as4.local_pose_sensor.query.QueryLocalPose",
        "as4.local_pose_sensor.command.SetLocalPose.outsider",
    ] {
        assert_eq!(outcome(&run, id).verdict, Verdict::Pass, "{id}");
    }
    // Each check cites its service and the transition's file:line.
    let o = outcome(&run, "as4.local_pose_sensor.query.QueryLocalPose");
    assert!(
        o.check
            .rule
            .source
            .starts_with("urn:jaus:jss:mobility:LocalPoseSensor v1.0"),
        "{}",
        o.check.rule.source
    );
    assert!(
        o.check.rule.source.contains("mobility_services.yaml:"),
        "{}",
        o.check.rule.source
    );
    // The pose set by the controller was read back, then put back.
    let o = outcome(
        &run,
        "as4.local_pose_sensor.command.SetLocalPose.controller",
    );
    assert_eq!(o.verdict, Verdict::Pass, "{}", o.detail);
    // Refused from a client without control, not run for the controller: the
    // component is in Standby (the transition lies under Ready).
    let o = outcome(
        &run,
        "as4.primitive_driver.command.SetWrenchEffort.outsider",
    );
    assert_eq!(o.verdict, Verdict::Pass, "{}", o.detail);
    let o = outcome(
        &run,
        "as4.primitive_driver.command.SetWrenchEffort.controller",
    );
    assert_eq!(o.verdict, Verdict::Inconclusive);
    assert!(o.detail.contains("Ready"), "{}", o.detail);
    // Without --allow-motion a Driver's commands are planned but not sent at all.
    let listed: Vec<(String, u8, u8)> = defs
        .services()
        .iter()
        .map(|s| {
            let mut v = s
                .version
                .split('.')
                .map(|p| p.parse::<u8>().expect("version"));
            (s.uri.clone(), v.next().unwrap_or(1), v.next().unwrap_or(0))
        })
        .collect();
    let (plan, unknown) = plan::plan(&defs, &listed, PlanOptions::default());
    assert!(unknown.is_empty(), "{unknown:?}");
    for id in [
        "as4.primitive_driver.command.SetWrenchEffort.outsider",
        "as4.primitive_driver.command.SetWrenchEffort.controller",
        "as4.local_waypoint_list_driver.command.ExecuteList.outsider",
    ] {
        let p = plan.iter().find(|p| p.check.id == id).expect(id);
        assert!(
            p.skip
                .as_deref()
                .is_some_and(|w| w.contains("--allow-motion")),
            "{id}: {:?}",
            p.skip
        );
    }
    assert!(plan
        .iter()
        .filter(|p| p.check.id.contains("local_pose_sensor"))
        .all(|p| p.skip.is_none()));
    // The reports read as the scenario's do.
    assert!(report::junit(&run).contains("as4.local_pose_sensor.query.QueryLocalPose"));
}

/// A vendor's beacon, written by hand as a [`Service`], with faults to switch on.
#[derive(Debug, Default)]
struct Beacon {
    rate: u16,
    /// Answers Query Beacon Rate with a one-byte report (its field is a u16).
    short_report: bool,
    /// Sets the rate for anyone, controller or not.
    obeys_anyone: bool,
}

impl<E: 'static> Service<E> for Beacon {
    fn id(&self) -> ServiceId {
        ServiceId::new("urn:acme:Beacon", 1, 0)
    }
    fn receives(&self, code: CommandCode) -> bool {
        code == SET_RATE || code == QUERY_RATE
    }
    fn needs_control(&self, code: CommandCode) -> bool {
        code == SET_RATE && !self.obeys_anyone
    }
    fn needs_ready(&self, _code: CommandCode) -> bool {
        false
    }
    fn handle(&mut self, _cx: &mut Cx<'_, E>, request: &Request<'_>) -> Handled {
        match request.message {
            Message::Raw(r) if r.code == SET_RATE => match r.body.get(..2) {
                Some(b) if u16::from_le_bytes([b[0], b[1]]) <= 600 => {
                    self.rate = u16::from_le_bytes([b[0], b[1]]);
                    Handled::Done
                }
                _ => Handled::Refused("rate out of range".into()),
            },
            Message::Raw(r) if r.code == QUERY_RATE => {
                let mut body = self.rate.to_le_bytes().to_vec();
                if self.short_report {
                    body.truncate(1);
                }
                Handled::Reply(Message::Raw(RawMessage {
                    code: REPORT_RATE,
                    body,
                }))
            }
            _ => Handled::NotMine,
        }
    }
}

fn beacon_session(beacon: Beacon) -> MemoryAs4Session {
    let t0 = Instant::now();
    let component =
        As4Component::new(BEACON, CoreConfig::named("acme beacon")).with_service(beacon);
    let node: As4Node<(), SocketAddr> = As4Node::new(()).with_component(component);
    MemoryAs4Session::new(As4Host::new(node), t0)
}

const BEACON_CHECKS: [&str; 5] = [
    "as4.beacon.query.QueryBeaconRate",
    "as4.beacon.command.SetBeaconRate.outsider",
    "as4.beacon.command.SetBeaconRate.controller",
    "as4.beacon.event.QueryBeaconRate",
    "as4.beacon.command.SetBeaconRate.command_event",
];

#[test]
fn every_required_check_planned_for_the_manipulator_passes_on_our_arm() {
    // The stock RA 3.3 manipulator components over the simulated 6-axis arm, behind the
    // gateway: the Manipulator v2.0 services are planned from their definitions.
    let t0 = Instant::now();
    let arm = jaus_sim::arm::SimArm::new(jaus_sim::arm::ArmParams::six_axis());
    let mut node = jaus::net::Node::new(NodeConfig::default(), t0);
    for c in jaus_sim::arm_demo::arm_components(&arm, 1, 1, t0) {
        node.add_boxed(c).expect("arm component");
    }
    let config = GatewayConfig::new(VEHICLE, Address::new(1, 1, 60, 1), 1, "arm");
    let mut session = MemoryAs4Session::new(DualNode::new(node, config).expect("gateway"), t0);
    let defs = Definitions::as4().expect("jaus-as4's definitions");
    let opts = As4Options {
        allow_motion: true,
        ..As4Options::default()
    };
    let run = run_planned(&mut session, &defs, &opts);
    print(&run);
    let bad: Vec<String> = run.components[0]
        .outcomes
        .iter()
        .filter(|o| o.check.level == Level::Required && o.verdict != Verdict::Pass)
        .map(|o| format!("{} {:?}: {}", o.check.id, o.verdict, o.detail))
        .collect();
    assert!(bad.is_empty(), "{bad:#?}");
    for id in [
        "as4.manipulator_joint_position_sensor.query.QueryJointPositions",
        "as4.manipulator_joint_velocity_sensor.query.QueryJointVelocity",
        "as4.manipulator_specification_service.query.QueryManipulatorSpecifications",
        "as4.manipulator_end_effector_pose_sensor.query.QueryEndEffectorPose",
        "as4.manipulator_joint_position_driver.query.QueryCommandedJointPositions",
        "as4.manipulator_joint_position_driver.command.SetJointPositions.outsider",
        "as4.manipulator_end_effector_pose_driver.command.SetEndEffectorPose.outsider",
    ] {
        assert_eq!(outcome(&run, id).verdict, Verdict::Pass, "{id}");
    }
    // Where the rule comes from: the service and the file:line of its transition.
    let o = outcome(
        &run,
        "as4.manipulator_joint_position_sensor.query.QueryJointPositions",
    );
    assert!(
        o.check.rule.source.contains("manipulator_services.yaml:"),
        "{}",
        o.check.rule.source
    );
}

#[test]
fn a_vendor_service_from_its_yaml_is_planned_and_checked() {
    let defs = vendor_defs();
    let mut session = beacon_session(Beacon {
        rate: 120,
        ..Beacon::default()
    });
    let run = run_planned(&mut session, &defs, &As4Options::default());
    print(&run);
    for id in BEACON_CHECKS {
        let o = outcome(&run, id);
        assert_eq!(o.verdict, Verdict::Pass, "{id}: {}", o.detail);
        assert!(o.check.rule.source.starts_with("urn:acme:Beacon v1.0"));
        assert!(o.check.rule.source.contains("beacon.yaml:"));
    }
    assert!(failed(&run).is_empty(), "{:?}", failed(&run));
    assert!(run.passed());
    // The evidence names the vendor's messages by the definitions.
    let o = outcome(&run, "as4.beacon.query.QueryBeaconRate");
    assert!(o.evidence.iter().any(|e| e.message == "ReportBeaconRate"));
    // Our Core v1.1 runs command events: confirmed, then reported Unsuccessful for a
    // client without control.
    let o = outcome(&run, "as4.beacon.command.SetBeaconRate.command_event");
    assert!(o.detail.contains("reported Unsuccessful"), "{}", o.detail);
    // The controller's value was put back.
    let o = outcome(&run, "as4.beacon.command.SetBeaconRate.controller");
    assert!(o.detail.contains("rate: 120 → 119"), "{}", o.detail);
}

#[test]
fn a_broken_vendor_service_fails_exactly_the_checks_it_breaks() {
    let defs = vendor_defs();
    // A wrong report: the query and the subscription to it fail, nothing else.
    let mut session = beacon_session(Beacon {
        rate: 120,
        short_report: true,
        ..Beacon::default()
    });
    let run = run_planned(&mut session, &defs, &As4Options::default());
    print(&run);
    assert_eq!(
        failed(&run),
        [
            "as4.beacon.event.QueryBeaconRate",
            "as4.beacon.query.QueryBeaconRate"
        ]
    );
    assert!(!run.passed());
    let o = outcome(&run, "as4.beacon.query.QueryBeaconRate");
    assert!(o.detail.contains("ReportBeaconRate"), "{}", o.detail);
    // A command obeyed without control: its outsider check fails, nothing else (the
    // beacon says the command needs no control, so the component does not take its
    // experimental ID inside a command event: refused, the command_event check passes).
    let mut session = beacon_session(Beacon {
        rate: 120,
        obeys_anyone: true,
        ..Beacon::default()
    });
    let run = run_planned(&mut session, &defs, &As4Options::default());
    print(&run);
    assert_eq!(failed(&run), ["as4.beacon.command.SetBeaconRate.outsider"]);
    let o = outcome(&run, "as4.beacon.command.SetBeaconRate.outsider");
    assert!(o.detail.contains("rate: 120 → 119"), "{}", o.detail);
    let o = outcome(&run, "as4.beacon.command.SetBeaconRate.command_event");
    assert!(o.detail.contains("refused"), "{}", o.detail);
}
