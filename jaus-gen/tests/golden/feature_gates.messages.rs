use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// core messages and types.
#[allow(clippy::module_inception)]
pub mod core_messages {
    #[allow(unused_imports)]
    use super::*;
    /// Query Global Pose (0x2402).
    ///
    /// In `core`, answered in `sensors`.
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
}
pub use core_messages::*;
/// planning messages and types.
#[cfg(feature = "planning")]
#[allow(clippy::module_inception)]
pub mod planning {
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
    /// Query Global Waypoint (0x240C).
    ///
    /// Answered in `sensors`.
    ///
    /// Answered by [`ReportGlobalWaypoint`].
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x240C)]
    pub struct QueryGlobalWaypoint {}
}
#[cfg(feature = "planning")]
pub use planning::*;
/// sensors messages and types.
#[cfg(feature = "sensors")]
#[allow(clippy::module_inception)]
pub mod sensors {
    #[allow(unused_imports)]
    use super::*;
    ///
    /// A value the definition does not name decodes to `Unknown(n)` and re-encodes
    /// unchanged.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausEnum)]
    #[cfg_attr(all(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(repr = u8)]
    pub enum Fix {
        /// Unavailable (0).
        #[default]
        #[jaus(value = 0)]
        Unavailable,
        /// Gps (1).
        #[jaus(value = 1)]
        Gps,
        /// A value the definition does not name.
        #[jaus(unknown)]
        Unknown(u8),
    }
    /// Report Global Pose (0x4402).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4402)]
    pub struct ReportGlobalPose {
        pub fix: Fix,
    }
    /// Report Global Waypoint (0x440C).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x440C)]
    pub struct ReportGlobalWaypoint {}
}
#[cfg(feature = "sensors")]
pub use sensors::*;
#[cfg(feature = "sensors")]
impl ::jaus::Query for QueryGlobalPose {
    type Report = ReportGlobalPose;
}
#[cfg(all(feature = "planning", feature = "sensors"))]
impl ::jaus::Query for QueryGlobalWaypoint {
    type Report = ReportGlobalWaypoint;
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
    /// Query Global Pose (0x2402).
    QueryGlobalPose(QueryGlobalPose),
    /// Set Global Waypoint (0x040C).
    #[cfg(feature = "planning")]
    SetGlobalWaypoint(SetGlobalWaypoint),
    /// Query Global Waypoint (0x240C).
    #[cfg(feature = "planning")]
    QueryGlobalWaypoint(QueryGlobalWaypoint),
    /// Report Global Pose (0x4402).
    #[cfg(feature = "sensors")]
    ReportGlobalPose(ReportGlobalPose),
    /// Report Global Waypoint (0x440C).
    #[cfg(feature = "sensors")]
    ReportGlobalWaypoint(ReportGlobalWaypoint),
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
            0x2402 => decode_as::<QueryGlobalPose>(body),
            #[cfg(feature = "planning")]
            0x040C => decode_as::<SetGlobalWaypoint>(body),
            #[cfg(feature = "planning")]
            0x240C => decode_as::<QueryGlobalWaypoint>(body),
            #[cfg(feature = "sensors")]
            0x4402 => decode_as::<ReportGlobalPose>(body),
            #[cfg(feature = "sensors")]
            0x440C => decode_as::<ReportGlobalWaypoint>(body),
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
            Self::QueryGlobalPose(_) => QueryGlobalPose::CODE,
            #[cfg(feature = "planning")]
            Self::SetGlobalWaypoint(_) => SetGlobalWaypoint::CODE,
            #[cfg(feature = "planning")]
            Self::QueryGlobalWaypoint(_) => QueryGlobalWaypoint::CODE,
            #[cfg(feature = "sensors")]
            Self::ReportGlobalPose(_) => ReportGlobalPose::CODE,
            #[cfg(feature = "sensors")]
            Self::ReportGlobalWaypoint(_) => ReportGlobalWaypoint::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::QueryGlobalPose(_) => QueryGlobalPose::NAME,
            #[cfg(feature = "planning")]
            Self::SetGlobalWaypoint(_) => SetGlobalWaypoint::NAME,
            #[cfg(feature = "planning")]
            Self::QueryGlobalWaypoint(_) => QueryGlobalWaypoint::NAME,
            #[cfg(feature = "sensors")]
            Self::ReportGlobalPose(_) => ReportGlobalPose::NAME,
            #[cfg(feature = "sensors")]
            Self::ReportGlobalWaypoint(_) => ReportGlobalWaypoint::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::QueryGlobalPose(m) => m,
            #[cfg(feature = "planning")]
            Self::SetGlobalWaypoint(m) => m,
            #[cfg(feature = "planning")]
            Self::QueryGlobalWaypoint(m) => m,
            #[cfg(feature = "sensors")]
            Self::ReportGlobalPose(m) => m,
            #[cfg(feature = "sensors")]
            Self::ReportGlobalWaypoint(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::QueryGlobalPose(m) => m,
            #[cfg(feature = "planning")]
            Self::SetGlobalWaypoint(m) => m,
            #[cfg(feature = "planning")]
            Self::QueryGlobalWaypoint(m) => m,
            #[cfg(feature = "sensors")]
            Self::ReportGlobalPose(m) => m,
            #[cfg(feature = "sensors")]
            Self::ReportGlobalWaypoint(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<QueryGlobalPose> for Message {
    fn from(m: QueryGlobalPose) -> Self {
        Self::QueryGlobalPose(m)
    }
}
#[cfg(feature = "planning")]
impl From<SetGlobalWaypoint> for Message {
    fn from(m: SetGlobalWaypoint) -> Self {
        Self::SetGlobalWaypoint(m)
    }
}
#[cfg(feature = "planning")]
impl From<QueryGlobalWaypoint> for Message {
    fn from(m: QueryGlobalWaypoint) -> Self {
        Self::QueryGlobalWaypoint(m)
    }
}
#[cfg(feature = "sensors")]
impl From<ReportGlobalPose> for Message {
    fn from(m: ReportGlobalPose) -> Self {
        Self::ReportGlobalPose(m)
    }
}
#[cfg(feature = "sensors")]
impl From<ReportGlobalWaypoint> for Message {
    fn from(m: ReportGlobalWaypoint) -> Self {
        Self::ReportGlobalWaypoint(m)
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
        code: CommandCode(0x2402),
        name: "QueryGlobalPose",
        title: "Query Global Pose",
        group: "core",
        report: Some("ReportGlobalPose"),
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
    #[cfg(feature = "planning")]
    ::jaus::MessageInfo {
        code: CommandCode(0x040C),
        name: "SetGlobalWaypoint",
        title: "Set Global Waypoint",
        group: "planning",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    #[cfg(feature = "planning")]
    ::jaus::MessageInfo {
        code: CommandCode(0x240C),
        name: "QueryGlobalWaypoint",
        title: "Query Global Waypoint",
        group: "planning",
        report: Some("ReportGlobalWaypoint"),
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
    #[cfg(feature = "sensors")]
    ::jaus::MessageInfo {
        code: CommandCode(0x4402),
        name: "ReportGlobalPose",
        title: "Report Global Pose",
        group: "sensors",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    #[cfg(feature = "sensors")]
    ::jaus::MessageInfo {
        code: CommandCode(0x440C),
        name: "ReportGlobalWaypoint",
        title: "Report Global Waypoint",
        group: "sensors",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
];
