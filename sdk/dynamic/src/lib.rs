//! Messages of a definition set loaded at run time.
//!
//! The generated SDK knows the messages it was built with. A tool that must speak a
//! vendor's experimental messages without being rebuilt — the `jaus` CLI with
//! `--spec vendor.yaml`, an operator station, a test harness — loads the vendor's
//! overlay (on the SDK's own definitions) into a [`Schema`] and decodes and encodes
//! every message of the union by its layout:
//!
//! ```
//! let schema = jaus_dynamic::Schema::sdk().unwrap();
//! let m = schema
//!     .from_json("SetTravelSpeed", &serde_json::json!({"speed": 2.0}))
//!     .unwrap();
//! let body = schema.encode(&m).unwrap();
//! assert_eq!(body, [13, 0]); // 2 m/s in a u16 over [0, 10000] m/s
//! let back = schema.decode(m.code, &body).unwrap();
//! let speed = back.fields.field("speed").and_then(|v| v.as_f64()).unwrap();
//! assert!((speed - 2.0).abs() < 10_000.0 / 65_535.0);
//! ```
//!
//! One source of truth: the layouts come from the same YAML, validated by the same
//! `jaus-spec`, as the generated types; the byte rules are the SDK codec's own
//! functions (`jaus::codec`: scaled integers, counts, strings, presence vectors), called
//! through a walk of the layout instead of through derived code. The JSON is the one
//! the generated types give through serde, text for text. The test suite holds both
//! to that on every OpenJAUS reference vector of all 160 messages (`tests/equal.rs`):
//! the same JSON line, and the same bytes back.

mod decode;
mod encode;
mod intern;
mod ints;
mod json;
mod overlay;
mod schema;
mod value;

pub use overlay::load_overlaid;
pub use schema::MessageLayout;
pub use value::Value;

use jaus::codec::{DecodeError, DecodeErrorKind, EncodeError};
pub use jaus::json::DecodeLineError;
use jaus::json::{HeaderInput, JsonError};
use jaus::{CommandCode, Header, Packet, PacketRef, RawMessage};
use jaus_spec::{Spec, SpecErrors};
use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;
use std::path::Path;

/// The messages of a definition set, decoded and encoded by their layouts.
#[derive(Debug)]
pub struct Schema {
    layouts: schema::Layouts,
}

/// A message of a [`Schema`]: its name, command code and fields.
#[derive(Debug, Clone, PartialEq)]
pub struct DynMessage {
    /// The message's name.
    pub name: &'static str,
    /// Its command code.
    pub code: CommandCode,
    /// Its fields ([`Value::Record`]).
    pub fields: Value,
}

impl Schema {
    /// The schema of a validated definition set.
    pub fn from_spec(spec: &Spec) -> Schema {
        Schema {
            layouts: schema::compile(spec),
        }
    }

    /// The SDK's own definitions.
    pub fn sdk() -> Result<Schema, SpecErrors> {
        let spec = jaus_spec::load_sdk()?;
        Ok(Schema::from_spec(&spec))
    }

    /// The SDK's definitions with a vendor's overlay files on them (as a vendor's
    /// build loads them: `extends: jaus` by default). Errors name the file and line.
    pub fn load<P: AsRef<Path>>(overlays: &[P]) -> Result<Schema, SpecErrors> {
        let spec = jaus_spec::load_overlays(overlays)?;
        Ok(Schema::from_spec(&spec))
    }

    /// Every message, in definition order.
    pub fn messages(&self) -> impl Iterator<Item = &MessageLayout> {
        self.layouts.messages.iter()
    }

    /// The message named `name`.
    pub fn message(&self, name: &str) -> Option<&MessageLayout> {
        self.layouts
            .by_name
            .get(name)
            .map(|&i| &self.layouts.messages[i])
    }

    /// The message with command code `code`.
    pub fn by_code(&self, code: CommandCode) -> Option<&MessageLayout> {
        self.layouts
            .by_code
            .get(&code.0)
            .map(|&i| &self.layouts.messages[i])
    }

