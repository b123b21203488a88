//! `jaus messages NAME`: one message's fields (type on the wire, unit, range and
//! resolution, presence bit, description) read from the YAML definitions, and an
//! example JSON line that `send`, `query` and `encode` accept.

use std::fmt::Write as _;

use jaus::messages::Message;
use jaus_spec::{Field, Spec, TypeForm, Wire};
use serde_json::{json, Map, Value};

/// The message set's definitions (the SDK's own YAML).
pub fn builtin_spec() -> Result<Spec, String> {
    jaus_spec::load_sdk().map_err(|e| e.to_string())
}

/// The SDK's definitions with a vendor's overlays on them (none: the SDK's alone).
pub fn spec_with(overlays: &[std::path::PathBuf]) -> Result<Spec, String> {
    if overlays.is_empty() {
        return builtin_spec();
    }
    jaus_spec::load_overlays(overlays).map_err(|e| format!("--spec: {e}"))
}

/// A definition file as a user should see it: the SDK's own files by name (they are
/// built into the binary, and the directory they were built from is the build
/// machine's), a vendor's overlay as its path was given.
fn shown_path(path: &std::path::Path) -> (String, &'static str) {
    match path.strip_prefix(jaus_spec::defs_dir()) {
        Ok(rel) => (rel.display().to_string(), " (the SDK's definitions)"),
        Err(_) => (path.display().to_string(), ""),
    }
}

fn wire_text(w: &Wire) -> String {
    match w {
        Wire::Int(i) => i.rust().to_string(),
        Wire::F32 => "f32".into(),
        Wire::F64 => "f64".into(),
        Wire::Scaled { int, .. } => format!("scaled {}", int.rust()),
        Wire::Named { name, size, .. } => match size {
            Some(s) => format!("{name} ({} size)", s.rust()),
            None => name.clone(),
        },
        Wire::Str(l) => format!("string ({})", len_text(l)),
        Wire::Bytes(l) => format!("bytes ({})", len_text(l)),
        Wire::List { count, elem } => match count {
            Some(c) => format!("list of {} ({} count)", wire_text(elem), c.rust()),
            None => format!("list of {} (to the end)", wire_text(elem)),
        },
        Wire::ListField { field, elem, .. } => {
            format!("list of {} (count in `{field}`)", wire_text(elem))
        }
        Wire::Flag => "flag (presence bit only)".into(),
        Wire::Packet { .. } => "embedded message".into(),
    }
}

fn len_text(l: &jaus_spec::Len) -> String {
    match l {
        jaus_spec::Len::Fixed { n, .. } => format!("{n} bytes"),
        jaus_spec::Len::Prefix(i) => format!("{} length", i.rust()),
        jaus_spec::Len::Rest { .. } => "to the end".into(),
        jaus_spec::Len::Nul => "NUL-terminated".into(),
    }
}

fn range_text(w: &Wire) -> String {
    match w {
        Wire::Scaled { int, lo, hi } => {
            format!("[{lo}, {hi}] step {:.3e}", (hi - lo) / int.divisor())
        }
        _ => String::new(),
    }
}

/// An example value of a field (in range, every optional field present).
fn example(spec: &Spec, w: &Wire, depth: usize) -> Value {
    if depth > 8 {
        return Value::Null;
    }
    match w {
        Wire::Int(_) => json!(0),
        Wire::F32 | Wire::F64 => json!(0.0),
        Wire::Scaled { lo, hi, .. } => json!(if *lo <= 0.0 && *hi >= 0.0 { 0.0 } else { *lo }),
        Wire::Str(_) => json!(""),
        Wire::Bytes(_) => json!(""),
        Wire::List { .. } | Wire::ListField { .. } => json!([]),
        Wire::Flag => json!(false),
        Wire::Packet { .. } => Value::Null,
        Wire::Named { name, .. } => match spec.ty(name).map(|t| &t.form) {
            Some(TypeForm::Record { fields, .. }) => Value::Object(object(spec, fields, depth + 1)),
            Some(TypeForm::Enum { .. }) => spec
                .ty(name)
                .and_then(|t| t.def.values.first())
                .map_or(Value::Null, |v| json!(v.name)),
            Some(TypeForm::Bitfield { members, .. }) => Value::Object(
                members
                    .iter()
                    .map(|m| {
                        let v = if m.def.bit.is_some() {
                            json!(false)
                        } else {
                            json!(0)
                        };
                        (m.def.name.clone(), v)
                    })
                    .collect(),
            ),
            _ => Value::Null,
        },
    }
}

fn object(spec: &Spec, fields: &[Field], depth: usize) -> Map<String, Value> {
    fields
        .iter()
        .map(|f| (f.def.name.clone(), example(spec, &f.wire, depth)))
        .filter(|(_, v)| !v.is_null())
        .collect()
}

/// The description of message `name` (or an error suggesting the closest names).
pub fn describe(spec: &Spec, name: &str) -> Result<String, String> {
    let m = spec
        .messages
        .iter()
        .find(|m| m.def.name == name || m.def.name.eq_ignore_ascii_case(name))
        .ok_or_else(|| {
            let near = jaus::json::closest_names(name);
            if near.is_empty() {
                format!("no message named `{name}` (`jaus messages` lists them)")
            } else {
                format!(
                    "no message named `{name}`; did you mean {}?",
                    near.join(", ")
                )
            }
        })?;
    let mut s = String::new();
    let title = m
        .def
        .title
        .clone()
        .unwrap_or_else(|| jaus_spec::title_of(&m.def.name));
    let _ = writeln!(
        s,
        "{} ({}), {} — group {}",
        m.def.name, m.def.code, title, m.group
    );
    if let Some(d) = &m.def.description {
        let _ = writeln!(s, "  {}", d.trim());
    }
    if let Some(r) = spec.report_of(&m.def) {
        let _ = writeln!(s, "  answered by {} ({})", r.def.name, r.def.code);
    }
    let src = &spec.sources[m.source];
    let (file, whose) = shown_path(&src.path);
    let _ = writeln!(
        s,
        "  defined in {file}:{}{whose}",
        src.index.find(&format!("{}.name", m.path)).line
    );
    if let Some(p) = m.presence {
        let _ = writeln!(
            s,
            "  presence vector: {} (computed from the fields present)",
            p.rust()
        );
    }
    if m.fields.is_empty() {
        let _ = writeln!(s, "  no fields");
    } else {
        let _ = writeln!(
            s,
            "  {:<28} {:<34} {:<8} {:<32} {:<4} description",
            "field", "type", "unit", "range", "bit"
        );
        for f in &m.fields {
            let _ = writeln!(
                s,
                "  {:<28} {:<34} {:<8} {:<32} {:<4} {}",
                f.def.name,
                wire_text(&f.wire),
                f.def.unit.as_deref().unwrap_or(""),
                range_text(&f.wire),
                f.def.bit.map_or(String::new(), |b| b.to_string()),
                f.def.description.as_deref().unwrap_or("").trim()
            );
        }
    }
    let example =
        json!({"message": m.def.name, "fields": Value::Object(object(spec, &m.fields, 0))});
    match serde_json::from_value::<Message>(example.clone()) {
        Ok(msg) => {
            let _ = writeln!(
                s,
                "example (every optional field present):\n  {}",
                serde_json::to_string(&msg).unwrap_or_default()
            );
        }
        Err(_) => {
            let _ = writeln!(s, "example (fill in the values):\n  {example}");
        }
    }
    Ok(s)
}
