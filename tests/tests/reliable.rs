//! Commands that arrive (issue 48 item 1), two nodes wired by hand so that the test
//! decides which datagram is lost: a command from the operator's node (reliability on)
//! whose acknowledgement is lost is resent; the vehicle's node carries it out once and
//! repeats the lost acknowledgement; the operator's node learns `Acknowledged` after two
//! copies. A peer that never acknowledges is given up on and then sent to once.

use std::net::SocketAddr;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::component::{Config, Refused};
use jaus::components::global_pose_sensor::{self, Ctx, GlobalPoseSensor};
use jaus::messages::*;
use jaus::net::reliable::{Outcome, RetryPolicy};
use jaus::net::{Node, NodeConfig};
use jaus::wire::AckNak;
use jaus::{Address, Header, JausMessage};

const GPS: Address = Address::new(1, 1, 38, 1);
const OCU: Address = Address::new(1, 2, 40, 1);

struct Gps;
impl GlobalPoseSensor for Gps {
    fn on_query_global_pose(
        &mut self,
        _c: &mut Ctx<'_>,
        _q: &QueryGlobalPose,
    ) -> Result<ReportGlobalPose, Refused> {
        Ok(ReportGlobalPose::default())
    }
}

fn addr(n: u8) -> SocketAddr {
    SocketAddr::from(([10, 0, 0, n], 3794))
}

fn node(n: u8, peer: u8, reliable: bool, t0: Instant) -> Node {
    let config = NodeConfig {
        subsystem: 1,
        node: n,
        peers: vec![addr(peer)],
        reliable: reliable.then(RetryPolicy::default),
        ..NodeConfig::default()
    };
    Node::new(config, t0)
}

/// The JAUS header of a JUDP datagram.
fn header_of(d: &[u8]) -> Header {
    let (h, _) = jaus::net::Framing::Judp.packet(d).unwrap();
    h
}

/// Every datagram `from` has queued, delivered to `to` unless `lose` says so; the
/// headers of those delivered.
fn carry(
    from: &mut Node,
    from_addr: SocketAddr,
    to: &mut Node,
    now: Instant,
    mut lose: impl FnMut(&Header) -> bool,
) -> Vec<Header> {
    let mut seen = Vec::new();
    while let Some(d) = from.poll_transmit() {
        let h = header_of(&d.bytes);
        if !lose(&h) {
            to.handle_datagram(now, from_addr, &d.bytes);
            seen.push(h);
        }
    }
    seen
}

fn request_control(ocu: &mut Node, now: Instant) {
    let msg = RequestComponentControl { authority_code: 10 };
    ocu.send(
        now,
        Header::new(RequestComponentControl::CODE, GPS, OCU),
        msg.to_bytes().unwrap(),
    );
}

