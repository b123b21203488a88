//! Captures of JAUS traffic: a node writes what it sends and receives as pcapng
//! (`jaus node --capture FILE`), and captures from any tool (pcap or pcapng; Ethernet,
//! raw IPv4, Linux cooked or loopback frames) are read back as UDP datagrams for
//! `jaus decode --pcap` and `jaus replay`.
//!
//! A written capture holds each datagram as a raw IPv4/UDP packet (link type IPv4), so
//! Wireshark and tshark show it like one taken on the wire. Its times are in
//! nanoseconds, which its interface description declares (`if_tsresol` 9): without
//! that option a pcapng reader takes them for microseconds. Reading honours each
//! interface's `if_tsresol` (microseconds when absent, as the format says) and
//! `if_tsoffset`.

use std::fs::File;
use std::io::{BufReader, BufWriter, Read, Write};
use std::net::{Ipv4Addr, SocketAddr, SocketAddrV4};
use std::path::Path;
use std::time::Duration;

use pcap_file::pcap::PcapReader;
use pcap_file::pcapng::blocks::enhanced_packet::EnhancedPacketBlock;
use pcap_file::pcapng::blocks::interface_description::{
    InterfaceDescriptionBlock, InterfaceDescriptionOption,
};
use pcap_file::pcapng::{Block, PcapNgReader, PcapNgWriter};
use pcap_file::DataLink;

/// One UDP datagram of a capture.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Datagram {
    /// When it was seen, since 1970-01-01 UTC.
    pub time: Duration,
    /// Sender.
    pub src: SocketAddrV4,
    /// Receiver.
    pub dst: SocketAddrV4,
    /// UDP payload.
    pub payload: Vec<u8>,
}

impl Datagram {
    /// Whether it crossed OpenJAUS's local component control socket (port 24627,
    /// docs/wire.md §8.5): 8-byte control datagrams (check-in, lookups), not JAUS
    /// messages.
    pub fn is_openjaus_control(&self) -> bool {
        let control = jaus::net::oj::CONTROL_PORT;
        self.src.port() == control || self.dst.port() == control
    }

    /// Whether it is an AS5669A datagram (JUDP version 2, AS-4 messages): its first
    /// byte is 2, and it did not cross OpenJAUS's local data socket (port 24629, raw RA
    /// 3.3 packets whose first byte may be anything).
    pub fn is_as5669a(&self) -> bool {
        let data = jaus::net::oj::DATA_PORT;
        self.src.port() != data
            && self.dst.port() != data
            && jaus::net::as5669a::Generation::of(&self.payload)
                == jaus::net::as5669a::Generation::As5669a
    }

    /// The RA 3.3 JAUS packet it carries, whichever framing it uses: JUDP, the OPC
    /// "JAUS01.0" prefix, or none on OpenJAUS's local data socket (port 24629).
    pub fn jaus_packet(&self) -> Result<&[u8], String> {
        let payload = &self.payload[..];
        let data = jaus::net::oj::DATA_PORT;
        if self.src.port() == data || self.dst.port() == data {
            return Ok(payload);
        }
        let framing = if payload.starts_with(b"JAUS01.0") {
            jaus::net::Framing::Opc
        } else {
            jaus::net::Framing::Judp
        };
        framing.decode(payload).map_err(|e| e.to_string())
    }
}

