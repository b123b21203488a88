//! A list of records with a u8 count, and a `rest` list of integers.

use jaus::codec::{Decode, Encode, EncodeError};
use jaus::{JausMessage, JausRecord};

#[derive(Debug, Clone, PartialEq, JausRecord)]
struct Waypoint {
    #[jaus(scaled(i32, -90.0, 90.0))]
    latitude: f64,
    speed: u16,
}

#[derive(Debug, PartialEq, JausMessage)]
#[jaus(code = 0xD500)]
struct ReportRoute {
    route_id: u16,
    #[jaus(count = u8)]
    points: Vec<Waypoint>,
    #[jaus(rest)]
    extra: Vec<u16>,
}

fn main() {
    let m = ReportRoute {
        route_id: 0x0102,
        points: vec![
            Waypoint {
                latitude: 0.0,
                speed: 3,
            },
            Waypoint {
                latitude: 90.0,
                speed: 0xABCD,
            },
        ],
        extra: vec![0x1122, 0x3344],
    };
    let bytes = m.to_bytes().unwrap();
    assert_eq!(
        bytes,
        [
            0x02, 0x01, // route_id
            0x02, // count
            0x00, 0x00, 0x00, 0x00, 0x03, 0x00, // 0.0 degrees, speed 3
            0xFF, 0xFF, 0xFF, 0x7F, 0xCD, 0xAB, // 90.0 degrees, speed 0xABCD
            0x22, 0x11, 0x44, 0x33, // rest
        ]
    );
    let back = ReportRoute::from_bytes(&bytes).unwrap();
    assert_eq!(back.points.len(), 2);
    assert_eq!(
        back.points[0],
        Waypoint {
            latitude: 0.0,
            speed: 3
        }
    );
    assert!((back.points[1].latitude - 90.0).abs() < 1e-6);
    assert_eq!(back.extra, [0x1122, 0x3344]);
    assert_eq!(back.to_bytes().unwrap(), bytes);

    // Empty list and empty rest.
    let empty = ReportRoute {
        route_id: 9,
        points: vec![],
        extra: vec![],
    };
    assert_eq!(empty.to_bytes().unwrap(), [0x09, 0x00, 0x00]);
    assert_eq!(ReportRoute::from_bytes(&[0x09, 0x00, 0x00]).unwrap(), empty);

    // A count that the remaining bytes cannot hold is rejected before allocating.
    let e = ReportRoute::from_bytes(&[0x09, 0x00, 0xFF, 0x00]).unwrap_err();
    let text = e.to_string();
    assert!(
        text.starts_with("count 255 beyond buffer (1 byte(s) left)"),
        "{text}"
    );
    assert!(text.contains("in field `ReportRoute.points`"), "{text}");

    // 256 elements do not fit a u8 count.
    let big = ReportRoute {
        route_id: 0,
        points: vec![
            Waypoint {
                latitude: 0.0,
                speed: 0
            };
            256
        ],
        extra: vec![],
    };
    assert!(matches!(
        big.to_bytes(),
        Err(EncodeError::CountOverflow {
            field: "ReportRoute.points",
            count: 256,
            max: 255
        })
    ));

    // An odd trailing byte cannot be a u16 of the rest list.
    assert!(ReportRoute::from_bytes(&[0x09, 0x00, 0x00, 0x01]).is_err());
}
