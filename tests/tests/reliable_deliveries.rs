//! Issue 48, item 3: the stock mission spooler's deliveries and the AS-4 gateway's
//! commands to RA 3.3 components go through the node's reliable delivery
//! (`NodeConfig::reliable`), and each learns what became of them.
//!
//! * A mission spooled on node 1.1 for a component on node 1.2, over a lossy,
//!   duplicating, reordering `SimNet`: with the nodes making commands arrive, every
//!   message is carried out exactly once and the mission finishes; without, on the same
//!   seed, some are lost.
//! * A delivery whose acknowledgement is lost is sent again and carried out once.
//! * A delivery refused pauses the mission with a reason; Resume Mission sends it again.
//! * The gateway's control request and waypoint upload, lost once, are sent again and
//!   acknowledged; without reliable delivery control of that driver is never had.

use std::net::SocketAddr;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::{Component, Config, ControlPolicy, Refused, StopReason};
use jaus::components::global_waypoint_driver::{self, GlobalWaypointDriver};
use jaus::components::mission_spooler;
use jaus::messages::*;
use jaus::net::as5669a::{As4Client, As4Id, As4Message, As4Side};
use jaus::net::reliable::{ReliableStats, RetryPolicy};
use jaus::net::{Datagram, Framing, Node, NodeConfig, Participant, Via};
use jaus::stock::spooler::{command, leaf_task, mission_of, SpoolerConfig, StockMissionSpooler};
use jaus::wire::{AckNak, Header};
use jaus::{Address, JausMessage};
use jaus_sim::network::{LinkModel, SimNet};

const MS: Address = Address::new(1, 1, 36, 1);
/// The spooler's owner: an address of the spooler's node (messages from it are local).
const OWNER: Address = Address::new(1, 1, 40, 1);
const RECORDER: Address = Address::new(1, 2, 45, 1);

type Spooler = Component<mission_spooler::Dispatch<StockMissionSpooler>>;
type Rec = Component<global_waypoint_driver::Dispatch<Recorder>>;

/// A waypoint driver on another node that records the uids of the mission messages it
/// carried out (Spool Mission, one message a batch; or the raw Set Global Waypoint,
/// numbered as its uid) and may refuse one uid once.
#[derive(Debug, Default)]
struct Recorder {
    uids: Vec<u16>,
    refuse_once: Option<u16>,
}

impl GlobalWaypointDriver for Recorder {
    /// Moves nothing.
    fn stop(&mut self, _c: &mut global_waypoint_driver::Ctx<'_>, _r: StopReason) {}

    fn on_spool_mission(
        &mut self,
        _c: &mut global_waypoint_driver::Ctx<'_>,
        m: &SpoolMission,
    ) -> Result<(), Refused> {
        if let Some(u) = self.refuse_once {
            if m.root.messages.iter().any(|c| c.uid == u) {
                self.refuse_once = None;
                return Err(Refused::Invalid(format!("not now: uid {u}")));
            }
        }
        self.uids.extend(m.root.messages.iter().map(|c| c.uid));
        Ok(())
    }

    /// (Sent raw when the spooling preference and services went unanswered: the
    /// queries are not resent.)
    fn on_set_global_waypoint(
        &mut self,
        _c: &mut global_waypoint_driver::Ctx<'_>,
        m: &SetGlobalWaypoint,
    ) -> Result<(), Refused> {
        self.uids.push(m.waypoint_number);
        Ok(())
    }

    fn on_query_spooling_preference(
        &mut self,
        _c: &mut global_waypoint_driver::Ctx<'_>,
        _q: &QuerySpoolingPreference,
    ) -> Result<ReportSpoolingPreference, Refused> {
        Ok(ReportSpoolingPreference {
            spool_type: SpoolingLimitType::MessageCount,
            data: 1,
        })
    }
}

/// A participant whose outgoing RA 3.3 datagrams matching `drop` are lost (the headers
/// of those lost are kept in `lost`); AS-4 datagrams pass.
struct Lossy<P> {
    inner: P,
    drop: Box<dyn FnMut(&Header) -> bool + Send>,
    lost: Arc<Mutex<Vec<Header>>>,
}

impl<P: std::fmt::Debug> std::fmt::Debug for Lossy<P> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Lossy").field("inner", &self.inner).finish()
    }
}

