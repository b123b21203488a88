//! Message bodies a plan sends, built from the definitions alone: a query asking for
//! everything its report can carry, and a command whose values differ a little from
//! those its read-back query reported (so that its effect, if any, shows).

use jaus_dynamic::{DynMessage, Value};
use jaus_spec::{Int, TypeKind, Wire};
use serde_json::{json, Value as Json};

use super::defs::Definitions;

/// Longest zero body tried for a message's smallest body.
const MAX_ZERO: usize = 64;

/// Arguments for the Core queries whose smallest body asks for nothing useful
/// (a reserved level, no node).
fn known(name: &str) -> Option<Json> {
    Some(match name {
        "QueryIdentification" => json!({ "query_type": "Component" }),
        "QueryConfiguration" => json!({ "query_type": "Node" }),
        "QueryServices" => json!({ "nodes": [{ "node_id": 255, "component_ids": [255] }] }),
        "QueryServiceList" => json!({ "subsystems": [{ "subsystem_id": 65535,
            "nodes": [{ "node_id": 255, "components": [{ "component_id": 255 }] }] }] }),
        "QueryEvents" => json!({ "filter": { "AllEvents": 0 } }),
        _ => return None,
    })
}

/// The smallest body of message `name` as JSON fields: the shortest run of zero bytes
/// that decodes and encodes back to itself (optional fields absent, lists empty), each
/// top-level enumeration whose 0 the definition does not name set to its smallest named
/// value (Query Odometry asks for the platform odometer, not for odometer 0).
fn zero(defs: &Definitions, name: &str) -> Result<Json, String> {
    let mut fields = zero_bytes(defs, name)?;
    let Some(m) = defs.message(name) else {
        return Ok(fields);
    };
    for f in &m.fields {
        let Wire::Named {
            name: ty,
            kind: TypeKind::Enum,
            ..
        } = &f.wire
        else {
            continue;
        };
        let Some(t) = defs.spec().ty(ty) else {
            continue;
        };
        let values = &t.def.values;
        if values.iter().any(|v| v.value == 0) {
            continue;
        }
        if let (Some(first), Some(slot)) = (
            values.iter().min_by_key(|v| v.value),
            fields.get_mut(&f.def.name),
        ) {
            *slot = json!(first.name);
        }
    }
    Ok(fields)
}

/// The shortest run of zero bytes that is a body of message `name`, as JSON fields.
fn zero_bytes(defs: &Definitions, name: &str) -> Result<Json, String> {
    let layout = defs
        .schema()
        .message(name)
        .ok_or_else(|| format!("{name} is not in the definitions"))?;
    let zeros = [0u8; MAX_ZERO];
    for n in 0..=MAX_ZERO {
        if let Ok(m) = defs.schema().decode(layout.code, &zeros[..n]) {
            if defs.schema().encode(&m).is_ok_and(|b| b.len() == n) {
                return serde_json::to_value(&m.fields).map_err(|e| e.to_string());
            }
        }
    }
    Err(format!(
        "no body of {name} could be built from its definition (give its fields by hand with jaus as4-query)"
    ))
}

/// The presence bits of message `name`'s optional fields, all set.
fn all_bits(defs: &Definitions, name: &str) -> u64 {
    defs.message(name).map_or(0, |m| {
        m.fields
            .iter()
            .filter_map(|f| f.def.bit)
            .filter(|b| *b < 64)
            .fold(0, |acc, b| acc | (1u64 << b))
    })
}

/// Query `name` asking for everything report `report` can carry: its arguments for the
/// Core's discovery queries, else its smallest body with a `presence_vector` field set
/// to every optional field of the report.
pub fn query(defs: &Definitions, name: &str, report: &str) -> Result<DynMessage, String> {
    let mut fields = match known(name) {
        Some(j) => j,
        None => zero(defs, name)?,
    };
    if let Some(Json::Number(_)) = fields.get("presence_vector") {
        let max = defs
            .message(name)
            .and_then(|m| m.fields.iter().find(|f| f.def.name == "presence_vector"))
            .and_then(|f| match f.wire {
                Wire::Int(i) if i.bytes() < 8 => Some((1u64 << (8 * i.bytes())) - 1),
                _ => None,
            })
            .unwrap_or(u64::MAX);
        fields["presence_vector"] = json!(all_bits(defs, report) & max);
    }
    defs.schema()
        .from_json(name, &fields)
        .map_err(|e| e.to_string())
}

