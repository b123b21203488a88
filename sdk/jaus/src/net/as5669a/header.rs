//! The AS5669A general transport header as typed values, and one message on the wire.
//!
//! ```text
//! byte 0       message type (bits 7-2, 0 = JAUS message) | HC flags (bits 1-0)
//! bytes 1-2    data size, u16 LE: header + payload + sequence number
//! [HC number, HC length]   only when the HC flags are not 0
//! next byte    priority (bits 1-0) | broadcast (3-2) | ack/nak (5-4) | data control (7-6)
//! 4 bytes      destination id, u32 LE: subsystem << 16 | node << 8 | component
//! 4 bytes      source id, likewise
//! payload      its first two bytes (LE) are the message ID of a single or first packet
//! 2 bytes      sequence number, u16 LE
//! ```

use super::error::As4Error;

/// Bytes of the general transport header without header compression: message type and
/// HC flags (1), data size (2), properties (1), destination (4), source (4).
pub const HEADER_LEN: usize = 12;

/// Bytes of the header-compression fields (HC number, HC length) present when the HC
/// flags are not 0.
pub const HC_LEN: usize = 2;

/// Bytes of the sequence number after the payload.
pub const SEQUENCE_LEN: usize = 2;

/// Bytes a message carries besides its payload (without header compression): header
/// and sequence number. The data size of a message is its payload plus this.
pub const OVERHEAD: usize = HEADER_LEN + SEQUENCE_LEN;

/// Largest payload in one packet: 4079 bytes, so that a datagram of one message with
/// header compression fields stays within 4096 bytes (1 + 14 + 2 + 4079), as the
/// Junior middleware of the JAUS Tool Set bounds it.
pub const MAX_PAYLOAD: usize = 4079;

/// The message type of a JAUS message (the only one this transport carries).
pub const JAUS_MESSAGE_TYPE: u8 = 0;

/// The 32-bit id of an AS-4 component: a 16-bit subsystem, 8-bit node and component.
/// On the wire it is the u32 `subsystem << 16 | node << 8 | component`, little-endian.
///
/// ```
/// use jaus::net::as5669a::As4Id;
/// let id = As4Id::new(42, 1, 1);
/// assert_eq!(id.to_string(), "42.1.1");
/// assert_eq!(id.to_bytes(), [1, 1, 42, 0]);
/// assert_eq!(As4Id::from_bytes([1, 1, 42, 0]), id);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub struct As4Id {
    /// Subsystem id (0xFFFF: every subsystem).
    pub subsystem: u16,
    /// Node id (0xFF: every node).
    pub node: u8,
    /// Component id (0xFF: every component).
    pub component: u8,
}

impl As4Id {
    /// The id `subsystem.node.component`.
    pub const fn new(subsystem: u16, node: u8, component: u8) -> Self {
        Self {
            subsystem,
            node,
            component,
        }
    }

    /// The id as one u32: `subsystem << 16 | node << 8 | component`.
    pub const fn to_u32(self) -> u32 {
        (self.subsystem as u32) << 16 | (self.node as u32) << 8 | self.component as u32
    }

    /// The id of a u32 `subsystem << 16 | node << 8 | component`.
    pub const fn from_u32(v: u32) -> Self {
        Self {
            subsystem: (v >> 16) as u16,
            node: (v >> 8) as u8,
            component: v as u8,
        }
    }

    /// The four bytes on the wire (little-endian).
    pub const fn to_bytes(self) -> [u8; 4] {
        self.to_u32().to_le_bytes()
    }

    /// The id of four bytes on the wire (little-endian).
    pub const fn from_bytes(b: [u8; 4]) -> Self {
        Self::from_u32(u32::from_le_bytes(b))
    }

    /// Whether the id names more than one component: a subsystem of 0xFFFF, a node or
    /// a component of 0xFF (every one). A message to such an id is sent as a global
    /// broadcast ([`As4Message::new`](super::As4Message::new)).
    ///
    /// ```
    /// use jaus::net::as5669a::As4Id;
    /// assert!(As4Id::new(0xFFFF, 0xFF, 0xFF).is_broadcast());
    /// assert!(As4Id::new(7, 1, 0xFF).is_broadcast());
    /// assert!(!As4Id::new(7, 1, 1).is_broadcast());
    /// ```
    pub const fn is_broadcast(self) -> bool {
        self.subsystem == 0xFFFF || self.node == 0xFF || self.component == 0xFF
    }
}

