use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// strings messages and types.
#[allow(clippy::module_inception)]
pub mod strings {
    #[allow(unused_imports)]
    use super::*;
    /// Report Labels (0xD060).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD060)]
    pub struct ReportLabels {
        /// NUL padded.
        ///
        /// A fixed 8-byte string, NUL padded.
        #[jaus(fixed = 8)]
        pub fixed: String,
        ///
        /// Preceded on the wire by its length as `u16`.
        #[jaus(size = u16)]
        pub prefixed: String,
        ///
        /// A NUL-terminated string.
        #[jaus(nul_terminated)]
        pub c_string: String,
        ///
        /// A fixed 4-byte blob, NUL padded.
        #[jaus(fixed = 4)]
        #[cfg_attr(all(), serde(with = "::jaus::hex::serde"))]
        pub serial: Vec<u8>,
        ///
        /// Preceded on the wire by its length as `u32`.
        #[jaus(size = u32)]
        #[cfg_attr(all(), serde(with = "::jaus::hex::serde"))]
        pub blob: Vec<u8>,
        ///
        /// Runs to the end of the body.
        /// Sent with a terminating NUL.
        #[jaus(rest, nul)]
        pub text: String,
    }
    /// Report Identity (0xD061).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD061)]
    pub struct ReportIdentity {
        pub kind: u8,
        /// A shorter field is accepted on receive.
        ///
        /// A fixed 16-byte string, NUL padded.
        /// A shorter field is accepted on receive.
        #[jaus(fixed = 16, accept_short)]
        pub identification: String,
    }
    /// Report Image (0xD062).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD062)]
    pub struct ReportImage {
        pub format: u8,
        ///
        /// Runs to the end of the body.
        #[jaus(rest)]
        #[cfg_attr(all(), serde(with = "::jaus::hex::serde"))]
        pub data: Vec<u8>,
    }
    /// Report Note (0xD063).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD063)]
    pub struct ReportNote {
        ///
        /// Runs to the end of the body.
        #[jaus(rest)]
        pub note: String,
    }
}
pub use strings::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Report Labels (0xD060).
    ReportLabels(ReportLabels),
    /// Report Identity (0xD061).
    ReportIdentity(ReportIdentity),
    /// Report Image (0xD062).
    ReportImage(ReportImage),
    /// Report Note (0xD063).
    ReportNote(ReportNote),
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
            0xD060 => decode_as::<ReportLabels>(body),
            0xD061 => decode_as::<ReportIdentity>(body),
            0xD062 => decode_as::<ReportImage>(body),
            0xD063 => decode_as::<ReportNote>(body),
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
            Self::ReportLabels(_) => ReportLabels::CODE,
            Self::ReportIdentity(_) => ReportIdentity::CODE,
            Self::ReportImage(_) => ReportImage::CODE,
            Self::ReportNote(_) => ReportNote::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::ReportLabels(_) => ReportLabels::NAME,
            Self::ReportIdentity(_) => ReportIdentity::NAME,
            Self::ReportImage(_) => ReportImage::NAME,
            Self::ReportNote(_) => ReportNote::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::ReportLabels(m) => m,
            Self::ReportIdentity(m) => m,
            Self::ReportImage(m) => m,
            Self::ReportNote(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::ReportLabels(m) => m,
            Self::ReportIdentity(m) => m,
            Self::ReportImage(m) => m,
            Self::ReportNote(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<ReportLabels> for Message {
    fn from(m: ReportLabels) -> Self {
        Self::ReportLabels(m)
    }
}
impl From<ReportIdentity> for Message {
    fn from(m: ReportIdentity) -> Self {
        Self::ReportIdentity(m)
    }
}
impl From<ReportImage> for Message {
    fn from(m: ReportImage) -> Self {
        Self::ReportImage(m)
    }
}
impl From<ReportNote> for Message {
    fn from(m: ReportNote) -> Self {
        Self::ReportNote(m)
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
        code: CommandCode(0xD060),
        name: "ReportLabels",
        title: "Report Labels",
        group: "strings",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD061),
        name: "ReportIdentity",
        title: "Report Identity",
        group: "strings",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD062),
        name: "ReportImage",
        title: "Report Image",
        group: "strings",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD063),
        name: "ReportNote",
        title: "Report Note",
        group: "strings",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
];
