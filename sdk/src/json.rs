//! Packets as JSON lines: the shape `jaus decode` prints and `jaus encode` reads
//! (`{"header": {...}, "message": NAME, "fields": {...}}`), for tools and consoles.

use crate::codec::Encode;
use crate::messages::Message;
use crate::{Header, Packet};

/// One JSON line of `jaus decode` / `jaus encode`.
#[derive(Debug, serde::Serialize, serde::Deserialize)]
pub struct JsonPacket {
    /// The header.
    pub header: Header,
    /// `"message": "<Name>", "fields": {...}`.
    #[serde(flatten)]
    pub message: Message,
}

/// Decodes one hex packet to a JSON line.
pub fn decode_line(hex: &str) -> Result<String, String> {
    let bytes = crate::hex::decode(hex.trim()).map_err(|e| format!("bad hex: {e}"))?;
    let packet = Packet::parse(&bytes).map_err(|e| e.to_string())?;
    decode_packet(&packet)
}

/// Decodes a parsed packet to a JSON line.
pub fn decode_packet(packet: &Packet) -> Result<String, String> {
    if packet.header.data_flag != crate::wire::DataFlag::Single {
        return Err(format!(
            "packet {} of a multi-packet message ({:?}): reassemble the sequence first",
            packet.header.sequence_number, packet.header.data_flag
        ));
    }
    let message =
        Message::decode(packet.header.command_code, &packet.body).map_err(|e| e.to_string())?;
    serde_json::to_string(&JsonPacket {
        header: packet.header,
        message,
    })
    .map_err(|e| e.to_string())
}

/// Encodes one JSON line to a hex packet. The data size is computed from the body; a
/// header command code that disagrees with the message is an error.
pub fn encode_line(line: &str) -> Result<String, String> {
    let p: JsonPacket = serde_json::from_str(line).map_err(|e| format!("bad JSON: {e}"))?;
    let code = p.message.code();
    if p.header.command_code != code {
        return Err(format!(
            "header command code {} does not match message {} ({code})",
            p.header.command_code,
            p.message.name()
        ));
    }
    let body = p
        .message
        .to_bytes()
        .map_err(|e| format!("{}: {e}", p.message.name()))?;
    let packet = Packet {
        header: p.header,
        body,
    };
    let bytes = packet
        .to_bytes()
        .map_err(|e| format!("{}: {e}", p.message.name()))?;
    Ok(crate::hex::encode(&bytes))
}

/// Three reference packets in OpenJAUS 3.3's byte layout (Report Global Pose, Set Wrench
/// Effort, Set Global Path Segment), used by the tour, the codec benchmark and tests.
pub const REFERENCE_PACKETS: &[(&str, &str)] = &[
    (
        "Report Global Pose, all nine fields",
        "0602024404030201080706051e000000ff016fd12b2a403a75c5dcd125b9333333030a0230ff0040d10015e3227b",
    ),
    ("Set Wrench Effort, all twelve fields", "06020504040302010807060514000000ff0f0a4734f30000480172fd662633000000000d"),
    (
        "Set Global Path Segment 7, both elevations",
        "06020f0404030201080706051d0000000307006fd12b2a403a75c54fcf1db9b7f62b2aee3075c523441fb9c500",
    ),
];
