//! The 16-byte JAUS message header, addresses, command codes and whole packets
//! (docs/wire.md §1). Hand-written: everything about a message body comes from the derive.

use crate::codec::{Decode, DecodeError, DecodeErrorKind, Encode, EncodeError, Reader, Writer};
use std::fmt;
use std::str::FromStr;

/// Size of the JAUS message header in bytes.
pub const HEADER_LEN: usize = 16;
/// Largest body the 12-bit data-size field can describe.
pub const MAX_DATA_SIZE: usize = 0x0FFF;
/// Largest body OpenJAUS puts in one packet; longer messages are split (docs/wire.md §1.6).
pub const MAX_PACKET_BODY: usize = 4080;

/// A 16-bit JAUS command code.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(transparent)
)]
pub struct CommandCode(pub u16);

/// The message class a command code falls in (docs/wire.md §3.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MessageClass {
    /// 0x0000–0x1FFF.
    Command,
    /// 0x2000–0x3FFF.
    Query,
    /// 0x4000–0x5FFF.
    Inform,
    /// 0x6000–0x7FFF (deprecated in RA 3.3).
    EventSetup,
    /// 0x8000–0x9FFF (deprecated in RA 3.3).
    EventNotification,
    /// 0xA000–0xBFFF.
    NodeManagement,
    /// 0xC000–0xCFFF.
    Reserved,
    /// 0xD000–0xFFFF.
    Experimental,
}

impl CommandCode {
    /// The class of this code. The runtime's one copy of the standard's range table;
    /// the definitions' (`jaus_spec::MessageClass::of_code`) is checked against it code
    /// by code (`tests/tests/consistency.rs`).
    pub fn class(self) -> MessageClass {
        match self.0 {
            0x0000..=0x1FFF => MessageClass::Command,
            0x2000..=0x3FFF => MessageClass::Query,
            0x4000..=0x5FFF => MessageClass::Inform,
            0x6000..=0x7FFF => MessageClass::EventSetup,
            0x8000..=0x9FFF => MessageClass::EventNotification,
            0xA000..=0xBFFF => MessageClass::NodeManagement,
            0xC000..=0xCFFF => MessageClass::Reserved,
            _ => MessageClass::Experimental,
        }
    }
}

impl CommandCode {
    /// The complementary code of the query/report pairing (docs/wire.md §3.3): a query's
    /// report is `query + 0x2000`, a report's query `report - 0x2000`. `None` outside
    /// the query and inform classes. Checked against the definitions' rule
    /// (`jaus_spec::MessageClass::report_code`) by `tests/tests/consistency.rs`.
    pub fn complement(self) -> Option<CommandCode> {
        match self.class() {
            MessageClass::Query => Some(CommandCode(self.0 + 0x2000)),
            MessageClass::Inform => Some(CommandCode(self.0 - 0x2000)),
            _ => None,
        }
    }
}

impl fmt::Debug for CommandCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "0x{:04X}", self.0)
    }
}

impl fmt::Display for CommandCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "0x{:04X}", self.0)
    }
}

/// A JAUS address: subsystem, node, component, instance. 255 is broadcast at any level;
/// 0 is not a valid identifier.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default, Debug)]
pub struct Address {
    /// Subsystem id.
    pub subsystem: u8,
    /// Node id.
    pub node: u8,
    /// Component id.
    pub component: u8,
    /// Instance id.
    pub instance: u8,
}

impl Address {
    /// The broadcast value of any level.
    pub const BROADCAST: u8 = 255;

    /// A new address.
    pub const fn new(subsystem: u8, node: u8, component: u8, instance: u8) -> Self {
        Self {
            subsystem,
            node,
            component,
            instance,
        }
    }

    /// True when every level is a valid id (1–254) or broadcast.
    pub fn is_valid(&self) -> bool {
        [self.subsystem, self.node, self.component, self.instance]
            .iter()
            .all(|&b| b != 0)
    }

    /// True when `self`, used as a destination, matches the concrete address `other`
    /// (255 at a level matches anything there).
    pub fn matches(&self, other: &Address) -> bool {
        let m = |d: u8, o: u8| d == Self::BROADCAST || d == o;
        m(self.subsystem, other.subsystem)
            && m(self.node, other.node)
            && m(self.component, other.component)
            && m(self.instance, other.instance)
    }

    #[inline]
    fn to_wire(self) -> [u8; 4] {
        [self.instance, self.component, self.node, self.subsystem]
    }

