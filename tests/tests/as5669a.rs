//! AS5669A (JUDP version 2) beside RA 3.3 (issue 32 item 2). Packets are written here
//! byte by byte from the standard's layout (docs/wire.md, "AS5669A"), not by the code
//! under test: version byte 2; then per message the message type / HC flags byte, the
//! data size (u16 LE, header + payload + sequence number), [HC number, HC length], the
//! properties byte (priority bits 0-1, broadcast 2-3, ack/nak 4-5, data control 6-7),
//! destination and source ids (u32 LE: subsystem << 16 | node << 8 | component), the
//! payload (message ID first, LE) and the sequence number (u16 LE).

use std::net::{SocketAddr, UdpSocket};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::messages::{QueryIdentification, QueryLevel};
use jaus::net::as5669a::{
    ack, parse_datagram, split, write_datagrams, AckNak, As4Config, As4Endpoint, As4Error,
    As4Header, As4Id, As4Message, As4Mux, As4Packet, As4Reassembler, As4ReassemblyLimits, As4Stack,
    Broadcast, DataControl, HcRequest, Priority,
};
use jaus::net::{udp, Framing, Node, NodeConfig, Participant, ReassemblyLimits};
use jaus::{Address, Header, JausMessage, Packet};

/// One message as the standard lays it out, written by hand.
#[allow(clippy::too_many_arguments)]
fn message(
    hc: Option<[u8; 2]>,
    props: u8,
    dest: [u8; 4],
    src: [u8; 4],
    payload: &[u8],
    seq: [u8; 2],
) -> Vec<u8> {
    let header = 12 + if hc.is_some() { 2 } else { 0 };
    let size = (header + payload.len() + 2) as u16;
    let mut m = vec![if hc.is_some() { 0b0000_0001 } else { 0 }];
    m.extend_from_slice(&size.to_le_bytes());
    if let Some(hc) = hc {
        m.extend_from_slice(&hc);
    }
    m.push(props);
    m.extend_from_slice(&dest);
    m.extend_from_slice(&src);
    m.extend_from_slice(payload);
    m.extend_from_slice(&seq);
    m
}

fn encode(packets: &[As4Packet]) -> Vec<u8> {
    let mut d = vec![2];
    for p in packets {
        p.write(&mut d).unwrap();
    }
    d
}

#[test]
fn a_hand_built_datagram_parses_to_its_fields_and_re_encodes_byte_for_byte() {
    // Query Identification (0x2B00, query type 2) from 42.1.1 to 300.2.5, priority high,
    // ack requested, sequence number 0x0102.
    let mut d = vec![2];
    d.extend(message(
        None,
        0b00_01_00_10,
        [5, 2, 0x2C, 0x01],
        [1, 1, 42, 0],
        &[0x00, 0x2B, 2],
        [0x02, 0x01],
    ));
    assert_eq!(d.len(), 1 + 17);
    assert_eq!(&d[1..4], &[0, 17, 0], "data size: 12 + 3 + 2");
    let ps = parse_datagram(&d).unwrap();
    assert_eq!(ps.len(), 1);
    let p = &ps[0];
    assert_eq!(p.header.destination, As4Id::new(300, 2, 5));
    assert_eq!(p.header.source, As4Id::new(42, 1, 1));
    assert_eq!(p.header.destination.to_string(), "300.2.5");
    assert_eq!(p.header.priority, Priority::High);
    assert_eq!(p.header.broadcast, Broadcast::None);
    assert_eq!(p.header.ack_nak, AckNak::Request);
    assert_eq!(p.header.data_control, DataControl::Single);
    assert_eq!(p.header.hc, None);
    assert_eq!(p.message_id(), Some(0x2B00));
    assert_eq!(p.payload, [0x00, 0x2B, 2]);
    assert_eq!(p.sequence, 0x0102);
    assert_eq!(encode(&ps), d);
    let m = As4Message::from_packet(p.clone()).unwrap();
    assert_eq!((m.message_id, m.body.as_slice()), (0x2B00, &[2u8][..]));
    assert!(m.ack_requested);
}

