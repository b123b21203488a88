//! What the CLI prints: every message addressed to it as a timestamped JSON line, read
//! off the datagrams before the hosts take them.

use std::time::{Instant, SystemTime, UNIX_EPOCH};

use jaus::json::JsonPacket;
use jaus::messages::Message;
use jaus::net::framing::Reassembler;
use jaus::net::Framing;
use jaus::wire::AckNak;
use jaus::{Address, Header};

/// An acknowledgement line (ACK/NAK carry no body).
#[derive(Debug, serde::Serialize)]
pub(super) struct AckLine<'a> {
    pub(super) t: f64,
    pub(super) utc: f64,
    pub(super) header: &'a Header,
    /// The message acknowledged.
    pub(super) acknowledges: &'a str,
}

/// A packet addressed to the CLI that did not decode.
#[derive(Debug, serde::Serialize)]
pub(super) struct RawLine<'a> {
    pub(super) t: f64,
    pub(super) utc: f64,
    pub(super) header: &'a Header,
    pub(super) error: String,
    pub(super) body: String,
}

/// What the tap saw of one datagram.
pub(super) enum Tapped {
    Packet(Box<JsonPacket>),
    Ack(Header),
    Raw(Header, Vec<u8>, String),
}

/// Reads what arrives for the CLI, before the hosts do, so that every message is
/// printed with its real header (flags, service-connection sequence numbers) and ACK/NAK
/// replies are seen.
pub(super) struct Tap {
    pub(super) me: Address,
    pub(super) framing: Framing,
    pub(super) reassembler: Reassembler,
}

impl Tap {
    /// A datagram for a component of this tool's node that is not this tool: another
    /// node with the same subsystem and node id is on the network.
    pub(super) fn foreign_twin(&self, datagram: &[u8]) -> Option<Address> {
        let (h, _) = self.framing.packet(datagram).ok()?;
        let d = h.destination;
        (d.subsystem == self.me.subsystem
            && d.node == self.me.node
            && d.component != 255
            && d.instance != 255
            && d.component != 1
            && d != self.me)
            .then_some(d)
    }

    pub(super) fn see(&mut self, now: Instant, datagram: &[u8]) -> Option<Tapped> {
        let (header, body) = self.framing.packet(datagram).ok()?;
        if !header.destination.matches(&self.me) || header.source == self.me {
            return None;
        }
        if matches!(header.ack_nak, AckNak::Ack | AckNak::Nak) {
            return Some(Tapped::Ack(header));
        }
        let (header, body) = self.reassembler.message(now, &header, body)?;
        Some(match Message::decode(header.command_code, &body) {
            Ok(message) => Tapped::Packet(Box::new(JsonPacket { header, message })),
            Err(e) => Tapped::Raw(header, body, e.to_string()),
        })
    }
}

pub(super) fn unix_now() -> f64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64())
}
