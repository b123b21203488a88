use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// follow messages and types.
#[allow(clippy::module_inception)]
pub mod follow {
    #[allow(unused_imports)]
    use super::*;
    /// Set Wrench Effort (0x0405).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0405)]
    pub struct SetWrenchEffort {}
    /// Set Global Waypoint (0x040C).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x040C)]
    pub struct SetGlobalWaypoint {}
    /// Set Local Waypoint (0x040D).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x040D)]
    pub struct SetLocalWaypoint {}
    /// Set Travel Speed (0x040A).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x040A)]
    pub struct SetTravelSpeed {}
    /// Query Travel Speed (0x240A).
    ///
    /// Answered by [`ReportTravelSpeed`].
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x240A)]
    pub struct QueryTravelSpeed {}
    /// Report Travel Speed (0x440A).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x440A)]
    pub struct ReportTravelSpeed {}
    /// Report Velocity State (0x4404).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4404)]
    pub struct ReportVelocityState {}
}
pub use follow::*;
impl ::jaus::Query for QueryTravelSpeed {
    type Report = ReportTravelSpeed;
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
    /// Set Wrench Effort (0x0405).
    SetWrenchEffort(SetWrenchEffort),
    /// Set Global Waypoint (0x040C).
    SetGlobalWaypoint(SetGlobalWaypoint),
    /// Set Local Waypoint (0x040D).
    SetLocalWaypoint(SetLocalWaypoint),
    /// Set Travel Speed (0x040A).
    SetTravelSpeed(SetTravelSpeed),
    /// Query Travel Speed (0x240A).
    QueryTravelSpeed(QueryTravelSpeed),
    /// Report Travel Speed (0x440A).
    ReportTravelSpeed(ReportTravelSpeed),
    /// Report Velocity State (0x4404).
    ReportVelocityState(ReportVelocityState),
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
            0x0405 => decode_as::<SetWrenchEffort>(body),
            0x040C => decode_as::<SetGlobalWaypoint>(body),
            0x040D => decode_as::<SetLocalWaypoint>(body),
            0x040A => decode_as::<SetTravelSpeed>(body),
            0x240A => decode_as::<QueryTravelSpeed>(body),
            0x440A => decode_as::<ReportTravelSpeed>(body),
            0x4404 => decode_as::<ReportVelocityState>(body),
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
            Self::SetWrenchEffort(_) => SetWrenchEffort::CODE,
            Self::SetGlobalWaypoint(_) => SetGlobalWaypoint::CODE,
            Self::SetLocalWaypoint(_) => SetLocalWaypoint::CODE,
            Self::SetTravelSpeed(_) => SetTravelSpeed::CODE,
            Self::QueryTravelSpeed(_) => QueryTravelSpeed::CODE,
            Self::ReportTravelSpeed(_) => ReportTravelSpeed::CODE,
            Self::ReportVelocityState(_) => ReportVelocityState::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::SetWrenchEffort(_) => SetWrenchEffort::NAME,
            Self::SetGlobalWaypoint(_) => SetGlobalWaypoint::NAME,
            Self::SetLocalWaypoint(_) => SetLocalWaypoint::NAME,
            Self::SetTravelSpeed(_) => SetTravelSpeed::NAME,
            Self::QueryTravelSpeed(_) => QueryTravelSpeed::NAME,
            Self::ReportTravelSpeed(_) => ReportTravelSpeed::NAME,
            Self::ReportVelocityState(_) => ReportVelocityState::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::SetWrenchEffort(m) => m,
            Self::SetGlobalWaypoint(m) => m,
            Self::SetLocalWaypoint(m) => m,
            Self::SetTravelSpeed(m) => m,
            Self::QueryTravelSpeed(m) => m,
            Self::ReportTravelSpeed(m) => m,
            Self::ReportVelocityState(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::SetWrenchEffort(m) => m,
            Self::SetGlobalWaypoint(m) => m,
            Self::SetLocalWaypoint(m) => m,
            Self::SetTravelSpeed(m) => m,
            Self::QueryTravelSpeed(m) => m,
            Self::ReportTravelSpeed(m) => m,
            Self::ReportVelocityState(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<SetWrenchEffort> for Message {
    fn from(m: SetWrenchEffort) -> Self {
        Self::SetWrenchEffort(m)
    }
}
impl From<SetGlobalWaypoint> for Message {
    fn from(m: SetGlobalWaypoint) -> Self {
        Self::SetGlobalWaypoint(m)
    }
}
impl From<SetLocalWaypoint> for Message {
    fn from(m: SetLocalWaypoint) -> Self {
        Self::SetLocalWaypoint(m)
    }
}
impl From<SetTravelSpeed> for Message {
    fn from(m: SetTravelSpeed) -> Self {
        Self::SetTravelSpeed(m)
    }
}
impl From<QueryTravelSpeed> for Message {
    fn from(m: QueryTravelSpeed) -> Self {
        Self::QueryTravelSpeed(m)
    }
}
impl From<ReportTravelSpeed> for Message {
    fn from(m: ReportTravelSpeed) -> Self {
        Self::ReportTravelSpeed(m)
    }
}
impl From<ReportVelocityState> for Message {
    fn from(m: ReportVelocityState) -> Self {
        Self::ReportVelocityState(m)
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
        code: CommandCode(0x0405),
        name: "SetWrenchEffort",
        title: "Set Wrench Effort",
        group: "follow",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x040C),
        name: "SetGlobalWaypoint",
        title: "Set Global Waypoint",
        group: "follow",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x040D),
        name: "SetLocalWaypoint",
        title: "Set Local Waypoint",
        group: "follow",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x040A),
        name: "SetTravelSpeed",
        title: "Set Travel Speed",
        group: "follow",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x240A),
        name: "QueryTravelSpeed",
        title: "Query Travel Speed",
        group: "follow",
        report: Some("ReportTravelSpeed"),
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x440A),
        name: "ReportTravelSpeed",
        title: "Report Travel Speed",
        group: "follow",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4404),
        name: "ReportVelocityState",
        title: "Report Velocity State",
        group: "follow",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
];
