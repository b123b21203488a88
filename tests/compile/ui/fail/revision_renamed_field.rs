//! A spec revision renamed a field: `jaus-gen diff` reports
//! `source-breaking  ... SetTravelSpeed.travel_speed: renamed `speed` → `travel_speed``.
//! The bytes on the wire are the same, so peers still interoperate, but vendor code
//! written against the old revision no longer compiles, and the compiler points at each
//! use of the old name.

use jaus::codec::Encode;
use jaus::JausMessage;

/// Revision 2 of the message, as the generator emits it (`speed` is now `travel_speed`).
#[derive(Debug, JausMessage)]
#[jaus(code = 0xD010)]
pub struct SetTravelSpeed {
    #[jaus(scaled(u16, 0.0, 327.67))]
    pub travel_speed: f64,
}

// Vendor code written against revision 1.
fn command(speed: f64) -> SetTravelSpeed {
    SetTravelSpeed { speed }
}

fn commanded(m: &SetTravelSpeed) -> f64 {
    m.speed
}

fn main() {
    let m = command(1.5);
    let _ = (commanded(&m), m.to_bytes());
}
