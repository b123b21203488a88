use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
#[allow(unused_imports)]
use ::jaus::messages::*;
::jaus::__jaus_requires_platform!(
    "vendor/acme.yaml:100:27: component `TankMonitor` uses message `QueryGlobalPose` of group `platform`"
);
/// ACME experimental messages and types.
///
/// Tank telemetry of the ACME tracked carrier (experimental, 0xD100-0xD1FF).
#[allow(clippy::module_inception)]
pub mod acme {
    #[allow(unused_imports)]
    use super::*;
    /// What a tank holds.
    ///
    /// A value the definition does not name decodes to `Unknown(n)` and re-encodes
    /// unchanged.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausEnum)]
    #[cfg_attr(all(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(repr = u8)]
    pub enum TankKind {
        /// Diesel.
        #[default]
        #[jaus(value = 0)]
        Fuel,
        /// Water (1).
        #[jaus(value = 1)]
        Water,
        /// Hydraulic (7).
        #[jaus(value = 7)]
        Hydraulic,
        /// A value the definition does not name.
        #[jaus(unknown)]
        Unknown(u8),
    }
    /// Tank state bits.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausBits)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(repr = u16)]
    pub struct TankFlags {
        /// Below the low-level mark.
        ///
        /// Bit 0.
        #[jaus(bit = 0)]
        pub low: bool,
        /// Bit 1.
        #[jaus(bit = 1)]
        pub leaking: bool,
        /// Level sensor in use.
        ///
        /// Bits 4-7.
        #[jaus(bits = 4..= 7)]
        pub sensor_id: u8,
        /// Bits the definition does not name, kept as received.
        #[jaus(reserved)]
        #[cfg_attr(
            all(),
            serde(default, skip_serializing_if = "::jaus::codec::is_default")
        )]
        pub reserved: u16,
    }
    /// A sensor reading, tagged by its type.
    #[derive(Debug, Clone, PartialEq, ::jaus::JausUnion)]
    #[cfg_attr(all(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(tag = u8)]
    pub enum Reading {
        #[jaus(tag = 1)]
        Level(u16),
        #[jaus(tag = 2)]
        Temperature(#[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))] f32),
        #[jaus(tag = 3)]
        Missing,
    }
    /// One tank.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(presence = u8)]
    pub struct Tank {
        /// Contents.
        pub kind: TankKind,
        /// Fill level.
        ///
        /// Unit: %.
        /// Range `[0, 100]`, carried as a scaled `u16` (resolution 1.526e-3).
        #[jaus(scaled(u16, 0.0, 100.0), unit = "%")]
        pub level: f64,
        /// State.
        pub flags: TankFlags,
        /// Operator label.
        ///
        /// Preceded on the wire by its length as `u8`.
        /// Optional: presence bit 0.
        #[jaus(bit = 0, size = u8)]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub label: Option<String>,
        /// Probe temperatures.
        ///
        /// Unit: °C.
        /// Preceded on the wire by its element count as `u8`.
        /// Each element: Range `[-40, 125]`, carried as a scaled `i16` (resolution 2.518e-3).
        /// Optional: presence bit 1.
        #[jaus(bit = 1, count = u8, scaled(i16, -40.0, 125.0), unit = "°C")]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub temperatures: Option<Vec<f64>>,
    }
    /// Query Tanks (0xD100).
    ///
    /// Asks for the tank report.
    ///
    /// Answered by [`ReportTanks`].
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD100)]
    pub struct QueryTanks {
        /// Tank fields wanted.
        pub presence_vector: u8,
    }
    /// Report Tanks (0xF100).
    ///
    /// The tanks of the carrier.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xF100, presence = u16)]
    pub struct ReportTanks {
        /// Vehicle name.
        ///
        /// A fixed 15-byte string, NUL padded.
        #[jaus(fixed = 15)]
        pub vehicle: String,
        /// Every tank.
        ///
        /// Preceded on the wire by its element count as `u8`.
        #[jaus(count = u8)]
        pub tanks: Vec<Tank>,
        /// Raw readings.
        ///
        /// Preceded on the wire by its element count as `u16`.
        /// Optional: presence bit 0.
        #[jaus(bit = 0, count = u16)]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub readings: Option<Vec<Reading>>,
        /// Controller serial number.
        ///
        /// A fixed 4-byte blob, NUL padded.
        /// Optional: presence bit 3.
        #[jaus(bit = 3, fixed = 4)]
        #[cfg_attr(
            all(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::hex::serde_opt"
            )
        )]
        pub serial: Option<Vec<u8>>,
        /// Controller uptime when measured.
        ///
        /// Unit: s.
        /// Optional: presence bit 2.
        #[jaus(bit = 2)]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub uptime: Option<u32>,
        /// Free text.
        ///
        /// Runs to the end of the body.
        /// Sent with a terminating NUL.
        /// Optional: presence bit 9.
        #[jaus(bit = 9, rest, nul)]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub note: Option<String>,
    }
    /// Replay Tanks (0xD101).
    ///
    /// Wraps another message, with and without its header.
    #[derive(Debug, Clone, PartialEq, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD101)]
    pub struct ReplayTanks {
        /// Code of `wrapped`.
        pub wrapped_code: u16,
        /// A body without header.
        ///
        /// Preceded on the wire by its length as `u32`.
        #[jaus(size = u32)]
        #[cfg_attr(all(), serde(with = "::jaus::hex::serde"))]
        pub wrapped: Vec<u8>,
        /// A whole message with header.
        ///
        /// A whole JAUS message, header included.
        /// Preceded on the wire by its byte length as `u16`.
        #[jaus(size = u16)]
        pub packet: ::jaus::Packet,
        /// Anything after.
        ///
        /// Runs to the end of the body.
        #[jaus(rest)]
        #[cfg_attr(all(), serde(with = "::jaus::hex::serde"))]
        pub tail: Vec<u8>,
    }
    impl ReplayTanks {
        /// Decodes `wrapped` as the message whose code is `wrapped_code`.
        pub fn wrapped_decoded(
            &self,
        ) -> ::core::result::Result<Message, ::jaus::codec::DecodeError> {
            let code = ::jaus::CommandCode(self.wrapped_code);
            Message::decode(code, &self.wrapped)
        }
    }
    /// Set Tank Valve (0xD102).
    ///
    /// Opens or closes the drain valve of one tank (executed only for the component in control).
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD102)]
    pub struct SetTankValve {
        /// Tank index.
        pub tank: u8,
        /// 1 opens the valve, 0 closes it.
        pub open: u8,
    }
    /// Report Tank Telemetry (0xD103).
    ///
    /// Level of one tank, sent on every change while draining.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0xD103)]
    pub struct ReportTankTelemetry {
        /// When measured (the SDK's core type).
        pub time_stamp: TimeStamp,
        /// Tank index.
        pub tank: u8,
        /// Fill level.
        ///
        /// Unit: %.
        /// Range `[0, 100]`, carried as a scaled `u16` (resolution 1.526e-3).
        #[jaus(scaled(u16, 0.0, 100.0), unit = "%")]
        pub level: f64,
    }
}
pub use acme::*;
impl ::jaus::Query for QueryTanks {
    type Report = ReportTanks;
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
    /// Query Tanks (0xD100).
    QueryTanks(QueryTanks),
    /// Report Tanks (0xF100).
    ReportTanks(ReportTanks),
    /// Replay Tanks (0xD101).
    ReplayTanks(ReplayTanks),
    /// Set Tank Valve (0xD102).
    SetTankValve(SetTankValve),
    /// Report Tank Telemetry (0xD103).
    ReportTankTelemetry(ReportTankTelemetry),
    /// A message of the SDK's set: a standard message, or one neither set defines
    /// (kept raw).
    #[cfg_attr(all(), serde(untagged))]
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
            0xD100 => decode_as::<QueryTanks>(body),
            0xF100 => decode_as::<ReportTanks>(body),
            0xD101 => decode_as::<ReplayTanks>(body),
            0xD102 => decode_as::<SetTankValve>(body),
            0xD103 => decode_as::<ReportTankTelemetry>(body),
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
            Self::QueryTanks(_) => QueryTanks::CODE,
            Self::ReportTanks(_) => ReportTanks::CODE,
            Self::ReplayTanks(_) => ReplayTanks::CODE,
            Self::SetTankValve(_) => SetTankValve::CODE,
            Self::ReportTankTelemetry(_) => ReportTankTelemetry::CODE,
            Self::Jaus(m) => m.code(),
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::QueryTanks(_) => QueryTanks::NAME,
            Self::ReportTanks(_) => ReportTanks::NAME,
            Self::ReplayTanks(_) => ReplayTanks::NAME,
            Self::SetTankValve(_) => SetTankValve::NAME,
            Self::ReportTankTelemetry(_) => ReportTankTelemetry::NAME,
            Self::Jaus(m) => m.name(),
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::QueryTanks(m) => m,
            Self::ReportTanks(m) => m,
            Self::ReplayTanks(m) => m,
            Self::SetTankValve(m) => m,
            Self::ReportTankTelemetry(m) => m,
            Self::Jaus(m) => m.body(),
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::QueryTanks(m) => m,
            Self::ReportTanks(m) => m,
            Self::ReplayTanks(m) => m,
            Self::SetTankValve(m) => m,
            Self::ReportTankTelemetry(m) => m,
            Self::Jaus(m) => m.body_mut(),
        }
    }
}
impl From<::jaus::messages::Message> for Message {
    fn from(m: ::jaus::messages::Message) -> Self {
        Self::Jaus(m)
    }
}
impl From<QueryTanks> for Message {
    fn from(m: QueryTanks) -> Self {
        Self::QueryTanks(m)
    }
}
impl From<ReportTanks> for Message {
    fn from(m: ReportTanks) -> Self {
        Self::ReportTanks(m)
    }
}
impl From<ReplayTanks> for Message {
    fn from(m: ReplayTanks) -> Self {
        Self::ReplayTanks(m)
    }
}
impl From<SetTankValve> for Message {
    fn from(m: SetTankValve) -> Self {
        Self::SetTankValve(m)
    }
}
impl From<ReportTankTelemetry> for Message {
    fn from(m: ReportTankTelemetry) -> Self {
        Self::ReportTankTelemetry(m)
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
            0xF100 => Some(CommandCode(0xD100)),
            _ => <::jaus::messages::Message as ::jaus::MessageSet>::query_of(report),
        }
    }
    fn report_of(query: CommandCode) -> Option<CommandCode> {
        match query.0 {
            0xD100 => Some(CommandCode(0xF100)),
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
        code: CommandCode(0xD100),
        name: "QueryTanks",
        title: "Query Tanks",
        group: "acme",
        report: Some("ReportTanks"),
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xF100),
        name: "ReportTanks",
        title: "Report Tanks",
        group: "acme",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD101),
        name: "ReplayTanks",
        title: "Replay Tanks",
        group: "acme",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Experimental,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD102),
        name: "SetTankValve",
        title: "Set Tank Valve",
        group: "acme",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0xD103),
        name: "ReportTankTelemetry",
        title: "Report Tank Telemetry",
        group: "acme",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
];