#[test]
fn several_messages_in_one_datagram_including_a_header_compression_request() {
    let mut d = vec![2];
    // Global broadcast, safety critical, first packet of a large message.
    d.extend(message(
        None,
        0b01_00_10_11,
        [0xFF, 0xFF, 0xFF, 0xFF],
        [1, 1, 7, 0],
        &[0x02, 0x44, 9, 9, 9],
        [10, 0],
    ));
    // HC flags 1: HC number 4, HC length 12; low priority, normal packet.
    d.extend(message(
        Some([4, 12]),
        0b10_00_00_00,
        [1, 1, 2, 0],
        [1, 1, 7, 0],
        &[8, 8],
        [11, 0],
    ));
    // An ack: no payload.
    d.extend(message(
        None,
        0b00_11_00_01,
        [1, 1, 7, 0],
        [1, 1, 2, 0],
        &[],
        [3, 0],
    ));
    let ps = parse_datagram(&d).unwrap();
    assert_eq!(ps.len(), 3);
    assert_eq!(ps[0].header.broadcast, Broadcast::Global);
    assert_eq!(ps[0].header.priority, Priority::SafetyCritical);
    assert_eq!(ps[0].header.data_control, DataControl::First);
    assert_eq!(ps[0].header.destination, As4Id::new(0xFFFF, 0xFF, 0xFF));
    assert_eq!(ps[0].message_id(), Some(0x4402));
    assert_eq!(
        ps[1].header.hc,
        Some(HcRequest {
            number: 4,
            length: 12
        })
    );
    assert_eq!(ps[1].header.data_control, DataControl::Normal);
    assert_eq!(ps[1].header.priority, Priority::Low);
    assert_eq!(
        (ps[1].payload.as_slice(), ps[1].sequence),
        (&[8u8, 8][..], 11)
    );
    assert_eq!(ps[2].header.ack_nak, AckNak::Ack);
    assert!(ps[2].payload.is_empty());
    assert_eq!(ps[2].message_id(), None);
    assert_eq!(encode(&ps), d);
    // The writer packs the same three into one datagram within a bound, two past it.
    assert_eq!(write_datagrams(&ps, d.len()).unwrap(), vec![d.clone()]);
    assert_eq!(write_datagrams(&ps, d.len() - 1).unwrap().len(), 2);
}

#[test]
fn every_malformed_case_is_a_named_error() {
    let good = message(None, 0, [1, 1, 1, 0], [1, 1, 2, 0], &[0, 0x2B], [0, 0]);
    let with = |f: &dyn Fn(&mut Vec<u8>)| {
        let mut d = vec![2];
        d.extend(good.clone());
        f(&mut d);
        parse_datagram(&d)
    };
    assert!(with(&|_| ()).is_ok());
    assert_eq!(parse_datagram(&[]), Err(As4Error::Empty));
    assert_eq!(parse_datagram(&[2]), Err(As4Error::NoMessage));
    assert_eq!(with(&|d| d[0] = 1), Err(As4Error::Version(1)));
    assert!(matches!(
        with(&|d| d.truncate(8)),
        Err(As4Error::TooShort {
            message: 0,
            at: 1,
            need: 12,
            have: 7
        })
    ));
    // Data size past the end, and below the header.
    assert!(matches!(
        with(&|d| d[2] = 17),
        Err(As4Error::DataSize {
            size: 17,
            have: 16,
            ..
        })
    ));
    assert!(matches!(
        with(&|d| d[2] = 13),
        Err(As4Error::DataSize {
            size: 13,
            min: 14,
            ..
        })
    ));
    assert!(matches!(
        with(&|d| d[1] = 1 << 2),
        Err(As4Error::MessageType { value: 1, .. })
    ));
    assert!(matches!(
        with(&|d| d[4] = 0b0000_1100),
        Err(As4Error::Broadcast { value: 3, .. })
    ));
    for flags in [2, 3] {
        assert!(matches!(
            with(&|d| d[1] = flags),
            Err(As4Error::Compressed { flags: f, .. }) if f == flags
        ));
    }
    // A single message of one payload byte has no message ID.
    let short = message(None, 0, [1, 1, 1, 0], [1, 1, 2, 0], &[0x2B], [0, 0]);
    let mut d = vec![2];
    d.extend(short);
    assert!(matches!(
        parse_datagram(&d),
        Err(As4Error::NoMessageId { len: 1, .. })
    ));
    // A second message cut short names message 1 and where it starts.
    assert!(matches!(
        with(&|d| d.extend_from_slice(&[0, 30, 0])),
        Err(As4Error::TooShort {
            message: 1,
            at: 17,
            ..
        })
    ));
}

