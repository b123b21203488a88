//! Why AS5669A bytes were refused or could not be written. Errors about received bytes
//! name the message (its index in the datagram, from 0) and the byte offset where it
//! starts.

/// Why an AS5669A datagram or message was refused, or could not be written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum As4Error {
    /// The datagram has no bytes at all.
    #[error("empty datagram")]
    Empty,
    /// The version byte is not 2.
    #[error("transport version {0} is not 2 (AS5669A)")]
    Version(u8),
    /// The version byte is followed by no message.
    #[error("AS5669A datagram without a message")]
    NoMessage,
    /// Fewer bytes are left than the header of the message needs.
    #[error("message {message} at byte {at}: header needs {need} bytes, {have} left")]
    TooShort {
        /// Index of the message in the datagram.
        message: usize,
        /// Byte offset of the message in the datagram.
        at: usize,
        /// Bytes the header (with its header-compression fields) needs.
        need: usize,
        /// Bytes left in the datagram.
        have: usize,
    },
    /// The data size field disagrees with the bytes: more than are left, or less than
    /// the header and sequence number take.
    #[error("message {message} at byte {at}: data size {size} but {have} bytes left (at least {min} needed)")]
    DataSize {
        /// Index of the message in the datagram.
        message: usize,
        /// Byte offset of the message in the datagram.
        at: usize,
        /// The data size field.
        size: u16,
        /// Bytes left in the datagram from the message's start.
        have: usize,
        /// The least data size the header allows (header and sequence number).
        min: usize,
    },
    /// A message type other than 0 (a JAUS message).
    #[error("message {message} at byte {at}: message type {value} is not 0 (JAUS message)")]
    MessageType {
        /// Index of the message in the datagram.
        message: usize,
        /// Byte offset of the message in the datagram.
        at: usize,
        /// The 6-bit message type.
        value: u8,
    },
    /// The broadcast field holds the reserved value 3.
    #[error("message {message} at byte {at}: broadcast flags {value} are reserved")]
    Broadcast {
        /// Index of the message in the datagram.
        message: usize,
        /// Byte offset of the message in the datagram.
        at: usize,
        /// The 2-bit broadcast field.
        value: u8,
    },
    /// The HC flags say the header is compressed (2 or 3), which is not implemented.
    #[error(
        "message {message} at byte {at}: header compression (HC flags {flags}) is not supported"
    )]
    Compressed {
        /// Index of the message in the datagram.
        message: usize,
        /// Byte offset of the message in the datagram.
        at: usize,
        /// The 2-bit HC flags.
        flags: u8,
    },
    /// A single or first packet of a JAUS message whose payload is shorter than the
    /// 2-byte message ID.
    #[error("message {message} at byte {at}: payload of {len} bytes has no message ID")]
    NoMessageId {
        /// Index of the message in the datagram.
        message: usize,
        /// Byte offset of the message in the datagram.
        at: usize,
        /// Payload bytes.
        len: usize,
    },
    /// A payload too large for the 16-bit data size of one packet (writing).
    #[error("payload of {len} bytes does not fit one packet (at most {max})")]
    PayloadTooLarge {
        /// Payload bytes.
        len: usize,
        /// The largest payload one packet can carry.
        max: usize,
    },
    /// A message that would need more packets than sequence numbers can tell apart
    /// (writing).
    #[error("message of {len} bytes needs more than {max} packets")]
    MessageTooLarge {
        /// Message bytes (message ID and body).
        len: usize,
        /// Most packets of one message.
        max: usize,
    },
    /// A datagram size bound too small for even one message (writing).
    #[error("datagram bound of {bound} bytes cannot hold a message of {need} bytes")]
    DatagramBound {
        /// The bound.
        bound: usize,
        /// Bytes of the message that did not fit (with the version byte).
        need: usize,
    },
}
