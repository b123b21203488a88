//! Property test: random values of every message round-trip through encode/decode.
//!
//! Strategies are built from the YAML definitions (one general mechanism, no
//! per-message code): each message gets random field values as JSON, which serde turns
//! into the typed message. Then `encode → decode` must give the same message up to the
//! resolution of scaled fields, and a second `encode` must give identical bytes. And a
//! scaled value beyond its limits, anywhere in a message, is a typed encode error that
//! names it, until the message is clamped.

use jaus::codec::{Encode, EncodeError};
use jaus::messages::Message;
use jaus_spec::{Field, Spec, TypeForm, TypeKind, Wire};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestCaseError, TestRunner};
use serde_json::{json, Map, Value};

#[path = "common/values.rs"]
mod values;
use values::record_strategy;

/// `a` (what was asked) and `b` (what came back) agree up to scaling resolution.
fn close(spec: &Spec, w: &Wire, a: &Value, b: &Value, at: &str) -> Result<(), String> {
    match (w, a, b) {
        (Wire::Scaled { int, lo, hi }, Value::Number(x), Value::Number(y)) => {
            let d = int.divisor();
            let step = (hi - lo) / d;
            let want = x.as_f64().unwrap();
            let got = y.as_f64().unwrap();
            if (want - got).abs() <= step * 0.5 + 1e-9 * want.abs().max(1.0) {
                Ok(())
            } else {
                Err(format!("{at}: sent {want}, got {got} (step {step:e})"))
            }
        }
        (
            Wire::Named {
                name,
                kind: TypeKind::Record,
                ..
            },
            Value::Object(x),
            Value::Object(y),
        ) => fields_close(spec, spec.ty(name).unwrap().fields(), x, y, at),
        (
            Wire::Named {
                name,
                kind: TypeKind::Union,
                ..
            },
            Value::Object(x),
            Value::Object(y),
        ) => {
            let (vn, xv) = x.iter().next().unwrap();
            let Some(TypeForm::Union { variants, .. }) = spec.ty(name).map(|t| &t.form) else {
                unreachable!("`{name}` is a union");
            };
            let w = variants
                .iter()
                .find(|v| &v.def.name == vn)
                .and_then(|v| v.wire.as_ref())
                .unwrap();
            close(
                spec,
                w,
                xv,
                y.get(vn).ok_or(format!("{at}: variant {vn} lost"))?,
                at,
            )
        }
        (
            Wire::List { elem, .. } | Wire::ListField { elem, .. },
            Value::Array(x),
            Value::Array(y),
        ) if x.len() == y.len() => x
            .iter()
            .zip(y)
            .enumerate()
            .try_for_each(|(i, (p, q))| close(spec, elem, p, q, &format!("{at}[{i}]"))),
        (Wire::F32, Value::Number(x), Value::Number(y)) => (x.as_f64().map(|v| v as f32)
            == y.as_f64().map(|v| v as f32))
        .then_some(())
        .ok_or(format!("{at}: {x} vs {y}")),
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
    for Field { def: f, wire } in fields {
        let here = format!("{at}.{}", f.name);
        // A count kept in its own field is computed from the list it counts when that
        // list is in the same record: what was sent there does not matter.
        let computed = fields
            .iter()
            .map(|g| &g.def)
            .any(|g| g.count_field.as_deref() == Some(&f.name) && g.offsets_of.is_none());
        if computed || f.offsets_of.is_some() {
            continue;
        }
        match (a.get(&f.name), b.get(&f.name)) {
            (Some(x), Some(y)) => close(spec, wire, x, y, &here)?,
            (None, None) => {}
            (x, y) => return Err(format!("{here}: sent {x:?}, got {y:?}")),
        }
    }
    Ok(())
}

#[test]
fn random_values_of_every_message_round_trip() {
    let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).expect("definitions validate");
    let mut cases = 0;
    for m in &spec.messages {
        let strategy = record_strategy(&spec, &m.fields, 0);
        let mut runner = TestRunner::new(Config {
            cases: 48,
            failure_persistence: None,
            max_global_rejects: 100_000,
            ..Config::default()
        });
        let result = runner.run(&strategy, |fields| {
            let input = json!({ "message": m.def.name, "fields": fields });
            let msg: Message = serde_json::from_value(input.clone())
                .map_err(|e| TestCaseError::fail(format!("JSON → {}: {e}", m.def.name)))?;
            let bytes = match msg.to_bytes() {
                Ok(b) => b,
                // Random values that contradict a count or flag kept in another field
                // are refused with a typed error, as they must be; skip those cases.
                Err(
                    EncodeError::CountMismatch { .. }
                    | EncodeError::PresenceMismatch { .. }
                    | EncodeError::TagMismatch { .. },
                ) => return Err(TestCaseError::reject("inconsistent dependent fields")),
                Err(e) => return Err(TestCaseError::fail(format!("encode: {e}"))),
            };
            let back = Message::decode(msg.code(), &bytes)
                .map_err(|e| TestCaseError::fail(format!("decode: {e}")))?;
            let again = back
                .to_bytes()
                .map_err(|e| TestCaseError::fail(format!("re-encode: {e}")))?;
            prop_assert_eq!(&bytes, &again, "second encoding differs");
            let out = serde_json::to_value(&back).unwrap();
            let empty = Map::new();
            fields_close(
                &spec,
                &m.fields,
                input["fields"].as_object().unwrap_or(&empty),
                out["fields"].as_object().unwrap_or(&empty),
                &m.def.name,
            )
            .map_err(TestCaseError::fail)?;
            Ok(())
        });
        if let Err(e) = result {
            panic!("{}: {e}", m.def.name);
        }
        cases += 48;
    }
    assert!(cases >= 48 * 90);
}

