//! Access Control and Management of the Core runtime, driven on an `As4Component` with
//! messages from three clients.

mod core_common;

use std::time::{Duration, Instant};

use core_common::*;
use jaus_as4::core::CoreConfig;
use jaus_as4::{
    ClearEmergency, ComponentAddress, ComponentState, ConfirmControl, ControlConfirmation,
    ControlRejection, EmergencyCode, Message, QueryAuthority, QueryControl, QueryStatus,
    QueryTimeout, QueryTravelSpeed, RejectControl, ReleaseControl, ReportAuthority, ReportControl,
    ReportStatus, ReportTimeout, ReportTravelSpeed, RequestControl, Reset, Resume, SetAuthority,
    SetEmergency, SetTravelSpeed, Shutdown, Standby,
};

fn config(authority: u8, timeout: u8) -> CoreConfig {
    CoreConfig {
        authority,
        control_timeout: timeout,
        ..CoreConfig::named("rover")
    }
}

fn confirm(code: ControlConfirmation) -> Message {
    ConfirmControl {
        response_code: code,
    }
    .into()
}

fn reject(code: ControlRejection) -> Message {
    RejectControl {
        response_code: code,
    }
    .into()
}

fn status(s: ComponentState) -> Message {
    ReportStatus {
        status: s,
        reserved: 0,
    }
    .into()
}

#[test]
fn grant_refuse_preempt_release() {
    let t = Instant::now();
    let (mut c, log) = component(config(5, 0));
    // Free: Report Control is all zero.
    let free = ReportControl {
        controller: ComponentAddress::default(),
        authority_code: 0,
    };
    assert_eq!(
        only_for(&send(&mut c, t, B, QueryControl {}), B),
        free.into()
    );
    // Below the default authority: refused.
    let out = send(&mut c, t, A, RequestControl { authority_code: 4 });
    assert_eq!(
        only_for(&out, A),
        confirm(ControlConfirmation::InsufficientAuthority)
    );
    assert_eq!(c.controller(), None);
    // At the default: granted.
    let out = send(&mut c, t, A, RequestControl { authority_code: 5 });
    assert_eq!(
        only_for(&out, A),
        confirm(ControlConfirmation::ControlAccepted)
    );
    assert_eq!(c.controller(), Some(A));
    let want = ReportControl {
        controller: ComponentAddress {
            subsystem_id: 42,
            node_id: 1,
            component_id: 1,
        },
        authority_code: 5,
    };
    assert_eq!(
        only_for(&send(&mut c, t, C, QueryControl {}), C),
        want.into()
    );
    // Same authority from another client: refused, A keeps control.
    let out = send(&mut c, t, B, RequestControl { authority_code: 5 });
    assert_eq!(
        only_for(&out, B),
        confirm(ControlConfirmation::InsufficientAuthority)
    );
    assert_eq!(c.controller(), Some(A));
    // Higher authority preempts: A gets Reject Control, B the confirmation.
    let out = send(&mut c, t, B, RequestControl { authority_code: 9 });
    assert_eq!(out.len(), 2);
    assert_eq!(only_for(&out, A), reject(ControlRejection::ControlReleased));
    assert_eq!(
        only_for(&out, B),
        confirm(ControlConfirmation::ControlAccepted)
    );
    assert_eq!(c.controller(), Some(B));
    assert_eq!(
        only_for(&send(&mut c, t, A, QueryAuthority {}), A),
        ReportAuthority { authority_code: 9 }.into()
    );
    // Set Authority from the controller within [default, current]; above is ignored.
    assert!(send(&mut c, t, B, SetAuthority { authority_code: 7 }).is_empty());
    assert_eq!(c.core().access().authority(), 7);
    send(&mut c, t, B, SetAuthority { authority_code: 8 });
    assert_eq!(c.core().access().authority(), 7);
    // Set Authority from a non-controller: ignored, counted.
    let before = c.stats().not_controller;
    send(&mut c, t, A, SetAuthority { authority_code: 6 });
    assert_eq!(c.stats().not_controller, before + 1);
    // Release from a non-controller: ignored.
    assert!(send(&mut c, t, A, ReleaseControl {}).is_empty());
    assert_eq!(c.controller(), Some(B));
    // Release by the controller.
    let out = send(&mut c, t, B, ReleaseControl {});
    assert_eq!(only_for(&out, B), reject(ControlRejection::ControlReleased));
    assert_eq!(c.controller(), None);
    assert_eq!(c.core().access().authority(), 5);
    // Release while free: Reject Control ControlReleased to the sender.
    let out = send(&mut c, t, C, ReleaseControl {});
    assert_eq!(only_for(&out, C), reject(ControlRejection::ControlReleased));
    // The service heard every change of controller.
    let log = log.lock().unwrap().clone();
    let changes: Vec<_> = log.iter().filter(|l| l.starts_with("controller")).collect();
    assert_eq!(changes.len(), 3, "{log:?}");
}