fn header() -> As4Header {
    As4Header::new(As4Id::new(1, 1, 1), As4Id::new(2, 1, 1))
}

fn pieces(len: usize, first_seq: u16) -> (Vec<u8>, Vec<As4Packet>) {
    let m: Vec<u8> = (0..len).map(|i| (i * 31 % 251) as u8).collect();
    let ps = split(&header(), &m, first_seq, 1000).unwrap();
    (m, ps)
}

#[test]
fn reassembly_tolerates_reordering_and_duplicates_and_wraps_sequence_numbers() {
    let t = Instant::now();
    let (m, mut ps) = pieces(5500, 65_533);
    assert_eq!(ps.len(), 6);
    assert_eq!(
        ps.iter().map(|p| p.sequence).collect::<Vec<_>>(),
        [65_533, 65_534, 65_535, 0, 1, 2]
    );
    // Last first, the first in the middle, one packet twice.
    ps.reverse();
    ps.swap(2, 5);
    let dup = ps[1].clone();
    ps.insert(3, dup);
    let mut r = As4Reassembler::new(As4ReassemblyLimits::default());
    let mut out = Vec::new();
    for p in ps {
        if let Some(whole) = r.push(t, p) {
            out.push(whole);
        }
    }
    assert_eq!(out.len(), 1);
    assert_eq!(out[0].payload, m);
    assert_eq!(out[0].header.data_control, DataControl::Single);
    assert_eq!(out[0].sequence, 65_533);
    let s = r.stats();
    assert_eq!((s.completed, s.duplicates), (1, 1));
    assert_eq!((r.buffered(), r.in_progress()), (0, 0));
}

#[test]
fn a_lost_packet_delivers_nothing_and_times_out() {
    let t = Instant::now();
    let (_, mut ps) = pieces(5000, 7);
    ps.remove(2);
    let mut r = As4Reassembler::new(As4ReassemblyLimits::default());
    for p in ps {
        assert!(r.push(t, p).is_none(), "never a partial message");
    }
    assert!(r.buffered() > 0);
    assert_eq!(r.next_timeout(), Some(t + Duration::from_secs(2)));
    r.expire(t + Duration::from_secs(2));
    assert_eq!(r.stats().timed_out, 1);
    assert_eq!((r.buffered(), r.in_progress()), (0, 0));
}

#[test]
fn a_message_whose_last_packet_is_lost_does_not_spoil_the_next() {
    let t = Instant::now();
    // Message A: sequence numbers 0, 1, 2 (its last lost); message B: 3, 4, 5, whose
    // middle packet comes before its first.
    let (_, mut a) = pieces(2500, 0);
    let (b_msg, b) = pieces(2500, 3);
    a.pop();
    let mut r = As4Reassembler::new(As4ReassemblyLimits::default());
    for p in a
        .into_iter()
        .chain([b[1].clone(), b[0].clone(), b[2].clone()])
    {
        if let Some(whole) = r.push(t, p) {
            assert_eq!(whole.payload, b_msg);
            assert_eq!(whole.sequence, 3);
        }
    }
    assert_eq!(r.stats().completed, 1);
    assert_eq!(r.in_progress(), 1, "A still waits for its last packet");
}