impl<P: Participant> Participant for Lossy<P> {
    fn handle_datagram(&mut self, now: Instant, peer: SocketAddr, datagram: &[u8]) {
        self.inner.handle_datagram(now, peer, datagram);
    }
    fn handle_via(&mut self, now: Instant, via: Via, peer: SocketAddr, datagram: &[u8]) {
        self.inner.handle_via(now, via, peer, datagram);
    }
    fn handle_timeout(&mut self, now: Instant) {
        self.inner.handle_timeout(now);
    }
    fn poll_transmit(&mut self) -> Option<Datagram<SocketAddr>> {
        loop {
            let d = self.inner.poll_transmit()?;
            if !As4Side::<SocketAddr>::is_as4(&d.bytes) {
                if let Ok((h, _)) = Framing::default().packet(&d.bytes) {
                    if (self.drop)(&h) {
                        self.lost.lock().unwrap().push(h);
                        continue;
                    }
                }
            }
            return Some(d);
        }
    }
    fn recycle(&mut self, bytes: Vec<u8>) {
        self.inner.recycle(bytes);
    }
    fn poll_timeout(&self) -> Option<Instant> {
        self.inner.poll_timeout()
    }
    fn wall_clock(&mut self, now: Instant, utc: Duration) {
        self.inner.wall_clock(now, utc);
    }
    fn as_any(&self) -> &dyn std::any::Any {
        self.inner.as_any()
    }
    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self.inner.as_any_mut()
    }
}

/// Drops the first `n` datagrams `matches` accepts.
fn first(
    mut n: usize,
    matches: impl Fn(&Header) -> bool + Send + 'static,
) -> Box<dyn FnMut(&Header) -> bool + Send> {
    Box::new(move |h| {
        if n > 0 && matches(h) {
            n -= 1;
            return true;
        }
        false
    })
}

fn node_config(node: u8, peer: usize, reliable: Option<RetryPolicy>) -> NodeConfig {
    NodeConfig {
        subsystem: 1,
        node,
        peers: vec![SimNet::addr(peer)],
        reliable,
        ..NodeConfig::default()
    }
}

/// The spooler's node (index 0) and the recorder's (index 1), the recorder's outgoing
/// datagrams passed through `drop`.
struct Mission {
    net: SimNet,
    spooler: usize,
    recorder: usize,
    lost: Arc<Mutex<Vec<Header>>>,
}

impl Mission {
    fn new(
        model: LinkModel,
        seed: u64,
        reliable: Option<RetryPolicy>,
        recorder: Recorder,
        drop: Box<dyn FnMut(&Header) -> bool + Send>,
    ) -> Self {
        let t0 = Instant::now();
        let mut net = SimNet::new(t0, model, seed);
        let mut a = Node::new(node_config(1, 1, reliable), t0);
        let open = Config {
            control: ControlPolicy::Open,
            ..Config::default()
        };
        let spooler = StockMissionSpooler::new(SpoolerConfig::default());
        a.add(mission_spooler::component(MS, spooler, open, t0))
            .unwrap();
        let mut b = Node::new(node_config(2, 0, reliable), t0);
        b.add(global_waypoint_driver::component(
            RECORDER,
            recorder,
            Config::default(),
            t0,
        ))
        .unwrap();
        let lost = Arc::new(Mutex::new(Vec::new()));
        let spooler = net.add(a);
        let recorder = net.add(Lossy {
            inner: b,
            drop,
            lost: lost.clone(),
        });
        Mission {
            net,
            spooler,
            recorder,
            lost,
        }
    }