/// Why a capture cannot be written or read.
#[derive(Debug, thiserror::Error)]
pub enum CaptureError {
    /// The file cannot be opened or written.
    #[error("{0}")]
    Io(#[from] std::io::Error),
    /// The pcap library refused the data.
    #[error("{0}")]
    Pcap(#[from] pcap_file::PcapError),
    /// Neither pcap nor pcapng.
    #[error("not a pcap or pcapng file (magic {0:02x?})")]
    Format([u8; 4]),
}

/// The `if_tsresol` of nanoseconds (10^-9 s): the unit the pcapng library writes an
/// Enhanced Packet Block's time in.
const NANOSECONDS: u8 = 9;

/// The `if_tsresol` a pcapng interface without the option has: microseconds.
const DEFAULT_TSRESOL: u8 = 6;

/// The time of a packet: `units` of the interface's resolution `tsresol` (bit 7 clear:
/// 10^-n s; set: 2^-n s) plus `offset` seconds (`if_tsoffset`, signed), since the Unix
/// epoch. Saturates instead of overflowing (the values come from the file); a time
/// before the epoch is zero.
fn packet_time(units: u64, tsresol: u8, offset: i64) -> Duration {
    let n = u32::from(tsresol & 0x7F);
    let nanos: u128 = if tsresol & 0x80 == 0 {
        match n.checked_sub(9) {
            // Coarser than a nanosecond: scale up (at most 10^9 per unit).
            None => u128::from(units) * 10u128.pow(9 - n),
            Some(finer) => 10u128
                .checked_pow(finer)
                .map_or(0, |div| u128::from(units) / div),
        }
    } else {
        // 2^-n s: units * 10^9 / 2^n (n at most 127).
        (u128::from(units) * 1_000_000_000) >> n
    };
    let secs = u64::try_from(nanos / 1_000_000_000).unwrap_or(u64::MAX);
    let sub = (nanos % 1_000_000_000) as u32;
    let secs = if offset >= 0 {
        secs.saturating_add(offset.unsigned_abs())
    } else {
        match secs.checked_sub(offset.unsigned_abs()) {
            Some(s) => s,
            None => return Duration::ZERO,
        }
    };
    Duration::new(secs, sub)
}

/// Writes datagrams to a pcapng file.
pub struct CaptureWriter<W: Write> {
    out: PcapNgWriter<W>,
    ip_id: u16,
    /// Datagrams not written because an address is not IPv4.
    pub skipped: u64,
}

impl<W: Write> std::fmt::Debug for CaptureWriter<W> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CaptureWriter")
            .field("ip_id", &self.ip_id)
            .field("skipped", &self.skipped)
            .finish()
    }
}

impl CaptureWriter<BufWriter<File>> {
    /// Creates (or truncates) `path`.
    pub fn create(path: &Path) -> Result<Self, CaptureError> {
        Self::new(BufWriter::new(File::create(path)?))
    }
}

impl<W: Write> CaptureWriter<W> {
    /// A capture on `w`: the section header and one raw-IPv4 interface whose times
    /// are in nanoseconds (`if_tsresol` 9, as the packets are written).
    pub fn new(w: W) -> Result<Self, CaptureError> {
        let mut out = PcapNgWriter::new(w)?;
        out.write_pcapng_block(InterfaceDescriptionBlock {
            linktype: DataLink::IPV4,
            snaplen: 0,
            options: vec![InterfaceDescriptionOption::IfTsResol(NANOSECONDS)],
        })?;
        Ok(Self {
            out,
            ip_id: 0,
            skipped: 0,
        })
    }

    /// Writes one datagram from `src` to `dst` seen at `time` (since the Unix epoch).
    pub fn write(
        &mut self,
        time: Duration,
        src: SocketAddr,
        dst: SocketAddr,
        payload: &[u8],
    ) -> Result<(), CaptureError> {
        let (SocketAddr::V4(src), SocketAddr::V4(dst)) = (src, dst) else {
            self.skipped += 1;
            return Ok(());
        };
        self.ip_id = self.ip_id.wrapping_add(1);
        let packet = ipv4_udp(src, dst, payload, self.ip_id);
        self.out.write_pcapng_block(EnhancedPacketBlock {
            interface_id: 0,
            timestamp: time,
            original_len: packet.len() as u32,
            data: packet.into(),
            options: Vec::new(),
        })?;
        Ok(())
    }

    /// Flushes what was written.
    pub fn flush(&mut self) -> Result<(), CaptureError> {
        self.out.get_mut().flush()?;
        Ok(())
    }
}

