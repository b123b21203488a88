//! Core v1.1 command events on the demo vehicle behind the gateway: a client runs
//! Resume, Set Local Pose, the waypoint list and Execute List each inside a Create Command
//! Event (as a Mission Spooler does), every one confirmed and reported Successful, Execute
//! List only once the simulated vehicle has driven the list; a list interrupted by
//! Standby is reported Unsuccessful; the same command event from a client without
//! control is reported Unsuccessful and changes nothing.

mod common;

use std::time::Duration;

use common::as4::As4Rig;
use jaus_as4::{
    embedded, CommandResult, ComponentState, CreateCommandEvent, Element, ExecuteList, Message,
    QueryLocalPose, QueryStatus, SetElement, SetLocalPose, SetLocalWaypoint,
};

/// Sends `command` inside a Create Command Event; the Confirm Event Request's event id,
/// the Command Event's result (for the same id) and what else came back.
fn command_event(
    rig: &mut As4Rig,
    request_id: u8,
    command: impl Into<Message>,
) -> (CommandResult, Vec<Message>) {
    let got = rig.ask(
        CreateCommandEvent {
            request_id,
            maximum_allowed_duration: 5,
            command_message: embedded::encode(&command.into()).expect("encodes"),
        },
        Duration::from_millis(500),
    );
    let confirmed = got
        .iter()
        .find_map(|m| match m {
            Message::ConfirmEventRequest(c) if c.request_id == request_id => Some(c.event_id),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no Confirm Event Request in {got:?}"));
    let result = got
        .iter()
        .find_map(|m| match m {
            Message::CommandEvent(e) if e.event_id == confirmed => Some(e.command_result),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no Command Event for event {confirmed} in {got:?}"));
    let others = got
        .into_iter()
        .filter(|m| {
            !matches!(
                m,
                Message::ConfirmEventRequest(_) | Message::CommandEvent(_)
            )
        })
        .collect();
    (result, others)
}

fn waypoint(x: f64, y: f64) -> Message {
    SetLocalWaypoint {
        x,
        y,
        waypoint_tolerance: Some(0.5),
        ..Default::default()
    }
    .into()
}

fn position(rig: &mut As4Rig) -> (f64, f64) {
    let Message::ReportLocalPose(p) = rig.one(QueryLocalPose {
        presence_vector: 0x0003,
    }) else {
        panic!("Report Local Pose expected")
    };
    (p.x.expect("x"), p.y.expect("y"))
}

#[test]
fn commands_inside_command_events_drive_the_vehicle_to_its_waypoints() {
    let mut rig = As4Rig::demo_vehicle();
    rig.take_control();

    // Resume, a Core command: Successful, and the component is Ready.
    let (r, _) = command_event(&mut rig, 1, jaus_as4::Resume {});
    assert_eq!(r, CommandResult::Successful);
    let Message::ReportStatus(s) = rig.one(QueryStatus {}) else {
        panic!("Report Status expected")
    };
    assert_eq!(s.status, ComponentState::Ready);

    // The local frame, then two waypoints 4 m ahead and 3 m to the left of that.
    let pose = SetLocalPose {
        x: Some(0.0),
        y: Some(0.0),
        yaw: Some(0.0),
        ..Default::default()
    };
    assert_eq!(
        command_event(&mut rig, 2, pose).0,
        CommandResult::Successful
    );
    let list = SetElement {
        request_id: 9,
        elements: vec![
            Element::holding(1, 0, 2, &waypoint(4.0, 0.0)).expect("element"),
            Element::holding(2, 1, 0, &waypoint(4.0, 3.0)).expect("element"),
        ],
    };
    let (r, others) = command_event(&mut rig, 3, list);
    assert_eq!(r, CommandResult::Successful);
    // The command's own answer comes back to the client too.
    assert!(
        others
            .iter()
            .any(|m| matches!(m, Message::ConfirmElementRequest(c) if c.request_id == 9)),
        "{others:?}"
    );
    // Execute List is carried out until the list is done: confirmed now, its Command
    // Event when the vehicle has driven the list.
    let execute = ExecuteList {
        speed: 1.5,
        element_uid: Some(1),
    };
    let event_id = confirmed(&mut rig, 4, execute);
    let (mut at, mut result) = (position(&mut rig), None);
    for _ in 0..60 {
        rig.net.run_for(Duration::from_millis(500));
        let got = rig.ask(
            QueryLocalPose {
                presence_vector: 0x0003,
            },
            Duration::from_millis(300),
        );
        for m in got {
            match m {
                Message::ReportLocalPose(p) => at = (p.x.expect("x"), p.y.expect("y")),
                Message::CommandEvent(e) if e.event_id == event_id => {
                    result = Some((e.command_result, at))
                }
                _ => {}
            }
        }
        if result.is_some() {
            break;
        }
    }
    let (result, last) = result.expect("a Command Event for Execute List");
    assert_eq!(result, CommandResult::Successful);
    // Reported on the last leg (the pose read in the same half second), and the vehicle
    // stops at the last waypoint.
    assert!(
        (last.0 - 4.0).hypot(last.1 - 3.0) < 1.5,
        "Execute List reported done at ({:.2}, {:.2})",
        last.0,
        last.1
    );
    rig.net.run_for(Duration::from_secs(2));
    let end = position(&mut rig);
    assert!(
        (end.0 - 4.0).hypot(end.1 - 3.0) < 1.0,
        "the vehicle ended at ({:.2}, {:.2})",
        end.0,
        end.1
    );
}

/// Sends `command` inside a Create Command Event; its event id, confirmed, and that no
/// Command Event came yet (the command is still being carried out).
fn confirmed(rig: &mut As4Rig, request_id: u8, command: impl Into<Message>) -> u8 {
    let got = rig.ask(
        CreateCommandEvent {
            request_id,
            maximum_allowed_duration: 60,
            command_message: embedded::encode(&command.into()).expect("encodes"),
        },
        Duration::from_millis(300),
    );
    assert!(
        !got.iter().any(|m| matches!(m, Message::CommandEvent(_))),
        "done at once: {got:?}"
    );
    got.iter()
        .find_map(|m| match m {
            Message::ConfirmEventRequest(c) if c.request_id == request_id => Some(c.event_id),
            _ => None,
        })
        .unwrap_or_else(|| panic!("no Confirm Event Request in {got:?}"))
}

#[test]
fn a_list_interrupted_by_standby_reports_its_command_event_unsuccessful() {
    let mut rig = As4Rig::demo_vehicle();
    rig.take_control();
    assert_eq!(
        command_event(&mut rig, 1, jaus_as4::Resume {}).0,
        CommandResult::Successful
    );
    let list = SetElement {
        request_id: 9,
        elements: vec![Element::holding(1, 0, 0, &waypoint(30.0, 0.0)).expect("element")],
    };
    assert_eq!(
        command_event(&mut rig, 2, list).0,
        CommandResult::Successful
    );
    let execute = ExecuteList {
        speed: 1.0,
        element_uid: Some(1),
    };
    let event_id = confirmed(&mut rig, 3, execute);
    rig.net.run_for(Duration::from_secs(1));
    // Standby stops the list: the command did not complete.
    let got = rig.ask(jaus_as4::Standby {}, Duration::from_millis(500));
    assert!(
        got.iter().any(|m| matches!(m, Message::CommandEvent(e)
            if e.event_id == event_id && e.command_result == CommandResult::Unsuccessful)),
        "{got:?}"
    );
}

#[test]
fn a_command_event_without_control_is_unsuccessful_and_changes_nothing() {
    let mut rig = As4Rig::demo_vehicle();
    // Nobody controls the vehicle: Resume inside a command event is confirmed, run as
    // if this client sent it, refused, and reported Unsuccessful.
    let (r, others) = command_event(&mut rig, 1, jaus_as4::Resume {});
    assert_eq!(r, CommandResult::Unsuccessful);
    assert!(others.is_empty(), "{others:?}");
    let Message::ReportStatus(s) = rig.one(QueryStatus {}) else {
        panic!("Report Status expected")
    };
    assert_eq!(s.status, ComponentState::Standby);
    // A query is no command: refused outright.
    let got = rig.ask(
        CreateCommandEvent {
            request_id: 2,
            maximum_allowed_duration: 5,
            command_message: embedded::encode(&QueryStatus {}.into()).expect("encodes"),
        },
        Duration::from_millis(500),
    );
    assert!(
        matches!(got.as_slice(), [Message::RejectEventRequest(r)] if r.request_id == 2),
        "{got:?}"
    );
}
