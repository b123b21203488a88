//! `jaus as4-query` and `jaus as4-send`: any AS-4 message by name, for any definitions.
//!
//! The messages are built and read with the definitions loaded at run time
//! (`jaus-dynamic`): jaus-as4's own (Core v1.1 and Mobility), with a vendor's YAML on
//! them (`--spec`), or a set imported from JSIDL instead (`--jsidl`). They travel over
//! AS5669A on UDP to one component; every message the component sends back is printed as
//! a JSON line (`{"t": seconds, "from": "S.N.C", "message": NAME, "fields": {...}}`).
//! With `--control` the tool takes control of the component first (Request Control at
//! that authority, refused: an error naming the answer) and gives it back at the end.
//!
//! `as4-query` sends each message and waits for the component's answer before the next
//! (an error when none came within `--wait`); `as4-send` sends them all and prints what
//! arrives for `--wait` seconds.

use std::io::Write;
use std::net::{SocketAddr, UdpSocket};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use jaus::net::as5669a::{As4Config, As4Id, As4Message, As4Stack};
use jaus::CommandCode;
use jaus_dynamic::{Decoded, DynMessage, Schema, Value};

/// Options of `jaus as4-query` and `jaus as4-send`.
#[derive(Debug, clap::Args)]
pub struct As4TalkArgs {
    /// The component's node (its AS5669A socket).
    #[arg(long)]
    pub peer: SocketAddr,
    /// Local address to send from.
    #[arg(long, default_value = "0.0.0.0:0")]
    pub bind: SocketAddr,
    /// This tool's AS-4 id.
    #[arg(long, default_value = "42.1.1")]
    pub me: String,
    /// The component's AS-4 id (subsystem.node.component).
    #[arg(long)]
    pub to: String,
    /// Directories of YAML definitions loaded on jaus-as4's (a vendor's messages and
    /// services, `extends: as4`). Not `--spec`: that is the RA 3.3 overlay of every
    /// command.
    #[arg(id = "as4_spec", long = "as4-spec", value_name = "DIR")]
    pub spec: Vec<PathBuf>,
    /// Directories of JSIDL to import and use instead of jaus-as4's definitions (give
    /// every set the services need, e.g. Core v1.1 with the vendor's).
    #[arg(long, conflicts_with = "as4_spec")]
    pub jsidl: Vec<PathBuf>,
    /// Take control at this authority before the messages, give it back after.
    #[arg(long)]
    pub control: Option<u8>,
    /// Seconds to wait: for each answer (`as4-query`), or after the last message
    /// (`as4-send`).
    #[arg(long, default_value_t = 2.0)]
    pub wait: f64,
    /// Messages: {"message": "QueryStatus"}, {"message": "SetElement", "fields": {...}}.
    #[arg(required = true)]
    pub messages: Vec<String>,
}

/// The definitions the tool reads messages with: jaus-as4's and `spec`, or `jsidl`.
pub fn schema(spec: &[PathBuf], jsidl: &[PathBuf]) -> Result<Schema, String> {
    as4_spec(spec, jsidl).map(|spec| Schema::from_spec(&spec))
}

/// The AS-4 definitions: jaus-as4's built-in ones with the YAML of the directories
/// `spec` on them, or the JSIDL of the directories `jsidl` imported instead.
pub fn as4_spec(spec: &[PathBuf], jsidl: &[PathBuf]) -> Result<jaus_spec::Spec, String> {
    let loaded = if jsidl.is_empty() {
        let base: Vec<(PathBuf, String)> = jaus_as4::DEFS
            .iter()
            .map(|(name, text)| (Path::new("jaus-as4/defs").join(name), text.to_string()))
            .collect();
        let mut own = Vec::new();
        for dir in spec {
            let entries = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
            let mut files: Vec<PathBuf> = entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|x| x == "yaml" || x == "yml"))
                .collect();
            files.sort();
            for f in files {
                let text =
                    std::fs::read_to_string(&f).map_err(|e| format!("{}: {e}", f.display()))?;
                own.push((f, text));
            }
        }
        jaus_spec::load_texts(base.into_iter().chain(own).collect())
    } else {
        let import = jaus_jsidl::import(jsidl).map_err(|e| e.to_string())?;
        jaus_spec::load_texts(import.texts(Path::new("jsidl")))
    };
    loaded.map_err(|e| e.to_string())
}

/// A message as the command line gives it.
fn parse(schema: &Schema, line: &str) -> Result<DynMessage, String> {
    let v: serde_json::Value =
        serde_json::from_str(line).map_err(|e| format!("`{line}`: not JSON: {e}"))?;
    let name = v
        .get("message")
        .and_then(|m| m.as_str())
        .ok_or_else(|| format!("`{line}`: no \"message\""))?;
    let fields = v.get("fields").cloned().unwrap_or(serde_json::json!({}));
    schema.from_json(name, &fields).map_err(|e| e.to_string())
}

/// One component over AS5669A on UDP.
struct Link<'s> {
    schema: &'s Schema,
    socket: UdpSocket,
    stack: As4Stack<SocketAddr>,
    peer: SocketAddr,
    me: As4Id,
    to: As4Id,
    start: Instant,
}

