//! UDP framing (docs/wire.md §9) and multi-packet messages (§1.6), sans-IO.
//!
//! * **JUDP** (AS5669): `[version 1][HC number 0][HC length/flags 0][u16 BE length]`
//!   before each JAUS message; received HC flags 0 and 1 are accepted, 2 and 3
//!   (compressed) refused.
//! * **OPC** ("JAUS01.0"): the eight ASCII bytes `JAUS01.0` before the message.
//!
//! A body longer than [`MAX_PACKET_BODY`] is split into packets flagged first / normal /
//! last with sequence numbers 0, 1, 2, …; the [`Reassembler`] rebuilds them with bounded
//! memory, tolerating duplicates and reordering, and never delivers a partial message.

use std::collections::{BTreeMap, HashMap};
use std::time::{Duration, Instant};

use crate::codec::EncodeError;
use crate::wire::{DataFlag, Header, HEADER_LEN};
use crate::{Address, CommandCode};

/// Largest body in one packet (OpenJAUS 3.3: 4080 bytes).
pub const MAX_PACKET_BODY: usize = 4080;

/// The UDP framing of an interface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "lowercase"))]
pub enum Framing {
    /// AS5669 JUDP (the OpenJAUS 3.3 default for subsystem communication).
    #[default]
    Judp,
    /// The OPC / ETG "JAUS01.0" prefix.
    Opc,
    /// No transport header: one JAUS packet per datagram, as OpenJAUS's local
    /// component interface carries them ([`oj`](super::oj)); a "JAUS01.0" prefix is
    /// accepted on receive, as OpenJAUS's component library does.
    Raw,
}

const OPC_PREFIX: &[u8; 8] = b"JAUS01.0";

/// Why a datagram was not taken.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum FramingError {
    /// Shorter than the transport header plus a JAUS header.
    #[error("datagram of {0} bytes is too short")]
    TooShort(usize),
    /// JUDP version other than 1.
    #[error("JUDP version {0} is not 1")]
    Version(u8),
    /// JUDP header compression in use (not supported).
    #[error("JUDP header compression (flags {0}) is not supported")]
    Compressed(u8),
    /// No "JAUS01.0" prefix.
    #[error("no JAUS01.0 prefix")]
    Prefix,
}

