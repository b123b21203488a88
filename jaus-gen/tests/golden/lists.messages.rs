use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// lists messages and types.
#[allow(clippy::module_inception)]
pub mod lists {
    #[allow(unused_imports)]
    use super::*;
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct Waypoint {
        #[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))]
        pub x: f32,
        #[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))]
        pub y: f32,
    }
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct JointPose {
        /// One per joint: the count is in the message holding this record.
        ///
        /// Its element count is the field `joint_count`.
        #[jaus(count_var = "joint_count")]
        pub angles: Vec<u16>,
    }
    /// Set Path (0xD040).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD040)]
    pub struct SetPath {
        ///
        /// Preceded on the wire by its element count as `u8`.
        #[jaus(count = u8)]
        pub flags: Vec<u8>,
        ///
        /// Preceded on the wire by its element count as `u16`.
        #[jaus(count = u16)]
        pub waypoints: Vec<Waypoint>,
        ///
        /// Preceded on the wire by its element count as `u32`.
        #[jaus(count = u32)]
        pub stamps: Vec<u32>,
        /// To the end of the body.
        ///
        /// Elements run to the end of the body.
        #[jaus(rest)]
        pub tail: Vec<i16>,
    }
    /// Set Joints (0xD041).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD041)]
    pub struct SetJoints {
        #[jaus(var = "joint_count")]
        pub joint_count: u8,
        /// As many as `joint_count`.
        ///
        /// Its element count is the field `joint_count`.
        #[jaus(count_var = "joint_count")]
        pub positions: Vec<f32>,
        /// One fewer than joints.
        ///
        /// Its element count is the field `joint_count - 1`.
        #[jaus(count_var = "joint_count - 1")]
        pub links: Vec<u16>,
        ///
        /// Preceded on the wire by its element count as `u8`.
        #[jaus(count = u8)]
        pub poses: Vec<JointPose>,
    }
}
pub use lists::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Set Path (0xD040).
    SetPath(SetPath),
    /// Set Joints (0xD041).
    SetJoints(SetJoints),
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
            0xD040 => decode_as::<SetPath>(body),
            0xD041 => decode_as::<SetJoints>(body),
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
            Self::SetPath(_) => SetPath::CODE,
            Self::SetJoints(_) => SetJoints::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::SetPath(_) => SetPath::NAME,
            Self::SetJoints(_) => SetJoints::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::SetPath(m) => m,
            Self::SetJoints(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::SetPath(m) => m,
            Self::SetJoints(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<SetPath> for Message {
    fn from(m: SetPath) -> Self {
        Self::SetPath(m)
    }
}
impl From<SetJoints> for Message {
    fn from(m: SetJoints) -> Self {
        Self::SetJoints(m)
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
        code: CommandCode(0xD040),
        name: "SetPath",
        title: "Set Path",
        group: "lists",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD041),
        name: "SetJoints",
        title: "Set Joints",
        group: "lists",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
];
