//! `As4Node` over the real AS5669A framing: a client's `As4Stack` and the node's own
//! stack exchange datagrams (encode → handle → decode), as `As4Mux` would, without a
//! socket. Routing by destination, broadcast, messages to another peer's address
//! (preemption, events), bad bodies and the bound on remembered peers.

mod core_common;

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use core_common::*;
use jaus::net::as5669a::{As4Config, As4Endpoint, As4Id, As4Message, As4Stack};
use jaus_as4::component::As4Component;
use jaus_as4::core::CoreConfig;
use jaus_as4::node::As4Node;
use jaus_as4::{
    embedded, ConfirmControl, ControlConfirmation, ControlRejection, CreateEvent, EventType,
    IdentificationType, Message, QueryIdentification, QueryStatus, RejectControl, RequestControl,
};

fn addr(last: u8) -> SocketAddr {
    SocketAddr::from(([10, 0, 0, last], 3794))
}

const NODE: u8 = 1;

/// The node with its own AS5669A stack, as a mux would hold it.
struct Side {
    node: As4Node<(), SocketAddr>,
    stack: As4Stack<SocketAddr>,
}

/// A client at an address with its stack.
struct Client {
    id: As4Id,
    at: SocketAddr,
    stack: As4Stack<SocketAddr>,
}

impl Client {
    fn new(id: As4Id, last: u8) -> Self {
        Self {
            id,
            at: addr(last),
            stack: As4Stack::new(As4Config::default()),
        }
    }

    /// Sends `msg` to `to` through the wire; what the node answered to this client.
    fn ask(
        &mut self,
        side: &mut Side,
        now: Instant,
        to: As4Id,
        msg: impl Into<Message>,
    ) -> Vec<Message> {
        let msg = msg.into();
        let body = embedded::encode(&msg).unwrap()[2..].to_vec();
        self.stack.send(
            addr(NODE),
            &[As4Message::new(msg.code().0, to, self.id, body)],
        );
        while let Some(d) = self.stack.poll_transmit() {
            assert_eq!(d.to, addr(NODE));
            let messages = side.stack.receive(now, self.at, &d.bytes).unwrap();
            let replies = side.node.handle(now, self.at, messages);
            side.stack.send(self.at, &replies);
        }
        self.take(side, now)
    }

    /// The datagrams the node's stack holds for this client, decoded.
    fn take(&mut self, side: &mut Side, now: Instant) -> Vec<Message> {
        let mut got = Vec::new();
        let mut other = Vec::new();
        while let Some(d) = side.stack.poll_transmit() {
            if d.to != self.at {
                other.push(d);
                continue;
            }
            for m in self.stack.receive(now, addr(NODE), &d.bytes).unwrap() {
                assert_eq!(m.destination, self.id);
                let mut payload = m.message_id.to_le_bytes().to_vec();
                payload.extend_from_slice(&m.body);
                got.push(embedded::decode(&payload).unwrap());
            }
        }
        // Keep the others' datagrams for them.
        for d in other {
            side.stack.send(d.to, &side_messages(&d.bytes));
        }
        got
    }
}

/// The messages of a datagram (to queue them again unchanged).
fn side_messages(bytes: &[u8]) -> Vec<As4Message> {
    jaus::net::as5669a::parse_datagram(bytes)
        .unwrap()
        .into_iter()
        .filter_map(As4Message::from_packet)
        .collect()
}

/// Runs the node's timers at `now` as the mux does: its sends go into the stack.
fn timers(side: &mut Side, now: Instant) {
    if side.node.poll_timeout().is_some_and(|t| t <= now) {
        for s in side.node.handle_timeout(now) {
            side.stack.send(s.to, std::slice::from_ref(&s.message));
        }
    }
}

fn side() -> Side {
    let vehicle = As4Component::new(ME, CoreConfig::named("rover")).with_service(Speedo::default());
    let other = As4Component::new(As4Id::new(7, 1, 2), CoreConfig::named("arm"));
    Side {
        node: As4Node::new(())
            .with_component(vehicle)
            .with_component(other),
        stack: As4Stack::new(As4Config::default()),
    }
}

