//! Enumerations: discriminant values, `value = N`, and an `unknown` variant.

use jaus::codec::{Decode, Encode};
use jaus::JausEnum;

#[derive(Debug, Clone, Copy, PartialEq, JausEnum)]
#[jaus(repr = u8)]
enum Mode {
    #[jaus(value = 0)]
    Standby,
    #[jaus(value = 1)]
    Ready,
    #[jaus(value = 5)]
    Emergency,
    #[jaus(unknown)]
    Unknown(u8),
}

/// A closed enumeration: undefined values are a decode error.
#[derive(Debug, Clone, Copy, PartialEq, JausEnum)]
#[jaus(repr = u16)]
enum Closed {
    A = 1,
    B = 0x0200,
}

fn main() {
    assert_eq!(Mode::Emergency.to_bytes().unwrap(), [5]);
    assert_eq!(Mode::from_bytes(&[1]).unwrap(), Mode::Ready);
    assert_eq!(Mode::from_bytes(&[0]).unwrap(), Mode::Standby);

    // An undefined value is preserved and re-encodes unchanged.
    let u = Mode::from_bytes(&[9]).unwrap();
    assert_eq!(u, Mode::Unknown(9));
    assert_eq!(u.to_bytes().unwrap(), [9]);
    assert_eq!(u.to_repr(), 9);
    assert_eq!(Mode::from_repr(9), None);
    assert_eq!(Mode::from_repr(5), Some(Mode::Emergency));
    assert_eq!(Mode::Unknown(200).encoded_len(), 1);

    assert_eq!(Closed::B.to_bytes().unwrap(), [0x00, 0x02]);
    assert_eq!(Closed::from_bytes(&[0x01, 0x00]).unwrap(), Closed::A);
    let e = Closed::from_bytes(&[0x02, 0x00]).unwrap_err();
    assert_eq!(e.to_string(), "undefined value 2 at byte 0");
    assert!(Closed::from_bytes(&[0x01]).is_err());
}