    #[inline]
    fn from_wire(b: [u8; 4]) -> Self {
        Self {
            instance: b[0],
            component: b[1],
            node: b[2],
            subsystem: b[3],
        }
    }
}

impl fmt::Display for Address {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}.{}.{}.{}",
            self.subsystem, self.node, self.component, self.instance
        )
    }
}

/// Error parsing an address from text.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("invalid JAUS address `{0}`: expected subsystem.node.component.instance, each 0-255")]
pub struct AddressParseError(pub String);

impl FromStr for Address {
    type Err = AddressParseError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let parts: Vec<&str> = s.split('.').collect();
        let p = |i: usize| parts.get(i).and_then(|x| x.parse::<u8>().ok());
        match (parts.len(), p(0), p(1), p(2), p(3)) {
            (4, Some(a), Some(b), Some(c), Some(d)) => Ok(Address::new(a, b, c, d)),
            _ => Err(AddressParseError(s.to_string())),
        }
    }
}

#[cfg(feature = "serde")]
impl serde::Serialize for Address {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        [self.subsystem, self.node, self.component, self.instance].serialize(s)
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for Address {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let [a, b, c, e] = <[u8; 4]>::deserialize(d)?;
        Ok(Address::new(a, b, c, e))
    }
}

/// ACK/NAK field of the header: the same two bits in RA 3.3's header and in AS5669A's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum AckNak {
    /// No acknowledgement required (0).
    #[default]
    None,
    /// Acknowledgement requested (1).
    Request,
    /// Negative acknowledgement (2).
    Nak,
    /// Acknowledgement (3).
    Ack,
}

impl AckNak {
    /// The field of the two low bits of `bits`.
    pub const fn from_bits(bits: u8) -> Self {
        match bits & 3 {
            0 => Self::None,
            1 => Self::Request,
            2 => Self::Nak,
            _ => Self::Ack,
        }
    }

    /// The 2-bit value.
    pub const fn bits(self) -> u8 {
        self as u8
    }

    /// Whether this is an answer (ack or nak) rather than a message.
    pub const fn is_answer(self) -> bool {
        matches!(self, Self::Nak | Self::Ack)
    }
}

/// Data flag of a packet in a multi-packet sequence (docs/wire.md §1.3).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "snake_case"))]
pub enum DataFlag {
    /// A whole message in one packet (0).
    #[default]
    Single,
    /// First packet of a sequence (1).
    First,
    /// Middle packet (2).
    Normal,
    /// Retransmitted packet (4).
    Retransmit,
    /// Last packet (8).
    Last,
    /// A value the standard does not define (kept so the packet round-trips).
    Other(u8),
}

impl DataFlag {
    #[inline]
    fn to_bits(self) -> u8 {
        match self {
            DataFlag::Single => 0,
            DataFlag::First => 1,
            DataFlag::Normal => 2,
            DataFlag::Retransmit => 4,
            DataFlag::Last => 8,
            DataFlag::Other(v) => v & 0x0F,
        }
    }
    #[inline]
    fn from_bits(v: u8) -> Self {
        match v {
            0 => DataFlag::Single,
            1 => DataFlag::First,
            2 => DataFlag::Normal,
            4 => DataFlag::Retransmit,
            8 => DataFlag::Last,
            v => DataFlag::Other(v),
        }
    }
}

/// The 16-byte JAUS message header, every field of docs/wire.md §1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(C)]
pub struct Header {
    /// Priority 0–15 (6 is the default; 12–15 are safety critical).
    pub priority: u8,
    /// ACK/NAK request or reply.
    pub ack_nak: AckNak,
    /// Part of a service connection.
    pub service_connection: bool,
    /// Experimental (user-defined) message.
    pub experimental: bool,
    /// Version: 2 for RA 3.2/3.3.
    pub version: u8,
    /// The two reserved bits of the properties word (kept as received).
    #[cfg_attr(feature = "serde", serde(default, skip_serializing_if = "is_zero"))]
    pub reserved: u8,
    /// What the body is.
    pub command_code: CommandCode,
    /// Where it goes.
    pub destination: Address,
    /// Who sent it.
    pub source: Address,
    /// Body bytes in this packet (12 bits). Computed from the body when a packet is
    /// encoded.
    pub data_size: u16,
    /// Position in a multi-packet sequence.
    pub data_flag: DataFlag,
    /// Multi-packet index or service-connection sequence number.
    pub sequence_number: u16,
}

#[cfg(feature = "serde")]
fn is_zero(v: &u8) -> bool {
    *v == 0
}

