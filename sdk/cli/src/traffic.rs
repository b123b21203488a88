//! Captured traffic put to use: `jaus decode --pcap FILE` (every JAUS message of a
//! capture as a JSON line, multi-packet messages reassembled) and `jaus replay FILE`
//! (the captured datagrams sent again, with their timing, to a node).

use std::io::Write;
use std::net::{SocketAddr, SocketAddrV4, UdpSocket};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use jaus::net::framing::{Reassembler, ReassemblyLimits};
use jaus::wire::PacketRef;

use crate::capture::{self, Datagram};

/// Which of OpenJAUS's local component-interface sockets a datagram crossed, if any
/// (docs/wire.md §8.5): its control socket carries 8-byte control datagrams (check-in,
/// lookups: not JAUS messages), its data socket raw JAUS packets without JUDP framing.
fn openjaus_socket(d: &Datagram) -> Option<u16> {
    use jaus::net::oj::{CONTROL_PORT, DATA_PORT};
    [d.src.port(), d.dst.port()]
        .into_iter()
        .find(|p| *p == CONTROL_PORT || *p == DATA_PORT)
}

/// `jaus decode --pcap FILE`: one JSON line per JAUS message (the form of `jaus decode`
/// plus `t`, seconds since the first datagram, and the `src`/`dst` sockets); datagrams
/// that are not JAUS get one error line each on `err`. OpenJAUS's local component
/// interface is recognised: raw packets on its data socket (port 24629) are decoded, its
/// control datagrams (port 24627) skipped with one note. Returns (messages, errors).
pub fn decode_capture(
    path: &Path,
    catalogue: &crate::catalogue::Catalogue,
    out: &mut impl Write,
    err: &mut impl Write,
) -> Result<(usize, usize), String> {
    let (datagrams, stats) = capture::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut reassembler = Reassembler::new(ReassemblyLimits::default());
    let t0 = datagrams.first().map_or(Duration::ZERO, |d| d.time);
    let clock = Instant::now();
    let (mut messages, mut errors, mut control) = (0, 0, 0);
    for (i, d) in datagrams.iter().enumerate() {
        if openjaus_socket(d) == Some(jaus::net::oj::CONTROL_PORT) {
            control += 1;
            continue;
        }
        let line = (|| -> Result<Option<String>, String> {
            let bytes = d.jaus_packet()?;
            let packet = PacketRef::parse(bytes).map_err(|e| e.to_string())?;
            // The capture's own clock orders the parts of a multi-packet message.
            let now = clock + d.time.saturating_sub(t0);
            let Some((header, body)) = reassembler.message(now, &packet.header, packet.body) else {
                return Ok(None);
            };
            let json = catalogue.decode_packet(PacketRef {
                header,
                body: &body,
            })?;
            let mut v: serde_json::Value =
                serde_json::from_str(&json).map_err(|e| e.to_string())?;
            v["t"] = serde_json::json!(d.time.saturating_sub(t0).as_secs_f64());
            v["src"] = serde_json::json!(d.src.to_string());
            v["dst"] = serde_json::json!(d.dst.to_string());
            Ok(Some(v.to_string()))
        })();
        match line {
            Ok(Some(l)) => {
                messages += 1;
                let _ = writeln!(out, "{l}");
            }
            Ok(None) => {}
            Err(e) => {
                errors += 1;
                let _ = writeln!(
                    err,
                    "{}: datagram {} ({} -> {}): {e}",
                    path.display(),
                    i + 1,
                    d.src,
                    d.dst
                );
            }
        }
    }
    if control > 0 {
        let _ = writeln!(
            err,
            "{}: {control} datagrams of OpenJAUS's component control socket (port {}: check-in and lookups, not JAUS messages) skipped",
            path.display(),
            jaus::net::oj::CONTROL_PORT
        );
    }
    if stats.skipped > 0 {
        let _ = writeln!(
            err,
            "{}: {} frames are not IPv4/UDP (skipped)",
            path.display(),
            stats.skipped
        );
    }
    Ok((messages, errors))
}

/// What `jaus replay` sends.
#[derive(Debug, Clone)]
pub struct Replay {
    /// Where every datagram goes.
    pub to: SocketAddr,
    /// Only the datagrams originally sent to this socket (e.g. what one node received).
    pub only_to: Option<SocketAddrV4>,
    /// Time scale: 1 keeps the captured timing, 0 sends as fast as possible.
    pub speed: f64,
    /// Local socket (port 0: any).
    pub bind: SocketAddr,
}

/// `jaus replay FILE --to ADDR`: sends the captured datagrams (those `only_to` selects)
/// to `to` with their captured spacing divided by `speed`. Returns how many were sent.
pub fn replay(path: &Path, r: &Replay, stop: &AtomicBool) -> Result<usize, String> {
    let (datagrams, _) = capture::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let selected: Vec<&Datagram> = datagrams
        .iter()
        .filter(|d| r.only_to.is_none_or(|a| d.dst == a))
        .collect();
    let socket = UdpSocket::bind(r.bind).map_err(|e| format!("{}: {e}", r.bind))?;
    let start = Instant::now();
    let t0 = selected.first().map_or(Duration::ZERO, |d| d.time);
    let mut sent = 0;
    for d in selected {
        if stop.load(Ordering::Relaxed) {
            break;
        }
        if r.speed > 0.0 {
            let due = start + d.time.saturating_sub(t0).div_f64(r.speed);
            let now = Instant::now();
            if due > now {
                std::thread::sleep(due - now);
            }
        }
        socket
            .send_to(&d.payload, r.to)
            .map_err(|e| format!("{}: {e}", r.to))?;
        sent += 1;
    }
    Ok(sent)
}
