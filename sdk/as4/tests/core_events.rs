//! Events of the Core runtime: periodic and every-change events over simulated time,
//! for a Core query and a service's query; update, cancel, refusals, lapse, Query
//! Events.

mod core_common;

use std::time::{Duration, Instant};

use core_common::*;
use jaus_as4::component::{As4Component, Outgoing};
use jaus_as4::core::CoreConfig;
use jaus_as4::{
    embedded, CancelEvent, ComponentState, ConfirmEventRequest, CreateEvent, Event, EventRejection,
    EventType, EventsFilter, Message, QueryEventTimeout, QueryEvents, QueryStatus,
    QueryTravelSpeed, RejectEventRequest, ReportEventTimeout, ReportEvents, ReportStatus,
    ReportTravelSpeed, RequestControl, Resume, SetTravelSpeed, UpdateEvent,
};

fn create(kind: EventType, rate: f64, query: impl Into<Message>) -> CreateEvent {
    CreateEvent {
        request_id: 9,
        event_type: kind,
        requested_periodic_rate: rate,
        query_message: embedded::encode(&query.into()).unwrap(),
    }
}

fn confirmed(out: &[Outgoing], to: jaus::net::as5669a::As4Id) -> ConfirmEventRequest {
    match out
        .iter()
        .find(|o| o.to == to && matches!(o.message, Message::ConfirmEventRequest(_)))
    {
        Some(Outgoing {
            message: Message::ConfirmEventRequest(c),
            ..
        }) => c.clone(),
        _ => panic!("no Confirm Event Request in {out:?}"),
    }
}

fn rejected(out: &[Outgoing]) -> EventRejection {
    match out {
        [Outgoing {
            message:
                Message::RejectEventRequest(RejectEventRequest {
                    response_code: Some(code),
                    ..
                }),
            ..
        }] => *code,
        _ => panic!("no Reject Event Request in {out:?}"),
    }
}

fn events(out: &[Outgoing]) -> Vec<Event> {
    out.iter()
        .filter_map(|o| match &o.message {
            Message::Event(e) => Some(e.clone()),
            _ => None,
        })
        .collect()
}

/// Runs the component's timers from `from` to `until`: every Event sent.
fn run(c: &mut As4Component<()>, from: Instant, until: Instant) -> Vec<Event> {
    let mut got = Vec::new();
    let mut now = from;
    while let Some(due) = c.poll_timeout() {
        if due > until {
            break;
        }
        now = now.max(due);
        got.extend(events(&c.handle_timeout(now, &mut ())));
    }
    got
}

#[test]
fn periodic_event_at_the_confirmed_rate() {
    let t = Instant::now();
    let (mut c, _) = component(CoreConfig::named("rover"));
    let out = send(
        &mut c,
        t,
        A,
        create(EventType::Periodic, 5.0, QueryStatus {}),
    );
    let conf = confirmed(&out, A);
    assert_eq!(conf.request_id, 9);
    assert!((conf.confirmed_periodic_rate - 5.0).abs() < 0.02);
    // The first report goes out at once.
    let first = events(&out);
    assert_eq!(first.len(), 1);
    assert_eq!(first[0].sequence_number, 0);
    let status = ReportStatus {
        status: ComponentState::Standby,
        reserved: 0,
    };
    assert_eq!(first[0].report().unwrap(), status.into());
    // 10 s more: 50 events (t + 0.2 s ... t + 10 s), numbered on.
    let got = run(&mut c, t, t + Duration::from_secs(10));
    assert_eq!(got.len(), 50);
    assert!(got
        .iter()
        .enumerate()
        .all(|(i, e)| e.sequence_number as usize == i + 1 && e.event_id == conf.event_id));
    assert_eq!(c.stats().events_sent, 51);
}

#[test]
fn periodic_rate_is_clamped_and_zero_refused() {
    let t = Instant::now();
    let (mut c, _) = component(CoreConfig::named("rover"));
    let out = send(
        &mut c,
        t,
        A,
        create(EventType::Periodic, 1000.0, QueryStatus {}),
    );
    assert!((confirmed(&out, A).confirmed_periodic_rate - 50.0).abs() < 0.02);
    let got = run(&mut c, t, t + Duration::from_secs(1));
    assert_eq!(got.len(), 50);
    let out = send(
        &mut c,
        t,
        B,
        create(EventType::Periodic, 0.0, QueryStatus {}),
    );
    assert_eq!(rejected(&out), EventRejection::InvalidEventSetup);
}