/// An IPv4 packet (20-byte header with its checksum, no options) carrying a UDP
/// datagram (checksum 0: not computed, which UDP over IPv4 allows).
fn ipv4_udp(src: SocketAddrV4, dst: SocketAddrV4, payload: &[u8], id: u16) -> Vec<u8> {
    let udp_len = 8 + payload.len();
    let total = 20 + udp_len;
    let mut p = Vec::with_capacity(total);
    p.extend_from_slice(&[0x45, 0]);
    p.extend_from_slice(&(total.min(usize::from(u16::MAX)) as u16).to_be_bytes());
    p.extend_from_slice(&id.to_be_bytes());
    p.extend_from_slice(&[0x40, 0, 64, 17, 0, 0]);
    p.extend_from_slice(&src.ip().octets());
    p.extend_from_slice(&dst.ip().octets());
    let sum = checksum(&p);
    p[10..12].copy_from_slice(&sum.to_be_bytes());
    p.extend_from_slice(&src.port().to_be_bytes());
    p.extend_from_slice(&dst.port().to_be_bytes());
    p.extend_from_slice(&(udp_len.min(usize::from(u16::MAX)) as u16).to_be_bytes());
    p.extend_from_slice(&[0, 0]);
    p.extend_from_slice(payload);
    p
}

fn checksum(header: &[u8]) -> u16 {
    let mut sum: u32 = header
        .chunks(2)
        .map(|c| u32::from(u16::from_be_bytes([c[0], *c.get(1).unwrap_or(&0)])))
        .sum();
    while sum > 0xFFFF {
        sum = (sum & 0xFFFF) + (sum >> 16);
    }
    !(sum as u16)
}

/// What [`read`] found besides the datagrams.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ReadStats {
    /// Frames that are not IPv4/UDP (or of a link type not read), skipped.
    pub skipped: u64,
    /// The file ends inside a block or packet (a capture still being written, or whose
    /// writer was killed): everything before it was read.
    pub truncated: bool,
}

/// Every IPv4 UDP datagram of a pcap or pcapng file, in file order.
pub fn read(path: &Path) -> Result<(Vec<Datagram>, ReadStats), CaptureError> {
    let (frames, stats) = read_frames(path)?;
    Ok((frames.into_iter().map(|(_, d)| d).collect(), stats))
}