    /// Decodes a body of the message with command code `code`; a code the schema does
    /// not define is [`DecodeErrorKind::UnknownCommandCode`].
    pub fn decode(&self, code: CommandCode, body: &[u8]) -> Result<DynMessage, DecodeError> {
        let m = self.by_code(code).ok_or_else(|| {
            DecodeError::new(DecodeErrorKind::UnknownCommandCode { code: code.0 }, 0)
        })?;
        let fields = decode::message::<decode::Tree>(&self.layouts, &m.body, body)
            .map_err(|e| e.in_message(m.name))?;
        Ok(DynMessage {
            name: m.name,
            code: m.code,
            fields,
        })
    }

    /// Checks a body of the message with command code `code` as [`Schema::decode`]
    /// does — every check, in the same order, with the same error — without making its
    /// values (nothing is allocated but for text and embedded packets). What passes
    /// decodes; what fails, fails to decode with this error. Gives the message's
    /// layout.
    pub fn check(&self, code: CommandCode, body: &[u8]) -> Result<&MessageLayout, DecodeError> {
        let m = self.by_code(code).ok_or_else(|| {
            DecodeError::new(DecodeErrorKind::UnknownCommandCode { code: code.0 }, 0)
        })?;
        decode::message::<decode::Check>(&self.layouts, &m.body, body)
            .map_err(|e| e.in_message(m.name))?;
        Ok(m)
    }

    /// Encodes a message's body.
    pub fn encode(&self, m: &DynMessage) -> Result<Vec<u8>, EncodeError> {
        let layout = self
            .by_code(m.code)
            .ok_or(EncodeError::ValueKind { field: m.name })?;
        encode::message(&self.layouts, layout.name, &layout.body, &m.fields)
    }

    /// The message `name` with the fields `fields` (a JSON object, as `jaus decode`
    /// prints them), checked against its layout.
    pub fn from_json(
        &self,
        name: &str,
        fields: &serde_json::Value,
    ) -> Result<DynMessage, JsonError> {
        let m = self
            .message(name)
            .ok_or_else(|| JsonError::UnknownMessage {
                name: name.to_string(),
                suggestions: jaus::json::closest_of(name, self.messages().map(|m| m.name)),
            })?;
        let fields =
            json::body(&self.layouts, &m.body, fields, m.name).map_err(|e| JsonError::Fields {
                message: m.name.to_string(),
                error: format!("{}: {}", e.path, e.error),
            })?;
        Ok(DynMessage {
            name: m.name,
            code: m.code,
            fields,
        })
    }

    /// Reads a message line as `jaus::json::parse_message` does, for every message of
    /// this schema: `{"message": NAME, "fields": {...}}` (`fields` may be left out for
    /// a message without fields; `"message": "Raw"` with `{"code", "body"}`), with an
    /// optional `"header"`; other keys are ignored. A raw message is returned as the
    /// schema's message when its code is one.
    pub fn parse_line(&self, line: &str) -> Result<(HeaderInput, Parsed), JsonError> {
        let mut v: serde_json::Value =
            serde_json::from_str(line).map_err(|e| JsonError::Syntax(e.to_string()))?;
        let obj = v.as_object_mut().ok_or(JsonError::NotAMessage)?;
        let name = obj
            .get("message")
            .and_then(|m| m.as_str())
            .ok_or(JsonError::NotAMessage)?
            .to_string();
        let header = match obj.remove("header") {
            Some(h) => serde_json::from_value(h).map_err(|e| JsonError::Header(e.to_string()))?,
            None => HeaderInput::default(),
        };
        let fields = obj
            .remove("fields")
            .unwrap_or_else(|| serde_json::Value::Object(Default::default()));
        if name == "Raw" && self.message("Raw").is_none() {
            let raw: RawMessage =
                serde_json::from_value(fields).map_err(|e| JsonError::Fields {
                    message: name,
                    error: e.to_string(),
                })?;
            return Ok((header, Parsed::Raw(raw)));
        }
        Ok((header, Parsed::Message(self.from_json(&name, &fields)?)))
    }

