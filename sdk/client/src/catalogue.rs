//! The messages the CLI speaks: the SDK's generated set, plus those of the vendor
//! overlays given with `--spec FILE` (loaded at run time with `jaus-dynamic`, on the
//! SDK's definitions, as a vendor's build loads them).
//!
//! A standard message keeps its typed path through the SDK. A vendor message is encoded
//! from its JSON by its layout and travels as a [`RawMessage`] (the node and the
//! session carry it unchanged); what arrives with a vendor code is printed by name with
//! its fields, in the same JSON form the vendor's generated crate prints.

use std::path::PathBuf;

use jaus::json::JsonPacket;
use jaus::messages::Message;
use jaus::wire::MessageClass;
use jaus::{Address, CommandCode, Header, MessageInfo, PacketRef, RawMessage};
use jaus_dynamic::{Decoded, Parsed, Schema};
use serde::ser::{SerializeMap, Serializer};
use serde::Serialize;

/// The message set of one CLI run.
#[derive(Debug, Default)]
pub struct Catalogue {
    /// The SDK's definitions with the overlays on them; `None` without `--spec`.
    schema: Option<Schema>,
}

/// An unknown message name, said without `--spec`: a vendor's message is known only
/// with its overlay, so the error says how to give it.
pub fn with_overlay_hint(error: String, overlays: bool) -> String {
    if overlays || !error.starts_with("no message named") {
        return error;
    }
    format!("{error} (the SDK's messages only: a vendor's experimental message needs its YAML overlay, e.g. --spec defs/my_vehicle.yaml)")
}

impl Catalogue {
    /// The SDK's messages only.
    pub fn sdk() -> Catalogue {
        Catalogue::default()
    }

    /// The SDK's messages and those of `overlays` (none: the SDK's only). Errors name
    /// the file and line of the YAML.
    pub fn load(overlays: &[PathBuf]) -> Result<Catalogue, String> {
        if overlays.is_empty() {
            return Ok(Catalogue::sdk());
        }
        let schema = Schema::load(overlays).map_err(|e| format!("--spec: {e}"))?;
        Ok(Catalogue {
            schema: Some(schema),
        })
    }

    /// The schema of the overlays, if any were given.
    pub fn schema(&self) -> Option<&Schema> {
        self.schema.as_ref()
    }

    /// The overlays' own messages: (code, name, report of a query).
    pub fn own_messages(&self) -> Vec<(CommandCode, &'static str, Option<&'static str>)> {
        let Some(s) = &self.schema else {
            return Vec::new();
        };
        s.messages()
            .filter(|m| m.own)
            .map(|m| {
                (
                    m.code,
                    m.name,
                    m.report.and_then(|r| s.by_code(r)).map(|r| r.name),
                )
            })
            .collect()
    }

    /// A message of an overlay (not of the SDK) with this code.
    fn own(&self, code: CommandCode) -> Option<&jaus_dynamic::MessageLayout> {
        self.schema.as_ref()?.by_code(code).filter(|m| m.own)
    }

    /// `jaus decode`: one hex packet to a JSON line.
    pub fn decode_line(&self, hex: &str) -> Result<String, String> {
        match &self.schema {
            Some(s) => s.decode_line(hex).map_err(|e| e.to_string()),
            None => jaus::json::decode_line(hex).map_err(|e| e.to_string()),
        }
    }

    /// A whole (reassembled) packet to a JSON line.
    pub fn decode_packet(&self, packet: PacketRef<'_>) -> Result<String, String> {
        match &self.schema {
            Some(s) => s.decode_packet(packet).map_err(|e| e.to_string()),
            None => jaus::json::decode_packet(&jaus::Packet {
                header: packet.header,
                body: packet.body.to_vec(),
            })
            .map_err(|e| e.to_string()),
        }
    }

    /// `jaus encode`: one JSON line to a hex packet.
    pub fn encode_line(&self, line: &str) -> Result<String, String> {
        match &self.schema {
            Some(s) => s.encode_line(line).map_err(|e| e.to_string()),
            None => {
                jaus::json::encode_line(line).map_err(|e| with_overlay_hint(e.to_string(), false))
            }
        }
    }

