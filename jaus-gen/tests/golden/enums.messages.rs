use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// enums messages and types.
#[allow(clippy::module_inception)]
pub mod enums {
    #[allow(unused_imports)]
    use super::*;
    /// How the vehicle is driven.
    ///
    /// A value the definition does not name decodes to `Unknown(n)` and re-encodes
    /// unchanged.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausEnum)]
    #[cfg_attr(all(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(repr = u8)]
    pub enum DriveMode {
        /// By an operator at the vehicle.
        #[default]
        #[jaus(value = 0)]
        Manual,
        /// Teleoperated (1).
        #[jaus(value = 1)]
        Teleoperated,
        /// By itself (2-6 are not named: they decode to Unknown).
        #[jaus(value = 7)]
        Autonomous,
        /// A value the definition does not name.
        #[jaus(unknown)]
        Unknown(u8),
    }
    ///
    /// A value the definition does not name decodes to `Unknown(n)` and re-encodes
    /// unchanged.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausEnum)]
    #[cfg_attr(all(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(repr = u16)]
    pub enum FaultCode {
        /// No Fault (0).
        #[default]
        #[jaus(value = 0)]
        NoFault,
        /// Overheat (513).
        #[jaus(value = 513)]
        Overheat,
        /// A value the definition does not name.
        #[jaus(unknown)]
        Unknown(u16),
    }
    /// Set Drive Mode (0xD010).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD010)]
    pub struct SetDriveMode {
        /// The mode to enter.
        pub mode: DriveMode,
        pub fault: FaultCode,
        /// Enums in a list.
        ///
        /// Preceded on the wire by its element count as `u8`.
        #[jaus(count = u8)]
        pub fallbacks: Vec<DriveMode>,
    }
}
pub use enums::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Set Drive Mode (0xD010).
    SetDriveMode(SetDriveMode),
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
            0xD010 => decode_as::<SetDriveMode>(body),
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
            Self::SetDriveMode(_) => SetDriveMode::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::SetDriveMode(_) => SetDriveMode::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::SetDriveMode(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::SetDriveMode(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<SetDriveMode> for Message {
    fn from(m: SetDriveMode) -> Self {
        Self::SetDriveMode(m)
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
        code: CommandCode(0xD010),
        name: "SetDriveMode",
        title: "Set Drive Mode",
        group: "enums",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
];
