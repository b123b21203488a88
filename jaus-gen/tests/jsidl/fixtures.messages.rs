use ::jaus::codec::{DecodeError, DecodeErrorKind, Encode, EncodeError, Writer};
use ::jaus::{CommandCode, JausMessage};
/// bits messages and types.
#[allow(clippy::module_inception)]
pub mod bits {
    #[allow(unused_imports)]
    use super::*;
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausBits)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(repr = u16)]
    pub struct LampState {
        /// Head lamp on. Values: 0 = Off, 1 = On.
        ///
        /// Bit 0.
        #[jaus(bit = 0)]
        pub head_lamp: bool,
        /// Valid values: [0, 15].
        ///
        /// Bits 4-7.
        #[jaus(bits = 4..= 7)]
        pub brightness: u8,
        /// Bits the definition does not name, kept as received.
        #[jaus(reserved)]
        #[cfg_attr(
            all(),
            serde(default, skip_serializing_if = "::jaus::codec::is_default")
        )]
        pub reserved: u16,
    }
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausBits)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(repr = u8)]
    pub struct ReportLampsFaults {
        /// Bit 0.
        #[jaus(bit = 0)]
        pub fuse: bool,
        /// Bit 1.
        #[jaus(bit = 1)]
        pub bulb: bool,
        /// Bits the definition does not name, kept as received.
        #[jaus(reserved)]
        #[cfg_attr(
            all(),
            serde(default, skip_serializing_if = "::jaus::codec::is_default")
        )]
        pub reserved: u8,
    }
    /// Report Lamps (0x4D02).
    ///
    /// Reports the lamps.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D02)]
    pub struct ReportLamps {
        pub lamps: LampState,
        pub faults: ReportLampsFaults,
    }
}
pub use bits::*;
/// constants messages and types.
#[allow(clippy::module_inception)]
pub mod constants {
    #[allow(unused_imports)]
    use super::*;
    /// Set Heading (0x0D40).
    ///
    /// Sets a heading.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D40)]
    pub struct SetHeading {
        ///
        /// Unit: rad.
        /// Range `[-3.5, 3.5]`, carried as a scaled `u16` (resolution 1.068e-4).
        #[jaus(scaled(u16, -3.5, 3.5), unit = "rad")]
        pub heading: f64,
        ///
        /// A fixed 12-byte string, NUL padded.
        #[jaus(fixed = 12)]
        pub label: String,
    }
}
pub use constants::*;
/// fields messages and types.
#[allow(clippy::module_inception)]
pub mod fields {
    #[allow(unused_imports)]
    use super::*;
    /// Selected gear
    ///
    /// A value the definition does not name decodes to `Unknown(n)` and re-encodes
    /// unchanged.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausEnum)]
    #[cfg_attr(all(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(repr = u8)]
    pub enum GearSelect {
        /// Park (0).
        #[default]
        #[jaus(value = 0)]
        Park,
        /// Crawling
        #[jaus(value = 1)]
        LowRange,
        /// High Range (2).
        #[jaus(value = 2)]
        HighRange,
        /// A value the definition does not name.
        #[jaus(unknown)]
        Unknown(u8),
    }
    /// Set Drive Trim (0x0D01).
    ///
    /// Sets the drive trim.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D01)]
    pub struct SetDriveTrim {
        /// Commanded speed
        ///
        /// Unit: m/s.
        /// Range `[-10, 10]`, carried as a scaled `u16` (resolution 3.052e-4).
        #[jaus(scaled(u16, -10.0, 10.0), unit = "m/s")]
        pub wheel_speed: f64,
        #[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))]
        pub gain: f64,
        ///
        /// Unit: rad.
        pub steer_limit: i32,
        /// Valid values: [0, 100).
        ///
        /// Unit: %.
        pub level: u8,
        /// Selected gear
        pub gear: GearSelect,
    }
}
pub use fields::*;
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
    pub struct ReportGridCells {
        ///
        /// Preceded on the wire by its element count as `u16`.
        #[jaus(count = u16)]
        pub cells: Vec<ReportGridCellsCellRec>,
    }
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct ReportGridCellsCellRec {
        pub cost: u8,
    }
    /// Report Grid (0x4D05).
    ///
    /// Reports a grid.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D05)]
    pub struct ReportGrid {
        ///
        /// Preceded on the wire by its element count as `u8`.
        #[jaus(count = u8)]
        pub rows: Vec<ReportGridCells>,
    }
}
pub use lists::*;
/// records messages and types.
#[allow(clippy::module_inception)]
pub mod records {
    #[allow(unused_imports)]
    use super::*;
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(presence = u8)]
    pub struct PointRec {
        ///
        /// Unit: m.
        #[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))]
        pub x: f32,
        ///
        /// Unit: m.
        /// Optional: presence bit 0.
        #[jaus(bit = 0)]
        #[cfg_attr(
            all(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::codec::serde_float::option"
            )
        )]
        pub y: Option<f32>,
        ///
        /// Unit: m.
        /// Optional: presence bit 1.
        #[jaus(bit = 1)]
        #[cfg_attr(
            all(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::codec::serde_float::option"
            )
        )]
        pub z: Option<f32>,
    }
    /// Set Marker (0x0D04).
    ///
    /// Sets a marker.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D04, presence = u8)]
    pub struct SetMarker {
        ///
        /// Unit: m.
        #[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))]
        pub x: f32,
        ///
        /// Unit: m.
        /// Optional: presence bit 0.
        #[jaus(bit = 0)]
        #[cfg_attr(
            all(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::codec::serde_float::option"
            )
        )]
        pub y: Option<f32>,
        ///
        /// Unit: m.
        /// Optional: presence bit 1.
        #[jaus(bit = 1)]
        #[cfg_attr(
            all(),
            serde(
                default,
                skip_serializing_if = "Option::is_none",
                with = "::jaus::codec::serde_float::option"
            )
        )]
        pub z: Option<f32>,
    }
    /// Report Marker (0x4D04).
    ///
    /// Reports a marker.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D04, presence = u16)]
    pub struct ReportMarker {
        pub id: u16,
        ///
        /// Unit: s.
        /// Optional: presence bit 0.
        #[jaus(bit = 0)]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub age: Option<u32>,
    }
}
pub use records::*;
/// refs messages and types.
#[allow(clippy::module_inception)]
pub mod refs {
    #[allow(unused_imports)]
    use super::*;
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct DriveRec {
        ///
        /// Unit: m/s.
        /// Range `[0, 50]`, carried as a scaled `u16` (resolution 7.630e-4).
        #[jaus(scaled(u16, 0.0, 50.0), unit = "m/s")]
        pub speed: f64,
    }
    /// Set Cruise (0x0D08).
    ///
    /// Sets the cruise speed.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D08)]
    pub struct SetCruise {
        ///
        /// Unit: m/s.
        /// Range `[0, 50]`, carried as a scaled `u16` (resolution 7.630e-4).
        #[jaus(scaled(u16, 0.0, 50.0), unit = "m/s")]
        pub cruise: f64,
    }
    /// Set Drive (0x0D09).
    ///
    /// Sets the drive.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D09)]
    pub struct SetDrive {
        ///
        /// Unit: m/s.
        /// Range `[0, 50]`, carried as a scaled `u16` (resolution 7.630e-4).
        #[jaus(scaled(u16, 0.0, 50.0), unit = "m/s")]
        pub speed: f64,
    }
}
pub use refs::*;
/// sequences messages and types.
#[allow(clippy::module_inception)]
pub mod sequences {
    #[allow(unused_imports)]
    use super::*;
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct ReportPlanPlanRec {
        pub plan_id: u16,
    }
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct ReportPlanOwnerRec {
        pub owner: u8,
    }
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct ReportPlanLegSeq {
        pub leg_rec: ReportPlanLegSeqLegRec,
    }
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct ReportPlanLegSeqLegRec {
        ///
        /// Unit: m.
        #[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))]
        pub length: f32,
    }
    /// Report Plan (0x4D07).
    ///
    /// Reports a plan.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D07, presence = u8)]
    pub struct ReportPlan {
        pub plan_rec: ReportPlanPlanRec,
        /// Optional: presence bit 0.
        #[jaus(bit = 0)]
        #[cfg_attr(all(), serde(default, skip_serializing_if = "Option::is_none"))]
        pub owner_rec: Option<ReportPlanOwnerRec>,
        ///
        /// Preceded on the wire by its element count as `u8`.
        #[jaus(count = u8)]
        pub legs: Vec<ReportPlanLegSeq>,
    }
}
pub use sequences::*;
/// service messages and types.
#[allow(clippy::module_inception)]
pub mod service {
    #[allow(unused_imports)]
    use super::*;
    ///
    /// A value the definition does not name decodes to `Unknown(n)` and re-encodes
    /// unchanged.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, ::jaus::JausEnum)]
    #[cfg_attr(all(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(repr = u8)]
    pub enum SetLampOn {
        /// Off (0).
        #[default]
        #[jaus(value = 0)]
        Off,
        /// On (1).
        #[jaus(value = 1)]
        On,
        /// A value the definition does not name.
        #[jaus(unknown)]
        Unknown(u8),
    }
    /// Set Lamp (0x0D10).
    ///
    /// Turns the lamp on or off.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D10)]
    pub struct SetLamp {
        pub on: SetLampOn,
    }
    /// Query Lamp (0x2D10).
    ///
    /// Asks for the lamp's state.
    ///
    /// Answered by [`ReportLamp`].
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x2D10)]
    pub struct QueryLamp {}
    /// Report Lamp (0x4D10).
    ///
    /// The lamp's state.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D10)]
    pub struct ReportLamp {
        ///
        /// Unit: %.
        pub level: u8,
    }
}
pub use service::*;
/// strings messages and types.
#[allow(clippy::module_inception)]
pub mod strings {
    #[allow(unused_imports)]
    use super::*;
    /// Report Label (0x4D03).
    ///
    /// Reports labels.
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D03)]
    pub struct ReportLabel {
        ///
        /// A fixed 8-byte string, NUL padded.
        #[jaus(fixed = 8)]
        pub tag: String,
        /// Count: 0 to 40.
        ///
        /// Preceded on the wire by its length as `u8`.
        #[jaus(size = u8)]
        pub label: String,
        /// Format: JAUS MESSAGE. Count: 2 to the type's maximum.
        ///
        /// Preceded on the wire by its length as `u32`.
        #[jaus(size = u32)]
        #[cfg_attr(all(), serde(with = "::jaus::hex::serde"))]
        pub blob: Vec<u8>,
        /// Format of `picture`: 0 = JPEG, 1 = RAW.
        pub picture_format: u8,
        ///
        /// Preceded on the wire by its length as `u16`.
        #[jaus(size = u16)]
        #[cfg_attr(all(), serde(with = "::jaus::hex::serde"))]
        pub picture: Vec<u8>,
    }
}
pub use strings::*;
/// variable fields messages and types.
#[allow(clippy::module_inception)]
pub mod variable_fields {
    #[allow(unused_imports)]
    use super::*;
    #[derive(Debug, Clone, PartialEq, ::jaus::JausUnion)]
    #[cfg_attr(all(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(tag = u8)]
    pub enum ReportReadingReading {
        #[jaus(tag = 0)]
        Count(u32),
        /// Unit: m.
        #[jaus(tag = 1)]
        Distance(#[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))] f32),
    }
    /// Report Reading (0x4D30).
    ///
    /// Reports a reading.
    #[derive(Debug, Clone, PartialEq, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x4D30)]
    pub struct ReportReading {
        pub reading: ReportReadingReading,
    }
}
pub use variable_fields::*;
/// variants messages and types.
#[allow(clippy::module_inception)]
pub mod variants {
    #[allow(unused_imports)]
    use super::*;
    #[derive(Debug, Clone, PartialEq, ::jaus::JausUnion)]
    #[cfg_attr(all(), derive(serde::Serialize, serde::Deserialize))]
    #[jaus(tag = u8)]
    pub enum SetTargetTargetVar {
        #[jaus(tag = 0)]
        PointRec(SetTargetTargetVarPointRec),
        #[jaus(tag = 1)]
        PathList(SetTargetTargetVarPathList),
    }
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct SetTargetTargetVarPointRec {
        ///
        /// Unit: m.
        #[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))]
        pub x: f32,
    }
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct SetTargetTargetVarPathList {
        ///
        /// Preceded on the wire by its element count as `u8`.
        #[jaus(count = u8)]
        pub path_list: Vec<SetTargetTargetVarPathListStepRec>,
    }
    #[derive(Debug, Clone, PartialEq, Default, ::jaus::JausRecord)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    pub struct SetTargetTargetVarPathListStepRec {
        ///
        /// Unit: rad.
        #[cfg_attr(all(), serde(with = "::jaus::codec::serde_float"))]
        pub heading: f32,
    }
    /// Set Target (0x0D06).
    ///
    /// Sets a target.
    #[derive(Debug, Clone, PartialEq, ::jaus::JausMessage)]
    #[cfg_attr(
        all(),
        derive(serde::Serialize, serde::Deserialize),
        serde(deny_unknown_fields)
    )]
    #[jaus(code = 0x0D06)]
    pub struct SetTarget {
        pub target_var: SetTargetTargetVar,
    }
}
pub use variants::*;
impl ::jaus::Query for QueryLamp {
    type Report = ReportLamp;
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
    /// Report Lamps (0x4D02).
    ReportLamps(ReportLamps),
    /// Set Heading (0x0D40).
    SetHeading(SetHeading),
    /// Set Drive Trim (0x0D01).
    SetDriveTrim(SetDriveTrim),
    /// Report Grid (0x4D05).
    ReportGrid(ReportGrid),
    /// Set Marker (0x0D04).
    SetMarker(SetMarker),
    /// Report Marker (0x4D04).
    ReportMarker(ReportMarker),
    /// Set Cruise (0x0D08).
    SetCruise(SetCruise),
    /// Set Drive (0x0D09).
    SetDrive(SetDrive),
    /// Report Plan (0x4D07).
    ReportPlan(ReportPlan),
    /// Set Lamp (0x0D10).
    SetLamp(SetLamp),
    /// Query Lamp (0x2D10).
    QueryLamp(QueryLamp),
    /// Report Lamp (0x4D10).
    ReportLamp(ReportLamp),
    /// Report Label (0x4D03).
    ReportLabel(ReportLabel),
    /// Report Reading (0x4D30).
    ReportReading(ReportReading),
    /// Set Target (0x0D06).
    SetTarget(SetTarget),
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
            0x4D02 => decode_as::<ReportLamps>(body),
            0x0D40 => decode_as::<SetHeading>(body),
            0x0D01 => decode_as::<SetDriveTrim>(body),
            0x4D05 => decode_as::<ReportGrid>(body),
            0x0D04 => decode_as::<SetMarker>(body),
            0x4D04 => decode_as::<ReportMarker>(body),
            0x0D08 => decode_as::<SetCruise>(body),
            0x0D09 => decode_as::<SetDrive>(body),
            0x4D07 => decode_as::<ReportPlan>(body),
            0x0D10 => decode_as::<SetLamp>(body),
            0x2D10 => decode_as::<QueryLamp>(body),
            0x4D10 => decode_as::<ReportLamp>(body),
            0x4D03 => decode_as::<ReportLabel>(body),
            0x4D30 => decode_as::<ReportReading>(body),
            0x0D06 => decode_as::<SetTarget>(body),
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
            Self::ReportLamps(_) => ReportLamps::CODE,
            Self::SetHeading(_) => SetHeading::CODE,
            Self::SetDriveTrim(_) => SetDriveTrim::CODE,
            Self::ReportGrid(_) => ReportGrid::CODE,
            Self::SetMarker(_) => SetMarker::CODE,
            Self::ReportMarker(_) => ReportMarker::CODE,
            Self::SetCruise(_) => SetCruise::CODE,
            Self::SetDrive(_) => SetDrive::CODE,
            Self::ReportPlan(_) => ReportPlan::CODE,
            Self::SetLamp(_) => SetLamp::CODE,
            Self::QueryLamp(_) => QueryLamp::CODE,
            Self::ReportLamp(_) => ReportLamp::CODE,
            Self::ReportLabel(_) => ReportLabel::CODE,
            Self::ReportReading(_) => ReportReading::CODE,
            Self::SetTarget(_) => SetTarget::CODE,
            Self::Raw(r) => r.code,
        }
    }
    /// The name of this message.
    pub fn name(&self) -> &'static str {
        match self {
            Self::ReportLamps(_) => ReportLamps::NAME,
            Self::SetHeading(_) => SetHeading::NAME,
            Self::SetDriveTrim(_) => SetDriveTrim::NAME,
            Self::ReportGrid(_) => ReportGrid::NAME,
            Self::SetMarker(_) => SetMarker::NAME,
            Self::ReportMarker(_) => ReportMarker::NAME,
            Self::SetCruise(_) => SetCruise::NAME,
            Self::SetDrive(_) => SetDrive::NAME,
            Self::ReportPlan(_) => ReportPlan::NAME,
            Self::SetLamp(_) => SetLamp::NAME,
            Self::QueryLamp(_) => QueryLamp::NAME,
            Self::ReportLamp(_) => ReportLamp::NAME,
            Self::ReportLabel(_) => ReportLabel::NAME,
            Self::ReportReading(_) => ReportReading::NAME,
            Self::SetTarget(_) => SetTarget::NAME,
            Self::Raw(_) => "Raw",
        }
    }
    /// The body as a value implementing [`Encode`].
    pub fn body(&self) -> &dyn Encode {
        match self {
            Self::ReportLamps(m) => m,
            Self::SetHeading(m) => m,
            Self::SetDriveTrim(m) => m,
            Self::ReportGrid(m) => m,
            Self::SetMarker(m) => m,
            Self::ReportMarker(m) => m,
            Self::SetCruise(m) => m,
            Self::SetDrive(m) => m,
            Self::ReportPlan(m) => m,
            Self::SetLamp(m) => m,
            Self::QueryLamp(m) => m,
            Self::ReportLamp(m) => m,
            Self::ReportLabel(m) => m,
            Self::ReportReading(m) => m,
            Self::SetTarget(m) => m,
            Self::Raw(r) => r,
        }
    }
    /// The body as a mutable value implementing [`Encode`].
    pub fn body_mut(&mut self) -> &mut dyn Encode {
        match self {
            Self::ReportLamps(m) => m,
            Self::SetHeading(m) => m,
            Self::SetDriveTrim(m) => m,
            Self::ReportGrid(m) => m,
            Self::SetMarker(m) => m,
            Self::ReportMarker(m) => m,
            Self::SetCruise(m) => m,
            Self::SetDrive(m) => m,
            Self::ReportPlan(m) => m,
            Self::SetLamp(m) => m,
            Self::QueryLamp(m) => m,
            Self::ReportLamp(m) => m,
            Self::ReportLabel(m) => m,
            Self::ReportReading(m) => m,
            Self::SetTarget(m) => m,
            Self::Raw(r) => r,
        }
    }
}
impl From<ReportLamps> for Message {
    fn from(m: ReportLamps) -> Self {
        Self::ReportLamps(m)
    }
}
impl From<SetHeading> for Message {
    fn from(m: SetHeading) -> Self {
        Self::SetHeading(m)
    }
}
impl From<SetDriveTrim> for Message {
    fn from(m: SetDriveTrim) -> Self {
        Self::SetDriveTrim(m)
    }
}
impl From<ReportGrid> for Message {
    fn from(m: ReportGrid) -> Self {
        Self::ReportGrid(m)
    }
}
impl From<SetMarker> for Message {
    fn from(m: SetMarker) -> Self {
        Self::SetMarker(m)
    }
}
impl From<ReportMarker> for Message {
    fn from(m: ReportMarker) -> Self {
        Self::ReportMarker(m)
    }
}
impl From<SetCruise> for Message {
    fn from(m: SetCruise) -> Self {
        Self::SetCruise(m)
    }
}
impl From<SetDrive> for Message {
    fn from(m: SetDrive) -> Self {
        Self::SetDrive(m)
    }
}
impl From<ReportPlan> for Message {
    fn from(m: ReportPlan) -> Self {
        Self::ReportPlan(m)
    }
}
impl From<SetLamp> for Message {
    fn from(m: SetLamp) -> Self {
        Self::SetLamp(m)
    }
}
impl From<QueryLamp> for Message {
    fn from(m: QueryLamp) -> Self {
        Self::QueryLamp(m)
    }
}
impl From<ReportLamp> for Message {
    fn from(m: ReportLamp) -> Self {
        Self::ReportLamp(m)
    }
}
impl From<ReportLabel> for Message {
    fn from(m: ReportLabel) -> Self {
        Self::ReportLabel(m)
    }
}
impl From<ReportReading> for Message {
    fn from(m: ReportReading) -> Self {
        Self::ReportReading(m)
    }
}
impl From<SetTarget> for Message {
    fn from(m: SetTarget) -> Self {
        Self::SetTarget(m)
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
        code: CommandCode(0x4D02),
        name: "ReportLamps",
        title: "Report Lamps",
        group: "bits",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0D40),
        name: "SetHeading",
        title: "Set Heading",
        group: "constants",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0D01),
        name: "SetDriveTrim",
        title: "Set Drive Trim",
        group: "fields",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D05),
        name: "ReportGrid",
        title: "Report Grid",
        group: "lists",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0D04),
        name: "SetMarker",
        title: "Set Marker",
        group: "records",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D04),
        name: "ReportMarker",
        title: "Report Marker",
        group: "records",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0D08),
        name: "SetCruise",
        title: "Set Cruise",
        group: "refs",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0D09),
        name: "SetDrive",
        title: "Set Drive",
        group: "refs",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D07),
        name: "ReportPlan",
        title: "Report Plan",
        group: "sequences",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0D10),
        name: "SetLamp",
        title: "Set Lamp",
        group: "service",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x2D10),
        name: "QueryLamp",
        title: "Query Lamp",
        group: "service",
        report: Some("ReportLamp"),
        experimental: false,
        class: ::jaus::wire::MessageClass::Query,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D10),
        name: "ReportLamp",
        title: "Report Lamp",
        group: "service",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D03),
        name: "ReportLabel",
        title: "Report Label",
        group: "strings",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x4D30),
        name: "ReportReading",
        title: "Report Reading",
        group: "variable_fields",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Inform,
        read_only: false,
        needs_control: false,
    },
    ::jaus::MessageInfo {
        code: CommandCode(0x0D06),
        name: "SetTarget",
        title: "Set Target",
        group: "variants",
        report: None,
        experimental: false,
        class: ::jaus::wire::MessageClass::Command,
        read_only: false,
        needs_control: true,
    },
];
