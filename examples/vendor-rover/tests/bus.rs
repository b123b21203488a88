//! The Tank Monitor on the SDK's in-process bus: an operator takes control, opens a
//! valve, receives the levels, and queries them; a command without control is refused.
//! (Struct literals of messages end with `..Default::default()`, the form that keeps
//! compiling when a revision adds an optional field: see src/lib.rs.)
#![allow(clippy::needless_update)]

use std::time::{Duration, Instant};

use jaus::component::local::{LocalBus, Probe};
use jaus::component::Component;
use jaus::messages::{QueryGlobalPose, RequestComponentControl, Resume};
use jaus::{Address, MessageSet};
use vendor_rover::messages::components::tank_monitor::{Dispatch, Mode};
use vendor_rover::messages::{Message, QueryTankLevels, SetDrainValve};
use vendor_rover::Tanks;

const MONITOR: Address = Address::new(1, 1, 210, 1);
const OCU: Address = Address::new(1, 1, 200, 1);

#[test]
fn the_tank_monitor_drains_under_control_and_reports() {
    let t0 = Instant::now();
    let mut bus = LocalBus::new(t0);
    for c in vendor_rover::components(1, 1, t0) {
        bus.add_boxed(c);
    }
    bus.add(Probe::<Message>::for_set(OCU));
    bus.run_for(Duration::from_millis(50));
    let open = Message::from(SetDrainValve {
        tank: 0,
        open: 1,
        ..Default::default()
    });

    bus.send_set(OCU, MONITOR, &open);
    bus.run_for(Duration::from_millis(50));
    let monitor = |bus: &LocalBus| -> (Mode, Tanks, u64) {
        let c: &Component<Dispatch<Tanks>> = bus.get(MONITOR).unwrap();
        (c.mode(), c.behaviour().0.clone(), c.stats().not_controller)
    };
    assert_eq!(monitor(&bus).2, 1, "refused without control");
    assert_eq!(monitor(&bus).1.open, None);

    let control = RequestComponentControl {
        authority_code: 10,
        ..Default::default()
    };
    bus.send(OCU, MONITOR, control);
    bus.send(OCU, MONITOR, Resume::default());
    bus.send_set(OCU, MONITOR, &open);
    bus.send_set(OCU, MONITOR, &Message::from(QueryTankLevels::default()));
    bus.run_for(Duration::from_millis(500));
    let (mode, tanks, _) = monitor(&bus);
    assert_eq!(mode, Mode::Draining);
    assert!(tanks.levels[0] < 80.0);
    let probe: &Probe<Message> = bus.get(OCU).unwrap();
    let levels = probe
        .messages()
        .filter(|m| matches!(m, Message::ReportTankLevels(_)))
        .count();
    assert!(levels >= 3, "{levels} level reports");

    // The stock Global Pose Sensor beside it answers a standard query.
    bus.send(
        OCU,
        Address::new(1, 1, 38, 1),
        QueryGlobalPose {
            presence_vector: 3,
            ..Default::default()
        },
    );
    bus.run_for(Duration::from_millis(50));
    let probe: &Probe<Message> = bus.get(OCU).unwrap();
    assert!(probe.messages().any(|m| matches!(
        m.standard(),
        Some(jaus::messages::Message::ReportGlobalPose(p))
            if p.latitude.is_some_and(|l| (l - 29.65).abs() < 1e-6)
    )));
}
