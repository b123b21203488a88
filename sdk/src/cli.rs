//! The logic of the `jaus` command-line tool, kept in the library so it is testable.

use crate::codec::Encode;
use crate::messages::{Message, MESSAGES};
use crate::{Header, Packet};
use std::io::Write;

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

/// Runs `f` over every non-empty line, printing results to `out` and one error line
/// per failure to `err`. Returns false if any line failed.
pub fn run_lines(
    lines: impl Iterator<Item = String>,
    out: &mut impl Write,
    err: &mut impl Write,
    f: impl Fn(&str) -> Result<String, String>,
) -> bool {
    let mut ok = true;
    for (i, line) in lines.enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        match f(&line) {
            Ok(s) => {
                let _ = writeln!(out, "{s}");
            }
            Err(e) => {
                ok = false;
                let _ = writeln!(err, "line {}: {e}", i + 1);
            }
        }
    }
    ok
}

/// Prints the message catalogue as a table.
pub fn print_messages(out: &mut impl Write, group: Option<&str>) {
    let _ = writeln!(out, "{:<8} {:<40} {:<22} report", "code", "name", "group");
    let mut n = 0;
    let mut rows: Vec<_> = MESSAGES
        .iter()
        .filter(|m| group.is_none_or(|g| g == m.group))
        .collect();
    rows.sort_by_key(|m| m.code);
    for m in rows {
        n += 1;
        let _ = writeln!(
            out,
            "{:<8} {:<40} {:<22} {}",
            m.code.to_string(),
            if m.experimental {
                format!("{} (experimental)", m.name)
            } else {
                m.name.to_string()
            },
            m.group,
            m.report.unwrap_or("")
        );
    }
    let _ = writeln!(out, "{n} messages");
}

/// Reference packets of TARGETS.md (OpenJAUS 3.3 byte layout).
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

/// `jaus tour`: decodes the reference packets, shows their JSON, re-encodes them and
/// checks the bytes are identical.
pub fn tour(out: &mut impl Write) -> bool {
    let mut ok = true;
    let _ = writeln!(
        out,
        "JAUS RA 3.3 SDK: {} messages in {} groups\n",
        MESSAGES.len(),
        groups().len()
    );
    for (title, hex) in REFERENCE_PACKETS {
        let _ = writeln!(out, "{title}\n  packet  {hex}");
        match decode_line(hex).and_then(|json| {
            let back = encode_line(&json)?;
            Ok((json, back))
        }) {
            Ok((json, back)) => {
                let same = back == *hex;
                ok &= same;
                let _ = writeln!(out, "  decoded {json}");
                let _ = writeln!(
                    out,
                    "  re-encoded identical: {}\n",
                    if same { "yes" } else { "NO" }
                );
            }
            Err(e) => {
                ok = false;
                let _ = writeln!(out, "  error: {e}\n");
            }
        }
    }
    ok
}

fn groups() -> Vec<&'static str> {
    let mut g: Vec<&str> = MESSAGES.iter().map(|m| m.group).collect();
    g.dedup();
    g
}
