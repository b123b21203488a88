//! Command events of the Core runtime (Events v1.1): a Create Command Event's command
//! runs as if its client had sent it, confirmed first and reported by a Command Event;
//! commands the component does not take are refused with why.

mod core_common;

use std::time::Instant;

use core_common::*;
use jaus_as4::component::{As4Component, Outgoing};
use jaus_as4::core::CoreConfig;
use jaus_as4::{
    embedded, CommandEvent, CommandResult, ComponentState, CreateCommandEvent, CreateEvent,
    EventRejection, EventType, Message, QueryStatus, QueryTravelSpeed, RejectEventRequest,
    ReportTravelSpeed, RequestControl, Resume, SetLocalWaypoint, SetTravelSpeed,
};

fn command_event(request_id: u8, command: impl Into<Message>) -> CreateCommandEvent {
    CreateCommandEvent {
        request_id,
        maximum_allowed_duration: 10,
        command_message: embedded::encode(&command.into()).unwrap(),
    }
}

/// The request id and event id of the Confirm Event Request in `out`, and the Command
/// Event's event id and result after it, both for `to`.
fn confirmed_then_completed(
    out: &[Outgoing],
    to: jaus::net::as5669a::As4Id,
) -> (u8, u8, CommandResult) {
    let mine: Vec<&Message> = out
        .iter()
        .filter(|o| o.to == to)
        .map(|o| &o.message)
        .collect();
    let confirm = mine
        .iter()
        .position(|m| matches!(m, Message::ConfirmEventRequest(_)))
        .unwrap_or_else(|| panic!("no Confirm Event Request in {out:?}"));
    let done = mine
        .iter()
        .position(|m| matches!(m, Message::CommandEvent(_)))
        .unwrap_or_else(|| panic!("no Command Event in {out:?}"));
    assert!(confirm < done, "the confirmation comes first: {out:?}");
    let (Message::ConfirmEventRequest(c), Message::CommandEvent(e)) = (mine[confirm], mine[done])
    else {
        unreachable!()
    };
    assert_eq!(c.event_id, e.event_id, "one event id: {out:?}");
    (c.request_id, c.event_id, e.command_result)
}

fn rejected(out: &[Outgoing]) -> (EventRejection, String) {
    match out {
        [Outgoing {
            message:
                Message::RejectEventRequest(RejectEventRequest {
                    response_code: Some(code),
                    error_message,
                    ..
                }),
            ..
        }] => (*code, error_message.clone().unwrap_or_default()),
        _ => panic!("one Reject Event Request expected in {out:?}"),
    }
}

fn controlled() -> (As4Component<()>, Instant) {
    let (mut c, _) = component(CoreConfig::named("cmd"));
    let t = Instant::now();
    send(&mut c, t, A, RequestControl { authority_code: 5 });
    assert_eq!(c.controller(), Some(A));
    (c, t)
}

#[test]
fn a_core_command_runs_as_an_event_and_reports_its_success() {
    let (mut c, t) = controlled();
    assert_eq!(c.state(), ComponentState::Standby);
    let out = send(&mut c, t, A, command_event(3, Resume {}));
    let (request, _, result) = confirmed_then_completed(&out, A);
    assert_eq!(request, 3);
    assert_eq!(result, CommandResult::Successful);
    assert_eq!(c.state(), ComponentState::Ready, "Resume ran");
    // It held no event: Query Events lists none afterwards.
    assert!(c.core().events().is_empty());
}

#[test]
fn a_services_command_runs_with_its_answer_between_confirmation_and_result() {
    let (mut c, t) = controlled();
    send(&mut c, t, A, Resume {});
    let out = send(
        &mut c,
        t,
        A,
        command_event(4, SetTravelSpeed { speed: 2.5 }),
    );
    assert_eq!(
        confirmed_then_completed(&out, A).2,
        CommandResult::Successful
    );
    let Message::ReportTravelSpeed(ReportTravelSpeed { speed }) =
        only_for(&send(&mut c, t, B, QueryTravelSpeed {}), B)
    else {
        panic!("no report");
    };
    assert!((speed - 2.5).abs() < 0.01, "the service took it: {speed}");
}

#[test]
fn a_command_refused_by_control_completes_unsuccessful_and_is_counted() {
    let (mut c, t) = controlled();
    send(&mut c, t, A, Resume {});
    let before = c.stats().not_controller;
    // B does not control the component: confirmed, run as if B sent it, refused.
    let out = send(
        &mut c,
        t,
        B,
        command_event(5, SetTravelSpeed { speed: 9.0 }),
    );
    assert_eq!(
        confirmed_then_completed(&out, B).2,
        CommandResult::Unsuccessful
    );
    assert_eq!(c.stats().not_controller, before + 1);
    assert!(
        out.iter().all(|o| o.to == B),
        "nothing for the controller: {out:?}"
    );
}

#[test]
fn command_events_the_component_cannot_run_are_refused_with_why() {
    let (mut c, t) = controlled();
    // A query is not a command.
    let (code, why) = rejected(&send(&mut c, t, A, command_event(1, QueryStatus {})));
    assert_eq!(code, EventRejection::MessageNotSupported);
    assert!(
        why.contains("QueryStatus") && why.contains("not a command"),
        "{why}"
    );
    // A command nothing of this component receives.
    let (code, why) = rejected(&send(
        &mut c,
        t,
        A,
        command_event(2, SetLocalWaypoint::default()),
    ));
    assert_eq!(code, EventRejection::MessageNotSupported);
    assert!(why.contains("SetLocalWaypoint"), "{why}");
    // An Events message is not run as a command event.
    let nested = CreateEvent {
        request_id: 1,
        event_type: EventType::EveryChange,
        requested_periodic_rate: 0.0,
        query_message: embedded::encode(&QueryStatus {}.into()).unwrap(),
    };
    let (code, _) = rejected(&send(&mut c, t, A, command_event(3, nested)));
    assert_eq!(code, EventRejection::MessageNotSupported);
    // Bytes that are no message.
    let mut bad = command_event(4, Resume {});
    bad.command_message = vec![0x05];
    let (code, why) = rejected(&send(&mut c, t, A, bad));
    assert_eq!(code, EventRejection::InvalidEventSetup);
    assert!(why.contains("does not decode"), "{why}");
    assert_eq!(c.state(), ComponentState::Standby, "nothing ran");
}

#[test]
fn a_command_event_takes_an_event_id_no_subscription_holds() {
    let (mut c, t) = controlled();
    let sub = CreateEvent {
        request_id: 1,
        event_type: EventType::EveryChange,
        requested_periodic_rate: 0.0,
        query_message: embedded::encode(&QueryStatus {}.into()).unwrap(),
    };
    send(&mut c, t, A, sub);
    assert_eq!(c.core().events().len(), 1);
    let out = send(&mut c, t, A, command_event(7, Resume {}));
    let (_, event_id, result) = confirmed_then_completed(&out, A);
    assert_eq!(result, CommandResult::Successful);
    assert_ne!(event_id, 0, "id 0 is the subscription's");
    assert_eq!(c.core().events().len(), 1, "the subscription stays");
    // The Command Event message itself round-trips.
    let e = CommandEvent {
        event_id,
        command_result: CommandResult::Successful,
    };
    let bytes = embedded::encode(&e.clone().into()).unwrap();
    assert_eq!(embedded::decode(&bytes).unwrap(), Message::CommandEvent(e));
}
