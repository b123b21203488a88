//! The Communicator (issue 14, item 3): its data-link messages and rules on a local bus,
//! and two subsystems whose only connection is the communicators' simulated radio
//! (Part 1 Figure 5-1): a service connection and a control connection across the link,
//! the link going down (Loss Of Command in the status reports, drops counted) and back
//! up (reports resume, control is taken again).

use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::local::{LocalBus, Probe};
use jaus::component::{Component, Config, Refused};
use jaus::components::global_pose_sensor::{self, GlobalPoseSensor};
use jaus::components::subsystem_commander::{self, SubsystemCommander};
use jaus::messages::*;
use jaus::net::{Node, NodeConfig};
use jaus::stock::communicator::{
    CommunicatorConfig, CommunicatorEndpoint, DataLink, LinkStats, StockCommunicator,
};
use jaus::wire::{AckNak, Header};
use jaus::{Address, JausMessage};

use jaus_sim::network::{LinkModel, SimNet};
use jaus_sim::radio::{radio_pair, Radio, RadioControl, RadioParams};

const C1: Address = Address::new(1, 1, 35, 1);
const C2: Address = Address::new(2, 1, 35, 1);
const OCU: Address = Address::new(1, 1, 32, 1);
const PROBE: Address = Address::new(1, 1, 200, 1);
const GPS: Address = Address::new(2, 1, 38, 1);

type Gateway = CommunicatorEndpoint<Radio>;

// ---------------------------------------------------------------------------------
// Messages and rules, on a local bus.

fn with_ack(bus: &mut LocalBus, msg: impl Into<Message>) {
    let msg: Message = msg.into();
    let mut h = Header::new(msg.code(), C1, PROBE);
    h.ack_nak = AckNak::Request;
    bus.send_with(h, Some(&msg));
}

fn answers(bus: &mut LocalBus, kind: AckNak) -> usize {
    bus.trace()
        .filter(|d| d.header.source == C1 && d.header.ack_nak == kind)
        .count()
}

fn replies(bus: &mut LocalBus) -> Vec<Message> {
    let p = bus.get_mut::<Probe>(PROBE).unwrap();
    let out = p.messages().cloned().collect();
    p.clear();
    out
}

fn link_status(bus: &mut LocalBus, id: u8) -> Option<DataLinkState> {
    bus.send(PROBE, C1, QueryDataLinkStatus { data_link_id: id });
    bus.run_for(Duration::from_millis(20));
    replies(bus).into_iter().find_map(|m| match m {
        Message::ReportDataLinkStatus(r) if r.data_link_id == id => Some(r.data_link_state),
        _ => None,
    })
}

fn selected(bus: &mut LocalBus) -> Option<u8> {
    bus.send(PROBE, C1, QuerySelectedDataLinkStatus {});
    bus.run_for(Duration::from_millis(20));
    replies(bus).into_iter().find_map(|m| match m {
        Message::ReportSelectedDataLinkStatus(r) => Some(r.data_link_id),
        _ => None,
    })
}

