//! A vendor's own component on the SDK's runtime (issue 11 item 2, issue 20 item 1):
//! `vendor/acme.yaml` defines an experimental command (`class: command`), an
//! experimental query with its report (`class: query`, `report:`) and a component,
//! `TankMonitor`, that takes them together with a standard query. `build.rs` generates
//! the vendor's message set (which wraps the SDK's) and the component skeleton; the
//! component runs under the same runtime as the SDK's own, on the in-process bus, on a
//! simulated network and over loopback UDP.

use std::net::UdpSocket;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::local::{LocalBus, Probe};
use jaus::component::{Component, Config, CoreState, Refused};
use jaus::messages::{
    ConfirmComponentControl, ControlResponse, CreateServiceConnection, QueryGlobalPose,
    QueryServices, ReportGlobalPose, RequestComponentControl, Resume,
};
use jaus::net::{Node, NodeConfig};
use jaus::{Address, Header, MessageSet};

#[allow(dead_code)]
mod acme {
    include!(concat!(env!("OUT_DIR"), "/messages.rs"));

    /// The vendor's component skeletons (a child of the module holding the messages).
    pub mod components {
        include!(concat!(env!("OUT_DIR"), "/components.rs"));
    }
}

use acme::components::tank_monitor::{self, Ctx, Mode, TankMonitor, Transition};
use acme::{QueryTanks, ReportTankTelemetry, ReportTanks, SetTankValve, Tank, TankFlags, TankKind};

const MONITOR: Address = Address::new(1, 1, 210, 1);
const OCU: Address = Address::new(1, 1, 200, 1);

/// The vendor's implementation: two tanks, one drain valve open at a time.
#[derive(Debug)]
struct Tanks {
    levels: Vec<f64>,
    open: Option<u8>,
}

impl TankMonitor for Tanks {
    fn on_set_tank_valve(&mut self, ctx: &mut Ctx<'_>, msg: &SetTankValve) -> Result<(), Refused> {
        if usize::from(msg.tank) >= self.levels.len() {
            return Err(Refused::Invalid(format!("no tank {}", msg.tank)));
        }
        let t = if msg.open == 1 {
            self.open = Some(msg.tank);
            Transition::Open
        } else {
            self.open = None;
            Transition::Close
        };
        ctx.transition(t)
            .map(|_| ())
            .map_err(|e| Refused::Invalid(e.to_string()))
    }

    fn on_query_tanks(&mut self, _: &mut Ctx<'_>, _: &QueryTanks) -> Result<ReportTanks, Refused> {
        Ok(ReportTanks {
            vehicle: "carrier-7".into(),
            tanks: self
                .levels
                .iter()
                .map(|l| Tank {
                    kind: TankKind::Fuel,
                    level: *l,
                    flags: TankFlags::default(),
                    label: None,
                    temperatures: None,
                })
                .collect(),
            ..Default::default()
        })
    }

    fn on_query_global_pose(
        &mut self,
        _: &mut Ctx<'_>,
        _: &QueryGlobalPose,
    ) -> Result<ReportGlobalPose, Refused> {
        Ok(ReportGlobalPose {
            latitude: Some(29.65),
            longitude: Some(-82.32),
            ..Default::default()
        })
    }

    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        let (Some(tank), Some(controller)) = (self.open, ctx.controller()) else {
            return;
        };
        let level = &mut self.levels[usize::from(tank)];
        *level = (*level - 1.0).max(0.0);
        let report = ReportTankTelemetry {
            time_stamp: Default::default(),
            tank,
            level: *level,
        };
        ctx.send(controller, report);
    }
}

fn monitor(t0: Instant) -> Component<tank_monitor::Dispatch<Tanks>> {
    tank_monitor::component(
        MONITOR,
        Tanks {
            levels: vec![80.0, 40.0],
            open: None,
        },
        Config::default(),
        t0,
    )
}

fn bus() -> LocalBus {
    let t0 = Instant::now();
    let mut bus = LocalBus::new(t0);
    bus.add(monitor(t0));
    bus.add(Probe::<acme::Message>::for_set(OCU));
    bus.run_for(Duration::from_millis(50));
    bus
}

fn probe(bus: &LocalBus) -> &Probe<acme::Message> {
    bus.get(OCU).unwrap()
}

fn tanks(bus: &LocalBus) -> &Tanks {
    &bus.get::<Component<tank_monitor::Dispatch<Tanks>>>(MONITOR)
        .unwrap()
        .behaviour()
        .0
}

fn valve(open: bool) -> acme::Message {
    SetTankValve {
        tank: 1,
        open: u8::from(open),
    }
    .into()
}

