use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// unions messages and types.
#[allow(clippy::module_inception)]
pub mod unions {
    #[allow(unused_imports)]
    use super::*;
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct Rgb {
        pub red: u8,
        pub green: u8,
        pub blue: u8,
    }
    /// A tag, then the value of the variant it names.
    #[derive(Debug, Clone, PartialEq, ::jaus::JausUnion)]
    #[cfg_attr(all(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(tag = u8)]
    pub enum Value {
        #[jaus(tag = 0)]
        Byte(u8),
        /// A double.
        #[jaus(tag = 1)]
        Real(#[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))] f64),
        #[jaus(tag = 9)]
        Colour(Rgb),
        /// A tag with no value.
        #[jaus(tag = 10)]
        Missing,
    }
    /// Set Limit (0xD070).
    #[derive(Debug, Clone, PartialEq, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD070)]
    pub struct SetLimit {
        /// The tag travels with the value.
        pub limit: Value,
        ///
        /// Preceded on the wire by its element count as `u8`.
        #[jaus(count = u8)]
        pub history: Vec<Value>,
    }
    /// Set Range (0xD071).
    #[derive(Debug, Clone, PartialEq, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD071)]
    pub struct SetRange {
        /// The tag of both values.
        #[jaus(var = "value_type")]
        pub value_type: u8,
        ///
        /// Its tag is the field `value_type`, not sent with the value.
        #[jaus(tag_var = "value_type")]
        pub low: Value,
        ///
        /// Its tag is the field `value_type`, not sent with the value.
        #[jaus(tag_var = "value_type")]
        pub high: Value,
    }
}
pub use unions::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Set Limit (0xD070).
    SetLimit(SetLimit),
    /// Set Range (0xD071).
    SetRange(SetRange),
    /// A message this set does not define, kept as its code and body.
    Raw(::jaus::RawMessage),
}
/// Decodes one message type into the set. Not inlined: the match of [`Message::decode`]
/// stays a jump to a small function per code, instead of one frame holding the
/// temporaries of every message (which costs more than the decode itself).
#[inline(never)]
#[allow(dead_code)]
fn decode_as<T: JausMessage + Into<Message>>(
    body: &[u8],
) -> ::core::result::Result<Message, DecodeError> {
    T::decode_body(body).map(Into::into)
}
impl Message {
    /// Decodes a body of the message with command code `code`.
    pub fn decode(
        code: CommandCode,
        body: &[u8],
    ) -> ::core::result::Result<Self, DecodeError> {
        match code.0 {
            0xD070 => decode_as::<SetLimit>(body),
            0xD071 => decode_as::<SetRange>(body),
            _ => {
                Ok(
                    Self::Raw(::jaus::RawMessage {
                        code,
                        body: body.to_vec(),
                    }),
                )
            }
        }
    }
    /// Like [`decode`](Self::decode), but a code this set does not define is an error
    /// instead of a [`Message::Raw`].
    pub fn decode_known(
        code: CommandCode,
        body: &[u8],
    ) -> ::core::result::Result<Self, DecodeError> {
        match Self::decode(code, body)? {
            Self::Raw(_) => {
                Err(
                    DecodeError::new(
                        DecodeErrorKind::UnknownCommandCode {
                            code: code.0,
                        },
                        0,
                    ),
                )
            }
            m => Ok(m),
        }
    }
    /// The command code of this message.
    pub fn code(&self) -> CommandCode {
        match self {
            Self::SetLimit(_) => SetLimit::CODE,
            Self::SetRange(_) => SetRange::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::SetLimit(_) => SetLimit::NAME,
            Self::SetRange(_) => SetRange::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::SetLimit(m) => m,
            Self::SetRange(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::SetLimit(m) => m,
            Self::SetRange(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<SetLimit> for Message {
    fn from(m: SetLimit) -> Self {
        Self::SetLimit(m)
    }
}
impl From<SetRange> for Message {
    fn from(m: SetRange) -> Self {
        Self::SetRange(m)
    }
}
impl Encode for Message {
    fn encoded_len(&self) -> usize {
        self.body().encoded_len()
    }
    fn encode(&self, w: &mut Writer<'_>) -> ::core::result::Result<(), EncodeError> {
        self.body().encode(w)
    }
    fn clamp_to_range(&mut self) {
        self.body_mut().clamp_to_range()
    }
}
/// Every message of the set: code, name, title, group and the report answering it.
pub static MESSAGES: &[::jaus::MessageInfo] = &[
    ::jaus::MessageInfo {
        code: CommandCode(0xD070),
        name: "SetLimit",
        title: "Set Limit",
        group: "unions",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD071),
        name: "SetRange",
        title: "Set Range",
        group: "unions",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
];