    /// Encodes one JSON line to a hex packet, as `jaus encode` does.
    pub fn encode_line(&self, line: &str) -> Result<String, EncodeLineError> {
        let (header, parsed) = self.parse_line(line)?;
        let (name, raw) = self.to_raw(&parsed).map_err(EncodeLineError::Body)?;
        let header = header.complete_for(raw.code, name, None, None)?;
        let bytes = jaus::codec::Encode::to_bytes(&Packet {
            header,
            body: raw.body,
        })
        .map_err(|error| EncodeLineError::Packet {
            message: name,
            error,
        })?;
        Ok(jaus::hex::encode(&bytes))
    }

    /// The code and body of a parsed message, with its name.
    pub fn to_raw(&self, parsed: &Parsed) -> Result<(&'static str, RawMessage), EncodeError> {
        match parsed {
            Parsed::Message(m) => Ok((
                m.name,
                RawMessage {
                    code: m.code,
                    body: self.encode(m)?,
                },
            )),
            Parsed::Raw(r) => Ok(("Raw", r.clone())),
        }
    }

    /// Decodes one hex packet to a JSON line, as `jaus decode` does; the errors are
    /// those of the generated decoder ([`jaus::json::decode_line`]).
    pub fn decode_line(&self, hex: &str) -> Result<String, DecodeLineError> {
        let bytes = jaus::hex::decode(hex.trim())?;
        let packet = PacketRef::parse(&bytes).map_err(DecodeLineError::Packet)?;
        self.decode_packet(packet)
    }

    /// Decodes a packet to the JSON line `jaus decode` prints: `{"header": {...},
    /// "message": NAME, "fields": {...}}`; a code this schema does not define is printed
    /// as `"message": "Raw"` with its code and body.
    pub fn decode_packet(&self, packet: PacketRef<'_>) -> Result<String, DecodeLineError> {
        if packet.header.data_flag != jaus::wire::DataFlag::Single {
            return Err(DecodeLineError::MultiPacket {
                sequence: packet.header.sequence_number,
                data_flag: packet.header.data_flag,
            });
        }
        let fields = self
            .fields_json(packet.header.command_code, packet.body)
            .map_err(DecodeLineError::Message)?;
        serde_json::to_string(&Line {
            header: &packet.header,
            fields: &fields,
        })
        .map_err(|e| DecodeLineError::Json(e.to_string()))
    }

    /// The `"message"` and `"fields"` of a body as JSON, as the generated types print
    /// them (`"Raw"` for a code this schema does not define).
    pub fn fields_json(&self, code: CommandCode, body: &[u8]) -> Result<Decoded, DecodeError> {
        match self.by_code(code) {
            Some(_) => self.decode(code, body).map(Decoded::Message),
            None => Ok(Decoded::Raw(RawMessage {
                code,
                body: body.to_vec(),
            })),
        }
    }
}

/// Why a JSON line does not encode ([`Schema::encode_line`]): the SDK's type, shared
/// with `jaus::json::encode_line`.
pub use jaus::json::EncodeLineError;

/// A message line read by [`Schema::parse_line`].
#[derive(Debug, Clone, PartialEq)]
pub enum Parsed {
    /// A message of the schema.
    Message(DynMessage),
    /// `"message": "Raw"`: a code and body given as they are.
    Raw(RawMessage),
}

/// A body decoded by [`Schema::fields_json`]: serialises as `"message": NAME, "fields":
/// {...}` inside a line.
#[derive(Debug, Clone, PartialEq)]
pub enum Decoded {
    /// A message of the schema.
    Message(DynMessage),
    /// A code the schema does not define.
    Raw(RawMessage),
}

impl Decoded {
    /// Writes `"message"` and `"fields"` into a JSON object being serialised.
    pub fn serialize_entries<M: SerializeMap>(&self, map: &mut M) -> Result<(), M::Error> {
        match self {
            Decoded::Message(m) => {
                map.serialize_entry("message", m.name)?;
                map.serialize_entry("fields", &m.fields)
            }
            Decoded::Raw(r) => {
                map.serialize_entry("message", "Raw")?;
                map.serialize_entry("fields", r)
            }
        }
    }
}

/// `{"header": ..., "message": ..., "fields": ...}`.
struct Line<'a> {
    header: &'a Header,
    fields: &'a Decoded,
}

impl Serialize for Line<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(3))?;
        map.serialize_entry("header", self.header)?;
        self.fields.serialize_entries(&mut map)?;
        map.end()
    }
}
