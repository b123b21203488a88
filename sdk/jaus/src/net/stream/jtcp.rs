//! JTCP: JAUS datagrams on a TCP stream, as AS5669A's TCP transport and the JAUS Tool
//! Set's runtime (`JTCPArchive.h`, `TCPConnection.cpp`) write them.
//!
//! ```text
//! stream   = version byte (1 or 2, once, at the start of each direction) frame*
//! frame v1 = u16 BE size (16 + body) | 16-byte RA 3.3 header | body
//! frame v2 = AS5669A message: type/HC byte | u16 LE data size | [HC 2] | properties |
//!            destination | source | payload | sequence   (data size = the whole frame)
//! ```
//!
//! A frame is a JUDP datagram without its first byte (version 1: without its first
//! three, the version and the two header-compression bytes). A stream carries one
//! version: a connection is version 1 or version 2. Nothing marks a frame's start, so
//! the first frame that does not parse leaves the stream unreadable: the decoder
//! fails for good ([`JtcpError`]) and the connection must be closed.

use super::{judp_datagram, messages, v2_min, v2_size, EncodeError, Version, DEFAULT_MAX_FRAME};
use crate::wire::HEADER_LEN;

/// Why a JTCP stream cannot be read on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum JtcpError {
    /// The stream's first byte is not version 1 or 2.
    #[error("JTCP stream starts with {0:#04x}, not version 1 or 2")]
    Version(u8),
    /// A frame's size is below its header.
    #[error("JTCP frame size {0} is below its header")]
    Short(usize),
    /// A frame's size is over the decoder's limit.
    #[error("JTCP frame of {len} bytes is over the limit of {max}")]
    TooLarge {
        /// The frame's size.
        len: usize,
        /// The limit.
        max: usize,
    },
    /// A version-1 frame whose RA 3.3 header's data size disagrees with its size
    /// prefix.
    #[error("JTCP frame size {size} but its JAUS header says {data_size} body bytes")]
    HeaderSize {
        /// The size prefix (header and body).
        size: usize,
        /// The header's data size.
        data_size: usize,
    },
}

/// What a [`JtcpDecoder`] counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct JtcpStats {
    /// Bytes taken.
    pub bytes: u64,
    /// Frames handed on.
    pub frames: u64,
    /// Streams refused (the decoder failed; at most 1 per decoder).
    pub errors: u64,
}

/// Reads a JTCP stream (one direction of a connection) into JUDP datagrams. It keeps at
/// most one partial frame, bounded by `max_frame`.
///
/// ```
/// use jaus::net::stream::{jtcp::JtcpEncoder, JtcpDecoder};
/// let datagram = [2u8, 0, 16, 0, 0, 1, 1, 1, 0, 2, 2, 2, 0, 0x02, 0x2B, 7, 0];
/// let mut wire = Vec::new();
/// JtcpEncoder::default().encode(&datagram, &mut wire).unwrap();
/// assert_eq!(wire.len(), datagram.len()); // the version byte once, then the message
/// let mut got = Vec::new();
/// let mut d = JtcpDecoder::default();
/// for b in &wire {
///     d.decode(&[*b], |g| got.push(g.to_vec())).unwrap();
/// }
/// assert_eq!(got, [datagram.to_vec()]);
/// ```
#[derive(Debug, Clone)]
pub struct JtcpDecoder {
    max_frame: usize,
    version: Option<Version>,
    /// The partial frame.
    buf: Vec<u8>,
    /// The datagram handed on.
    out: Vec<u8>,
    stats: JtcpStats,
    failed: Option<JtcpError>,
}

impl Default for JtcpDecoder {
    fn default() -> Self {
        Self::new(DEFAULT_MAX_FRAME)
    }
}

impl JtcpDecoder {
    /// A decoder of frames up to `max_frame` bytes (at least a version-1 header).
    pub fn new(max_frame: usize) -> Self {
        Self {
            max_frame: max_frame.max(2 + HEADER_LEN),
            version: None,
            buf: Vec::new(),
            out: Vec::new(),
            stats: JtcpStats::default(),
            failed: None,
        }
    }

    /// The stream's version, once its first byte came.
    pub fn version(&self) -> Option<Version> {
        self.version
    }

    /// The counters.
    pub fn stats(&self) -> JtcpStats {
        self.stats
    }

    /// Bytes of a frame not yet complete.
    pub fn pending(&self) -> usize {
        self.buf.len()
    }

    /// Takes the next bytes of the stream, handing `on` each whole frame as a JUDP
    /// datagram. After an error the stream is unreadable: this and every later call
    /// return it.
    pub fn decode(&mut self, mut input: &[u8], mut on: impl FnMut(&[u8])) -> Result<(), JtcpError> {
        if let Some(e) = self.failed {
            return Err(e);
        }
        self.stats.bytes += input.len() as u64;
        while !input.is_empty() {
            let Some(version) = self.version else {
                let b = input[0];
                input = &input[1..];
                self.version =
                    Some(Version::from_byte(b).ok_or_else(|| self.fail(JtcpError::Version(b)))?);
                continue;
            };
            let need = match self.frame_len(version) {
                Ok(n) => n,
                Err(e) => return Err(self.fail(e)),
            };
            let take = need.saturating_sub(self.buf.len()).min(input.len());
            self.buf.extend_from_slice(&input[..take]);
            input = &input[take..];
            if self.buf.len() < need {
                continue;
            }
            match self.frame_len(version) {
                Ok(n) if n == need => {}
                // The size field is in: read on to the frame's end.
                Ok(_) => continue,
                Err(e) => return Err(self.fail(e)),
            }
            if version == Version::As5669 {
                let size = need - 2;
                let data_size =
                    usize::from(u16::from_le_bytes([self.buf[14], self.buf[15]]) & 0x0FFF);
                if data_size + HEADER_LEN != size {
                    return Err(self.fail(JtcpError::HeaderSize { size, data_size }));
                }
            }
            judp_datagram(version, &self.buf, &mut self.out);
            self.buf.clear();
            self.stats.frames += 1;
            on(&self.out);
        }
        Ok(())
    }

