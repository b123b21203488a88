//! Issue 29 item 6: a component joining or leaving a node is told to the node managers
//! of other subsystems that hold the node's configuration, on a virtual clock, without
//! OpenJAUS. The peer here behaves as OpenJAUS's node manager does toward another
//! subsystem (docs/wire.md §7.3, §8.3): it learns the subsystem from a heartbeat, asks
//! its identification and configuration (subsystem level) and subscribes to it (Create
//! Event, every change, query body `02`), then replaces its whole view of the subsystem
//! with every Report Configuration it receives, directly or in an Event; it never asks
//! again while it hears heartbeats, and it drops a controller its view does not list.
//!
//! * `a_subscriber_is_told_of_a_component_joining_and_leaving`: the configuration event
//!   carries the join and the leave (and nothing is sent twice);
//! * `a_peer_that_subscribed_to_an_earlier_run_is_told_too`: the node restarted (the
//!   peer keeps the configuration and the subscription of the earlier run, as OpenJAUS
//!   does within its 5 s timeout), so nobody subscribes here: the node sends the
//!   configuration as a report, once after `announce_after` and on every change.

use std::collections::BTreeSet;
use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::codec::{Decode, Encode};
use jaus::component::local::Probe;
use jaus::messages::*;
use jaus::net::framing::Framing;
use jaus::net::{Node, NodeConfig};
use jaus::{Address, Header, JausMessage};

/// The vendor's node: subsystem 30, node 1, hosting a primitive driver (a probe here).
const NM: Address = Address::new(30, 1, 1, 1);
const PD: Address = Address::new(30, 1, 33, 1);
/// The component joining the node from a process of its own (the `jaus` CLI).
const CLI: Address = Address::new(30, 1, 40, 1);
/// The peer: subsystem 10's node manager and communicator (OpenJAUS's addresses).
const PEER_NM: Address = Address::new(10, 1, 1, 1);
const PEER_COMM: Address = Address::new(10, 1, 35, 1);

fn peer_socket() -> SocketAddr {
    "127.0.0.1:3794".parse().unwrap()
}

fn cli_socket() -> SocketAddr {
    "127.0.0.3:3794".parse().unwrap()
}

fn vendor_node(t0: Instant) -> Node {
    let mut node = Node::new(
        NodeConfig {
            subsystem: 30,
            node: 1,
            peers: vec![peer_socket()],
            ..NodeConfig::default()
        },
        t0,
    );
    node.add(Probe::new(PD)).unwrap();
    node
}

fn datagram(msg: impl Into<Message>, from: Address, to: Address) -> Vec<u8> {
    let msg = msg.into();
    let body = msg.to_bytes().unwrap();
    let mut p = Header::new(msg.code(), to, from)
        .encode_with_size(body.len())
        .unwrap()
        .to_vec();
    p.extend_from_slice(&body);
    Framing::Judp.encode(&p)
}

/// What the peer received, in order: (time since start, source, message).
type Log = Vec<(Duration, Address, Message)>;

/// The OpenJAUS-like node manager of subsystem 10.
struct Peer {
    /// Its view of subsystem 30: (node, component, instance).
    view: BTreeSet<(u8, u8, u8)>,
    log: Log,
}

impl Peer {
    /// Takes what the node sent to the peer's socket; applies configurations.
    fn receive(&mut self, node: &mut Node, t0: Instant) {
        let now = node.now();
        while let Some(d) = node.poll_transmit() {
            if d.to != peer_socket() {
                continue;
            }
            let (header, body) = Framing::Judp.packet(&d.bytes).unwrap();
            let msg = Message::decode(header.command_code, body).unwrap();
            let report = match &msg {
                Message::ReportConfiguration(r) => Some(r.clone()),
                Message::Event(e) if e.report_message_code == ReportConfiguration::CODE.0 => {
                    Some(ReportConfiguration::from_bytes(&e.report_message).unwrap())
                }
                _ => None,
            };
            if let Some(r) = report {
                // OpenJAUS replaces the whole subsystem with the report's.
                self.view = r
                    .nodes
                    .iter()
                    .flat_map(|n| {
                        n.components
                            .iter()
                            .map(move |c| (n.node_id, c.component_id, c.instance_id))
                    })
                    .collect();
            }
            self.log.push((now - t0, header.source, msg));
        }
    }

