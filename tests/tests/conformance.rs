//! Conformance against packets serialised by the OpenJAUS 3.3 C library
//! (`data/openjaus33.jsonl`, copied from the shared reference vectors).
//!
//! For every vector whose command code the definitions know: the packet decodes to the
//! right message, re-encodes to identical bytes, the header fields equal the vector's,
//! and every field value equals OpenJAUS's within one least significant bit of its
//! scaling. The comparison is driven by the YAML definitions (field by field, with the
//! wire form of each), so no per-message code exists here either.

use jaus::codec::Encode;
use jaus::messages::Message;
use jaus::Packet;
use jaus_spec::{Bits, Field, FieldDef, Spec, TypeForm, TypeKind, Wire};
use serde_json::{Map, Value};
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

fn data_dir() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/data"))
}

#[derive(Debug)]
pub struct Vector {
    pub message: String,
    pub variant: String,
    pub bytes: Vec<u8>,
    pub header: Value,
    pub fields: Value,
}

pub fn vectors() -> Vec<Vector> {
    let text =
        std::fs::read_to_string(data_dir().join("openjaus33.jsonl")).expect("vectors present");
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Value = serde_json::from_str(l).expect("vector is JSON");
            Vector {
                message: v["message"].as_str().unwrap().to_string(),
                variant: v["variant"].as_str().unwrap().to_string(),
                bytes: jaus::hex::decode(v["hex"].as_str().unwrap()).unwrap(),
                header: v["header"].clone(),
                fields: v["fields"].clone(),
            }
        })
        .collect()
}

/// `Owner.field = ojKey.path` lines, and `TypeName = ojKey` for every field of a type.
fn name_overrides() -> HashMap<String, String> {
    let text = std::fs::read_to_string(data_dir().join("openjaus-names.txt")).unwrap_or_default();
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
        .filter_map(|l| {
            l.split_once('=')
                .map(|(a, b)| (a.trim().to_string(), b.trim().to_string()))
        })
        .collect()
}

const UNIT_SUFFIXES: &[&str] = &[
    "Degrees", "Radians", "Percent", "Celsius", "Meters", "Hertz", "Deg", "Mps", "Rps", "M",
];

fn norm_oj(key: &str) -> String {
    let mut k = key;
    for s in UNIT_SUFFIXES {
        if let Some(stripped) = k.strip_suffix(s) {
            if !stripped.is_empty() {
                k = stripped;
                break;
            }
        }
    }
    k.to_lowercase()
}

fn norm_mine(name: &str) -> String {
    name.replace('_', "").to_lowercase()
}

struct Cmp<'a> {
    spec: &'a Spec,
    names: HashMap<String, String>,
    errors: Vec<String>,
}

/// `key[i]`, `key[-1]` (from the end) or `key[..-1]` (all but the last) of an OpenJAUS
/// list.
fn index_path(obj: &Map<String, Value>, path: &str) -> Option<Value> {
    let (key, rest) = path.split_once('[')?;
    let idx = rest.strip_suffix(']')?;
    // A list OpenJAUS leaves out when it is empty.
    let empty = Vec::new();
    let list = match obj.get(key) {
        Some(v) => v.as_array()?,
        None if idx.contains("..") => &empty,
        None => return None,
    };
    let n = list.len() as i64;
    let at = |i: i64| if i < 0 { n + i } else { i };
    match idx.split_once("..") {
        Some((a, b)) => {
            let a = if a.is_empty() { 0 } else { at(a.parse().ok()?) };
            let b = if b.is_empty() {
                n
            } else {
                at(b.parse().ok()?).max(0)
            };
            (0 <= a && a <= b && b <= n)
                .then(|| Value::Array(list[a as usize..b as usize].to_vec()))
        }
        None => {
            let i = at(idx.parse().ok()?);
            (0..n).contains(&i).then(|| list[i as usize].clone())
        }
    }
}

fn get_path<'v>(obj: &'v Map<String, Value>, path: &str) -> Option<&'v Value> {
    let mut parts = path.split('.');
    let mut cur = obj.get(parts.next()?)?;
    for p in parts {
        cur = cur.get(p)?;
    }
    Some(cur)
}

