use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// scaled messages and types.
#[allow(clippy::module_inception)]
pub mod scaled {
    #[allow(unused_imports)]
    use super::*;
    /// Report Motion (0xD001).
    ///
    /// Scaled values of every integer type.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD001)]
    pub struct ReportMotion {
        /// Signed: the bias is the midpoint.
        ///
        /// Unit: rad.
        /// Range `[-3.14159265, 3.14159265]`, carried as a scaled `i16` (resolution 9.588e-5).
        #[jaus(scaled(i16, -3.14159265, 3.14159265), unit = "rad")]
        pub roll: f64,
        /// Unsigned: the bias is the lower limit.
        ///
        /// Unit: m/s.
        /// Range `[0, 10]`, carried as a scaled `u8` (resolution 3.922e-2).
        #[jaus(scaled(u8, 0.0, 10.0), unit = "m/s")]
        pub speed: f64,
        ///
        /// Unit: %.
        /// Range `[0, 100]`, carried as a scaled `u16` (resolution 1.526e-3).
        #[jaus(scaled(u16, 0.0, 100.0), unit = "%")]
        pub level: f64,
        ///
        /// Unit: m.
        /// Range `[-10000, 35000]`, carried as a scaled `u32` (resolution 1.048e-5).
        #[jaus(scaled(u32, -10000.0, 35000.0), unit = "m")]
        pub altitude: f64,
        ///
        /// Unit: deg.
        /// Range `[-90, 90]`, carried as a scaled `i32` (resolution 4.191e-8).
        #[jaus(scaled(i32, -90.0, 90.0), unit = "deg")]
        pub latitude: f64,
        ///
        /// Unit: m.
        /// Range `[0, 1000000000]`, carried as a scaled `u64` (resolution 5.421e-11).
        #[jaus(scaled(u64, 0.0, 1000000000.0), unit = "m")]
        pub odometer: f64,
        ///
        /// Range `[-1, 1]`, carried as a scaled `i64` (resolution 1.084e-19).
        #[jaus(scaled(i64, -1.0, 1.0))]
        pub trim: f64,
        /// Each element scaled.
        ///
        /// Unit: °C.
        /// Preceded on the wire by its element count as `u8`.
        /// Each element: Range `[-40, 125]`, carried as a scaled `i16` (resolution 2.518e-3).
        #[jaus(count = u8, scaled(i16, -40.0, 125.0), unit = "°C")]
        pub temperatures: Vec<f64>,
    }
}
pub use scaled::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    all(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Report Motion (0xD001).
    ReportMotion(ReportMotion),
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
            0xD001 => decode_as::<ReportMotion>(body),
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
            Self::ReportMotion(_) => ReportMotion::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::ReportMotion(_) => ReportMotion::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::ReportMotion(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::ReportMotion(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<ReportMotion> for Message {
    fn from(m: ReportMotion) -> Self {
        Self::ReportMotion(m)
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
        code: CommandCode(0xD001),
        name: "ReportMotion",
        title: "Report Motion",
        group: "scaled",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
];