#[test]
fn data_link_messages_select_set_and_report_only_for_the_controller() {
    let t0 = Instant::now();
    // Two radios, ids 1 and 2; the far ends stay silent.
    let (r1, _far1, _) = radio_pair(1, RadioParams::default());
    let (r2, _far2, _) = radio_pair(2, RadioParams::default());
    let stock = StockCommunicator::new(vec![r1, r2], CommunicatorConfig::default(), t0).unwrap();
    let mut bus = LocalBus::new(t0).with_trace(10_000);
    bus.add(CommunicatorEndpoint::new(C1, stock, Config::default(), t0));
    bus.add(Probe::new(PROBE));
    bus.run_for(Duration::from_millis(100));

    // Queries from anyone.
    assert_eq!(selected(&mut bus), Some(1));
    assert_eq!(link_status(&mut bus, 1), Some(DataLinkState::On));
    assert_eq!(link_status(&mut bus, 2), Some(DataLinkState::On));
    // An unknown link: refused (a NAK when asked for one), no report.
    with_ack(&mut bus, QueryDataLinkStatus { data_link_id: 9 });
    bus.run_for(Duration::from_millis(20));
    assert_eq!(answers(&mut bus, AckNak::Nak), 1);
    // No report: only the reason of the NAK (the SDK's Report Refusal).
    let r = replies(&mut bus);
    assert!(
        r.iter().all(|m| matches!(m, Message::ReportRefusal(_))) && r.len() == 1,
        "{r:?}"
    );

    // Commands need control.
    with_ack(&mut bus, SetDataLinkSelect { data_link_id: 2 });
    bus.run_for(Duration::from_millis(20));
    assert_eq!(answers(&mut bus, AckNak::Nak), 2);
    assert_eq!(selected(&mut bus), Some(1), "not selected without control");
    bus.send(PROBE, C1, RequestComponentControl { authority_code: 10 });
    bus.run_for(Duration::from_millis(50));
    let g = bus.get::<Gateway>(C1).unwrap();
    assert_eq!(g.component().controller().map(|c| c.0), Some(PROBE));

    // Select link 2; an unknown link is refused and changes nothing.
    with_ack(&mut bus, SetDataLinkSelect { data_link_id: 2 });
    with_ack(&mut bus, SetDataLinkSelect { data_link_id: 7 });
    bus.run_for(Duration::from_millis(20));
    assert_eq!(answers(&mut bus, AckNak::Ack), 1);
    assert_eq!(answers(&mut bus, AckNak::Nak), 3);
    assert_eq!(selected(&mut bus), Some(2));

    // Set Selected Data Link State names its link; Set Data Link Status sets the
    // selected one's.
    with_ack(
        &mut bus,
        SetSelectedDataLinkState {
            data_link_id: 1,
            state: DataLinkState::Standby,
        },
    );
    with_ack(
        &mut bus,
        SetDataLinkStatus {
            state: DataLinkState::Off,
        },
    );
    bus.run_for(Duration::from_millis(20));
    assert_eq!(answers(&mut bus, AckNak::Ack), 3);
    assert_eq!(link_status(&mut bus, 1), Some(DataLinkState::Standby));
    assert_eq!(link_status(&mut bus, 2), Some(DataLinkState::Off));

    // Refused: an unknown link, Loss Of Command (a condition, not a command), a state
    // the definition does not name.
    for m in [
        Message::from(SetSelectedDataLinkState {
            data_link_id: 3,
            state: DataLinkState::On,
        }),
        Message::from(SetSelectedDataLinkState {
            data_link_id: 1,
            state: DataLinkState::LossOfCommand,
        }),
        Message::from(SetDataLinkStatus {
            state: DataLinkState::Unknown(7),
        }),
    ] {
        with_ack(&mut bus, m);
    }
    bus.run_for(Duration::from_millis(20));
    assert_eq!(answers(&mut bus, AckNak::Nak), 6);
    assert_eq!(link_status(&mut bus, 1), Some(DataLinkState::Standby));
    let refused = bus.get::<Gateway>(C1).unwrap().component().stats();
    // The query on link 9, the selection of link 7, the three commands above; the
    // selection before control.
    assert_eq!(
        (refused.invalid, refused.not_controller),
        (5, 1),
        "{refused:?}"
    );

    // On again, and nothing heard from the far side for the silence timeout (3 s):
    // Loss Of Command.
    with_ack(
        &mut bus,
        SetSelectedDataLinkState {
            data_link_id: 1,
            state: DataLinkState::On,
        },
    );
    bus.run_for(Duration::from_millis(20));
    assert_eq!(link_status(&mut bus, 1), Some(DataLinkState::On));
    bus.run_for(Duration::from_secs(3));
    assert_eq!(link_status(&mut bus, 1), Some(DataLinkState::LossOfCommand));
    // The accessor says the same.
    let now = bus.now();
    let c = bus.get::<Gateway>(C1).unwrap().communicator();
    assert_eq!(c.link_state(1, now), Some(DataLinkState::LossOfCommand));
    assert_eq!(c.link_state(2, now), Some(DataLinkState::Off));
    assert_eq!(c.link_state(5, now), None);
}

