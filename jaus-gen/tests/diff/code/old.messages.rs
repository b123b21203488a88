use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// rev messages and types.
#[allow(clippy::module_inception)]
pub mod rev {
    #[allow(unused_imports)]
    use super::*;
    ///
    /// A value the definition does not name decodes to `Unknown(n)` and re-encodes
    /// unchanged.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausEnum)]
    #[cfg_attr(any(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(repr = u8)]
    pub enum Mode {
        /// Idle (0).
        #[default]
        #[jaus(value = 0)]
        Idle,
        /// Run (1).
        #[jaus(value = 1)]
        Run,
        /// Stop (2).
        #[jaus(value = 2)]
        Stop,
        /// Old (5).
        #[jaus(value = 5)]
        Old,
        /// Gone (7).
        #[jaus(value = 7)]
        Gone,
        /// A value the definition does not name.
        #[jaus(unknown)]
        Unknown(u8),
    }
    ///
    /// A value the definition does not name decodes to `Unknown(n)` and re-encodes
    /// unchanged.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausEnum)]
    #[cfg_attr(any(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(repr = u8)]
    pub enum Level {
        /// Low (0).
        #[default]
        #[jaus(value = 0)]
        Low,
        /// High (1).
        #[jaus(value = 1)]
        High,
        /// A value the definition does not name.
        #[jaus(unknown)]
        Unknown(u8),
    }
    ///
    /// A value the definition does not name decodes to `Unknown(n)` and re-encodes
    /// unchanged.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausEnum)]
    #[cfg_attr(any(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(repr = u8)]
    pub enum Unused {
        /// Nothing (0).
        #[default]
        #[jaus(value = 0)]
        Nothing,
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
    #[jaus(repr = u16)]
    pub struct Flags {
        /// Bit 0.
        #[jaus(bit = 0)]
        pub a: bool,
        /// Bits 1-2.
        #[jaus(bits = 1..= 2)]
        pub b: u8,
        /// Bits 4-5.
        #[jaus(bits = 4..= 5)]
        pub c: u8,
        /// Bit 6.
        #[jaus(bit = 6)]
        pub d: bool,
        /// Bit 7.
        #[jaus(bit = 7)]
        pub e: bool,
        /// Bits the definition does not name, kept as received.
        #[jaus(reserved)]
        #[cfg_attr(
            any(),
            serde(default, skip_serializing_if = "::jaus::codec::is_default")
        )]
        pub reserved: u16,
    }
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausBits)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(repr = u8)]
    pub struct Wide {
        /// Bit 0.
        #[jaus(bit = 0)]
        pub on: bool,
        /// Bits the definition does not name, kept as received.
        #[jaus(reserved)]
        #[cfg_attr(
            any(),
            serde(default, skip_serializing_if = "::jaus::codec::is_default")
        )]
        pub reserved: u8,
    }
    #[derive(Debug, Clone, PartialEq, ::jaus::JausUnion)]
    #[cfg_attr(any(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(tag = u8)]
    pub enum Value {
        #[jaus(tag = 0)]
        Byte(u8),
        #[jaus(tag = 1)]
        Short(i16),
        #[jaus(tag = 3)]
        Int(i32),
        #[jaus(tag = 4)]
        Old(u8),
        #[jaus(tag = 9)]
        None,
    }
    #[derive(Debug, Clone, PartialEq, ::jaus::JausUnion)]
    #[cfg_attr(any(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(tag = u8)]
    pub enum Tag {
        #[jaus(tag = 0)]
        A(u8),
    }
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct Color {
        pub red: u8,
        pub green: u8,
        pub blue: u8,
    }
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct Extent {
        #[cfg_attr(any(), serde(with = "::jaus::codec::serde_float"))]
        pub w: f32,
        #[cfg_attr(any(), serde(with = "::jaus::codec::serde_float"))]
        pub h: f32,
    }
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(presence = u8)]
    pub struct Point {
        #[cfg_attr(any(), serde(with = "::jaus::codec::serde_float"))]
        pub x: f32,
        #[cfg_attr(any(), serde(with = "::jaus::codec::serde_float"))]
        pub y: f32,
    }
    /// Set Travel Speed (0x0D01).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D01)]
    pub struct SetTravelSpeed {
        ///
        /// Unit: m/s.
        /// Range `[0, 10000]`, carried as a scaled `u16` (resolution 1.526e-1).
        #[jaus(scaled(u16, 0.0, 10000.0), unit = "m/s")]
        pub speed: f64,
    }
    /// Set Limits (0x0D02).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D02)]
    pub struct SetLimits {
        pub a: u8,
        pub b: u16,
        pub c: u32,
    }
    /// Set Mode (0x0D03).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D03)]
    pub struct SetMode {
        pub mode: Mode,
    }
    /// Set Speed Limit (0x0D04).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D04)]
    pub struct SetSpeedLimit {
        pub limit: u16,
    }
    /// Set Light (0x0D05).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D05)]
    pub struct SetLight {
        pub on: u8,
    }
    /// Report State (0x4D01).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D01, presence = u8)]
    pub struct ReportState {
        pub mode: u8,
        ///
        /// Unit: m/s.
        /// Range `[0, 100]`, carried as a scaled `u16` (resolution 1.526e-3).
        #[jaus(scaled(u16, 0.0, 100.0), unit = "m/s")]
        pub speed: f64,
        ///
        /// Unit: rad.
        /// Range `[-3.14, 3.14]`, carried as a scaled `i16` (resolution 9.583e-5).
        #[jaus(scaled(i16, -3.14, 3.14), unit = "rad")]
        pub heading: f64,
        ///
        /// A fixed 15-byte string, NUL padded.
        #[jaus(fixed = 15)]
        pub name: String,
        ///
        /// Preceded on the wire by its length as `u8`.
        #[jaus(size = u8)]
        pub notes: String,
        ///
        /// Preceded on the wire by its element count as `u8`.
        #[jaus(count = u8)]
        pub samples: Vec<u16>,
        /// Optional: presence bit 0.
        #[jaus(bit = 0)]
        #[cfg_attr(any(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub altitude: Option<i32>,
        /// Optional: presence bit 2.
        #[jaus(bit = 2)]
        #[cfg_attr(any(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub battery: Option<u8>,
    }
    /// Report Object (0x4D02).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D02, presence = u8)]
    pub struct ReportObject {
        /// Presence-vector bit 0 (no bytes of its own).
        #[jaus(flag = 0, var = "buffered")]
        pub buffered: bool,
        /// Presence-vector bit 1 (no bytes of its own).
        #[jaus(flag = 1)]
        pub has_id: bool,
        /// Present exactly when `buffered` is set.
        #[jaus(present_if = "buffered")]
        #[cfg_attr(
            any(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::codec::serde_float::option"
            )
        )]
        pub size: Option<f32>,
        /// Optional: presence bit 2.
        #[jaus(bit = 2)]
        #[cfg_attr(any(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub id: Option<u32>,
    }
    /// Report Status (0x4D03).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D03)]
    pub struct ReportStatus {
        pub status: u8,
        pub flags: Flags,
        pub reserved: u16,
    }
    /// Report Pose (0x4D04).
    #[derive(Debug, Clone, PartialEq, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D04, presence = u8)]
    pub struct ReportPose {
        pub level: Level,
        pub wide: Wide,
        pub tag: Tag,
        /// Optional: presence bit 0.
        #[jaus(bit = 0)]
        #[cfg_attr(
            any(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::codec::serde_float::option"
            )
        )]
        pub x: Option<f32>,
    }
    /// Report Legacy (0x4D05).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D05)]
    pub struct ReportLegacy {}
    /// Report Color (0x4D06).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D06)]
    pub struct ReportColor {
        pub color: Color,
    }
    /// Report Extent (0x4D07).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D07)]
    pub struct ReportExtent {
        pub extent: Extent,
    }
    /// Report Path (0x4D08).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D08)]
    pub struct ReportPath {
        ///
        /// Preceded on the wire by its element count as `u16`.
        #[jaus(count = u16)]
        pub points: Vec<Point>,
    }
    /// Report Target (0x4D09).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D09)]
    pub struct ReportTarget {
        pub target: Point,
    }
    /// Report Value (0x4D0A).
    #[derive(Debug, Clone, PartialEq, ::jaus::JausMessage)]
    #[cfg_attr(
        any(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D0A)]
    pub struct ReportValue {
        pub value: Value,
    }
}
pub use rev::*;
/// Any message of the set, by command code.
#[allow(clippy::enum_variant_names, clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    any(),
    derive(serde::Serialize, serde::Deserialize),
    serde(tag = "message", content = "fields")
)]
pub enum Message {
    /// Set Travel Speed (0x0D01).
    SetTravelSpeed(SetTravelSpeed),
    /// Set Limits (0x0D02).
    SetLimits(SetLimits),
    /// Set Mode (0x0D03).
    SetMode(SetMode),
    /// Set Speed Limit (0x0D04).
    SetSpeedLimit(SetSpeedLimit),
    /// Set Light (0x0D05).
    SetLight(SetLight),
    /// Report State (0x4D01).
    ReportState(ReportState),
    /// Report Object (0x4D02).
    ReportObject(ReportObject),
    /// Report Status (0x4D03).
    ReportStatus(ReportStatus),
    /// Report Pose (0x4D04).
    ReportPose(ReportPose),
    /// Report Legacy (0x4D05).
    ReportLegacy(ReportLegacy),
    /// Report Color (0x4D06).
    ReportColor(ReportColor),
    /// Report Extent (0x4D07).
    ReportExtent(ReportExtent),
    /// Report Path (0x4D08).
    ReportPath(ReportPath),
    /// Report Target (0x4D09).
    ReportTarget(ReportTarget),
    /// Report Value (0x4D0A).
    ReportValue(ReportValue),
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
            0x0D01 => decode_as::<SetTravelSpeed>(body),
            0x0D02 => decode_as::<SetLimits>(body),
            0x0D03 => decode_as::<SetMode>(body),
            0x0D04 => decode_as::<SetSpeedLimit>(body),
            0x0D05 => decode_as::<SetLight>(body),
            0x4D01 => decode_as::<ReportState>(body),
            0x4D02 => decode_as::<ReportObject>(body),
            0x4D03 => decode_as::<ReportStatus>(body),
            0x4D04 => decode_as::<ReportPose>(body),
            0x4D05 => decode_as::<ReportLegacy>(body),
            0x4D06 => decode_as::<ReportColor>(body),
            0x4D07 => decode_as::<ReportExtent>(body),
            0x4D08 => decode_as::<ReportPath>(body),
            0x4D09 => decode_as::<ReportTarget>(body),
            0x4D0A => decode_as::<ReportValue>(body),
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
            Self::SetTravelSpeed(_) => SetTravelSpeed::CODE,
            Self::SetLimits(_) => SetLimits::CODE,
            Self::SetMode(_) => SetMode::CODE,
            Self::SetSpeedLimit(_) => SetSpeedLimit::CODE,
            Self::SetLight(_) => SetLight::CODE,
            Self::ReportState(_) => ReportState::CODE,
            Self::ReportObject(_) => ReportObject::CODE,
            Self::ReportStatus(_) => ReportStatus::CODE,
            Self::ReportPose(_) => ReportPose::CODE,
            Self::ReportLegacy(_) => ReportLegacy::CODE,
            Self::ReportColor(_) => ReportColor::CODE,
            Self::ReportExtent(_) => ReportExtent::CODE,
            Self::ReportPath(_) => ReportPath::CODE,
            Self::ReportTarget(_) => ReportTarget::CODE,
            Self::ReportValue(_) => ReportValue::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::SetTravelSpeed(_) => SetTravelSpeed::NAME,
            Self::SetLimits(_) => SetLimits::NAME,
            Self::SetMode(_) => SetMode::NAME,
            Self::SetSpeedLimit(_) => SetSpeedLimit::NAME,
            Self::SetLight(_) => SetLight::NAME,
            Self::ReportState(_) => ReportState::NAME,
            Self::ReportObject(_) => ReportObject::NAME,
            Self::ReportStatus(_) => ReportStatus::NAME,
            Self::ReportPose(_) => ReportPose::NAME,
            Self::ReportLegacy(_) => ReportLegacy::NAME,
            Self::ReportColor(_) => ReportColor::NAME,
            Self::ReportExtent(_) => ReportExtent::NAME,
            Self::ReportPath(_) => ReportPath::NAME,
            Self::ReportTarget(_) => ReportTarget::NAME,
            Self::ReportValue(_) => ReportValue::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::SetTravelSpeed(m) => m,
            Self::SetLimits(m) => m,
            Self::SetMode(m) => m,
            Self::SetSpeedLimit(m) => m,
            Self::SetLight(m) => m,
            Self::ReportState(m) => m,
            Self::ReportObject(m) => m,
            Self::ReportStatus(m) => m,
            Self::ReportPose(m) => m,
            Self::ReportLegacy(m) => m,
            Self::ReportColor(m) => m,
            Self::ReportExtent(m) => m,
            Self::ReportPath(m) => m,
            Self::ReportTarget(m) => m,
            Self::ReportValue(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::SetTravelSpeed(m) => m,
            Self::SetLimits(m) => m,
            Self::SetMode(m) => m,
            Self::SetSpeedLimit(m) => m,
            Self::SetLight(m) => m,
            Self::ReportState(m) => m,
            Self::ReportObject(m) => m,
            Self::ReportStatus(m) => m,
            Self::ReportPose(m) => m,
            Self::ReportLegacy(m) => m,
            Self::ReportColor(m) => m,
            Self::ReportExtent(m) => m,
            Self::ReportPath(m) => m,
            Self::ReportTarget(m) => m,
            Self::ReportValue(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<SetTravelSpeed> for Message {
    fn from(m: SetTravelSpeed) -> Self {
        Self::SetTravelSpeed(m)
    }
}
impl From<SetLimits> for Message {
    fn from(m: SetLimits) -> Self {
        Self::SetLimits(m)
    }
}
impl From<SetMode> for Message {
    fn from(m: SetMode) -> Self {
        Self::SetMode(m)
    }
}
impl From<SetSpeedLimit> for Message {
    fn from(m: SetSpeedLimit) -> Self {
        Self::SetSpeedLimit(m)
    }
}
impl From<SetLight> for Message {
    fn from(m: SetLight) -> Self {
        Self::SetLight(m)
    }
}
impl From<ReportState> for Message {
    fn from(m: ReportState) -> Self {
        Self::ReportState(m)
    }
}
impl From<ReportObject> for Message {
    fn from(m: ReportObject) -> Self {
        Self::ReportObject(m)
    }
}
impl From<ReportStatus> for Message {
    fn from(m: ReportStatus) -> Self {
        Self::ReportStatus(m)
    }
}
impl From<ReportPose> for Message {
    fn from(m: ReportPose) -> Self {
        Self::ReportPose(m)
    }
}
impl From<ReportLegacy> for Message {
    fn from(m: ReportLegacy) -> Self {
        Self::ReportLegacy(m)
    }
}
impl From<ReportColor> for Message {
    fn from(m: ReportColor) -> Self {
        Self::ReportColor(m)
    }
}
impl From<ReportExtent> for Message {
    fn from(m: ReportExtent) -> Self {
        Self::ReportExtent(m)
    }
}
impl From<ReportPath> for Message {
    fn from(m: ReportPath) -> Self {
        Self::ReportPath(m)
    }
}
impl From<ReportTarget> for Message {
    fn from(m: ReportTarget) -> Self {
        Self::ReportTarget(m)
    }
}
impl From<ReportValue> for Message {
    fn from(m: ReportValue) -> Self {
        Self::ReportValue(m)
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
        code: CommandCode(0x0D01),
        name: "SetTravelSpeed",
        title: "Set Travel Speed",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0D02),
        name: "SetLimits",
        title: "Set Limits",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0D03),
        name: "SetMode",
        title: "Set Mode",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0D04),
        name: "SetSpeedLimit",
        title: "Set Speed Limit",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0D05),
        name: "SetLight",
        title: "Set Light",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D01),
        name: "ReportState",
        title: "Report State",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D02),
        name: "ReportObject",
        title: "Report Object",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D03),
        name: "ReportStatus",
        title: "Report Status",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D04),
        name: "ReportPose",
        title: "Report Pose",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D05),
        name: "ReportLegacy",
        title: "Report Legacy",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D06),
        name: "ReportColor",
        title: "Report Color",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D07),
        name: "ReportExtent",
        title: "Report Extent",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D08),
        name: "ReportPath",
        title: "Report Path",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D09),
        name: "ReportTarget",
        title: "Report Target",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D0A),
        name: "ReportValue",
        title: "Report Value",
        group: "rev",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
];