impl Cmp<'_> {
    fn fail(&mut self, at: &str, msg: String) {
        self.errors.push(format!("{at}: {msg}"));
    }

    /// Finds the OpenJAUS key of `owner.field` in `oj`.
    fn lookup<'v>(
        &self,
        owner: &str,
        field: &str,
        oj: &'v Map<String, Value>,
    ) -> Option<(String, &'v Value)> {
        if let Some(path) = self.names.get(&format!("{owner}.{field}")) {
            let first = path.split('.').next().unwrap_or("").to_string();
            return get_path(oj, path).map(|v| (first, v));
        }
        let want = norm_mine(field);
        oj.iter()
            .find(|(k, _)| norm_oj(k) == want)
            .map(|(k, v)| (k.clone(), v))
    }

    fn fields(
        &mut self,
        owner: &str,
        defs: &[Field],
        mine: &Map<String, Value>,
        oj: &Map<String, Value>,
        at: &str,
    ) {
        let used = self.fields_used(owner, defs, mine, oj, at, Vec::new());
        self.check_unused(owner, oj, &used, at);
    }

    /// Compares the fields of `owner`; returns the OpenJAUS keys used.
    fn fields_used(
        &mut self,
        owner: &str,
        defs: &[Field],
        mine: &Map<String, Value>,
        oj: &Map<String, Value>,
        at: &str,
        mut used: Vec<String>,
    ) -> Vec<String> {
        for Field { def: f, wire } in defs {
            let here = format!("{at}.{}", f.name);
            let my = mine.get(&f.name);
            if let Wire::Named {
                name,
                kind: TypeKind::Bitfield,
                ..
            } = wire
            {
                self.bitfield(owner, f, name, my, oj, &here, &mut used);
                continue;
            }
            let rule = self.names.get(&format!("{owner}.{}", f.name)).cloned();
            if rule.as_deref() == Some("-") {
                // A field OpenJAUS does not expose (a count or offsets it recomputes);
                // the byte comparison covers it.
                continue;
            }
            if rule.as_deref() == Some(".") {
                // A record whose fields OpenJAUS keeps in the enclosing object.
                let inner = match wire {
                    Wire::Named { name, .. } => self
                        .spec
                        .ty(name)
                        .map(|t| (name.clone(), t.fields().to_vec())),
                    _ => None,
                };
                match (my.and_then(Value::as_object), inner) {
                    (Some(m), Some((name, defs))) => {
                        used = self.fields_used(&name, &defs, m, oj, &here, used)
                    }
                    (None, _) if f.present_if.is_some() || f.bit.is_some() => {}
                    _ => self.fail(&here, "cannot compare a flattened record".into()),
                }
                continue;
            }
            if let Some(r) = rule
                .as_deref()
                .filter(|r| r.contains('[') && !oj.contains_key(*r))
            {
                // An element or a slice of an OpenJAUS list.
                let key = r.split('[').next().unwrap_or("").to_string();
                match (my, index_path(oj, r)) {
                    (Some(m), Some(o)) => {
                        used.push(key);
                        self.value(wire, m, &o, &here);
                    }
                    (None, None) => {}
                    (m, o) => self.fail(&here, format!("{m:?} vs OpenJAUS {o:?}")),
                }
                continue;
            }
            // `key * factor`: OpenJAUS holds the value in other units.
            let factor = rule
                .as_deref()
                .and_then(|r| r.split_once('*'))
                .and_then(|(_, f)| f.trim().parse::<f64>().ok());
            let found = match (&rule, factor) {
                (Some(r), Some(_)) => {
                    let key = r.split('*').next().unwrap_or("").trim();
                    get_path(oj, key).map(|v| (key.split('.').next().unwrap_or("").to_string(), v))
                }
                _ => self.lookup(owner, &f.name, oj),
            };
            let scaled_oj;
            let found = match (found, factor) {
                (Some((k, o)), Some(x)) => {
                    scaled_oj = o.as_f64().map_or(Value::Null, |v| serde_json::json!(v * x));
                    Some((k, &scaled_oj))
                }
                (f, _) => f,
            };
            // OpenJAUS keeps some lists of records as a record of lists (one list per
            // field); compare element-wise after transposing.
            let transposed;
            let found = match (found, wire) {
                (None, Wire::List { elem, .. } | Wire::ListField { elem, .. }) => {
                    match elem.as_ref() {
                        Wire::Named {
                            name,
                            kind: TypeKind::Record,
                            ..
                        } => {
                            transposed = self.transpose(name, oj, &mut used);
                            transposed.as_ref().map(|v| (String::new(), v))
                        }
                        _ => None,
                    }
                }
                (f, _) => f,
            };
            if *wire == Wire::Flag && found.is_none() {
                // A presence bit with no value of its own: OpenJAUS shows it only in
                // its presence vector, which the byte comparison covers.
                continue;
            }
            match (my, found) {
                (Some(m), Some((k, o))) => {
                    used.push(k);
                    self.value(wire, m, o, &here);
                }
                (None, None) if f.bit.is_some() || f.present_if.is_some() => {}
                (None, Some((k, o))) => {
                    used.push(k);
                    self.fail(&here, format!("absent here but OpenJAUS has {o}"));
                }
                (Some(m), None) => self.fail(
                    &here,
                    format!("present here ({m}) but OpenJAUS has no such field"),
                ),
                (None, None) => self.fail(&here, "missing on both sides".into()),
            }
        }
        used
    }

    fn check_unused(&mut self, owner: &str, oj: &Map<String, Value>, used: &[String], at: &str) {
        for (k, v) in oj {
            // Counts OpenJAUS reports next to the lists they count.
            let ignorable = matches!(
                k.as_str(),
                "presenceVector"
                    | "count"
                    | "subsystemCount"
                    | "dataSize"
                    | "commandCode"
                    | "objectCount"
                    | "numMsgs"
                    | "numMsgsToRemove"
                    | "numberInterfaces"
                    | "numJoints"
                    | "numPoses"
                    | "numCommands"
                    | "numChildren"
                    | "bufferSizeBytes"
            );
            if !used.iter().any(|u| u == k) && !ignorable {
                self.fail(
                    at,
                    format!("OpenJAUS field `{k}` = {v} matches no field of {owner}"),
                );
            }
        }
    }

    /// Builds `[{a: x0, b: y0}, ...]` from OpenJAUS's `{a: [x0, ...], b: [y0, ...]}` when
    /// every field of the record `ty` is such a list in `oj`.
    fn transpose(
        &self,
        ty: &str,
        oj: &Map<String, Value>,
        used: &mut Vec<String>,
    ) -> Option<Value> {
        let fields = self.spec.ty(ty)?.fields();
        let mut cols = Vec::new();
        for Field { def: f, .. } in fields {
            let (k, v) = self.lookup(ty, &f.name, oj)?;
            cols.push((f.name.clone(), k, v.as_array()?));
        }
        let n = cols.first()?.2.len();
        if cols.iter().any(|c| c.2.len() != n) {
            return None;
        }
        used.extend(cols.iter().map(|c| c.1.clone()));
        Some(Value::Array(
            (0..n)
                .map(|i| {
                    Value::Object(cols.iter().map(|c| (c.1.clone(), c.2[i].clone())).collect())
                })
                .collect(),
        ))
    }

    #[allow(clippy::too_many_arguments)]
    fn bitfield(
        &mut self,
        owner: &str,
        f: &FieldDef,
        ty: &str,
        my: Option<&Value>,
        oj: &Map<String, Value>,
        at: &str,
        used: &mut Vec<String>,
    ) {
        let Some(TypeForm::Bitfield { members, .. }) = self.spec.ty(ty).map(|t| &t.form) else {
            unreachable!("`{ty}` is a bit field");
        };
        let raw_of = |v: &Value| -> u64 {
            members
                .iter()
                .map(|b| {
                    let lo = match b.bits {
                        Bits::Flag(x) | Bits::Range { lo: x, .. } => x,
                    };
                    let x = match &v[&b.def.name] {
                        Value::Bool(t) => u64::from(*t),
                        n => n.as_u64().unwrap_or(0),
                    };
                    x << lo
                })
                .sum::<u64>()
                | v.get("reserved").and_then(Value::as_u64).unwrap_or(0)
        };
        // Whole bit field as a raw number, or inside an object (OpenJAUS's `time`). A
        // line `TypeName = key` maps every field of that type.
        let by_type = self
            .names
            .get(ty)
            .and_then(|k| oj.get(k).map(|v| (k.clone(), v)));
        if let Some((k, o)) = by_type.or_else(|| self.lookup(owner, &f.name, oj)) {
            used.push(k);
            let raw = match o {
                Value::Object(obj) => {
                    let key = obj
                        .keys()
                        .find(|key| norm_oj(key) == norm_mine(ty))
                        .cloned();
                    key.and_then(|key| obj.get(&key)).and_then(Value::as_u64)
                }
                n => n.as_u64(),
            };
            match (my, raw) {
                (Some(m), Some(r)) if raw_of(m) == r => {}
                (None, None) if f.bit.is_some() || f.present_if.is_some() => {}
                (Some(m), r) => self.fail(at, format!("bits {} vs OpenJAUS {r:?}", raw_of(m))),
                (None, r) => self.fail(at, format!("absent here but OpenJAUS has {r:?}")),
            }
            return;
        }
        // Members flattened into the parent object.
        for b in members.iter().map(|m| &m.def) {
            let here = format!("{at}.{}", b.name);
            match (my, self.lookup(ty, &b.name, oj)) {
                (Some(m), Some((k, o))) => {
                    used.push(k);
                    let mine = &m[&b.name];
                    let equal = match (mine, o) {
                        (Value::Bool(a), Value::Bool(c)) => a == c,
                        (a, c) => a.as_u64().is_some() && a.as_u64() == c.as_u64(),
                    };
                    if !equal {
                        self.fail(&here, format!("{mine} vs OpenJAUS {o}"));
                    }
                }
                (None, None) => {}
                (None, Some((k, o))) => {
                    used.push(k);
                    self.fail(&here, format!("absent here but OpenJAUS has {o}"));
                }
                (Some(_), None) => self.fail(&here, "OpenJAUS has no such member".into()),
            }
        }
    }

    fn value(&mut self, wire: &Wire, my: &Value, oj: &Value, at: &str) {
        match wire {
            Wire::Int(_) => {
                let same = match (my.as_i64(), oj.as_i64(), my.as_u64(), oj.as_u64()) {
                    (Some(a), Some(b), _, _) => a == b,
                    (_, _, Some(a), Some(b)) => a == b,
                    // OpenJAUS holds some raw integers in floating-point fields.
                    _ if oj.is_f64() => my.as_f64() == oj.as_f64(),
                    _ => oj.as_bool().map(u64::from) == my.as_u64(),
                };
                if !same {
                    self.fail(at, format!("{my} vs OpenJAUS {oj}"));
                }
            }
            Wire::F32 | Wire::F64 => {
                let (a, b) = (
                    my.as_f64().unwrap_or(f64::NAN),
                    oj.as_f64().unwrap_or(f64::NAN),
                );
                if (a - b).abs() > 1e-9 * b.abs().max(1.0) {
                    self.fail(at, format!("{a} vs OpenJAUS {b}"));
                }
            }
            Wire::Scaled { int, lo, hi } => {
                let step = (hi - lo) / int.divisor();
                let (a, b) = (
                    my.as_f64().unwrap_or(f64::NAN),
                    oj.as_f64().unwrap_or(f64::NAN),
                );
                if a.is_nan() || b.is_nan() || (a - b).abs() > step * 1.000_001 {
                    self.fail(at, format!("{a} vs OpenJAUS {b} (one count = {step:e})"));
                }
            }
            Wire::Named { name, kind, .. } => {
                let ty = self.spec.ty(name).expect("named type");
                let def = &ty.def;
                match kind {
                    TypeKind::Enum => {
                        let n = match my {
                            Value::String(s) => {
                                def.values.iter().find(|v| &v.name == s).map(|v| v.value)
                            }
                            Value::Object(o) => o.get("Unknown").and_then(Value::as_u64),
                            _ => None,
                        };
                        if n != oj.as_u64() {
                            self.fail(at, format!("{my} ({n:?}) vs OpenJAUS {oj}"));
                        }
                    }
                    TypeKind::Record => match (my.as_object(), oj.as_object()) {
                        (Some(m), Some(o)) => self.fields(name, ty.fields(), m, o, at),
                        _ => self.fail(at, format!("record {my} vs OpenJAUS {oj}")),
                    },
                    TypeKind::Union => {
                        let (vname, payload) = match my {
                            Value::Object(o) if o.len() == 1 => o
                                .iter()
                                .next()
                                .map(|(k, v)| (k.clone(), v.clone()))
                                .unwrap(),
                            Value::String(s) => (s.clone(), Value::Null),
                            _ => (String::new(), Value::Null),
                        };
                        let TypeForm::Union { variants, .. } = &ty.form else {
                            unreachable!("`{name}` is a union");
                        };
                        let Some(var) = variants.iter().find(|v| v.def.name == vname) else {
                            return self.fail(at, format!("unknown variant in {my}"));
                        };
                        // The named type the variant carries, if any.
                        let inner = match &var.wire {
                            Some(Wire::Named { name, .. }) => self.spec.ty(name),
                            _ => None,
                        };
                        let var = &var.def;
                        if let Some(tag_key) = self.names.get(&format!("{name}.tag")).cloned() {
                            // OpenJAUS keeps the tag and the variant's fields in one object.
                            if Some(var.tag) != oj.get(&tag_key).and_then(Value::as_u64) {
                                return self.fail(
                                    at,
                                    format!("variant {vname} (tag {}) vs OpenJAUS {oj}", var.tag),
                                );
                            }
                            let rec = inner.map(|t| (t.def.name.clone(), t.fields().to_vec()));
                            if let (Some((rname, defs)), Some(p), Some(o)) =
                                (rec, payload.as_object(), oj.as_object())
                            {
                                let used = self.fields_used(&rname, &defs, p, o, at, vec![tag_key]);
                                self.check_unused(&rname, o, &used, at);
                            }
                            return;
                        }
                        if Some(var.tag) != oj.get("dataType").and_then(Value::as_u64) {
                            return self.fail(
                                at,
                                format!("variant {vname} (tag {}) vs OpenJAUS {oj}", var.tag),
                            );
                        }
                        let ojv = oj.get("value").cloned().unwrap_or(Value::Null);
                        let payload = match (payload, inner) {
                            // A record payload compares with OpenJAUS's array form, in field order.
                            (Value::Object(o), Some(rec)) => Value::Array(
                                rec.fields()
                                    .iter()
                                    .map(|f| o.get(&f.def.name).cloned().unwrap_or(Value::Null))
                                    .collect(),
                            ),
                            (p, _) => p,
                        };
                        let same = match (&payload, &ojv) {
                            (Value::Array(a), Value::Array(b)) => a == b,
                            (a, b) if a.is_f64() || b.is_f64() => {
                                let (x, y) = (
                                    a.as_f64().unwrap_or(f64::NAN),
                                    b.as_f64().unwrap_or(f64::NAN),
                                );
                                (x - y).abs() <= 1e-9 * y.abs().max(1.0)
                            }
                            (a, b) => a == b,
                        };
                        if !same {
                            self.fail(at, format!("{payload} vs OpenJAUS {ojv}"));
                        }
                    }
                    TypeKind::Bitfield => unreachable!("handled by the caller"),
                }
            }
            Wire::Str(_) => {
                if my.as_str() != oj.as_str() {
                    self.fail(at, format!("{my} vs OpenJAUS {oj}"));
                }
            }
            Wire::Bytes(_) => {
                let theirs = oj.get("data").unwrap_or(oj);
                if my.as_str() != theirs.as_str() {
                    self.fail(at, format!("{my} vs OpenJAUS {theirs}"));
                }
            }
            Wire::Flag => {
                if my.as_bool() != oj.as_bool().or(oj.as_u64().map(|v| v != 0)) {
                    self.fail(at, format!("{my} vs OpenJAUS {oj}"));
                }
            }
            Wire::List { elem, .. } | Wire::ListField { elem, .. } => {
                match (my.as_array(), oj.as_array()) {
                    (Some(a), Some(b)) if a.len() == b.len() => {
                        for (i, (x, y)) in a.iter().zip(b).enumerate() {
                            self.value(elem, x, y, &format!("{at}[{i}]"));
                        }
                    }
                    _ => self.fail(at, format!("list {my} vs OpenJAUS {oj}")),
                }
            }
            Wire::Packet { .. } => {
                if my["body"].as_str() != oj["data"].as_str() {
                    self.fail(
                        at,
                        format!("embedded body {} vs OpenJAUS {}", my["body"], oj["data"]),
                    );
                }
                self.header(&my["header"], &oj["header"], at);
            }
        }
    }

    fn header(&mut self, mine: &Value, oj: &Value, at: &str) {
        let ack = ["none", "request", "nak", "ack"];
        let flag = |v: &Value| v.as_bool().map(u64::from);
        let pairs: [(&str, Option<u64>, Option<u64>); 7] = [
            (
                "priority",
                mine["priority"].as_u64(),
                oj["priority"].as_u64(),
            ),
            (
                "ack_nak",
                ack.iter()
                    .position(|a| Some(*a) == mine["ack_nak"].as_str())
                    .map(|p| p as u64),
                oj["ack_nak"].as_u64(),
            ),
            (
                "sc_flag",
                flag(&mine["service_connection"]),
                oj["sc_flag"].as_u64(),
            ),
            (
                "exp_flag",
                flag(&mine["experimental"]),
                oj["exp_flag"].as_u64(),
            ),
            ("version", mine["version"].as_u64(), oj["version"].as_u64()),
            (
                "command_code",
                mine["command_code"].as_u64(),
                oj["command_code"].as_u64(),
            ),
            (
                "sequence_number",
                mine["sequence_number"].as_u64(),
                oj["sequence_number"].as_u64(),
            ),
        ];
        for (name, a, b) in pairs {
            if a != b || a.is_none() {
                self.fail(at, format!("header {name}: {a:?} vs OpenJAUS {b:?}"));
            }
        }
        // Both list addresses as [subsystem, node, component, instance].
        for key in ["destination", "source"] {
            let m: Vec<u64> = mine[key]
                .as_array()
                .map(|a| a.iter().filter_map(Value::as_u64).collect())
                .unwrap_or_default();
            let o: Vec<u64> = oj[key]
                .as_array()
                .map(|a| a.iter().filter_map(Value::as_u64).collect())
                .unwrap_or_default();
            if m != o {
                self.fail(at, format!("header {key}: {m:?} vs OpenJAUS {o:?}"));
            }
        }
    }
}