impl Header {
    /// Version value of RA 3.2 and 3.3.
    pub const VERSION_3_3: u8 = 2;
    /// Default priority.
    pub const DEFAULT_PRIORITY: u8 = 6;

    /// A header with the defaults OpenJAUS uses (priority 6, version 2, no flags).
    pub fn new(command_code: CommandCode, destination: Address, source: Address) -> Self {
        Self {
            priority: Self::DEFAULT_PRIORITY,
            ack_nak: AckNak::None,
            service_connection: false,
            experimental: false,
            version: Self::VERSION_3_3,
            reserved: 0,
            command_code,
            destination,
            source,
            data_size: 0,
            data_flag: DataFlag::Single,
            sequence_number: 0,
        }
    }

    /// The acknowledgement answering a message with this header: the same command code,
    /// from `from` (the component it was for) to its source, ACK when `ok`, else NAK,
    /// with the request's sequence number; the body is empty.
    pub fn acknowledgement(&self, from: Address, ok: bool) -> Header {
        let mut h = Header::new(self.command_code, self.source, from);
        h.ack_nak = if ok { AckNak::Ack } else { AckNak::Nak };
        // The request's number, so that a sender with several commands of one code
        // waiting knows which one is answered (`jaus::net::reliable`).
        h.sequence_number = self.sequence_number;
        h
    }

    /// The 16 header bytes with `data_size` as given (the body length of this packet).
    pub fn encode_with_size(&self, data_size: usize) -> Result<[u8; HEADER_LEN], EncodeError> {
        let (lo, hi) = self.words_with_size(data_size)?;
        let mut b = [0u8; HEADER_LEN];
        b[..8].copy_from_slice(&lo.to_le_bytes());
        b[8..].copy_from_slice(&hi.to_le_bytes());
        Ok(b)
    }

    /// Writes the header with `data_size` as given.
    #[inline]
    fn put(&self, w: &mut Writer<'_>, data_size: usize) -> Result<(), EncodeError> {
        // Two word stores straight into the buffer: a 16-byte array returned inside a
        // `Result` sat one byte off alignment on the stack and was copied out in pieces
        // that straddled the two stores, a store-forwarding stall that cost more than
        // encoding the whole body of a fixed-size message.
        let (lo, hi) = self.words_with_size(data_size)?;
        w.put(&lo.to_le_bytes())?;
        w.put(&hi.to_le_bytes())
    }

    /// The 16 bytes as two little-endian words (one range check for the four narrow
    /// fields, its error built off the hot path).
    #[inline]
    fn words_with_size(&self, data_size: usize) -> Result<(u64, u64), EncodeError> {
        if (self.priority >> 4) | (self.version >> 6) | (self.reserved >> 2) != 0
            || data_size >> 12 != 0
        {
            return Err(self.narrow_field_error(data_size));
        }
        let ack = u64::from(self.ack_nak.bits());
        let props: u64 = u64::from(self.priority)
            | ack << 4
            | u64::from(self.service_connection) << 6
            | u64::from(self.experimental) << 7
            | u64::from(self.version) << 8
            | u64::from(self.reserved) << 14;
        let address = |a: Address| u32::from_le_bytes(a.to_wire());
        let lo = props
            | u64::from(self.command_code.0) << 16
            | u64::from(address(self.destination)) << 32;
        let control = data_size as u64 | u64::from(self.data_flag.to_bits()) << 12;
        let hi =
            u64::from(address(self.source)) | control << 32 | u64::from(self.sequence_number) << 48;
        Ok((lo, hi))
    }

