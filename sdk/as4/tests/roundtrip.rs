//! Every message of the crate encodes and decodes back to itself.
//!
//! Values are built from the definitions (`defs/*.yaml`, loaded with `jaus-spec`) as
//! JSON, which serde turns into the typed [`Message`]: once with every optional field
//! present and every list holding two elements, then for many pseudo-random seeds
//! (optional fields present or not, lists of 0 to 3 elements, values across their
//! ranges). Each case must encode, decode to the same message up to the resolution of
//! its scaled values, and encode again to the same bytes. The generated catalogue and
//! the definitions must list the same messages.

#![cfg(feature = "serde")]

use jaus::codec::Encode;
use jaus_as4::{Message, MESSAGES};
use jaus_spec::{Bits, Field, Int, Len, Spec, TypeForm, Wire};
use serde_json::{json, Map, Value};
use std::path::Path;

fn spec() -> Spec {
    jaus_spec::load_dirs(&[Path::new(env!("CARGO_MANIFEST_DIR")).join("defs")])
        .expect("definitions validate")
}

/// A small deterministic generator (SplitMix64).
struct Gen {
    state: u64,
    /// Every optional field present, every list two elements long.
    full: bool,
}

impl Gen {
    fn next(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n.max(1)
    }

    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn int(&mut self, i: Int) -> Value {
        let v = self.next();
        match i {
            Int::U8 => json!(v as u8),
            Int::U16 => json!(v as u16),
            Int::U32 => json!(v as u32),
            Int::U64 => json!(v),
            Int::I8 => json!(v as i8),
            Int::I16 => json!(v as i16),
            Int::I32 => json!(v as i32),
            Int::I64 => json!(v as i64),
        }
    }

    fn text(&mut self, max: usize) -> Value {
        let n = if self.full {
            max.min(12)
        } else {
            self.below(max as u64 + 1) as usize
        };
        let s: String = (0..n)
            .map(|_| (b' ' + self.below(95) as u8) as char)
            .collect();
        json!(s)
    }

    fn list_len(&mut self) -> usize {
        if self.full {
            2
        } else {
            self.below(4) as usize
        }
    }

    fn wire(&mut self, spec: &Spec, w: &Wire) -> Value {
        match w {
            Wire::Int(i) => self.int(*i),
            Wire::F32 => json!(self.unit() as f32),
            Wire::F64 => json!(self.unit()),
            Wire::Scaled { lo, hi, .. } => json!(lo + (hi - lo) * self.unit()),
            Wire::Str(len) => match len {
                Len::Fixed { n, .. } => self.text(*n),
                _ => self.text(40),
            },
            Wire::Bytes(len) => {
                let n = match len {
                    Len::Fixed { n, .. } => *n,
                    _ => self.list_len() * 3,
                };
                let b: Vec<u8> = (0..n).map(|_| self.next() as u8).collect();
                json!(jaus::hex::encode(&b))
            }
            Wire::List { elem, .. } => {
                let n = self.list_len();
                Value::Array((0..n).map(|_| self.wire(spec, elem)).collect())
            }
            Wire::Named { name, .. } => {
                let ty = spec.ty(name).expect("named type");
                match &ty.form {
                    TypeForm::Record { fields, .. } => self.record(spec, fields),
                    TypeForm::Enum { .. } => {
                        let values = &ty.def.values;
                        // Now and then a value the definition does not name.
                        let i = self.below(values.len() as u64 + 1) as usize;
                        match values.get(i) {
                            Some(v) => json!(v.name),
                            None => {
                                let named: Vec<u64> = values.iter().map(|v| v.value).collect();
                                let n = (0..=255u64).find(|n| !named.contains(n)).unwrap_or(255);
                                json!({ "Unknown": n })
                            }
                        }
                    }
                    TypeForm::Bitfield { members, .. } => {
                        let mut o = Map::new();
                        for b in members {
                            let v = match b.bits {
                                Bits::Flag(_) => json!(self.below(2) == 1),
                                Bits::Range { lo, hi } => json!(self.below(1u64 << (hi - lo + 1))),
                            };
                            o.insert(b.def.name.clone(), v);
                        }
                        Value::Object(o)
                    }
                    TypeForm::Union { variants, .. } => {
                        let v = &variants[self.below(variants.len() as u64) as usize];
                        match &v.wire {
                            Some(w) => json!({ v.def.name.clone(): self.wire(spec, w) }),
                            None => json!(v.def.name),
                        }
                    }
                }
            }
            other => panic!("{other:?} is not used by the AS-4 definitions"),
        }
    }

