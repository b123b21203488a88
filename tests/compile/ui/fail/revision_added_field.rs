//! A spec revision added an optional field under a new presence bit: `jaus-gen diff`
//! reports `compatible  ... ReportImplementState.draft_force: added at the end under new
//! presence bit 1 (...): older decoders skip it; struct literals and patterns of
//! ReportImplementState without `..` no longer compile`. Peers interoperate, and code
//! that builds the message with `..Default::default()` still compiles
//! (tests/tests/revision_compile.rs); a struct literal listing every field of the old
//! revision does not: Rust has no way to add a field such a literal survives.

use jaus::codec::Encode;
use jaus::JausMessage;

/// Revision 2 of the message, as the generator emits it (`draft_force` is new).
#[derive(Debug, Default, JausMessage)]
#[jaus(code = 0xD201, presence = u8)]
pub struct ReportImplementState {
    #[jaus(scaled(u16, 0.0, 1.5), unit = "m")]
    pub depth: f64,
    #[jaus(bit = 0, scaled(i16, -0.5, 0.5), unit = "rad")]
    pub hitch_angle: Option<f64>,
    #[jaus(bit = 1, scaled(u16, 0.0, 60000.0), unit = "N")]
    pub draft_force: Option<f64>,
}

// Vendor code written against revision 1: the form that keeps compiling...
fn report(depth: f64) -> ReportImplementState {
    ReportImplementState {
        depth,
        hitch_angle: None,
        ..Default::default()
    }
}

// ...and the one that does not.
fn report_listing_every_field(depth: f64) -> ReportImplementState {
    ReportImplementState {
        depth,
        hitch_angle: None,
    }
}

fn main() {
    let _ = (
        report(1.0).to_bytes(),
        report_listing_every_field(1.0).to_bytes(),
    );
}