    #[cold]
    #[inline(never)]
    fn narrow_field_error(&self, data_size: usize) -> EncodeError {
        let fields: [(&'static str, u64, u32); 4] = [
            ("Header.priority", self.priority.into(), 4),
            ("Header.version", self.version.into(), 6),
            ("Header.reserved", self.reserved.into(), 2),
            ("Header.data_size", data_size as u64, 12),
        ];
        let (field, value, width) = fields
            .into_iter()
            .find(|(_, v, w)| v >> w != 0)
            .unwrap_or(fields[3]);
        EncodeError::BitsOverflow {
            field,
            value,
            width,
        }
    }

    /// Writes a whole packet, this header (its data size set from the body) and `body`,
    /// into `buf`; returns the packet's length. Nothing is allocated: the hot path's
    /// encoder, into a buffer the caller reuses (`buf[..n]` is the packet).
    ///
    /// The body is walked once: it is written after a reserved header, then the header
    /// is written with the data size the body took.
    ///
    /// Errors, first match wins: the body is longer than [`MAX_DATA_SIZE`]
    /// ([`EncodeError::BodyTooLarge`]); a header field is wider than its bits; `buf` is
    /// too small for the packet ([`EncodeError::BufferTooSmall`], `needed` counting the
    /// bytes up to the one that did not fit); a body field's own error. After an error
    /// the bytes of `buf` are unspecified (part of a packet may have been written): do
    /// not send them.
    #[inline]
    pub fn write_packet<B: Encode + ?Sized>(
        &self,
        body: &B,
        buf: &mut [u8],
    ) -> Result<usize, EncodeError> {
        // The writer ends where the longest body would: a body over the limit stops
        // there instead of being written out in full.
        let end = buf.len().min(HEADER_LEN + MAX_DATA_SIZE);
        let (head, rest) = buf.split_at_mut(end.min(HEADER_LEN));
        let (Ok(head), Some(window)) = (
            <&mut [u8; HEADER_LEN]>::try_from(head),
            rest.get_mut(..end.saturating_sub(HEADER_LEN)),
        ) else {
            return Err(self.packet_error(body, buf));
        };
        let mut w = Writer::new(window);
        let written = body.encode(&mut w).map(|()| w.position());
        match written.and_then(|len| self.words_with_size(len).map(|words| (len, words))) {
            Ok((len, (lo, hi))) => {
                head[..8].copy_from_slice(&lo.to_le_bytes());
                head[8..].copy_from_slice(&hi.to_le_bytes());
                Ok(HEADER_LEN + len)
            }
            Err(_) => Err(self.packet_error(body, buf)),
        }
    }

    /// The error of a packet [`Header::write_packet`] could not write, in the order it
    /// documents (off the hot path: the body is measured and written again from the
    /// start of `buf`, so that offsets and sizes count from the packet's first byte).
    #[cold]
    #[inline(never)]
    fn packet_error<B: Encode + ?Sized>(&self, body: &B, buf: &mut [u8]) -> EncodeError {
        let len = body.encoded_len();
        if len > MAX_DATA_SIZE {
            return EncodeError::BodyTooLarge {
                len,
                max: MAX_DATA_SIZE,
            };
        }
        let capacity = buf.len();
        let mut w = Writer::new(buf);
        match self.put(&mut w, len).and_then(|()| body.encode(&mut w)) {
            Err(e) => e,
            // Unreachable for a body whose encoding does not change between calls.
            Ok(()) => EncodeError::BufferTooSmall {
                needed: HEADER_LEN + len,
                capacity,
            },
        }
    }

    /// Parses the first 16 bytes of `bytes`.
    #[inline]
    pub fn parse(bytes: &[u8]) -> Result<Header, DecodeError> {
        let Some(b) = bytes.first_chunk::<HEADER_LEN>() else {
            return Err(truncated_header(bytes.len()));
        };
        Ok(Header::from_array(b))
    }

    /// The header of these 16 bytes (every bit pattern is a header).
    #[inline(always)]
    fn from_array(b: &[u8; HEADER_LEN]) -> Header {
        let (lo, hi) = b.split_at(8);
        let lo = u64::from_le_bytes(lo.try_into().unwrap_or_default());
        let hi = u64::from_le_bytes(hi.try_into().unwrap_or_default());
        let props = lo as u16;
        let control = (hi >> 32) as u16;
        let address = |w: u64| Address::from_wire((w as u32).to_le_bytes());
        Header {
            priority: (props & 0x0F) as u8,
            ack_nak: AckNak::from_bits((props >> 4) as u8),
            service_connection: props & (1 << 6) != 0,
            experimental: props & (1 << 7) != 0,
            version: ((props >> 8) & 0x3F) as u8,
            reserved: (props >> 14) as u8,
            command_code: CommandCode((lo >> 16) as u16),
            destination: address(lo >> 32),
            source: address(hi),
            data_size: control & 0x0FFF,
            data_flag: DataFlag::from_bits((control >> 12) as u8),
            sequence_number: (hi >> 48) as u16,
        }
    }
}

#[cold]
#[inline(never)]
fn truncated_header(len: usize) -> DecodeError {
    DecodeError::new(DecodeErrorKind::TruncatedHeader { len }, 0)
}

impl Encode for Header {
    fn encoded_len(&self) -> usize {
        HEADER_LEN
    }
    fn encode(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
        self.put(w, usize::from(self.data_size))
    }
}

impl Decode for Header {
    const MIN_LEN: usize = HEADER_LEN;
    fn decode(r: &mut Reader<'_>) -> Result<Self, DecodeError> {
        let at = r.offset();
        let bytes = r.take(HEADER_LEN).map_err(|e| {
            DecodeError::new(
                DecodeErrorKind::TruncatedHeader {
                    len: match e.kind() {
                        DecodeErrorKind::Truncated { available, .. } => *available,
                        _ => 0,
                    },
                },
                at,
            )
        })?;
        Header::parse(bytes)
    }
}

/// A whole JAUS packet: header and raw body. Also the form of a message embedded with
/// its header in another message (Spool Mission tasks, Report Events queries).
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Packet {
    /// The header; its `data_size` is recomputed from `body` on encode.
    pub header: Header,
    /// The body bytes.
    #[cfg_attr(feature = "serde", serde(with = "crate::hex::serde"))]
    pub body: Vec<u8>,
}

impl Packet {
    /// A packet of `body` under `header`, with the header's data size set from the body
    /// (saturating at the 12-bit maximum; encoding a longer body fails).
    pub fn new(mut header: Header, body: Vec<u8>) -> Packet {
        header.data_size = body.len().min(MAX_DATA_SIZE) as u16;
        Packet { header, body }
    }