#[test]
fn a_communicator_needs_links_with_distinct_ids() {
    let t0 = Instant::now();
    let none: Vec<Radio> = Vec::new();
    assert!(StockCommunicator::new(none, CommunicatorConfig::default(), t0).is_err());
    let (a, b, _) = radio_pair(4, RadioParams::default());
    let e = StockCommunicator::new(vec![a, b], CommunicatorConfig::default(), t0).unwrap_err();
    assert_eq!(e.to_string(), "two data links have id 4");
}

// ---------------------------------------------------------------------------------
// Two subsystems joined by the radio only.

struct Gps;
impl GlobalPoseSensor for Gps {
    fn on_query_global_pose(
        &mut self,
        _c: &mut global_pose_sensor::Ctx<'_>,
        _q: &QueryGlobalPose,
    ) -> Result<ReportGlobalPose, Refused> {
        Ok(ReportGlobalPose {
            latitude: Some(29.6),
            longitude: Some(-82.3),
            ..Default::default()
        })
    }
}

/// An operator in subsystem 1: keeps a service connection on the GPS of subsystem 2
/// (asks again when reports stop for 2 s) and control of subsystem 2's communicator
/// (asks again, once a second, while it does not have it).
#[derive(Default)]
struct Operator {
    reports: Vec<Instant>,
    asked_at: Option<Instant>,
    subscriptions: u32,
    control_asked_at: Option<Instant>,
    control_requests: u32,
}

impl SubsystemCommander for Operator {
    fn tick(&mut self, ctx: &mut subsystem_commander::Ctx<'_>) {
        let now = ctx.now();
        // Asked for once: the runtime asks again when the reports stop.
        if self.asked_at.is_none()
            && ctx
                .create_service_connection(GPS, ReportGlobalPose::CODE, 5.0, 0x3)
                .is_ok()
        {
            self.subscriptions += 1;
            self.asked_at = Some(now);
        }
        let again = self
            .control_asked_at
            .is_none_or(|t| now.duration_since(t) >= Duration::from_secs(1));
        if !ctx.has_control_of(C2) && again {
            ctx.request_control(C2);
            self.control_requests += 1;
            self.control_asked_at = Some(now);
        }
    }

    fn on_other_message(
        &mut self,
        ctx: &mut subsystem_commander::Ctx<'_>,
        msg: &Message,
    ) -> Result<Option<Message>, Refused> {
        if let Message::ReportGlobalPose(_) = msg {
            self.reports.push(ctx.now());
        }
        Ok(None)
    }
}

type Ocu = Component<subsystem_commander::Dispatch<Operator>>;

fn subsystem(ss: u8, link: Radio, t0: Instant) -> Node {
    let comm = Address::new(ss, 1, 35, 1);
    let mut config = NodeConfig {
        subsystem: ss,
        node: 1,
        communicator: Some(comm),
        ..NodeConfig::default()
    };
    config.manager.subsystem_name = format!("subsystem {ss}");
    let mut node = Node::new(config, t0);
    let stock = StockCommunicator::new(vec![link], CommunicatorConfig::default(), t0).unwrap();
    node.add(CommunicatorEndpoint::new(
        comm,
        stock,
        Config::default(),
        t0,
    ))
    .unwrap();
    node
}

struct System {
    net: SimNet,
    radio: RadioControl,
}

/// Subsystem 1 (slot 0: communicator, operator, probe) and subsystem 2 (slot 1:
/// communicator, GPS) on a simulated network with no peers configured: nothing
/// crosses it; the radio (9.6 kbit/s, 40 ms, 2 % loss) is the only path.
fn system(seed: u64) -> System {
    let t0 = Instant::now();
    let params = RadioParams {
        loss: 0.02,
        latency: Duration::from_millis(40),
        bandwidth_bps: 9_600,
        queue_frames: 16,
        seed,
        ..RadioParams::default()
    };
    let (a, b, radio) = radio_pair(1, params);
    let mut n1 = subsystem(1, a, t0);
    n1.add(subsystem_commander::component(
        OCU,
        Operator::default(),
        Config::default(),
        t0,
    ))
    .unwrap();
    n1.add(Probe::new(PROBE)).unwrap();
    let mut n2 = subsystem(2, b, t0);
    n2.add(global_pose_sensor::component(
        GPS,
        Gps,
        Config::default(),
        t0,
    ))
    .unwrap();
    let mut net = SimNet::new(t0, LinkModel::default(), seed);
    net.add(n1);
    net.add(n2);
    System { net, radio }
}

