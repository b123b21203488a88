//! Random values of a message's fields as JSON, from the definitions (one general
//! mechanism, no per-message code): the strategies of the round-trip property test and
//! of the dissector test's AS-4 capture. A field that carries a message
//! (`embeds: message`) gets a whole small message of the same definitions.

use jaus_spec::{Bits, Field, Int, Len, Spec, TypeForm, TypeKind, Wire};
use proptest::prelude::*;
use serde_json::{json, Map, Value};

fn int_strategy(i: Int) -> BoxedStrategy<Value> {
    match i {
        Int::U8 => any::<u8>().prop_map(|v| json!(v)).boxed(),
        Int::U16 => any::<u16>().prop_map(|v| json!(v)).boxed(),
        Int::U32 => any::<u32>().prop_map(|v| json!(v)).boxed(),
        Int::U64 => any::<u64>().prop_map(|v| json!(v)).boxed(),
        Int::I8 => any::<i8>().prop_map(|v| json!(v)).boxed(),
        Int::I16 => any::<i16>().prop_map(|v| json!(v)).boxed(),
        Int::I32 => any::<i32>().prop_map(|v| json!(v)).boxed(),
        Int::I64 => any::<i64>().prop_map(|v| json!(v)).boxed(),
    }
}

fn hex_of(n: std::ops::Range<usize>) -> BoxedStrategy<Value> {
    prop::collection::vec(any::<u8>(), n)
        .prop_map(|b| json!(jaus::hex::encode(&b)))
        .boxed()
}

fn text(max: usize) -> BoxedStrategy<Value> {
    prop::collection::vec(prop::char::range(' ', '~'), 0..=max)
        .prop_map(|c| json!(c.into_iter().collect::<String>()))
        .boxed()
}

pub fn wire_strategy(spec: &Spec, w: &Wire, depth: u32) -> BoxedStrategy<Value> {
    match w {
        Wire::Int(i) => int_strategy(*i),
        Wire::F32 => any::<f32>()
            .prop_filter("finite", |v| v.is_finite())
            .prop_map(|v| json!(v))
            .boxed(),
        Wire::F64 => any::<f64>()
            .prop_filter("finite", |v| v.is_finite())
            .prop_map(|v| json!(v))
            .boxed(),
        // In range: a value beyond the limits is an encode error (see
        // `out_of_range_scaled_values_are_typed_errors`).
        Wire::Scaled { lo, hi, .. } => (*lo..=*hi).prop_map(|v| json!(v)).boxed(),
        Wire::Str(len) => match len {
            Len::Fixed { n, .. } => text(*n),
            _ => text(40),
        },
        Wire::Bytes(len) => match len {
            Len::Fixed { n, .. } => hex_of(*n..*n + 1),
            _ => hex_of(0..40),
        },
        // Recursive records (task trees) stop nesting after a few levels.
        Wire::List { elem, .. } | Wire::ListField { elem, .. }
            if depth >= 3
                && matches!(
                    elem.as_ref(),
                    Wire::Named {
                        kind: TypeKind::Record,
                        ..
                    }
                ) =>
        {
            Just(json!([])).boxed()
        }
        Wire::List { elem, .. } => prop::collection::vec(wire_strategy(spec, elem, depth), 0..5)
            .prop_map(Value::Array)
            .boxed(),
        // Counts kept in another field: short lists, so that random counts often agree
        // (cases where they do not are rejected by the encoder, and skipped here).
        Wire::ListField { elem, .. } => {
            prop::collection::vec(wire_strategy(spec, elem, depth), 0..3)
                .prop_map(Value::Array)
                .boxed()
        }
        Wire::Flag => any::<bool>().prop_map(|b| json!(b)).boxed(),
        Wire::Packet { .. } => (
            any::<u8>(),
            any::<u16>(),
            any::<u16>(),
            prop::collection::vec(any::<u8>(), 0..20),
        )
            .prop_map(|(prio, code, seq, body)| {
                json!({
                    "header": {
                        "priority": prio & 15, "ack_nak": "none", "service_connection": false,
                        "experimental": prio & 16 != 0, "version": 2, "command_code": code,
                        "destination": [1, 2, 3, 4], "source": [5, 6, 7, 8],
                        "data_size": body.len(), "data_flag": "single", "sequence_number": seq
                    },
                    "body": jaus::hex::encode(&body)
                })
            })
            .boxed(),
        Wire::Named { name, .. } => {
            let ty = spec.ty(name).expect("named type");
            match &ty.form {
                TypeForm::Record { fields, .. } => record_strategy(spec, fields, depth + 1),
                TypeForm::Enum { .. } => {
                    let values = ty.def.values.clone();
                    any::<u8>()
                        .prop_map(
                            move |n| match values.iter().find(|v| v.value == u64::from(n)) {
                                Some(v) => json!(v.name),
                                None => json!({ "Unknown": n }),
                            },
                        )
                        .boxed()
                }
                TypeForm::Bitfield { members, .. } => {
                    let members: Vec<BoxedStrategy<(String, Value)>> = members
                        .iter()
                        .map(|b| {
                            let name = b.def.name.clone();
                            match b.bits {
                                Bits::Flag(_) => any::<bool>()
                                    .prop_map(move |v| (name.clone(), json!(v)))
                                    .boxed(),
                                Bits::Range { lo, hi } => {
                                    let max = (1u64 << (hi - lo + 1)) - 1;
                                    (0..=max)
                                        .prop_map(move |v| (name.clone(), json!(v)))
                                        .boxed()
                                }
                            }
                        })
                        .collect();
                    members
                        .prop_map(|m| Value::Object(m.into_iter().collect()))
                        .boxed()
                }
                TypeForm::Union { variants, .. } => {
                    let variants: Vec<BoxedStrategy<Value>> = variants
                        .iter()
                        .map(|v| {
                            let name = v.def.name.clone();
                            match &v.wire {
                                Some(w) => wire_strategy(spec, w, depth)
                                    .prop_map(move |x| json!({ name.clone(): x }))
                                    .boxed(),
                                None => Just(json!(name)).boxed(),
                            }
                        })
                        .collect();
                    proptest::strategy::Union::new(variants).boxed()
                }
            }
        }
    }
}

