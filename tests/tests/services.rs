//! A generated AS-4 service at work: the access-control fixture of jaus-gen
//! (`jaus-gen/tests/services/access/`, JSIDL written for these tests: exclusive control
//! by rank, preemption, release, lapse) imported and generated (kept up to date by
//! jaus-gen's `services` test), its guards and actions implemented here, and its state
//! machine driven over the simulated network (SimNet) by two clients: request →
//! granted, rank too low → refused, preemption → the old controller told and the new one
//! granted, release → free, lapse (an internal event raised by the service's own
//! timer) → free. The messages travel in a minimal test framing (a 16-bit code, then the
//! body): the AS5669A transport had not landed when this was written.

use std::collections::VecDeque;
use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::net::{Datagram, Participant, Via};
use jaus_sim::network::{LinkModel, SimNet};

#[allow(unused, clippy::match_single_binding)]
mod access {
    include!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../jaus-gen/tests/services/access.messages.rs"
    ));
    pub mod services {
        include!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../jaus-gen/tests/services/access.services.rs"
        ));
    }
}

use access::services::access::{Access, Machines, Trigger};
use access::services::link::{event::Delivered, Link};
use access::services::Arg;
use access::{AnswerControl, AnswerControlVerdict, AskForControl, EndControl, Message};

/// How long a grant lasts without renewal.
const LEASE: Duration = Duration::from_secs(2);

/// The service's guards and actions, recording each action in order.
#[derive(Debug)]
struct Gate {
    own_rank: u8,
    controller: Option<u32>,
    rank: u8,
    now: Instant,
    deadline: Option<Instant>,
    calls: Vec<String>,
    out: Vec<(u32, Message)>,
}