    /// Parses one datagram-sized packet: a header and exactly `data_size` body bytes
    /// (a copy of them; [`PacketRef::parse`] borrows instead).
    pub fn parse(bytes: &[u8]) -> Result<Packet, DecodeError> {
        let p = PacketRef::parse(bytes)?;
        Ok(Packet {
            header: p.header,
            body: p.body.to_vec(),
        })
    }

    /// A view of this packet.
    pub fn view(&self) -> PacketRef<'_> {
        PacketRef {
            header: self.header,
            body: &self.body,
        }
    }
}

/// A packet borrowed from the bytes it was received in: the parsed header and the body
/// as a slice. Parsing copies nothing; decode the body from it by command code
/// (`Message::decode(p.header.command_code, p.body)`) or as a known type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PacketRef<'a> {
    /// The header.
    pub header: Header,
    /// The body bytes (exactly `header.data_size` of them).
    pub body: &'a [u8],
}

impl<'a> PacketRef<'a> {
    /// Parses one datagram-sized packet: a header and exactly `data_size` body bytes.
    #[inline]
    pub fn parse(bytes: &'a [u8]) -> Result<PacketRef<'a>, DecodeError> {
        let (Some(raw), Some(body)) = (bytes.first_chunk::<HEADER_LEN>(), bytes.get(HEADER_LEN..))
        else {
            return Err(truncated_header(bytes.len()));
        };
        // The data size read from the datagram, not from a parsed header: the compiler
        // otherwise reloaded it together with the command code in one 8-byte load
        // straddling the header's narrow field stores on the stack (a store-forwarding
        // stall that cost about 40 % of decoding a fixed-size packet).
        let data_size = u16::from_le_bytes([raw[12], raw[13]]) & 0x0FFF;
        if body.len() != usize::from(data_size) {
            return Err(DecodeError::new(
                DecodeErrorKind::DataSizeMismatch {
                    header: data_size.into(),
                    actual: body.len(),
                },
                12,
            ));
        }
        // The header built here, after both checks, not taken out of `Header::parse`'s
        // `Result`: moved out of that `Result`, it was left on the stack in narrow
        // stores, and the command code was read back for `Message::decode` in one 8-byte
        // load across them (the same stall: 5-6 ns on every packet decoded by command
        // code, more than the dispatch itself; issue 49, docs/performance.md).
        Ok(PacketRef {
            header: Header::from_array(raw),
            body,
        })
    }
}

impl Encode for Packet {
    fn encoded_len(&self) -> usize {
        HEADER_LEN + self.body.len()
    }
    fn encode(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
        if self.body.len() > MAX_DATA_SIZE {
            return Err(EncodeError::BodyTooLarge {
                len: self.body.len(),
                max: MAX_DATA_SIZE,
            });
        }
        self.header.put(w, self.body.len())?;
        w.put(&self.body)
    }
}

impl Decode for Packet {
    const MIN_LEN: usize = HEADER_LEN;
    fn decode(r: &mut Reader<'_>) -> Result<Self, DecodeError> {
        let header = Header::decode(r)?;
        let body = r.take(usize::from(header.data_size))?.to_vec();
        Ok(Packet { header, body })
    }
}

#[cfg(test)]
mod tests;