/// As [`read`], each datagram with its frame number in the file (from 1, counting
/// every packet record, as Wireshark numbers them).
pub fn read_frames(path: &Path) -> Result<(Vec<(u64, Datagram)>, ReadStats), CaptureError> {
    let mut f = BufReader::new(File::open(path)?);
    let mut magic = [0u8; 4];
    f.read_exact(&mut magic)?;
    let f = BufReader::new(File::open(path)?);
    let mut out = Vec::new();
    let mut stats = ReadStats::default();
    let mut number = 0u64;
    let mut push = |time: Duration, link: DataLink, data: &[u8]| {
        number += 1;
        match frame(link, data) {
            Some((src, dst, payload)) => out.push((
                number,
                Datagram {
                    time,
                    src,
                    dst,
                    payload: payload.to_vec(),
                },
            )),
            None => stats.skipped += 1,
        }
    };
    match magic {
        [0x0a, 0x0d, 0x0d, 0x0a] => {
            let mut r = PcapNgReader::new(f)?;
            // The interfaces of the current section, in the order they were described:
            // link type, time resolution, time offset.
            let mut links: Vec<(DataLink, u8, i64)> = Vec::new();
            while let Some(block) = r.next_block() {
                let block = match block {
                    Ok(b) => b,
                    Err(e) if is_truncation(&e) => {
                        stats.truncated = true;
                        break;
                    }
                    Err(e) => return Err(e.into()),
                };
                match block {
                    // A new section describes its interfaces anew.
                    Block::SectionHeader(_) => links.clear(),
                    Block::InterfaceDescription(i) => {
                        let mut tsresol = DEFAULT_TSRESOL;
                        let mut offset = 0;
                        for o in &i.options {
                            match o {
                                InterfaceDescriptionOption::IfTsResol(r) => tsresol = *r,
                                // A signed count of seconds (the library reads it
                                // unsigned).
                                InterfaceDescriptionOption::IfTsOffset(s) => offset = *s as i64,
                                _ => {}
                            }
                        }
                        links.push((i.linktype, tsresol, offset));
                    }
                    Block::EnhancedPacket(p) => {
                        let (link, tsresol, offset) = links
                            .get(p.interface_id as usize)
                            .copied()
                            .unwrap_or((DataLink::IPV4, DEFAULT_TSRESOL, 0));
                        // The library gives the block's raw 64-bit count of units as
                        // nanoseconds, whatever the interface's resolution.
                        let units = u64::try_from(p.timestamp.as_nanos()).unwrap_or(u64::MAX);
                        push(packet_time(units, tsresol, offset), link, &p.data);
                    }
                    Block::SimplePacket(p) => {
                        let link = links.first().map_or(DataLink::IPV4, |l| l.0);
                        push(Duration::ZERO, link, &p.data);
                    }
                    _ => {}
                }
            }
        }
        [0xd4, 0xc3, 0xb2, 0xa1]
        | [0xa1, 0xb2, 0xc3, 0xd4]
        | [0x4d, 0x3c, 0xb2, 0xa1]
        | [0xa1, 0xb2, 0x3c, 0x4d] => {
            let mut r = PcapReader::new(f)?;
            let link = r.header().datalink;
            while let Some(p) = r.next_packet() {
                match p {
                    Ok(p) => push(p.timestamp, link, &p.data),
                    Err(e) if is_truncation(&e) => {
                        stats.truncated = true;
                        break;
                    }
                    Err(e) => return Err(e.into()),
                }
            }
        }
        other => return Err(CaptureError::Format(other)),
    }
    Ok((out, stats))
}

/// An error that means the file ends early (rather than a corrupt block).
fn is_truncation(e: &pcap_file::PcapError) -> bool {
    matches!(e, pcap_file::PcapError::IncompleteBuffer)
        || matches!(e, pcap_file::PcapError::IoError(io) if io.kind() == std::io::ErrorKind::UnexpectedEof)
}

