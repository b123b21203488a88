//! Unit tests of confirmation by effect: the checks made from the definitions, the
//! comparison within one step, and the state machine of one command.

use super::*;

fn sdk() -> &'static Checks {
    checks().expect("the SDK's definitions load")
}

fn body(name: &str, fields: serde_json::Value) -> (CommandCode, Vec<u8>) {
    let s = &sdk().schema;
    let m = s.from_json(name, &fields).unwrap();
    (m.code, s.encode(&m).unwrap())
}

const GWD: Address = Address::new(1, 1, 45, 1);

/// A confirmation whose command left at `now`.
fn started(
    to: Address,
    code: CommandCode,
    name: &str,
    check: Check,
    habit: Habit,
    now: Instant,
    wait: Duration,
) -> Confirming {
    let mut c = Confirming::new(to, code, name, check, habit, now, wait);
    c.departed(now);
    c
}

#[test]
fn the_read_back_is_timed_from_the_departure() {
    let t0 = Instant::now();
    let mut c = Confirming::new(
        GWD,
        CommandCode(0x0004),
        "Resume",
        Check::State(Wanted::Is(&["Ready"])),
        Habit::Silent,
        t0,
        Duration::from_secs(1),
    );
    // Held by its node for 2 s: nothing asked before it left.
    assert_eq!(c.poll(t0 + Duration::from_secs(2)), Step::Idle);
    let left = t0 + Duration::from_secs(2);
    let packet = jaus::Packet::new(
        jaus::Header::new(CommandCode(0x0004), GWD, Address::new(2, 1, 40, 1)),
        Vec::new(),
    );
    let datagram =
        jaus::net::Framing::Judp.encode(&jaus::codec::Encode::to_bytes(&packet).unwrap());
    c.leaving(jaus::net::Framing::Judp, &datagram, left);
    assert_eq!(c.poll(left + SETTLE / 2), Step::Idle);
    assert!(matches!(c.poll(left + SETTLE), Step::Ask(..)));
}

#[test]
fn set_travel_speed_is_read_back_with_query_travel_speed_within_one_step() {
    let (code, b) = body("SetTravelSpeed", serde_json::json!({"speed": 2.5}));
    let Check::ReadBack {
        query,
        report,
        expect,
        report_title,
        ..
    } = sdk().of(code, &b)
    else {
        panic!("no read-back")
    };
    assert_eq!((query, report), (CommandCode(0x240A), CommandCode(0x440A)));
    assert_eq!(expect.len(), 1);
    let step = 10_000.0 / 65_535.0;
    assert!((expect[0].step - step).abs() < 1e-9);
    let sent = expect[0].value.as_f64().unwrap();
    let got = |v: f64| {
        let mut m = Map::new();
        m.insert("speed".into(), v.into());
        m
    };
    let ok = compare(&expect, &report_title, &got(sent + 0.9 * step)).unwrap();
    assert_eq!(ok, "Report Travel Speed 2.58 m/s");
    let bad = compare(&expect, &report_title, &got(sent + 1.5 * step)).unwrap_err();
    assert!(bad.contains("not the 2.44 m/s sent"), "{bad}");
    assert!(compare(&expect, &report_title, &Map::new()).is_err());
}

#[test]
fn state_commands_and_control_have_their_checks() {
    assert_eq!(
        sdk().of(CommandCode(0x0004), &[]),
        Check::State(Wanted::Is(&["Ready"]))
    );
    assert_eq!(
        sdk().of(CommandCode(0x0007), &[]),
        Check::State(Wanted::Not("Emergency"))
    );
    assert_eq!(sdk().of(CommandCode(0x000D), &[10]), Check::Control);
    let (code, b) = body(
        "SetGlobalWaypoint",
        serde_json::json!({"waypoint_number": 0, "latitude": 1.0, "longitude": 2.0}),
    );
    assert!(matches!(sdk().of(code, &b), Check::Nothing(_)));
}

#[test]
fn a_query_with_a_presence_vector_asks_for_every_field() {
    let (code, b) = body(
        "SetGlobalVector",
        serde_json::json!({"speed": 1.0, "heading": 0.5}),
    );
    let Check::ReadBack { body, expect, .. } = sdk().of(code, &b) else {
        panic!("no read-back")
    };
    assert_eq!(body, [0xFF]);
    let fields: Vec<&str> = expect.iter().map(|e| e.field.as_str()).collect();
    assert_eq!(fields, ["speed", "heading"]);
}

fn report(name: &str, fields: serde_json::Value) -> (CommandCode, Vec<u8>) {
    body(name, fields)
}

