//! One function per fuzz target. Network bytes and user input go in; the functions
//! panic only when an invariant of the SDK is broken.

use std::net::{Ipv4Addr, SocketAddr, SocketAddrV4};
use std::time::{Duration, Instant};

use jaus::codec::Encode;
use jaus::messages::Message;
use jaus::net::{Node, NodeConfig, ReassemblyLimits};
use jaus::PacketRef;

/// (a) A packet: header parse, decode by command code; whatever decodes re-encodes to
/// a body that decodes again and encodes to the same bytes (a fixed point; values are
/// not compared directly because NaN payloads are not equal to themselves).
pub fn packet(data: &[u8]) {
    let Ok(p) = PacketRef::parse(data) else {
        return;
    };
    let Ok(m) = Message::decode(p.header.command_code, p.body) else {
        return;
    };
    let Ok(once) = m.to_bytes() else {
        // A received value the encoder refuses would be a codec asymmetry, except
        // for scaled values outside their range, which decoding never produces.
        panic!("{} decoded from {:02x?} does not encode", m.name(), p.body);
    };
    let again = Message::decode(m.code(), &once).unwrap_or_else(|e| {
        panic!(
            "{} re-encoded as {once:02x?} does not decode: {e}",
            m.name()
        )
    });
    let twice = again.to_bytes().expect("a decoded message encodes");
    assert_eq!(once, twice, "{}: encoding is not a fixed point", m.name());
}

/// (b) A line of `jaus encode` / `jaus send`: errors are fine, panics are not; a line
/// that encodes decodes back.
pub fn json(data: &[u8]) {
    let Ok(line) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(hex) = jaus::json::encode_line(line) {
        jaus::json::decode_line(&hex)
            .unwrap_or_else(|e| panic!("`{line}` encoded to {hex}, which does not decode: {e}"));
    }
}

/// (c) A node fed datagrams from several peers at virtual times: the input is a
/// sequence of records `[peer (1), delay ms (1), length (2, LE), bytes]`. The
/// reassembly buffer stays within its bound and the node keeps answering.
pub fn node(data: &[u8]) {
    let t0 = Instant::now();
    let limits = ReassemblyLimits {
        max_message: 64 * 1024,
        per_source: 128 * 1024,
        total: 256 * 1024,
        timeout: Duration::from_millis(500),
    };
    let mut node = Node::new(
        NodeConfig {
            reassembly: limits,
            ..NodeConfig::default()
        },
        t0,
    );
    let mut now = t0;
    let mut rest = data;
    while rest.len() >= 4 {
        let peer = SocketAddr::V4(SocketAddrV4::new(
            Ipv4Addr::new(10, 0, 0, rest[0] % 8),
            3794,
        ));
        now += Duration::from_millis(u64::from(rest[1]));
        let len = usize::from(u16::from_le_bytes([rest[2], rest[3]])).min(rest.len() - 4);
        let datagram = &rest[4..4 + len];
        rest = &rest[4 + len..];
        node.handle_datagram(now, peer, datagram);
        node.handle_timeout(now);
        while node.poll_transmit().is_some() {}
        let (_, buffered) = node.reassembly();
        assert!(
            buffered <= limits.total,
            "reassembly holds {buffered} bytes"
        );
    }
}

/// (e) The YAML loader and validator: errors with positions, never a panic.
pub fn spec_yaml(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let _ = jaus_spec::load_texts(vec![("fuzz.yaml".into(), text.to_string())]);
}