#[test]
fn controller_renewing_with_low_authority_loses_control() {
    let t = Instant::now();
    let (mut c, _) = component(config(5, 0));
    send(&mut c, t, A, RequestControl { authority_code: 6 });
    let out = send(&mut c, t, A, RequestControl { authority_code: 2 });
    assert_eq!(only_for(&out, A), reject(ControlRejection::ControlReleased));
    assert_eq!(c.controller(), None);
}

#[test]
fn control_lapses_after_the_timeout_unless_renewed() {
    let t = Instant::now();
    let (mut c, _) = component(config(0, 2));
    assert_eq!(
        only_for(&send(&mut c, t, A, QueryTimeout {}), A),
        ReportTimeout { timeout: 2 }.into()
    );
    send(&mut c, t, A, RequestControl { authority_code: 1 });
    send(&mut c, t, A, Resume {});
    assert_eq!(c.state(), ComponentState::Ready);
    assert_eq!(c.poll_timeout(), Some(t + Duration::from_secs(2)));
    // Commands do not renew control; Request Control does.
    let t1 = t + Duration::from_millis(1500);
    send(&mut c, t1, A, SetTravelSpeed { speed: 1.0 });
    assert_eq!(c.poll_timeout(), Some(t + Duration::from_secs(2)));
    send(&mut c, t1, A, RequestControl { authority_code: 1 });
    assert!(c
        .handle_timeout(t + Duration::from_secs(2), &mut ())
        .is_empty());
    assert!(c
        .handle_timeout(t + Duration::from_secs(3), &mut ())
        .is_empty());
    assert_eq!(c.controller(), Some(A));
    // Nothing more from A: control lapses at t1 + 2 s, and Ready becomes Standby.
    let due = c.poll_timeout().unwrap();
    assert_eq!(due, t1 + Duration::from_secs(2));
    let out = c.handle_timeout(due, &mut ());
    assert_eq!(only_for(&out, A), reject(ControlRejection::ControlReleased));
    assert_eq!(c.controller(), None);
    assert_eq!(c.state(), ComponentState::Standby);
    assert_eq!(c.poll_timeout(), None);
}

#[test]
fn commands_need_the_controller_and_ready() {
    let t = Instant::now();
    let (mut c, _) = component(config(0, 0));
    let speed = |c: &mut _| only_for(&send(c, t, C, QueryTravelSpeed {}), C);
    // No controller: refused, counted.
    send(&mut c, t, A, SetTravelSpeed { speed: 2.0 });
    assert_eq!(c.stats().not_controller, 1);
    send(&mut c, t, A, RequestControl { authority_code: 0 });
    // Controller, but Standby: refused as not ready.
    send(&mut c, t, A, SetTravelSpeed { speed: 2.0 });
    assert_eq!(c.stats().not_ready, 1);
    assert_eq!(speed(&mut c), ReportTravelSpeed { speed: 0.0 }.into());
    // Resume from a non-controller: ignored.
    send(&mut c, t, B, Resume {});
    assert_eq!(c.state(), ComponentState::Standby);
    assert_eq!(c.stats().not_controller, 2);
    // Resume from the controller: Ready; the command is carried out.
    send(&mut c, t, A, Resume {});
    assert_eq!(c.state(), ComponentState::Ready);
    send(&mut c, t, A, SetTravelSpeed { speed: 2.0 });
    assert!((speed(&mut c).clone() == ReportTravelSpeed { speed: 2.0 }.into()));
    // From another client while Ready: refused.
    send(&mut c, t, B, SetTravelSpeed { speed: 3.0 });
    assert_eq!(c.stats().not_controller, 3);
    assert_eq!(speed(&mut c), ReportTravelSpeed { speed: 2.0 }.into());
    // Standby from the controller.
    send(&mut c, t, A, Standby {});
    assert_eq!(
        only_for(&send(&mut c, t, B, QueryStatus {}), B),
        status(ComponentState::Standby)
    );
}