/// The IPv4 UDP datagram of a frame: (source, destination, payload).
fn frame(link: DataLink, data: &[u8]) -> Option<(SocketAddrV4, SocketAddrV4, &[u8])> {
    let ip = match link {
        DataLink::IPV4 | DataLink::RAW => data,
        DataLink::ETHERNET => {
            let ether_type = u16::from_be_bytes([*data.get(12)?, *data.get(13)?]);
            match ether_type {
                0x0800 => data.get(14..)?,
                // One 802.1Q tag.
                0x8100 if data.get(16..18)? == [0x08, 0x00] => data.get(18..)?,
                _ => return None,
            }
        }
        DataLink::LINUX_SLL => {
            if data.get(14..16)? != [0x08, 0x00] {
                return None;
            }
            data.get(16..)?
        }
        DataLink::NULL | DataLink::LOOP => {
            // A 4-byte address family in the capturing host's order (2 = IPv4).
            let family = data.get(..4)?;
            if family != [2, 0, 0, 0] && family != [0, 0, 0, 2] {
                return None;
            }
            data.get(4..)?
        }
        _ => return None,
    };
    if ip.first()? >> 4 != 4 || *ip.get(9)? != 17 {
        return None;
    }
    let ihl = usize::from(ip[0] & 0x0F) * 4;
    let total = usize::from(u16::from_be_bytes([*ip.get(2)?, *ip.get(3)?])).min(ip.len());
    let udp = ip.get(ihl..total)?;
    let len = usize::from(u16::from_be_bytes([*udp.get(4)?, *udp.get(5)?]));
    let payload = udp.get(8..len.max(8).min(udp.len()))?;
    // Every byte through `get`: a capture file is untrusted input.
    let addr = |o: usize, p: usize| -> Option<SocketAddrV4> {
        let a: [u8; 4] = ip.get(o..o + 4)?.try_into().ok()?;
        let port: [u8; 2] = udp.get(p..p + 2)?.try_into().ok()?;
        Some(SocketAddrV4::new(
            Ipv4Addr::from(a),
            u16::from_be_bytes(port),
        ))
    };
    Some((addr(12, 0)?, addr(16, 2)?, payload))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_datagrams_read_back() {
        let dir = std::env::temp_dir().join(format!("jaus-capture-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.pcapng");
        let a: SocketAddr = "127.0.0.1:3794".parse().unwrap();
        let b: SocketAddr = "127.0.0.2:3794".parse().unwrap();
        let v6: SocketAddr = "[::1]:3794".parse().unwrap();
        let mut w = CaptureWriter::create(&path).unwrap();
        w.write(Duration::from_millis(1_500), a, b, b"\x01hello")
            .unwrap();
        w.write(Duration::from_millis(1_600), b, a, &[7; 5000])
            .unwrap();
        w.write(Duration::from_millis(1_700), v6, a, b"x").unwrap();
        assert_eq!(w.skipped, 1);
        w.flush().unwrap();
        drop(w);
        let (got, stats) = read(&path).unwrap();
        assert_eq!(stats, ReadStats::default());
        assert_eq!(got.len(), 2);
        assert_eq!(got[0].payload, b"\x01hello");
        assert_eq!((got[0].src, got[0].dst), (sock(a), sock(b)));
        assert_eq!(got[0].time, Duration::from_millis(1_500));
        assert_eq!(got[1].payload.len(), 5000);
        // A capture cut short (its writer killed mid-block) reads up to the cut.
        let bytes = std::fs::read(&path).unwrap();
        std::fs::write(&path, &bytes[..bytes.len() - 100]).unwrap();
        let (cut, stats) = read(&path).unwrap();
        assert!(stats.truncated);
        assert_eq!(cut.len(), 1);
        std::fs::remove_dir_all(&dir).ok();
    }

    /// 2024-01-02 03:04:05.123456789 UTC, and 12.3 s later (docs: a 12 s run read as
    /// microseconds lasted 12,277 s and began in the year 58877).
    const T0: Duration = Duration::new(1_704_164_645, 123_456_789);
    const RUN: Duration = Duration::from_millis(12_300);

    fn temp(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("jaus-capture-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn times_are_nanoseconds_and_the_interface_says_so() {
        let dir = temp("tsresol");
        let path = dir.join("t.pcapng");
        let a: SocketAddr = "127.0.0.1:3794".parse().unwrap();
        let mut w = CaptureWriter::create(&path).unwrap();
        w.write(T0, a, a, b"first").unwrap();
        w.write(T0 + RUN, a, a, b"last").unwrap();
        w.flush().unwrap();
        drop(w);
        // The interface description declares nanoseconds.
        let mut r = PcapNgReader::new(File::open(&path).unwrap()).unwrap();
        match r.next_block().unwrap().unwrap() {
            Block::InterfaceDescription(i) => assert_eq!(
                i.options,
                [InterfaceDescriptionOption::IfTsResol(9)],
                "{i:?}"
            ),
            other => panic!("{other:?}"),
        }
        let (got, _) = read(&path).unwrap();
        let times: Vec<Duration> = got.iter().map(|d| d.time).collect();
        assert_eq!(times, [T0, T0 + RUN]);
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn each_interface_is_read_at_its_own_resolution_and_offset() {
        use pcap_file::pcapng::blocks::section_header::SectionHeaderBlock;
        let dir = temp("interfaces");
        let path = dir.join("t.pcapng");
        let packet = ipv4_udp(
            "10.0.0.1:3794".parse().unwrap(),
            "10.0.0.2:3794".parse().unwrap(),
            b"x",
            1,
        );
        let mut w = PcapNgWriter::new(File::create(&path).unwrap()).unwrap();
        let interface = |options| InterfaceDescriptionBlock {
            linktype: DataLink::IPV4,
            snaplen: 0,
            options,
        };
        // The library writes a block's raw count of units from a Duration's nanoseconds.
        let epb = |interface_id, units: u64| EnhancedPacketBlock {
            interface_id,
            timestamp: Duration::from_nanos(units),
            original_len: packet.len() as u32,
            data: packet.clone().into(),
            options: Vec::new(),
        };
        // 0: no if_tsresol (microseconds); 1: 2^-10 s; 2: milliseconds, 100 s later.
        w.write_pcapng_block(interface(Vec::new())).unwrap();
        w.write_pcapng_block(interface(vec![InterfaceDescriptionOption::IfTsResol(
            0x80 | 10,
        )]))
        .unwrap();
        w.write_pcapng_block(interface(vec![
            InterfaceDescriptionOption::IfTsResol(3),
            InterfaceDescriptionOption::IfTsOffset(100),
        ]))
        .unwrap();
        w.write_pcapng_block(epb(0, 1_704_164_645_123_456)).unwrap();
        w.write_pcapng_block(epb(1, 3 * 1024 + 512)).unwrap();
        w.write_pcapng_block(epb(2, 1_500)).unwrap();
        // A second section describes its interfaces anew: its interface 0 is in
        // nanoseconds.
        w.write_pcapng_block(SectionHeaderBlock::default()).unwrap();
        w.write_pcapng_block(interface(vec![InterfaceDescriptionOption::IfTsResol(9)]))
            .unwrap();
        w.write_pcapng_block(epb(0, 7)).unwrap();
        drop(w);
        let (got, stats) = read(&path).unwrap();
        assert_eq!(stats, ReadStats::default());
        let times: Vec<Duration> = got.iter().map(|d| d.time).collect();
        assert_eq!(
            times,
            [
                Duration::new(1_704_164_645, 123_456_000),
                Duration::from_millis(3_500),
                Duration::from_millis(101_500),
                Duration::from_nanos(7),
            ]
        );
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn any_resolution_and_offset_gives_a_time_without_panicking() {
        assert_eq!(packet_time(5, 0, 0), Duration::from_secs(5));
        assert_eq!(packet_time(5_000, 12, 0), Duration::from_nanos(5));
        assert_eq!(packet_time(1, 0x80, -1), Duration::ZERO);
        assert_eq!(packet_time(10, 0, -3), Duration::from_secs(7));
        for tsresol in [0, 6, 9, 19, 38, 39, 127, 0x80, 0x80 | 63, 0x80 | 127, 0xFF] {
            for units in [0, 1, u64::MAX] {
                for offset in [i64::MIN, -1, 0, 1, i64::MAX] {
                    let _ = packet_time(units, tsresol, offset);
                }
            }
        }
        assert_eq!(packet_time(u64::MAX, 0, i64::MAX).as_secs(), u64::MAX);
    }

    fn sock(a: SocketAddr) -> SocketAddrV4 {
        match a {
            SocketAddr::V4(v) => v,
            SocketAddr::V6(_) => unreachable!(),
        }
    }

    #[test]
    fn the_ip_header_checksum_verifies() {
        let p = ipv4_udp(
            "10.0.0.1:1".parse().unwrap(),
            "10.0.0.2:2".parse().unwrap(),
            b"abc",
            5,
        );
        assert_eq!(checksum(&p[..20]), 0);
        assert_eq!(frame(DataLink::IPV4, &p).unwrap().2, b"abc");
        // Garbage frames are skipped, never a panic: a header length of 4 bytes puts the
        // UDP header inside the IP addresses.
        let mut short = p[..18].to_vec();
        short[0] = 0x41;
        assert!(frame(DataLink::IPV4, &short).is_none());
        for n in 0..p.len() {
            let _ = frame(DataLink::IPV4, &p[..n]);
            let _ = frame(DataLink::ETHERNET, &p[..n]);
            let _ = frame(DataLink::LINUX_SLL, &p[..n]);
            let _ = frame(DataLink::NULL, &p[..n]);
        }
    }
}
