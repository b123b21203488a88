//! The AS-4 judge (`jaus conform --as4`) leaves the vehicle as it found it: against the
//! SDK's own AS-4 component (the demo vehicle behind the node's gateway, in memory on a
//! virtual clock), the run ends with the component in Standby, nobody in control, and a
//! client can take control at once. Shutdown is sent only when asked.

use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::net::as5669a::{As4Id, As4Message};
use jaus::net::NodeConfig;
use jaus::Address;
use jaus_as4::gateway::{DualNode, GatewayConfig};
use jaus_as4::messages::{
    ComponentState, ControlConfirmation, Message, QueryStatus, RequestControl,
};
use jaus_conform::as4::{run_as4, As4Options, As4Session, MemoryAs4Session};
use jaus_conform::{report, RunReport, Verdict};

/// The vehicle's AS-4 component.
const VEHICLE: As4Id = As4Id::new(1, 1, 1);
/// A client other than the judge (42.1.1).
const CLIENT: As4Id = As4Id::new(43, 1, 1);

fn session(t0: Instant) -> MemoryAs4Session {
    let node = jaus_sim::demo::vehicle_node(t0, NodeConfig::default(), 1, 1).expect("vehicle");
    let config = GatewayConfig::new(VEHICLE, Address::new(1, 1, 60, 1), 1, "demo vehicle");
    MemoryAs4Session::new(DualNode::new(node, config).expect("gateway"), t0)
}

fn judge(shutdown: bool) -> As4Options {
    As4Options {
        allow_motion: true,
        shutdown,
        ..As4Options::default()
    }
}

fn outcome<'r>(run: &'r RunReport, id: &str) -> Option<&'r jaus_conform::Outcome> {
    run.components[0].outcomes.iter().find(|o| o.check.id == id)
}

/// Sends `msg` from `CLIENT` and waits a second for an answer with message ID `id`.
fn ask(session: &mut dyn As4Session, msg: Message, id: u16) -> Option<Message> {
    let body = msg.to_bytes().expect("encodes");
    session.send(As4Message::new(msg.code().0, VEHICLE, CLIENT, body));
    let deadline = session.now() + Duration::from_secs(1);
    while let Some(a) = session.recv(deadline) {
        if a.message.message_id == id && a.message.destination == CLIENT {
            return Message::decode(jaus::CommandCode(id), &a.message.body).ok();
        }
    }
    None
}

fn state(session: &mut dyn As4Session) -> Option<ComponentState> {
    match ask(session, QueryStatus {}.into(), 0x4002)? {
        Message::ReportStatus(r) => Some(r.status),
        _ => None,
    }
}

#[test]
fn the_judge_leaves_the_vehicle_in_standby_and_free() {
    let t0 = Instant::now();
    let mut session = session(t0);
    let run = run_as4(&mut session, &judge(false));
    println!("{}", report::summary(&run));
    let bad: Vec<String> = run.components[0]
        .outcomes
        .iter()
        .filter(|o| o.verdict != Verdict::Pass)
        .map(|o| format!("{} {:?}: {}", o.check.id, o.verdict, o.detail))
        .collect();
    assert!(bad.is_empty(), "{bad:#?}");
    assert!(outcome(&run, "as4.management.shutdown").is_none());
    let release = outcome(&run, "as4.control.release").expect("the last check");
    println!("as4.control.release: {}", release.detail);
    assert_eq!(
        run.components[0]
            .outcomes
            .last()
            .map(|o| o.check.id.as_str()),
        Some("as4.control.release")
    );
    assert!(
        release.detail.contains("Report Control names nobody"),
        "{}",
        release.detail
    );
    // The pose and the list it loaded are not undone, and the detail says so.
    assert!(
        release.detail.contains("not restored") && release.detail.contains("Set Element"),
        "{}",
        release.detail
    );
    // Not in Shutdown: in Standby, as found; another client takes control at once.
    assert_eq!(state(&mut session), Some(ComponentState::Standby));
    let confirm = ask(
        &mut session,
        RequestControl { authority_code: 1 }.into(),
        0x000F,
    );
    match confirm {
        Some(Message::ConfirmControl(c)) => {
            assert_eq!(c.response_code, ControlConfirmation::ControlAccepted)
        }
        other => panic!("Request Control answered by {other:?}"),
    }
}

#[test]
fn a_second_run_passes_as_the_first() {
    let t0 = Instant::now();
    let mut session = session(t0);
    let first = run_as4(&mut session, &judge(false));
    assert!(first.passed());
    let second = run_as4(&mut session, &judge(false));
    println!("{}", report::summary(&second));
    assert!(second.passed());
    let request = outcome(&second, "as4.control.request").expect("planned");
    assert_eq!(request.verdict, Verdict::Pass, "{}", request.detail);
}

#[test]
fn shutdown_is_sent_only_when_asked() {
    let t0 = Instant::now();
    let mut session = session(t0);
    let run = run_as4(&mut session, &judge(true));
    let shutdown = outcome(&run, "as4.management.shutdown").expect("asked for");
    assert_eq!(shutdown.verdict, Verdict::Pass, "{}", shutdown.detail);
    assert!(outcome(&run, "as4.control.release").is_none());
    assert_eq!(state(&mut session), Some(ComponentState::Shutdown));
    assert!(!As4Options::default().shutdown);
}
