//! JSerial: JAUS datagrams on a serial line, as AS5669A's serial transport and the JAUS
//! Tool Set's runtime (`JSerialArchive.h`, `JSerial.cpp`, `ChecksumCRC.cpp`) write
//! them.
//!
//! ```text
//! DLE SOH | version | u16 LE length | [address, 2 bytes] | DLE STX | u16 LE header CRC |
//! payload (length bytes) | DLE ETX | u16 LE packet CRC
//!
//! DLE 0x10, SOH 0x01, STX 0x02, ETX 0x03
//! header CRC = crc16(0xFFFF, version, length[, address])
//! packet CRC = crc16(header CRC, header CRC bytes .. payload .. DLE ETX)
//! payload v1 = HC number 0 | HC flags 0 | u16 LE size (16 + body) | RA 3.3 header | body
//! payload v2 = one AS5669A message (general transport header, payload, sequence)
//! ```
//!
//! Every byte 0x10 between the SOH and the end of the packet CRC that is not one of the
//! three markers' DLE is sent twice ("DLE stuffing"); a reader takes DLE DLE as one data
//! byte 0x10. The CRC ([`crc16`]) is CRC-16/MCRF4XX. Only the low four bits of the version byte
//! are the version. The optional 2-byte address (between length and DLE STX) is read
//! and ignored, never written.
//!
//! A DLE SOH appears nowhere but at a packet's start, so the decoder resynchronises on
//! it: bytes outside a packet, packets with a bad CRC, length or marker are skipped
//! and counted, and a DLE SOH inside a packet abandons it for the new one.

use super::{crc16, judp_datagram, messages, v2_min, EncodeError, Version, DEFAULT_MAX_FRAME};
use crate::wire::HEADER_LEN;

/// The data-link escape.
pub const DLE: u8 = 0x10;
/// Start of header (after a DLE).
pub const SOH: u8 = 0x01;
/// Start of text (after a DLE).
pub const STX: u8 = 0x02;
/// End of text (after a DLE).
pub const ETX: u8 = 0x03;

/// Bytes a version-1 payload holds besides the RA 3.3 packet: HC number, HC flags, u16
/// size.
const V1_PREFIX: usize = 4;

/// Why a packet was skipped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum JSerialError {
    /// The header CRC does not match.
    #[error("JSerial header checksum mismatch")]
    HeaderChecksum,
    /// The packet CRC does not match.
    #[error("JSerial packet checksum mismatch")]
    Checksum,
    /// The version is not 1 or 2.
    #[error("JSerial version {0} is not 1 or 2")]
    Version(u8),
    /// The length is below the version's header or over the limit.
    #[error("JSerial length {0} is out of range")]
    Length(usize),
    /// A marker where data was due, data where a marker was due, or a DLE followed by
    /// a byte that is no marker.
    #[error("JSerial packet broken: {0}")]
    Malformed(&'static str),
    /// A version-1 payload's own size or header-compression bytes are wrong.
    #[error("JSerial version-1 payload: {0}")]
    Payload(&'static str),
}

/// What a [`JSerialDecoder`] counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct JSerialStats {
    /// Bytes taken.
    pub bytes: u64,
    /// Packets handed on.
    pub frames: u64,
    /// Bytes skipped: outside any packet, or of packets dropped.
    pub bytes_skipped: u64,
    /// Times a packet start was found after skipped bytes or a dropped packet.
    pub resyncs: u64,
    /// Packets whose header CRC did not match.
    pub bad_header_checksum: u64,
    /// Packets whose packet CRC did not match.
    pub bad_checksum: u64,
    /// Packets whose length was out of range (over the limit included).
    pub bad_length: u64,
    /// Packets of a version other than 1 and 2.
    pub bad_version: u64,
    /// Packets with a marker out of place, or a version-1 payload whose own fields are
    /// wrong.
    pub malformed: u64,
    /// Packets cut short by a new packet's start.
    pub abandoned: u64,
}