impl Link<'_> {
    fn send(&mut self, m: &DynMessage) -> Result<(), String> {
        let body = self
            .schema
            .encode(m)
            .map_err(|e| format!("{}: {e}", m.name))?;
        self.send_raw(m.code, body)
    }

    fn send_raw(&mut self, code: CommandCode, body: Vec<u8>) -> Result<(), String> {
        self.stack.send(
            self.peer,
            &[As4Message::new(code.0, self.to, self.me, body)],
        );
        while let Some(d) = self.stack.poll_transmit() {
            self.socket
                .send_to(&d.bytes, d.to)
                .map_err(|e| format!("{}: {e}", self.peer))?;
        }
        Ok(())
    }

    /// The messages from the component within `wait`, each printed as it comes;
    /// returns at the first for which `stop` says yes (with it), or `None` at the end.
    fn receive(
        &mut self,
        wait: Duration,
        out: &mut impl Write,
        mut stop: impl FnMut(CommandCode, &Decoded) -> bool,
    ) -> Result<Option<Decoded>, String> {
        let until = Instant::now() + wait;
        let mut buf = vec![0u8; 65536];
        loop {
            let left = until.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Ok(None);
            }
            let _ = self.socket.set_read_timeout(Some(left));
            let Ok((n, from)) = self.socket.recv_from(&mut buf) else {
                continue;
            };
            let Ok(messages) = self.stack.receive(Instant::now(), from, &buf[..n]) else {
                continue;
            };
            for m in messages {
                if m.source != self.to {
                    continue;
                }
                let code = CommandCode(m.message_id);
                let decoded = match self.schema.fields_json(code, &m.body) {
                    Ok(d) => d,
                    Err(e) => {
                        writeln!(
                            out,
                            "{}",
                            serde_json::json!({
                                "t": self.start.elapsed().as_secs_f64(),
                                "from": m.source.to_string(),
                                "error": format!("{:#06X}: {e}", code.0),
                            })
                        )
                        .map_err(|e| e.to_string())?;
                        continue;
                    }
                };
                self.print(out, m.source, &decoded)?;
                if stop(code, &decoded) {
                    return Ok(Some(decoded));
                }
            }
        }
    }

    fn print(&self, out: &mut impl Write, from: As4Id, d: &Decoded) -> Result<(), String> {
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
        let line = Line(self.start.elapsed().as_secs_f64(), from.to_string(), d);
        let text = serde_json::to_string(&line).map_err(|e| e.to_string())?;
        writeln!(out, "{text}").map_err(|e| e.to_string())
    }

    /// Request Control at `authority`: Ok when accepted, else the answer as the error.
    fn take_control(
        &mut self,
        authority: u8,
        wait: Duration,
        out: &mut impl Write,
    ) -> Result<(), String> {
        let request = self
            .schema
            .from_json(
                "RequestControl",
                &serde_json::json!({ "authority_code": authority }),
            )
            .map_err(|e| e.to_string())?;
        self.send(&request)?;
        let confirm = self.schema.message("ConfirmControl").map(|m| m.code);
        let answer = self.receive(wait, out, |code, _| Some(code) == confirm)?;
        match answer {
            Some(Decoded::Message(m)) => {
                // Confirm Control's response code: 0 is Control Accepted.
                let code = m.fields.field("response_code");
                match code.and_then(Value::as_u64) {
                    Some(0) => Ok(()),
                    _ => Err(format!(
                        "control of {} refused: {}",
                        self.to,
                        match code {
                            Some(Value::Enum(name, v)) => format!("{name} ({v})"),
                            Some(v) => format!("{v:?}"),
                            None => "no response code".into(),
                        }
                    )),
                }
            }
            _ => Err(format!(
                "no Confirm Control from {} at {} within {:.1} s",
                self.to,
                self.peer,
                wait.as_secs_f64()
            )),
        }
    }
}

/// `jaus as4-query` (`wait_each`) and `jaus as4-send`.
pub fn as4_talk(args: &As4TalkArgs, wait_each: bool, out: &mut impl Write) -> Result<(), String> {
    let schema = schema(&args.spec, &args.jsidl)?;
    let messages = args
        .messages
        .iter()
        .map(|m| parse(&schema, m))
        .collect::<Result<Vec<_>, _>>()?;
    let me = jaus_conform::as4::parse_id(&args.me)?;
    let to = jaus_conform::as4::parse_id(&args.to)?;
    let wait = Duration::from_secs_f64(args.wait.clamp(0.0, 3600.0));
    let socket = UdpSocket::bind(args.bind).map_err(|e| format!("{}: {e}", args.bind))?;
    let mut link = Link {
        schema: &schema,
        socket,
        stack: As4Stack::new(As4Config::default()),
        peer: args.peer,
        me,
        to,
        start: Instant::now(),
    };
    if let Some(a) = args.control {
        link.take_control(a, wait, out)?;
    }
    let mut result = Ok(());
    for m in &messages {
        link.send(m)?;
        if wait_each && link.receive(wait, out, |_, _| true)?.is_none() {
            result = Err(format!(
                "{} to {} at {}: no answer within {:.1} s",
                m.name,
                to,
                args.peer,
                wait.as_secs_f64()
            ));
            break;
        }
    }
    if !wait_each {
        link.receive(wait, out, |_, _| false)?;
    }
    if args.control.is_some() {
        if let Some(release) = schema.message("ReleaseControl") {
            let code = release.code;
            link.send_raw(code, Vec::new())?;
            let reject = schema.message("RejectControl").map(|m| m.code);
            link.receive(wait, out, |c, _| Some(c) == reject)?;
        }
    }
    result
}