impl Link for Gate {
    fn reply(&mut self, args: &[Arg<'_>]) {
        let mut text = Vec::new();
        let mut to = self.controller;
        for a in args {
            match a {
                Arg::Const(c) => text.push(c.to_string()),
                Arg::LinkDelivered(d) => to = Some(d.from),
            }
        }
        self.calls.push(format!("reply({})", text.join(", ")));
        let msg: Message = match text.first().map(String::as_str) {
            Some("AnswerControl") => AnswerControl {
                verdict: if text.get(1).map(String::as_str) == Some("GRANTED") {
                    AnswerControlVerdict::Granted
                } else {
                    AnswerControlVerdict::RankTooLow
                },
            }
            .into(),
            _ => EndControl {}.into(),
        };
        if let Some(to) = to {
            self.out.push((to, msg));
        }
    }
}

impl Access for Gate {
    fn is_controller(&self, from: &Delivered) -> bool {
        self.controller == Some(from.from)
    }
    fn outranks(&self, msg: &AskForControl) -> bool {
        msg.rank > self.rank
    }
    fn rank_too_low(&self, msg: &AskForControl) -> bool {
        msg.rank < self.own_rank
    }
    fn forget_controller(&mut self) {
        self.calls.push("forget_controller".into());
        self.controller = None;
        self.rank = 0;
    }
    fn remember_controller(&mut self, from: &Delivered) {
        self.calls
            .push(format!("remember_controller({})", from.from));
        self.controller = Some(from.from);
    }
    fn restart_clock(&mut self) {
        self.calls.push("restart_clock".into());
        self.deadline = Some(self.now + LEASE);
    }
    fn stop_clock(&mut self) {
        self.calls.push("stop_clock".into());
        self.deadline = None;
    }
    fn take_rank(&mut self, msg: &AskForControl) {
        self.calls.push(format!("take_rank({})", msg.rank));
        self.rank = msg.rank;
    }
}

/// A client's or the service's id: the last octet of its simulated address.
fn id_of(a: SocketAddr) -> u32 {
    match a {
        SocketAddr::V4(v4) => u32::from(v4.ip().octets()[3]),
        SocketAddr::V6(_) => 0,
    }
}

fn frame(m: &Message) -> Vec<u8> {
    let mut b = m.code().0.to_le_bytes().to_vec();
    b.extend(m.to_bytes().unwrap());
    b
}

fn unframe(bytes: &[u8]) -> Option<Message> {
    let (code, body) = bytes.split_at_checked(2)?;
    let code = u16::from_le_bytes([code[0], code[1]]);
    Message::decode(jaus::CommandCode(code), body).ok()
}

/// The node hosting the service: decodes what arrives, raises the triggers, sends the
/// replies, and raises `Lapsed` when the lease runs out.
#[derive(Debug)]
struct Server {
    gate: Gate,
    machines: Machines,
    peers: Vec<SocketAddr>,
    outbox: VecDeque<Datagram>,
}

impl Server {
    fn flush(&mut self) {
        for (to, m) in self.gate.out.drain(..) {
            if let Some(peer) = self.peers.iter().find(|p| id_of(**p) == to) {
                self.outbox.push_back(Datagram {
                    to: *peer,
                    bytes: frame(&m),
                    via: Via::Network,
                });
            }
        }
    }
}

impl Participant for Server {
    fn handle_datagram(&mut self, now: Instant, peer: SocketAddr, datagram: &[u8]) {
        self.gate.now = now;
        let from = Delivered { from: id_of(peer) };
        match unframe(datagram) {
            Some(Message::AskForControl(msg)) => {
                let t = Trigger::AskForControl {
                    msg: &msg,
                    from: &from,
                };
                self.machines.handle(&mut self.gate, &t);
            }
            Some(Message::GiveUpControl(msg)) => {
                let t = Trigger::GiveUpControl {
                    msg: &msg,
                    from: &from,
                };
                self.machines.handle(&mut self.gate, &t);
            }
            _ => {}
        }
        self.flush();
    }
    fn handle_timeout(&mut self, now: Instant) {
        self.gate.now = now;
        if self.gate.deadline.is_some_and(|d| d <= now) {
            self.gate.deadline = None;
            self.machines.handle(&mut self.gate, &Trigger::Lapsed {});
            self.flush();
        }
    }
    fn poll_transmit(&mut self) -> Option<Datagram> {
        self.outbox.pop_front()
    }
    fn poll_timeout(&self) -> Option<Instant> {
        self.gate.deadline
    }
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}

/// A client: sends what the test queues, keeps what it receives.
#[derive(Debug, Default)]
struct Client {
    server: Option<SocketAddr>,
    outbox: VecDeque<Message>,
    inbox: Vec<Message>,
}

impl Participant for Client {
    fn handle_datagram(&mut self, _: Instant, _: SocketAddr, datagram: &[u8]) {
        self.inbox.extend(unframe(datagram));
    }
    fn handle_timeout(&mut self, _: Instant) {}
    fn poll_transmit(&mut self) -> Option<Datagram> {
        let to = self.server?;
        self.outbox.pop_front().map(|m| Datagram {
            to,
            bytes: frame(&m),
            via: Via::Network,
        })
    }
    fn poll_timeout(&self) -> Option<Instant> {
        None
    }
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn std::any::Any {
        self
    }
}

struct World {
    net: SimNet,
    server: usize,
    low: usize,
    high: usize,
    weak: usize,
}

impl World {
    fn new() -> Self {
        let start = Instant::now();
        let mut net = SimNet::new(start, LinkModel::default(), 7);
        let mut gate = Gate {
            own_rank: 10,
            controller: None,
            rank: 0,
            now: start,
            deadline: None,
            calls: Vec::new(),
            out: Vec::new(),
        };
        let mut machines = Machines::new();
        machines.start(&mut gate);
        let server = net.add(Server {
            gate,
            machines,
            peers: (1..=3).map(SimNet::addr).collect(),
            outbox: VecDeque::new(),
        });
        let mut client = || {
            net.add(Client {
                server: Some(SimNet::addr(server)),
                ..Client::default()
            })
        };
        let (low, high, weak) = (client(), client(), client());
        World {
            net,
            server,
            low,
            high,
            weak,
        }
    }

    fn ask(&mut self, client: usize, rank: u8) {
        let c = self.net.get_mut::<Client>(client).unwrap();
        c.outbox.push_back(AskForControl { rank }.into());
        self.net.run_for(Duration::from_millis(10));
    }

    fn give_up(&mut self, client: usize) {
        let c = self.net.get_mut::<Client>(client).unwrap();
        c.outbox.push_back(access::GiveUpControl {}.into());
        self.net.run_for(Duration::from_millis(10));
    }

    fn server(&mut self) -> &mut Server {
        self.net.get_mut::<Server>(self.server).unwrap()
    }

