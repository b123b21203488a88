//! Fields named like the decoder's own locals (`r` the reader, `pv` the presence
//! vector, `present`, `n`, `v`, `e`) and a raw identifier (`r#type`) decode as any
//! other: a colour record with `r`, `g`, `b`, and a message around it.

use jaus::codec::{Decode, Encode};
use jaus::{JausMessage, JausRecord};

#[derive(Debug, Clone, PartialEq, Default, JausRecord)]
struct Rgb {
    r: u8,
    g: u8,
    b: u8,
}

#[derive(Debug, PartialEq, JausMessage)]
#[jaus(code = 0xD201, presence = u8)]
struct ReportLamp {
    r: u8,
    #[jaus(bit = 0)]
    pv: Option<u16>,
    #[jaus(bit = 1)]
    present: Option<u8>,
    n: u8,
    v: u16,
    e: Rgb,
    r#type: u8,
}

fn main() {
    let m = ReportLamp {
        r: 1,
        pv: Some(0x0302),
        present: None,
        n: 4,
        v: 0x0605,
        e: Rgb { r: 7, g: 8, b: 9 },
        r#type: 10,
    };
    let bytes = m.to_bytes().unwrap();
    assert_eq!(bytes, [0x01, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 7, 8, 9, 10]);
    assert_eq!(ReportLamp::from_bytes(&bytes).unwrap(), m);
}