#[test]
fn a_command_whose_acknowledgement_is_lost_is_resent_and_carried_out_once() {
    let t0 = Instant::now();
    let mut vehicle = node(1, 2, false, t0);
    vehicle
        .add(global_pose_sensor::component(
            GPS,
            Gps,
            Config::default(),
            t0,
        ))
        .unwrap();
    let mut ocu = node(2, 1, true, t0);
    request_control(&mut ocu, t0);
    // The command leaves asking for an acknowledgement, numbered by the node.
    let sent = carry(&mut ocu, addr(2), &mut vehicle, t0, |_| false);
    let cmd = sent
        .iter()
        .find(|h| h.command_code == RequestComponentControl::CODE)
        .expect("the command went out");
    assert_eq!(cmd.ack_nak, AckNak::Request);
    assert_ne!(cmd.sequence_number, 0);
    // The vehicle acknowledges with the same number; the acknowledgement is lost.
    let back = carry(&mut vehicle, addr(1), &mut ocu, t0, |h| {
        h.ack_nak == AckNak::Ack
    });
    assert!(back.iter().all(|h| h.ack_nak != AckNak::Ack));
    let received_once = vehicle
        .component_stats()
        .find(|(a, _)| *a == GPS)
        .unwrap()
        .1
        .received;
    assert_eq!(ocu.poll_delivery(), None, "nothing settled yet");

    // 200 ms later the command goes again, with the same number.
    let t1 = t0 + Duration::from_millis(200);
    assert!(ocu.poll_timeout().is_some_and(|t| t <= t1));
    ocu.handle_timeout(t1);
    let again = carry(&mut ocu, addr(2), &mut vehicle, t1, |_| false);
    assert!(again
        .iter()
        .any(|h| h.command_code == RequestComponentControl::CODE
            && h.sequence_number == cmd.sequence_number));
    // The vehicle drops it (the component never sees it) and repeats the answer.
    let received_after = vehicle
        .component_stats()
        .find(|(a, _)| *a == GPS)
        .unwrap()
        .1
        .received;
    assert_eq!(received_after, received_once, "carried out once");
    let back = carry(&mut vehicle, addr(1), &mut ocu, t1, |_| false);
    let ack = back
        .iter()
        .find(|h| h.ack_nak == AckNak::Ack)
        .expect("the acknowledgement is repeated");
    assert_eq!(
        (ack.command_code, ack.sequence_number),
        (RequestComponentControl::CODE, cmd.sequence_number)
    );
    assert!(
        back.iter()
            .all(|h| h.command_code != ConfirmComponentControl::CODE),
        "the command was not carried out again: {back:?}"
    );
    let d = ocu.poll_delivery().expect("settled");
    assert_eq!((d.outcome, d.attempts), (Outcome::Acknowledged, 2));
    assert_eq!(
        d.key,
        (GPS, RequestComponentControl::CODE, cmd.sequence_number)
    );
    let (o, v) = (ocu.reliable_stats(), vehicle.reliable_stats());
    // (The node managers' own commands, Confirm Event Request to the vehicle's Create
    // Event, are tracked too; one copy each here.)
    assert_eq!((o.retried, o.acknowledged, o.given_up), (1, 1, 0));
    assert_eq!((v.duplicates_dropped, v.answers_repeated), (1, 1));
    // Nothing left to resend.
    ocu.handle_timeout(t1 + Duration::from_secs(10));
    assert!(carry(&mut ocu, addr(2), &mut vehicle, t1, |_| false)
        .iter()
        .all(|h| h.command_code != RequestComponentControl::CODE));
}

#[test]
fn a_peer_that_never_acknowledges_is_given_up_on_then_sent_to_once() {
    let t0 = Instant::now();
    let mut ocu = node(2, 1, true, t0);
    let mut now = t0;
    let mut copies = Vec::new();
    // Two commands to a component that never answers (every datagram lost).
    for _ in 0..2 {
        request_control(&mut ocu, now);
        let end = now + Duration::from_secs(7);
        loop {
            while let Some(d) = ocu.poll_transmit() {
                if header_of(&d.bytes).command_code == RequestComponentControl::CODE {
                    copies.push(now - t0);
                }
            }
            match ocu.poll_timeout() {
                Some(t) if t <= end => {
                    now = t.max(now);
                    ocu.handle_timeout(now);
                }
                _ => break,
            }
        }
        now = end;
    }
    let outcomes: Vec<Outcome> = std::iter::from_fn(|| ocu.poll_delivery())
        .map(|d| d.outcome)
        .collect();
    assert_eq!(outcomes, [Outcome::GaveUp, Outcome::GaveUp]);
    assert_eq!(copies.len(), 12, "six copies each: {copies:?}");
    assert!(!ocu.acknowledges(GPS));
    // The third goes once, without asking.
    request_control(&mut ocu, now);
    let third: Vec<Header> = std::iter::from_fn(|| ocu.poll_transmit())
        .map(|d| header_of(&d.bytes))
        .filter(|h| h.command_code == RequestComponentControl::CODE)
        .collect();
    assert_eq!(third.len(), 1);
    assert_eq!(third[0].ack_nak, AckNak::None);
    ocu.handle_timeout(now + Duration::from_secs(10));
    assert!(std::iter::from_fn(|| ocu.poll_transmit())
        .all(|d| header_of(&d.bytes).command_code != RequestComponentControl::CODE));
    assert_eq!(ocu.reliable_stats().untracked_peer, 1);
}

