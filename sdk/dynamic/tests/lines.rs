//! The JSON-line entry points fail with typed errors that say what failed: the same
//! errors as the generated decoder's on the same input.

use jaus::json::{DecodeLineError, JsonError, REFERENCE_PACKETS};
use jaus_dynamic::{EncodeLineError, Schema};

#[test]
fn decode_line_errors_are_those_of_the_generated_decoder() {
    let schema = Schema::sdk().expect("the SDK's definitions");
    let bad_hex = "0g";
    let e = schema.decode_line(bad_hex).unwrap_err();
    assert!(matches!(e, DecodeLineError::Hex(_)), "{e:?}");
    assert_eq!(Err(e), jaus::json::decode_line(bad_hex));

    let short = "0200";
    let e = schema.decode_line(short).unwrap_err();
    assert!(matches!(e, DecodeLineError::Packet(_)), "{e:?}");
    assert_eq!(Err(e), jaus::json::decode_line(short));

    // A reference packet with its body cut short: the message and field are named.
    let (_, hex) = REFERENCE_PACKETS[0];
    let mut bytes = jaus::hex::decode(hex).unwrap();
    bytes.truncate(bytes.len() - 2);
    // The data control field: the body's size (the data flag bits are 0: single).
    let size = u16::try_from(bytes.len() - 16).unwrap();
    bytes[12..14].copy_from_slice(&size.to_le_bytes());
    let cut = jaus::hex::encode(&bytes);
    let e = schema.decode_line(&cut).unwrap_err();
    assert!(matches!(e, DecodeLineError::Message(_)), "{e:?}");
    assert_eq!(Err(e.clone()), jaus::json::decode_line(&cut));
    assert!(e.to_string().contains("ReportGlobalPose"), "{e}");
}

#[test]
fn encode_line_errors_name_what_failed() {
    let schema = Schema::sdk().expect("the SDK's definitions");
    let e = schema.encode_line("{").unwrap_err();
    assert!(
        matches!(e, EncodeLineError::Json(JsonError::Syntax(_))),
        "{e:?}"
    );
    let e = schema
        .encode_line(r#"{"message": "ReportGlobalPoze"}"#)
        .unwrap_err();
    assert!(
        matches!(&e, EncodeLineError::Json(JsonError::UnknownMessage { name, .. }) if name == "ReportGlobalPoze"),
        "{e:?}"
    );
    // No addresses: the header cannot be completed.
    let e = schema
        .encode_line(r#"{"message": "QueryGlobalPose", "fields": {"presence_vector": 0}}"#)
        .unwrap_err();
    assert!(
        matches!(&e, EncodeLineError::Json(JsonError::Header(h)) if h.contains("destination")),
        "{e:?}"
    );
}