impl std::fmt::Display for As4Id {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}.{}.{}", self.subsystem, self.node, self.component)
    }
}

/// Why text is not an AS-4 id (`subsystem.node.component`): the text and, where one
/// part is wrong, which part and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct As4IdParseError {
    text: String,
    part: Option<(&'static str, String)>,
}

impl std::fmt::Display for As4IdParseError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.part {
            None => write!(
                f,
                "`{}`: expected an AS-4 id subsystem.node.component, e.g. 42.1.1",
                self.text
            ),
            Some((part, why)) => write!(f, "`{}`: {part}: {why}", self.text),
        }
    }
}

impl std::error::Error for As4IdParseError {}

/// `subsystem.node.component`, subsystem 0-65535, node and component 0-255 (65535 and
/// 255 name every one); white space around the text is ignored.
///
/// ```
/// use jaus::net::as5669a::As4Id;
/// assert_eq!("42.1.1".parse::<As4Id>().unwrap(), As4Id::new(42, 1, 1));
/// assert_eq!(
///     "42.1.300".parse::<As4Id>().unwrap_err().to_string(),
///     "`42.1.300`: component: number too large to fit in target type"
/// );
/// assert!("42.1".parse::<As4Id>().is_err());
/// ```
impl std::str::FromStr for As4Id {
    type Err = As4IdParseError;

    fn from_str(text: &str) -> Result<Self, Self::Err> {
        let err = |part| As4IdParseError {
            text: text.to_string(),
            part,
        };
        let parts: Vec<&str> = text.trim().split('.').collect();
        let [s, n, c] = parts.as_slice() else {
            return Err(err(None));
        };
        let bad = |what: &'static str, e: std::num::ParseIntError| err(Some((what, e.to_string())));
        Ok(As4Id::new(
            s.parse().map_err(|e| bad("subsystem", e))?,
            n.parse().map_err(|e| bad("node", e))?,
            c.parse().map_err(|e| bad("component", e))?,
        ))
    }
}

/// The 2-bit priority of a message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub enum Priority {
    /// 0: low.
    Low,
    /// 1: standard (the default).
    #[default]
    Standard,
    /// 2: high.
    High,
    /// 3: safety critical.
    SafetyCritical,
}

impl Priority {
    /// The priority of the two low bits of `bits`.
    pub const fn from_bits(bits: u8) -> Self {
        match bits & 3 {
            0 => Self::Low,
            1 => Self::Standard,
            2 => Self::High,
            _ => Self::SafetyCritical,
        }
    }

    /// The 2-bit value.
    pub const fn bits(self) -> u8 {
        self as u8
    }

    /// Its name in lower case (`low`, `standard`, `high`, `safety_critical`), as
    /// `jaus decode --pcap` prints it.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Low => "low",
            Self::Standard => "standard",
            Self::High => "high",
            Self::SafetyCritical => "safety_critical",
        }
    }
}

/// The 2-bit broadcast field (3 is reserved and refused).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Broadcast {
    /// 0: to the destination only.
    #[default]
    None,
    /// 1: a local broadcast.
    Local,
    /// 2: a global broadcast.
    Global,
}

impl Broadcast {
    /// The broadcast of a 2-bit value; `None` for the reserved 3.
    pub const fn from_bits(bits: u8) -> Option<Self> {
        match bits & 3 {
            0 => Some(Self::None),
            1 => Some(Self::Local),
            2 => Some(Self::Global),
            _ => None,
        }
    }

    /// The 2-bit value.
    pub const fn bits(self) -> u8 {
        self as u8
    }

    /// Its name in lower case (`none`, `local`, `global`), as `jaus decode --pcap`
    /// prints it.
    pub const fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Local => "local",
            Self::Global => "global",
        }
    }
}

/// The 2-bit acknowledgement field: the same as RA 3.3's.
pub use crate::wire::AckNak;

/// The 2-bit data control field: where a packet stands in a message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum DataControl {
    /// 0: a whole message in one packet.
    #[default]
    Single,
    /// 1: the first packet of a large message (it holds the message ID).
    First,
    /// 2: a packet between the first and the last.
    Normal,
    /// 3: the last packet of a large message.
    Last,
}

impl DataControl {
    /// The field of the two low bits of `bits`.
    pub const fn from_bits(bits: u8) -> Self {
        match bits & 3 {
            0 => Self::Single,
            1 => Self::First,
            2 => Self::Normal,
            _ => Self::Last,
        }
    }

    /// The 2-bit value.
    pub const fn bits(self) -> u8 {
        self as u8
    }
}

