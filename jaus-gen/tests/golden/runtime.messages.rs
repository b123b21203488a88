use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// runtime messages and types.
#[allow(clippy::module_inception)]
pub mod runtime {
    #[allow(unused_imports)]
    use super::*;
    /// Report Status (0x4002).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4002)]
    pub struct ReportStatus {}
    /// Query Name (0x2B00).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x2B00)]
    pub struct QueryName {}
    /// Request Control (0x000D).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x000D)]
    pub struct RequestControl {}
    /// Standby (0x0003).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0003)]
    pub struct Standby {}
    /// Set Speed (0x0402).
    ///
    /// Not the runtime's: components list it.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0402)]
    pub struct SetSpeed {}
}
pub use runtime::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Report Status (0x4002).
    ReportStatus(ReportStatus),
    /// Query Name (0x2B00).
    QueryName(QueryName),
    /// Request Control (0x000D).
    RequestControl(RequestControl),
    /// Standby (0x0003).
    Standby(Standby),
    /// Set Speed (0x0402).
    SetSpeed(SetSpeed),
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
            0x4002 => decode_as::<ReportStatus>(body),
            0x2B00 => decode_as::<QueryName>(body),
            0x000D => decode_as::<RequestControl>(body),
            0x0003 => decode_as::<Standby>(body),
            0x0402 => decode_as::<SetSpeed>(body),
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
            Self::ReportStatus(_) => ReportStatus::CODE,
            Self::QueryName(_) => QueryName::CODE,
            Self::RequestControl(_) => RequestControl::CODE,
            Self::Standby(_) => Standby::CODE,
            Self::SetSpeed(_) => SetSpeed::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::ReportStatus(_) => ReportStatus::NAME,
            Self::QueryName(_) => QueryName::NAME,
            Self::RequestControl(_) => RequestControl::NAME,
            Self::Standby(_) => Standby::NAME,
            Self::SetSpeed(_) => SetSpeed::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::ReportStatus(m) => m,
            Self::QueryName(m) => m,
            Self::RequestControl(m) => m,
            Self::Standby(m) => m,
            Self::SetSpeed(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::ReportStatus(m) => m,
            Self::QueryName(m) => m,
            Self::RequestControl(m) => m,
            Self::Standby(m) => m,
            Self::SetSpeed(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<ReportStatus> for Message {
    fn from(m: ReportStatus) -> Self {
        Self::ReportStatus(m)
    }
}
impl From<QueryName> for Message {
    fn from(m: QueryName) -> Self {
        Self::QueryName(m)
    }
}
impl From<RequestControl> for Message {
    fn from(m: RequestControl) -> Self {
        Self::RequestControl(m)
    }
}
impl From<Standby> for Message {
    fn from(m: Standby) -> Self {
        Self::Standby(m)
    }
}
impl From<SetSpeed> for Message {
    fn from(m: SetSpeed) -> Self {
        Self::SetSpeed(m)
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
        code: CommandCode(0x4002),
        name: "ReportStatus",
        title: "Report Status",
        group: "runtime",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x2B00),
        name: "QueryName",
        title: "Query Name",
        group: "runtime",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x000D),
        name: "RequestControl",
        title: "Request Control",
        group: "runtime",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0003),
        name: "Standby",
        title: "Standby",
        group: "runtime",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0402),
        name: "SetSpeed",
        title: "Set Speed",
        group: "runtime",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
];
/// The messages the component runtime takes for every component (`runtime: [handles]`
/// or `[shares]` in the definitions), in code order: the inputs of the core service in
/// Report Services. Whatever features are on: these are codes, not types.
pub const RUNTIME_INPUTS: &[CommandCode] = &[
    CommandCode(0x0003),
    CommandCode(0x000D),
    CommandCode(0x2B00),
];
/// The messages the component runtime sends for every component (`runtime: [emits]`
/// in the definitions), in code order: the outputs of the core service in Report
/// Services.
pub const RUNTIME_OUTPUTS: &[CommandCode] = &[CommandCode(0x000D), CommandCode(0x4002)];