/// Reads the elements of Set/Report Payload Data Element with the type codes of the
/// vector's interface definition and compares them with OpenJAUS's values.
fn check_payload_elements(
    cmp: &mut Cmp<'_>,
    message: &Message,
    iface: &Value,
    oj: &Map<String, Value>,
    at: &str,
) {
    use jaus::messages::PayloadValue as P;
    let (list, elements) = match message {
        Message::SetPayloadDataElement(m) => (
            "commandInterfaces",
            m.data_elements(&types(iface, "commandInterfaces")),
        ),
        Message::ReportPayloadDataElement(m) => (
            "informationInterfaces",
            m.data_elements(&types(iface, "informationInterfaces")),
        ),
        _ => {
            return cmp.fail(
                at,
                "interface definition on a message without data elements".into(),
            )
        }
    };
    fn types(iface: &Value, list: &str) -> jaus::payload::PayloadTypes {
        jaus::payload::PayloadTypes::new(
            iface[list]
                .as_array()
                .map(|a| {
                    a.iter()
                        .map(|i| i["typeCode"].as_u64().unwrap_or(0) as u8)
                        .collect()
                })
                .unwrap_or_default(),
        )
    }
    let elements = match elements {
        Ok(e) => e,
        Err(e) => return cmp.fail(at, format!("elements with the {list}: {e}")),
    };
    let theirs = oj
        .get("elements")
        .and_then(Value::as_array)
        .cloned()
        .unwrap_or_default();
    if theirs.len() != elements.len() {
        return cmp.fail(
            at,
            format!("{} elements vs OpenJAUS {}", elements.len(), theirs.len()),
        );
    }
    for (e, o) in elements.iter().zip(&theirs) {
        // OpenJAUS prints 16-bit values through a signed field; compare bit patterns.
        let mine: i128 = match &e.value {
            P::Short(v) | P::ScaledShort(v) => i128::from(*v),
            P::UnsignedShort(v) | P::ScaledUnsignedShort(v) | P::Enumeration(v) => {
                i128::from(*v as i16)
            }
            P::Integer(v) | P::ScaledInteger(v) => i128::from(*v),
            P::UnsignedInteger(v) | P::ScaledUnsignedInteger(v) => i128::from(*v),
            P::Long(v) | P::ScaledLong(v) => i128::from(*v),
            P::UnsignedLong(v) | P::ScaledUnsignedLong(v) => i128::from(*v),
            P::Byte(v) | P::ScaledByte(v) | P::Boolean(v) => i128::from(*v),
            other => return cmp.fail(at, format!("unexpected element value {other:?}")),
        };
        let value = &o["value"];
        let theirs: Option<i128> = value
            .as_i64()
            .map(i128::from)
            .or(value.as_u64().map(i128::from))
            .or(value.as_bool().map(i128::from));
        let same = match (&e.value, theirs) {
            (P::UnsignedShort(_) | P::ScaledUnsignedShort(_) | P::Enumeration(_), Some(t)) => {
                (t as i16) as i128 == mine
            }
            (_, Some(t)) => t == mine,
            _ => false,
        };
        if Some(u64::from(e.index)) != o["index"].as_u64() || !same {
            cmp.fail(
                at,
                format!("element {} = {:?} vs OpenJAUS {o}", e.index, e.value),
            );
        }
    }
}

