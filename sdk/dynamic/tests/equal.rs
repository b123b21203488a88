//! The run-time codec against the generated one, on every OpenJAUS 3.3 reference
//! vector of the SDK's 160 messages: the same JSON line, the same bytes back, and the
//! same verdict (decoded or refused) on thousands of damaged bodies.

use jaus::codec::Encode;
use jaus_dynamic::Schema;

fn vectors() -> Vec<String> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tests/data/openjaus33.jsonl"
    );
    let text = std::fs::read_to_string(path).expect("reference vectors");
    text.lines()
        .map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).expect("vector line");
            v["hex"].as_str().expect("hex").to_string()
        })
        .collect()
}

#[test]
fn every_reference_vector_decodes_to_the_same_json_and_encodes_to_the_same_bytes() {
    let schema = Schema::sdk().expect("the SDK's definitions");
    assert_eq!(schema.messages().count(), jaus::messages::MESSAGES.len());
    let vectors = vectors();
    assert!(vectors.len() > 1000, "{} vectors", vectors.len());
    let mut codes = std::collections::BTreeSet::new();
    for hex in &vectors {
        let generated = jaus::json::decode_line(hex).expect("the generated decoder");
        let dynamic = schema
            .decode_line(hex)
            .unwrap_or_else(|e| panic!("{hex}: {e}"));
        assert_eq!(dynamic, generated, "decoded JSON of {hex}");
        let back = schema
            .encode_line(&generated)
            .unwrap_or_else(|e| panic!("{generated}: {e}"));
        assert_eq!(&back, hex, "re-encoded {generated}");
        codes.insert(hex[4..8].to_string());
    }
    // Every message of the SDK has vectors.
    assert!(codes.len() >= 158, "{} codes", codes.len());
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

#[test]
fn damaged_bodies_get_the_same_verdict_and_the_same_json() {
    let schema = Schema::sdk().expect("the SDK's definitions");
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut same_ok, mut same_err) = (0usize, 0usize);
    for hex in vectors() {
        let bytes = jaus::hex::decode(&hex).expect("hex");
        let code = jaus::CommandCode(u16::from_le_bytes([bytes[2], bytes[3]]));
        let body = &bytes[16..];
        for _ in 0..12 {
            let mut b = body.to_vec();
            match rng.below(4) {
                0 if !b.is_empty() => {
                    let i = rng.below(b.len());
                    b[i] = rng.next() as u8;
                }
                1 if !b.is_empty() => b.truncate(rng.below(b.len())),
                2 => b.push(rng.next() as u8),
                _ => {
                    for _ in 0..3 {
                        if !b.is_empty() {
                            let i = rng.below(b.len());
                            b[i] ^= 1 << rng.below(8);
                        }
                    }
                }
            }
            let generated = jaus::messages::Message::decode(code, &b);
            let dynamic = schema.decode(code, &b);
            match (generated, dynamic) {
                (Ok(g), Ok(d)) => {
                    let gj = serde_json::to_value(&g).expect("json");
                    assert_eq!(
                        serde_json::to_value(&d.fields).expect("json"),
                        gj["fields"],
                        "{code} {}",
                        jaus::hex::encode(&b)
                    );
                    // And what decoded encodes to the same bytes on both sides.
                    assert_eq!(
                        schema.encode(&d).ok(),
                        g.to_bytes().ok(),
                        "{code} {}",
                        jaus::hex::encode(&b)
                    );
                    same_ok += 1;
                }
                (Err(g), Err(d)) => {
                    assert_eq!(
                        g.kind(),
                        d.kind(),
                        "{code} {}: {g} / {d}",
                        jaus::hex::encode(&b)
                    );
                    same_err += 1;
                }
                (g, d) => panic!(
                    "{code} {}: generated {:?}, run-time {:?}",
                    jaus::hex::encode(&b),
                    g.map(|_| ()),
                    d.map(|_| ())
                ),
            }
        }
    }
    assert!(same_ok > 3000 && same_err > 3000, "{same_ok} / {same_err}");
}

#[test]
fn json_errors_name_the_field() {
    let schema = Schema::sdk().expect("the SDK's definitions");
    let e = schema
        .from_json("SetTravelSpeed", &serde_json::json!({"sped": 2.0}))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("unknown field `sped`, expected one of speed"),
        "{e}"
    );
    let e = schema
        .from_json("SetTravelSpeed", &serde_json::json!({}))
        .unwrap_err()
        .to_string();
    assert!(e.contains("SetTravelSpeed.speed: missing field"), "{e}");
    let e = schema
        .from_json("SetTravelSpee", &serde_json::json!({}))
        .unwrap_err()
        .to_string();
    assert!(e.contains("did you mean SetTravelSpeed"), "{e}");
    // Beyond the limits: the SDK's own range error, with the unit.
    let m = schema
        .from_json("SetTravelSpeed", &serde_json::json!({"speed": 20000.0}))
        .expect("a number");
    let e = schema.encode(&m).unwrap_err().to_string();
    assert!(
        e.contains("SetTravelSpeed.speed") && e.contains("20000"),
        "{e}"
    );
}