    fn state(&mut self) -> &'static str {
        self.server().machines.state("InFSM").unwrap()
    }

    fn calls(&mut self) -> Vec<String> {
        std::mem::take(&mut self.server().gate.calls)
    }

    fn inbox(&mut self, client: usize) -> Vec<Message> {
        std::mem::take(&mut self.net.get_mut::<Client>(client).unwrap().inbox)
    }

    fn id(&self, client: usize) -> u32 {
        id_of(SimNet::addr(client))
    }
}

fn granted() -> Message {
    AnswerControl {
        verdict: AnswerControlVerdict::Granted,
    }
    .into()
}

fn too_low() -> Message {
    AnswerControl {
        verdict: AnswerControlVerdict::RankTooLow,
    }
    .into()
}

#[test]
fn the_access_service_walks_its_control_transitions_over_simnet() {
    let mut w = World::new();
    assert_eq!(w.state(), "Listening.Serving.Free");
    assert_eq!(w.calls(), ["forget_controller"]);
    let (low, high, weak) = (w.low, w.high, w.weak);
    let (low_id, high_id) = (w.id(low), w.id(high));

    // Request with enough rank: granted.
    w.ask(low, 50);
    assert_eq!(w.state(), "Listening.Serving.Held");
    assert_eq!(
        w.calls(),
        [
            format!("remember_controller({low_id})"),
            "take_rank(50)".into(),
            "restart_clock".into(),
            "reply(AnswerControl, GRANTED)".into(),
        ]
    );
    assert_eq!(w.inbox(low), [granted()]);

    // Not enough rank to take over (and below the service's own): refused, still held.
    w.ask(weak, 5);
    assert_eq!(w.state(), "Listening.Serving.Held");
    assert_eq!(w.calls(), ["reply(AnswerControl, RANK_TOO_LOW)"]);
    assert_eq!(w.inbox(weak), [too_low()]);
    assert_eq!(w.server().gate.controller, Some(low_id));

    // Preemption by a higher rank: the old controller is told, the new one granted.
    w.ask(high, 90);
    assert_eq!(w.state(), "Listening.Serving.Held");
    assert_eq!(
        w.calls(),
        [
            "reply(EndControl)".to_string(),
            format!("remember_controller({high_id})"),
            "take_rank(90)".into(),
            "restart_clock".into(),
            "reply(AnswerControl, GRANTED)".into(),
        ]
    );
    assert_eq!(w.inbox(low), [EndControl {}.into()]);
    assert_eq!(w.inbox(high), [granted()]);

    // Release by the controller: free again (Held's exit, then the reply, then Free's
    // entry).
    w.give_up(high);
    assert_eq!(w.state(), "Listening.Serving.Free");
    assert_eq!(
        w.calls(),
        ["stop_clock", "reply(EndControl)", "forget_controller"]
    );
    assert_eq!(w.inbox(high), [EndControl {}.into()]);

    // A request when free, below the service's own rank: refused.
    w.ask(weak, 5);
    assert_eq!(w.state(), "Listening.Serving.Free");
    assert_eq!(w.calls(), ["reply(AnswerControl, RANK_TOO_LOW)"]);

    // Granted again, then not renewed: the lease lapses (an internal event).
    w.ask(low, 50);
    assert_eq!(w.state(), "Listening.Serving.Held");
    w.calls();
    w.inbox(low);
    w.net.run_for(LEASE + Duration::from_millis(100));
    assert_eq!(w.state(), "Listening.Serving.Free");
    assert_eq!(
        w.calls(),
        ["stop_clock", "reply(EndControl)", "forget_controller"]
    );
    assert_eq!(w.inbox(low), [EndControl {}.into()]);
}

#[test]
fn a_renewal_by_the_controller_keeps_control() {
    let mut w = World::new();
    w.calls();
    let low = w.low;
    w.ask(low, 50);
    w.net.run_for(LEASE / 2);
    w.calls();
    w.ask(low, 60);
    assert_eq!(
        w.calls(),
        [
            "take_rank(60)",
            "restart_clock",
            "reply(AnswerControl, GRANTED)"
        ]
    );
    // Past the first lease but within the renewed one: still held.
    w.net.run_for(LEASE * 3 / 4);
    assert_eq!(w.state(), "Listening.Serving.Held");
}
