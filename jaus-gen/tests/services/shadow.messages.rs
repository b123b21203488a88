use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// shadow messages and types.
#[allow(clippy::module_inception)]
pub mod shadow {
    #[allow(unused_imports)]
    use super::*;
    /// Switch On (0x0D21).
    ///
    /// Switches the light on.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D21)]
    pub struct SwitchOn {
        /// The level to start at.
        ///
        /// Unit: %.
        pub level: u8,
    }
    /// Set Level (0x0D20).
    ///
    /// Sets the light level.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D20)]
    pub struct SetLevel {
        /// The level asked for.
        ///
        /// Unit: %.
        pub level: u8,
    }
}
pub use shadow::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Switch On (0x0D21).
    SwitchOn(SwitchOn),
    /// Set Level (0x0D20).
    SetLevel(SetLevel),
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
            0x0D21 => decode_as::<SwitchOn>(body),
            0x0D20 => decode_as::<SetLevel>(body),
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
            Self::SwitchOn(_) => SwitchOn::CODE,
            Self::SetLevel(_) => SetLevel::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::SwitchOn(_) => SwitchOn::NAME,
            Self::SetLevel(_) => SetLevel::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::SwitchOn(m) => m,
            Self::SetLevel(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::SwitchOn(m) => m,
            Self::SetLevel(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<SwitchOn> for Message {
    fn from(m: SwitchOn) -> Self {
        Self::SwitchOn(m)
    }
}
impl From<SetLevel> for Message {
    fn from(m: SetLevel) -> Self {
        Self::SetLevel(m)
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
        code: CommandCode(0x0D21),
        name: "SwitchOn",
        title: "Switch On",
        group: "shadow",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0D20),
        name: "SetLevel",
        title: "Set Level",
        group: "shadow",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
];
