//! Strings: fixed length, u16 size prefix, and the rest of the body with a NUL.

use jaus::codec::{Decode, Encode, EncodeError};
use jaus::JausMessage;

#[derive(Debug, PartialEq, JausMessage)]
#[jaus(code = 0xD300)]
struct ReportNames {
    #[jaus(fixed = 8)]
    short: String,
    #[jaus(size = u16)]
    label: String,
    #[jaus(rest, nul)]
    note: String,
}

#[derive(Debug, PartialEq, JausMessage)]
#[jaus(code = 0xD301)]
struct ReportIdent {
    kind: u8,
    #[jaus(fixed = 6, accept_short)]
    ident: String,
}

#[derive(Debug, PartialEq, JausMessage)]
#[jaus(code = 0xD302)]
struct ReportText {
    #[jaus(rest)]
    text: String,
}

fn main() {
    let m = ReportNames {
        short: "abc".into(),
        label: "hi".into(),
        note: "ok".into(),
    };
    let bytes = m.to_bytes().unwrap();
    assert_eq!(
        bytes,
        [
            b'a', b'b', b'c', 0, 0, 0, 0, 0, // fixed 8, NUL padded
            0x02, 0x00, b'h', b'i', // u16 size, bytes
            b'o', b'k', 0x00, // rest, NUL terminated
        ]
    );
    assert_eq!(ReportNames::from_bytes(&bytes).unwrap(), m);

    // Exactly 8 characters fill the fixed field without a NUL; 9 do not fit.
    let full = ReportNames {
        short: "12345678".into(),
        label: String::new(),
        note: String::new(),
    };
    assert_eq!(full.to_bytes().unwrap(), b"12345678\x00\x00\x00");
    assert_eq!(
        ReportNames::from_bytes(b"12345678\x00\x00\x00").unwrap(),
        full
    );
    let long = ReportNames {
        short: "123456789".into(),
        label: String::new(),
        note: String::new(),
    };
    assert!(matches!(
        long.to_bytes(),
        Err(EncodeError::TooLong {
            field: "ReportNames.short",
            len: 9,
            max: 8
        })
    ));

    // ISO-8859-1 characters are one byte each; others are rejected.
    let latin = ReportNames {
        short: "é".into(),
        label: "ü".into(),
        note: String::new(),
    };
    assert_eq!(
        latin.to_bytes().unwrap(),
        [0xE9, 0, 0, 0, 0, 0, 0, 0, 0x01, 0x00, 0xFC, 0x00]
    );
    assert_eq!(
        ReportNames::from_bytes(&latin.to_bytes().unwrap()).unwrap(),
        latin
    );
    let wide = ReportNames {
        short: "€".into(),
        label: String::new(),
        note: String::new(),
    };
    assert!(matches!(
        wide.to_bytes(),
        Err(EncodeError::NotLatin1 { .. })
    ));

    // accept_short: a shorter final fixed field decodes; encoding pads to full length.
    let id = ReportIdent::from_bytes(&[3, b'a', b'b']).unwrap();
    assert_eq!(
        id,
        ReportIdent {
            kind: 3,
            ident: "ab".into()
        }
    );
    assert_eq!(id.to_bytes().unwrap(), [3, b'a', b'b', 0, 0, 0, 0]);

    // rest without nul: no terminator.
    let t = ReportText {
        text: "hello".into(),
    };
    assert_eq!(t.to_bytes().unwrap(), b"hello");
    assert_eq!(ReportText::from_bytes(b"hello").unwrap(), t);
}