impl System {
    fn operator(&self) -> &Operator {
        &self
            .net
            .node(0)
            .unwrap()
            .get::<Ocu>(OCU)
            .unwrap()
            .behaviour()
            .0
    }

    fn reports(&self) -> usize {
        self.operator().reports.len()
    }

    /// Service connections the operator's runtime asked for again (reports stopped).
    fn renewed(&self) -> u64 {
        let ocu = self.net.node(0).unwrap().get::<Ocu>(OCU).unwrap();
        ocu.stats().subscriptions_renewed
    }

    fn link(&self, slot: usize) -> LinkStats {
        let c = Address::new(slot as u8 + 1, 1, 35, 1);
        let g = self.net.node(slot).unwrap().get::<Gateway>(c).unwrap();
        g.communicator().link_stats(1).unwrap()
    }

    /// Data link 1's state, as subsystem 1's communicator reports it to a query.
    fn reported_state(&mut self) -> Option<DataLinkState> {
        let q = Message::from(QueryDataLinkStatus { data_link_id: 1 });
        let now = self.net.now();
        let node = self.net.node_mut(0).unwrap();
        node.send(now, Header::new(q.code(), C1, PROBE), q.to_bytes().unwrap());
        self.net.run_for(Duration::from_millis(20));
        let p = self
            .net
            .node_mut(0)
            .unwrap()
            .get_mut::<Probe>(PROBE)
            .unwrap();
        let state = p.messages().find_map(|m| match m {
            Message::ReportDataLinkStatus(r) => Some(r.data_link_state),
            _ => None,
        });
        p.clear();
        state
    }

    fn controller_of_c2(&self) -> Option<Address> {
        let g = self.net.node(1).unwrap().get::<Gateway>(C2).unwrap();
        g.component().controller().map(|c| c.0)
    }
}