#[test]
fn an_acknowledgement_ends_it_at_once() {
    let t0 = Instant::now();
    let (code, b) = body("SetTravelSpeed", serde_json::json!({"speed": 1.0}));
    let mut c = started(
        GWD,
        code,
        "SetTravelSpeed",
        sdk().of(code, &b),
        Habit::Unknown,
        t0,
        Duration::from_secs(1),
    );
    assert_eq!(c.poll(t0), Step::Idle);
    c.ack(false, None);
    assert_eq!(c.poll(t0), Step::Done(Confirmation::Acknowledged));
    assert_eq!(c.learnt(), Some(true));
    let mut n = started(
        GWD,
        code,
        "SetTravelSpeed",
        sdk().of(code, &b),
        Habit::Unknown,
        t0,
        Duration::from_secs(1),
    );
    n.ack(true, Some("speed beyond [0, 2] m/s"));
    let Step::Done(Confirmation::Refused(r)) = n.poll(t0) else {
        panic!("not refused")
    };
    assert!(r.contains("[0, 2] m/s"), "{r}");
}

#[test]
fn without_an_acknowledgement_the_value_is_read_back() {
    let t0 = Instant::now();
    let (code, b) = body("SetTravelSpeed", serde_json::json!({"speed": 1.0}));
    let wait = Duration::from_secs(1);
    let mut c = started(
        GWD,
        code,
        "SetTravelSpeed",
        sdk().of(code, &b),
        Habit::Unknown,
        t0,
        wait,
    );
    assert_eq!(c.poll(t0 + ACK_WAIT / 2), Step::Idle, "waits for the ACK");
    let t1 = t0 + ACK_WAIT;
    let Step::Ask(q, _) = c.poll(t1) else {
        panic!("no query")
    };
    assert_eq!(q, CommandCode(0x240A));
    assert_eq!(c.poll(t1), Step::Idle, "asked once per period");
    // A value not stored yet, then the one sent.
    let (rc, old) = report("ReportTravelSpeed", serde_json::json!({"speed": 0.0}));
    assert!(c.message(sdk(), GWD, rc, &old));
    assert!(!c.message(sdk(), Address::new(1, 1, 38, 1), rc, &old));
    assert!(matches!(c.poll(t1 + ASK_EVERY), Step::Ask(..)));
    let (_, new) = report("ReportTravelSpeed", serde_json::json!({"speed": 1.0}));
    assert!(c.message(sdk(), GWD, rc, &new));
    let Step::Done(Confirmation::ReadBack(d)) = c.poll(t1 + ASK_EVERY) else {
        panic!("not confirmed")
    };
    assert!(d.starts_with("Report Travel Speed 1.0"), "{d}");
    assert_eq!(c.learnt(), Some(false));
}

#[test]
fn a_driver_that_stays_in_standby_after_resume_is_not_confirmed() {
    let t0 = Instant::now();
    let wait = Duration::from_secs(1);
    let mut c = started(
        GWD,
        CommandCode(0x0004),
        "Resume",
        sdk().of(CommandCode(0x0004), &[]),
        Habit::Silent,
        t0,
        wait,
    );
    let t1 = t0 + SETTLE;
    assert_eq!(c.poll(t1), Step::Ask(CommandCode(0x2002), Vec::new()));
    let (rc, standby) = report(
        "ReportComponentStatus",
        serde_json::json!({"primary_status_code": "Standby", "secondary_status_code": 0}),
    );
    assert!(c.message(sdk(), GWD, rc, &standby));
    let Step::Done(Confirmation::NotConfirmed(d)) = c.poll(t1 + wait) else {
        panic!("not 'not confirmed'")
    };
    assert!(
        d.contains("still Standby after Resume (Ready expected)"),
        "{d}"
    );
    assert!(d.contains("never acknowledges"), "{d}");
}

#[test]
fn silence_is_not_confirmed_and_says_so() {
    let t0 = Instant::now();
    let (code, b) = body("SetTravelSpeed", serde_json::json!({"speed": 1.0}));
    let wait = Duration::from_millis(500);
    let mut c = started(
        GWD,
        code,
        "SetTravelSpeed",
        sdk().of(code, &b),
        Habit::Unknown,
        t0,
        wait,
    );
    let end = t0 + ACK_WAIT.min(wait) + wait;
    let Step::Done(Confirmation::NotConfirmed(d)) = c.poll(end) else {
        panic!("not 'not confirmed'")
    };
    assert!(d.contains("was not answered"), "{d}");
    assert_eq!(c.learnt(), None);
}

#[test]
fn habits_are_remembered_and_bounded() {
    let mut h = Habits::default();
    assert_eq!(h.of(GWD), Habit::Unknown);
    h.learn(GWD, false);
    assert_eq!(h.of(GWD), Habit::Silent);
    h.learn(GWD, true);
    assert_eq!(h.of(GWD), Habit::Acknowledges);
    for i in 0..2000u32 {
        h.learn(
            Address::new((i % 200) as u8 + 1, (i / 200) as u8 + 1, 1, 1),
            true,
        );
    }
    assert!(h.map.len() <= MAX_HABITS);
}
