//! `jaus as4-query` and `jaus as4-send`: any AS-4 message by name, for any definitions.
//!
//! The messages are built and read with the definitions loaded at run time
//! (`jaus-dynamic`): jaus-as4's own (every set of `jaus_as4::DEFS`), with a vendor's YAML on
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
use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Duration;

use jaus_dynamic::{DynMessage, Schema};

use jaus_client::as4_link::{parse_id, schema, As4Link, Incoming};

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

/// `jaus as4-query` (`wait_each`) and `jaus as4-send`.
pub fn as4_talk(args: &As4TalkArgs, wait_each: bool, out: &mut impl Write) -> Result<(), String> {
    let schema = schema(&args.spec, &args.jsidl)?;
    let messages = args
        .messages
        .iter()
        .map(|m| parse(&schema, m))
        .collect::<Result<Vec<_>, _>>()?;
    let me = parse_id(&args.me)?;
    let to = parse_id(&args.to)?;
    let wait = Duration::from_secs_f64(args.wait.clamp(0.0, 3600.0));
    let mut link = As4Link::open(schema, args.peer, args.bind, me)?;
    let mut print = |i: &Incoming| -> Result<(), String> {
        writeln!(out, "{}", i.line()).map_err(|e| e.to_string())
    };
    if let Some(a) = args.control {
        link.take_control(to, a, wait, &mut print)?;
    }
    let mut result = Ok(());
    for m in &messages {
        link.send(to, m)?;
        if wait_each
            && link
                .receive(to, wait, |i| print(i).map(|()| true))?
                .is_none()
        {
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
        link.receive(to, wait, |i| print(i).map(|()| false))?;
    }
    if args.control.is_some() {
        link.release_control(to, wait, &mut print)?;
    }
    result
}
