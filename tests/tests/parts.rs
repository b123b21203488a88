//! Shared parts of the generated component traits (`parts:` of the YAML): a vendor
//! implements the Navigation Driver part once, generic over the interface, and the
//! Global Waypoint and Global Path Segment Driver traits pass the shared messages and
//! `initialize`/`tick` to it; a method written in the component's own impl takes
//! precedence over the part; a component that returns no part leaves the shared
//! messages unsupported.

use std::time::{Duration, Instant};

use jaus::component::local::{LocalBus, Probe};
use jaus::component::{Component, Config, Context, InitError, Interface, Refused, StopReason};
use jaus::components::parts::NavigationDriver;
use jaus::components::{
    global_path_segment_driver as gpsd, global_waypoint_driver as gwd, local_waypoint_driver as lwd,
};
use jaus::components::{GlobalPathSegmentDriver, GlobalWaypointDriver, LocalWaypointDriver};
use jaus::messages::*;
use jaus::Address;

const OCU: Address = Address::new(1, 2, 40, 1);
const GWD: Address = Address::new(1, 1, 45, 1);
const GPSD: Address = Address::new(1, 1, 47, 1);
const LWD: Address = Address::new(1, 1, 46, 1);

/// The shared part: one travel speed, counted ticks.
#[derive(Debug, Default)]
struct Nav {
    speed: f64,
    initialized: bool,
    ticks: u32,
}

impl<I: Interface> NavigationDriver<I> for Nav {
    fn on_query_travel_speed(
        &mut self,
        _ctx: &mut Context<'_, I>,
        _q: &QueryTravelSpeed,
    ) -> Result<ReportTravelSpeed, Refused> {
        Ok(ReportTravelSpeed { speed: self.speed })
    }

    fn initialize(&mut self, _ctx: &mut Context<'_, I>) -> Result<(), InitError> {
        self.initialized = true;
        Ok(())
    }

    fn tick(&mut self, _ctx: &mut Context<'_, I>) {
        self.ticks += 1;
    }
}

/// The part in a field.
#[derive(Debug, Default)]
struct Waypoints {
    nav: Nav,
}

impl GlobalWaypointDriver for Waypoints {
    fn navigation_driver(&mut self) -> Option<&mut dyn NavigationDriver<gwd::Interface>> {
        Some(&mut self.nav)
    }

    fn stop(&mut self, _ctx: &mut gwd::Ctx<'_>, _reason: StopReason) {}
}

/// The part in a field, one of its messages answered by the component itself.
#[derive(Debug, Default)]
struct Segments {
    nav: Nav,
}

impl GlobalPathSegmentDriver for Segments {
    fn navigation_driver(&mut self) -> Option<&mut dyn NavigationDriver<gpsd::Interface>> {
        Some(&mut self.nav)
    }

    fn stop(&mut self, _ctx: &mut gpsd::Ctx<'_>, _reason: StopReason) {}

    fn on_query_travel_speed(
        &mut self,
        _ctx: &mut gpsd::Ctx<'_>,
        _q: &QueryTravelSpeed,
    ) -> Result<ReportTravelSpeed, Refused> {
        Ok(ReportTravelSpeed { speed: 7.0 })
    }
}

/// No part.
#[derive(Debug, Default)]
struct Bare;

impl LocalWaypointDriver for Bare {
    fn stop(&mut self, _ctx: &mut lwd::Ctx<'_>, _reason: StopReason) {}
}

type Gwd = Component<gwd::Dispatch<Waypoints>>;
type Gpsd = Component<gpsd::Dispatch<Segments>>;
type Lwd = Component<lwd::Dispatch<Bare>>;

fn travel_speeds(bus: &LocalBus) -> Vec<(Address, f64)> {
    bus.get::<Probe>(OCU)
        .unwrap()
        .received()
        .iter()
        .filter_map(|r| match &r.message {
            Message::ReportTravelSpeed(m) => Some((r.header.source, m.speed)),
            _ => None,
        })
        .collect()
}

#[test]
fn shared_messages_and_hooks_reach_the_part_the_component_returns() {
    let t0 = Instant::now();
    let mut bus = LocalBus::new(t0);
    let nav = |speed| Nav {
        speed,
        ..Nav::default()
    };
    bus.add(gwd::component(
        GWD,
        Waypoints { nav: nav(2.5) },
        Config::default(),
        t0,
    ));
    bus.add(gpsd::component(
        GPSD,
        Segments { nav: nav(3.5) },
        Config::default(),
        t0,
    ));
    bus.add(lwd::component(LWD, Bare, Config::default(), t0));
    bus.add(Probe::new(OCU));
    bus.run_for(Duration::from_secs(1));

    let w = &bus.get::<Gwd>(GWD).unwrap().behaviour().0.nav;
    assert!(w.initialized, "the part's initialize ran");
    assert!(w.ticks > 0, "the part ticks");
    let s = &bus.get::<Gpsd>(GPSD).unwrap().behaviour().0.nav;
    assert!(s.initialized && s.ticks > 0);

    for to in [GWD, GPSD, LWD] {
        bus.send(OCU, to, QueryTravelSpeed {});
    }
    bus.run_for(Duration::from_millis(100));
    let mut got = travel_speeds(&bus);
    got.sort_by_key(|(a, _)| a.component);
    // The waypoint driver's part answers; the path segment driver's own method wins
    // over its part; the bare driver has no part, so no answer.
    // (Report Travel Speed carries the speed scaled over 16 bits: compare within a
    // step.)
    let from: Vec<Address> = got.iter().map(|g| g.0).collect();
    assert_eq!(from, [GWD, GPSD]);
    for ((_, speed), want) in got.iter().zip([2.5, 7.0]) {
        assert!((speed - want).abs() < 0.1, "speed {speed}, expected {want}");
    }
    let lwd = bus.get::<Lwd>(LWD).unwrap();
    assert_eq!(lwd.stats().unsupported, 1);
}