#[test]
fn an_experimental_command_obeys_control() {
    let mut bus = bus();
    // Not in control: refused by the runtime, counted, nothing opens.
    bus.send_set(OCU, MONITOR, &valve(true));
    bus.run_for(Duration::from_millis(50));
    let c = bus
        .get::<Component<tank_monitor::Dispatch<Tanks>>>(MONITOR)
        .unwrap();
    assert_eq!(c.stats().not_controller, 1);
    assert_eq!(tanks(&bus).open, None);

    // In control and Ready: executed; the mode follows; telemetry flows to the controller.
    bus.send(OCU, MONITOR, RequestComponentControl { authority_code: 10 });
    bus.run_for(Duration::from_millis(50));
    assert!(probe(&bus).messages().any(|m| matches!(
        m.standard(),
        Some(jaus::messages::Message::ConfirmComponentControl(
            ConfirmComponentControl {
                response_code: ControlResponse::ControlAccepted
            }
        ))
    )));
    bus.send(OCU, MONITOR, Resume {});
    bus.send_set(OCU, MONITOR, &valve(true));
    bus.run_for(Duration::from_millis(500));
    let c = bus
        .get::<Component<tank_monitor::Dispatch<Tanks>>>(MONITOR)
        .unwrap();
    assert_eq!(c.state(), CoreState::Ready);
    assert_eq!(c.mode(), Mode::Draining);
    assert_eq!(tanks(&bus).open, Some(1));
    let telemetry: Vec<&ReportTankTelemetry> = probe(&bus)
        .messages()
        .filter_map(|m| match m {
            acme::Message::ReportTankTelemetry(t) => Some(t),
            _ => None,
        })
        .collect();
    assert!(telemetry.len() >= 3, "{telemetry:?}");
    assert!(telemetry.iter().all(|t| t.tank == 1 && t.level < 40.0));

    // A bad value is the vendor's refusal, not a crash.
    bus.send_set(
        OCU,
        MONITOR,
        &acme::Message::SetTankValve(SetTankValve { tank: 9, open: 1 }),
    );
    bus.run_for(Duration::from_millis(50));
    let c = bus
        .get::<Component<tank_monitor::Dispatch<Tanks>>>(MONITOR)
        .unwrap();
    assert_eq!(c.stats().invalid, 1);
}

#[test]
fn an_experimental_query_gets_its_typed_report_and_streams_by_service_connection() {
    let mut bus = bus();
    bus.send_set(
        OCU,
        MONITOR,
        &acme::Message::QueryTanks(QueryTanks { presence_vector: 0 }),
    );
    bus.send(OCU, MONITOR, QueryGlobalPose { presence_vector: 3 });
    bus.send(OCU, MONITOR, QueryServices {});
    bus.run_for(Duration::from_millis(50));
    let got = probe(&bus).messages().cloned().collect::<Vec<_>>();
    let report = got
        .iter()
        .find_map(|m| match m {
            acme::Message::ReportTanks(r) => Some(r),
            _ => None,
        })
        .expect("ReportTanks, typed");
    assert_eq!(report.vehicle, "carrier-7");
    assert_eq!(report.tanks.len(), 2);
    assert!(got.iter().any(|m| matches!(
        m.standard(),
        Some(jaus::messages::Message::ReportGlobalPose(p)) if p.latitude.is_some()
    )));
    // Report Services lists the experimental command and query as inputs and the
    // experimental report as an output (from `report:`, not the complement rule).
    let services = got
        .iter()
        .find_map(|m| match m.standard() {
            Some(jaus::messages::Message::ReportServices(s)) => Some(s.clone()),
            _ => None,
        })
        .unwrap();
    let own = services
        .services
        .iter()
        .find(|s| s.service_type == 210)
        .unwrap();
    let inputs: Vec<u16> = own.input_commands.iter().map(|c| c.command_code).collect();
    let outputs: Vec<u16> = own.output_commands.iter().map(|c| c.command_code).collect();
    assert!(
        inputs.contains(&0xD102) && inputs.contains(&0xD100),
        "{inputs:x?}"
    );
    assert!(
        outputs.contains(&0xF100) && outputs.contains(&0xD103),
        "{outputs:x?}"
    );

    // A service connection on the experimental report: the runtime rebuilds the query
    // from the report code through the set (`report:`), and streams the typed reports.
    bus.send(
        OCU,
        MONITOR,
        CreateServiceConnection {
            service_connection_command_code: 0xF100,
            requested_periodic_update_rate: 10.0,
            presence_vector: 0,
        },
    );
    bus.run_for(Duration::from_secs(1));
    let streamed = probe(&bus)
        .received()
        .iter()
        .filter(|r| {
            r.header.service_connection && matches!(r.message, acme::Message::ReportTanks(_))
        })
        .count();
    assert!(
        (9..=12).contains(&streamed),
        "{streamed} reports in 1 s at 10 Hz"
    );
}

