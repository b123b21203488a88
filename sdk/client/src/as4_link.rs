//! An AS-4 client over AS5669A on UDP, for any definitions loaded at run time: messages
//! built from their names and JSON fields, every message received decoded by the same
//! definitions. `jaus as4-query`/`as4-send` and Python's
//! `jaus.As4Client` talk through it.

use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::{Duration, Instant};

use jaus::net::as5669a::{As4Config, As4Id, As4Message};
use jaus::CommandCode;
use jaus_dynamic::{Decoded, DynMessage, Schema, Value};

use crate::as4_socket::As4Socket;

/// An AS-4 id from `subsystem.node.component`, the error as text naming the part.
pub fn parse_id(text: &str) -> Result<As4Id, String> {
    text.parse()
        .map_err(|e: jaus::net::as5669a::As4IdParseError| e.to_string())
}

/// A message received from a component: when (seconds since the link opened), from
/// whom, and what it is (or why it did not decode).
#[derive(Debug)]
pub struct Incoming {
    /// Seconds since the link opened.
    pub t: f64,
    /// The sender.
    pub from: As4Id,
    /// Its message ID.
    pub code: CommandCode,
    /// The message, or why its body does not decode with the definitions.
    pub decoded: Result<Decoded, String>,
}

/// A decoded message as a JSON line, its keys in the documented order.
struct Line<'a>(f64, String, &'a Decoded);

impl serde::Serialize for Line<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = s.serialize_map(None)?;
        map.serialize_entry("t", &self.0)?;
        map.serialize_entry("from", &self.1)?;
        self.2.serialize_entries(&mut map)?;
        map.end()
    }
}

impl Incoming {
    /// `{"t", "from", "message", "fields"}`, or `{"t", "from", "error"}`.
    pub fn json(&self) -> serde_json::Value {
        match &self.decoded {
            Ok(d) => serde_json::to_value(Line(self.t, self.from.to_string(), d))
                .unwrap_or_else(|e| serde_json::json!({ "t": self.t, "error": e.to_string() })),
            Err(_) => self.error_json(),
        }
    }

    /// [`json`](Self::json) as one line of text, the keys in that order (`t`, `from`,
    /// `message`, `fields`), as `jaus as4-query` prints it.
    pub fn line(&self) -> String {
        match &self.decoded {
            Ok(d) => {
                serde_json::to_string(&Line(self.t, self.from.to_string(), d)).unwrap_or_else(|e| {
                    serde_json::json!({ "t": self.t, "error": e.to_string() }).to_string()
                })
            }
            Err(_) => self.error_json().to_string(),
        }
    }

    fn error_json(&self) -> serde_json::Value {
        let why = match &self.decoded {
            Err(e) => e.as_str(),
            Ok(_) => "",
        };
        serde_json::json!({
            "t": self.t,
            "from": self.from.to_string(),
            "error": format!("{:#06X}: {why}", self.code.0),
        })
    }

    /// The message's name, when it decoded as a message of the definitions.
    pub fn name(&self) -> Option<&str> {
        match &self.decoded {
            Ok(Decoded::Message(m)) => Some(m.name),
            _ => None,
        }
    }
}

/// One AS-4 client endpoint: its id, its socket ([`As4Socket`], on the SDK's one I/O
/// loop), the peer node it talks to.
#[derive(Debug)]
pub struct As4Link {
    schema: Schema,
    socket: As4Socket,
    me: As4Id,
    start: Instant,
}

impl As4Link {
    /// A client `me` on a socket bound to `bind`, talking to the node at `peer`, reading
    /// and writing messages with `schema`.
    pub fn open(
        schema: Schema,
        peer: SocketAddr,
        bind: SocketAddr,
        me: As4Id,
    ) -> Result<Self, String> {
        Ok(Self {
            schema,
            socket: As4Socket::bind(bind, peer, As4Config::default())?,
            me,
            start: Instant::now(),
        })
    }

    /// The definitions.
    pub fn schema(&self) -> &Schema {
        &self.schema
    }

    /// The message `name` with `fields` (JSON, by field name).
    pub fn message(&self, name: &str, fields: &serde_json::Value) -> Result<DynMessage, String> {
        self.schema
            .from_json(name, fields)
            .map_err(|e| e.to_string())
    }

