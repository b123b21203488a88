//! JUDP version 2 datagrams: the version byte 2 followed by one or more messages, each
//! as long as its data size says; and which generation a datagram on the shared port
//! belongs to.

use super::error::As4Error;
use super::header::As4Packet;

/// The transport version byte of an AS5669A datagram.
pub const VERSION: u8 = 2;

/// Which generation of JAUS over UDP a datagram belongs to, by its first byte(s).
///
/// ```
/// use jaus::net::as5669a::Generation;
/// assert_eq!(Generation::of(&[1, 0, 0, 0, 16]), Generation::Judp1);
/// assert_eq!(Generation::of(b"JAUS01.0...."), Generation::Opc);
/// assert_eq!(Generation::of(&[2, 0]), Generation::As5669a);
/// assert_eq!(Generation::of(&[]), Generation::Unknown);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Generation {
    /// Version byte 1: AS5669 JUDP carrying RA 3.3 packets.
    Judp1,
    /// The "JAUS01.0" prefix: RA 3.3 packets in the OPC framing.
    Opc,
    /// Version byte 2: AS5669A.
    As5669a,
    /// Anything else (empty, another version byte).
    Unknown,
}

impl Generation {
    /// The generation of `datagram`.
    pub fn of(datagram: &[u8]) -> Self {
        match datagram.first() {
            Some(1) => Self::Judp1,
            Some(&VERSION) => Self::As5669a,
            Some(b'J') if datagram.starts_with(b"JAUS01.0") => Self::Opc,
            _ => Self::Unknown,
        }
    }
}

/// Every message of an AS5669A datagram, in order. The messages must fill the
/// datagram exactly: a data size that runs past the end, or bytes left over that are
/// not a whole message, refuse the whole datagram.
pub fn parse_datagram(datagram: &[u8]) -> Result<Vec<As4Packet>, As4Error> {
    let (&version, mut rest) = datagram.split_first().ok_or(As4Error::Empty)?;
    if version != VERSION {
        return Err(As4Error::Version(version));
    }
    if rest.is_empty() {
        return Err(As4Error::NoMessage);
    }
    let mut at = 1;
    let mut out = Vec::new();
    while !rest.is_empty() {
        let (p, n) = As4Packet::parse(rest, out.len(), at)?;
        out.push(p);
        at += n;
        rest = &rest[n..];
    }
    Ok(out)
}

/// Writes `packets` in order into as few datagrams as the bound allows: each datagram
/// is the version byte followed by as many whole messages as fit within `max_len`
/// bytes. An error if a message does not fit even alone, or does not encode.
pub fn write_datagrams(packets: &[As4Packet], max_len: usize) -> Result<Vec<Vec<u8>>, As4Error> {
    let mut out = Vec::new();
    let mut current = vec![VERSION];
    for p in packets {
        let need = p.wire_len();
        if 1 + need > max_len {
            return Err(As4Error::DatagramBound {
                bound: max_len,
                need: 1 + need,
            });
        }
        if current.len() + need > max_len {
            out.push(std::mem::replace(&mut current, vec![VERSION]));
        }
        p.write(&mut current)?;
    }
    if current.len() > 1 {
        out.push(current);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::net::as5669a::{As4Header, As4Id};

    fn packet(id: u16, body: usize, seq: u16) -> As4Packet {
        let mut payload = id.to_le_bytes().to_vec();
        payload.extend(std::iter::repeat_n(0xAB, body));
        As4Packet {
            header: As4Header::new(As4Id::new(1, 1, 1), As4Id::new(2, 1, 1)),
            payload,
            sequence: seq,
        }
    }

    #[test]
    fn several_messages_share_a_datagram_up_to_the_bound() {
        let ps: Vec<_> = (0..5).map(|i| packet(0x4000 + i, 10, i)).collect();
        // Each message is 14 + 12 = 26 bytes; 1 + 3 * 26 = 79 fits 80, a fourth does not.
        let ds = write_datagrams(&ps, 80).unwrap();
        assert_eq!(ds.iter().map(Vec::len).collect::<Vec<_>>(), [79, 53]);
        let back: Vec<_> = ds.iter().flat_map(|d| parse_datagram(d).unwrap()).collect();
        assert_eq!(back, ps);
        assert!(matches!(
            write_datagrams(&ps, 26),
            Err(As4Error::DatagramBound {
                bound: 26,
                need: 27
            })
        ));
    }

    #[test]
    fn bad_datagrams_are_named_errors() {
        assert_eq!(parse_datagram(&[]), Err(As4Error::Empty));
        assert_eq!(parse_datagram(&[1, 0]), Err(As4Error::Version(1)));
        assert_eq!(parse_datagram(&[2]), Err(As4Error::NoMessage));
        let mut d = write_datagrams(&[packet(1, 0, 0)], 100).unwrap().remove(0);
        d.push(0);
        assert!(matches!(
            parse_datagram(&d),
            Err(As4Error::TooShort {
                message: 1,
                at: 17,
                ..
            })
        ));
    }
}