#[test]
fn a_service_connection_across_the_radio_survives_the_link_going_down_and_up() {
    let mut s = system(7);

    // Up: the subsystems find each other through the communicators' heartbeats, the
    // operator gets GPS reports and control of the far communicator.
    s.net.run_for(Duration::from_secs(6));
    assert_eq!(
        s.net.stats().sent,
        0,
        "no datagram on the network: the radio is the only path"
    );
    let tree = s.net.node(0).unwrap().tree();
    assert!(tree.has_node(2, 1), "subsystem 2 seen:\n{}", tree.render());
    let n = s.reports();
    assert!(n >= 15, "reports at 5 Hz across the radio: {n}");
    assert_eq!(s.controller_of_c2(), Some(OCU));
    assert_eq!(s.reported_state(), Some(DataLinkState::On));
    let (l1, l2) = (s.link(0), s.link(1));
    assert!(l1.frames_sent > 0 && l1.frames_received > 0, "{l1:?}");
    assert!(l2.frames_sent > 0 && l2.frames_received > 0, "{l2:?}");
    let node1 = s.net.node(0).unwrap().stats();
    assert!(
        node1.to_communicator > 0 && node1.from_communicator > 0,
        "{node1:?}"
    );
    let renewed = s.renewed();

    // A short outage (1.5 s, under the silence and subsystem timeouts): Loss Of
    // Command while the radio is down, drops counted, and the same service connection
    // goes on afterwards.
    s.radio.set_up(false);
    s.net.run_for(Duration::from_millis(500));
    assert_eq!(s.reported_state(), Some(DataLinkState::LossOfCommand));
    s.net.run_for(Duration::from_millis(1_000));
    let stalled = s.reports();
    s.radio.set_up(true);
    s.net.run_for(Duration::from_secs(2));
    assert!(
        s.reports() >= stalled + 7,
        "reports resume: {} -> {}",
        stalled,
        s.reports()
    );
    assert_eq!(s.reported_state(), Some(DataLinkState::On));
    assert_eq!(s.renewed(), renewed, "no new subscription needed");
    assert!(
        s.link(1).dropped_link_down > 0,
        "GPS reports dropped at subsystem 2"
    );

    // A long outage (10 s): both node managers drop the other subsystem, the GPS ends
    // the service connection and the far communicator forgets its controller.
    let before = (s.link(0), s.link(1));
    s.radio.set_up(false);
    s.net.run_for(Duration::from_secs(10));
    assert_eq!(s.reported_state(), Some(DataLinkState::LossOfCommand));
    let stalled = s.reports();
    let last = s.operator().reports.last().copied().unwrap();
    assert!(s.net.now().duration_since(last) > Duration::from_secs(9));
    assert!(!s.net.node(0).unwrap().tree().has_node(2, 1));
    assert!(!s.net.node(1).unwrap().tree().has_node(1, 1));
    let gps = s
        .net
        .node(1)
        .unwrap()
        .get::<Component<global_pose_sensor::Dispatch<Gps>>>(GPS);
    assert_eq!(gps.unwrap().service_connections(), 0);
    assert_eq!(s.controller_of_c2(), None);
    let (d1, d2) = (s.link(0), s.link(1));
    assert!(
        d1.dropped_link_down >= before.0.dropped_link_down + 10,
        "heartbeats, queries and requests dropped at subsystem 1: {d1:?}"
    );
    assert!(
        d2.dropped_link_down > before.1.dropped_link_down,
        "drops at subsystem 2: {d2:?}"
    );
    assert_eq!(d1.frames_received, before.0.frames_received);

    // Up again: the subsystems meet again, the operator's runtime subscribes again, it takes
    // control again.
    s.radio.set_up(true);
    s.net.run_for(Duration::from_secs(8));
    assert_eq!(s.reported_state(), Some(DataLinkState::On));
    assert!(s.net.node(0).unwrap().tree().has_node(2, 1));
    assert!(
        s.reports() >= stalled + 15,
        "reports resume: {} -> {}",
        stalled,
        s.reports()
    );
    // Asked for once by the operator; the runtime asked again by itself.
    assert_eq!(s.operator().subscriptions, 1);
    assert!(
        s.renewed() > renewed,
        "renewed {} -> {}",
        renewed,
        s.renewed()
    );
    assert_eq!(s.controller_of_c2(), Some(OCU), "control taken again");
    assert!(s.operator().control_requests >= 2);
    assert_eq!(s.net.stats().sent, 0);
}

#[test]
fn without_a_communicator_nothing_changes_and_with_one_udp_from_other_subsystems_is_dropped() {
    // Subsystem 1 has a communicator; subsystem 2 talks to it over UDP directly, which
    // Figure 5-1 does not allow: dropped and counted.
    let t0 = Instant::now();
    let (a, _b, _) = radio_pair(1, RadioParams::default());
    let mut n1 = subsystem(1, a, t0);
    n1.add(Probe::new(PROBE)).unwrap();
    let n2 = Node::new(
        NodeConfig {
            subsystem: 2,
            node: 1,
            peers: vec![SimNet::addr(0)],
            ..NodeConfig::default()
        },
        t0,
    );
    let mut net = SimNet::new(t0, LinkModel::default(), 1);
    net.add(n1);
    net.add(n2);
    net.run_for(Duration::from_secs(3));
    let s1 = net.node(0).unwrap().stats();
    assert!(s1.not_via_communicator >= 2, "{s1:?}");
    assert!(!net.node(0).unwrap().tree().has_node(2, 1));
}

