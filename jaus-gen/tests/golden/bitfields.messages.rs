use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// bits messages and types.
#[allow(clippy::module_inception)]
pub mod bits {
    #[allow(unused_imports)]
    use super::*;
    /// Lights, a flag each, and a two-bit brightness.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausBits)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(repr = u8)]
    pub struct LightState {
        /// Headlights on.
        ///
        /// Bit 0.
        #[jaus(bit = 0)]
        pub headlights: bool,
        /// Bit 1.
        #[jaus(bit = 1)]
        pub beacon: bool,
        /// 0 (off) to 3 (full).
        ///
        /// Bits 4-5.
        #[jaus(bits = 4..= 5)]
        pub brightness: u8,
        /// Bits the definition does not name, kept as received.
        #[jaus(reserved)]
        #[cfg_attr(
            all(),
            serde(default, skip_serializing_if = "::jaus::codec::is_default")
        )]
        pub reserved: u8,
    }
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausBits)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(repr = u64)]
    pub struct WideBits {
        /// Bits 0-11.
        #[jaus(bits = 0..= 11)]
        pub low: u16,
        /// Bits 12-31.
        #[jaus(bits = 12..= 31)]
        pub middle: u32,
        /// Bits 32-63.
        #[jaus(bits = 32..= 63)]
        pub high: u32,
        /// Bits the definition does not name, kept as received.
        #[jaus(reserved)]
        #[cfg_attr(
            all(),
            serde(default, skip_serializing_if = "::jaus::codec::is_default")
        )]
        pub reserved: u64,
    }
    /// Set Lights (0xD020).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD020)]
    pub struct SetLights {
        pub lights: LightState,
        pub wide: WideBits,
    }
}
pub use bits::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Set Lights (0xD020).
    SetLights(SetLights),
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
            0xD020 => decode_as::<SetLights>(body),
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
            Self::SetLights(_) => SetLights::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::SetLights(_) => SetLights::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::SetLights(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::SetLights(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<SetLights> for Message {
    fn from(m: SetLights) -> Self {
        Self::SetLights(m)
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
        code: CommandCode(0xD020),
        name: "SetLights",
        title: "Set Lights",
        group: "bits",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
];