/// Where the decoder is in a packet.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum State {
    /// Looking for DLE SOH.
    Hunt,
    /// Version, length, perhaps an address, until DLE STX.
    Header,
    /// The two bytes of the header CRC.
    HeaderCrc,
    /// `length` payload bytes.
    Payload,
    /// DLE ETX due.
    End,
    /// The two bytes of the packet CRC.
    Crc,
}

/// One unit of the line after unstuffing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Unit {
    Data(u8),
    Marker(u8),
}

/// Reads a serial line's bytes into JUDP datagrams, resynchronising after garbage and
/// lost bytes. It keeps at most one partial packet, bounded by `max_frame` bytes of
/// payload.
///
/// ```
/// use jaus::net::stream::{jserial, JSerialDecoder};
/// let datagram = [2u8, 0, 16, 0, 0, 0x10, 1, 1, 0, 2, 2, 2, 0, 0x02, 0x2B, 7, 0];
/// let wire = jserial::encode(&datagram).unwrap();
/// let mut line = b"noise".to_vec();
/// line.extend_from_slice(&wire);
/// let mut got = Vec::new();
/// let mut d = JSerialDecoder::default();
/// d.decode(&line, |g| got.push(g.to_vec()));
/// assert_eq!(got, [datagram.to_vec()]);
/// assert_eq!((d.stats().bytes_skipped, d.stats().resyncs), (5, 1));
/// ```
#[derive(Debug, Clone)]
pub struct JSerialDecoder {
    max_frame: usize,
    state: State,
    /// The previous byte was an unpaired DLE.
    escape: bool,
    /// Bytes were skipped since the last packet.
    dirty: bool,
    /// Raw bytes of the current packet after its DLE SOH, read again if it is dropped.
    raw: Vec<u8>,
    /// Bytes to read again before the next of the input.
    backlog: std::collections::VecDeque<u8>,
    /// Version, length and address bytes.
    head: [u8; 5],
    head_len: usize,
    length: usize,
    /// Header CRC bytes, then the packet CRC's.
    crc: [u8; 2],
    crc_len: usize,
    payload: Vec<u8>,
    out: Vec<u8>,
    stats: JSerialStats,
}

impl Default for JSerialDecoder {
    fn default() -> Self {
        Self::new(DEFAULT_MAX_FRAME)
    }
}

impl JSerialDecoder {
    /// A decoder of packets whose payload is at most `max_frame` bytes.
    pub fn new(max_frame: usize) -> Self {
        Self {
            max_frame,
            state: State::Hunt,
            escape: false,
            dirty: false,
            raw: Vec::new(),
            backlog: std::collections::VecDeque::new(),
            head: [0; 5],
            head_len: 0,
            length: 0,
            crc: [0; 2],
            crc_len: 0,
            payload: Vec::new(),
            out: Vec::new(),
            stats: JSerialStats::default(),
        }
    }

    /// The counters.
    pub fn stats(&self) -> JSerialStats {
        self.stats
    }

    /// Takes the next bytes of the line, handing `on` each good packet as a JUDP
    /// datagram. Bad packets and garbage are counted, never returned.
    pub fn decode(&mut self, input: &[u8], mut on: impl FnMut(&[u8])) {
        self.stats.bytes += input.len() as u64;
        for &b in input {
            self.byte(b, &mut on);
            while let Some(r) = self.backlog.pop_front() {
                self.byte(r, &mut on);
            }
        }
    }

