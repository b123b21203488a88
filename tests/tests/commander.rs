//! Commander operator logic (issue 14 item 4, in part): `jaus::stock::commander::
//! ControlKeeper` inside a System Commander takes control of a Primitive Driver with
//! its authority and resumes it, loses control to a higher authority, takes it back
//! when that one lets go, and sees the driver enter and leave Emergency.

use std::time::Duration;

use jaus::component::local::{LocalBus, Probe};
use jaus::component::{Config, CoreState, Refused};
use jaus::components::primitive_driver;
use jaus::components::system_commander::{self, Ctx, SystemCommander};
use jaus::messages::*;
use jaus::stock::commander::{ControlEvent, ControlKeeper, KeeperConfig};
use jaus::stock::drivers::{PrimitiveConfig, StockPrimitiveDriver};
use jaus::Address;
use jaus_sim::vehicle::{SimVehicle, VehicleParams};

const PD: Address = Address::new(1, 1, 33, 1);
const OCU: Address = Address::new(1, 2, 40, 1);
const INTRUDER: Address = Address::new(1, 3, 40, 1);

#[derive(Debug)]
struct Operator {
    keeper: ControlKeeper,
    events: Vec<ControlEvent>,
}

impl SystemCommander for Operator {
    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        let events = self.keeper.tick(ctx);
        self.events.extend(events);
    }

    fn on_other_message(
        &mut self,
        ctx: &mut Ctx<'_>,
        msg: &Message,
    ) -> Result<Option<Message>, Refused> {
        if let (Message::ReportComponentStatus(r), Some(from)) = (msg, ctx.source()) {
            self.events.extend(self.keeper.on_status(from, r));
        }
        Ok(None)
    }
}

type Ocu = jaus::component::Component<system_commander::Dispatch<Operator>>;
type Pd = jaus::component::Component<primitive_driver::Dispatch<StockPrimitiveDriver<SimVehicle>>>;

fn events(bus: &mut LocalBus) -> Vec<ControlEvent> {
    let o = bus.get_mut::<Ocu>(OCU).unwrap();
    std::mem::take(&mut o.behaviour_mut().0.events)
}