/// A numeric field of command `command` that report `report` carries too: its name and
/// how its value may be moved.
#[derive(Debug, Clone, PartialEq)]
pub struct Shared {
    /// The field's name.
    pub name: String,
    wire: Wire,
}

/// The numeric top-level fields `command` and `report` share (what a read-back can
/// show).
pub fn shared(defs: &Definitions, command: &str, report: &str) -> Vec<Shared> {
    let (Some(c), Some(r)) = (defs.message(command), defs.message(report)) else {
        return Vec::new();
    };
    c.fields
        .iter()
        .filter(|f| {
            matches!(
                f.wire,
                Wire::Int(_) | Wire::Scaled { .. } | Wire::F32 | Wire::F64
            )
        })
        .filter(|f| f.def.name != "presence_vector" && f.def.name != "request_id")
        .filter(|f| r.fields.iter().any(|g| g.def.name == f.def.name))
        .map(|f| Shared {
            name: f.def.name.clone(),
            wire: f.wire.clone(),
        })
        .collect()
}

/// Whether `report` cannot be `command`'s read-back: a field of both names with
/// different types (HMI's Set DCM sets how a button is shown, `state` of flags; Report
/// DCM reports its last action, `state` pressed or released: same names, two things).
pub fn conflicts(defs: &Definitions, command: &str, report: &str) -> bool {
    let (Some(c), Some(r)) = (defs.message(command), defs.message(report)) else {
        return false;
    };
    c.fields.iter().any(|f| {
        r.fields
            .iter()
            .any(|g| g.def.name == f.def.name && (g.def.ty != f.def.ty || g.wire != f.wire))
    })
}

/// `v` moved a little within its wire type: down by one step when it can, else up.
fn nudge(v: f64, wire: &Wire) -> f64 {
    match wire {
        Wire::Scaled { int, lo, hi } => {
            let res = (hi - lo) / int_max(*int);
            let step = ((hi - lo) / 100.0).min(1.0).max(res * 4.0);
            if v - step >= *lo {
                v - step
            } else {
                v + step
            }
        }
        _ if v >= 1.0 => v - 1.0,
        _ => v + 1.0,
    }
}

fn int_max(i: Int) -> f64 {
    2f64.powi(8 * i.bytes() as i32) - 1.0
}

/// Command `command` setting each field of `fields` it shares with the report `r0`
/// (as read back before), moved a little when `nudge_them` (else as read: the value
/// put back); the values sent, by field.
pub fn command(
    defs: &Definitions,
    command: &str,
    fields: &[Shared],
    r0: Option<&Value>,
    nudge_them: bool,
) -> Result<(DynMessage, Vec<(String, f64)>), String> {
    let mut body = zero(defs, command)?;
    let mut sent = Vec::new();
    for f in fields {
        let Some(v) = r0.and_then(|r| r.field(&f.name)).and_then(Value::as_f64) else {
            continue;
        };
        let v = if nudge_them { nudge(v, &f.wire) } else { v };
        body[f.name.as_str()] = match f.wire {
            Wire::Int(_) => json!(v.round() as i64),
            _ => json!(v),
        };
        sent.push((f.name.clone(), v));
    }
    let m = defs
        .schema()
        .from_json(command, &body)
        .map_err(|e| e.to_string())?;
    Ok((m, sent))
}

/// The fields of `sent` that `r1` shows closer to the value sent than to the one of
/// `r0`: `name: before → after (sent)`.
pub fn moved(r0: &Value, r1: &Value, sent: &[(String, f64)]) -> Vec<String> {
    sent.iter()
        .filter_map(|(name, s)| {
            let a = r0.field(name)?.as_f64()?;
            let b = r1.field(name)?.as_f64()?;
            ((b - s).abs() < (b - a).abs()).then(|| format!("{name}: {a} → {b} (sent {s})"))
        })
        .collect()
}

/// A message's fields as JSON (for details).
pub fn text(v: &Value) -> String {
    serde_json::to_string(v).unwrap_or_default()
}