#[test]
fn every_change_event_of_a_service_query() {
    let t = Instant::now();
    let (mut c, _) = component(CoreConfig::named("rover"));
    let out = send(
        &mut c,
        t,
        B,
        create(EventType::EveryChange, 0.0, QueryTravelSpeed {}),
    );
    assert_eq!(confirmed(&out, B).confirmed_periodic_rate, 0.0);
    assert_eq!(events(&out).len(), 1, "the current report at once");
    // Nothing changes for 5 s: nothing sent.
    assert!(run(&mut c, t, t + Duration::from_secs(5)).is_empty());
    // A changes the speed: one Event at the next tick, with the new report.
    let t5 = t + Duration::from_secs(5);
    send(&mut c, t5, A, RequestControl { authority_code: 0 });
    send(&mut c, t5, A, Resume {});
    send(&mut c, t5, A, SetTravelSpeed { speed: 1.5 });
    let got = run(&mut c, t5, t + Duration::from_secs(10));
    assert_eq!(got.len(), 1);
    assert_eq!(got[0].sequence_number, 1);
    match got[0].report().unwrap() {
        Message::ReportTravelSpeed(ReportTravelSpeed { speed }) => {
            assert!((speed - 1.5).abs() < 0.01)
        }
        m => panic!("{m:?}"),
    }
}

#[test]
fn update_and_cancel() {
    let t = Instant::now();
    let (mut c, _) = component(CoreConfig::named("rover"));
    let out = send(
        &mut c,
        t,
        A,
        create(EventType::Periodic, 2.0, QueryStatus {}),
    );
    let id = confirmed(&out, A).event_id;
    // Create Event of the same query again: the same event, updated.
    let out = send(
        &mut c,
        t,
        A,
        create(EventType::Periodic, 10.0, QueryStatus {}),
    );
    assert_eq!(confirmed(&out, A).event_id, id);
    assert_eq!(c.core().events().len(), 1);
    // Update Event: another rate.
    let update = UpdateEvent {
        request_id: 3,
        event_type: EventType::Periodic,
        requested_periodic_rate: 1.0,
        event_id: id,
        query_message: embedded::encode(&QueryStatus {}.into()).unwrap(),
    };
    // Not B's event.
    let out = send(&mut c, t, B, update.clone());
    assert_eq!(rejected(&out), EventRejection::InvalidEventIdForUpdate);
    let out = send(&mut c, t, A, update);
    assert_eq!(confirmed(&out, A).request_id, 3);
    let t1 = t + Duration::from_millis(10);
    assert_eq!(run(&mut c, t1, t1 + Duration::from_secs(10)).len(), 10);
    // Cancel: by someone else refused; by A confirmed; then nothing more.
    let cancel = CancelEvent {
        request_id: 4,
        event_id: id,
    };
    assert_eq!(
        rejected(&send(&mut c, t, B, cancel.clone())),
        EventRejection::InvalidEventIdForUpdate
    );
    let out = send(&mut c, t, A, cancel.clone());
    assert_eq!(confirmed(&out, A).event_id, id);
    assert!(c.core().events().is_empty());
    assert_eq!(c.poll_timeout(), None);
    assert_eq!(
        rejected(&send(&mut c, t, A, cancel)),
        EventRejection::InvalidEventIdForUpdate
    );
}