    /// Sends `m` to component `to`.
    pub fn send(&mut self, to: As4Id, m: &DynMessage) -> Result<(), String> {
        let body = self
            .schema
            .encode(m)
            .map_err(|e| format!("{}: {e}", m.name))?;
        self.send_raw(to, m.code, body)
    }

    /// Sends message `code` with `body` to component `to`.
    pub fn send_raw(&mut self, to: As4Id, code: CommandCode, body: Vec<u8>) -> Result<(), String> {
        self.socket
            .send(&[As4Message::new(code.0, to, self.me, body)])
    }

    /// The messages from `from` until `wait` has passed, each handed to `each`; returns
    /// at the first for which `each` answers true (with it), or `None` at the end.
    /// Messages from other components are skipped.
    pub fn receive(
        &mut self,
        from: As4Id,
        wait: Duration,
        mut each: impl FnMut(&Incoming) -> Result<bool, String>,
    ) -> Result<Option<Incoming>, String> {
        let until = Instant::now() + wait;
        while let Some(m) = self.socket.next(until)? {
            if m.source != from {
                continue;
            }
            let code = CommandCode(m.message_id);
            let incoming = Incoming {
                t: self.start.elapsed().as_secs_f64(),
                from: m.source,
                code,
                decoded: self
                    .schema
                    .fields_json(code, &m.body)
                    .map_err(|e| e.to_string()),
            };
            if each(&incoming)? {
                return Ok(Some(incoming));
            }
        }
        Ok(None)
    }

    /// Request Control of `to` at `authority`: Ok when accepted, else the answer as the
    /// error. Every message received meanwhile is handed to `each`.
    pub fn take_control(
        &mut self,
        to: As4Id,
        authority: u8,
        wait: Duration,
        mut each: impl FnMut(&Incoming) -> Result<(), String>,
    ) -> Result<(), String> {
        let request = self.message(
            "RequestControl",
            &serde_json::json!({ "authority_code": authority }),
        )?;
        self.send(to, &request)?;
        let confirm = self.schema.message("ConfirmControl").map(|m| m.code);
        let answer = self.receive(to, wait, |i| {
            each(i)?;
            Ok(Some(i.code) == confirm)
        })?;
        match answer.map(|i| i.decoded) {
            Some(Ok(Decoded::Message(m))) => {
                // Confirm Control's response code: 0 is Control Accepted.
                let code = m.fields.field("response_code");
                match code.and_then(Value::as_u64) {
                    Some(0) => Ok(()),
                    _ => Err(format!(
                        "control of {to} refused: {}",
                        match code {
                            Some(Value::Enum(name, v)) => format!("{name} ({v})"),
                            Some(v) => format!("{v:?}"),
                            None => "no response code".into(),
                        }
                    )),
                }
            }
            _ => Err(format!(
                "no Confirm Control from {to} at {} within {:.1} s",
                self.socket.peer(),
                wait.as_secs_f64()
            )),
        }
    }

    /// Release Control of `to`; waits for its Reject Control (Control Released) at most
    /// `wait`, handing every message received meanwhile to `each`.
    pub fn release_control(
        &mut self,
        to: As4Id,
        wait: Duration,
        mut each: impl FnMut(&Incoming) -> Result<(), String>,
    ) -> Result<(), String> {
        let Some(release) = self.schema.message("ReleaseControl").map(|m| m.code) else {
            return Err("the definitions have no Release Control".into());
        };
        self.send_raw(to, release, Vec::new())?;
        let reject = self.schema.message("RejectControl").map(|m| m.code);
        self.receive(to, wait, |i| {
            each(i)?;
            Ok(Some(i.code) == reject)
        })?;
        Ok(())
    }
}

/// The definitions the tool reads messages with: jaus-as4's and `spec`, or `jsidl`.
pub fn schema(spec: &[PathBuf], jsidl: &[PathBuf]) -> Result<Schema, String> {
    as4_spec(spec, jsidl).map(|spec| Schema::from_spec(&spec))
}

/// The AS-4 definitions: jaus-as4's built-in ones with the YAML of the directories
/// `spec` on them, or the JSIDL of the directories `jsidl` imported instead.
pub fn as4_spec(spec: &[PathBuf], jsidl: &[PathBuf]) -> Result<jaus_spec::Spec, String> {
    jaus_dynamic::load_overlaid(jaus_as4::DEFS, "jaus-as4/defs", spec, jsidl)
}
