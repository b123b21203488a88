//! A node's access policy over real UDP, one test per rule: the demo vehicle's node with
//! a policy, and senders on sockets of their own as other subsystems. Each refusal is
//! seen three ways: the sender gets the JAUS answer a refusing component gives (Confirm
//! Component Control with insufficient authority, a NAK), the node counts it (in total
//! and per rule), and it is logged at warn with the sender, the message and the rule.

mod common;

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use common::LogBuffer;
use jaus::codec::{Decode, Encode};
use jaus::messages::{
    ClearEmergency, ClearEmergencyCode, ComponentState, ConfirmComponentControl, ControlResponse,
    EmergencyCode, QueryComponentStatus, RefusalReason, ReportComponentStatus, ReportRefusal,
    RequestComponentControl, SetEmergency, Standby,
};
use jaus::net::policy::{Permission, Policy, Rule};
use jaus::net::{udp, Framing, NetStats, NodeConfig};
use jaus::wire::AckNak;
use jaus::{Address, CommandCode, Header, JausMessage, Packet};

const PD: &str = "1.1.33.1";

/// What the node thread publishes after every event.
#[derive(Debug, Default, Clone)]
struct Seen {
    stats: NetStats,
    per_rule: Vec<u64>,
}

/// The demo vehicle (subsystem 1) on a UDP socket with `policy`, its log captured.
struct Vehicle {
    at: SocketAddr,
    stop: Arc<AtomicBool>,
    seen: Arc<Mutex<Seen>>,
    log: LogBuffer,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Drop for Vehicle {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

fn vehicle(policy: Option<Policy>) -> Vehicle {
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let at = socket.local_addr().unwrap();
    let stop = Arc::new(AtomicBool::new(false));
    let seen = Arc::new(Mutex::new(Seen::default()));
    let log = LogBuffer::default();
    let (s, seen2, buf) = (stop.clone(), seen.clone(), log.clone());
    let thread = std::thread::spawn(move || {
        let _log = buf.capture();
        {
            let config = NodeConfig {
                policy,
                ..NodeConfig::default()
            };
            let mut node = jaus_sim::demo::vehicle_node(Instant::now(), config, 1, 1).unwrap();
            udp::run_on(&mut node, &socket, &s, None, |n| {
                let mut seen = seen2.lock().unwrap();
                seen.stats = n.stats();
                seen.per_rule = n.policy().map(|p| p.counts().to_vec()).unwrap_or_default();
            })
            .unwrap();
        }
    });
    Vehicle {
        at,
        stop,
        seen,
        log,
        thread: Some(thread),
    }
}

impl Vehicle {
    fn seen(&self) -> Seen {
        // The node publishes after every event; give it one.
        std::thread::sleep(Duration::from_millis(150));
        self.seen.lock().unwrap().clone()
    }

    fn log(&self) -> String {
        self.log.text()
    }
}

/// A sender: its own socket, as `me`.
struct Sender {
    socket: UdpSocket,
    me: Address,
    to: SocketAddr,
}

impl Sender {
    fn new(me: &str, v: &Vehicle) -> Self {
        let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
        socket
            .set_read_timeout(Some(Duration::from_millis(100)))
            .unwrap();
        Self {
            socket,
            me: me.parse().unwrap(),
            to: v.at,
        }
    }

    fn send<M: JausMessage + Encode>(&self, to: &str, msg: &M, ack: bool) {
        let mut h = Header::new(M::CODE, to.parse().unwrap(), self.me);
        if ack {
            h.ack_nak = AckNak::Request;
        }
        let bytes = Packet::new(h, msg.to_bytes().unwrap()).to_bytes().unwrap();
        self.socket
            .send_to(&Framing::Judp.encode(&bytes), self.to)
            .unwrap();
    }

    /// Everything addressed to this sender within `wait`, as (header, body).
    fn received(&self, wait: Duration) -> Vec<(Header, Vec<u8>)> {
        let until = Instant::now() + wait;
        let mut out = Vec::new();
        let mut buf = [0u8; 65536];
        while Instant::now() < until {
            if let Ok((n, _)) = self.socket.recv_from(&mut buf) {
                if let Ok((h, b)) = Framing::Judp.packet(&buf[..n]) {
                    if h.destination == self.me {
                        out.push((h, b.to_vec()));
                    }
                }
            }
        }
        out
    }

    /// The first message with `code` within 2 s.
    fn answer(&self, code: CommandCode) -> Option<(Header, Vec<u8>)> {
        let until = Instant::now() + Duration::from_secs(2);
        while Instant::now() < until {
            if let Some(m) = self
                .received(Duration::from_millis(100))
                .into_iter()
                .find(|(h, _)| h.command_code == code)
            {
                return Some(m);
            }
        }
        None
    }

    fn control(&self, authority: u8) -> ControlResponse {
        self.send(
            PD,
            &RequestComponentControl {
                authority_code: authority,
            },
            false,
        );
        let (h, b) = self
            .answer(ConfirmComponentControl::CODE)
            .expect("a Confirm Component Control");
        assert_eq!(h.source, PD.parse().unwrap());
        ConfirmComponentControl::from_bytes(&b)
            .unwrap()
            .response_code
    }

    fn status(&self) -> Option<ComponentState> {
        self.send(PD, &QueryComponentStatus {}, false);
        self.answer(ReportComponentStatus::CODE).map(|(_, b)| {
            ReportComponentStatus::from_bytes(&b)
                .unwrap()
                .primary_status_code
        })
    }

    /// Sends `msg` asking for an acknowledgement; whether it was ACKed (true) or NAKed.
    fn acked<M: JausMessage + Encode>(&self, msg: &M) -> bool {
        self.send(PD, msg, true);
        let (h, _) = self.answer(M::CODE).expect("an ACK or NAK");
        assert_ne!(h.ack_nak, AckNak::Request);
        h.ack_nak == AckNak::Ack
    }
}

fn policy() -> Policy {
    Policy {
        rules: vec![
            Rule {
                from: "200.*.*.*".parse().unwrap(),
                may: Permission::Command { max_authority: 100 },
                emergency: true,
            },
            Rule {
                from: "42.1.*.*".parse().unwrap(),
                may: Permission::Query,
                emergency: true,
            },
            Rule {
                from: "66.*.*.*".parse().unwrap(),
                may: Permission::None,
                emergency: false,
            },
        ],
        default: Permission::Query,
        default_emergency: true,
    }
}

fn emergency() -> SetEmergency {
    SetEmergency {
        emergency_code: EmergencyCode {
            transition_to_emergency: true,
            ..Default::default()
        },
    }
}

fn clear() -> ClearEmergency {
    ClearEmergency {
        emergency_code: ClearEmergencyCode {
            clear_emergency: true,
            ..Default::default()
        },
    }
}

/// The vehicle's components take a moment to reach Standby/Ready.
fn ready(s: &Sender) {
    let until = Instant::now() + Duration::from_secs(5);
    while !matches!(
        s.status(),
        Some(ComponentState::Ready | ComponentState::Standby)
    ) {
        assert!(Instant::now() < until, "the primitive driver never came up");
    }
}

#[test]
fn a_command_rule_bounds_the_authority_of_control() {
    let v = vehicle(Some(policy()));
    let op = Sender::new("200.1.40.1", &v);
    ready(&op);
    assert_eq!(op.control(150), ControlResponse::InsufficientAuthority);
    let seen = v.seen();
    assert_eq!(seen.stats.policy_refused, 1);
    assert_eq!(seen.per_rule, [1, 0, 0, 0]);
    assert!(
        v.log().contains("refused by the node's policy"),
        "{}",
        v.log()
    );
    assert!(
        v.log().contains("sender=200.1.40.1") && v.log().contains("rule 0 (from 200.*.*.*)"),
        "{}",
        v.log()
    );
    // Within its bound: accepted by the component itself, and then it may command.
    assert_eq!(op.control(100), ControlResponse::ControlAccepted);
    assert!(op.acked(&Standby {}));
    assert_eq!(v.seen().stats.policy_refused, 1);
}

#[test]
fn a_query_rule_answers_queries_refuses_commands_and_lets_emergencies_through() {
    let v = vehicle(Some(policy()));
    let q = Sender::new("42.1.40.1", &v);
    ready(&q);
    // NAKed, and by the policy (counted below): the component never saw it.
    assert!(
        !q.acked(&Standby {}),
        "a command from a query-only sender was ACKed"
    );
    assert_eq!(q.control(1), ControlResponse::InsufficientAuthority);
    // Part 1's safety rule: Set/Clear Emergency from anyone.
    assert!(q.acked(&emergency()));
    assert_eq!(q.status(), Some(ComponentState::Emergency));
    assert!(q.acked(&clear()));
    assert_ne!(q.status(), Some(ComponentState::Emergency));
    let seen = v.seen();
    assert_eq!(seen.stats.policy_refused, 2);
    assert_eq!(seen.per_rule, [0, 2, 0, 0]);
    assert!(v.log().contains("sender=42.1.40.1"), "{}", v.log());
    // (tracing prints the `message` field, the message's name, without its key.)
    assert!(
        v.log().contains("refused by the node's policy: rule 1 (from 42.1.*.*) may query only sender=42.1.40.1 destination=1.1.33.1 Standby code=0x0003"),
        "{}",
        v.log()
    );
}

#[test]
fn a_none_rule_refuses_everything_even_emergencies_when_it_says_so() {
    let v = vehicle(Some(policy()));
    let watcher = Sender::new("42.1.40.2", &v);
    ready(&watcher);
    let x = Sender::new("66.1.40.1", &v);
    // A query that asked for an acknowledgement: NAKed, and no report.
    x.send(PD, &QueryComponentStatus {}, true);
    let got = x.received(Duration::from_secs(1));
    assert!(
        got.iter()
            .any(|(h, _)| h.command_code == QueryComponentStatus::CODE && h.ack_nak == AckNak::Nak),
        "{got:?}"
    );
    assert!(!got
        .iter()
        .any(|(h, _)| h.command_code == ReportComponentStatus::CODE));
    assert!(!x.acked(&emergency()));
    assert_eq!(x.control(255), ControlResponse::InsufficientAuthority);
    assert_ne!(watcher.status(), Some(ComponentState::Emergency));
    let seen = v.seen();
    assert_eq!(seen.per_rule, [0, 0, 3, 0]);
    assert_eq!(seen.stats.policy_refused, 3);
    assert!(
        v.log().contains("emergency messages refused"),
        "{}",
        v.log()
    );
}

#[test]
fn senders_no_rule_names_get_the_default() {
    let v = vehicle(Some(policy()));
    let d = Sender::new("9.1.40.1", &v);
    ready(&d);
    // NAKed, and the reason comes first, in the SDK's Report Refusal.
    d.send(PD, &Standby {}, true);
    let got = d.received(Duration::from_secs(1));
    let codes: Vec<_> = got
        .iter()
        .map(|(h, _)| (h.command_code, h.ack_nak))
        .collect();
    let at = |code, ack| codes.iter().position(|c| *c == (code, ack));
    let report = at(ReportRefusal::CODE, AckNak::None).expect("a Report Refusal");
    let nak = at(Standby::CODE, AckNak::Nak).expect("a NAK");
    assert!(report < nak, "{codes:?}");
    let r = ReportRefusal::from_bytes(&got[report].1).unwrap();
    assert_eq!(
        (r.refused_code, r.reason),
        (Standby::CODE.0, RefusalReason::Policy)
    );
    assert_eq!(
        r.text,
        "refused by the node's policy: the default may query only"
    );
    assert_eq!(v.seen().per_rule, [0, 0, 0, 1]);
    assert!(
        v.log().contains("the default may query only"),
        "{}",
        v.log()
    );
}

#[test]
fn without_a_policy_the_node_is_open() {
    let v = vehicle(None);
    let x = Sender::new("66.1.40.1", &v);
    ready(&x);
    assert_eq!(x.control(255), ControlResponse::ControlAccepted);
    assert!(x.acked(&Standby {}));
    assert_eq!(v.seen().stats.policy_refused, 0);
    assert!(!v.log().contains("policy"));
}

#[test]
fn the_example_node_file_carries_this_policy() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/nodes/policy-vehicle.yaml");
    let file = jaus_node::NodeFile::load(&path).unwrap();
    assert_eq!(file.node_config().policy, Some(policy()));
    let node = file.build_node(&path, Instant::now()).unwrap();
    assert_eq!(node.policy().map(|p| p.policy()), Some(&policy()));
    // A mistake names the file, line and field.
    let bad = std::env::temp_dir().join(format!("jaus-policy-{}.yaml", std::process::id()));
    std::fs::write(
        &bad,
        "subsystem: 1\nnode: 1\nbind: 127.0.0.1:0\npolicy:\n  rules:\n    - { from: 200.*.*.*, may: drive }\n",
    )
    .unwrap();
    let e = jaus_node::NodeFile::load(&bad).unwrap_err();
    assert!(
        e.contains(":6:") && e.contains("`drive` is not a permission"),
        "{e}"
    );
    let _ = std::fs::remove_file(bad);
}
