//! Bad input is normal input: every truncation and over a million random mutations of
//! the reference vectors must decode to `Ok` or a typed error — never a panic — and
//! whatever decodes must re-encode to bytes that decode to the same message.

use jaus::codec::Encode;
use jaus::messages::Message;
use jaus::{CommandCode, Packet};

fn vector_packets() -> Vec<Vec<u8>> {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/openjaus33.jsonl"
    ))
    .unwrap();
    let mut packets: Vec<Vec<u8>> = text
        .lines()
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .map(|v| jaus::hex::decode(v["hex"].as_str().unwrap()).unwrap())
        .collect();
    // The two messages of the set that have no reference vector get seeds of their own.
    packets.extend(extra_seeds().iter().map(|m| {
        let header = jaus::Header::new(
            m.code(),
            jaus::Address::new(1, 2, 3, 4),
            jaus::Address::new(5, 6, 7, 8),
        );
        jaus::Packet::new(header, m.to_bytes().unwrap())
            .to_bytes()
            .unwrap()
    }));
    packets
}

fn extra_seeds() -> Vec<Message> {
    let json = [
        r#"{"message":"SetVksFeatureClassMetadata","fields":{"metadata_option":"Overwrite","feature_class_id":77,"metadata":"buildings, 2 floors"}}"#,
        r#"{"message":"ReportPayloadInterface","fields":{"has_hmi_recommendation":true,"has_hmi_x":true,"has_hmi_y":true,"has_hmi_width":false,"has_hmi_height":false,
            "command_interface_count":0,"information_interface_count":0,
            "command_interfaces":[{"identifier":"flail","type_code":5,"units":3,"blocking":1,"min_value":{"UnsignedShort":0},"default_value":{"UnsignedShort":10},"max_value":{"UnsignedShort":900},"enumeration":"","hmi_recommendation":2,"hmi_x":10,"hmi_y":20}],
            "information_interfaces":[{"identifier":"armed","command_association":1,"type_code":18,"units":0,"min_value":{"Boolean":0},"default_value":{"Boolean":0},"max_value":{"Boolean":1},"enumeration":"off,on","hmi_recommendation":1,"hmi_x":5,"hmi_y":6},
                                      {"identifier":"temp","command_association":0,"type_code":9,"units":7,"min_value":{"LongFloat":-40.0},"default_value":{"LongFloat":20.0},"max_value":{"LongFloat":125.0},"enumeration":"","hmi_recommendation":0,"hmi_x":0,"hmi_y":0}]}}"#,
    ];
    let seeds: Vec<Message> = json
        .iter()
        .map(|j| serde_json::from_str(j).unwrap())
        .collect();
    assert!(matches!(seeds[0], Message::SetVksFeatureClassMetadata(_)));
    assert!(matches!(seeds[1], Message::ReportPayloadInterface(_)));
    seeds
}

/// Decodes a body; if it decodes, checks that it re-encodes, and that encoding is then
/// a fixed point (a second decode/encode gives the same bytes and message). The first
/// encoding may differ from the input only where the input is outside the definition:
/// undefined presence bits are dropped (with what a newer revision appended under them),
/// the two spare integers one count beyond a scaled field's limit re-encode as the limit.
fn check(code: CommandCode, body: &[u8]) -> bool {
    match Message::decode(code, body) {
        Ok(m) => {
            let bytes = m
                .to_bytes()
                .unwrap_or_else(|e| panic!("{} decoded but does not encode: {e}", m.name()));
            let m2 = Message::decode(code, &bytes)
                .unwrap_or_else(|e| panic!("{} re-encoding does not decode: {e}", m.name()));
            let bytes2 = m2.to_bytes().unwrap();
            assert_eq!(bytes2, bytes, "{}: encoding is not a fixed point", m.name());
            // Compared as text: a NaN float (a valid f32/f64 on the wire) is not equal
            // to itself.
            assert_eq!(
                format!("{:?}", Message::decode(code, &bytes2).unwrap()),
                format!("{m2:?}"),
                "{}: decoding is not a fixed point",
                m.name()
            );
            true
        }
        Err(e) => {
            // Errors render (this walks every Display path) and carry a location.
            assert!(!e.to_string().is_empty());
            false
        }
    }
}