/// Why a datagram carried no JAUS packet.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DatagramError {
    /// The transport framing is wrong.
    #[error(transparent)]
    Framing(#[from] FramingError),
    /// The 16-byte JAUS header does not parse.
    #[error(transparent)]
    Header(#[from] crate::codec::DecodeError),
    /// The header's data size disagrees with the bytes that follow it.
    #[error("data size {header} but {actual} body bytes")]
    DataSize {
        /// What the header says.
        header: u16,
        /// What the datagram holds.
        actual: usize,
    },
}

impl Framing {
    /// The JAUS header and body of the packet in `datagram`: transport framing, header
    /// and data size checked.
    pub fn packet(self, datagram: &[u8]) -> Result<(Header, &[u8]), DatagramError> {
        let packet = self.decode(datagram)?;
        let header = Header::parse(packet)?;
        let body = &packet[HEADER_LEN..];
        if body.len() != usize::from(header.data_size) {
            return Err(DatagramError::DataSize {
                header: header.data_size,
                actual: body.len(),
            });
        }
        Ok((header, body))
    }

    /// Bytes of transport header before the JAUS message.
    pub fn overhead(self) -> usize {
        match self {
            Framing::Judp => 5,
            Framing::Opc => 8,
            Framing::Raw => 0,
        }
    }

    /// Wraps one JAUS packet (header + body) in a datagram.
    pub fn encode(self, packet: &[u8]) -> Vec<u8> {
        let mut d = Vec::with_capacity(self.overhead() + packet.len());
        match self {
            Framing::Judp => {
                d.extend_from_slice(&[1, 0, 0]);
                d.extend_from_slice(
                    &(packet.len().min(usize::from(u16::MAX)) as u16).to_be_bytes(),
                );
            }
            Framing::Opc => d.extend_from_slice(OPC_PREFIX),
            Framing::Raw => {}
        }
        d.extend_from_slice(packet);
        d
    }

    /// Frames the packet `header` + `body` (one packet: the body fits
    /// [`MAX_PACKET_BODY`]) into `out`, replacing what it held: nothing is allocated
    /// when `out` has the capacity.
    pub fn write_packet(
        self,
        out: &mut Vec<u8>,
        header: &Header,
        body: &[u8],
    ) -> Result<(), EncodeError> {
        let head = header.encode_with_size(body.len())?;
        out.clear();
        match self {
            Framing::Judp => {
                let n = (HEADER_LEN + body.len()).min(usize::from(u16::MAX)) as u16;
                out.extend_from_slice(&[1, 0, 0]);
                out.extend_from_slice(&n.to_be_bytes());
            }
            Framing::Opc => out.extend_from_slice(OPC_PREFIX),
            Framing::Raw => {}
        }
        out.extend_from_slice(&head);
        out.extend_from_slice(body);
        Ok(())
    }

    /// The JAUS packet inside a datagram.
    pub fn decode(self, datagram: &[u8]) -> Result<&[u8], FramingError> {
        let n = self.overhead();
        if datagram.len() < n + HEADER_LEN {
            return Err(FramingError::TooShort(datagram.len()));
        }
        match self {
            Framing::Judp => {
                if datagram[0] != 1 {
                    return Err(FramingError::Version(datagram[0]));
                }
                let flags = datagram[2] & 0x03;
                if flags >= 2 {
                    return Err(FramingError::Compressed(flags));
                }
            }
            Framing::Opc => {
                if &datagram[..8] != OPC_PREFIX {
                    return Err(FramingError::Prefix);
                }
            }
            Framing::Raw => {
                if datagram.len() >= 8 + HEADER_LEN && &datagram[..8] == OPC_PREFIX {
                    return Ok(&datagram[8..]);
                }
            }
        }
        Ok(&datagram[n..])
    }
}

/// Splits a message into packets (header bytes + body slice each): one packet, flag
/// unchanged, when the body fits; otherwise packets of [`MAX_PACKET_BODY`] bytes flagged
/// first/normal/last with sequence numbers 0, 1, 2, …. An error if a header field does
/// not fit or the body would need more than 65,536 packets.
pub fn split(header: &Header, body: &[u8]) -> Result<Vec<Vec<u8>>, EncodeError> {
    let one = |h: &Header, part: &[u8]| -> Result<Vec<u8>, EncodeError> {
        let mut out = Vec::with_capacity(HEADER_LEN + part.len());
        out.extend_from_slice(&h.encode_with_size(part.len())?);
        out.extend_from_slice(part);
        Ok(out)
    };
    if body.len() <= MAX_PACKET_BODY {
        return Ok(vec![one(header, body)?]);
    }
    let chunks: Vec<&[u8]> = body.chunks(MAX_PACKET_BODY).collect();
    if chunks.len() > usize::from(u16::MAX) + 1 {
        return Err(EncodeError::BodyTooLarge {
            len: body.len(),
            max: MAX_PACKET_BODY * (usize::from(u16::MAX) + 1),
        });
    }
    let last = chunks.len() - 1;
    chunks
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let h = Header {
                data_flag: match i {
                    0 => DataFlag::First,
                    i if i == last => DataFlag::Last,
                    _ => DataFlag::Normal,
                },
                sequence_number: i as u16,
                ..*header
            };
            one(&h, c)
        })
        .collect()
}

/// Limits of the [`Reassembler`].
#[derive(Debug, Clone, Copy)]
pub struct ReassemblyLimits {
    /// Largest rebuilt message body, bytes. Default 1 MiB.
    pub max_message: usize,
    /// Most bytes buffered for one source address. Default 2 MiB.
    pub per_source: usize,
    /// Most bytes buffered in total. Default 16 MiB.
    pub total: usize,
    /// An incomplete message is dropped this long after its last packet. Default 2 s.
    pub timeout: Duration,
}

/// The defaults the field documentation states:
///
/// ```
/// let l = jaus::net::ReassemblyLimits::default();
/// assert_eq!((l.max_message, l.per_source, l.total), (1 << 20, 2 << 20, 16 << 20));
/// assert_eq!(l.timeout, std::time::Duration::from_secs(2));
/// ```
impl Default for ReassemblyLimits {
    fn default() -> Self {
        Self {
            max_message: 1 << 20,
            per_source: 2 << 20,
            total: 16 << 20,
            timeout: Duration::from_secs(2),
        }
    }
}

