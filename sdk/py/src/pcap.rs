//! `jaus.read_pcap`: the JAUS messages of a pcap/pcapng capture, read by the CLI's
//! capture reader (`jaus_cli::capture`, the reader of `jaus decode --pcap`).

use crate::errors::decode_error_text;
use crate::packet::Packet;
use crate::schema::Catalog;
use jaus::net::framing::{Reassembler, ReassemblyLimits};
use jaus::wire::PacketRef;
use jaus_cli::capture;
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use std::path::Path;
use std::sync::Arc;
use std::time::{Duration, Instant};

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
    let mut reassembler = Reassembler::new(ReassemblyLimits::default());
    let t0 = datagrams.first().map_or(Duration::ZERO, |d| d.time);
    let clock = Instant::now();
    let mut out = Vec::new();
    for (i, d) in datagrams.iter().enumerate() {
        // OpenJAUS's component control socket: check-in and lookups, not messages.
        if d.src.port() == jaus::net::oj::CONTROL_PORT
            || d.dst.port() == jaus::net::oj::CONTROL_PORT
        {
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
        let packet = d
            .jaus_packet()
            .and_then(|b| PacketRef::parse(b).map_err(|e| e.to_string()));
        let packet = match packet {
            Ok(p) => p,
            Err(e) if strict => return Err(decode_error_text(py, format!("{}: {e}", at()), None)),
            Err(_) => continue,
        };
        // The capture's own clock orders the parts of a multi-packet message.
        let now = clock + d.time.saturating_sub(t0);
        let Some((header, body)) = reassembler.message(now, &packet.header, packet.body) else {
            continue;
        };
        let packet = match Packet::decode(py, cat, header, body) {
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
    Ok(out)
}
