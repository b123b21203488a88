//! Properties: no bytes make the parser panic; every valid message re-encodes byte for
//! byte; a split message comes back whole from any order with duplicates, and never
//! partly when a piece is lost.

use std::time::Instant;

use proptest::prelude::*;

use super::*;

fn packet() -> impl Strategy<Value = As4Packet> {
    (
        proptest::option::of(any::<(u8, u8)>()),
        (0u8..4, 0u8..3, 0u8..4, 0u8..4),
        any::<(u32, u32, u16)>(),
        proptest::collection::vec(any::<u8>(), 2..200),
        any::<bool>(),
    )
        .prop_map(|(hc, (pr, bc, an, dc), (d, s, seq), payload, empty)| {
            let header = As4Header {
                hc: hc.map(|(number, length)| HcRequest { number, length }),
                priority: Priority::from_bits(pr),
                broadcast: Broadcast::from_bits(bc).unwrap_or_default(),
                ack_nak: AckNak::from_bits(an),
                data_control: DataControl::from_bits(dc),
                destination: As4Id::from_u32(d),
                source: As4Id::from_u32(s),
            };
            // Answers and continuation packets may be empty.
            let may_be_empty = header.ack_nak.is_answer()
                || matches!(header.data_control, DataControl::Normal | DataControl::Last);
            let payload = if empty && may_be_empty {
                Vec::new()
            } else {
                payload
            };
            As4Packet {
                header,
                payload,
                sequence: seq,
            }
        })
}

proptest! {
    #[test]
    fn arbitrary_bytes_never_panic(
        mut bytes in proptest::collection::vec(any::<u8>(), 0..300),
        v2 in any::<bool>(),
    ) {
        if v2 && !bytes.is_empty() {
            bytes[0] = VERSION;
        }
        let _ = parse_datagram(&bytes);
        let _ = As4Packet::parse(&bytes, 0, 0);
        let _ = Generation::of(&bytes);
    }

    #[test]
    fn valid_messages_round_trip_byte_for_byte(ps in proptest::collection::vec(packet(), 1..6)) {
        let mut d = vec![VERSION];
        for p in &ps {
            p.write(&mut d).unwrap();
        }
        let back = parse_datagram(&d).unwrap();
        prop_assert_eq!(&back, &ps);
        let mut again = vec![VERSION];
        for p in &back {
            p.write(&mut again).unwrap();
        }
        prop_assert_eq!(again, d);
    }

    #[test]
    fn split_messages_come_back_whole_or_not_at_all(
        len in 2usize..3000,
        max in 2usize..700,
        first in any::<u16>(),
        order in proptest::collection::vec(any::<u16>(), 0..40),
        dups in proptest::collection::vec(any::<u16>(), 0..5),
        lose in proptest::option::of(any::<u16>()),
    ) {
        let h = As4Header::new(As4Id::new(1, 1, 1), As4Id::new(2, 3, 4));
        let m: Vec<u8> = (0..len).map(|i| (i * 7 % 256) as u8).collect();
        let mut ps = split(&h, &m, first, max).unwrap();
        let n = ps.len();
        for (i, k) in order.iter().enumerate() {
            ps.swap(i % n, usize::from(*k) % n);
        }
        // (A single packet is a whole message each time it comes.)
        for k in dups.iter().filter(|_| n > 1) {
            let p = ps[usize::from(*k) % n].clone();
            ps.push(p);
        }
        let lost = lose.filter(|_| n > 1).map(|k| ps[usize::from(k) % n].sequence);
        if let Some(seq) = lost {
            ps.retain(|p| p.sequence != seq);
        }
        let mut r = As4Reassembler::new(As4ReassemblyLimits::default());
        let out: Vec<As4Packet> = ps
            .into_iter()
            .filter_map(|p| r.message(Instant::now(), p))
            .collect();
        if lost.is_some() {
            prop_assert!(out.is_empty());
        } else {
            // Once, unless every piece came twice (a whole resend is a new delivery).
            prop_assert!(!out.is_empty());
            if dups.len() < n {
                prop_assert_eq!(out.len(), 1);
            }
            for o in &out {
                prop_assert_eq!(&o.payload, &m);
                prop_assert_eq!(o.sequence, first);
            }
            if n > 1 && dups.is_empty() {
                prop_assert_eq!(r.buffered(), 0);
            }
        }
    }
}

proptest! {
    #[test]
    fn any_packets_keep_the_reassembler_bounded_and_its_counts_exact(
        ops in proptest::collection::vec(
            (0u8..4, 0u16..3, 0u16..12, 0usize..40, any::<u8>()),
            0..200,
        ),
    ) {
        let limits = As4ReassemblyLimits {
            bytes: crate::net::ReassemblyLimits {
                max_message: 300,
                per_source: 400,
                total: 700,
                ..Default::default()
            },
            max_in_progress: 3,
        };
        let mut r = As4Reassembler::new(limits);
        let t = Instant::now();
        for (dc, src, seq, len, fill) in ops {
            let p = As4Packet {
                header: As4Header {
                    data_control: DataControl::from_bits(dc),
                    ..As4Header::new(As4Id::new(1, 1, 1), As4Id::new(src, 1, 1))
                },
                payload: vec![fill; len.max(2)],
                sequence: seq,
            };
            let _ = r.message(t, p);
            prop_assert!(r.buffered() <= 700);
            prop_assert!(r.in_progress() <= 3);
        }
        r.expire(t + std::time::Duration::from_secs(2));
        prop_assert_eq!((r.buffered(), r.in_progress()), (0, 0));
    }
}