    /// One byte of the line (or of a dropped packet, read again).
    fn byte(&mut self, b: u8, on: &mut impl FnMut(&[u8])) {
        if self.state != State::Hunt {
            self.raw.push(b);
        }
        let unit = if self.escape {
            if b == DLE && self.state == State::Hunt {
                // Outside a packet DLE DLE is no data: the second DLE may start the
                // DLE SOH of a packet after garbage that ended in a lone DLE.
                self.skipped(1);
                return;
            }
            self.escape = false;
            if b == DLE {
                Unit::Data(DLE)
            } else {
                Unit::Marker(b)
            }
        } else if b == DLE {
            self.escape = true;
            return;
        } else {
            Unit::Data(b)
        };
        if unit == Unit::Marker(SOH) {
            if self.state != State::Hunt {
                // Cut short by a new packet: it and its start are skipped.
                self.stats.abandoned += 1;
                self.skipped(self.raw.len());
            }
            self.start();
            return;
        }
        if self.state == State::Hunt {
            self.skipped(if matches!(unit, Unit::Marker(_)) {
                2
            } else {
                1
            });
            return;
        }
        if let Err(e) = self.step(unit, on) {
            self.refuse(e);
        }
    }

    /// A new packet after DLE SOH.
    fn start(&mut self) {
        if self.dirty {
            self.stats.resyncs += 1;
            self.dirty = false;
        }
        self.state = State::Header;
        self.raw.clear();
        self.head_len = 0;
        self.crc_len = 0;
        self.payload.clear();
    }

    /// `n` bytes were skipped.
    fn skipped(&mut self, n: usize) {
        self.stats.bytes_skipped += n as u64;
        self.dirty = true;
    }

    /// The packet is dropped: its DLE SOH is skipped and the bytes after it are read
    /// again outside a packet, where a packet start they hide (a DLE SOH after a
    /// lost or added DLE) is found.
    fn refuse(&mut self, e: JSerialError) {
        match e {
            JSerialError::HeaderChecksum => self.stats.bad_header_checksum += 1,
            JSerialError::Checksum => self.stats.bad_checksum += 1,
            JSerialError::Version(_) => self.stats.bad_version += 1,
            JSerialError::Length(_) => self.stats.bad_length += 1,
            JSerialError::Malformed(_) | JSerialError::Payload(_) => self.stats.malformed += 1,
        }
        tracing::trace!("JSerial packet skipped: {e}");
        self.skipped(2);
        self.state = State::Hunt;
        self.escape = false;
        for &b in self.raw.iter().rev() {
            self.backlog.push_front(b);
        }
        self.raw.clear();
        self.payload = Vec::new();
    }

    fn step(&mut self, unit: Unit, on: &mut impl FnMut(&[u8])) -> Result<(), JSerialError> {
        match (self.state, unit) {
            (State::Hunt, _) => {}
            (State::Header, Unit::Data(b)) => {
                let slot = self
                    .head
                    .get_mut(self.head_len)
                    .ok_or(JSerialError::Malformed("no DLE STX after the header"))?;
                *slot = b;
                self.head_len += 1;
            }
            (State::Header, Unit::Marker(STX)) if matches!(self.head_len, 3 | 5) => {
                self.state = State::HeaderCrc;
            }
            (State::HeaderCrc, Unit::Data(b)) => {
                self.crc[self.crc_len] = b;
                self.crc_len += 1;
                if self.crc_len == 2 {
                    self.header_done()?;
                }
            }
            (State::Payload, Unit::Data(b)) => {
                self.payload.push(b);
                if self.payload.len() == self.length {
                    self.state = State::End;
                }
            }
            (State::End, Unit::Marker(ETX)) => {
                self.state = State::Crc;
            }
            (State::Crc, Unit::Data(b)) => {
                self.crc[self.crc_len] = b;
                self.crc_len += 1;
                if self.crc_len == 2 {
                    self.packet_done(on)?;
                }
            }
            (_, Unit::Marker(_)) => return Err(JSerialError::Malformed("marker out of place")),
            (_, Unit::Data(_)) => {
                return Err(JSerialError::Malformed("data where a marker is due"))
            }
        }
        Ok(())
    }

    fn header_crc(&self) -> u16 {
        crc16(0xFFFF, &self.head[..self.head_len])
    }

