//! A list of scaled reals, a u16-counted list, and a record nested without a prefix.

use jaus::codec::{Decode, Encode};
use jaus::{JausMessage, JausRecord};

#[derive(Debug, Clone, PartialEq, Default, JausRecord)]
#[jaus(presence = u32)]
struct Extras {
    #[jaus(bit = 31)]
    flag: Option<u8>,
}

#[derive(Debug, PartialEq, JausMessage)]
#[jaus(code = 0xD600)]
struct ReportLevels {
    #[jaus(count = u16, scaled(u8, 0.0, 255.0))]
    levels: Vec<f64>,
    extras: Extras,
    #[jaus(rest, scaled(i16, -PI, PI))]
    angles: Vec<f64>,
}

fn main() {
    let m = ReportLevels {
        levels: vec![0.0, 1.0, 255.0],
        extras: Extras { flag: Some(0x5A) },
        angles: vec![0.0],
    };
    let bytes = m.to_bytes().unwrap();
    assert_eq!(
        bytes,
        [
            0x03, 0x00, 0x00, 0x01, 0xFF, // count u16, three u8 levels
            0x00, 0x00, 0x00, 0x80, 0x5A, // presence u32 with bit 31, flag
            0x00, 0x00, // one angle
        ]
    );
    let back = ReportLevels::from_bytes(&bytes).unwrap();
    assert_eq!(back, m);

    let none = ReportLevels {
        levels: vec![],
        extras: Extras::default(),
        angles: vec![],
    };
    assert_eq!(none.to_bytes().unwrap(), [0, 0, 0, 0, 0, 0]);
    assert_eq!(ReportLevels::from_bytes(&[0, 0, 0, 0, 0, 0]).unwrap(), none);

    // Angle PI encodes to the largest i16 count and decodes back within one step.
    let pi = ReportLevels {
        levels: vec![],
        extras: Extras::default(),
        angles: vec![std::f64::consts::PI],
    };
    let bytes = pi.to_bytes().unwrap();
    assert_eq!(&bytes[6..], [0xFF, 0x7F]);
    let back = ReportLevels::from_bytes(&bytes).unwrap();
    assert!((back.angles[0] - std::f64::consts::PI).abs() <= 2.0 * std::f64::consts::PI / 65534.0);

    // An odd byte at the end of a `rest` list of i16 is an error.
    assert!(ReportLevels::from_bytes(&[0, 0, 0, 0, 0, 0, 0x01]).is_err());
}
