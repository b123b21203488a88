//! Properties of both framings: every datagram comes back byte for byte however the
//! stream is cut; no bytes make a decoder panic; on a serial line, garbage between
//! packets costs nothing but the garbage, and a damaged packet costs only itself.

use proptest::prelude::*;

use super::jserial::{self, DLE, SOH};
use super::jtcp::JtcpEncoder;
use super::*;

/// A JUDP version-1 datagram: random header bytes, the data size set to the body's.
fn v1() -> impl Strategy<Value = Vec<u8>> {
    (
        any::<[u8; 16]>(),
        proptest::collection::vec(any::<u8>(), 0..300),
    )
        .prop_map(|(mut h, body)| {
            let flags = u16::from_le_bytes([h[12], h[13]]) & 0xF000;
            h[12..14].copy_from_slice(&(flags | body.len() as u16).to_le_bytes());
            let mut d = vec![1, 0, 0];
            d.extend_from_slice(&((16 + body.len()) as u16).to_be_bytes());
            d.extend_from_slice(&h);
            d.extend_from_slice(&body);
            d
        })
}

/// One AS5669A message: random fields, with or without header compression, the data
/// size right.
fn v2_message() -> impl Strategy<Value = Vec<u8>> {
    (
        any::<bool>(),
        any::<[u8; 11]>(),
        proptest::collection::vec(any::<u8>(), 0..300),
    )
        .prop_map(|(hc, fields, payload)| {
            let extra = if hc { 2 } else { 0 };
            let size = 14 + extra + payload.len();
            let mut m = vec![u8::from(hc)];
            m.extend_from_slice(&(size as u16).to_le_bytes());
            m.extend_from_slice(&fields[..9 + extra]);
            m.extend_from_slice(&payload);
            m.extend_from_slice(&fields[9..11]);
            m
        })
}

fn v2() -> impl Strategy<Value = Vec<u8>> {
    v2_message().prop_map(|m| {
        let mut d = vec![2];
        d.extend_from_slice(&m);
        d
    })
}

fn datagrams() -> impl Strategy<Value = Vec<Vec<u8>>> {
    prop_oneof![
        proptest::collection::vec(v1(), 1..6),
        proptest::collection::vec(v2(), 1..6),
    ]
}

/// Feeds `wire` in pieces cut at `cuts` (positions, any order).
fn pieces(wire: &[u8], cuts: &[usize]) -> Vec<Vec<u8>> {
    let mut at: Vec<usize> = cuts.iter().map(|c| c % (wire.len() + 1)).collect();
    at.push(0);
    at.push(wire.len());
    at.sort_unstable();
    at.windows(2).map(|w| wire[w[0]..w[1]].to_vec()).collect()
}

proptest! {
    #[test]
    fn jtcp_round_trips_however_the_stream_is_cut(
        ds in datagrams(),
        cuts in proptest::collection::vec(any::<usize>(), 0..20),
    ) {
        let mut e = JtcpEncoder::default();
        let mut wire = Vec::new();
        for d in &ds {
            e.encode(d, &mut wire).unwrap();
        }
        let mut dec = JtcpDecoder::default();
        let mut got = Vec::new();
        for p in pieces(&wire, &cuts) {
            dec.decode(&p, |g| got.push(g.to_vec())).unwrap();
        }
        prop_assert_eq!(&got, &ds);
        prop_assert_eq!(dec.pending(), 0);
    }

    #[test]
    fn jserial_round_trips_however_the_line_is_cut(
        ds in datagrams(),
        cuts in proptest::collection::vec(any::<usize>(), 0..20),
    ) {
        let mut wire = Vec::new();
        for d in &ds {
            jserial::encode_into(d, &mut wire).unwrap();
        }
        let mut dec = JSerialDecoder::default();
        let mut got = Vec::new();
        for p in pieces(&wire, &cuts) {
            dec.decode(&p, |g| got.push(g.to_vec()));
        }
        prop_assert_eq!(&got, &ds);
        prop_assert_eq!(dec.stats().bytes_skipped, 0);
    }

    /// Garbage (any bytes but a DLE SOH) between packets: every packet still comes,
    /// and exactly the garbage is skipped.
    #[test]
    fn jserial_resyncs_after_garbage_between_packets(
        ds in proptest::collection::vec(prop_oneof![v1(), v2()], 1..5),
        garbage in proptest::collection::vec(proptest::collection::vec(any::<u8>(), 0..40), 5),
    ) {
        let mut wire = Vec::new();
        let mut skipped = 0;
        for (i, d) in ds.iter().enumerate() {
            // No DLE at all in the garbage: a lone DLE would pair with the packet's.
            let g: Vec<u8> = garbage[i].iter().map(|b| if *b == DLE { 0x55 } else { *b }).collect();
            skipped += g.len();
            wire.extend_from_slice(&g);
            jserial::encode_into(d, &mut wire).unwrap();
        }
        let mut dec = JSerialDecoder::default();
        let mut got = Vec::new();
        dec.decode(&wire, |g| got.push(g.to_vec()));
        prop_assert_eq!(&got, &ds);
        prop_assert_eq!(dec.stats().bytes_skipped as usize, skipped);
    }

    /// A packet damaged anywhere (a byte lost, changed or added) is lost alone: the
    /// packets after it come.
    #[test]
    fn jserial_loses_only_the_damaged_packet(
        a in prop_oneof![v1(), v2()],
        b in prop_oneof![v1(), v2()],
        at in any::<usize>(),
        how in 0u8..3,
        byte in any::<u8>(),
    ) {
        let mut first = jserial::encode(&a).unwrap();
        // Not the leading DLE SOH: damage there is just garbage before the next one.
        let i = 2 + at % (first.len() - 2);
        match how {
            0 => { first.remove(i); }
            1 => first[i] ^= byte | 1,
            _ => first.insert(i, byte),
        }
        let mut wire = first;
        jserial::encode_into(&b, &mut wire).unwrap();
        let mut dec = JSerialDecoder::default();
        let mut got = Vec::new();
        dec.decode(&wire, |g| got.push(g.to_vec()));
        // The damaged one is normally lost (its checksums match only by a 1 in 65,536
        // chance); the next one always comes.
        prop_assert_eq!(got.last(), Some(&b));
        prop_assert!(got.len() <= 2);
    }

    #[test]
    fn no_bytes_make_a_decoder_panic(
        bytes in proptest::collection::vec(any::<u8>(), 0..2000),
        serial_prefix in any::<bool>(),
    ) {
        let mut line = if serial_prefix { vec![DLE, SOH, 1] } else { Vec::new() };
        line.extend_from_slice(&bytes);
        let mut s = JSerialDecoder::new(512);
        s.decode(&line, |g| assert!(!g.is_empty()));
        prop_assert_eq!(s.stats().bytes as usize, line.len());
        let mut t = JtcpDecoder::new(512);
        let _ = t.decode(&bytes, |g| assert!(!g.is_empty()));
        prop_assert!(t.pending() <= 512);
    }
}
