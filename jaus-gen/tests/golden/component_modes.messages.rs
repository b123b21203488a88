use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// modes messages and types.
#[allow(clippy::module_inception)]
pub mod modes {
    #[allow(unused_imports)]
    use super::*;
    /// Set Global Waypoint (0x040C).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x040C)]
    pub struct SetGlobalWaypoint {}
}
pub use modes::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Set Global Waypoint (0x040C).
    SetGlobalWaypoint(SetGlobalWaypoint),
}
impl Message {
    /// Decodes a body of the message with command code `code`.
    pub fn decode(
        code: CommandCode,
        body: &[u8],
    ) -> ::core::result::Result<Self, DecodeError> {
        match code.0 {
            0x040C => SetGlobalWaypoint::decode_body(body).map(Self::SetGlobalWaypoint),
            other => {
                Err(
                    DecodeError::new(
                        DecodeErrorKind::UnknownCommandCode {
                            code: other,
                        },
                        0,
                    ),
                )
            }
        }
    }
    /// The command code of this message.
    pub fn code(&self) -> CommandCode {
        match self {
            Self::SetGlobalWaypoint(_) => SetGlobalWaypoint::CODE,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::SetGlobalWaypoint(_) => SetGlobalWaypoint::NAME,
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::SetGlobalWaypoint(m) => m,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::SetGlobalWaypoint(m) => m,
        }
    }
}
impl From<SetGlobalWaypoint> for Message {
    fn from(m: SetGlobalWaypoint) -> Self {
        Self::SetGlobalWaypoint(m)
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
        code: CommandCode(0x040C),
        name: "SetGlobalWaypoint",
        title: "Set Global Waypoint",
        group: "modes",
        report: None,
        experimental: false,
    },
];