    fn lists(&self, a: Address) -> bool {
        self.view.contains(&(a.node, a.component, a.instance))
    }

    /// Configuration reports received since `from`: (time, as an Event?, lists `a`?).
    fn reports_since(&self, from: Duration, a: Address) -> Vec<(Duration, bool, bool)> {
        let lists = |r: &ReportConfiguration| {
            r.nodes.iter().any(|n| {
                n.node_id == a.node
                    && n.components
                        .iter()
                        .any(|c| (c.component_id, c.instance_id) == (a.component, a.instance))
            })
        };
        self.log
            .iter()
            .filter(|(t, ..)| *t >= from)
            .filter_map(|(t, _, m)| match m {
                Message::ReportConfiguration(r) => Some((*t, false, lists(r))),
                Message::Event(e) if e.report_message_code == ReportConfiguration::CODE.0 => {
                    let r = ReportConfiguration::from_bytes(&e.report_message).unwrap();
                    Some((*t, true, lists(&r)))
                }
                _ => None,
            })
            .collect()
    }
}

/// Runs the node to `until` in 5 ms steps: the peer's communicator heartbeats every
/// second, the joined component every second while `cli_alive` says so.
fn run(
    node: &mut Node,
    peer: &mut Peer,
    t0: Instant,
    until: Duration,
    cli_alive: impl Fn(Duration) -> bool,
) {
    let step = Duration::from_millis(5);
    let mut t = node.now() - t0;
    while t < until {
        t += step;
        let now = t0 + t;
        let second = t.as_millis() % 1000 < step.as_millis();
        if second {
            node.handle_datagram(
                now,
                peer_socket(),
                &datagram(
                    ReportHeartbeatPulse {},
                    PEER_COMM,
                    Address::new(255, 255, 1, 1),
                ),
            );
            if cli_alive(t) {
                node.handle_datagram(
                    now,
                    cli_socket(),
                    &datagram(ReportHeartbeatPulse {}, CLI, NM),
                );
            }
        }
        if node.poll_timeout().is_some_and(|w| w <= now) {
            node.handle_timeout(now);
        }
        peer.receive(node, t0);
    }
}

#[test]
fn a_subscriber_is_told_of_a_component_joining_and_leaving() {
    let t0 = Instant::now();
    let mut node = vendor_node(t0);
    let mut peer = Peer {
        view: BTreeSet::new(),
        log: Vec::new(),
    };
    node.handle_timeout(t0);
    peer.receive(&mut node, t0);
    // Discovery as OpenJAUS does it on the node's first heartbeat: identification,
    // configuration and the subscription, all subsystem level.
    let ask = |m: Message| datagram(m, PEER_NM, NM);
    for m in [
        QueryIdentification {
            query_field: QueryLevel::Subsystem,
        }
        .into(),
        QueryConfiguration {
            query_field: QueryLevel::Subsystem,
        }
        .into(),
        CreateEvent {
            request_id: 0,
            report_message_code: ReportConfiguration::CODE.0,
            event_type: EventType::EveryChange,
            query_message: Some(vec![2]),
            ..Default::default()
        }
        .into(),
    ] {
        node.handle_datagram(t0, peer_socket(), &ask(m));
    }
    peer.receive(&mut node, t0);
    assert!(
        peer.log.iter().any(|(_, _, m)| matches!(m,
            Message::ConfirmEventRequest(c) if c.response_code == EventResponseCode::Successful)),
        "{:?}",
        peer.log
    );
    assert!(peer.lists(NM) && peer.lists(PD) && !peer.lists(CLI));
    // The component joins 2 s later and heartbeats until 6 s.
    let joined = Duration::from_secs(2);
    let last_heartbeat = Duration::from_secs(6);
    let alive = |t: Duration| t >= joined && t <= last_heartbeat;
    run(&mut node, &mut peer, t0, Duration::from_secs(4), alive);
    let told = peer.reports_since(joined, CLI);
    let (t, event, lists) = told[0];
    assert!(event && lists, "{told:?}");
    assert!(t <= joined + Duration::from_millis(100), "told after {t:?}");
    assert!(peer.lists(CLI), "{:?}", peer.view);
    // Its view names every component of the node (what OpenJAUS checks a controller
    // against).
    assert!(peer.lists(NM) && peer.lists(PD));
    // Silent from 6 s, the component is removed 3 s later, and the peer is told.
    run(&mut node, &mut peer, t0, Duration::from_secs(11), alive);
    let told = peer.reports_since(last_heartbeat, CLI);
    let (t, event, lists) = *told.last().unwrap();
    assert!(event && !lists, "{told:?}");
    assert!(
        t <= last_heartbeat + Duration::from_millis(3100),
        "told after {t:?}"
    );
    assert!(!peer.lists(CLI) && peer.lists(PD), "{:?}", peer.view);
    // A subscriber gets the configuration as Events only: no plain report beside them,
    // and one Event per change.
    let all = peer.reports_since(Duration::from_millis(1), CLI);
    assert!(all.iter().all(|(_, event, _)| *event), "{all:?}");
    assert_eq!(all.len(), 2, "{all:?}");
}