/// A union field whose tag is another field: (field, tag field, variant names and tags).
type Tagged = (String, String, Vec<(String, u64)>);

pub fn record_strategy(spec: &Spec, fields: &[Field], depth: u32) -> BoxedStrategy<Value> {
    let parts: Vec<BoxedStrategy<Option<(String, Value)>>> = fields
        .iter()
        .map(|Field { def: f, wire }| {
            let name = f.name.clone();
            // Fields other fields depend on (counts kept apart, presence flags) take
            // small values, so that random cases are often consistent.
            let governs = fields.iter().any(|g| {
                g.def.present_if.as_deref() == Some(f.name.as_str())
                    || matches!(&g.wire, Wire::ListField { field, .. } if field.field == f.name)
            });
            let s = match wire {
                Wire::Int(_) if governs => (0u64..4).prop_map(|v| json!(v)).boxed(),
                _ if f.embeds.is_some() => embedded_strategy(spec),
                w => wire_strategy(spec, w, depth),
            }
            .prop_map(move |v| (name.clone(), v));
            if f.bit.is_some() && *wire != Wire::Flag || f.present_if.is_some() {
                prop::option::of(s).boxed()
            } else {
                s.prop_map(Some).boxed()
            }
        })
        .collect();
    // Unions whose tag lives in another field: make the tag field and every such union
    // agree with the first union's variant.
    let tagged: Vec<Tagged> = fields
        .iter()
        .map(|f| &f.def)
        .filter_map(|f| {
            let tag = f.tag_field.clone()?;
            let variants = spec
                .ty(&f.ty)?
                .def
                .variants
                .iter()
                .map(|v| (v.name.clone(), v.tag))
                .collect();
            Some((f.name.clone(), tag, variants))
        })
        .collect();
    parts
        .prop_map(move |p| {
            let mut obj = p.into_iter().flatten().collect::<Map<_, _>>();
            if let Some((first, tag_field, variants)) = tagged.first() {
                if let Some(v) = obj.get(first).cloned() {
                    let name = v
                        .as_object()
                        .and_then(|o| o.keys().next().cloned())
                        .or(v.as_str().map(String::from));
                    if let Some(tag) =
                        name.and_then(|n| variants.iter().find(|(vn, _)| *vn == n).map(|x| x.1))
                    {
                        obj.insert(tag_field.clone(), json!(tag));
                    }
                    for (other, _, _) in &tagged[1..] {
                        obj.insert(other.clone(), v.clone());
                    }
                }
            }
            Value::Object(obj)
        })
        .boxed()
}

/// A message as `embeds: message` carries it (message ID, then body): one of the
/// definitions' messages without fields, as hex.
fn embedded_strategy(spec: &Spec) -> BoxedStrategy<Value> {
    let ids: Vec<Value> = spec
        .messages
        .iter()
        .filter(|m| m.fields.is_empty())
        .map(|m| json!(jaus::hex::encode(&m.def.code.0.to_le_bytes())))
        .collect();
    assert!(!ids.is_empty(), "a message without fields to embed");
    proptest::sample::select(ids).boxed()
}