    /// How many bytes the current frame needs in all: its length once the size field
    /// is in, else the bytes up to the size field.
    fn frame_len(&self, version: Version) -> Result<usize, JtcpError> {
        let (size, min, extra) = match version {
            Version::As5669 => match self.buf.as_slice() {
                [hi, lo, ..] => (usize::from(u16::from_be_bytes([*hi, *lo])), HEADER_LEN, 2),
                _ => return Ok(2),
            },
            Version::As5669A => match v2_size(&self.buf) {
                Some(size) => (size, v2_min(self.buf[0]), 0),
                None => return Ok(3),
            },
        };
        if size < min {
            return Err(JtcpError::Short(size));
        }
        if size + extra > self.max_frame {
            return Err(JtcpError::TooLarge {
                len: size + extra,
                max: self.max_frame,
            });
        }
        Ok(size + extra)
    }

    fn fail(&mut self, e: JtcpError) -> JtcpError {
        self.stats.errors += 1;
        self.failed = Some(e);
        self.buf = Vec::new();
        e
    }
}

/// Writes JUDP datagrams as one direction of a JTCP stream: the version byte before the
/// first frame, then one frame per message.
#[derive(Debug, Clone, Copy, Default)]
pub struct JtcpEncoder {
    version: Option<Version>,
}

impl JtcpEncoder {
    /// The stream's version, once a frame was written.
    pub fn version(&self) -> Option<Version> {
        self.version
    }

    /// Appends the frames of JUDP `datagram` to `out` (after the version byte when it
    /// is the stream's first). A datagram of the other version than the stream's is
    /// refused ([`EncodeError::Version`]): a stream carries one.
    pub fn encode(&mut self, datagram: &[u8], out: &mut Vec<u8>) -> Result<Version, EncodeError> {
        let (version, parts) = messages(datagram)?;
        match self.version {
            Some(v) if v != version => return Err(EncodeError::Version(version.byte())),
            Some(_) => {}
            None => out.push(version.byte()),
        }
        for part in parts {
            match version {
                Version::As5669 => {
                    let size = part.len() - 2;
                    let size = u16::try_from(size).map_err(|_| EncodeError::TooLarge {
                        len: size,
                        max: usize::from(u16::MAX),
                    })?;
                    out.extend_from_slice(&size.to_be_bytes());
                    out.extend_from_slice(&part[2..]);
                }
                Version::As5669A => out.extend_from_slice(part),
            }
        }
        self.version = Some(version);
        Ok(version)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A JUDP version-1 datagram of a packet with `body`.
    pub(crate) fn v1(body: &[u8]) -> Vec<u8> {
        let mut h = [0u8; 16];
        h[1] = 2;
        h[2..4].copy_from_slice(&0x2B02u16.to_le_bytes());
        h[12..14].copy_from_slice(&(body.len() as u16).to_le_bytes());
        let mut d = vec![1, 0, 0];
        d.extend_from_slice(&((16 + body.len()) as u16).to_be_bytes());
        d.extend_from_slice(&h);
        d.extend_from_slice(body);
        d
    }

    #[test]
    fn version_one_is_the_size_prefix_header_and_body_after_one_version_byte() {
        let (a, b) = (v1(b"abc"), v1(&[0x10; 40]));
        let mut e = JtcpEncoder::default();
        let mut wire = Vec::new();
        e.encode(&a, &mut wire).unwrap();
        e.encode(&b, &mut wire).unwrap();
        assert_eq!(wire[0], 1);
        assert_eq!(&wire[1..3], &19u16.to_be_bytes());
        assert_eq!(wire.len(), 1 + (a.len() - 3) + (b.len() - 3));
        let mut got = Vec::new();
        let mut d = JtcpDecoder::default();
        d.decode(&wire, |g| got.push(g.to_vec())).unwrap();
        assert_eq!(got, [a.clone(), b]);
        assert_eq!(d.stats().frames, 2);
        assert_eq!(d.pending(), 0);
        // The other version on the same stream is refused.
        let v2 = [2u8, 0, 14, 0, 0, 1, 1, 1, 0, 2, 2, 2, 0, 7, 0];
        assert_eq!(e.encode(&v2, &mut wire), Err(EncodeError::Version(2)));
    }

    #[test]
    fn a_bad_stream_fails_for_good() {
        let mut d = JtcpDecoder::default();
        assert_eq!(d.decode(&[3], |_| {}), Err(JtcpError::Version(3)));
        assert_eq!(d.decode(&[1], |_| {}), Err(JtcpError::Version(3)));
        assert_eq!(d.stats().errors, 1);

        let mut d = JtcpDecoder::new(100);
        assert_eq!(
            d.decode(&[1, 0x10, 0], |_| {}),
            Err(JtcpError::TooLarge {
                len: 4098,
                max: 100
            })
        );
        let mut d = JtcpDecoder::default();
        assert_eq!(d.decode(&[2, 0, 13, 0], |_| {}), Err(JtcpError::Short(13)));
        // Size prefix and JAUS header disagree.
        let mut wire = Vec::new();
        JtcpEncoder::default()
            .encode(&v1(b"abcd"), &mut wire)
            .unwrap();
        wire[15] = 3;
        let mut d = JtcpDecoder::default();
        assert_eq!(
            d.decode(&wire, |_| {}),
            Err(JtcpError::HeaderSize {
                size: 20,
                data_size: 3
            })
        );
    }
}
