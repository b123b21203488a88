//! Floats in JSON: finite values as numbers; NaN and infinities (which JSON numbers
//! cannot hold) as `"NaN"`, `"inf"`, `"-inf"`, or the bit pattern `"0x…"` for other NaNs,
//! so that every value decoded from the wire encodes back to the same bytes.

use serde::{Deserialize, Deserializer, Serializer};

/// A float type the JSON form applies to.
pub trait Float: Copy {
    /// Whether the value is finite.
    fn finite(self) -> bool;
    /// The canonical text of a non-finite value, or its bits.
    fn text(self) -> String;
    /// Parses the text form.
    fn parse(s: &str) -> Option<Self>;
    /// Widens to f64 for JSON.
    fn to_f64(self) -> f64;
    /// Narrows from a JSON number.
    fn from_f64(v: f64) -> Self;
}

macro_rules! float {
    ($t:ty, $bits:ty) => {
        impl Float for $t {
            fn finite(self) -> bool {
                self.is_finite()
            }
            fn text(self) -> String {
                if self.to_bits() == <$t>::NAN.to_bits() {
                    "NaN".into()
                } else if self == <$t>::INFINITY {
                    "inf".into()
                } else if self == <$t>::NEG_INFINITY {
                    "-inf".into()
                } else {
                    format!("0x{:x}", self.to_bits())
                }
            }
            fn parse(s: &str) -> Option<Self> {
                match s {
                    "NaN" => Some(<$t>::NAN),
                    "inf" => Some(<$t>::INFINITY),
                    "-inf" => Some(<$t>::NEG_INFINITY),
                    _ => <$bits>::from_str_radix(s.strip_prefix("0x")?, 16)
                        .ok()
                        .map(<$t>::from_bits),
                }
            }
            fn to_f64(self) -> f64 {
                f64::from(self)
            }
            #[allow(clippy::cast_possible_truncation)]
            fn from_f64(v: f64) -> Self {
                v as $t
            }
        }
    };
}
float!(f32, u32);
float!(f64, u64);

#[derive(Deserialize)]
#[serde(untagged)]
enum Repr {
    Number(f64),
    Text(String),
}

/// Serialises a float.
pub fn serialize<T: Float, S: Serializer>(v: &T, s: S) -> Result<S::Ok, S::Error> {
    if v.finite() {
        s.serialize_f64(v.to_f64())
    } else {
        s.serialize_str(&v.text())
    }
}

/// Deserialises a float.
pub fn deserialize<'de, T: Float, D: Deserializer<'de>>(d: D) -> Result<T, D::Error> {
    match Repr::deserialize(d)? {
        Repr::Number(v) => Ok(T::from_f64(v)),
        Repr::Text(t) => {
            T::parse(&t).ok_or_else(|| serde::de::Error::custom(format!("`{t}` is not a float")))
        }
    }
}

/// The same for optional floats.
pub mod option {
    use super::Float;
    use serde::{Deserializer, Serializer};

    /// Serialises an optional float.
    pub fn serialize<T: Float, S: Serializer>(v: &Option<T>, s: S) -> Result<S::Ok, S::Error> {
        match v {
            Some(v) => super::serialize(v, s),
            None => s.serialize_none(),
        }
    }

    /// Deserialises an optional float.
    pub fn deserialize<'de, T: Float, D: Deserializer<'de>>(d: D) -> Result<Option<T>, D::Error> {
        super::deserialize(d).map(Some)
    }
}
