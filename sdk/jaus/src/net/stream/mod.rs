//! Byte-stream framings of JAUS datagrams, sans-IO: AS5669A's JTCP ([`jtcp`]) for TCP
//! and JSerial ([`jserial`]) for serial lines (docs/wire.md, "Three transports").
//!
//! Both carry the same messages a JUDP datagram carries and hand them back in JUDP
//! form, so that a node, its AS5669A side and every tap see one datagram format
//! whatever the carrier:
//!
//! * version 1 (AS5669, RA 3.3): `[1][HC 0][HC 0][u16 BE size][16-byte header][body]`,
//!   one JAUS packet;
//! * version 2 (AS5669A, AS-4): `[2]` and one AS5669A message (general transport
//!   header, payload, sequence number). A JUDP datagram of several AS5669A messages is
//!   carried as one frame per message.
//!
//! Decoders take bytes as they come (any split, any garbage) and call back with whole
//! datagrams; they keep at most one partial frame, bounded by their `max_frame`;
//! nothing they are given makes them panic; every frame refused is counted.

pub mod jserial;
pub mod jtcp;

mod crc;

#[cfg(test)]
mod proptests;

pub use crc::crc16;
pub use jserial::{JSerialDecoder, JSerialError, JSerialStats};
pub use jtcp::{JtcpDecoder, JtcpError, JtcpStats};

use super::as5669a::{HC_LEN, OVERHEAD};
use crate::wire::HEADER_LEN;

/// Bytes of JUDP version 1's transport header: version, two header-compression bytes,
/// u16 size.
pub(crate) const JUDP1_OVERHEAD: usize = 5;

/// Largest frame the decoders take by default: a version-1 packet (16-byte header and
/// the 12-bit data size's 4095 bytes) or a version-2 message of 4096 bytes with its
/// header-compression fields, rounded up.
pub const DEFAULT_MAX_FRAME: usize = 4096 + 64;

/// The transport version of a JUDP datagram, as its first byte says.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Version {
    /// AS5669 (version 1): an RA 3.3 packet.
    As5669,
    /// AS5669A (version 2): AS-4 messages.
    As5669A,
}

impl Version {
    /// The version of byte `b` (1 or 2), else `None`.
    pub const fn from_byte(b: u8) -> Option<Self> {
        match b {
            1 => Some(Version::As5669),
            2 => Some(Version::As5669A),
            _ => None,
        }
    }

    /// The version byte.
    pub const fn byte(self) -> u8 {
        match self {
            Version::As5669 => 1,
            Version::As5669A => 2,
        }
    }
}

/// Why a JUDP datagram cannot be put on a stream.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum EncodeError {
    /// The first byte is not a JUDP version a stream carries (1 or 2); an OPC
    /// ("JAUS01.0") or raw datagram has no stream form.
    #[error("a datagram starting with byte {0:#04x} is not JUDP version 1 or 2")]
    Version(u8),
    /// Empty, or shorter than its version's header.
    #[error("datagram of {0} bytes is too short")]
    TooShort(usize),
    /// A version-1 datagram with compressed headers (HC flags 2 or 3).
    #[error("JUDP header compression (flags {0}) is not carried")]
    Compressed(u8),
    /// A version-2 message's data size runs past the datagram or is below the header.
    #[error("AS5669A message at byte {at}: data size {size} does not fit the datagram")]
    Size {
        /// Where the message starts in the datagram.
        at: usize,
        /// Its data size field.
        size: usize,
    },
    /// Longer than the framing carries.
    #[error("frame of {len} bytes is over the limit of {max}")]
    TooLarge {
        /// The frame's length.
        len: usize,
        /// The limit.
        max: usize,
    },
}

/// The messages of JUDP datagram `d`, each as the bytes a stream frame carries after
/// the version byte: version 1, the u16 BE size, header and body (the two
/// header-compression bytes, always 0 when uncompressed, are left out); version 2, each
/// AS5669A message whole.
pub(crate) fn messages(d: &[u8]) -> Result<(Version, Vec<&[u8]>), EncodeError> {
    let first = *d.first().ok_or(EncodeError::TooShort(0))?;
    let version = Version::from_byte(first).ok_or(EncodeError::Version(first))?;
    match version {
        Version::As5669 => {
            if d.len() < JUDP1_OVERHEAD + HEADER_LEN {
                return Err(EncodeError::TooShort(d.len()));
            }
            let flags = d[2] & 0x03;
            if flags >= 2 {
                return Err(EncodeError::Compressed(flags));
            }
            Ok((version, vec![&d[3..]]))
        }
        Version::As5669A => {
            let mut out = Vec::new();
            let mut at = 1;
            while at < d.len() {
                let rest = &d[at..];
                let size = v2_size(rest).ok_or(EncodeError::TooShort(d.len()))?;
                if size < v2_min(rest[0]) || size > rest.len() {
                    return Err(EncodeError::Size { at, size });
                }
                out.push(&rest[..size]);
                at += size;
            }
            if out.is_empty() {
                return Err(EncodeError::TooShort(d.len()));
            }
            Ok((version, out))
        }
    }
}

/// The data size of the AS5669A message starting `m` (bytes 1-2, LE), if there are
/// three bytes.
pub(crate) fn v2_size(m: &[u8]) -> Option<usize> {
    match m {
        [_, lo, hi, ..] => Some(usize::from(u16::from_le_bytes([*lo, *hi]))),
        _ => None,
    }
}

/// The smallest data size of an AS5669A message whose first byte is `type_byte`: header,
/// header compression fields when its HC flags are set, and sequence number.
pub(crate) fn v2_min(type_byte: u8) -> usize {
    OVERHEAD + if type_byte & 0x03 != 0 { HC_LEN } else { 0 }
}

/// Appends to `out` the JUDP datagram of one version-1 frame body (`u16 BE size`,
/// header, body) or one version-2 message.
pub(crate) fn judp_datagram(version: Version, frame: &[u8], out: &mut Vec<u8>) {
    out.clear();
    out.push(version.byte());
    if version == Version::As5669 {
        out.extend_from_slice(&[0, 0]);
    }
    out.extend_from_slice(frame);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn judp_datagrams_split_into_the_messages_a_stream_carries() {
        let mut v1 = vec![1, 0, 0, 0, 18];
        v1.extend_from_slice(&[0u8; 18]);
        let (v, m) = messages(&v1).unwrap();
        assert_eq!((v, m.len(), m[0].len()), (Version::As5669, 1, 20));
        // Two AS5669A messages of 16 bytes each (header, 2-byte payload, sequence).
        let mut one = vec![0u8, 16, 0];
        one.extend_from_slice(&[0; 13]);
        let mut v2 = vec![2];
        v2.extend_from_slice(&one);
        v2.extend_from_slice(&one);
        let (v, m) = messages(&v2).unwrap();
        assert_eq!((v, m.len()), (Version::As5669A, 2));
        assert_eq!(m[1], &one[..]);
        assert_eq!(messages(&[]), Err(EncodeError::TooShort(0)));
        assert_eq!(messages(b"JAUS01.0"), Err(EncodeError::Version(b'J')));
        assert_eq!(messages(&[2]), Err(EncodeError::TooShort(1)));
        v2.pop();
        assert_eq!(messages(&v2), Err(EncodeError::Size { at: 17, size: 16 }));
        v1[2] = 2;
        assert_eq!(messages(&v1), Err(EncodeError::Compressed(2)));
    }
}
