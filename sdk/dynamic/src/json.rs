//! JSON → [`Value`], checked against a layout: the forms the generated types read
//! through serde (enumerations by name or `{"Unknown": n}`, bit fields as objects,
//! unions as `{"Variant": value}` or `"Variant"`, bytes as hex, non-finite floats as
//! text), with an error naming the field path (`ReportTanks.tanks[1].level`).

use crate::schema::{Body, FormLayout, Layouts, WireLayout};
use crate::value::Value;
use jaus::codec::serde_float::Float;
use jaus_spec::Int;
use serde_json::Value as Json;

/// A JSON value that does not fit its field: the field path and what was wrong.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct FieldError {
    pub(crate) path: String,
    pub(crate) error: String,
}

type Result<T> = std::result::Result<T, FieldError>;

fn err<T>(path: &str, error: impl Into<String>) -> Result<T> {
    Err(FieldError {
        path: path.to_string(),
        error: error.into(),
    })
}

fn kind(j: &Json) -> &'static str {
    match j {
        Json::Null => "null",
        Json::Bool(_) => "a boolean",
        Json::Number(_) => "a number",
        Json::String(_) => "a string",
        Json::Array(_) => "an array",
        Json::Object(_) => "an object",
    }
}

/// The fields of a message body (`{}` for a message without fields).
pub(crate) fn body(l: &Layouts, b: &Body, j: &Json, path: &str) -> Result<Value> {
    let Json::Object(obj) = j else {
        return err(
            path,
            format!("expected an object of fields, found {}", kind(j)),
        );
    };
    if let Some(k) = obj
        .keys()
        .find(|k| !b.fields.iter().any(|f| f.name == k.as_str()))
    {
        let names: Vec<&str> = b.fields.iter().map(|f| f.name).collect();
        return err(
            path,
            if names.is_empty() {
                format!("unknown field `{k}`: this has no fields")
            } else {
                format!("unknown field `{k}`, expected one of {}", names.join(", "))
            },
        );
    }
    let mut out = Vec::with_capacity(b.fields.len());
    for f in &b.fields {
        let p = format!("{path}.{}", f.name);
        match obj.get(f.name) {
            Some(Json::Null) | None if f.is_optional() => {}
            None => return err(&p, "missing field"),
            Some(x) => out.push((f.name, value(l, &f.wire, x, &p)?)),
        }
    }
    Ok(Value::Record(out))
}

fn value(l: &Layouts, w: &WireLayout, j: &Json, path: &str) -> Result<Value> {
    match w {
        WireLayout::Int(i) => int(*i, j, path),
        WireLayout::F32 => float::<f32>(j, path).map(Value::F32),
        WireLayout::F64 => float::<f64>(j, path).map(Value::F64),
        WireLayout::Scaled(..) => match j.as_f64() {
            Some(v) => Ok(Value::Real(v)),
            None => err(path, format!("expected a number, found {}", kind(j))),
        },
        WireLayout::Flag => match j {
            Json::Bool(b) => Ok(Value::Bool(*b)),
            _ => err(path, format!("expected true or false, found {}", kind(j))),
        },
        WireLayout::Str(_) => match j {
            Json::String(s) => Ok(Value::Text(s.clone())),
            _ => err(path, format!("expected a string, found {}", kind(j))),
        },
        WireLayout::Bytes(_) => match j {
            Json::String(s) => jaus::hex::decode(s)
                .map(Value::Bytes)
                .or_else(|e| err(path, format!("bad hex: {e}"))),
            _ => err(path, format!("expected a hex string, found {}", kind(j))),
        },
        WireLayout::List { elem, .. } | WireLayout::ListVar { elem, .. } => match j {
            Json::Array(items) => items
                .iter()
                .enumerate()
                .map(|(i, x)| value(l, elem, x, &format!("{path}[{i}]")))
                .collect::<Result<Vec<_>>>()
                .map(Value::List),
            _ => err(path, format!("expected an array, found {}", kind(j))),
        },
        WireLayout::Packet { .. } => serde_json::from_value::<jaus::Packet>(j.clone())
            .map(Value::Packet)
            .or_else(|e| err(path, e.to_string())),
        WireLayout::Named { ty, .. } => named(l, *ty, j, path),
    }
}

fn int(i: Int, j: &Json, path: &str) -> Result<Value> {
    let out_of_range = || err(path, format!("{j} does not fit a {}", i.rust()));
    if i.unsigned() {
        match j.as_u64() {
            Some(v) if crate::ints::fits_u(i, v) => Ok(Value::UInt(v)),
            Some(_) => out_of_range(),
            None if j.is_number() => out_of_range(),
            None => err(path, format!("expected an integer, found {}", kind(j))),
        }
    } else {
        match j.as_i64() {
            Some(v) if crate::ints::fits_i(i, v) => Ok(Value::Int(v)),
            Some(_) => out_of_range(),
            None if j.is_number() => out_of_range(),
            None => err(path, format!("expected an integer, found {}", kind(j))),
        }
    }
}

