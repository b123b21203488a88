//! AS-4 messages as byte strings: the 16-bit message ID (little-endian) followed by the
//! body.
//!
//! That is the payload of an AS5669A packet, and the form in which AS-4 carries a
//! message inside another: the query of [`CreateEvent`] and [`UpdateEvent`] (and of a
//! reported [`EventInfo`]), the report of [`Event`], the command of
//! [`CreateCommandEvent`] and the data of a list [`Element`] whose format is
//! [`ElementFormat::JausMessage`]. The accessors below decode those fields into a
//! [`Message`]; a message ID this crate does not define decodes to [`Message::Raw`].

use crate::messages::{
    CreateCommandEvent, CreateEvent, Element, ElementFormat, Event, EventInfo, Message, UpdateEvent,
};
use jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError};
use jaus::{CommandCode, JausMessage};

/// Bytes of the message ID in front of a body.
pub const ID_LEN: usize = 2;

/// The message ID and body of `msg`.
pub fn encode(msg: &Message) -> Result<Vec<u8>, EncodeError> {
    with_id(msg.code(), msg)
}

/// The message ID and body of a typed message.
pub fn encode_typed<M: JausMessage>(msg: &M) -> Result<Vec<u8>, EncodeError> {
    with_id(M::CODE, msg)
}

fn with_id(code: CommandCode, body: &dyn Encode) -> Result<Vec<u8>, EncodeError> {
    let mut out = Vec::with_capacity(ID_LEN + body.encoded_len());
    out.extend_from_slice(&code.0.to_le_bytes());
    out.extend_from_slice(&body.to_bytes()?);
    Ok(out)
}

/// Reads a message ID and body. Fewer than two bytes is a
/// [`DecodeErrorKind::Truncated`] error; a body that does not decode as the message its
/// ID names is that message's decode error (offsets counted from the start of the
/// body); an ID this crate does not define gives [`Message::Raw`].
pub fn decode(bytes: &[u8]) -> Result<Message, DecodeError> {
    let [lo, hi, body @ ..] = bytes else {
        return Err(DecodeError::new(
            DecodeErrorKind::Truncated {
                needed: ID_LEN,
                available: bytes.len(),
            },
            0,
        ));
    };
    Message::decode(CommandCode(u16::from_le_bytes([*lo, *hi])), body)
}

impl CreateEvent {
    /// The query whose reports the event is to send.
    pub fn query(&self) -> Result<Message, DecodeError> {
        decode(&self.query_message)
    }
}

impl UpdateEvent {
    /// The query whose reports the event is to send.
    pub fn query(&self) -> Result<Message, DecodeError> {
        decode(&self.query_message)
    }
}

impl EventInfo {
    /// The query whose reports the event sends.
    pub fn query(&self) -> Result<Message, DecodeError> {
        decode(&self.query_message)
    }
}

impl Event {
    /// The report the event carries.
    pub fn report(&self) -> Result<Message, DecodeError> {
        decode(&self.report_message)
    }
}

impl CreateCommandEvent {
    /// The command to run.
    pub fn command(&self) -> Result<Message, DecodeError> {
        decode(&self.command_message)
    }
}

impl Element {
    /// The message the element holds, or `None` when its data is of a user-defined
    /// format.
    pub fn message(&self) -> Option<Result<Message, DecodeError>> {
        (self.format == ElementFormat::JausMessage).then(|| decode(&self.data))
    }

    /// An element holding `msg` (format [`ElementFormat::JausMessage`]).
    pub fn holding(
        uid: u16,
        previous_uid: u16,
        next_uid: u16,
        msg: &Message,
    ) -> Result<Self, EncodeError> {
        Ok(Self {
            uid,
            previous_uid,
            next_uid,
            format: ElementFormat::JausMessage,
            data: encode(msg)?,
        })
    }
}