#[test]
fn a_peer_that_subscribed_to_an_earlier_run_is_told_too() {
    let t0 = Instant::now();
    let mut node = vendor_node(t0);
    // The peer holds what the earlier run of the node reported (it hosted one more
    // component), believes it is subscribed, and so asks nothing: it only heartbeats.
    let mut peer = Peer {
        view: [(1, 1, 1), (1, 33, 1), (1, 38, 1)].into_iter().collect(),
        log: Vec::new(),
    };
    node.handle_timeout(t0);
    peer.receive(&mut node, t0);
    let alive_from = |from: Duration, to: Duration| move |t: Duration| t >= from && t <= to;
    // Nothing changes: after `announce_after` (3 s) the peer gets the configuration
    // once, without the component of the earlier run.
    let after = jaus::net::ManagerConfig::default().announce_after;
    run(
        &mut node,
        &mut peer,
        t0,
        Duration::from_secs(4),
        alive_from(Duration::MAX, Duration::MAX),
    );
    let told = peer.reports_since(Duration::ZERO, PD);
    assert_eq!(told.len(), 1, "{told:?}");
    let (t, event, lists) = told[0];
    assert!(!event && lists, "{told:?}");
    assert!(
        t >= after && t <= after + Duration::from_millis(1100),
        "told at {t:?}"
    );
    assert!(!peer.view.contains(&(1, 38, 1)), "{:?}", peer.view);
    // A component joins at 5 s: told at once, as a report.
    let (joined, last_heartbeat) = (Duration::from_secs(5), Duration::from_secs(8));
    let alive = alive_from(joined, last_heartbeat);
    run(&mut node, &mut peer, t0, Duration::from_secs(7), alive);
    let told = peer.reports_since(joined, CLI);
    assert_eq!(told.len(), 1, "{told:?}");
    let (t, event, lists) = told[0];
    assert!(!event && lists, "{told:?}");
    assert!(t <= joined + Duration::from_millis(100), "told after {t:?}");
    assert!(peer.lists(CLI) && peer.lists(PD), "{:?}", peer.view);
    // It leaves: removed 3 s after its last heartbeat, and the peer is told.
    run(&mut node, &mut peer, t0, Duration::from_secs(13), alive);
    let told = peer.reports_since(last_heartbeat, CLI);
    assert_eq!(told.len(), 1, "{told:?}");
    let (t, event, lists) = told[0];
    assert!(!event && !lists, "{told:?}");
    assert!(
        t <= last_heartbeat + Duration::from_millis(3100),
        "told after {t:?}"
    );
    assert!(!peer.lists(CLI) && peer.lists(PD), "{:?}", peer.view);
}