#[test]
fn a_commander_keeps_control_loses_it_to_a_higher_authority_and_takes_it_back() {
    let t0 = std::time::Instant::now();
    let mut bus = LocalBus::new(t0);
    bus.add(primitive_driver::component(
        PD,
        StockPrimitiveDriver::new(
            SimVehicle::new(VehicleParams::default()),
            PrimitiveConfig::default(),
        ),
        Config::default(),
        t0,
    ));
    let mut keeper = ControlKeeper::new(KeeperConfig::default());
    keeper.keep(PD);
    bus.add(system_commander::component(
        OCU,
        Operator {
            keeper,
            events: Vec::new(),
        },
        Config {
            authority: 200,
            ..Config::default()
        },
        t0,
    ));
    bus.add(Probe::new(INTRUDER));

    // Control taken and the driver resumed: Ready, and the commander saw it.
    bus.run_for(Duration::from_secs(1));
    assert_eq!(bus.get::<Pd>(PD).unwrap().controller(), Some((OCU, 200)));
    assert_eq!(bus.get::<Pd>(PD).unwrap().state(), CoreState::Ready);
    let e = events(&mut bus);
    let at = |x: ControlEvent| e.iter().position(|y| *y == x);
    let (gained, ready) = (
        at(ControlEvent::Gained(PD)),
        at(ControlEvent::State(PD, CoreState::Ready)),
    );
    assert!(gained.is_some() && ready > gained, "{e:?}");

    // A higher authority takes it: lost, and asking again is rejected meanwhile.
    bus.send(
        INTRUDER,
        PD,
        RequestComponentControl {
            authority_code: 250,
        },
    );
    bus.run_for(Duration::from_secs(2));
    assert_eq!(
        bus.get::<Pd>(PD).unwrap().controller(),
        Some((INTRUDER, 250))
    );
    let e = events(&mut bus);
    assert!(e.contains(&ControlEvent::Lost(PD)), "{e:?}");
    assert!(!e.contains(&ControlEvent::Gained(PD)), "{e:?}");
    let ocu = bus.get::<Ocu>(OCU).unwrap();
    assert!(!ocu.behaviour().0.keeper.holds(PD));

    // It lets go: the commander takes control back and resumes the driver.
    bus.send(INTRUDER, PD, ReleaseComponentControl {});
    bus.run_for(Duration::from_secs(2));
    assert_eq!(bus.get::<Pd>(PD).unwrap().controller(), Some((OCU, 200)));
    assert_eq!(bus.get::<Pd>(PD).unwrap().state(), CoreState::Ready);
    let e = events(&mut bus);
    assert!(e.contains(&ControlEvent::Gained(PD)), "{e:?}");
    let keeper = &bus.get::<Ocu>(OCU).unwrap().behaviour().0.keeper;
    assert!(keeper.holds_all());
    assert_eq!(keeper.counts(PD), Some((2, 1)));

    // Emergency from anyone: the commander sees the driver enter and leave it.
    bus.send(
        INTRUDER,
        PD,
        SetEmergency {
            emergency_code: EmergencyCode {
                transition_to_emergency: true,
                ..Default::default()
            },
        },
    );
    bus.run_for(Duration::from_secs(1));
    assert!(events(&mut bus).contains(&ControlEvent::State(PD, CoreState::Emergency)));
    bus.send(
        INTRUDER,
        PD,
        ClearEmergency {
            emergency_code: ClearEmergencyCode {
                clear_emergency: true,
                ..Default::default()
            },
        },
    );
    bus.run_for(Duration::from_secs(1));
    let e = events(&mut bus);
    assert!(
        e.iter()
            .any(|e| matches!(e, ControlEvent::State(PD, s) if *s != CoreState::Emergency)),
        "{e:?}"
    );
}

/// A driver that restarts (a new process: no controller, Standby) without the
/// commander's node seeing it leave: the driver reports no controller, so the runtime
/// drops the control held, the keeper asks again and resumes it (issue 35).
#[test]
fn a_kept_component_that_restarts_is_controlled_again() {
    let t0 = std::time::Instant::now();
    let mut bus = LocalBus::new(t0);
    let driver = |t| {
        primitive_driver::component(
            PD,
            StockPrimitiveDriver::new(
                SimVehicle::new(VehicleParams::default()),
                PrimitiveConfig::default(),
            ),
            Config::default(),
            t,
        )
    };
    bus.add(driver(t0));
    let mut keeper = ControlKeeper::new(KeeperConfig::default());
    keeper.keep(PD);
    bus.add(system_commander::component(
        OCU,
        Operator {
            keeper,
            events: Vec::new(),
        },
        Config {
            authority: 200,
            ..Config::default()
        },
        t0,
    ));
    bus.run_for(Duration::from_secs(1));
    assert_eq!(bus.get::<Pd>(PD).unwrap().controller(), Some((OCU, 200)));
    events(&mut bus);

    // The new process: same address, nobody in control.
    bus.remove(PD);
    let now = bus.now();
    bus.add(driver(now));
    bus.run_for(Duration::from_secs(2));
    let pd = bus.get::<Pd>(PD).unwrap();
    assert_eq!(pd.controller(), Some((OCU, 200)));
    assert_eq!(pd.state(), CoreState::Ready);
    let e = events(&mut bus);
    let lost = e.iter().position(|x| *x == ControlEvent::Lost(PD));
    let gained = e.iter().position(|x| *x == ControlEvent::Gained(PD));
    assert!(lost.is_some() && gained > lost, "{e:?}");
    let keeper = &bus.get::<Ocu>(OCU).unwrap().behaviour().0.keeper;
    assert_eq!(keeper.counts(PD), Some((2, 1)));
}
