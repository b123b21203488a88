//! Packets as JSON lines: the shape `jaus decode` prints and `jaus encode` reads
//! (`{"header": {...}, "message": NAME, "fields": {...}}`), for tools and consoles.

use crate::codec::Encode;
use crate::messages::Message;
use crate::{Header, Packet};

/// One JSON line of `jaus decode` / `jaus encode`.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
pub struct JsonPacket {
    /// The header.
    pub header: Header,
    /// `"message": "<Name>", "fields": {...}`.
    #[serde(flatten)]
    pub message: Message,
}

/// Decodes one hex packet to a JSON line.
pub fn decode_line(hex: &str) -> Result<String, DecodeLineError> {
    let bytes = crate::hex::decode(hex.trim())?;
    let packet = Packet::parse(&bytes).map_err(DecodeLineError::Packet)?;
    decode_packet(&packet)
}

/// Decodes a parsed packet to a JSON line.
pub fn decode_packet(packet: &Packet) -> Result<String, DecodeLineError> {
    if packet.header.data_flag != crate::wire::DataFlag::Single {
        return Err(DecodeLineError::MultiPacket {
            sequence: packet.header.sequence_number,
            data_flag: packet.header.data_flag,
        });
    }
    let message = Message::decode(packet.header.command_code, &packet.body)
        .map_err(DecodeLineError::Message)?;
    serde_json::to_string(&JsonPacket {
        header: packet.header,
        message,
    })
    .map_err(|e| DecodeLineError::Json(e.to_string()))
}

/// Why a hex packet is not a JSON line ([`decode_line`], [`decode_packet`]): each names
/// what failed (the hex digit and its position, the header field, the message and its
/// field, with their byte offsets).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DecodeLineError {
    /// The line is not hex.
    #[error("bad hex: {0}")]
    Hex(#[from] crate::hex::HexError),
    /// The bytes are not a packet (header too short, data size wrong).
    #[error("{0}")]
    Packet(crate::codec::DecodeError),
    /// The packet is one of a multi-packet message.
    #[error("packet {sequence} of a multi-packet message ({data_flag:?}): reassemble the sequence first")]
    MultiPacket {
        /// Its sequence number.
        sequence: u16,
        /// Its place in the sequence.
        data_flag: crate::wire::DataFlag,
    },
    /// The body is not the message its command code names (the error names the message
    /// and the field).
    #[error("{0}")]
    Message(crate::codec::DecodeError),
    /// The message does not serialise to JSON.
    #[error("{0}")]
    Json(String),
}

/// Why a JSON line is not a message.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum JsonError {
    /// Not JSON.
    #[error("bad JSON: {0}")]
    Syntax(String),
    /// JSON, but not an object with a `"message"` name.
    #[error("a message is a JSON object: {{\"message\": NAME, \"fields\": {{...}}}} (`jaus messages NAME` shows one)")]
    NotAMessage,
    /// No message of that name.
    #[error("no message named `{name}`{}", suggest(.suggestions))]
    UnknownMessage {
        /// The name given.
        name: String,
        /// The closest names of the set.
        suggestions: Vec<&'static str>,
    },
    /// The fields do not fit the message.
    #[error("{message}: {error}")]
    Fields {
        /// The message.
        message: String,
        /// What serde said.
        error: String,
    },
    /// The header part is wrong.
    #[error("header: {0}")]
    Header(String),
}

fn suggest(s: &[&str]) -> String {
    if s.is_empty() {
        String::new()
    } else {
        format!("; did you mean {}?", s.join(", "))
    }
}

/// A header given in JSON: every field may be left out. Defaults are those of
/// [`Header::new`] (priority 6, version 2, no flags, single packet, sequence number 0);
/// the command code is the message's, the data size is computed; a command code that
/// is given (a number or a hex string such as `"0x4402"`) must match the message.
#[derive(Debug, Clone, Default, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeaderInput {
    /// Priority 0–15.
    pub priority: Option<u8>,
    /// ACK/NAK field.
    pub ack_nak: Option<crate::wire::AckNak>,
    /// Service-connection flag.
    pub service_connection: Option<bool>,
    /// Experimental flag.
    pub experimental: Option<bool>,
    /// Version.
    pub version: Option<u8>,
    /// Reserved bits.
    pub reserved: Option<u8>,
    /// Command code (checked against the message).
    #[serde(default, deserialize_with = "code_opt")]
    pub command_code: Option<crate::CommandCode>,
    /// Destination.
    pub destination: Option<crate::Address>,
    /// Source.
    pub source: Option<crate::Address>,
    /// Ignored (computed from the body).
    pub data_size: Option<u16>,
    /// Data flag.
    pub data_flag: Option<crate::wire::DataFlag>,
    /// Sequence number.
    pub sequence_number: Option<u16>,
}

