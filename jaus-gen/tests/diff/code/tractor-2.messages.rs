use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
#[allow(unused_imports)]
use ::jaus::messages::*;
/// My Tractor messages and types.
///
/// Experimental messages of the my-tractor crate.
#[allow(clippy::module_inception)]
pub mod my_tractor {
    #[allow(unused_imports)]
    use super::*;
    ///
    /// A value the definition does not name decodes to `Unknown(n)` and re-encodes
    /// unchanged.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausEnum)]
    #[cfg_attr(any(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(repr = u8)]
    pub enum ImplementMode {
        /// Raised (0).
        #[default]
        #[jaus(value = 0)]
        Raised,
        /// Working (1).
        #[jaus(value = 1)]
        Working,
        /// Floating (2).
        #[jaus(value = 2)]
        Floating,
        /// A value the definition does not name.
        #[jaus(unknown)]
        Unknown(u8),
    }
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausBits)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(repr = u8)]
    pub struct HitchFlags {
        /// Bit 0.
        #[jaus(bit = 0)]
        pub locked: bool,
        /// Bit 1.
        #[jaus(bit = 1)]
        pub floating: bool,
        /// Bit 2.
        #[jaus(bit = 2)]
        pub overload: bool,
        /// Bits the definition does not name, kept as received.
        #[jaus(reserved)]
        #[cfg_attr(
            any(),
            serde(default, skip_serializing_if = "::jaus::codec::is_default")
        )]
        pub reserved: u8,
    }
    ///
    /// A value the definition does not name decodes to `Unknown(n)` and re-encodes
    /// unchanged.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausEnum)]
    #[cfg_attr(any(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(repr = u8)]
    pub enum FaultCode {
        /// None (0).
        #[default]
        #[jaus(value = 0)]
        None,
        /// Blocked (1).
        #[jaus(value = 1)]
        Blocked,
        /// A value the definition does not name.
        #[jaus(unknown)]
        Unknown(u8),
    }
    /// Set Implement Depth (0xD200).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD200)]
    pub struct SetImplementDepth {
        pub time_stamp: TimeStamp,
        ///
        /// Unit: m.
        /// Range `[0, 1.5]`, carried as a scaled `u16` (resolution 2.289e-5).
        #[jaus(scaled(u16, 0.0, 1.5), unit = "m")]
        pub depth: f64,
    }
    /// Report Implement State (0xD201).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD201, presence = u8)]
    pub struct ReportImplementState {
        pub time_stamp: TimeStamp,
        pub mode: ImplementMode,
        ///
        /// Unit: m.
        /// Range `[0, 1.5]`, carried as a scaled `u16` (resolution 2.289e-5).
        #[jaus(scaled(u16, 0.0, 1.5), unit = "m")]
        pub depth: f64,
        pub hitch: HitchFlags,
        ///
        /// Unit: radian.
        /// Range `[-0.5, 0.5]`, carried as a scaled `i16` (resolution 1.526e-5).
        /// Optional: presence bit 0.
        #[jaus(bit = 0, scaled(i16, -0.5, 0.5), unit = "radian")]
        #[cfg_attr(any(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub hitch_angle: Option<f64>,
        ///
        /// Unit: N.
        /// Range `[0, 60000]`, carried as a scaled `u16` (resolution 9.155e-1).
        /// Optional: presence bit 1.
        #[jaus(bit = 1, scaled(u16, 0.0, 60000.0), unit = "N")]
        #[cfg_attr(any(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub draft_force: Option<f64>,
    }
    /// Set Implement Mode (0xD202).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD202)]
    pub struct SetImplementMode {
        pub mode: ImplementMode,
    }
    /// Query Implement State (0xD203).
    ///
    /// Answered by [`ReportImplementState`].
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD203)]
    pub struct QueryImplementState {}
    /// Report Implement Fault (0xD204).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD204)]
    pub struct ReportImplementFault {
        pub time_stamp: TimeStamp,
        pub fault: FaultCode,
    }
    /// Clear Implement Fault (0xD205).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD205)]
    pub struct ClearImplementFault {}
}
pub use my_tractor::*;
impl ::jaus::Query for QueryImplementState {
    type Report = ReportImplementState;
}
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    any(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Set Implement Depth (0xD200).
    SetImplementDepth(SetImplementDepth),
    /// Report Implement State (0xD201).
    ReportImplementState(ReportImplementState),
    /// Set Implement Mode (0xD202).
    SetImplementMode(SetImplementMode),
    /// Query Implement State (0xD203).
    QueryImplementState(QueryImplementState),
    /// Report Implement Fault (0xD204).
    ReportImplementFault(ReportImplementFault),
    /// Clear Implement Fault (0xD205).
    ClearImplementFault(ClearImplementFault),
    /// A message of the SDK's set: a standard message, or one neither set defines
    /// (kept raw).
    #[cfg_attr(any(), serde(untagged))]
    Jaus(::jaus::messages::Message),
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
            0xD200 => decode_as::<SetImplementDepth>(body),
            0xD201 => decode_as::<ReportImplementState>(body),
            0xD202 => decode_as::<SetImplementMode>(body),
            0xD203 => decode_as::<QueryImplementState>(body),
            0xD204 => decode_as::<ReportImplementFault>(body),
            0xD205 => decode_as::<ClearImplementFault>(body),
            _ => ::jaus::messages::Message::decode(code, body).map(Self::Jaus),
        }
    }
    /// Like [`decode`](Self::decode), but a code this set does not define is an error
    /// instead of a [`Message::Raw`].
    pub fn decode_known(
        code: CommandCode,
        body: &[u8],
    ) -> ::core::result::Result<Self, DecodeError> {
        match Self::decode(code, body)? {
            Self::Jaus(::jaus::messages::Message::Raw(_)) => {
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
            Self::SetImplementDepth(_) => SetImplementDepth::CODE,
            Self::ReportImplementState(_) => ReportImplementState::CODE,
            Self::SetImplementMode(_) => SetImplementMode::CODE,
            Self::QueryImplementState(_) => QueryImplementState::CODE,
            Self::ReportImplementFault(_) => ReportImplementFault::CODE,
            Self::ClearImplementFault(_) => ClearImplementFault::CODE,
            Self::Jaus(m) => m.code(),
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::SetImplementDepth(_) => SetImplementDepth::NAME,
            Self::ReportImplementState(_) => ReportImplementState::NAME,
            Self::SetImplementMode(_) => SetImplementMode::NAME,
            Self::QueryImplementState(_) => QueryImplementState::NAME,
            Self::ReportImplementFault(_) => ReportImplementFault::NAME,
            Self::ClearImplementFault(_) => ClearImplementFault::NAME,
            Self::Jaus(m) => m.name(),
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::SetImplementDepth(m) => m,
            Self::ReportImplementState(m) => m,
            Self::SetImplementMode(m) => m,
            Self::QueryImplementState(m) => m,
            Self::ReportImplementFault(m) => m,
            Self::ClearImplementFault(m) => m,
            Self::Jaus(m) => m.body(),
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::SetImplementDepth(m) => m,
            Self::ReportImplementState(m) => m,
            Self::SetImplementMode(m) => m,
            Self::QueryImplementState(m) => m,
            Self::ReportImplementFault(m) => m,
            Self::ClearImplementFault(m) => m,
            Self::Jaus(m) => m.body_mut(),
        }
    }
}
impl From<::jaus::messages::Message> for Message {
    fn from(m: ::jaus::messages::Message) -> Self {
        Self::Jaus(m)
    }
}
impl From<SetImplementDepth> for Message {
    fn from(m: SetImplementDepth) -> Self {
        Self::SetImplementDepth(m)
    }
}
impl From<ReportImplementState> for Message {
    fn from(m: ReportImplementState) -> Self {
        Self::ReportImplementState(m)
    }
}
impl From<SetImplementMode> for Message {
    fn from(m: SetImplementMode) -> Self {
        Self::SetImplementMode(m)
    }
}
impl From<QueryImplementState> for Message {
    fn from(m: QueryImplementState) -> Self {
        Self::QueryImplementState(m)
    }
}
impl From<ReportImplementFault> for Message {
    fn from(m: ReportImplementFault) -> Self {
        Self::ReportImplementFault(m)
    }
}
impl From<ClearImplementFault> for Message {
    fn from(m: ClearImplementFault) -> Self {
        Self::ClearImplementFault(m)
    }
}
impl ::jaus::MessageSet for Message {
    fn decode(
        code: CommandCode,
        body: &[u8],
    ) -> ::core::result::Result<Self, DecodeError> {
        Message::decode(code, body)
    }
    fn code(&self) -> CommandCode {
        Message::code(self)
    }
    fn name(&self) -> &'static str {
        Message::name(self)
    }
    fn standard(&self) -> Option<&::jaus::messages::Message> {
        match self {
            Self::Jaus(m) => Some(m),
            #[allow(unreachable_patterns)]
            _ => None,
        }
    }
    fn from_standard(m: ::jaus::messages::Message) -> Self {
        Self::Jaus(m)
    }
    fn query_of(report: CommandCode) -> Option<CommandCode> {
        match report.0 {
            0xD201 => Some(CommandCode(0xD203)),
            _ => <::jaus::messages::Message as ::jaus::MessageSet>::query_of(report),
        }
    }
    fn report_of(query: CommandCode) -> Option<CommandCode> {
        match query.0 {
            0xD203 => Some(CommandCode(0xD201)),
            _ => <::jaus::messages::Message as ::jaus::MessageSet>::report_of(query),
        }
    }
    fn info(code: CommandCode) -> Option<&'static ::jaus::MessageInfo> {
        MESSAGES
            .iter()
            .find(|m| m.code == code)
            .or_else(|| <::jaus::messages::Message as ::jaus::MessageSet>::info(code))
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
        code: CommandCode(0xD200),
        name: "SetImplementDepth",
        title: "Set Implement Depth",
        group: "my_tractor",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD201),
        name: "ReportImplementState",
        title: "Report Implement State",
        group: "my_tractor",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD202),
        name: "SetImplementMode",
        title: "Set Implement Mode",
        group: "my_tractor",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD203),
        name: "QueryImplementState",
        title: "Query Implement State",
        group: "my_tractor",
        report: Some("ReportImplementState"),
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD204),
        name: "ReportImplementFault",
        title: "Report Implement Fault",
        group: "my_tractor",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD205),
        name: "ClearImplementFault",
        title: "Clear Implement Fault",
        group: "my_tractor",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
];
