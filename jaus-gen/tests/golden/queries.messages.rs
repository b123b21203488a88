use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// queries messages and types.
#[allow(clippy::module_inception)]
pub mod queries {
    #[allow(unused_imports)]
    use super::*;
    /// Query Temperature (0x2D10).
    ///
    /// Answered by 0x4D10 (the complement rule).
    ///
    /// Answered by [`ReportTemperature`].
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x2D10)]
    pub struct QueryTemperature {
        /// The report fields wanted (data, not a presence vector).
        pub presence_vector: u8,
    }
    /// Report Temperature (0x4D10).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D10, presence = u8)]
    pub struct ReportTemperature {
        ///
        /// Range `[-100, 100]`, carried as a scaled `i16` (resolution 3.052e-3).
        /// Optional: presence bit 0.
        #[jaus(bit = 0, scaled(i16, -100.0, 100.0))]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub celsius: Option<f64>,
    }
    /// Query History (0x2D11).
    ///
    /// Answered by a report the complement rule does not give.
    ///
    /// Answered by [`ReportTemperatureLog`].
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x2D11)]
    pub struct QueryHistory {}
    /// Report Temperature History Log (0x4D20).
    ///
    /// Interoperability:
    /// Some peers send it without the experimental flag.
    ///
    /// Experimental (not part of RA 3.3).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D20)]
    pub struct ReportTemperatureLog {
        ///
        /// Preceded on the wire by its element count as `u8`.
        #[jaus(count = u8)]
        pub values: Vec<i16>,
    }
    /// Query Ping (0x2D12).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x2D12)]
    pub struct QueryPing {}
}
pub use queries::*;
impl ::jaus::Query for QueryTemperature {
    type Report = ReportTemperature;
}
impl ::jaus::Query for QueryHistory {
    type Report = ReportTemperatureLog;
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
    /// Query Temperature (0x2D10).
    QueryTemperature(QueryTemperature),
    /// Report Temperature (0x4D10).
    ReportTemperature(ReportTemperature),
    /// Query History (0x2D11).
    QueryHistory(QueryHistory),
    /// Report Temperature History Log (0x4D20).
    ReportTemperatureLog(ReportTemperatureLog),
    /// Query Ping (0x2D12).
    QueryPing(QueryPing),
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
            0x2D10 => decode_as::<QueryTemperature>(body),
            0x4D10 => decode_as::<ReportTemperature>(body),
            0x2D11 => decode_as::<QueryHistory>(body),
            0x4D20 => decode_as::<ReportTemperatureLog>(body),
            0x2D12 => decode_as::<QueryPing>(body),
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
            Self::QueryTemperature(_) => QueryTemperature::CODE,
            Self::ReportTemperature(_) => ReportTemperature::CODE,
            Self::QueryHistory(_) => QueryHistory::CODE,
            Self::ReportTemperatureLog(_) => ReportTemperatureLog::CODE,
            Self::QueryPing(_) => QueryPing::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::QueryTemperature(_) => QueryTemperature::NAME,
            Self::ReportTemperature(_) => ReportTemperature::NAME,
            Self::QueryHistory(_) => QueryHistory::NAME,
            Self::ReportTemperatureLog(_) => ReportTemperatureLog::NAME,
            Self::QueryPing(_) => QueryPing::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::QueryTemperature(m) => m,
            Self::ReportTemperature(m) => m,
            Self::QueryHistory(m) => m,
            Self::ReportTemperatureLog(m) => m,
            Self::QueryPing(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::QueryTemperature(m) => m,
            Self::ReportTemperature(m) => m,
            Self::QueryHistory(m) => m,
            Self::ReportTemperatureLog(m) => m,
            Self::QueryPing(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<QueryTemperature> for Message {
    fn from(m: QueryTemperature) -> Self {
        Self::QueryTemperature(m)
    }
}
impl From<ReportTemperature> for Message {
    fn from(m: ReportTemperature) -> Self {
        Self::ReportTemperature(m)
    }
}
impl From<QueryHistory> for Message {
    fn from(m: QueryHistory) -> Self {
        Self::QueryHistory(m)
    }
}
impl From<ReportTemperatureLog> for Message {
    fn from(m: ReportTemperatureLog) -> Self {
        Self::ReportTemperatureLog(m)
    }
}
impl From<QueryPing> for Message {
    fn from(m: QueryPing) -> Self {
        Self::QueryPing(m)
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
        code: CommandCode(0x2D10),
        name: "QueryTemperature",
        title: "Query Temperature",
        group: "queries",
        report: Some("ReportTemperature"),
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D10),
        name: "ReportTemperature",
        title: "Report Temperature",
        group: "queries",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x2D11),
        name: "QueryHistory",
        title: "Query History",
        group: "queries",
        report: Some("ReportTemperatureLog"),
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D20),
        name: "ReportTemperatureLog",
        title: "Report Temperature History Log",
        group: "queries",
        report: None,
        experimental: true,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x2D12),
        name: "QueryPing",
        title: "Query Ping",
        group: "queries",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
];