/// The header-compression fields of a message whose sender asks for header compression
/// (HC flags 1): the header is sent in full, so the message is read as any other, and
/// the request is declined by never answering with a compressed header. Kept so that
/// the message re-encodes byte for byte.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct HcRequest {
    /// The HC number.
    pub number: u8,
    /// The HC length.
    pub length: u8,
}

/// The general transport header of one AS5669A message, without the data size (which
/// follows from the payload) and the sequence number (which trails the payload).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct As4Header {
    /// Header-compression fields (HC flags 1); `None` for HC flags 0.
    pub hc: Option<HcRequest>,
    /// Priority.
    pub priority: Priority,
    /// Broadcast.
    pub broadcast: Broadcast,
    /// Acknowledgement.
    pub ack_nak: AckNak,
    /// Place of the packet in its message.
    pub data_control: DataControl,
    /// Destination.
    pub destination: As4Id,
    /// Source.
    pub source: As4Id,
}

impl As4Header {
    /// A header for one whole message from `source` to `destination`, standard
    /// priority, no broadcast, no acknowledgement asked.
    pub fn new(destination: As4Id, source: As4Id) -> Self {
        Self {
            destination,
            source,
            ..Self::default()
        }
    }

    /// Bytes of the header on the wire (with its header-compression fields).
    pub fn wire_len(&self) -> usize {
        HEADER_LEN + if self.hc.is_some() { HC_LEN } else { 0 }
    }

    /// The properties byte: priority, broadcast, ack/nak, data control.
    pub fn properties(&self) -> u8 {
        self.priority.bits()
            | self.broadcast.bits() << 2
            | self.ack_nak.bits() << 4
            | self.data_control.bits() << 6
    }
}

/// One AS5669A message on the wire: header, payload, sequence number.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Default)]
pub struct As4Packet {
    /// The transport header.
    pub header: As4Header,
    /// The payload: a whole JAUS message (message ID first) for a single packet, its
    /// first piece for a first packet, a further piece otherwise; empty in an ack.
    pub payload: Vec<u8>,
    /// The sequence number.
    pub sequence: u16,
}

impl As4Packet {
    /// The largest payload one packet can carry with this header: what the 16-bit
    /// data size leaves.
    pub fn max_payload(header: &As4Header) -> usize {
        usize::from(u16::MAX) - header.wire_len() - SEQUENCE_LEN
    }

    /// The message ID: the first two bytes (LE) of the payload of a single or first
    /// packet; `None` for other packets, acks and naks, or a payload too short.
    pub fn message_id(&self) -> Option<u16> {
        let first = matches!(
            self.header.data_control,
            DataControl::Single | DataControl::First
        );
        match self.payload.as_slice() {
            [a, b, ..] if first && !self.header.ack_nak.is_answer() => {
                Some(u16::from_le_bytes([*a, *b]))
            }
            _ => None,
        }
    }

    /// Bytes of the message on the wire (its data size).
    pub fn wire_len(&self) -> usize {
        self.header.wire_len() + self.payload.len() + SEQUENCE_LEN
    }

    /// Appends the message to `out`: an error if the payload does not fit the 16-bit
    /// data size.
    pub fn write(&self, out: &mut Vec<u8>) -> Result<(), As4Error> {
        let max = Self::max_payload(&self.header);
        let size = u16::try_from(self.wire_len())
            .ok()
            .filter(|_| self.payload.len() <= max)
            .ok_or(As4Error::PayloadTooLarge {
                len: self.payload.len(),
                max,
            })?;
        let h = &self.header;
        let flags = if h.hc.is_some() { 1 } else { 0 };
        out.push(JAUS_MESSAGE_TYPE << 2 | flags);
        out.extend_from_slice(&size.to_le_bytes());
        if let Some(hc) = h.hc {
            out.extend_from_slice(&[hc.number, hc.length]);
        }
        out.push(h.properties());
        out.extend_from_slice(&h.destination.to_bytes());
        out.extend_from_slice(&h.source.to_bytes());
        out.extend_from_slice(&self.payload);
        out.extend_from_slice(&self.sequence.to_le_bytes());
        Ok(())
    }

