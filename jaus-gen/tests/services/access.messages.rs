use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// access messages and types.
#[allow(clippy::module_inception)]
pub mod access {
    #[allow(unused_imports)]
    use super::*;
    ///
    /// A value the definition does not name decodes to `Unknown(n)` and re-encodes
    /// unchanged.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausEnum)]
    #[cfg_attr(all(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(repr = u8)]
    pub enum AnswerControlVerdict {
        /// Granted (0).
        #[default]
        #[jaus(value = 0)]
        Granted,
        /// Rank Too Low (1).
        #[jaus(value = 1)]
        RankTooLow,
        /// A value the definition does not name.
        #[jaus(unknown)]
        Unknown(u8),
    }
    /// Ask For Control (0x0A0D).
    ///
    /// A client asks to become the controller, with its rank.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0A0D)]
    pub struct AskForControl {
        pub rank: u8,
    }
    /// Give Up Control (0x0A0E).
    ///
    /// The controller gives control up.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0A0E)]
    pub struct GiveUpControl {}
    /// Answer Control (0x0A0F).
    ///
    /// The answer to a request: granted or refused.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0A0F)]
    pub struct AnswerControl {
        pub verdict: AnswerControlVerdict,
    }
    /// End Control (0x0A10).
    ///
    /// Tells a client it no longer has control.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0A10)]
    pub struct EndControl {}
}
pub use access::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Ask For Control (0x0A0D).
    AskForControl(AskForControl),
    /// Give Up Control (0x0A0E).
    GiveUpControl(GiveUpControl),
    /// Answer Control (0x0A0F).
    AnswerControl(AnswerControl),
    /// End Control (0x0A10).
    EndControl(EndControl),
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
            0x0A0D => decode_as::<AskForControl>(body),
            0x0A0E => decode_as::<GiveUpControl>(body),
            0x0A0F => decode_as::<AnswerControl>(body),
            0x0A10 => decode_as::<EndControl>(body),
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
            Self::AskForControl(_) => AskForControl::CODE,
            Self::GiveUpControl(_) => GiveUpControl::CODE,
            Self::AnswerControl(_) => AnswerControl::CODE,
            Self::EndControl(_) => EndControl::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::AskForControl(_) => AskForControl::NAME,
            Self::GiveUpControl(_) => GiveUpControl::NAME,
            Self::AnswerControl(_) => AnswerControl::NAME,
            Self::EndControl(_) => EndControl::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::AskForControl(m) => m,
            Self::GiveUpControl(m) => m,
            Self::AnswerControl(m) => m,
            Self::EndControl(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::AskForControl(m) => m,
            Self::GiveUpControl(m) => m,
            Self::AnswerControl(m) => m,
            Self::EndControl(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<AskForControl> for Message {
    fn from(m: AskForControl) -> Self {
        Self::AskForControl(m)
    }
}
impl From<GiveUpControl> for Message {
    fn from(m: GiveUpControl) -> Self {
        Self::GiveUpControl(m)
    }
}
impl From<AnswerControl> for Message {
    fn from(m: AnswerControl) -> Self {
        Self::AnswerControl(m)
    }
}
impl From<EndControl> for Message {
    fn from(m: EndControl) -> Self {
        Self::EndControl(m)
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
        code: CommandCode(0x0A0D),
        name: "AskForControl",
        title: "Ask For Control",
        group: "access",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0A0E),
        name: "GiveUpControl",
        title: "Give Up Control",
        group: "access",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0A0F),
        name: "AnswerControl",
        title: "Answer Control",
        group: "access",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0A10),
        name: "EndControl",
        title: "End Control",
        group: "access",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
];
