//! `Schema::check` (the check-only pass: no values made) accepts exactly what
//! `Schema::decode` accepts and refuses the rest with the same error — kind, offset,
//! message, field path, text — on every OpenJAUS 3.3 reference vector and on every
//! truncation, single-bit flip and a few thousand random damages of them, and on the
//! vendor-rover example's overlay messages.

use jaus::CommandCode;
use jaus_dynamic::Schema;

fn vectors() -> Vec<Vec<u8>> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/data/openjaus33.jsonl"
    );
    let text = std::fs::read_to_string(path).expect("reference vectors");
    text.lines()
        .map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).expect("vector line");
            jaus::hex::decode(v["hex"].as_str().expect("hex")).expect("hex")
        })
        .collect()
}

/// Counts of inputs both passes accepted and both refused.
#[derive(Default)]
struct Tally {
    ok: usize,
    err: usize,
}

impl Tally {
    /// Checks one body both ways.
    fn same(&mut self, schema: &Schema, code: CommandCode, body: &[u8]) {
        let checked = schema.check(code, body);
        let decoded = schema.decode(code, body);
        match (checked, decoded) {
            (Ok(layout), Ok(m)) => {
                assert_eq!((layout.name, layout.code), (m.name, m.code));
                self.ok += 1;
            }
            (Err(c), Err(d)) => {
                assert_eq!(c, d, "{code} {}", jaus::hex::encode(body));
                assert_eq!(c.to_string(), d.to_string());
                assert_eq!((c.field(), c.message()), (d.field(), d.message()));
                self.err += 1;
            }
            (c, d) => panic!(
                "{code} {}: check {:?}, decode {:?}",
                jaus::hex::encode(body),
                c.map(|l| l.name),
                d.map(|m| m.name)
            ),
        }
    }
}

/// A small deterministic generator (no dependency).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Every prefix of `body`, every single-bit flip of its first 48 bytes, a byte
/// appended, and `random` random damages (bytes replaced, bits flipped, bytes cut or
/// inserted, counts made large).
fn damaged(body: &[u8], rng: &mut Rng, random: usize) -> Vec<Vec<u8>> {
    let mut out = vec![body.to_vec()];
    for n in 0..body.len() {
        out.push(body[..n].to_vec());
    }
    for i in 0..body.len().min(48) {
        for bit in 0..8 {
            let mut b = body.to_vec();
            b[i] ^= 1 << bit;
            out.push(b);
        }
    }
    let mut longer = body.to_vec();
    longer.push(0);
    out.push(longer);
    for _ in 0..random {
        let mut b = body.to_vec();
        for _ in 0..1 + rng.below(4) {
            match rng.below(5) {
                0 if !b.is_empty() => {
                    let i = rng.below(b.len());
                    b[i] = rng.next() as u8;
                }
                1 if !b.is_empty() => {
                    let i = rng.below(b.len());
                    b[i] = 0xFF;
                }
                2 if !b.is_empty() => {
                    let i = rng.below(b.len());
                    b.remove(i);
                }
                3 => {
                    let i = rng.below(b.len() + 1);
                    b.insert(i, rng.next() as u8);
                }
                _ if !b.is_empty() => {
                    let i = rng.below(b.len());
                    b[i] ^= 1 << rng.below(8);
                }
                _ => b.push(rng.next() as u8),
            }
        }
        out.push(b);
    }
    out
}

#[test]
fn check_accepts_exactly_what_decode_accepts_with_the_same_errors() {
    let schema = Schema::sdk().expect("the SDK's definitions");
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let mut t = Tally::default();
    let mut codes = std::collections::BTreeSet::new();
    for packet in vectors() {
        let code = CommandCode(u16::from_le_bytes([packet[2], packet[3]]));
        codes.insert(code.0);
        for body in damaged(&packet[16..], &mut rng, 24) {
            t.same(&schema, code, &body);
        }
        // The body under another message's code, and under a code nobody defines.
        let other = CommandCode(code.0 ^ 0x0001);
        t.same(&schema, other, &packet[16..]);
        t.same(&schema, CommandCode(0xFFFF), &packet[16..]);
    }
    assert!(codes.len() >= 158, "{} codes", codes.len());
    // Both verdicts are exercised, many times each.
    assert!(
        t.ok > 20_000 && t.err > 20_000,
        "{} ok / {} refused",
        t.ok,
        t.err
    );
}

#[test]
fn check_agrees_with_decode_on_a_vendor_overlay() {
    let overlay = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/vendor-rover/defs/vendor_rover.yaml"
    );
    let schema = Schema::load(&[overlay]).expect("the vendor-rover overlay");
    let own: Vec<_> = schema.messages().filter(|m| m.own).cloned().collect();
    assert!(!own.is_empty());
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut t = Tally::default();
    for m in &own {
        // Bodies from nothing: random bytes of every length up to 64.
        for len in 0..64 {
            for _ in 0..16 {
                let body: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
                t.same(&schema, m.code, &body);
            }
        }
    }
    assert!(t.err > 1000, "{} ok / {} refused", t.ok, t.err);
}

#[test]
fn check_finds_the_error_decode_finds_deep_in_a_body() {
    let schema = Schema::sdk().expect("the SDK's definitions");
    // The SDK's Report Global Pose, its time stamp cut short: the field is named.
    let (_, hex) = jaus::json::REFERENCE_PACKETS[0];
    let packet = jaus::hex::decode(hex).expect("hex");
    let code = CommandCode(u16::from_le_bytes([packet[2], packet[3]]));
    let body = &packet[16..packet.len() - 2];
    let e = schema.check(code, body).unwrap_err();
    assert_eq!(Some("ReportGlobalPose"), e.message());
    assert_eq!(Some("ReportGlobalPose.time_stamp"), e.field());
    assert_eq!(e, schema.decode(code, body).unwrap_err());
    assert_eq!(
        "ReportGlobalPose",
        schema
            .check(code, &packet[16..])
            .expect("the whole body")
            .name
    );
}
