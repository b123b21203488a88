//! Captured traffic put to use: `jaus decode --pcap FILE` (every JAUS message of a
//! capture as a JSON line, multi-packet messages reassembled) and `jaus replay FILE`
//! (the captured datagrams sent again, with their timing, to a node).
//!
//! A capture may hold both generations, as a node's socket carries them:
//! [`CaptureDecoder`] turns each datagram into whole messages, RA 3.3 ones (JUDP,
//! "JAUS01.0", OpenJAUS's data socket) and AS-4 ones (AS5669A, JUDP version 2); it is
//! the one decoder of `jaus decode --pcap` and of Python's `jaus.read_pcap`.

use std::io::Write;
use std::net::{SocketAddr, SocketAddrV4, UdpSocket};
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use jaus::net::as5669a::{AckNak, As4Config, As4Id, As4Message, As4Stack};
use jaus::net::framing::{Reassembler, ReassemblyLimits};
use jaus::wire::PacketRef;
use jaus::{CommandCode, Header};

use crate::capture::{self, Datagram};

/// A whole message of a capture.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Captured {
    /// An RA 3.3 message (the header of its last packet when it came in several).
    Ra33 {
        /// Its header.
        header: Header,
        /// Its body, reassembled.
        body: Vec<u8>,
    },
    /// An AS-4 message of an AS5669A datagram (reassembled when it came in several
    /// packets).
    As4(As4Message),
}

/// Reads the datagrams of a capture, in file order, into whole messages: an RA 3.3
/// packet through the RA 3.3 reassembler, an AS5669A datagram (first byte 2, on any
/// port but OpenJAUS's data socket) through an [`As4Stack`], which reads every message
/// it packs and rebuilds large ones. The capture's own clock orders the parts of a
/// message: a datagram is taken at its captured time, counted from the first one.
#[derive(Debug)]
pub struct CaptureDecoder {
    ra33: Reassembler,
    as4: As4Stack<SocketAddrV4>,
    /// The first datagram's captured time and the instant it stands for.
    start: Option<(Duration, Instant)>,
}

impl Default for CaptureDecoder {
    fn default() -> Self {
        Self::new()
    }
}

impl CaptureDecoder {
    /// A decoder with the default reassembly limits of both generations.
    pub fn new() -> Self {
        Self {
            ra33: Reassembler::new(ReassemblyLimits::default()),
            as4: As4Stack::new(As4Config::default()),
            start: None,
        }
    }

    /// The whole messages datagram `d` completes, in order: none while a large message
    /// waits for its other parts, and none for an AS5669A acknowledgement. An error
    /// says why `d` is not JAUS (its framing or header, named).
    pub fn datagram(&mut self, d: &Datagram) -> Result<Vec<Captured>, String> {
        let (t0, clock) = *self.start.get_or_insert_with(|| (d.time, Instant::now()));
        let now = clock + d.time.saturating_sub(t0);
        if d.is_as5669a() {
            if self.as4.poll_timeout().is_some_and(|t| t <= now) {
                self.as4.handle_timeout(now);
            }
            let messages = self
                .as4
                .receive(now, d.src, &d.payload)
                .map_err(|e| format!("AS5669A: {e}"))?;
            // The acknowledgements the stack queues for packets that asked: a reader
            // of a capture sends nothing.
            while self.as4.poll_transmit().is_some() {}
            return Ok(messages.into_iter().map(Captured::As4).collect());
        }
        let packet = PacketRef::parse(d.jaus_packet()?).map_err(|e| e.to_string())?;
        Ok(self
            .ra33
            .message(now, &packet.header, packet.body)
            .map(|(header, body)| Captured::Ra33 { header, body })
            .into_iter()
            .collect())
    }
}

/// The JSON of an AS-4 message, in the form of an RA 3.3 line of `jaus decode`: its
/// transport header under `as4` where an RA 3.3 line has `header` (`message_id`,
/// `destination` and `source` as `[subsystem, node, component]`, `priority`,
/// `broadcast`, `ack_nak`: `request` when an acknowledgement was asked, else `none`),
/// then `message` (its name in the AS-4 definitions, `jaus-as4`) and `fields`. A message
/// ID the definitions do not have gives their raw message; a body that does not decode
/// is an error naming the message ID, the sender and the field.
pub fn as4_json(m: &As4Message) -> Result<serde_json::Value, String> {
    let id = m.message_id;
    let message = jaus_as4::Message::decode(CommandCode(id), &m.body)
        .map_err(|e| format!("AS-4 message 0x{id:04X} from {}: {e}", m.source))?;
    let mut v = serde_json::to_value(&message).map_err(|e| e.to_string())?;
    let ack_nak = if m.ack_requested {
        AckNak::Request
    } else {
        AckNak::None
    };
    let id_parts = |a: As4Id| serde_json::json!([a.subsystem, a.node, a.component]);
    v["as4"] = serde_json::json!({
        "message_id": id,
        "destination": id_parts(m.destination),
        "source": id_parts(m.source),
        "priority": m.priority.name(),
        "broadcast": m.broadcast.name(),
        "ack_nak": serde_json::to_value(ack_nak).map_err(|e| e.to_string())?,
    });
    Ok(v)
}