fn float<T: Float>(j: &Json, path: &str) -> Result<T> {
    match j {
        Json::Number(n) => match n.as_f64() {
            Some(v) => Ok(T::from_f64(v)),
            None => err(path, "expected a number"),
        },
        Json::String(s) => match T::parse(s) {
            Some(v) => Ok(v),
            None => err(
                path,
                format!(
                    "`{s}` is not a float (a number, \"NaN\", \"inf\", \"-inf\" or \"0x<bits>\")"
                ),
            ),
        },
        _ => err(path, format!("expected a number, found {}", kind(j))),
    }
}

fn named(l: &Layouts, ty: usize, j: &Json, path: &str) -> Result<Value> {
    let Some(t) = l.types.get(ty) else {
        return err(path, "type not in the definitions");
    };
    match &t.form {
        FormLayout::Record(b) => body(l, b, j, path),
        FormLayout::Enum { repr, values } => match j {
            Json::String(s) => match values.iter().find(|(n, _)| *n == s.as_str()) {
                Some((n, v)) => Ok(Value::Enum(n, *v)),
                None => err(
                    path,
                    format!(
                        "unknown value `{s}`, expected one of {} or {{\"Unknown\": n}}",
                        values.iter().map(|v| v.0).collect::<Vec<_>>().join(", ")
                    ),
                ),
            },
            Json::Object(o) if o.len() == 1 && o.contains_key("Unknown") => {
                match int(*repr, &o["Unknown"], &format!("{path}.Unknown"))? {
                    Value::UInt(v) => Ok(match values.iter().find(|(_, x)| *x == v) {
                        // A named value given by number is that value.
                        Some((n, _)) => Value::Enum(n, v),
                        None => Value::UnknownEnum(v),
                    }),
                    _ => err(path, "an enumeration's value is unsigned"),
                }
            }
            _ => err(
                path,
                format!(
                    "expected a value name or {{\"Unknown\": n}}, found {}",
                    kind(j)
                ),
            ),
        },
        FormLayout::Bits { repr, members, .. } => {
            let Json::Object(o) = j else {
                return err(
                    path,
                    format!("expected an object of bits, found {}", kind(j)),
                );
            };
            if let Some(k) = o
                .keys()
                .find(|k| k.as_str() != "reserved" && !members.iter().any(|m| m.0 == k.as_str()))
            {
                return err(
                    path,
                    format!(
                        "unknown member `{k}`, expected one of {}",
                        members.iter().map(|m| m.0).collect::<Vec<_>>().join(", ")
                    ),
                );
            }
            let mut out = Vec::with_capacity(members.len());
            for &(name, _, _, _, flag) in members {
                let p = format!("{path}.{name}");
                let Some(x) = o.get(name) else {
                    return err(&p, "missing member");
                };
                out.push((
                    name,
                    if flag {
                        value(l, &WireLayout::Flag, x, &p)?
                    } else {
                        int(Int::U64, x, &p)?
                    },
                ));
            }
            let reserved = match o.get("reserved") {
                None => 0,
                Some(x) => match int(*repr, x, &format!("{path}.reserved"))? {
                    Value::UInt(v) => v,
                    _ => 0,
                },
            };
            Ok(Value::Bits(out, reserved))
        }
        FormLayout::Union { variants, .. } => {
            let names = || variants.iter().map(|v| v.0).collect::<Vec<_>>().join(", ");
            let (name, payload) = match j {
                Json::String(s) => (s.as_str(), None),
                Json::Object(o) if o.len() == 1 => {
                    let (k, v) = o
                        .iter()
                        .next()
                        .map(|(k, v)| (k.as_str(), v))
                        .unwrap_or(("", j));
                    (k, Some(v))
                }
                _ => {
                    return err(
                        path,
                        format!(
                            "expected {{\"Variant\": value}} (one of {}), found {}",
                            names(),
                            kind(j)
                        ),
                    )
                }
            };
            let Some(v) = variants.iter().find(|v| v.0 == name) else {
                return err(
                    path,
                    format!("unknown variant `{name}`, expected one of {}", names()),
                );
            };
            match (&v.3, payload) {
                (Some(w), Some(x)) => {
                    let x = value(l, w, x, &format!("{path}.{name}"))?;
                    Ok(Value::Union(v.0, Some(Box::new(x))))
                }
                (None, None) => Ok(Value::Union(v.0, None)),
                (Some(_), None) => err(
                    path,
                    format!("variant `{name}` holds a value: {{\"{name}\": value}}"),
                ),
                (None, Some(_)) => err(
                    path,
                    format!("variant `{name}` holds no value: write \"{name}\""),
                ),
            }
        }
    }
}
