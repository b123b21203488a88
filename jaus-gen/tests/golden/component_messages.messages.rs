use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// drive messages and types.
#[allow(clippy::module_inception)]
pub mod drive {
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
    /// Set Travel Speed (0x040A).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x040A)]
    pub struct SetTravelSpeed {}
    /// Query Wrench Effort (0x2405).
    ///
    /// Answered by [`ReportWrenchEffort`].
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x2405)]
    pub struct QueryWrenchEffort {}
    /// Report Wrench Effort (0x4405).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4405)]
    pub struct ReportWrenchEffort {}
    /// Query Global Pose (0x2402).
    ///
    /// Answered by [`ReportGlobalPose`].
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x2402)]
    pub struct QueryGlobalPose {}
    /// Report Global Pose (0x4402).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4402)]
    pub struct ReportGlobalPose {}
}
pub use drive::*;
impl ::jaus::Query for QueryWrenchEffort {
    type Report = ReportWrenchEffort;
}
impl ::jaus::Query for QueryGlobalPose {
    type Report = ReportGlobalPose;
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
    /// Set Travel Speed (0x040A).
    SetTravelSpeed(SetTravelSpeed),
    /// Query Wrench Effort (0x2405).
    QueryWrenchEffort(QueryWrenchEffort),
    /// Report Wrench Effort (0x4405).
    ReportWrenchEffort(ReportWrenchEffort),
    /// Query Global Pose (0x2402).
    QueryGlobalPose(QueryGlobalPose),
    /// Report Global Pose (0x4402).
    ReportGlobalPose(ReportGlobalPose),
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
            0x040A => decode_as::<SetTravelSpeed>(body),
            0x2405 => decode_as::<QueryWrenchEffort>(body),
            0x4405 => decode_as::<ReportWrenchEffort>(body),
            0x2402 => decode_as::<QueryGlobalPose>(body),
            0x4402 => decode_as::<ReportGlobalPose>(body),
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
            Self::SetTravelSpeed(_) => SetTravelSpeed::CODE,
            Self::QueryWrenchEffort(_) => QueryWrenchEffort::CODE,
            Self::ReportWrenchEffort(_) => ReportWrenchEffort::CODE,
            Self::QueryGlobalPose(_) => QueryGlobalPose::CODE,
            Self::ReportGlobalPose(_) => ReportGlobalPose::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::SetWrenchEffort(_) => SetWrenchEffort::NAME,
            Self::SetTravelSpeed(_) => SetTravelSpeed::NAME,
            Self::QueryWrenchEffort(_) => QueryWrenchEffort::NAME,
            Self::ReportWrenchEffort(_) => ReportWrenchEffort::NAME,
            Self::QueryGlobalPose(_) => QueryGlobalPose::NAME,
            Self::ReportGlobalPose(_) => ReportGlobalPose::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::SetWrenchEffort(m) => m,
            Self::SetTravelSpeed(m) => m,
            Self::QueryWrenchEffort(m) => m,
            Self::ReportWrenchEffort(m) => m,
            Self::QueryGlobalPose(m) => m,
            Self::ReportGlobalPose(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::SetWrenchEffort(m) => m,
            Self::SetTravelSpeed(m) => m,
            Self::QueryWrenchEffort(m) => m,
            Self::ReportWrenchEffort(m) => m,
            Self::QueryGlobalPose(m) => m,
            Self::ReportGlobalPose(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<SetWrenchEffort> for Message {
    fn from(m: SetWrenchEffort) -> Self {
        Self::SetWrenchEffort(m)
    }
}
impl From<SetTravelSpeed> for Message {
    fn from(m: SetTravelSpeed) -> Self {
        Self::SetTravelSpeed(m)
    }
}
impl From<QueryWrenchEffort> for Message {
    fn from(m: QueryWrenchEffort) -> Self {
        Self::QueryWrenchEffort(m)
    }
}
impl From<ReportWrenchEffort> for Message {
    fn from(m: ReportWrenchEffort) -> Self {
        Self::ReportWrenchEffort(m)
    }
}
impl From<QueryGlobalPose> for Message {
    fn from(m: QueryGlobalPose) -> Self {
        Self::QueryGlobalPose(m)
    }
}
impl From<ReportGlobalPose> for Message {
    fn from(m: ReportGlobalPose) -> Self {
        Self::ReportGlobalPose(m)
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
        group: "drive",
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
        group: "drive",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x2405),
        name: "QueryWrenchEffort",
        title: "Query Wrench Effort",
        group: "drive",
        report: Some("ReportWrenchEffort"),
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4405),
        name: "ReportWrenchEffort",
        title: "Report Wrench Effort",
        group: "drive",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x2402),
        name: "QueryGlobalPose",
        title: "Query Global Pose",
        group: "drive",
        report: Some("ReportGlobalPose"),
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4402),
        name: "ReportGlobalPose",
        title: "Report Global Pose",
        group: "drive",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
];