/// Counters of the [`Reassembler`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ReassemblyStats {
    /// Messages rebuilt and delivered.
    pub completed: u64,
    /// Packets that repeated one already held.
    pub duplicates: u64,
    /// Incomplete messages dropped after the timeout.
    pub timed_out: u64,
    /// Incomplete messages replaced by a new first packet.
    pub restarted: u64,
    /// Packets refused for a memory limit.
    pub over_limit: u64,
    /// Packets of no open message (normal/last without first, bad flags, ...).
    pub orphans: u64,
}

#[derive(Debug)]
struct Stream {
    header: Header,
    parts: BTreeMap<u16, Vec<u8>>,
    last: Option<u16>,
    bytes: usize,
    touched: Instant,
}

/// The memory and time bounds of a reassembler, one rule for both generations (this
/// module's [`Reassembler`] and AS5669A's): bytes held per source and in total, the
/// size of one message, and when an incomplete message times out.
#[derive(Debug)]
pub(crate) struct ByteBudget<K> {
    limits: ReassemblyLimits,
    per_source: HashMap<K, usize>,
    total: usize,
}

impl<K: Copy + Eq + std::hash::Hash> ByteBudget<K> {
    /// An empty budget with `limits`.
    pub(crate) fn new(limits: ReassemblyLimits) -> Self {
        Self {
            limits,
            per_source: HashMap::new(),
            total: 0,
        }
    }

    /// Bytes held now.
    pub(crate) fn total(&self) -> usize {
        self.total
    }

    /// Whether a packet fits: it adds `add_message` bytes to a message of `message`
    /// bytes, and `add_held` bytes to what `source` and everyone hold (the same number
    /// where a packet costs its body; more where it also costs its header).
    pub(crate) fn admits(
        &self,
        source: K,
        message: usize,
        add_message: usize,
        add_held: usize,
    ) -> bool {
        let src = self.per_source.get(&source).copied().unwrap_or(0);
        message + add_message <= self.limits.max_message
            && src + add_held <= self.limits.per_source
            && self.total + add_held <= self.limits.total
    }

    /// `source` holds `delta` bytes more (or fewer).
    pub(crate) fn adjust(&mut self, source: K, delta: isize) {
        let src = self.per_source.get(&source).copied().unwrap_or(0);
        self.total = (self.total as isize + delta) as usize;
        *self.per_source.entry(source).or_insert(0) = (src as isize + delta) as usize;
    }

    /// `source` no longer holds `bytes` bytes.
    pub(crate) fn release(&mut self, source: K, bytes: usize) {
        self.total -= bytes;
        if let Some(b) = self.per_source.get_mut(&source) {
            *b -= bytes;
            if *b == 0 {
                self.per_source.remove(&source);
            }
        }
    }

    /// Whether a message last touched at `touched` has timed out at `now`.
    pub(crate) fn expired(&self, touched: Instant, now: Instant) -> bool {
        now.saturating_duration_since(touched) >= self.limits.timeout
    }

    /// When a message last touched at `touched` times out.
    pub(crate) fn deadline(&self, touched: Instant) -> Instant {
        touched + self.limits.timeout
    }
}

/// Rebuilds multi-packet messages, keyed by (command code, source) as OpenJAUS does.
#[derive(Debug)]
pub struct Reassembler {
    budget: ByteBudget<Address>,
    streams: HashMap<(CommandCode, Address), Stream>,
    stats: ReassemblyStats,
}

impl Reassembler {
    /// With `limits`.
    pub fn new(limits: ReassemblyLimits) -> Self {
        Self {
            budget: ByteBudget::new(limits),
            streams: HashMap::new(),
            stats: ReassemblyStats::default(),
        }
    }

    /// Counters.
    pub fn stats(&self) -> ReassemblyStats {
        self.stats
    }

    /// Bytes buffered now.
    pub fn buffered(&self) -> usize {
        self.budget.total()
    }

