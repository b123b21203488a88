//! A message with a u16 presence vector, optional scaled fields and a required one.

use jaus::codec::{Decode, Encode};
use jaus::JausMessage;

#[derive(Debug, PartialEq, JausMessage)]
#[jaus(code = 0xD200, presence = u16)]
struct ReportProbe {
    id: u8,
    #[jaus(bit = 0, scaled(i16, -100.0, 100.0))]
    effort: Option<f64>,
    #[jaus(bit = 9, scaled(u8, 0.0, 100.0))]
    level: Option<f64>,
    #[jaus(scaled(u16, 0.0, 1092.0))]
    speed: f64,
}

fn main() {
    assert_eq!(ReportProbe::CODE.0, 0xD200);
    assert_eq!(ReportProbe::NAME, "ReportProbe");

    // Both optional fields present: PV = bit 0 | bit 9 = 0x0201. Values are chosen away
    // from rounding ties: 25 % of ±100 is 8191.75 → 8192 counts, 40 % of 0..100 is
    // 102 counts, 10 of 0..1092 is 600.14 → 600 counts.
    let m = ReportProbe {
        id: 7,
        effort: Some(25.0),
        level: Some(40.0),
        speed: 10.0,
    };
    let bytes = m.to_bytes().unwrap();
    assert_eq!(bytes, [0x01, 0x02, 0x07, 0x00, 0x20, 0x66, 0x58, 0x02]);
    assert_eq!(m.encoded_len(), bytes.len());

    let back = ReportProbe::from_bytes(&bytes).unwrap();
    assert_eq!(back.id, 7);
    assert!((back.effort.unwrap() - 25.0).abs() <= 200.0 / 65534.0);
    assert!((back.level.unwrap() - 40.0).abs() <= 100.0 / 255.0);
    assert!((back.speed - 10.0).abs() <= 1092.0 / 65535.0);
    assert_eq!(back.to_bytes().unwrap(), bytes);

    // No optional field: the presence vector is zero and nothing else is written for them.
    let m = ReportProbe {
        id: 1,
        effort: None,
        level: None,
        speed: 0.0,
    };
    let bytes = m.to_bytes().unwrap();
    assert_eq!(bytes, [0x00, 0x00, 0x01, 0x00, 0x00]);
    assert_eq!(ReportProbe::from_bytes(&bytes).unwrap(), m);

    // Negative values round half away from zero; the limits map to the extreme counts.
    let m = ReportProbe {
        id: 3,
        effort: Some(-100.0),
        level: None,
        speed: 0.0,
    };
    assert_eq!(
        m.to_bytes().unwrap(),
        [0x01, 0x00, 0x03, 0x01, 0x80, 0x00, 0x00]
    );

    // Only bit 9.
    let m = ReportProbe {
        id: 2,
        effort: None,
        level: Some(100.0),
        speed: 1092.0,
    };
    assert_eq!(m.to_bytes().unwrap(), [0x00, 0x02, 0x02, 0xFF, 0xFF, 0xFF]);

    // The minimum length is the presence vector and the required fields.
    assert_eq!(<ReportProbe as Decode>::MIN_LEN, 2 + 1 + 2);
    // A presence bit promising a field that is not there is an error, not a panic.
    assert!(ReportProbe::from_bytes(&[0x01, 0x00, 0x07, 0x00]).is_err());
    // Scaled values must be finite.
    assert!(ReportProbe {
        id: 0,
        effort: Some(f64::NAN),
        level: None,
        speed: 0.0
    }
    .to_bytes()
    .is_err());
}