    /// The owner tells the spooler `msg` (a message local to its node).
    fn tell(&mut self, msg: impl Into<Message>) {
        let m: Message = msg.into();
        let now = self.net.now();
        let body = m.to_bytes().unwrap();
        self.net
            .node_mut(self.spooler)
            .unwrap()
            .send(now, Header::new(m.code(), MS, OWNER), body);
    }

    /// Spools and runs mission 1 of `n` Set Global Waypoint messages for the recorder.
    fn start(&mut self, n: u16) {
        self.net.run_for(Duration::from_secs(2));
        self.tell(Resume {});
        let cmds = (1..=n)
            .map(|uid| {
                let wp = SetGlobalWaypoint {
                    waypoint_number: uid,
                    ..Default::default()
                };
                command(uid, MS, RECORDER, &wp.into(), false).unwrap()
            })
            .collect();
        self.tell(mission_of(1, vec![leaf_task(1, cmds)]));
        self.tell(RunMission { mission_id: 1 });
    }

    fn spooler(&self) -> &StockMissionSpooler {
        &self
            .net
            .node(self.spooler)
            .unwrap()
            .get::<Spooler>(MS)
            .unwrap()
            .behaviour()
            .0
    }

    fn finished(&self) -> bool {
        self.spooler()
            .status(1)
            .is_some_and(|(s, _, _)| s == MissionStatus::Finished)
    }

    fn recorded(&self) -> Vec<u16> {
        self.net
            .node(self.recorder)
            .unwrap()
            .get::<Rec>(RECORDER)
            .unwrap()
            .behaviour()
            .0
            .uids
            .clone()
    }

    /// Runs until the recorder has `n` messages and nothing is left to settle, or `limit`.
    fn run(&mut self, n: usize, limit: Duration) {
        let end = self.net.now() + limit;
        while self.net.now() < end {
            self.net.run_for(Duration::from_millis(200));
            let waiting = self.spooler().delivery_stats();
            let settled =
                waiting.acknowledged + waiting.refused + waiting.unconfirmed >= waiting.tracked;
            if self.finished() && self.recorded().len() >= n && settled {
                // Let late copies arrive: they must change nothing.
                self.net.run_for(Duration::from_secs(3));
                return;
            }
        }
    }

    fn stats(&self) -> (ReliableStats, ReliableStats) {
        (
            self.net.node(self.spooler).unwrap().reliable_stats(),
            self.net.node(self.recorder).unwrap().reliable_stats(),
        )
    }
}

/// 15 % loss, 0.2-40 ms delay (reordering), 5 % duplication.
fn lossy() -> LinkModel {
    LinkModel {
        drop: 0.15,
        duplicate: 0.05,
        min_delay: Duration::from_micros(200),
        max_delay: Duration::from_millis(40),
    }
}

fn each_once(got: &[u16], n: u16) -> bool {
    let mut sorted = got.to_vec();
    sorted.sort_unstable();
    sorted == (1..=n).collect::<Vec<_>>()
}