#[test]
fn emergency_from_anyone_and_back_when_all_cleared() {
    let t = Instant::now();
    let (mut c, log) = component(config(0, 0));
    send(&mut c, t, A, RequestControl { authority_code: 0 });
    send(&mut c, t, A, Resume {});
    let stop = EmergencyCode::Stop;
    send(
        &mut c,
        t,
        B,
        SetEmergency {
            emergency_code: stop,
        },
    );
    send(
        &mut c,
        t,
        C,
        SetEmergency {
            emergency_code: stop,
        },
    );
    assert_eq!(c.state(), ComponentState::Emergency);
    // Control is kept, but not available to others; commands are refused.
    assert_eq!(c.controller(), Some(A));
    let out = send(
        &mut c,
        t,
        B,
        RequestControl {
            authority_code: 200,
        },
    );
    assert_eq!(
        only_for(&out, B),
        confirm(ControlConfirmation::NotAvailable)
    );
    let out = send(&mut c, t, A, ReleaseControl {});
    assert_eq!(only_for(&out, A), reject(ControlRejection::NotAvailable));
    send(&mut c, t, A, SetTravelSpeed { speed: 1.0 });
    assert_eq!(c.stats().not_ready, 1);
    // Shutdown is ignored during an emergency.
    send(&mut c, t, A, Shutdown {});
    assert_eq!(c.state(), ComponentState::Emergency);
    // A client that set none cannot clear; B clears its own, C's remains.
    send(
        &mut c,
        t,
        A,
        ClearEmergency {
            emergency_code: stop,
        },
    );
    send(
        &mut c,
        t,
        B,
        ClearEmergency {
            emergency_code: stop,
        },
    );
    assert_eq!(c.state(), ComponentState::Emergency);
    send(
        &mut c,
        t,
        C,
        ClearEmergency {
            emergency_code: stop,
        },
    );
    // Back to the state before: Ready, still under A's control.
    assert_eq!(c.state(), ComponentState::Ready);
    assert_eq!(c.controller(), Some(A));
    let log = log.lock().unwrap().clone();
    assert!(
        log.contains(&"state Ready->Emergency".to_string()),
        "{log:?}"
    );
    assert!(
        log.contains(&"state Emergency->Ready".to_string()),
        "{log:?}"
    );
}

#[test]
fn shutdown_releases_control_and_stays() {
    let t = Instant::now();
    let (mut c, _) = component(config(0, 0));
    send(&mut c, t, A, RequestControl { authority_code: 0 });
    send(&mut c, t, A, Resume {});
    // Not from a non-controller.
    send(&mut c, t, B, Shutdown {});
    assert_eq!(c.state(), ComponentState::Ready);
    let out = send(&mut c, t, A, Shutdown {});
    assert_eq!(only_for(&out, A), reject(ControlRejection::ControlReleased));
    assert_eq!(c.state(), ComponentState::Shutdown);
    assert_eq!(c.controller(), None);
    let out = send(&mut c, t, A, RequestControl { authority_code: 0 });
    assert_eq!(
        only_for(&out, A),
        confirm(ControlConfirmation::NotAvailable)
    );
    assert_eq!(
        only_for(&send(&mut c, t, B, QueryStatus {}), B),
        status(ComponentState::Shutdown)
    );
}

#[test]
fn reset_releases_control_and_returns_to_standby() {
    let t = Instant::now();
    let (mut c, _) = component(config(0, 0));
    send(&mut c, t, A, RequestControl { authority_code: 0 });
    send(&mut c, t, A, Resume {});
    let out = send(&mut c, t, A, Reset {});
    assert_eq!(only_for(&out, A), reject(ControlRejection::ControlReleased));
    assert_eq!((c.state(), c.controller()), (ComponentState::Standby, None));
}

#[test]
fn failure_declared_by_the_owner() {
    let t = Instant::now();
    let (mut c, _) = component(config(0, 0));
    send(&mut c, t, A, RequestControl { authority_code: 0 });
    let out = c.fail(t, &mut ());
    assert_eq!(only_for(&out, A), reject(ControlRejection::ControlReleased));
    assert_eq!(c.state(), ComponentState::Failure);
    let out = send(&mut c, t, B, RequestControl { authority_code: 0 });
    assert_eq!(
        only_for(&out, B),
        confirm(ControlConfirmation::NotAvailable)
    );
}

#[test]
fn unknown_and_unhandled_messages_are_counted() {
    let t = Instant::now();
    let (mut c, _) = component(config(0, 0));
    let raw = jaus_as4::Message::decode(jaus::CommandCode(0xD00D), &[1, 2, 3]).unwrap();
    assert!(send(&mut c, t, A, raw).is_empty());
    // A known message that nothing here receives (a report).
    assert!(send(&mut c, t, A, ReportTravelSpeed { speed: 1.0 }).is_empty());
    let s = c.stats();
    assert_eq!((s.unknown, s.unhandled, s.received), (1, 1, 2));
}