    fn header_done(&mut self) -> Result<(), JSerialError> {
        if u16::from_le_bytes(self.crc) != self.header_crc() {
            return Err(JSerialError::HeaderChecksum);
        }
        let version = self.head[0] & 0x0F;
        let length = usize::from(u16::from_le_bytes([self.head[1], self.head[2]]));
        let min = match Version::from_byte(version) {
            Some(Version::As5669) => V1_PREFIX + HEADER_LEN,
            Some(Version::As5669A) => v2_min(0),
            None => return Err(JSerialError::Version(version)),
        };
        if length < min || length > self.max_frame {
            return Err(JSerialError::Length(length));
        }
        self.length = length;
        self.crc_len = 0;
        self.payload.reserve(length);
        self.state = State::Payload;
        Ok(())
    }

    fn packet_done(&mut self, on: &mut impl FnMut(&[u8])) -> Result<(), JSerialError> {
        let header_crc = self.header_crc();
        let mut c = crc16(header_crc, &header_crc.to_le_bytes());
        c = crc16(c, &self.payload);
        c = crc16(c, &[DLE, ETX]);
        if u16::from_le_bytes(self.crc) != c {
            return Err(JSerialError::Checksum);
        }
        let p = &self.payload;
        match Version::from_byte(self.head[0] & 0x0F) {
            Some(Version::As5669) => {
                if p[1] & 0x03 >= 2 {
                    return Err(JSerialError::Payload("compressed header"));
                }
                let size = usize::from(u16::from_le_bytes([p[2], p[3]]));
                if size != p.len() - V1_PREFIX {
                    return Err(JSerialError::Payload("size disagrees with the length"));
                }
                self.out.clear();
                self.out.extend_from_slice(&[1, p[0], p[1]]);
                self.out.extend_from_slice(&(size as u16).to_be_bytes());
                self.out.extend_from_slice(&p[V1_PREFIX..]);
            }
            _ => {
                let size = super::v2_size(p).unwrap_or(0);
                if size != p.len() || size < v2_min(p[0]) {
                    return Err(JSerialError::Payload(
                        "AS5669A data size disagrees with the length",
                    ));
                }
                judp_datagram(Version::As5669A, p, &mut self.out);
            }
        }
        self.stats.frames += 1;
        self.state = State::Hunt;
        self.raw.clear();
        on(&self.out);
        Ok(())
    }
}

/// The JSerial packets of JUDP `datagram` (one per message), stuffed, ready for the
/// line.
pub fn encode(datagram: &[u8]) -> Result<Vec<u8>, EncodeError> {
    let mut out = Vec::new();
    encode_into(datagram, &mut out)?;
    Ok(out)
}

/// [`encode`] appending to `out`.
pub fn encode_into(datagram: &[u8], out: &mut Vec<u8>) -> Result<(), EncodeError> {
    let (version, parts) = messages(datagram)?;
    let mut payload = Vec::new();
    for part in parts {
        payload.clear();
        match version {
            Version::As5669 => {
                // `part`: u16 BE size, header, body; HC bytes from the datagram.
                payload.extend_from_slice(&datagram[1..3]);
                let size = (part.len() - 2) as u16;
                payload.extend_from_slice(&size.to_le_bytes());
                payload.extend_from_slice(&part[2..]);
            }
            Version::As5669A => payload.extend_from_slice(part),
        }
        packet(version.byte(), &payload, out)?;
    }
    Ok(())
}

/// Appends the stuffed packet of `payload` with version byte `version` to `out`.
fn packet(version: u8, payload: &[u8], out: &mut Vec<u8>) -> Result<(), EncodeError> {
    let length = u16::try_from(payload.len()).map_err(|_| EncodeError::TooLarge {
        len: payload.len(),
        max: usize::from(u16::MAX),
    })?;
    let [lo, hi] = length.to_le_bytes();
    let head = [version, lo, hi];
    let header_crc = crc16(0xFFFF, &head);
    let mut c = crc16(header_crc, &header_crc.to_le_bytes());
    c = crc16(c, payload);
    c = crc16(c, &[DLE, ETX]);
    out.extend_from_slice(&[DLE, SOH]);
    stuff(out, &head);
    out.extend_from_slice(&[DLE, STX]);
    stuff(out, &header_crc.to_le_bytes());
    stuff(out, payload);
    out.extend_from_slice(&[DLE, ETX]);
    stuff(out, &c.to_le_bytes());
    Ok(())
}

