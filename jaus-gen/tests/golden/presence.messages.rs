use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// presence messages and types.
#[allow(clippy::module_inception)]
pub mod presence {
    #[allow(unused_imports)]
    use super::*;
    /// A record with its own presence vector.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(presence = u8)]
    pub struct Limits {
        /// Optional: presence bit 0.
        #[jaus(bit = 0)]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub minimum: Option<i16>,
        /// Optional: presence bit 1.
        #[jaus(bit = 1)]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub maximum: Option<i16>,
    }
    /// Report Position (0xD030).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD030, presence = u8)]
    pub struct ReportPosition {
        /// Mandatory: always sent.
        ///
        /// Unit: m.
        #[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))]
        pub x: f32,
        ///
        /// Unit: m.
        /// Optional: presence bit 0.
        #[jaus(bit = 0)]
        #[cfg_attr(
            all(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::codec::serde_float::option"
            )
        )]
        pub y: Option<f32>,
        ///
        /// Unit: m.
        /// Optional: presence bit 7.
        #[jaus(bit = 7)]
        #[cfg_attr(
            all(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::codec::serde_float::option"
            )
        )]
        pub z: Option<f64>,
    }
    /// Report Readings (0xD031).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD031, presence = u16)]
    pub struct ReportReadings {
        ///
        /// Preceded on the wire by its length as `u8`.
        /// Optional: presence bit 0.
        #[jaus(bit = 0, size = u8)]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub label: Option<String>,
        ///
        /// Preceded on the wire by its length as `u8`.
        /// Optional: presence bit 1.
        #[jaus(bit = 1, size = u8)]
        #[cfg_attr(
            all(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::hex::serde_opt"
            )
        )]
        pub raw: Option<Vec<u8>>,
        ///
        /// Unit: °C.
        /// Range `[-100, 100]`, carried as a scaled `i16` (resolution 3.052e-3).
        /// Optional: presence bit 9.
        #[jaus(bit = 9, scaled(i16, -100.0, 100.0), unit = "°C")]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub temperature: Option<f64>,
        /// Optional: presence bit 15.
        #[jaus(bit = 15)]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub limits: Option<Limits>,
        /// A mandatory record with optional fields.
        pub always: Limits,
    }
    /// Report Mask (0xD032).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD032, presence = u32)]
    pub struct ReportMask {
        /// Optional: presence bit 0.
        #[jaus(bit = 0)]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub first: Option<u8>,
        /// Optional: presence bit 31.
        #[jaus(bit = 31)]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub last: Option<u64>,
    }
}
pub use presence::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Report Position (0xD030).
    ReportPosition(ReportPosition),
    /// Report Readings (0xD031).
    ReportReadings(ReportReadings),
    /// Report Mask (0xD032).
    ReportMask(ReportMask),
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
            0xD030 => decode_as::<ReportPosition>(body),
            0xD031 => decode_as::<ReportReadings>(body),
            0xD032 => decode_as::<ReportMask>(body),
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
            Self::ReportPosition(_) => ReportPosition::CODE,
            Self::ReportReadings(_) => ReportReadings::CODE,
            Self::ReportMask(_) => ReportMask::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::ReportPosition(_) => ReportPosition::NAME,
            Self::ReportReadings(_) => ReportReadings::NAME,
            Self::ReportMask(_) => ReportMask::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::ReportPosition(m) => m,
            Self::ReportReadings(m) => m,
            Self::ReportMask(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::ReportPosition(m) => m,
            Self::ReportReadings(m) => m,
            Self::ReportMask(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<ReportPosition> for Message {
    fn from(m: ReportPosition) -> Self {
        Self::ReportPosition(m)
    }
}
impl From<ReportReadings> for Message {
    fn from(m: ReportReadings) -> Self {
        Self::ReportReadings(m)
    }
}
impl From<ReportMask> for Message {
    fn from(m: ReportMask) -> Self {
        Self::ReportMask(m)
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
        code: CommandCode(0xD030),
        name: "ReportPosition",
        title: "Report Position",
        group: "presence",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD031),
        name: "ReportReadings",
        title: "Report Readings",
        group: "presence",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD032),
        name: "ReportMask",
        title: "Report Mask",
        group: "presence",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
];
