use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// embedded messages and types.
#[allow(clippy::module_inception)]
pub mod embedded {
    #[allow(unused_imports)]
    use super::*;
    /// Query Thing (0x2D00).
    ///
    /// Answered by [`ReportThing`].
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x2D00)]
    pub struct QueryThing {}
    /// Report Thing (0x4D00).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D00)]
    pub struct ReportThing {
        pub value: u16,
    }
    /// Replay (0xD080).
    #[derive(Debug, Clone, PartialEq, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD080, presence = u8)]
    pub struct Replay {
        /// Code of the wrapped query.
        pub query_code: u16,
        /// The query's body.
        ///
        /// Preceded on the wire by its length as `u32`.
        #[jaus(size = u32)]
        #[cfg_attr(all(), serde(with = "::jaus::hex::serde"))]
        pub query_body: Vec<u8>,
        /// The answer's body.
        ///
        /// Preceded on the wire by its length as `u32`.
        /// Optional: presence bit 0.
        #[jaus(bit = 0, size = u32)]
        #[cfg_attr(
            all(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::hex::serde_opt"
            )
        )]
        pub report_body: Option<Vec<u8>>,
        /// With its byte length.
        ///
        /// A whole JAUS message, header included.
        /// Preceded on the wire by its byte length as `u32`.
        #[jaus(size = u32)]
        pub sized: ::jaus::Packet,
        /// Its length from its header.
        ///
        /// A whole JAUS message, header included.
        pub packet: ::jaus::Packet,
    }
    impl Replay {
        /// Decodes `query_body` as the message whose code is `query_code`.
        pub fn query_body_decoded(
            &self,
        ) -> ::core::result::Result<Message, ::jaus::codec::DecodeError> {
            let code = ::jaus::CommandCode(self.query_code);
            Message::decode(code, &self.query_body)
        }
        /// Decodes `report_body` as the message whose code is the complement (query ↔ report) of `query_code`, if present.
        pub fn report_body_decoded(
            &self,
        ) -> Option<::core::result::Result<Message, ::jaus::codec::DecodeError>> {
            let code = ::jaus::CommandCode(self.query_code);
            let code = code.complement().unwrap_or(code);
            self.report_body.as_deref().map(|body| Message::decode(code, body))
        }
    }
}
pub use embedded::*;
impl ::jaus::Query for QueryThing {
    type Report = ReportThing;
}
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Query Thing (0x2D00).
    QueryThing(QueryThing),
    /// Report Thing (0x4D00).
    ReportThing(ReportThing),
    /// Replay (0xD080).
    Replay(Replay),
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
            0x2D00 => decode_as::<QueryThing>(body),
            0x4D00 => decode_as::<ReportThing>(body),
            0xD080 => decode_as::<Replay>(body),
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
            Self::QueryThing(_) => QueryThing::CODE,
            Self::ReportThing(_) => ReportThing::CODE,
            Self::Replay(_) => Replay::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::QueryThing(_) => QueryThing::NAME,
            Self::ReportThing(_) => ReportThing::NAME,
            Self::Replay(_) => Replay::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::QueryThing(m) => m,
            Self::ReportThing(m) => m,
            Self::Replay(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::QueryThing(m) => m,
            Self::ReportThing(m) => m,
            Self::Replay(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<QueryThing> for Message {
    fn from(m: QueryThing) -> Self {
        Self::QueryThing(m)
    }
}
impl From<ReportThing> for Message {
    fn from(m: ReportThing) -> Self {
        Self::ReportThing(m)
    }
}
impl From<Replay> for Message {
    fn from(m: Replay) -> Self {
        Self::Replay(m)
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
        code: CommandCode(0x2D00),
        name: "QueryThing",
        title: "Query Thing",
        group: "embedded",
        report: Some("ReportThing"),
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D00),
        name: "ReportThing",
        title: "Report Thing",
        group: "embedded",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD080),
        name: "Replay",
        title: "Replay",
        group: "embedded",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
];