#[test]
fn openjaus_vectors_decode_reencode_and_match_field_values() {
    let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).expect("definitions validate");
    let mut cmp = Cmp {
        spec: &spec,
        names: name_overrides(),
        errors: Vec::new(),
    };
    let mut per_group: BTreeMap<String, (usize, usize)> = BTreeMap::new();
    let mut uncovered: BTreeMap<String, usize> = BTreeMap::new();
    let vectors = vectors();
    assert_eq!(vectors.len(), 1264, "the full reference set is present");
    for v in &vectors {
        let at = format!("{} [{}]", v.message, v.variant);
        let code = u16::from_le_bytes([v.bytes[2], v.bytes[3]]);
        let Some(def) = spec.message_by_code(code) else {
            // Every message of the reference set must be defined: none is skipped.
            cmp.fail(&at, format!("no definition for command code 0x{code:04X}"));
            *uncovered.entry(v.message.clone()).or_default() += 1;
            continue;
        };
        let entry = per_group.entry(def.group.clone()).or_default();
        entry.0 += 1;
        let before = cmp.errors.len();
        if def.def.name != v.message {
            cmp.fail(&at, format!("code 0x{code:04X} is `{}` here", def.def.name));
        }
        let packet = match Packet::parse(&v.bytes) {
            Ok(p) => p,
            Err(e) => {
                cmp.fail(&at, format!("packet: {e}"));
                continue;
            }
        };
        let message = match Message::decode(packet.header.command_code, &packet.body) {
            Ok(m) => m,
            Err(e) => {
                cmp.fail(&at, format!("decode: {e}"));
                continue;
            }
        };
        let reencoded = Packet {
            header: packet.header,
            body: message.to_bytes().expect("re-encode"),
        };
        let ours = reencoded.to_bytes().unwrap();
        if ours != v.bytes {
            cmp.fail(
                &at,
                format!(
                    "re-encoded bytes differ:\n  vector {}\n  ours   {}",
                    jaus::hex::encode(&v.bytes),
                    jaus::hex::encode(&reencoded.to_bytes().unwrap())
                ),
            );
        }
        let json = serde_json::to_value(&message).unwrap();
        let header = serde_json::to_value(packet.header).unwrap();
        cmp.header(&header, &v.header, &at);
        let empty = Map::new();
        let mine = json["fields"].as_object().unwrap_or(&empty);
        let oj = v.fields.as_object().unwrap_or(&empty);
        let mut oj = oj.clone();
        if let Some(iface) = oj.remove("interfaceDefinition") {
            // Payload data elements: readable only with the interface's type codes.
            check_payload_elements(&mut cmp, &message, &iface, &oj, &at);
            oj.remove("elements");
        }
        cmp.fields(&def.def.name, &def.fields.clone(), mine, &oj, &at);
        if cmp.errors.len() == before {
            entry.1 += 1;
        }
    }
    println!("{:<24} {:>8} {:>8}", "group", "vectors", "passed");
    for (g, (n, ok)) in &per_group {
        println!("{g:<24} {n:>8} {ok:>8}");
    }
    println!(
        "not defined: {} message types, {} vectors",
        uncovered.len(),
        uncovered.values().sum::<usize>()
    );
    if !cmp.errors.is_empty() {
        let shown: Vec<&String> = cmp.errors.iter().take(400).collect();
        panic!(
            "{} conformance failure(s):\n{}",
            cmp.errors.len(),
            shown
                .iter()
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join("\n")
        );
    }
}
