//! Time, Liveness and Discovery on their generated machines (`defs/core_services.yaml`):
//! each extends the Core's machine and follows its state, so Set Time is taken only in
//! `Controlled` from the controlling client, and the queries in every state.

mod core_common;

use std::time::Instant;

use core_common::*;
use jaus_as4::core::CoreConfig;
use jaus_as4::{
    DateStamp, Message, QueryHeartbeatPulse, QueryIdentification, QueryTime, ReleaseControl,
    ReportTime, RequestControl, SetTime, TimeStamp,
};

fn half_past_noon(day: u8) -> SetTime {
    SetTime {
        time_stamp: Some(TimeStamp {
            millisecond: 0,
            second: 0,
            minute: 30,
            hour: 12,
            day,
            ..Default::default()
        }),
        date_stamp: Some(DateStamp {
            day,
            month: 6,
            year: 26,
            ..Default::default()
        }),
    }
}

fn time_of(c: &mut jaus_as4::component::As4Component<()>, t: Instant) -> Option<TimeStamp> {
    match only_for(&send(c, t, B, QueryTime { presence_vector: 3 }), B) {
        Message::ReportTime(ReportTime { time_stamp, .. }) => time_stamp,
        m => panic!("expected Report Time, got {m:?}"),
    }
}

#[test]
fn only_the_controller_sets_the_time_and_anyone_reads_it() {
    let t = Instant::now();
    let (mut c, _) = component(CoreConfig::named("clock"));
    // Not controlled: the Time machine is in NotControlled, where Set Time has no
    // transition.
    assert!(send(&mut c, t, A, half_past_noon(5)).is_empty());
    assert_eq!(c.stats().not_controller, 1);
    assert_eq!(time_of(&mut c, t).map(|s| s.hour), None, "no time set yet");

    send(&mut c, t, A, RequestControl { authority_code: 10 });
    assert_eq!(c.controller(), Some(A));
    // Another client, then the controller.
    assert!(send(&mut c, t, B, half_past_noon(6)).is_empty());
    assert_eq!(c.stats().not_controller, 2);
    send(&mut c, t, A, half_past_noon(7));
    let now = time_of(&mut c, t).expect("the time is set");
    assert_eq!((now.hour, now.minute, now.day), (12, 30, 7));

    // A time out of range is refused by the action, counted.
    let refused = c.stats().refused;
    let mut bad = half_past_noon(8);
    if let Some(ts) = bad.time_stamp.as_mut() {
        ts.hour = 25;
    }
    send(&mut c, t, A, bad);
    assert_eq!(c.stats().refused, refused + 1);
    assert_eq!(time_of(&mut c, t).map(|s| s.day), Some(7));

    // Released: refused again, whoever sends it.
    send(&mut c, t, A, ReleaseControl {});
    assert!(send(&mut c, t, A, half_past_noon(9)).is_empty());
    assert_eq!(c.stats().not_controller, 3);
}

#[test]
fn liveness_and_discovery_answer_in_every_state() {
    let t = Instant::now();
    let (mut c, _) = component(CoreConfig::named("beacon"));
    for controlled in [false, true] {
        if controlled {
            send(&mut c, t, A, RequestControl { authority_code: 10 });
        }
        assert!(matches!(
            only_for(&send(&mut c, t, B, QueryHeartbeatPulse {}), B),
            Message::ReportHeartbeatPulse(_)
        ));
        let q = QueryIdentification {
            query_type: jaus_as4::IdentificationType::Component,
        };
        assert!(matches!(
            only_for(&send(&mut c, t, B, q), B),
            Message::ReportIdentification(_)
        ));
    }
}