    fn record(&mut self, spec: &Spec, fields: &[Field]) -> Value {
        let mut o = Map::new();
        for Field { def, wire } in fields {
            if def.bit.is_some() && !self.full && self.below(3) == 0 {
                continue;
            }
            o.insert(def.name.clone(), self.wire(spec, wire));
        }
        Value::Object(o)
    }
}

/// `a` (what was sent) and `b` (what came back) agree up to the resolution of scaled
/// values.
fn close(spec: &Spec, w: &Wire, a: &Value, b: &Value, at: &str) -> Result<(), String> {
    match (w, a, b) {
        (Wire::Scaled { int, lo, hi }, Value::Number(x), Value::Number(y)) => {
            let step = (hi - lo) / int.divisor();
            let (x, y) = (
                x.as_f64().unwrap_or(f64::NAN),
                y.as_f64().unwrap_or(f64::NAN),
            );
            ((x - y).abs() <= step * 0.5 + 1e-9 * x.abs().max(1.0))
                .then_some(())
                .ok_or(format!("{at}: sent {x}, got {y} (step {step:e})"))
        }
        (Wire::List { elem, .. }, Value::Array(x), Value::Array(y)) if x.len() == y.len() => x
            .iter()
            .zip(y)
            .enumerate()
            .try_for_each(|(i, (p, q))| close(spec, elem, p, q, &format!("{at}[{i}]"))),
        (Wire::Named { name, .. }, Value::Object(x), Value::Object(y)) => {
            match spec.ty(name).map(|t| &t.form) {
                Some(TypeForm::Record { fields, .. }) => fields_close(spec, fields, x, y, at),
                Some(TypeForm::Union { variants, .. }) => {
                    let (vn, xv) = x.iter().next().ok_or(format!("{at}: empty union"))?;
                    let yv = y.get(vn).ok_or(format!("{at}: variant {vn} lost"))?;
                    match variants
                        .iter()
                        .find(|v| &v.def.name == vn)
                        .and_then(|v| v.wire.as_ref())
                    {
                        Some(w) => close(spec, w, xv, yv, &format!("{at}.{vn}")),
                        None => Err(format!("{at}: variant {vn} has no value")),
                    }
                }
                _ => (a == b)
                    .then_some(())
                    .ok_or(format!("{at}: sent {a}, got {b}")),
            }
        }
        _ => (a == b)
            .then_some(())
            .ok_or(format!("{at}: sent {a}, got {b}")),
    }
}

fn fields_close(
    spec: &Spec,
    fields: &[Field],
    a: &Map<String, Value>,
    b: &Map<String, Value>,
    at: &str,
) -> Result<(), String> {
    for Field { def, wire } in fields {
        let here = format!("{at}.{}", def.name);
        match (a.get(&def.name), b.get(&def.name)) {
            (Some(x), Some(y)) => close(spec, wire, x, y, &here)?,
            (None, None) => {}
            (x, y) => return Err(format!("{here}: sent {x:?}, got {y:?}")),
        }
    }
    Ok(())
}

