//! Large messages and acknowledgements, as pure functions.
//!
//! A message (message ID and body) longer than the per-packet limit is cut into packets
//! flagged first / normal / last whose sequence numbers follow each other (wrapping at
//! 65,535), as AS5669A numbers a sender's packets with one running counter; the
//! receiver rebuilds it from a run first, normal…, last of consecutive numbers
//! ([`As4Reassembler`](super::As4Reassembler)).

use super::error::As4Error;
use super::header::{AckNak, As4Header, As4Packet, Broadcast, DataControl};

/// Most packets of one message: fewer than the sequence numbers, so that a run never
/// meets itself.
pub const MAX_PACKETS: usize = u16::MAX as usize;

/// The packets of `message` (message ID first) under `header` (its data control is
/// set here), numbered from `first_sequence`: one single packet when it fits
/// `max_payload` bytes, otherwise first / normal… / last packets of at most
/// `max_payload` bytes each. `max_payload` is taken within 2 (so that the first packet
/// holds the message ID) and what one packet's data size allows.
///
/// ```
/// use jaus::net::as5669a::{split, As4Header, As4Id, DataControl};
/// let h = As4Header::new(As4Id::new(1, 1, 1), As4Id::new(2, 1, 1));
/// let ps = split(&h, &[7u8; 10], 65_534, 4).unwrap();
/// assert_eq!(ps.len(), 3);
/// assert_eq!(ps[0].header.data_control, DataControl::First);
/// assert_eq!(ps.iter().map(|p| p.sequence).collect::<Vec<_>>(), [65_534, 65_535, 0]);
/// ```
pub fn split(
    header: &As4Header,
    message: &[u8],
    first_sequence: u16,
    max_payload: usize,
) -> Result<Vec<As4Packet>, As4Error> {
    let max_payload = max_payload.clamp(2, As4Packet::max_payload(header));
    let with = |data_control, i: usize, payload: &[u8]| As4Packet {
        header: As4Header {
            data_control,
            ..*header
        },
        payload: payload.to_vec(),
        sequence: first_sequence.wrapping_add(i as u16),
    };
    if message.len() <= max_payload {
        return Ok(vec![with(DataControl::Single, 0, message)]);
    }
    let count = message.len().div_ceil(max_payload);
    if count > MAX_PACKETS {
        return Err(As4Error::MessageTooLarge {
            len: message.len(),
            max: MAX_PACKETS,
        });
    }
    Ok(message
        .chunks(max_payload)
        .enumerate()
        .map(|(i, c)| {
            let dc = match i {
                0 => DataControl::First,
                i if i + 1 == count => DataControl::Last,
                _ => DataControl::Normal,
            };
            with(dc, i, c)
        })
        .collect())
}

/// The acknowledgement of `packet` (which asked for one): from its destination to its
/// source, the same sequence number and priority, the ack flag, no broadcast, no
/// payload (the message ID is not repeated).
///
/// ```
/// use jaus::net::as5669a::{ack, AckNak, As4Header, As4Id, As4Packet, Priority};
/// let mut h = As4Header::new(As4Id::new(1, 1, 1), As4Id::new(2, 1, 1));
/// h.ack_nak = AckNak::Request;
/// h.priority = Priority::High;
/// let p = As4Packet { header: h, payload: vec![0, 0x2B, 1], sequence: 9 };
/// let a = ack(&p);
/// assert_eq!((a.header.source, a.header.destination), (h.destination, h.source));
/// assert_eq!((a.header.ack_nak, a.header.priority, a.sequence), (AckNak::Ack, Priority::High, 9));
/// ```
pub fn ack(packet: &As4Packet) -> As4Packet {
    answer(packet, AckNak::Ack)
}

/// The negative acknowledgement of `packet`: as [`ack`], with the nak flag.
pub fn nak(packet: &As4Packet) -> As4Packet {
    answer(packet, AckNak::Nak)
}

fn answer(packet: &As4Packet, ack_nak: AckNak) -> As4Packet {
    let h = &packet.header;
    As4Packet {
        header: As4Header {
            hc: None,
            priority: h.priority,
            broadcast: Broadcast::None,
            ack_nak,
            data_control: DataControl::Single,
            destination: h.source,
            source: h.destination,
        },
        payload: Vec::new(),
        sequence: packet.sequence,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::net::as5669a::{As4Id, MAX_PAYLOAD};

    #[test]
    fn a_large_message_becomes_numbered_pieces() {
        let h = As4Header::new(As4Id::new(1, 1, 1), As4Id::new(2, 1, 1));
        let m: Vec<u8> = (0..10_000u32).map(|i| i as u8).collect();
        let ps = split(&h, &m, 100, MAX_PAYLOAD).unwrap();
        assert_eq!(ps.len(), 3);
        assert_eq!(
            ps.iter()
                .map(|p| (p.header.data_control, p.sequence, p.payload.len()))
                .collect::<Vec<_>>(),
            [
                (DataControl::First, 100, 4079),
                (DataControl::Normal, 101, 4079),
                (DataControl::Last, 102, 10_000 - 8158)
            ]
        );
        assert_eq!(ps.concat_payloads(), m);
        let one = split(&h, &m[..MAX_PAYLOAD], 5, MAX_PAYLOAD).unwrap();
        assert_eq!(
            (one.len(), one[0].header.data_control),
            (1, DataControl::Single)
        );
        assert!(matches!(
            split(&h, &vec![0; 2 * MAX_PACKETS + 1], 0, 2),
            Err(As4Error::MessageTooLarge { .. })
        ));
    }

    trait Concat {
        fn concat_payloads(&self) -> Vec<u8>;
    }
    impl Concat for Vec<As4Packet> {
        fn concat_payloads(&self) -> Vec<u8> {
            self.iter().flat_map(|p| p.payload.clone()).collect()
        }
    }
}
