//! A tagged union with unit, record and integer variants.

use jaus::codec::{Decode, Encode};
use jaus::{JausRecord, JausUnion};

#[derive(Debug, Clone, PartialEq, JausRecord)]
struct Point {
    x: i16,
    y: i16,
}

#[derive(Debug, Clone, PartialEq, JausUnion)]
#[jaus(tag = u8)]
enum Target {
    #[jaus(tag = 0)]
    Nothing,
    #[jaus(tag = 1)]
    Point(Point),
    #[jaus(tag = 7)]
    Id(u16),
}

#[derive(Debug, Clone, PartialEq, JausUnion)]
#[jaus(tag = u16)]
enum Wide {
    #[jaus(tag = 0x0100)]
    Byte(u8),
}

fn main() {
    assert_eq!(Target::Nothing.to_bytes().unwrap(), [0x00]);
    assert_eq!(Target::Nothing.encoded_len(), 1);
    let p = Target::Point(Point { x: 1, y: -2 });
    assert_eq!(p.to_bytes().unwrap(), [0x01, 0x01, 0x00, 0xFE, 0xFF]);
    assert_eq!(p.encoded_len(), 5);
    assert_eq!(Target::Id(0x1234).to_bytes().unwrap(), [0x07, 0x34, 0x12]);

    for v in [Target::Nothing, p, Target::Id(0x1234)] {
        assert_eq!(Target::from_bytes(&v.to_bytes().unwrap()).unwrap(), v);
    }

    let e = Target::from_bytes(&[0x02]).unwrap_err();
    assert_eq!(e.to_string(), "undefined value 2 at byte 0");
    let e = Target::from_bytes(&[0x01, 0x00]).unwrap_err();
    // The innermost field is named.
    assert!(e.to_string().contains("in field `Point.x`"), "{e}");

    assert_eq!(Wide::Byte(9).to_bytes().unwrap(), [0x00, 0x01, 0x09]);
    assert_eq!(
        Wide::from_bytes(&[0x00, 0x01, 0x09]).unwrap(),
        Wide::Byte(9)
    );
}