/// Appends `bytes` with every DLE doubled.
fn stuff(out: &mut Vec<u8>, bytes: &[u8]) {
    for &b in bytes {
        out.push(b);
        if b == DLE {
            out.push(DLE);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::jtcp::tests::v1;
    use super::*;

    fn decode_all(d: &mut JSerialDecoder, line: &[u8]) -> Vec<Vec<u8>> {
        let mut got = Vec::new();
        d.decode(line, |g| got.push(g.to_vec()));
        got
    }

    /// The packet the JAUS Tool Set writes for a version-1 message (its
    /// `JSerialArchive::pack`, fields worked out by hand): header CRC over version and
    /// length, packet CRC from the header CRC on, DLE stuffed everywhere but the
    /// markers.
    #[test]
    fn version_one_layout_and_stuffing() {
        let d = v1(&[0x10, 0xAA]);
        let wire = encode(&d).unwrap();
        assert_eq!(&wire[..2], &[DLE, SOH]);
        assert_eq!(wire[2], 1);
        // length 4 + 16 + 2 = 22, LE
        assert_eq!(&wire[3..5], &[22, 0]);
        assert_eq!(&wire[5..7], &[DLE, STX]);
        // The body's DLE was doubled.
        assert!(wire.windows(3).any(|w| w == [DLE, DLE, 0xAA]));
        let hcrc = crc16(0xFFFF, &[1, 22, 0]);
        assert_eq!(u16::from_le_bytes([wire[7], wire[8]]), hcrc);
        let mut dec = JSerialDecoder::default();
        assert_eq!(decode_all(&mut dec, &wire), [d]);
        assert_eq!(dec.stats().bytes_skipped, 0);
    }

    #[test]
    fn garbage_bad_checksums_and_cut_packets_are_skipped_and_counted() {
        let a = v1(b"first");
        let b = v1(b"second");
        let wa = encode(&a).unwrap();
        let wb = encode(&b).unwrap();
        let mut line = vec![0x55, DLE, DLE, STX, 0xFF];
        // A packet with a flipped payload bit.
        let mut bad = wa.clone();
        let n = bad.len();
        bad[n - 6] ^= 0x01;
        line.extend_from_slice(&bad);
        // A packet cut short by the next one's start.
        line.extend_from_slice(&wa[..12]);
        line.extend_from_slice(&wb);
        line.extend_from_slice(&wa);
        let mut d = JSerialDecoder::default();
        assert_eq!(decode_all(&mut d, &line), [b, a]);
        let s = d.stats();
        assert_eq!(s.bad_checksum, 1, "{s:?}");
        assert_eq!(s.abandoned, 1, "{s:?}");
        assert!(s.resyncs >= 2, "{s:?}");
        assert_eq!(s.frames, 2);
        assert_eq!(
            s.bytes_skipped as usize,
            line.len() - wa.len() - wb.len(),
            "{s:?}"
        );
    }

    #[test]
    fn lengths_over_the_limit_and_unknown_versions_are_refused() {
        let d = v1(&[0; 200]);
        let mut dec = JSerialDecoder::new(100);
        assert!(decode_all(&mut dec, &encode(&d).unwrap()).is_empty());
        assert_eq!(dec.stats().bad_length, 1);
        let mut w = Vec::new();
        packet(3, &v1(b"x")[1..], &mut w).unwrap();
        packet(0x21, &[0u8; 22], &mut w).unwrap();
        let mut dec = JSerialDecoder::default();
        assert!(decode_all(&mut dec, &w).is_empty());
        assert_eq!(dec.stats().bad_version, 1);
        // The high bits of the version byte are not the version; the v1 payload's own
        // size must agree with the length.
        assert_eq!(dec.stats().malformed, 1);
    }
}
