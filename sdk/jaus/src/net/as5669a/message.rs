//! A whole AS-4 message ([`As4Message`]): what the sans-IO [`As4Stack`](super::As4Stack)
//! hands on and takes, and what an [`As4Endpoint`](super::As4Endpoint) of the
//! [`As4Mux`](super::As4Mux) answers; its packets' header and payload.

use super::header::{AckNak, As4Header, As4Id, As4Packet, Broadcast, DataControl, Priority};

/// A whole AS-4 message: addresses, transport flags, message ID and body.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct As4Message {
    /// Destination.
    pub destination: As4Id,
    /// Source.
    pub source: As4Id,
    /// Priority.
    pub priority: Priority,
    /// Broadcast: [`Broadcast::Global`] when [`new`](Self::new) is given a destination
    /// that [names several components](As4Id::is_broadcast), else none.
    pub broadcast: Broadcast,
    /// Whether the sender asks for an acknowledgement of every packet.
    pub ack_requested: bool,
    /// The message ID (e.g. 0x2B00 Query Identification).
    pub message_id: u16,
    /// The message after its ID.
    pub body: Vec<u8>,
}

impl As4Message {
    /// Message `message_id` with `body` from `source` to `destination`, standard
    /// priority, no acknowledgement asked. A destination that names several
    /// components (0xFFFF subsystem, 0xFF node or component:
    /// [`As4Id::is_broadcast`]) makes it a global broadcast, as every sender of such a
    /// message must mark it; any other destination, no broadcast. This is the one
    /// place the field is chosen: senders do not set it themselves.
    ///
    /// ```
    /// use jaus::net::as5669a::{As4Id, As4Message, Broadcast};
    /// let me = As4Id::new(42, 1, 1);
    /// let all = As4Message::new(0x2B00, As4Id::new(0xFFFF, 0xFF, 0xFF), me, vec![2]);
    /// assert_eq!(all.broadcast, Broadcast::Global);
    /// let one = As4Message::new(0x2B00, As4Id::new(7, 1, 1), me, vec![2]);
    /// assert_eq!(one.broadcast, Broadcast::None);
    /// ```
    pub fn new(message_id: u16, destination: As4Id, source: As4Id, body: Vec<u8>) -> Self {
        Self {
            destination,
            source,
            priority: Priority::Standard,
            broadcast: if destination.is_broadcast() {
                Broadcast::Global
            } else {
                Broadcast::None
            },
            ack_requested: false,
            message_id,
            body,
        }
    }

    /// An answer to this message: from its destination to its source, at its priority.
    pub fn reply(&self, message_id: u16, body: Vec<u8>) -> Self {
        Self {
            priority: self.priority,
            ..Self::new(message_id, self.source, self.destination, body)
        }
    }

    /// The message a whole (single) packet carries; `None` for an ack or nak, a piece
    /// of a large message, or a payload without a message ID.
    pub fn from_packet(p: As4Packet) -> Option<Self> {
        let message_id = p.message_id()?;
        if p.header.data_control != DataControl::Single {
            return None;
        }
        let h = p.header;
        let mut body = p.payload;
        body.drain(..2);
        Some(Self {
            destination: h.destination,
            source: h.source,
            priority: h.priority,
            broadcast: h.broadcast,
            ack_requested: h.ack_nak == AckNak::Request,
            message_id,
            body,
        })
    }

    /// The payload on the wire: message ID (LE), then the body.
    pub fn payload(&self) -> Vec<u8> {
        let mut p = Vec::with_capacity(2 + self.body.len());
        p.extend_from_slice(&self.message_id.to_le_bytes());
        p.extend_from_slice(&self.body);
        p
    }

    /// The transport header of its packets (data control set when split).
    pub fn header(&self) -> As4Header {
        As4Header {
            priority: self.priority,
            broadcast: self.broadcast,
            ack_nak: if self.ack_requested {
                AckNak::Request
            } else {
                AckNak::None
            },
            ..As4Header::new(self.destination, self.source)
        }
    }
}
