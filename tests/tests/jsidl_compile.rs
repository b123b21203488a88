//! The Rust that jaus-gen generates from the JSIDL fixtures of jaus-jsidl (one per
//! language feature, imported together: `jaus-gen/tests/jsidl/fixtures.messages.rs`,
//! kept up to date by jaus-gen's `jsidl` test) compiles against the SDK, and a message
//! of it round-trips.

#[allow(unused, clippy::match_single_binding)]
mod imported {
    include!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../jaus-gen/tests/jsidl/fixtures.messages.rs"
    ));
}

use jaus::codec::Encode;
use jaus::JausMessage;

#[test]
fn an_imported_message_round_trips() {
    use imported::records::{ReportMarker, SetMarker};
    let m = SetMarker {
        x: 1.5,
        y: Some(-2.0),
        z: None,
    };
    let buf = m.to_bytes().unwrap();
    // Presence vector (bit 0: y), then x and y.
    assert_eq!(buf.len(), 1 + 4 + 4);
    assert_eq!(buf[0], 0b01);
    assert_eq!(SetMarker::decode_body(&buf).unwrap(), m);
    assert_eq!(SetMarker::CODE.0, 0x0D04);
    assert_eq!(ReportMarker::CODE.0, 0x4D04);
}