/// A small deterministic generator (xorshift64*), so failures reproduce.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

#[test]
fn every_truncation_is_a_typed_error_or_a_message() {
    let mut n = 0;
    for p in vector_packets() {
        for k in 0..p.len() {
            // Whole packet cut short: the header/data-size checks must catch it.
            assert!(Packet::parse(&p[..k]).is_err(), "a cut packet was accepted");
        }
        let code = CommandCode(u16::from_le_bytes([p[2], p[3]]));
        let body = &p[16..];
        for k in 0..body.len() {
            check(code, &body[..k]);
            n += 1;
        }
    }
    assert!(n > 10_000, "{n} truncations");
}

#[test]
fn a_million_random_mutations_never_panic() {
    let packets = vector_packets();
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let (mut ok, mut err) = (0usize, 0usize);
    let per_vector = 1_000_000usize.div_ceil(packets.len());
    for p in &packets {
        let code = CommandCode(u16::from_le_bytes([p[2], p[3]]));
        let body = &p[16..];
        let mut buf = Vec::with_capacity(body.len() + 8);
        for _ in 0..per_vector {
            buf.clear();
            buf.extend_from_slice(body);
            for _ in 0..=rng.below(3) {
                match rng.below(5) {
                    0 if !buf.is_empty() => {
                        let i = rng.below(buf.len());
                        buf[i] ^= 1 << rng.below(8);
                    }
                    1 if !buf.is_empty() => {
                        let i = rng.below(buf.len());
                        buf[i] = rng.next() as u8;
                    }
                    2 => {
                        let i = rng.below(buf.len() + 1);
                        buf.insert(i, rng.next() as u8);
                    }
                    3 if !buf.is_empty() => {
                        let i = rng.below(buf.len());
                        buf.remove(i);
                    }
                    _ if !buf.is_empty() => {
                        // Counts and sizes are usually near the front: hit them harder.
                        let i = rng.below(buf.len().min(4));
                        buf[i] = [0x00, 0xFF, 0x7F, 0x80][rng.below(4)];
                    }
                    _ => {}
                }
            }
            if check(code, &buf) {
                ok += 1;
            } else {
                err += 1;
            }
        }
    }
    println!(
        "mutations: {} decoded, {} rejected with a typed error",
        ok, err
    );
    assert_eq!(
        packets.len(),
        1264 + 2,
        "every message of the set is mutated"
    );
    assert!(ok + err >= 1_000_000);
    assert!(err > 0 && ok > 0);
}

#[test]
fn garbage_packets_are_rejected_not_panicked_on() {
    let mut rng = Rng(42);
    for _ in 0..20_000 {
        let len = rng.below(64);
        let bytes: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
        if let Ok(p) = Packet::parse(&bytes) {
            check(p.header.command_code, &p.body);
        }
    }
}

#[test]
fn a_hostile_task_tree_nesting_is_refused_without_exhausting_the_stack() {
    // Spool Mission: mission id, append flag, then 20 000 tasks each with one child.
    let mut body = vec![1, 0, 0];
    for id in 0..20_000u16 {
        body.extend_from_slice(&id.to_le_bytes());
        body.extend_from_slice(&1u16.to_le_bytes()); // one child
        body.extend_from_slice(&0u32.to_le_bytes()); // its offset
        body.extend_from_slice(&0u16.to_le_bytes()); // no messages
    }
    body.extend_from_slice(&[0, 0, 0, 0, 0, 0]); // a leaf
    let err = Message::decode(CommandCode(0x0E00), &body).unwrap_err();
    assert!(err.to_string().contains("nested deeper than"), "{err}");
    // A tree as deep as allowed still decodes.
    let mut ok = vec![1, 0, 0];
    for id in 0..(jaus::codec::MAX_DEPTH - 1) {
        ok.extend_from_slice(&id.to_le_bytes());
        ok.extend_from_slice(&1u16.to_le_bytes());
        ok.extend_from_slice(&0u32.to_le_bytes());
        ok.extend_from_slice(&0u16.to_le_bytes());
    }
    ok.extend_from_slice(&[0, 0, 0, 0, 0, 0]);
    assert!(Message::decode(CommandCode(0x0E00), &ok).is_ok());
}
