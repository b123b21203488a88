//! A decoded value of any field, and its JSON form: the same text the generated types
//! print through serde, field for field.

use serde::ser::{SerializeMap, SerializeSeq, Serializer};
use serde::Serialize;

/// The value of a field, record or whole message body, typed by its layout.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// An unsigned integer (`u8` … `u64`).
    UInt(u64),
    /// A signed integer (`i16` … `i64`).
    Int(i64),
    /// An IEEE-754 single.
    F32(f32),
    /// An IEEE-754 double.
    F64(f64),
    /// The real value of a scaled integer.
    Real(f64),
    /// A presence-vector flag, or a one-bit member of a bit field.
    Bool(bool),
    /// 8-bit text (ISO-8859-1).
    Text(String),
    /// Opaque bytes (hex in JSON).
    Bytes(Vec<u8>),
    /// A list.
    List(Vec<Value>),
    /// A record or message body: its fields in wire order; optional fields that are
    /// absent are left out.
    Record(Vec<(&'static str, Value)>),
    /// A named value of an enumeration, with its wire value.
    Enum(&'static str, u64),
    /// A value the enumeration does not name (`{"Unknown": n}` in JSON).
    UnknownEnum(u64),
    /// A bit field: its members in definition order, and the undefined bits as
    /// received (`reserved`, left out of JSON when zero).
    Bits(Vec<(&'static str, Value)>, u64),
    /// A union: the variant's name and its value (none for a tag-only variant).
    Union(&'static str, Option<Box<Value>>),
    /// A whole embedded JAUS message with its header.
    Packet(jaus::Packet),
}

impl Value {
    /// The field `name` of a record.
    pub fn field(&self, name: &str) -> Option<&Value> {
        match self {
            Value::Record(f) => f.iter().find(|(n, _)| *n == name).map(|(_, v)| v),
            _ => None,
        }
    }

    /// The value as an unsigned integer (integers, flags, enumerations).
    pub fn as_u64(&self) -> Option<u64> {
        match self {
            Value::UInt(v) => Some(*v),
            Value::Int(v) => u64::try_from(*v).ok(),
            Value::Bool(b) => Some(u64::from(*b)),
            Value::Enum(_, v) | Value::UnknownEnum(v) => Some(*v),
            _ => None,
        }
    }

    /// The real value of a float or scaled field.
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::F32(v) => Some(f64::from(*v)),
            Value::F64(v) | Value::Real(v) => Some(*v),
            Value::UInt(v) => Some(*v as f64),
            Value::Int(v) => Some(*v as f64),
            _ => None,
        }
    }
}

impl Serialize for Value {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Value::UInt(v) => s.serialize_u64(*v),
            Value::Int(v) => s.serialize_i64(*v),
            Value::F32(v) => jaus::codec::serde_float::serialize(v, s),
            Value::F64(v) => jaus::codec::serde_float::serialize(v, s),
            Value::Real(v) => s.serialize_f64(*v),
            Value::Bool(v) => s.serialize_bool(*v),
            Value::Text(v) => s.serialize_str(v),
            Value::Bytes(v) => s.serialize_str(&jaus::hex::encode(v)),
            Value::List(items) => {
                let mut seq = s.serialize_seq(Some(items.len()))?;
                for i in items {
                    seq.serialize_element(i)?;
                }
                seq.end()
            }
            Value::Record(fields) => {
                let mut map = s.serialize_map(Some(fields.len()))?;
                for (k, v) in fields {
                    map.serialize_entry(k, v)?;
                }
                map.end()
            }
            Value::Enum(name, _) => s.serialize_str(name),
            Value::UnknownEnum(v) => {
                let mut map = s.serialize_map(Some(1))?;
                map.serialize_entry("Unknown", v)?;
                map.end()
            }
            Value::Bits(members, reserved) => {
                let n = members.len() + usize::from(*reserved != 0);
                let mut map = s.serialize_map(Some(n))?;
                for (k, v) in members {
                    map.serialize_entry(k, v)?;
                }
                if *reserved != 0 {
                    map.serialize_entry("reserved", reserved)?;
                }
                map.end()
            }
            Value::Union(name, None) => s.serialize_str(name),
            Value::Union(name, Some(v)) => {
                let mut map = s.serialize_map(Some(1))?;
                map.serialize_entry(name, v)?;
                map.end()
            }
            Value::Packet(p) => p.serialize(s),
        }
    }
}