#[test]
fn a_spooled_mission_over_a_lossy_link_is_carried_out_exactly_once_with_reliable_delivery() {
    const N: u16 = 30;
    for seed in [4, 7, 11] {
        // Without reliable delivery, the same seed loses some of the messages (the
        // mission still "finishes": each message was sent once).
        let mut plain = Mission::new(
            lossy(),
            seed,
            None,
            Recorder::default(),
            first(0, |_| false),
        );
        plain.start(N);
        plain.run(N as usize, Duration::from_secs(20));
        let got = plain.recorded();
        println!("seed {seed} without: {} of {N} carried out", got.len());
        assert!(got.len() < N as usize, "nothing lost without: {got:?}");

        let mut m = Mission::new(
            lossy(),
            seed,
            Some(RetryPolicy::default()),
            Recorder::default(),
            first(0, |_| false),
        );
        m.start(N);
        m.run(N as usize, Duration::from_secs(40));
        let (a, b) = m.stats();
        let d = m.spooler().delivery_stats();
        println!(
            "seed {seed} with: net {:?}; spooler's node {a:?}; recorder's node {b:?}; deliveries {d:?}",
            m.net.stats()
        );
        assert!(m.finished(), "seed {seed}: the mission did not finish");
        let got = m.recorded();
        assert!(
            each_once(&got, N),
            "seed {seed}: each message once: {got:?}"
        );
        assert!(m.net.stats().dropped > 0);
        // Deliveries were lost and sent again; every one was acknowledged. (A message
        // sent before the recorder's Confirm Component Control came back is refused,
        // control asked for again and the message sent again: not a pause.)
        assert!(a.retried > 0, "{a:?}");
        assert_eq!(d.acknowledged, u64::from(N), "{d:?}");
        assert_eq!(d.tracked, d.acknowledged + d.refused, "{d:?}");
        assert_eq!(d.refused, d.resent_refused, "{d:?}");
        assert_eq!((d.given_up, d.paused), (0, 0), "{d:?}");
    }
}

#[test]
fn a_delivery_whose_acknowledgement_is_lost_is_sent_again_and_carried_out_once() {
    const N: u16 = 5;
    // The recorder's first two acknowledgements of a Spool Mission are lost.
    let drop = first(2, |h| {
        h.ack_nak == AckNak::Ack && h.command_code == SpoolMission::CODE
    });
    let mut m = Mission::new(
        LinkModel::default(),
        1,
        Some(RetryPolicy::default()),
        Recorder::default(),
        drop,
    );
    m.start(N);
    m.run(N as usize, Duration::from_secs(15));
    let (a, b) = m.stats();
    assert_eq!(m.lost.lock().unwrap().len(), 2);
    assert!(m.finished());
    let got = m.recorded();
    assert!(each_once(&got, N), "carried out once each: {got:?}");
    // The lost answers' commands went again; the recorder's node dropped the copies
    // and answered them again.
    assert!(a.retried >= 2, "{a:?}");
    assert!(
        b.duplicates_dropped >= 2 && b.answers_repeated >= 2,
        "{b:?}"
    );
    let d = m.spooler().delivery_stats();
    assert_eq!((d.tracked, d.acknowledged), (5, 5), "{d:?}");
}

#[test]
fn a_refused_delivery_pauses_the_mission_with_its_reason_and_resume_sends_it_again() {
    const N: u16 = 4;
    let recorder = Recorder {
        refuse_once: Some(3),
        ..Recorder::default()
    };
    let mut m = Mission::new(
        LinkModel::default(),
        1,
        Some(RetryPolicy::default()),
        recorder,
        first(0, |_| false),
    );
    m.start(N);
    m.net.run_for(Duration::from_secs(4));
    let s = m.spooler();
    let reason = s.pause_reason(1).expect("paused with a reason").to_string();
    assert!(
        reason.contains("refused") && reason.contains("[3]") && reason.contains("1.2.45.1"),
        "{reason}"
    );
    assert_eq!(s.status(1).unwrap().0, MissionStatus::Paused);
    assert_eq!(s.delivery_stats().refused, 1);
    // Uid 3 was not carried out; 4 was, as it went before the refusal came back.
    assert_eq!(m.recorded(), vec![1, 2, 4]);
    m.tell(ResumeMission {
        mission_id: 1,
        task_id: 0,
    });
    m.run(N as usize, Duration::from_secs(10));
    assert!(m.finished());
    assert_eq!(m.recorded(), vec![1, 2, 4, 3]);
    assert!(m.spooler().pause_reason(1).is_none());
}

// ---- The AS-4 gateway ----------------------------------------------------------------

const AS4_ME: As4Id = As4Id::new(42, 1, 1);
const AS4_VEHICLE: As4Id = As4Id::new(1, 1, 1);
const GATEWAY: Address = Address::new(1, 2, 60, 1);

