//! A bit field with single bits, a bit range and the reserved bits.

use jaus::codec::{Decode, Encode, EncodeError};
use jaus::JausBits;

#[derive(Debug, Clone, Copy, PartialEq, Default, JausBits)]
#[jaus(repr = u16)]
struct Status {
    #[jaus(bit = 0)]
    ready: bool,
    #[jaus(bits = 2..=5)]
    mode: u8,
    #[jaus(bit = 15)]
    fault: bool,
    #[jaus(reserved)]
    reserved: u16,
}

fn main() {
    let s = Status {
        ready: true,
        mode: 0b1010,
        fault: true,
        reserved: 0,
    };
    // 1 | 10 << 2 | 1 << 15 = 0x8029
    assert_eq!(s.to_bytes().unwrap(), [0x29, 0x80]);
    assert_eq!(Status::from_bytes(&[0x29, 0x80]).unwrap(), s);
    assert_eq!(Status::default().to_bytes().unwrap(), [0x00, 0x00]);

    // Undefined bits (1 and 6..=14) land in `reserved` and re-encode unchanged.
    let raw = [0x42, 0x7F];
    let d = Status::from_bytes(&raw).unwrap();
    assert!(!d.ready && !d.fault);
    assert_eq!(d.mode, 0);
    assert_eq!(d.reserved, 0x7F42);
    assert_eq!(d.to_bytes().unwrap(), raw);

    // All ones.
    let d = Status::from_bytes(&[0xFF, 0xFF]).unwrap();
    assert!(d.ready && d.fault);
    assert_eq!(d.mode, 0b1111);
    assert_eq!(d.to_bytes().unwrap(), [0xFF, 0xFF]);

    // A value wider than its bits is an encode error, not silent truncation.
    let bad = Status {
        mode: 16,
        ..Status::default()
    };
    assert!(matches!(
        bad.to_bytes(),
        Err(EncodeError::BitsOverflow {
            field: "Status.mode",
            value: 16,
            width: 4
        })
    ));
}
