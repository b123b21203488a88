//! Hexadecimal text for packets and blobs (CLI input/output, JSON).

/// Lowercase hex of `bytes`.
pub fn encode(bytes: &[u8]) -> String {
    const DIGITS: &[u8; 16] = b"0123456789abcdef";
    let mut s = String::with_capacity(bytes.len() * 2);
    for b in bytes {
        s.push(DIGITS[usize::from(b >> 4)] as char);
        s.push(DIGITS[usize::from(b & 15)] as char);
    }
    s
}

/// Why a hex string could not be read.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum HexError {
    /// Odd number of digits.
    #[error("odd number of hex digits ({0})")]
    OddLength(usize),
    /// A character that is not a hex digit.
    #[error("invalid hex digit {ch:?} at position {at}")]
    BadDigit {
        /// The character.
        ch: char,
        /// Its index.
        at: usize,
    },
}

/// Bytes of a hex string; whitespace is ignored.
pub fn decode(s: &str) -> Result<Vec<u8>, HexError> {
    let digits: Vec<(usize, char)> = s
        .char_indices()
        .filter(|(_, c)| !c.is_whitespace())
        .collect();
    if digits.len() % 2 != 0 {
        return Err(HexError::OddLength(digits.len()));
    }
    let val = |(at, ch): (usize, char)| {
        ch.to_digit(16)
            .map(|d| d as u8)
            .ok_or(HexError::BadDigit { ch, at })
    };
    digits
        .chunks(2)
        .map(|p| Ok(val(p[0])? << 4 | val(p[1])?))
        .collect()
}

/// `#[serde(with = "jaus::hex::serde")]` for `Vec<u8>` fields: a hex string in JSON.
#[cfg(feature = "serde")]
pub mod serde {
    use serde::{Deserialize, Deserializer, Serializer};

    /// Serialises bytes as a hex string.
    pub fn serialize<S: Serializer>(v: &[u8], s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&super::encode(v))
    }

    /// Deserialises bytes from a hex string.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<u8>, D::Error> {
        let s = String::deserialize(d)?;
        super::decode(&s).map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn round_trip() {
        let b = [0u8, 1, 0xab, 0xff];
        assert_eq!(super::decode(&super::encode(&b)).unwrap(), b);
        assert!(super::decode("abc").is_err());
        assert!(super::decode("zz").is_err());
    }
}

/// `#[serde(with = "jaus::hex::serde_opt")]` for `Option<Vec<u8>>` fields.
#[cfg(feature = "serde")]
pub mod serde_opt {
    use serde::{Deserialize, Deserializer, Serializer};

    /// Serialises present bytes as a hex string.
    pub fn serialize<S: Serializer>(v: &Option<Vec<u8>>, s: S) -> Result<S::Ok, S::Error> {
        match v {
            Some(b) => s.serialize_str(&super::encode(b)),
            None => s.serialize_none(),
        }
    }

    /// Deserialises optional bytes from a hex string.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Vec<u8>>, D::Error> {
        let s = Option::<String>::deserialize(d)?;
        s.map(|s| super::decode(&s).map_err(serde::de::Error::custom))
            .transpose()
    }
}

/// `#[serde(with = "jaus::hex::code")]` for a [`CommandCode`](crate::CommandCode): written
/// as a number, read from a number or a hex string (`"0x4402"`).
#[cfg(feature = "serde")]
pub mod code {
    use crate::CommandCode;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    /// Serialises the code as a number.
    pub fn serialize<S: Serializer>(c: &CommandCode, s: S) -> Result<S::Ok, S::Error> {
        c.0.serialize(s)
    }

    /// Deserialises a code from a number or a `0x` hex string.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<CommandCode, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Code {
            Number(u16),
            Text(String),
        }
        match Code::deserialize(d)? {
            Code::Number(n) => Ok(CommandCode(n)),
            Code::Text(t) => parse(&t).map_err(serde::de::Error::custom),
        }
    }

    /// Parses hex with a `0x` prefix (`0x4402`) or a decimal number.
    pub fn parse(t: &str) -> Result<CommandCode, String> {
        let t = t.trim();
        let r = match t.strip_prefix("0x").or_else(|| t.strip_prefix("0X")) {
            Some(h) => u16::from_str_radix(h, 16),
            None => t.parse(),
        };
        r.map(CommandCode)
            .map_err(|_| format!("`{t}` is not a command code (a number, or hex as \"0x4402\")"))
    }
}