/// A sender restarted with the same sequence numbers is not taken for a retransmission
/// when its command differs: the receiver compares the content too.
#[test]
fn the_same_number_with_another_command_is_carried_out() {
    let t0 = Instant::now();
    let mut vehicle = node(1, 2, false, t0);
    vehicle
        .add(global_pose_sensor::component(
            GPS,
            Gps,
            Config::default(),
            t0,
        ))
        .unwrap();
    let datagram = |authority: u8| {
        let body = RequestComponentControl {
            authority_code: authority,
        }
        .to_bytes()
        .unwrap();
        let mut h = Header::new(RequestComponentControl::CODE, GPS, OCU);
        h.ack_nak = AckNak::Request;
        h.sequence_number = 5;
        let mut p = h.encode_with_size(body.len()).unwrap().to_vec();
        p.extend_from_slice(&body);
        jaus::net::Framing::Judp.encode(&p)
    };
    let received = |v: &Node| {
        v.component_stats()
            .find(|(a, _)| *a == GPS)
            .unwrap()
            .1
            .received
    };
    let before = received(&vehicle);
    vehicle.handle_datagram(t0, addr(2), &datagram(10));
    vehicle.handle_datagram(t0, addr(2), &datagram(20));
    assert_eq!(received(&vehicle), before + 2, "two different commands");
    vehicle.handle_datagram(t0, addr(2), &datagram(20));
    assert_eq!(
        received(&vehicle),
        before + 2,
        "a retransmission of the second"
    );
    assert_eq!(vehicle.reliable_stats().duplicates_dropped, 1);
    // Past the window (10 s) the same bytes are a new command.
    vehicle.handle_datagram(t0 + Duration::from_secs(11), addr(2), &datagram(20));
    assert_eq!(received(&vehicle), before + 3);
}

/// The AS-4 side, one mechanism (AS5669A acknowledgements): a reliable stack asks for an
/// acknowledgement of a command, resends it when the acknowledgement is lost; the
/// receiving stack hands it on once and acknowledges it again.
#[test]
fn an_as4_command_whose_acknowledgement_is_lost_is_resent_and_handed_on_once() {
    use jaus::net::as5669a::{As4Config, As4Id, As4Message, As4Stack};
    let t0 = Instant::now();
    let (client_at, vehicle_at) = (addr(1), addr(2));
    let mut client: As4Stack<SocketAddr> = As4Stack::new(As4Config {
        reliable: Some(RetryPolicy::default()),
        ..As4Config::default()
    });
    let mut vehicle: As4Stack<SocketAddr> = As4Stack::new(As4Config::default());
    let (me, car) = (As4Id::new(200, 1, 1), As4Id::new(126, 1, 11));
    // Resume (0x0004) is a command: it asks for an acknowledgement.
    client.send_at(
        t0,
        vehicle_at,
        &[As4Message::new(0x0004, car, me, Vec::new())],
    );
    let first = client.poll_transmit().unwrap();
    let got = vehicle.receive(t0, client_at, &first.bytes).unwrap();
    assert_eq!(got.len(), 1);
    assert!(got[0].ack_requested);
    // The acknowledgement is lost.
    assert!(vehicle.poll_transmit().is_some());
    // 200 ms later the packet goes again, byte for byte.
    let t1 = t0 + Duration::from_millis(200);
    assert_eq!(client.poll_timeout(), Some(t1));
    client.handle_timeout(t1);
    let again = client.poll_transmit().unwrap();
    assert_eq!(again.bytes, first.bytes);
    // Handed on once; acknowledged again.
    assert!(vehicle
        .receive(t1, client_at, &again.bytes)
        .unwrap()
        .is_empty());
    let ack = vehicle.poll_transmit().expect("acknowledged again");
    assert!(client
        .receive(t1, vehicle_at, &ack.bytes)
        .unwrap()
        .is_empty());
    let d = client.poll_delivery().unwrap();
    assert_eq!((d.outcome, d.attempts), (Outcome::Acknowledged, 2));
    assert_eq!((d.key.0, d.key.1), (vehicle_at, car));
    let (c, v) = (client.reliable_stats(), vehicle.reliable_stats());
    assert_eq!((c.tracked, c.retried, c.acknowledged), (1, 1, 1));
    assert_eq!(v.duplicates_dropped, 1);
    // A query (0x2002, Query Status) goes once, unasked.
    client.send_at(
        t1,
        vehicle_at,
        &[As4Message::new(0x2002, car, me, Vec::new())],
    );
    let q = client.poll_transmit().unwrap();
    assert!(!vehicle.receive(t1, client_at, &q.bytes).unwrap()[0].ack_requested);
    assert_eq!(client.reliable_stats().tracked, 1);
}