#[test]
fn reassembly_bounds_are_hit_and_counted() {
    let t = Instant::now();
    let limits = As4ReassemblyLimits {
        bytes: ReassemblyLimits {
            max_message: 3000,
            per_source: 64 * 1024,
            total: 100 * 1024,
            ..Default::default()
        },
        max_in_progress: 4,
    };
    let mut r = As4Reassembler::new(limits);
    // Too large a message: dropped when it passes max_message, never delivered.
    let (_, ps) = pieces(5000, 0);
    for p in ps {
        assert!(r.push(t, p).is_none());
    }
    assert_eq!(r.stats().over_limit, 1);
    // More first packets than messages in progress may be.
    for i in 0..10u16 {
        let mut p = pieces(1500, 100 * i).1.remove(0);
        p.header.source = As4Id::new(10 + i, 1, 1);
        r.push(t, p);
    }
    assert_eq!(r.in_progress(), 4);
    assert_eq!(r.stats().over_limit, 1 + 6);
    // A flood of tiny normal packets from many sources stays within the total.
    for i in 0..20_000u32 {
        let p = As4Packet {
            header: As4Header {
                data_control: DataControl::Normal,
                source: As4Id::new((i % 500) as u16 + 1000, 1, 1),
                ..header()
            },
            payload: vec![0; 10],
            sequence: i as u16,
        };
        r.push(t, p);
        assert!(r.buffered() <= 100 * 1024);
    }
    assert!(r.stats().over_limit > 7);
}

#[test]
fn an_ack_answers_a_packet_that_asks_for_one() {
    let mut h = header();
    h.ack_nak = AckNak::Request;
    h.priority = Priority::SafetyCritical;
    let p = As4Packet {
        header: h,
        payload: vec![0x00, 0x2B, 1],
        sequence: 0xBEEF,
    };
    let a = ack(&p);
    // Built by hand: type 0, size 14, priority 3 | ack 3 << 4, ids swapped, seq kept.
    let mut want = vec![2];
    want.extend(message(
        None,
        0b00_11_00_11,
        [1, 1, 2, 0],
        [1, 1, 1, 0],
        &[],
        [0xEF, 0xBE],
    ));
    assert_eq!(encode(&[a]), want);
    // The stack acknowledges it to the sender and hands the message on.
    let mut stack: As4Stack<u8> = As4Stack::new(As4Config::default());
    let mut d = vec![2];
    p.write(&mut d).unwrap();
    let got = stack.receive(Instant::now(), 7, &d).unwrap();
    assert_eq!(got.len(), 1);
    let sent = stack.poll_transmit().unwrap();
    assert_eq!((sent.to, sent.bytes), (7, want));
    assert_eq!(stack.stats().acks_sent, 1);
}

#[test]
fn without_an_as4_endpoint_a_version_2_datagram_stays_a_framing_error() {
    let t = Instant::now();
    let mut node = Node::new(NodeConfig::default(), t);
    let mut d = vec![2];
    d.extend(message(
        None,
        0,
        [1, 1, 1, 0],
        [1, 1, 2, 0],
        &[0, 0x2B, 1],
        [0, 0],
    ));
    let peer: SocketAddr = "127.0.0.1:9".parse().unwrap();
    node.handle_datagram(t, peer, &d);
    assert_eq!(node.stats().bad_framing, 1);
    assert!(node.poll_transmit().is_none());
    // With one, the same datagram is answered and the node never sees it.
    let mut mux = As4Mux::new(
        Node::new(NodeConfig::default(), t),
        Identify,
        As4Config::default(),
    );
    mux.handle_datagram(t, peer, &d);
    assert_eq!(mux.inner().stats().received, 0);
    let reply = mux.poll_transmit().expect("a Report Identification");
    assert_eq!(reply.to, peer);
    assert_eq!(&reply.bytes[13..15], &[0x00, 0x4B]);
}

/// A small AS-4 endpoint: answers Query Identification (0x2B00) with Report
/// Identification (0x4B00): query type, type 10001 (u16 LE), "AS4" (u8 count).
#[derive(Debug)]
struct Identify;