/// `jaus decode --pcap FILE`: one JSON line per JAUS message (the form of `jaus decode`
/// plus `t`, seconds since the first datagram, and the `src`/`dst` sockets); datagrams
/// that are not JAUS get one error line each on `err`. RA 3.3 and AS-4 messages may be
/// mixed: an AS5669A message is printed by its name in the AS-4 definitions with its
/// fields, its transport header under `as4` ([`as4_json`]) where an RA 3.3 one has
/// `header`. OpenJAUS's local component interface is recognised: raw packets on its
/// data socket (port 24629) are decoded, its control datagrams (port 24627) skipped with
/// one note. Returns (messages, errors).
pub fn decode_capture(
    path: &Path,
    catalogue: &crate::catalogue::Catalogue,
    out: &mut impl Write,
    err: &mut impl Write,
) -> Result<(usize, usize), String> {
    let (datagrams, stats) = capture::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut decoder = CaptureDecoder::new();
    let t0 = datagrams.first().map_or(Duration::ZERO, |d| d.time);
    let (mut messages, mut errors, mut control) = (0, 0, 0);
    for (i, d) in datagrams.iter().enumerate() {
        if d.is_openjaus_control() {
            control += 1;
            continue;
        }
        let lines = decoder.datagram(d).map(|whole| {
            whole
                .iter()
                .map(|m| {
                    let mut v = match m {
                        Captured::Ra33 { header, body } => {
                            let json = catalogue.decode_packet(PacketRef {
                                header: *header,
                                body,
                            })?;
                            serde_json::from_str(&json).map_err(|e| e.to_string())?
                        }
                        Captured::As4(m) => as4_json(m)?,
                    };
                    v["t"] = serde_json::json!(d.time.saturating_sub(t0).as_secs_f64());
                    v["src"] = serde_json::json!(d.src.to_string());
                    v["dst"] = serde_json::json!(d.dst.to_string());
                    Ok(v.to_string())
                })
                .collect::<Vec<Result<String, String>>>()
        });
        let lines = lines.unwrap_or_else(|e| vec![Err(e)]);
        for line in lines {
            match line {
                Ok(l) => {
                    messages += 1;
                    let _ = writeln!(out, "{l}");
                }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::capture::CaptureWriter;
    use jaus::codec::Encode;
    use jaus::net::framing::{split, Framing};
    use jaus::{Address, JausMessage};
    use jaus_as4::{ComponentState, Event, IdentificationType, QueryIdentification, ReportStatus};

    /// One capture holding an RA 3.3 datagram (JUDP) and AS5669A datagrams written by an
    /// [`As4Stack`] (a broadcast query asking for an ack, the ack, a report and a large
    /// event in several packets), as a node's socket carries them: every message is
    /// printed by name with its fields, the AS-4 ones with their transport header.
    #[test]
    fn a_capture_of_both_generations_decodes_every_message_by_name() {
        let dir = std::env::temp_dir().join(format!("jaus-traffic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("mixed.pcapng");
        let ocu: SocketAddr = "10.0.0.1:3794".parse().unwrap();
        let vehicle: SocketAddr = "10.0.0.2:3794".parse().unwrap();
        let mut w = CaptureWriter::create(&path).unwrap();
        let t0 = Duration::new(1_704_164_645, 0);
        let mut t = t0;
        let mut write = |w: &mut CaptureWriter<_>, from, to, bytes: &[u8]| {
            t += Duration::from_millis(10);
            w.write(t, from, to, bytes).unwrap();
        };

        // RA 3.3: Set Travel Speed, in JUDP.
        let speed = jaus::messages::SetTravelSpeed { speed: 2.0 };
        let header = Header::new(
            jaus::messages::SetTravelSpeed::CODE,
            Address::new(1, 1, 2, 1),
            Address::new(1, 1, 1, 1),
        );
        for p in split(&header, &speed.to_bytes().unwrap()).unwrap() {
            write(&mut w, ocu, vehicle, &Framing::Judp.encode(&p));
        }

        // AS-4: Query Identification to every component, an ack asked.
        let (me, car) = (As4Id::new(42, 1, 1), As4Id::new(1, 1, 1));
        let mut judge = As4Stack::<SocketAddr>::new(As4Config::default());
        let mut car_stack = As4Stack::<SocketAddr>::new(As4Config::default());
        let query = QueryIdentification {
            query_type: IdentificationType::Component,
        };
        let mut m = As4Message::new(
            QueryIdentification::CODE.0,
            As4Id::new(0xFFFF, 0xFF, 0xFF),
            me,
            query.to_bytes().unwrap(),
        );
        m.ack_requested = true;
        judge.send(vehicle, &[m]);
        let now = Instant::now();
        while let Some(d) = judge.poll_transmit() {
            write(&mut w, ocu, vehicle, &d.bytes);
            assert_eq!(car_stack.receive(now, ocu, &d.bytes).unwrap().len(), 1);
        }
        // The vehicle: the ack, Report Status, and an Event of 6000 bytes (two packets).
        let status = ReportStatus {
            status: ComponentState::Ready,
            reserved: 0,
        };
        let event = Event {
            event_id: 3,
            sequence_number: 9,
            report_message: vec![0xAB; 6000],
        };
        car_stack.send(
            ocu,
            &[
                As4Message::new(ReportStatus::CODE.0, me, car, status.to_bytes().unwrap()),
                As4Message::new(Event::CODE.0, me, car, event.to_bytes().unwrap()),
            ],
        );
        let mut datagrams = 0;
        while let Some(d) = car_stack.poll_transmit() {
            datagrams += 1;
            write(&mut w, vehicle, ocu, &d.bytes);
        }
        assert!(
            datagrams >= 3,
            "{datagrams} datagrams: ack, then the messages"
        );
        // An AS5669A datagram that is not one: an error line, the rest still read.
        write(&mut w, vehicle, ocu, &[2, 0xFF]);
        w.flush().unwrap();
        drop(w);

        let (mut out, mut err) = (Vec::new(), Vec::new());
        let (messages, errors) = decode_capture(
            &path,
            &crate::catalogue::Catalogue::sdk(),
            &mut out,
            &mut err,
        )
        .unwrap();
        let err = String::from_utf8(err).unwrap();
        assert_eq!((messages, errors), (4, 1), "{err}");
        assert!(err.contains("AS5669A"), "{err}");
        assert!(err.contains(&format!("({vehicle} -> {ocu})")), "{err}");
        let lines: Vec<serde_json::Value> = String::from_utf8(out)
            .unwrap()
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        let names: Vec<&str> = lines.iter().filter_map(|l| l["message"].as_str()).collect();
        assert_eq!(
            names,
            [
                "SetTravelSpeed",
                "QueryIdentification",
                "ReportStatus",
                "Event"
            ]
        );
        // RA 3.3: its header and fields, as `jaus decode` prints them.
        let speed = lines[0]["fields"]["speed"].as_f64().unwrap();
        assert!((speed - 2.0).abs() < 0.05, "{speed} (scaled on the wire)");
        assert!(lines[0]["header"].is_object() && lines[0].get("as4").is_none());
        // AS-4: the transport header, and the fields by the AS-4 definitions.
        let q = &lines[1];
        assert_eq!(q["as4"]["source"], serde_json::json!([42, 1, 1]));
        assert_eq!(
            q["as4"]["destination"],
            serde_json::json!([65535, 255, 255])
        );
        assert_eq!(q["as4"]["broadcast"], "global");
        assert_eq!(q["as4"]["priority"], "standard");
        assert_eq!(q["as4"]["ack_nak"], "request");
        assert_eq!(q["as4"]["message_id"], 0x2B00);
        assert_eq!(
            q["fields"]["query_type"],
            serde_json::to_value(IdentificationType::Component).unwrap()
        );
        let s = &lines[2];
        assert_eq!(s["as4"]["source"], serde_json::json!([1, 1, 1]));
        assert_eq!(
            (s["as4"]["broadcast"].as_str(), s["src"].as_str()),
            (Some("none"), Some("10.0.0.2:3794"))
        );
        assert_eq!(
            s["fields"]["status"],
            serde_json::to_value(ComponentState::Ready).unwrap()
        );
        assert_eq!(lines[3]["fields"]["event_id"], 3);
        assert!(lines[3]["t"].as_f64().unwrap() > s["t"].as_f64().unwrap());
        std::fs::remove_dir_all(&dir).ok();
    }
}
