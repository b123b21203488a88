use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// flags messages and types.
#[allow(clippy::module_inception)]
pub mod flags {
    #[allow(unused_imports)]
    use super::*;
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct Obstacle {
        ///
        /// Unit: m.
        #[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))]
        pub distance: f32,
        /// Present when the message's flag is set.
        ///
        /// Unit: m.
        /// Present exactly when `buffered` is set.
        #[jaus(present_if = "buffered")]
        #[cfg_attr(
            all(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::codec::serde_float::option"
            )
        )]
        pub buffer: Option<f32>,
        ///
        /// Preceded on the wire by its length as `u8`.
        /// Present exactly when `buffered` is set.
        #[jaus(present_if = "buffered", size = u8)]
        #[cfg_attr(
            all(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::hex::serde_opt"
            )
        )]
        pub label: Option<Vec<u8>>,
    }
    /// Report Obstacles (0xD090).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD090, presence = u8)]
    pub struct ReportObstacles {
        /// A presence bit standing for itself.
        /// Presence-vector bit 0 (no bytes of its own).
        #[jaus(flag = 0, var = "buffered")]
        pub buffered: bool,
        /// Presence-vector bit 1 (no bytes of its own).
        #[jaus(flag = 1, var = "has_confidence")]
        pub has_confidence: bool,
        /// Present exactly when `has_confidence` is set.
        #[jaus(present_if = "has_confidence")]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub confidence: Option<u8>,
        #[jaus(var = "joints")]
        pub joints: u8,
        /// Present when `joints` is non-zero.
        /// Present exactly when `joints` is set.
        #[jaus(present_if = "joints")]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub frame: Option<u8>,
        ///
        /// Preceded on the wire by its element count as `u16`.
        #[jaus(count = u16)]
        pub obstacles: Vec<Obstacle>,
    }
}
pub use flags::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Report Obstacles (0xD090).
    ReportObstacles(ReportObstacles),
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
            0xD090 => decode_as::<ReportObstacles>(body),
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
            Self::ReportObstacles(_) => ReportObstacles::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::ReportObstacles(_) => ReportObstacles::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::ReportObstacles(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::ReportObstacles(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<ReportObstacles> for Message {
    fn from(m: ReportObstacles) -> Self {
        Self::ReportObstacles(m)
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
        code: CommandCode(0xD090),
        name: "ReportObstacles",
        title: "Report Obstacles",
        group: "flags",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
];
