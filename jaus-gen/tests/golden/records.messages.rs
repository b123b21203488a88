use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// records messages and types.
#[allow(clippy::module_inception)]
pub mod records {
    #[allow(unused_imports)]
    use super::*;
    /// A point in the plane.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct Point {
        ///
        /// Unit: m.
        #[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))]
        pub x: f64,
        ///
        /// Unit: m.
        #[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))]
        pub y: f64,
    }
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct Segment {
        pub start: Point,
        pub end: Point,
    }
    /// Records nest to any depth.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct Route {
        ///
        /// A fixed 8-byte string, NUL padded.
        #[jaus(fixed = 8)]
        pub name: String,
        ///
        /// Preceded on the wire by its element count as `u8`.
        #[jaus(count = u8)]
        pub segments: Vec<Segment>,
        /// Preceded by its byte size.
        #[jaus(size = u16)]
        pub origin: Point,
    }
    /// Report Route (0xD050).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD050)]
    pub struct ReportRoute {
        pub route: Route,
        ///
        /// Preceded on the wire by its element count as `u8`.
        #[jaus(count = u8)]
        pub alternatives: Vec<Route>,
    }
}
pub use records::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Report Route (0xD050).
    ReportRoute(ReportRoute),
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
            0xD050 => decode_as::<ReportRoute>(body),
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
            Self::ReportRoute(_) => ReportRoute::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::ReportRoute(_) => ReportRoute::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::ReportRoute(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::ReportRoute(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<ReportRoute> for Message {
    fn from(m: ReportRoute) -> Self {
        Self::ReportRoute(m)
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
        code: CommandCode(0xD050),
        name: "ReportRoute",
        title: "Report Route",
        group: "records",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
];