#[test]
fn refusals_unknown_query_not_a_query_bad_bytes_and_the_bound() {
    let t = Instant::now();
    let config = CoreConfig {
        max_events: 2,
        ..CoreConfig::named("rover")
    };
    let (mut c, _) = component(config);
    // A query nothing here answers.
    let out = send(
        &mut c,
        t,
        A,
        create(
            EventType::Periodic,
            1.0,
            jaus_as4::QueryLocalPose::default(),
        ),
    );
    assert_eq!(rejected(&out), EventRejection::MessageNotSupported);
    // A command is not a query.
    let out = send(&mut c, t, A, create(EventType::Periodic, 1.0, Resume {}));
    assert_eq!(rejected(&out), EventRejection::MessageNotSupported);
    // Bytes that are no message.
    let mut bad = create(EventType::Periodic, 1.0, QueryStatus {});
    bad.query_message = vec![0x02];
    assert_eq!(
        rejected(&send(&mut c, t, A, bad)),
        EventRejection::InvalidEventSetup
    );
    // The bound: two events, the third refused and counted.
    send(
        &mut c,
        t,
        A,
        create(EventType::Periodic, 1.0, QueryStatus {}),
    );
    send(
        &mut c,
        t,
        B,
        create(EventType::Periodic, 1.0, QueryStatus {}),
    );
    let out = send(
        &mut c,
        t,
        C,
        create(EventType::Periodic, 1.0, QueryStatus {}),
    );
    assert_eq!(rejected(&out), EventRejection::ConnectionRefused);
    assert_eq!(c.stats().bounds, 1);
    assert_eq!(c.core().events().len(), 2);
}

#[test]
fn query_events_by_filter_and_event_timeout() {
    let t = Instant::now();
    let (mut c, _) = component(CoreConfig::named("rover"));
    send(
        &mut c,
        t,
        A,
        create(EventType::Periodic, 1.0, QueryStatus {}),
    );
    send(
        &mut c,
        t,
        B,
        create(EventType::EveryChange, 0.0, QueryTravelSpeed {}),
    );
    let ask = |c: &mut As4Component<()>, filter| match only_for(
        &send(c, t, C, QueryEvents { filter }),
        C,
    ) {
        Message::ReportEvents(ReportEvents { events }) => events,
        m => panic!("{m:?}"),
    };
    assert_eq!(ask(&mut c, EventsFilter::AllEvents(0)).len(), 2);
    let by_code = ask(&mut c, EventsFilter::MessageCode(0x2002));
    assert_eq!(by_code.len(), 1);
    assert_eq!(by_code[0].query().unwrap(), QueryStatus {}.into());
    let by_type = ask(&mut c, EventsFilter::EventType(EventType::EveryChange));
    assert_eq!(by_type.len(), 1);
    assert_eq!(by_type[0].query().unwrap(), QueryTravelSpeed {}.into());
    assert_eq!(
        ask(&mut c, EventsFilter::EventId(by_type[0].event_id)).len(),
        1
    );
    assert!(ask(&mut c, EventsFilter::EventId(200)).is_empty());
    assert_eq!(
        only_for(&send(&mut c, t, C, QueryEventTimeout {}), C),
        ReportEventTimeout { timeout: 0 }.into()
    );
}

#[test]
fn events_lapse_after_the_event_timeout() {
    let t = Instant::now();
    let config = CoreConfig {
        event_timeout: 1,
        ..CoreConfig::named("rover")
    };
    let (mut c, _) = component(config);
    let out = send(
        &mut c,
        t,
        A,
        create(EventType::Periodic, 1.0, QueryStatus {}),
    );
    let id = confirmed(&out, A).event_id;
    // Renewed at 40 s by the same Create Event.
    let t40 = t + Duration::from_secs(40);
    run(&mut c, t, t40);
    send(
        &mut c,
        t40,
        A,
        create(EventType::Periodic, 1.0, QueryStatus {}),
    );
    let mut lapse = None;
    let mut now = t40;
    while let Some(due) = c.poll_timeout() {
        now = now.max(due);
        let out = c.handle_timeout(now, &mut ());
        if let Some(o) = out
            .iter()
            .find(|o| matches!(o.message, Message::ConfirmEventRequest(_)))
        {
            lapse = Some((now, o.clone()));
            break;
        }
    }
    let (when, o) = lapse.expect("the event lapses");
    assert_eq!(when, t40 + Duration::from_secs(60));
    assert_eq!(o.to, A);
    assert!(
        matches!(o.message, Message::ConfirmEventRequest(ConfirmEventRequest { event_id, .. }) if event_id == id)
    );
    assert!(c.core().events().is_empty());
}