fn code_opt<'de, D: serde::Deserializer<'de>>(
    d: D,
) -> Result<Option<crate::CommandCode>, D::Error> {
    crate::hex::code::deserialize(d).map(Some)
}

impl HeaderInput {
    /// The header of `message`, with `destination`/`source` used where the JSON gave
    /// none.
    pub fn complete(
        &self,
        message: &Message,
        destination: Option<crate::Address>,
        source: Option<crate::Address>,
    ) -> Result<Header, JsonError> {
        self.complete_for(message.code(), message.name(), destination, source)
    }

    /// The header of the message `name` with command code `code` (of any message set,
    /// such as one loaded at run time), with `destination`/`source` used where the JSON
    /// gave none.
    pub fn complete_for(
        &self,
        code: crate::CommandCode,
        name: &str,
        destination: Option<crate::Address>,
        source: Option<crate::Address>,
    ) -> Result<Header, JsonError> {
        if let Some(c) = self.command_code.filter(|c| *c != code) {
            return Err(JsonError::Header(format!(
                "command code {c} does not match message {name} ({code})"
            )));
        }
        let need = |v: Option<crate::Address>, what: &str| {
            v.ok_or_else(|| {
                JsonError::Header(format!(
                    "no {what} address (\"{what}\": [subsystem, node, component, instance])"
                ))
            })
        };
        let mut h = Header::new(
            code,
            need(self.destination.or(destination), "destination")?,
            need(self.source.or(source), "source")?,
        );
        h.priority = self.priority.unwrap_or(h.priority);
        h.ack_nak = self.ack_nak.unwrap_or(h.ack_nak);
        h.service_connection = self.service_connection.unwrap_or(false);
        h.experimental = self.experimental.unwrap_or(false);
        h.version = self.version.unwrap_or(h.version);
        h.reserved = self.reserved.unwrap_or(0);
        h.data_flag = self.data_flag.unwrap_or_default();
        h.sequence_number = self.sequence_number.unwrap_or(0);
        Ok(h)
    }
}

/// Names of the message set closest to `name` (case-insensitive edit distance), best
/// first, at most three.
pub fn closest_names(name: &str) -> Vec<&'static str> {
    closest_of(name, crate::messages::MESSAGES.iter().map(|m| m.name))
}