/// A scaled value inside a message's JSON: where it is (a JSON pointer below `fields`),
/// the derive's path of its field (`Type.field`) and its limits.
struct Leaf {
    ptr: String,
    field: String,
    lo: f64,
    hi: f64,
}

/// Every scaled value of `obj`, the JSON of a record or message `owner` with `fields`.
fn scaled_leaves(spec: &Spec, owner: &str, fields: &[Field], obj: &Value, ptr: &str) -> Vec<Leaf> {
    let mut out = Vec::new();
    for Field { def: f, wire } in fields {
        if let Some(v) = obj.get(&f.name) {
            let path = format!("{owner}.{}", f.name);
            leaves_of(spec, &path, wire, v, &format!("{ptr}/{}", f.name), &mut out);
        }
    }
    out
}

fn leaves_of(spec: &Spec, path: &str, w: &Wire, v: &Value, ptr: &str, out: &mut Vec<Leaf>) {
    match (w, v) {
        (Wire::Scaled { lo, hi, .. }, Value::Number(_)) => out.push(Leaf {
            ptr: ptr.to_string(),
            field: path.to_string(),
            lo: *lo,
            hi: *hi,
        }),
        (Wire::List { elem, .. } | Wire::ListField { elem, .. }, Value::Array(items)) => {
            for (i, item) in items.iter().enumerate() {
                leaves_of(spec, path, elem, item, &format!("{ptr}/{i}"), out);
            }
        }
        (Wire::Named { name, .. }, _) => match spec.ty(name).map(|t| &t.form) {
            Some(TypeForm::Record { fields, .. }) => {
                out.extend(scaled_leaves(spec, name, fields, v, ptr));
            }
            Some(TypeForm::Union { variants, .. }) => {
                if let Some((vn, value)) = v.as_object().and_then(|o| o.iter().next()) {
                    let variant = variants.iter().find(|x| &x.def.name == vn);
                    if let Some(w) = variant.and_then(|x| x.wire.as_ref()) {
                        leaves_of(spec, path, w, value, &format!("{ptr}/{vn}"), out);
                    }
                }
            }
            _ => {}
        },
        _ => {}
    }
}

#[test]
fn out_of_range_scaled_values_are_typed_errors() {
    let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).expect("definitions validate");
    let mut messages = 0;
    for m in &spec.messages {
        // Which scaled value goes out of range, on which side, and how far (in spans of
        // its range: at least 1 %, far more than the 1.5 counts that are clamped).
        let strategy = (
            record_strategy(&spec, &m.fields, 0),
            any::<prop::sample::Index>(),
            any::<bool>(),
            0.01f64..10.0,
        );
        let mut runner = TestRunner::new(Config {
            cases: 16,
            failure_persistence: None,
            max_global_rejects: 100_000,
            ..Config::default()
        });
        let tested = std::cell::Cell::new(false);
        let result = runner.run(&strategy, |(mut fields, pick, above, by)| {
            let leaves = scaled_leaves(&spec, &m.def.name, &m.fields, &fields, "");
            if leaves.is_empty() {
                return Ok(());
            }
            tested.set(true);
            let leaf = pick.get(&leaves);
            let span = leaf.hi - leaf.lo;
            let bad = if above {
                leaf.hi + span * by
            } else {
                leaf.lo - span * by
            };
            *fields.pointer_mut(&leaf.ptr).unwrap() = json!(bad);
            let input = json!({ "message": m.def.name, "fields": fields });
            let msg: Message = serde_json::from_value(input)
                .map_err(|e| TestCaseError::fail(format!("JSON → {}: {e}", m.def.name)))?;
            match msg.to_bytes() {
                Err(EncodeError::OutOfRange { scaled, value, .. }) => {
                    prop_assert_eq!(scaled.field, leaf.field.as_str());
                    prop_assert_eq!((scaled.lo, scaled.hi), (leaf.lo, leaf.hi));
                    prop_assert_eq!(value, bad);
                }
                Err(
                    EncodeError::CountMismatch { .. }
                    | EncodeError::PresenceMismatch { .. }
                    | EncodeError::TagMismatch { .. },
                ) => return Err(TestCaseError::reject("inconsistent dependent fields")),
                other => {
                    return Err(TestCaseError::fail(format!(
                        "{} = {bad} (limits [{}, {}]) gave {other:?}",
                        leaf.field, leaf.lo, leaf.hi
                    )))
                }
            }
            // Clamped, the value is at its limit and the message encodes.
            let clamped = msg.clamped();
            let json = serde_json::to_value(&clamped).unwrap();
            let limit = if above { leaf.hi } else { leaf.lo };
            prop_assert_eq!(
                json.pointer(&format!("/fields{}", leaf.ptr)),
                Some(&json!(limit))
            );
            match clamped.to_bytes() {
                Ok(_)
                | Err(
                    EncodeError::CountMismatch { .. }
                    | EncodeError::PresenceMismatch { .. }
                    | EncodeError::TagMismatch { .. },
                ) => Ok(()),
                Err(e) => Err(TestCaseError::fail(format!("clamped: {e}"))),
            }
        });
        if let Err(e) = result {
            panic!("{}: {e}", m.def.name);
        }
        messages += usize::from(tested.get());
    }
    assert!(messages >= 50, "{messages} messages with scaled values");
}