    /// A message given to `send`/`query`/`watch`, with the destination of its header if
    /// it has one. An overlay's message becomes a [`Message::Raw`] of its encoded body.
    pub fn parse_message(&self, json: &str) -> Result<(Option<Address>, Message), String> {
        let Some(s) = &self.schema else {
            return parse_message(json).map_err(|e| with_overlay_hint(e, false));
        };
        let (header, parsed) = s.parse_line(json).map_err(|e| e.to_string())?;
        match &parsed {
            Parsed::Message(m) if self.own(m.code).is_some() => {
                let (_, raw) = s.to_raw(&parsed).map_err(|e| format!("{}: {e}", m.name))?;
                Ok((header.destination, Message::Raw(raw)))
            }
            // The SDK's own messages keep their typed form (control is tracked on it).
            _ => parse_message(json),
        }
    }

    /// The name of the message with this code, in the SDK or an overlay.
    pub fn name_of(&self, code: CommandCode) -> Option<&'static str> {
        match self.own(code) {
            Some(m) => Some(m.name),
            None => MessageInfo::of(code).map(|i| i.name),
        }
    }

    /// The code of the message named `name`, in the SDK or an overlay.
    pub fn code_of(&self, name: &str) -> Option<CommandCode> {
        jaus::messages::MESSAGES
            .iter()
            .find(|m| m.name == name)
            .map(|m| m.code)
            .or_else(|| self.schema.as_ref()?.message(name).map(|m| m.code))
    }

    /// The class of a code: an overlay's explicit `class:` for its experimental codes,
    /// else the standard's range.
    pub fn class_of(&self, code: CommandCode) -> MessageClass {
        match self.own(code).map(|m| m.class) {
            Some(jaus_spec::MessageClass::Command) => MessageClass::Command,
            Some(jaus_spec::MessageClass::Query) => MessageClass::Query,
            Some(jaus_spec::MessageClass::Inform) => MessageClass::Inform,
            _ => code.class(),
        }
    }

    /// The code of the report answering a query (an overlay's `report:`, the SDK's
    /// table, or the complement rule); `None` for other messages.
    pub fn answer_of(&self, code: CommandCode) -> Option<CommandCode> {
        if let Some(m) = self.own(code) {
            return m.report;
        }
        if code.class() != MessageClass::Query {
            return None;
        }
        MessageInfo::of(code)
            .and_then(|i| i.report)
            .and_then(|r| self.code_of(r))
            .or(code.complement())
    }

    /// A received packet as the CLI prints it: `{"t", "utc", "header", "message",
    /// "fields"}`; a raw message with an overlay's code is printed by name with its
    /// fields (or raw, with the decode error, when its body does not fit its layout).
    pub fn print_line(&self, t: f64, utc: f64, packet: &JsonPacket) -> String {
        let body = match (&packet.message, &self.schema) {
            (Message::Raw(r), Some(s)) if self.own(r.code).is_some() => {
                match s.decode(r.code, &r.body) {
                    Ok(m) => Body::Decoded(Decoded::Message(m)),
                    Err(e) => Body::Raw(r, e.to_string()),
                }
            }
            _ => return serde_json::to_string(&TypedLine { t, utc, packet }).unwrap_or_default(),
        };
        serde_json::to_string(&Printed {
            t,
            utc,
            header: &packet.header,
            body,
        })
        .unwrap_or_default()
    }
}

/// A line of a message of the SDK's set.
#[derive(Serialize)]
struct TypedLine<'a> {
    t: f64,
    utc: f64,
    #[serde(flatten)]
    packet: &'a JsonPacket,
}

/// One printed line.
struct Printed<'a> {
    t: f64,
    utc: f64,
    header: &'a Header,
    body: Body<'a>,
}

enum Body<'a> {
    Decoded(Decoded),
    Raw(&'a RawMessage, String),
}

impl Serialize for Printed<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(None)?;
        map.serialize_entry("t", &self.t)?;
        map.serialize_entry("utc", &self.utc)?;
        map.serialize_entry("header", self.header)?;
        match &self.body {
            Body::Decoded(d) => d.serialize_entries(&mut map)?,
            Body::Raw(r, e) => {
                map.serialize_entry("message", "Raw")?;
                map.serialize_entry("fields", r)?;
                map.serialize_entry("error", e)?;
            }
        }
        map.end()
    }
}

/// A message given to the CLI, in the shape [`jaus::json::parse_message`] reads
/// (`{"message": NAME, "fields": {...}}`, `fields` optional, or a whole line as `jaus
/// decode` prints it); the destination of its header, if it has one, is returned.
pub fn parse_message(json: &str) -> Result<(Option<Address>, Message), String> {
    let (header, message) = jaus::json::parse_message(json).map_err(|e| e.to_string())?;
    Ok((header.destination, message))
}