struct Gw {
    net: SimNet,
    dual: usize,
    client: usize,
    lost: Arc<Mutex<Vec<Header>>>,
}

impl Gw {
    /// The demo's vehicle on node 1.1; the gateway on node 1.2 presenting it, its
    /// first Request Component Control and first Set Local Waypoint lost.
    fn new(reliable: Option<RetryPolicy>) -> Self {
        use jaus_as4::gateway::{DualNode, GatewayConfig};
        let t0 = Instant::now();
        let mut net = SimNet::new(t0, LinkModel::default(), 3);
        let vehicle = jaus_sim::demo::vehicle_node(t0, node_config(1, 1, None), 1, 1).unwrap();
        net.add(vehicle);
        let node = Node::new(node_config(2, 0, reliable), t0);
        let config = GatewayConfig::new(AS4_VEHICLE, GATEWAY, 1, "vehicle");
        let lost = Arc::new(Mutex::new(Vec::new()));
        let mut control: u32 = 1;
        let mut waypoint: u32 = 1;
        let drop = Box::new(move |h: &Header| {
            if h.ack_nak != AckNak::Request && h.ack_nak != AckNak::None {
                return false;
            }
            let n = if h.command_code == RequestComponentControl::CODE {
                &mut control
            } else if h.command_code == SetLocalWaypoint::CODE {
                &mut waypoint
            } else {
                return false;
            };
            let drop = *n > 0;
            *n = n.saturating_sub(1);
            drop
        });
        let dual = net.add(Lossy {
            inner: DualNode::new(node, config).unwrap(),
            drop,
            lost: lost.clone(),
        });
        let client = net.add(As4Client::<SocketAddr>::default());
        net.run_for(Duration::from_secs(5));
        Gw {
            net,
            dual,
            client,
            lost,
        }
    }

    fn ask(&mut self, m: impl Into<jaus_as4::Message>, wait: Duration) -> Vec<jaus_as4::Message> {
        let m: jaus_as4::Message = m.into();
        let body = m.body().to_bytes().unwrap();
        let to = SimNet::addr(self.dual);
        let c = self.net.get_mut::<As4Client>(self.client).unwrap();
        c.send(
            to,
            &[As4Message::new(m.code().0, AS4_VEHICLE, AS4_ME, body)],
        );
        self.net.run_for(wait);
        let c = self.net.get_mut::<As4Client>(self.client).unwrap();
        c.take()
            .into_iter()
            .map(|(_, a)| {
                jaus_as4::Message::decode(jaus::CommandCode(a.message_id), &a.body).unwrap()
            })
            .collect()
    }

    fn dual(&self) -> &jaus_as4::gateway::DualNode {
        self.net
            .get::<jaus_as4::gateway::DualNode>(self.dual)
            .unwrap()
    }

    /// Takes control, resumes, uploads one waypoint 3 m ahead and executes it; the
    /// active element followed until the list ends (or 30 s).
    fn drive(&mut self) -> Vec<u16> {
        use jaus_as4::{Element, ExecuteList, QueryActiveElement, RequestControl, SetElement};
        let a = self.ask(
            RequestControl { authority_code: 10 },
            Duration::from_secs(1),
        );
        assert!(
            matches!(a.first(), Some(jaus_as4::Message::ConfirmControl(_))),
            "{a:?}"
        );
        let a = self.ask(jaus_as4::Resume {}, Duration::from_secs(1));
        assert!(a.is_empty(), "{a:?}");
        let wp: jaus_as4::Message = jaus_as4::SetLocalWaypoint {
            x: 3.0,
            y: 0.0,
            waypoint_tolerance: Some(0.5),
            ..Default::default()
        }
        .into();
        let a = self.ask(
            SetElement {
                request_id: 1,
                elements: vec![Element::holding(1, 0, 0, &wp).unwrap()],
            },
            Duration::from_millis(500),
        );
        assert!(
            matches!(a.first(), Some(jaus_as4::Message::ConfirmElementRequest(_))),
            "{a:?}"
        );
        let _ = self.ask(
            ExecuteList {
                speed: 1.0,
                element_uid: Some(1),
            },
            Duration::from_millis(500),
        );
        let mut active = Vec::new();
        for _ in 0..60 {
            for m in self.ask(QueryActiveElement {}, Duration::from_millis(500)) {
                if let jaus_as4::Message::ReportActiveElement(a) = m {
                    active.push(a.element_uid);
                }
            }
            if active.last() == Some(&0) {
                break;
            }
        }
        active
    }
}

