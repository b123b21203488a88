//! `jaus.read_pcap`: the JAUS messages of a pcap/pcapng capture, read by the CLI's
//! capture reader and decoder (`jaus_client::capture`, `jaus_client::traffic::CaptureDecoder`:
//! those of `jaus decode --pcap`). The packets are RA 3.3 ones: an AS-4 message
//! (AS5669A) is recognised and named, raised in strict mode and skipped otherwise.

use crate::body::Body;
use crate::catalog::Catalog;
use crate::errors::decode_error_text;
use crate::packet::Packet;
use jaus_client::capture;
use jaus_client::traffic::{as4_json, CaptureDecoder, Captured};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use std::path::Path;
use std::sync::Arc;

/// One message of a capture: (time, source, destination, packet).
pub(crate) type Entry = (f64, (String, u16), (String, u16), Packet);

/// Every message of the capture at `path`.
pub(crate) fn read(
    py: Python<'_>,
    cat: &Arc<Catalog>,
    path: &Path,
    strict: bool,
) -> PyResult<Vec<Entry>> {
    let (datagrams, _stats) =
        capture::read(path).map_err(|e| PyOSError::new_err(format!("{}: {e}", path.display())))?;
    let mut decoder = CaptureDecoder::new();
    let mut out = Vec::new();
    for (i, d) in datagrams.iter().enumerate() {
        // OpenJAUS's component control socket: check-in and lookups, not messages.
        if d.is_openjaus_control() {
            continue;
        }
        let at = || {
            format!(
                "{}: datagram {} ({} -> {})",
                path.display(),
                i + 1,
                d.src,
                d.dst
            )
        };
        let whole = match decoder.datagram(d) {
            Ok(w) => w,
            Err(e) if strict => return Err(decode_error_text(py, format!("{}: {e}", at()), None)),
            Err(_) => continue,
        };
        for m in whole {
            let (header, body) = match m {
                Captured::Ra33 { header, body } => (header, body),
                Captured::As4(m) if strict => {
                    let name = as4_json(&m)
                        .ok()
                        .and_then(|v| v["message"].as_str().map(str::to_string))
                        .unwrap_or_else(|| "a body that does not decode".to_string());
                    let text = format!(
                        "{}: AS-4 message 0x{:04X} ({name}) from {}: read_pcap returns RA 3.3 packets only (strict=False skips AS-4 messages; `jaus decode --pcap` prints them)",
                        at(),
                        m.message_id,
                        m.source
                    );
                    return Err(decode_error_text(py, text, None));
                }
                Captured::As4(_) => continue,
            };
            let packet = match Packet::decode(py, cat, header, Body::Owned(body.into())) {
                Ok(p) => p,
                Err(e) if strict => {
                    let text = format!("{}: {}", at(), e.value(py));
                    let err = decode_error_text(py, text, None);
                    // Keep the codec's context (message, field, offset).
                    for attr in ["message", "field", "path", "offset"] {
                        if let Ok(v) = e.value(py).getattr(attr) {
                            let _ = err.value(py).setattr(attr, v);
                        }
                    }
                    return Err(err);
                }
                Err(_) => continue,
            };
            let sock = |s: std::net::SocketAddrV4| (s.ip().to_string(), s.port());
            out.push((d.time.as_secs_f64(), sock(d.src), sock(d.dst), packet));
        }
    }
    Ok(out)
}