#[test]
fn query_identification_over_the_wire() {
    let t = Instant::now();
    let mut side = side();
    let mut judge = Client::new(As4Id::new(42, 1, 1), 42);
    let got = judge.ask(
        &mut side,
        t,
        ME,
        QueryIdentification {
            query_type: IdentificationType::Subsystem,
        },
    );
    let [Message::ReportIdentification(r)] = &got[..] else {
        panic!("{got:?}");
    };
    assert_eq!(r.identification, "rover");
    assert_eq!(side.node.peer(judge.id), Some(judge.at));
    // Broadcast to every component: both answer.
    let all = As4Id::new(0xFFFF, 0xFF, 0xFF);
    let got = judge.ask(&mut side, t, all, QueryStatus {});
    assert_eq!(got.len(), 2);
    // To a component that is not here: counted.
    assert!(judge
        .ask(&mut side, t, As4Id::new(7, 1, 9), QueryStatus {})
        .is_empty());
    assert_eq!(side.node.stats().no_destination, 1);
    // The node's components know each other.
    let known: Vec<As4Id> = side
        .node
        .component(ME)
        .unwrap()
        .core()
        .discovery()
        .known()
        .map(|(id, _)| id)
        .collect();
    assert_eq!(known, vec![ME, As4Id::new(7, 1, 2)]);
}

#[test]
fn preemption_reaches_the_old_controller_at_its_address() {
    let t = Instant::now();
    let mut side = side();
    let mut a = Client::new(A, 42);
    let mut b = Client::new(B, 43);
    let got = a.ask(&mut side, t, ME, RequestControl { authority_code: 1 });
    assert_eq!(
        got,
        vec![ConfirmControl {
            response_code: ControlConfirmation::ControlAccepted
        }
        .into()]
    );
    let got = b.ask(&mut side, t, ME, RequestControl { authority_code: 5 });
    assert_eq!(
        got,
        vec![ConfirmControl {
            response_code: ControlConfirmation::ControlAccepted
        }
        .into()]
    );
    // The Reject Control for A waits for the timer, due at once.
    assert_eq!(side.node.poll_timeout(), Some(t));
    timers(&mut side, t);
    let got = a.take(&mut side, t);
    assert_eq!(
        got,
        vec![RejectControl {
            response_code: ControlRejection::ControlReleased
        }
        .into()]
    );
    assert_eq!(side.node.component(ME).unwrap().controller(), Some(B));
}

#[test]
fn periodic_event_over_the_wire() {
    let t = Instant::now();
    let mut side = side();
    let mut a = Client::new(A, 42);
    let create = CreateEvent {
        request_id: 1,
        event_type: EventType::Periodic,
        requested_periodic_rate: 10.0,
        query_message: embedded::encode(&QueryStatus {}.into()).unwrap(),
    };
    let got = a.ask(&mut side, t, ME, create);
    assert!(matches!(got[0], Message::ConfirmEventRequest(_)), "{got:?}");
    assert!(matches!(got[1], Message::Event(_)), "{got:?}");
    // One second of timers at the node's own pace: 10 more events.
    let mut now = t;
    let mut events = 0;
    while let Some(due) = side.node.poll_timeout() {
        if due > t + Duration::from_secs(1) {
            break;
        }
        now = now.max(due);
        timers(&mut side, now);
        events += a
            .take(&mut side, now)
            .iter()
            .filter(|m| matches!(m, Message::Event(_)))
            .count();
    }
    assert_eq!(events, 10);
}

#[test]
fn bad_bodies_are_counted_and_peers_bounded() {
    let t = Instant::now();
    let mut side = side();
    side.node.set_max_peers(2);
    // Query Identification needs one byte of body: none sent.
    let bad = As4Message::new(0x2B00, ME, A, vec![]);
    assert!(side.node.handle(t, addr(42), vec![bad]).is_empty());
    assert_eq!(side.node.stats().decode_errors, 1);
    // An unknown message ID is handed on as Raw and counted by the component.
    let raw = As4Message::new(0xEEEE, ME, A, vec![1, 2]);
    assert!(side.node.handle(t, addr(42), vec![raw]).is_empty());
    assert_eq!(side.node.component(ME).unwrap().stats().unknown, 1);
    // Three senders, room for two: the one heard from least recently goes.
    for (id, last) in [(A, 42), (B, 43), (C, 44)] {
        let m = As4Message::new(0x2202, ME, id, vec![]);
        assert_eq!(side.node.handle(t, addr(last), vec![m]).len(), 1);
    }
    assert_eq!(side.node.stats().peers_evicted, 1);
    assert_eq!(side.node.peer(A), None);
    assert_eq!(side.node.peer(C), Some(addr(44)));
}
