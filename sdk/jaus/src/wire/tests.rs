//! The wire layer's tests: the header example of docs/wire.md, packet size checks, the
//! size of `messages::Message`.

use super::*;

#[test]
fn header_example_of_wire_md() {
    // Query Component Status from 1.1.40.1 to 1.1.33.1 (docs/wire.md §1.5).
    let bytes = [6, 2, 2, 0x20, 1, 0x21, 1, 1, 1, 0x28, 1, 1, 0, 0, 0, 0];
    let h = Header::parse(&bytes).unwrap();
    assert_eq!(h.command_code, CommandCode(0x2002));
    assert_eq!(h.destination, Address::new(1, 1, 33, 1));
    assert_eq!(h.source, Address::new(1, 1, 40, 1));
    assert_eq!(h.priority, 6);
    assert_eq!(h.version, 2);
    assert_eq!(h.to_bytes().unwrap(), bytes);
    assert_eq!(Header::new(CommandCode(0x2002), h.destination, h.source), h);
}

#[test]
fn packet_size_checks() {
    let mut bytes = vec![6, 2, 1, 0, 1, 1, 1, 1, 2, 2, 2, 2, 1, 0, 0, 0, 7];
    assert_eq!(Packet::parse(&bytes).unwrap().body, vec![7]);
    bytes.push(0);
    assert!(matches!(
        Packet::parse(&bytes).unwrap_err().kind(),
        &DecodeErrorKind::DataSizeMismatch {
            header: 1,
            actual: 2
        }
    ));
    assert!(matches!(
        Packet::parse(&bytes[..5]).unwrap_err().kind(),
        &DecodeErrorKind::TruncatedHeader { len: 5 }
    ));
    // `PacketRef::parse` builds its header itself (after the size checks): the same
    // header as `Header::parse`.
    let p = PacketRef::parse(&bytes[..17]).unwrap();
    assert_eq!(p.header, Header::parse(&bytes).unwrap());
    assert_eq!(p.body, &[7]);
}

/// The size of `messages::Message`, which `Message::decode` (the README's first
/// example, by command code) returns and every hand-over of a decoded message moves.
/// 344 bytes is Report Platform Specifications, the largest message (the next is
/// 192: Set/Report Wrench Effort); a message that outgrows it fails here. Boxing
/// large variants was considered and not done (issue 49): the fixed-size messages
/// decoded most (pose, wrench effort, path segment) are 80–192 bytes, so a box
/// would allocate on every decode (`tests/tests/alloc.rs` pins none), and the
/// enum's size was measured not to be where decoding by code lost time
/// (docs/performance.md).
#[test]
fn message_enum_size_is_bounded() {
    use crate::messages::Message;
    let size = std::mem::size_of::<Message>();
    assert!(
        size <= 344,
        "messages::Message grew to {size} bytes (bound 344): find the message that \
         grew, or raise the bound with a measurement (docs/performance.md)"
    );
    // The decode error in the enum's niche: `Result` adds nothing to copy.
    assert_eq!(std::mem::size_of::<Result<Message, DecodeError>>(), size);
}

/// A body of `n` bytes that counts the calls of `encoded_len`.
struct Counted(Vec<u8>, std::cell::Cell<u32>);

impl Encode for Counted {
    fn encoded_len(&self) -> usize {
        self.1.set(self.1.get() + 1);
        self.0.len()
    }
    fn encode(&self, w: &mut Writer<'_>) -> Result<(), EncodeError> {
        w.put(&self.0)
    }
}

fn body(n: usize) -> Counted {
    Counted((0..n).map(|i| i as u8).collect(), Default::default())
}

#[test]
fn write_packet_walks_the_body_once() {
    let h = Header::new(
        CommandCode(0x4402),
        Address::new(1, 2, 3, 4),
        Address::new(5, 6, 7, 8),
    );
    let mut buf = vec![0xAA; 64];
    for n in [0, 3, 48] {
        let b = body(n);
        let len = h.write_packet(&b, &mut buf).unwrap();
        assert_eq!(b.1.get(), 0, "encoded_len called on the success path");
        let packet = Packet::new(h, b.0.clone()).to_bytes().unwrap();
        assert_eq!(buf[..len], packet[..]);
        assert_eq!(PacketRef::parse(&buf[..len]).unwrap().body, &b.0[..]);
    }
    let mut buf = vec![0; HEADER_LEN + MAX_DATA_SIZE];
    assert_eq!(
        h.write_packet(&body(MAX_DATA_SIZE), &mut buf),
        Ok(buf.len())
    );
    assert_eq!(Header::parse(&buf).unwrap().data_size, 0x0FFF);
}

#[test]
fn write_packet_errors_in_their_order() {
    let h = Header::new(
        CommandCode(0x4402),
        Address::new(1, 2, 3, 4),
        Address::new(5, 6, 7, 8),
    );
    let too_large = Err(EncodeError::BodyTooLarge {
        len: MAX_DATA_SIZE + 1,
        max: MAX_DATA_SIZE,
    });
    // Over the limit whatever the buffer, and before a bad header field.
    for cap in [4, 64, HEADER_LEN + MAX_DATA_SIZE, 8192] {
        let mut buf = vec![0; cap];
        assert_eq!(
            h.write_packet(&body(MAX_DATA_SIZE + 1), &mut buf),
            too_large
        );
    }
    let bad = Header { priority: 16, ..h };
    let mut buf = vec![0; 8192];
    assert_eq!(
        bad.write_packet(&body(MAX_DATA_SIZE + 1), &mut buf),
        too_large
    );
    assert!(matches!(
        bad.write_packet(&body(3), &mut buf),
        Err(EncodeError::BitsOverflow {
            field: "Header.priority",
            value: 16,
            width: 4
        })
    ));
    let small = |cap: usize, n: usize| h.write_packet(&body(n), &mut vec![0; cap]);
    let short = |needed, capacity| Err(EncodeError::BufferTooSmall { needed, capacity });
    assert_eq!(small(18, 3), short(19, 18));
    assert_eq!(small(12, 0), short(16, 12));
    assert_eq!(small(5, 0), short(8, 5));
    assert_eq!(small(HEADER_LEN + 3, 3), Ok(HEADER_LEN + 3));
}

#[test]
fn address_text() {
    let a: Address = "1.2.3.4".parse().unwrap();
    assert_eq!(a.to_string(), "1.2.3.4");
    assert!("1.2.3".parse::<Address>().is_err());
    assert!(Address::new(1, 255, 255, 255).matches(&Address::new(1, 2, 3, 4)));
    assert!(!Address::new(2, 255, 255, 255).matches(&Address::new(1, 2, 3, 4)));
}