/// One case: JSON → message → bytes → message → bytes.
fn round_trip(spec: &Spec, m: &jaus_spec::Message, fields: Value) -> Result<Vec<u8>, String> {
    let name = &m.def.name;
    let input = json!({ "message": name, "fields": fields });
    let msg: Message =
        serde_json::from_value(input.clone()).map_err(|e| format!("JSON → {name}: {e}"))?;
    if msg.code().0 != m.def.code.0 {
        return Err(format!("{name}: code 0x{:04X}", msg.code().0));
    }
    let bytes = msg.to_bytes().map_err(|e| format!("encode {name}: {e}"))?;
    let back = Message::decode(msg.code(), &bytes).map_err(|e| format!("decode {name}: {e}"))?;
    let again = back
        .to_bytes()
        .map_err(|e| format!("re-encode {name}: {e}"))?;
    if again != bytes {
        return Err(format!(
            "{name}: second encoding differs\n {bytes:02X?}\n {again:02X?}"
        ));
    }
    let out = serde_json::to_value(&back).map_err(|e| format!("{name} → JSON: {e}"))?;
    let empty = Map::new();
    fields_close(
        spec,
        &m.fields,
        input["fields"].as_object().unwrap_or(&empty),
        out["fields"].as_object().unwrap_or(&empty),
        name,
    )?;
    Ok(bytes)
}

#[test]
fn the_catalogue_holds_every_defined_message() {
    let spec = spec();
    assert_eq!(MESSAGES.len(), spec.messages.len());
    assert_eq!(
        MESSAGES.len(),
        283,
        "57 Core v1.1 + 46 Mobility + 62 Manipulator v2.0 (their List Manager is the Core's) \
         + 35 Environment Sensing + 47 UGV + 17 Mission Spooling + 19 HMI"
    );
    for m in &spec.messages {
        let info = MESSAGES
            .iter()
            .find(|i| i.code.0 == m.def.code.0)
            .unwrap_or_else(|| panic!("{} missing from MESSAGES", m.def.name));
        assert_eq!(info.name, m.def.name);
        assert_eq!(info.group, "as4");
    }
}

#[test]
fn every_message_with_every_field_round_trips() {
    let spec = spec();
    for (i, m) in spec.messages.iter().enumerate() {
        let mut g = Gen {
            state: i as u64,
            full: true,
        };
        let fields = g.record(&spec, &m.fields);
        let bytes = round_trip(&spec, m, fields).unwrap_or_else(|e| panic!("{e}"));
        // A message with fields has a body: at least one byte per field.
        assert!(
            bytes.len() >= m.fields.len(),
            "{}: {} bytes",
            m.def.name,
            bytes.len()
        );
    }
}

#[test]
fn random_values_of_every_message_round_trip() {
    let spec = spec();
    let mut cases = 0;
    for (i, m) in spec.messages.iter().enumerate() {
        for seed in 0..64u64 {
            let mut g = Gen {
                state: (i as u64) << 32 | seed,
                full: false,
            };
            let fields = g.record(&spec, &m.fields);
            round_trip(&spec, m, fields).unwrap_or_else(|e| panic!("seed {seed}: {e}"));
            cases += 1;
        }
    }
    assert_eq!(cases, 64 * 283);
}

#[test]
fn a_truncated_or_extended_body_is_a_typed_error() {
    let spec = spec();
    for (i, m) in spec
        .messages
        .iter()
        .enumerate()
        .filter(|(_, m)| !m.fields.is_empty())
    {
        let mut g = Gen {
            state: i as u64,
            full: true,
        };
        let fields = g.record(&spec, &m.fields);
        let bytes = round_trip(&spec, m, fields).unwrap_or_else(|e| panic!("{e}"));
        let code = jaus::CommandCode(m.def.code.0);
        for cut in 0..bytes.len() {
            assert!(
                Message::decode(code, &bytes[..cut]).is_err(),
                "{}: {cut} of {} bytes decoded",
                m.def.name,
                bytes.len()
            );
        }
        let mut longer = bytes.clone();
        longer.push(0);
        assert!(
            Message::decode(code, &longer).is_err(),
            "{}: a trailing byte was accepted",
            m.def.name
        );
    }
}