    /// The message at the start of `bytes`, and the bytes it takes; `message` and `at`
    /// (its index and offset in the datagram) name it in errors.
    pub fn parse(bytes: &[u8], message: usize, at: usize) -> Result<(Self, usize), As4Error> {
        let short = |need: usize| As4Error::TooShort {
            message,
            at,
            need,
            have: bytes.len(),
        };
        let (&first, rest) = bytes.split_first().ok_or(short(HEADER_LEN))?;
        let value = first >> 2;
        if value != JAUS_MESSAGE_TYPE {
            return Err(As4Error::MessageType { message, at, value });
        }
        let flags = first & 3;
        if flags >= 2 {
            return Err(As4Error::Compressed { message, at, flags });
        }
        let header_len = HEADER_LEN + if flags == 1 { HC_LEN } else { 0 };
        if bytes.len() < header_len {
            return Err(short(header_len));
        }
        let size = u16::from_le_bytes([rest[0], rest[1]]);
        let min = header_len + SEQUENCE_LEN;
        if usize::from(size) > bytes.len() || usize::from(size) < min {
            return Err(As4Error::DataSize {
                message,
                at,
                size,
                have: bytes.len(),
                min,
            });
        }
        let mut i = 3;
        let hc = (flags == 1).then(|| {
            i += HC_LEN;
            HcRequest {
                number: bytes[3],
                length: bytes[4],
            }
        });
        let props = bytes[i];
        let id = |j: usize| As4Id::from_bytes([bytes[j], bytes[j + 1], bytes[j + 2], bytes[j + 3]]);
        let broadcast = Broadcast::from_bits(props >> 2).ok_or(As4Error::Broadcast {
            message,
            at,
            value: (props >> 2) & 3,
        })?;
        let header = As4Header {
            hc,
            priority: Priority::from_bits(props),
            broadcast,
            ack_nak: AckNak::from_bits(props >> 4),
            data_control: DataControl::from_bits(props >> 6),
            destination: id(i + 1),
            source: id(i + 5),
        };
        let end = usize::from(size);
        let payload = &bytes[header_len..end - SEQUENCE_LEN];
        let first_piece = matches!(
            header.data_control,
            DataControl::Single | DataControl::First
        );
        if first_piece && !header.ack_nak.is_answer() && payload.len() < 2 {
            return Err(As4Error::NoMessageId {
                message,
                at,
                len: payload.len(),
            });
        }
        let sequence = u16::from_le_bytes([bytes[end - 2], bytes[end - 1]]);
        let packet = Self {
            header,
            payload: payload.to_vec(),
            sequence,
        };
        Ok((packet, end))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_and_flags_map_to_their_bits() {
        let id = As4Id::new(0x1234, 5, 6);
        assert_eq!(id.to_u32(), 0x1234_0506);
        assert_eq!(id.to_bytes(), [6, 5, 0x34, 0x12]);
        assert_eq!(As4Id::from_u32(id.to_u32()), id);
        assert_eq!(id.to_string(), "4660.5.6");
        for b in 0..4u8 {
            assert_eq!(Priority::from_bits(b).bits(), b);
            assert_eq!(AckNak::from_bits(b).bits(), b);
            assert_eq!(DataControl::from_bits(b).bits(), b);
        }
        assert_eq!(Broadcast::from_bits(3), None);
        let h = As4Header {
            priority: Priority::High,
            broadcast: Broadcast::Global,
            ack_nak: AckNak::Request,
            data_control: DataControl::Last,
            ..As4Header::new(id, id)
        };
        assert_eq!(h.properties(), 0b11_01_10_10);
    }

    #[test]
    fn a_message_parses_and_writes_back() {
        let mut bytes = vec![
            0x00, 18, 0, 0x01, 1, 1, 42, 0, 2, 3, 7, 0, 0x00, 0x2B, 4, 9, 0x34, 0x12,
        ];
        let (p, n) = As4Packet::parse(&bytes, 0, 1).unwrap();
        assert_eq!(n, 18);
        assert_eq!(p.header.priority, Priority::Standard);
        assert_eq!(p.header.destination, As4Id::new(42, 1, 1));
        assert_eq!(p.header.source, As4Id::new(7, 3, 2));
        assert_eq!(p.message_id(), Some(0x2B00));
        assert_eq!(p.payload, [0x00, 0x2B, 4, 9]);
        assert_eq!(p.sequence, 0x1234);
        let mut out = Vec::new();
        p.write(&mut out).unwrap();
        assert_eq!(out, bytes);
        // One byte of payload: no message ID.
        bytes[1] = 15;
        bytes.truncate(15);
        assert!(matches!(
            As4Packet::parse(&bytes, 0, 1),
            Err(As4Error::NoMessageId { len: 1, .. })
        ));
    }
}
