//! AS5669A, JUDP version 2: the transport of the SAE AS-4 JAUS Service Sets, sans-IO,
//! beside RA 3.3's JUDP on the same socket (docs/wire.md, "AS5669A (JUDP version 2)").
//!
//! * [`header`]: the general transport header as typed values ([`As4Header`],
//!   [`As4Id`], the flag enums) and one message on the wire ([`As4Packet`]: header,
//!   payload whose first two bytes are the message ID, trailing sequence number).
//! * [`message`]: a whole message ([`As4Message`]): addresses, transport flags, message
//!   ID and body, what the sans-IO [`As4Stack`] takes and hands on.
//! * [`datagram`]: a datagram is the version byte 2 followed by one or more messages:
//!   [`parse_datagram`] reads all of them, [`write_datagrams`] packs several into each
//!   datagram up to a size bound; [`Generation::of`] tells the generations apart by the
//!   first byte.
//! * [`split`](mod@split): a payload larger than the per-packet limit becomes first /
//!   normal / last packets with consecutive sequence numbers ([`split()`]); the
//!   acknowledgement of a packet is a pure function ([`ack`], [`nak`]).
//! * [`reassembly`]: the bounded [`As4Reassembler`] (the byte and time bounds of the RA
//!   3.3 [`Reassembler`](super::Reassembler), one rule for both).
//! * [`client`]: an AS-4 client as a participant ([`As4Client`]), for tools and tests.
//! * [`mux`]: one socket, both generations: [`As4Mux`] wraps a host (a
//!   [`Node`](super::Node)) and hands version-2 datagrams to an [`As4Endpoint`] the host
//!   supplies, framing its replies as AS5669A to the sender from the same socket.
//!
//! Every multi-byte field is little-endian, as the AS-4 messages themselves are (RA 3.3
//! and its JUDP length are the other way round). Nothing here panics on any bytes:
//! every malformed input is an [`As4Error`].

pub mod client;
pub mod datagram;
pub mod error;
pub mod header;
pub mod message;
pub mod mux;
pub mod reassembly;
pub mod split;
pub mod stack;

#[cfg(test)]
mod proptests;

pub use client::As4Client;
pub use datagram::{parse_datagram, write_datagrams, Generation, VERSION};
pub use error::As4Error;
pub use header::{
    AckNak, As4Header, As4Id, As4IdParseError, As4Packet, Broadcast, DataControl, HcRequest,
    Priority, HC_LEN, HEADER_LEN, JAUS_MESSAGE_TYPE, MAX_PAYLOAD, OVERHEAD, SEQUENCE_LEN,
};
pub use message::As4Message;
pub use mux::{As4Endpoint, As4Mux, As4Send, As4Side};
pub use reassembly::{As4Reassembler, As4ReassemblyLimits};
pub use split::{ack, nak, split};
pub use stack::{As4Config, As4Stack, As4Stats};