    /// The earliest instant an incomplete message times out.
    pub fn next_timeout(&self) -> Option<Instant> {
        self.streams
            .values()
            .map(|s| self.budget.deadline(s.touched))
            .min()
    }

    /// Drops incomplete messages older than the timeout.
    pub fn expire(&mut self, now: Instant) {
        let old: Vec<_> = self
            .streams
            .iter()
            .filter(|(_, s)| self.budget.expired(s.touched, now))
            .map(|(k, _)| *k)
            .collect();
        for k in old {
            self.remove(k);
            self.stats.timed_out += 1;
        }
    }

    fn remove(&mut self, k: (CommandCode, Address)) -> Option<Stream> {
        let s = self.streams.remove(&k)?;
        self.budget.release(k.1, s.bytes);
        Some(s)
    }

    /// The whole message a packet brings: a single packet as it is, a packet of a
    /// multi-packet message once it completes the message ([`push`](Self::push)).
    pub fn message(
        &mut self,
        now: Instant,
        header: &Header,
        body: &[u8],
    ) -> Option<(Header, Vec<u8>)> {
        if header.data_flag == DataFlag::Single {
            Some((*header, body.to_vec()))
        } else {
            self.push(now, header, body)
        }
    }

    /// Takes one packet of a multi-packet message; returns the rebuilt message (header
    /// with flag single and the whole body) when it is complete.
    pub fn push(
        &mut self,
        now: Instant,
        header: &Header,
        body: &[u8],
    ) -> Option<(Header, Vec<u8>)> {
        let key = (header.command_code, header.source);
        let seq = header.sequence_number;
        match header.data_flag {
            DataFlag::First => {
                if seq != 0 {
                    self.stats.orphans += 1;
                    return None;
                }
                if let Some(s) = self.streams.get(&key) {
                    if s.parts.get(&0).is_some_and(|p| p == body) {
                        self.stats.duplicates += 1;
                        return None;
                    }
                    self.remove(key);
                    self.stats.restarted += 1;
                }
                self.streams.insert(
                    key,
                    Stream {
                        header: *header,
                        parts: BTreeMap::new(),
                        last: None,
                        bytes: 0,
                        touched: now,
                    },
                );
            }
            DataFlag::Normal | DataFlag::Last | DataFlag::Retransmit => {
                if !self.streams.contains_key(&key) {
                    self.stats.orphans += 1;
                    return None;
                }
            }
            DataFlag::Single | DataFlag::Other(_) => {
                self.stats.orphans += 1;
                return None;
            }
        }
        // Memory limits, checked before buffering.
        let stream_bytes = self.streams.get(&key).map_or(0, |s| s.bytes);
        if !self
            .budget
            .admits(key.1, stream_bytes, body.len(), body.len())
        {
            self.stats.over_limit += 1;
            self.remove(key);
            return None;
        }
        let s = self.streams.get_mut(&key)?;
        s.touched = now;
        if header.data_flag == DataFlag::Last {
            s.last = Some(seq);
        }
        let replace = header.data_flag == DataFlag::Retransmit;
        let added = match s.parts.get(&seq) {
            Some(_) if !replace => {
                self.stats.duplicates += 1;
                0
            }
            old => {
                let before = old.map_or(0, Vec::len);
                s.parts.insert(seq, body.to_vec());
                body.len() as isize - before as isize
            }
        };
        s.bytes = (s.bytes as isize + added) as usize;
        self.budget.adjust(key.1, added);
        let last = s.last?;
        if s.parts.len() != usize::from(last) + 1 || s.parts.keys().next_back() != Some(&last) {
            return None;
        }
        let s = self.remove(key)?;
        let mut body = Vec::with_capacity(s.bytes);
        for p in s.parts.values() {
            body.extend_from_slice(p);
        }
        self.stats.completed += 1;
        let header = Header {
            data_flag: DataFlag::Single,
            sequence_number: 0,
            data_size: 0,
            ..s.header
        };
        Some((header, body))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wire::Packet;

    fn header() -> Header {
        Header::new(
            CommandCode(0x4F00),
            Address::new(1, 2, 3, 1),
            Address::new(1, 1, 40, 1),
        )
    }

    fn packets(body: &[u8]) -> Vec<(Header, Vec<u8>)> {
        split(&header(), body)
            .unwrap()
            .into_iter()
            .map(|p| {
                let h = Header::parse(&p).unwrap();
                (h, p[HEADER_LEN..].to_vec())
            })
            .collect()
    }

    #[test]
    fn framing_round_trips_and_refuses_bad_datagrams() {
        let p = Packet::new(header(), vec![1, 2, 3]);
        let bytes = crate::codec::Encode::to_bytes(&p).unwrap();
        for f in [Framing::Judp, Framing::Opc] {
            let d = f.encode(&bytes);
            assert_eq!(f.decode(&d).unwrap(), &bytes[..]);
        }
        let d = Framing::Judp.encode(&bytes);
        assert_eq!(&d[..5], &[1, 0, 0, 0, 19]);
        let mut bad = d.clone();
        bad[0] = 2;
        assert_eq!(Framing::Judp.decode(&bad), Err(FramingError::Version(2)));
        bad[0] = 1;
        bad[2] = 3;
        assert_eq!(Framing::Judp.decode(&bad), Err(FramingError::Compressed(3)));
        assert_eq!(Framing::Opc.decode(&d), Err(FramingError::Prefix));
        assert_eq!(
            Framing::Opc.decode(b"JAUS01.0"),
            Err(FramingError::TooShort(8))
        );
    }

    #[test]
    fn split_follows_openjaus() {
        let body: Vec<u8> = (0..10_000u32).map(|i| i as u8).collect();
        let ps = packets(&body);
        assert_eq!(ps.len(), 3);
        assert_eq!(ps[0].0.data_flag, DataFlag::First);
        assert_eq!(ps[1].0.data_flag, DataFlag::Normal);
        assert_eq!(ps[2].0.data_flag, DataFlag::Last);
        assert_eq!(
            ps.iter().map(|p| p.0.sequence_number).collect::<Vec<_>>(),
            [0, 1, 2]
        );
        assert_eq!(ps[0].1.len(), 4080);
        assert_eq!(ps[2].1.len(), 10_000 - 8160);
        assert_eq!(packets(&body[..4080]).len(), 1);
    }

    #[test]
    fn reorder_and_duplicates_are_tolerated() {
        let t = Instant::now();
        let body: Vec<u8> = (0..20_000u32).map(|i| (i * 7) as u8).collect();
        let mut ps = packets(&body);
        ps.reverse();
        let dup = ps[2].clone();
        ps.insert(1, dup);
        let mut r = Reassembler::new(ReassemblyLimits::default());
        // The last packet first: nothing open yet, it is an orphan; resend it at the end.
        let first_last = ps.remove(0);
        let mut out = None;
        for (h, b) in ps.iter().rev().chain([&first_last]) {
            if let Some(m) = r.push(t, h, b) {
                out = Some(m);
            }
        }
        let (h, b) = out.expect("rebuilt");
        assert_eq!(b, body);
        assert_eq!(h.data_flag, DataFlag::Single);
        assert_eq!(r.buffered(), 0);
        assert_eq!(r.stats().completed, 1);
        assert_eq!(r.stats().duplicates, 1);
    }

    #[test]
    fn losses_time_out_and_floods_stay_bounded() {
        let t = Instant::now();
        let body = vec![9u8; 40_000];
        let mut ps = packets(&body);
        ps.remove(3);
        let limits = ReassemblyLimits {
            per_source: 64 * 1024,
            total: 256 * 1024,
            ..Default::default()
        };
        let mut r = Reassembler::new(limits);
        for (h, b) in &ps {
            assert!(r.push(t, h, b).is_none(), "never partial");
        }
        r.expire(t + Duration::from_secs(3));
        assert_eq!(r.stats().timed_out, 1);
        assert_eq!(r.buffered(), 0);
        // A flood of first packets from many sources and codes never completes.
        for i in 0..10_000u32 {
            let mut h = header();
            h.data_flag = DataFlag::First;
            h.command_code = CommandCode((i % 300) as u16);
            h.source = Address::new(1, (i % 40) as u8 + 1, 5, 1);
            r.push(t, &h, &[0u8; 4080]);
            assert!(r.buffered() <= limits.total);
        }
        assert!(r.stats().over_limit > 0);
    }
}