impl As4Endpoint for Identify {
    fn handle(&mut self, _: Instant, _: SocketAddr, ms: Vec<As4Message>) -> Vec<As4Message> {
        ms.iter()
            .filter(|m| m.message_id == 0x2B00)
            .map(|m| {
                let query_type = m.body.first().copied().unwrap_or(0);
                m.reply(0x4B00, vec![query_type, 0x11, 0x27, 3, b'A', b'S', b'4'])
            })
            .collect()
    }
}

#[test]
fn one_node_socket_answers_an_ra33_peer_and_an_as5669a_peer() {
    let socket = UdpSocket::bind("127.0.0.1:0").unwrap();
    let at = socket.local_addr().unwrap();
    let stop = Arc::new(AtomicBool::new(false));
    let s = stop.clone();
    let host = std::thread::spawn(move || {
        let node = Node::new(NodeConfig::default(), Instant::now());
        let mut mux = As4Mux::new(node, Identify, As4Config::default());
        udp::run_on(&mut mux, &socket, &s, None, |_| {}).unwrap();
        (mux.inner().stats(), mux.stack().stats())
    });

    // The RA 3.3 peer: Query Identification to the node manager 1.1.1.1, as today.
    let ra = UdpSocket::bind("127.0.0.1:0").unwrap();
    ra.set_read_timeout(Some(Duration::from_millis(100)))
        .unwrap();
    let q = QueryIdentification {
        query_field: QueryLevel::Node,
    };
    let h = Header::new(
        QueryIdentification::CODE,
        Address::new(1, 1, 1, 1),
        Address::new(9, 1, 40, 1),
    );
    let ra_query = Framing::Judp.encode(&Packet::new(h, q.to_bytes().unwrap()).to_bytes().unwrap());
    // The AS5669A peer: Query Identification (query type 3) from 42.1.1 to 1.1.1.
    let as4 = UdpSocket::bind("127.0.0.1:0").unwrap();
    as4.set_read_timeout(Some(Duration::from_millis(100)))
        .unwrap();
    let mut as4_query = vec![2];
    as4_query.extend(message(
        None,
        0b00_00_00_01,
        [1, 1, 1, 0],
        [1, 1, 42, 0],
        &[0x00, 0x2B, 3],
        [5, 0],
    ));

    let until = Instant::now() + Duration::from_secs(5);
    let (mut ra_ok, mut as4_ok) = (false, false);
    let mut buf = [0u8; 4096];
    while !(ra_ok && as4_ok) {
        assert!(
            Instant::now() < until,
            "answered: RA 3.3 {ra_ok}, AS5669A {as4_ok}"
        );
        if !ra_ok {
            ra.send_to(&ra_query, at).unwrap();
            if let Ok((n, from)) = ra.recv_from(&mut buf) {
                let answered = Framing::Judp.packet(&buf[..n]).is_ok_and(|(h, _)| {
                    h.command_code.0 == 0x4B00 && h.source == Address::new(1, 1, 1, 1)
                });
                ra_ok = answered && from == at;
            }
        }
        if !as4_ok {
            as4.send_to(&as4_query, at).unwrap();
            if let Ok((n, from)) = as4.recv_from(&mut buf) {
                // Byte by byte: version 2, type 0, size 12 + 9 + 2, standard priority,
                // 42.1.1 ← 1.1.1, Report Identification, query type 3 echoed.
                let want_head = [2, 0, 23, 0, 0b01, 1, 1, 42, 0, 1, 1, 1, 0];
                let d = &buf[..n];
                as4_ok = from == at
                    && n == 24
                    && d[..13] == want_head
                    && d[13..22] == [0x00, 0x4B, 3, 0x11, 0x27, 3, b'A', b'S', b'4'];
            }
        }
    }
    stop.store(true, Ordering::Relaxed);
    let (node_stats, as4_stats) = host.join().unwrap();
    assert_eq!(
        node_stats.bad_framing, 0,
        "no AS5669A datagram reached the node"
    );
    assert!(as4_stats.messages_received >= 1 && as4_stats.messages_sent >= 1);
}