#[test]
fn the_vendor_set_keeps_standard_and_unknown_messages() {
    // A standard message decodes into the wrapped SDK set, an unknown code stays raw,
    // and both encode back to the same bytes.
    let pose = ReportGlobalPose {
        latitude: Some(1.0),
        ..Default::default()
    };
    let body = pose.to_bytes().unwrap();
    let m =
        <acme::Message as MessageSet>::decode(<ReportGlobalPose as jaus::JausMessage>::CODE, &body)
            .unwrap();
    assert!(matches!(
        m.standard(),
        Some(jaus::messages::Message::ReportGlobalPose(_))
    ));
    assert_eq!(m.to_bytes().unwrap(), body);
    let raw = <acme::Message as MessageSet>::decode(jaus::CommandCode(0xE123), &[1, 2, 3]).unwrap();
    assert!(matches!(
        raw.standard(),
        Some(jaus::messages::Message::Raw(_))
    ));
    assert_eq!(raw.to_bytes().unwrap(), [1, 2, 3]);
    assert_eq!(
        <acme::Message as MessageSet>::query_of(jaus::CommandCode(0xF100)),
        Some(jaus::CommandCode(0xD100))
    );
    assert_eq!(
        <acme::Message as MessageSet>::info(jaus::CommandCode(0xD102)).map(|i| i.class),
        Some(jaus::wire::MessageClass::Command)
    );
}

/// Issue 11, done when: the vendor component is discovered and answers queries from
/// another node over loopback UDP. Two nodes, each on its own socket and thread: node 1
/// hosts the Tank Monitor, node 2 an operator probe that queries it once discovered.
#[test]
fn the_vendor_component_is_discovered_and_answers_over_udp() {
    let s1 = UdpSocket::bind("127.0.0.1:0").unwrap();
    let s2 = UdpSocket::bind("127.0.0.1:0").unwrap();
    let (a1, a2) = (s1.local_addr().unwrap(), s2.local_addr().unwrap());
    let t0 = Instant::now();
    let config = |ss: u8, peer| NodeConfig {
        subsystem: ss,
        node: 1,
        peers: vec![peer],
        ..NodeConfig::default()
    };
    let mut n1 = Node::new(config(1, a2), t0);
    n1.add(monitor(t0)).unwrap();
    let ocu = Address::new(2, 1, 200, 1);
    let mut n2 = Node::new(config(2, a1), t0);
    n2.add(Probe::<acme::Message>::for_set(ocu)).unwrap();

    let stop = Arc::new(AtomicBool::new(false));
    let until = Some(Instant::now() + Duration::from_secs(20));
    let stop1 = stop.clone();
    let t1 = std::thread::spawn(move || {
        jaus::net::udp::run_on(&mut n1, &s1, &stop1, until, |_| {}).unwrap();
    });
    let mut asked = false;
    let mut answer: Option<ReportTanks> = None;
    let mut name = None;
    jaus::net::udp::run_on(&mut n2, &s2, &stop, until, |n| {
        let info = n
            .tree()
            .subsystems
            .get(&1)
            .and_then(|s| s.nodes.get(&1))
            .and_then(|node| node.components.get(&(210, 1)));
        if let Some(i) = info {
            name = i.name.clone().or(name.take());
        }
        if !asked && info.is_some() {
            asked = true;
            let body = QueryTanks { presence_vector: 0 }.to_bytes().unwrap();
            let h = Header::new(<QueryTanks as jaus::JausMessage>::CODE, MONITOR, ocu);
            n.send(Instant::now(), h, body);
        }
        let probe: &Probe<acme::Message> = n.get(ocu).unwrap();
        answer = probe.messages().find_map(|m| match m {
            acme::Message::ReportTanks(r) => Some(r.clone()),
            _ => None,
        });
        if answer.is_some() && name.is_some() {
            stop.store(true, Ordering::Relaxed);
        }
    })
    .unwrap();
    stop.store(true, Ordering::Relaxed);
    t1.join().unwrap();
    assert!(asked, "the Tank Monitor was never discovered");
    assert_eq!(name.as_deref(), Some("TankMonitor"));
    let answer = answer.expect("no ReportTanks over UDP");
    assert_eq!(answer.vehicle, "carrier-7");
}