#[test]
fn a_slow_link_queues_then_drops_and_counts() {
    let t0 = Instant::now();
    // 9.6 kbit/s, room for 4 frames in the radio; 8 more wait in the communicator.
    let params = RadioParams {
        bandwidth_bps: 9_600,
        queue_frames: 4,
        latency: Duration::from_millis(10),
        ..RadioParams::default()
    };
    let (a, mut b, radio) = radio_pair(1, params);
    let config = CommunicatorConfig {
        max_queue: 8,
        ..CommunicatorConfig::default()
    };
    let mut c = StockCommunicator::new(vec![a], config, t0).unwrap();
    let frame = [0u8; 116]; // a 16-byte header and 100 bytes: 96.7 ms at 9.6 kbit/s
    for _ in 0..100 {
        c.forward(t0, &frame);
    }
    let s = c.link_stats(1).unwrap();
    assert_eq!((s.frames_sent, s.queued, s.dropped_queue_full), (4, 8, 88));
    assert_eq!(
        radio.stats(0).refused_busy,
        8,
        "the radio refused each frame offered to it while full"
    );
    // The radio wakes the communicator when room frees; after 2 s everything queued
    // is on the air and delivered.
    let mut now = t0;
    let mut got = 0;
    let mut buf = Vec::new();
    while let Some(t) = [c.poll_timeout(), b.poll_timeout()]
        .into_iter()
        .flatten()
        .min()
    {
        if t > t0 + Duration::from_secs(2) {
            break;
        }
        now = t;
        c.service(now);
        while b.recv(now, &mut buf) {
            assert_eq!(buf.len(), 116);
            got += 1;
        }
    }
    let s = c.link_stats(1).unwrap();
    assert_eq!((s.frames_sent, s.queued, s.bytes_sent), (12, 0, 12 * 116));
    assert_eq!(got, 12);
    // The twelfth frame left after 12 air times and arrived 10 ms later.
    let expect = Duration::from_secs_f64(12.0 * 116.0 * 8.0 / 9_600.0) + Duration::from_millis(10);
    assert!(
        now.duration_since(t0).abs_diff(expect) < Duration::from_millis(1),
        "{:?}",
        now.duration_since(t0)
    );
    // Down: frames are dropped as link-down, not queued.
    radio.set_up(false);
    c.forward(now, &frame);
    let s = c.link_stats(1).unwrap();
    assert_eq!((s.dropped_link_down, s.queued), (1, 0));
    assert_eq!(c.link_state(1, now), Some(DataLinkState::LossOfCommand));
}

#[test]
fn a_node_without_the_communicator_reaches_other_subsystems_through_the_node_that_has_it() {
    let t0 = Instant::now();
    let (a, b, radio) = radio_pair(1, RadioParams::default());
    // Subsystem 1: node 1 (slot 0) has the communicator, node 2 (slot 1) the operator.
    let n11 = subsystem(1, a, t0);
    let ocu = Address::new(1, 2, 32, 1);
    let mut n12 = Node::new(
        NodeConfig {
            subsystem: 1,
            node: 2,
            peers: vec![SimNet::addr(0)],
            communicator: Some(C1),
            ..NodeConfig::default()
        },
        t0,
    );
    n12.add(subsystem_commander::component(
        ocu,
        Operator::default(),
        Config::default(),
        t0,
    ))
    .unwrap();
    let mut n21 = subsystem(2, b, t0);
    n21.add(global_pose_sensor::component(
        GPS,
        Gps,
        Config::default(),
        t0,
    ))
    .unwrap();
    let mut net = SimNet::new(t0, LinkModel::default(), 3);
    net.add(n11);
    net.add(n12);
    net.add(n21);
    net.run_for(Duration::from_secs(6));
    let op = &net.node(1).unwrap().get::<Ocu>(ocu).unwrap().behaviour().0;
    assert!(
        op.reports.len() >= 15,
        "reports relayed by node 1: {}",
        op.reports.len()
    );
    let g = net.node(2).unwrap().get::<Gateway>(C2).unwrap();
    assert_eq!(g.component().controller().map(|c| c.0), Some(ocu));
    // Node 1 handed node 2's traffic to its communicator and relayed the answers; the
    // far subsystem is in both trees of subsystem 1.
    let s11 = net.node(0).unwrap().stats();
    assert!(
        s11.to_communicator > 20 && s11.from_communicator > 20,
        "{s11:?}"
    );
    assert!(net.node(1).unwrap().tree().has_node(2, 1));
    assert!(net.node(2).unwrap().tree().has_node(1, 2));
    assert_eq!(net.node(1).unwrap().stats().not_via_communicator, 0);
    assert!(radio.stats(1).delivered > 20);
}