/// The names of `names` closest to `name` (case-insensitive edit distance), best
/// first, at most three.
pub fn closest_of(name: &str, names: impl Iterator<Item = &'static str>) -> Vec<&'static str> {
    let lower = name.to_ascii_lowercase();
    let mut scored: Vec<(usize, &'static str)> = names
        .map(|n| {
            let l = n.to_ascii_lowercase();
            let d = if l.contains(&lower) || lower.contains(&l) {
                0
            } else {
                distance(&lower, &l)
            };
            (d, n)
        })
        .collect();
    scored.sort();
    let best = scored.first().map_or(0, |s| s.0);
    scored
        .into_iter()
        .filter(|(d, _)| *d <= best.max(1) && *d <= lower.len() / 2 + 1)
        .take(3)
        .map(|(_, n)| n)
        .collect()
}

/// The edit (Levenshtein) distance between `a` and `b`, in characters: what the
/// "did you mean" suggestions of names rank by.
pub fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

/// Reads a message line: `{"message": NAME, "fields": {...}}` (`fields` may be left out
/// for a message without fields; `"message": "Raw"` with `{"code", "body"}` for one the
/// set does not define), optionally with a `"header"` whose fields may all be left out.
/// Other keys (`t`, `utc` of the CLI's output) are ignored, so any line the CLI prints
/// can be read back.
pub fn parse_message(line: &str) -> Result<(HeaderInput, Message), JsonError> {
    let mut v: serde_json::Value =
        serde_json::from_str(line).map_err(|e| JsonError::Syntax(e.to_string()))?;
    let obj = v.as_object_mut().ok_or(JsonError::NotAMessage)?;
    let name = obj
        .get("message")
        .and_then(|m| m.as_str())
        .ok_or(JsonError::NotAMessage)?
        .to_string();
    if name != "Raw" && !crate::messages::MESSAGES.iter().any(|m| m.name == name) {
        return Err(JsonError::UnknownMessage {
            suggestions: closest_names(&name),
            name,
        });
    }
    let header = match obj.remove("header") {
        Some(h) => serde_json::from_value(h).map_err(|e| JsonError::Header(e.to_string()))?,
        None => HeaderInput::default(),
    };
    let fields = obj
        .remove("fields")
        .unwrap_or_else(|| serde_json::Value::Object(Default::default()));
    let m = serde_json::json!({ "message": name, "fields": fields });
    let message = serde_json::from_value(m).map_err(|e| JsonError::Fields {
        message: name,
        error: e.to_string(),
    })?;
    Ok((header, message))
}

/// Why a JSON line does not encode ([`encode_line`], and `jaus_dynamic`'s
/// `Schema::encode_line` for a set loaded at run time): each names what failed (the
/// JSON, the header, the message and its field).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EncodeLineError {
    /// The line is not a message (not JSON, an unknown message, fields that do not fit
    /// the layout), or its header is incomplete.
    #[error("{0}")]
    Json(#[from] JsonError),
    /// The message's body does not encode; the error names the message and field.
    #[error("{0}")]
    Body(crate::codec::EncodeError),
    /// The body of `message` does not encode (the error names the field).
    #[error("{message}: {error}")]
    Message {
        /// The message.
        message: &'static str,
        /// What failed.
        error: crate::codec::EncodeError,
    },
    /// The packet holding the body does not encode (a body too long for one packet).
    #[error("{message}: {error}")]
    Packet {
        /// The message.
        message: &'static str,
        /// What failed.
        error: crate::codec::EncodeError,
    },
}

/// Encodes one JSON line to a hex packet. The data size is computed from the body; the
/// header's other fields default as [`HeaderInput`] says, but the destination and the
/// source must be given.
pub fn encode_line(line: &str) -> Result<String, EncodeLineError> {
    let (header, message) = parse_message(line)?;
    let header = header.complete(&message, None, None)?;
    let name = message.name();
    let body = message
        .to_bytes()
        .map_err(|error| EncodeLineError::Message {
            message: name,
            error,
        })?;
    let bytes = Packet { header, body }
        .to_bytes()
        .map_err(|error| EncodeLineError::Packet {
            message: name,
            error,
        })?;
    Ok(crate::hex::encode(&bytes))
}

/// Three reference packets in OpenJAUS 3.3's byte layout (Report Global Pose, Set Wrench
/// Effort, Set Global Path Segment), used by the tour, the codec benchmark and tests.
pub const REFERENCE_PACKETS: &[(&str, &str)] = &[
    (
        "Report Global Pose, all nine fields",
        "0602024404030201080706051e000000ff016fd12b2a403a75c5dcd125b9333333030a0230ff0040d10015e3227b",
    ),
    ("Set Wrench Effort, all twelve fields", "06020504040302010807060514000000ff0f0a4734f30000480172fd662633000000000d"),
    (
        "Set Global Path Segment 7, both elevations",
        "06020f0404030201080706051d0000000307006fd12b2a403a75c54fcf1db9b7f62b2aee3075c523441fb9c500",
    ),
];

#[cfg(test)]
mod tests {
    use super::*;

    /// Each failure of `decode_line` is its own variant, and its text names what failed.
    #[test]
    fn decode_line_errors_name_what_failed() {
        let pose = REFERENCE_PACKETS[0].1;
        let e = decode_line(&format!("zz{}", &pose[2..])).unwrap_err();
        assert!(matches!(e, DecodeLineError::Hex(_)), "{e:?}");
        assert!(e.to_string().contains("invalid hex digit"), "{e}");

        let e = decode_line(&pose[..10]).unwrap_err();
        assert!(matches!(e, DecodeLineError::Packet(_)), "{e:?}");
        assert!(e.to_string().contains("truncated header"), "{e}");

        // The header says 6 body bytes, and 6 follow: the body ends inside the longitude.
        let short = format!("{}0600{}", &pose[..24], &pose[28..44]);
        let e = decode_line(&short).unwrap_err();
        assert!(matches!(e, DecodeLineError::Message(_)), "{e:?}");
        let text = e.to_string();
        assert!(
            text.contains("ReportGlobalPose") && text.contains("longitude"),
            "{text}"
        );

        let mut first = Packet::parse(&crate::hex::decode(pose).unwrap()).unwrap();
        first.header.data_flag = crate::wire::DataFlag::First;
        let e = decode_packet(&first).unwrap_err();
        assert!(
            matches!(e, DecodeLineError::MultiPacket { sequence: 0, .. }),
            "{e:?}"
        );
        assert!(e.to_string().contains("reassemble"), "{e}");

        assert!(decode_line(pose).is_ok());
    }
}
