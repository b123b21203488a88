//! Byte blobs (u8 size, fixed, rest) and a u32 size prefix around a nested record.

use jaus::codec::{Decode, Encode};
use jaus::{JausMessage, JausRecord};

#[derive(Debug, Clone, PartialEq, JausRecord)]
#[jaus(presence = u8)]
struct Inner {
    a: u16,
    #[jaus(bit = 0)]
    b: Option<u8>,
}

#[derive(Debug, PartialEq, JausMessage)]
#[jaus(code = 0xD400)]
struct ReportBlob {
    #[jaus(size = u8)]
    raw: Vec<u8>,
    #[jaus(fixed = 4)]
    key: Vec<u8>,
    #[jaus(size = u32)]
    inner: Inner,
    #[jaus(rest)]
    tail: Vec<u8>,
}

fn main() {
    let m = ReportBlob {
        raw: vec![0xAA, 0xBB],
        key: vec![1, 2, 3, 4],
        inner: Inner {
            a: 0x0102,
            b: Some(9),
        },
        tail: vec![0xEE],
    };
    let bytes = m.to_bytes().unwrap();
    assert_eq!(
        bytes,
        [
            0x02, 0xAA, 0xBB, // size u8, raw
            1, 2, 3, 4, // fixed 4
            0x04, 0x00, 0x00, 0x00, // size u32 of inner
            0x01, 0x02, 0x01, 0x09, // inner: pv, a, b
            0xEE, // rest
        ]
    );
    assert_eq!(ReportBlob::from_bytes(&bytes).unwrap(), m);

    // A shorter fixed blob is zero padded on encode.
    let short = ReportBlob {
        raw: vec![],
        key: vec![7],
        inner: Inner { a: 0, b: None },
        tail: vec![],
    };
    let bytes = short.to_bytes().unwrap();
    assert_eq!(
        bytes,
        [0x00, 7, 0, 0, 0, 0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00]
    );
    let back = ReportBlob::from_bytes(&bytes).unwrap();
    assert_eq!(back.key, [7, 0, 0, 0]);

    // A size prefix larger than what the record consumes is a size mismatch.
    let bad = [
        0x00, 0, 0, 0, 0, 0x04, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00,
    ];
    let e = ReportBlob::from_bytes(&bad).unwrap_err();
    let text = e.to_string();
    assert!(
        text.contains("size prefix says 4 byte(s) but content is 3"),
        "{text}"
    );
    assert!(text.contains("in field `ReportBlob.inner`"), "{text}");

    // A size prefix beyond the buffer is rejected.
    assert!(ReportBlob::from_bytes(&[0x05, 0xAA]).is_err());
}