#[test]
fn the_gateways_control_request_and_waypoint_upload_lost_once_are_sent_again_and_acknowledged() {
    use jaus_as4::gateway::ra33::Ra33Control;
    let mut g = Gw::new(Some(RetryPolicy::default()));
    let active = g.drive();
    let lost = g.lost.lock().unwrap().clone();
    let dual = g.dual();
    let side = dual.gateway().node().env();
    let (r, s) = (dual.node().reliable_stats(), side.stats());
    println!("lost {lost:?}\nnode {r:?}\ngateway {s:?}\nactive {active:?}");
    assert_eq!(lost.len(), 2, "{lost:?}");
    let driver = lost
        .iter()
        .find(|h| h.command_code == RequestComponentControl::CODE)
        .expect("a control request was lost")
        .destination;
    assert!(lost
        .iter()
        .any(|h| h.command_code == SetLocalWaypoint::CODE));
    // Both went again and were acknowledged; control of that driver was had, and the
    // list ran to its end.
    assert_eq!(side.control_of(driver), Ra33Control::Granted);
    assert!(r.retried >= 2, "{r:?}");
    assert!(
        s.acknowledged > 2 && s.given_up == 0 && s.refused == 0,
        "{s:?}"
    );
    assert_eq!(
        active.last(),
        Some(&0),
        "the list did not finish: {active:?}"
    );
    assert!(active.contains(&1), "{active:?}");

    // Without reliable delivery the lost control request is never asked again.
    let mut g = Gw::new(None);
    let _ = g.drive();
    let lost = g.lost.lock().unwrap().clone();
    let driver = lost
        .iter()
        .find(|h| h.command_code == RequestComponentControl::CODE)
        .expect("a control request was lost")
        .destination;
    let side = g.dual().gateway().node().env();
    assert_ne!(side.control_of(driver), Ra33Control::Granted);
    assert_eq!(side.stats().acknowledged, 0);
}

#[test]
fn a_set_point_stream_goes_once_while_the_commands_beside_it_are_tracked() {
    use jaus::component::Outgoing;
    let t0 = Instant::now();
    let me = Address::new(1, 1, 60, 1);
    let driver = Address::new(1, 2, 33, 1);
    let mut node: Node = Node::new(node_config(1, 1, Some(RetryPolicy::default())), t0);
    node.add_companion(me).unwrap();
    for code in jaus_as4::ra33::STREAMED {
        assert!(node.send_once(me, *code));
    }
    let out = |m: Message| Outgoing {
        header: Header::new(m.code(), driver, me),
        name: m.name(),
        body: m.to_bytes(),
    };
    node.handle_companion(t0, out(SetWrenchEffort::default().into()));
    node.handle_companion(t0, out(Resume {}.into()));
    let mut sent = Vec::new();
    while let Some(d) = node.poll_transmit() {
        if let Ok((h, _)) = Framing::default().packet(&d.bytes) {
            if h.destination == driver {
                sent.push((h.command_code, h.ack_nak));
            }
        }
    }
    assert_eq!(
        sent,
        [
            (SetWrenchEffort::CODE, AckNak::None),
            (Resume::CODE, AckNak::Request)
        ]
    );
    assert_eq!(node.reliable_stats().tracked, 1);
}
