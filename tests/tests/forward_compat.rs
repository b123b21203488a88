//! Forward compatibility: a decoder meets a message from a newer revision of its
//! definition, which appends optional fields at the end of the body under presence
//! bits the older revision does not define.
//!
//! `V1` is the older revision, `V2` the newer one (same command code): V2 keeps V1's
//! fields in order and appends a scalar, a string and a list under bits 3, 4 and 5.

use jaus::codec::{DecodeErrorKind, Encode, UndefinedBit};
use jaus::{JausMessage, JausRecord};

#[derive(Debug, Clone, PartialEq, JausRecord)]
struct Point {
    #[jaus(scaled(i32, -90.0, 90.0))]
    latitude: f64,
    #[jaus(scaled(i32, -180.0, 180.0))]
    longitude: f64,
}

/// A record with a presence vector, older revision.
#[derive(Debug, Clone, PartialEq, JausRecord)]
#[jaus(presence = u8)]
struct TagV1 {
    id: u16,
    #[jaus(bit = 0)]
    weight: Option<u8>,
}

/// The same record, newer revision: one more optional field under bit 1.
#[derive(Debug, Clone, PartialEq, JausRecord)]
#[jaus(presence = u8)]
struct TagV2 {
    id: u16,
    #[jaus(bit = 0)]
    weight: Option<u8>,
    #[jaus(bit = 1)]
    colour: Option<u32>,
}

#[derive(Debug, Clone, PartialEq, Default, JausMessage)]
#[jaus(code = 0xD700, presence = u16)]
struct V1 {
    route_id: u16,
    #[jaus(bit = 0)]
    speed: Option<u16>,
    #[jaus(bit = 1, count = u8)]
    points: Option<Vec<Point>>,
    #[jaus(bit = 2, size = u8)]
    name: Option<String>,
}

#[derive(Debug, Clone, PartialEq, Default, JausMessage)]
#[jaus(code = 0xD700, presence = u16)]
struct V2 {
    route_id: u16,
    #[jaus(bit = 0)]
    speed: Option<u16>,
    #[jaus(bit = 1, count = u8)]
    points: Option<Vec<Point>>,
    #[jaus(bit = 2, size = u8)]
    name: Option<String>,
    // Appended by the newer revision:
    #[jaus(bit = 3)]
    priority: Option<u32>,
    #[jaus(bit = 4, size = u16)]
    comment: Option<String>,
    #[jaus(bit = 5, count = u8)]
    waypoints: Option<Vec<Point>>,
}

/// Lists of records with presence vectors, older and newer revision of the record.
#[derive(Debug, Clone, PartialEq, JausMessage)]
#[jaus(code = 0xD701)]
struct TagsV1 {
    #[jaus(count = u8)]
    tags: Vec<TagV1>,
    trailer: u8,
}

#[derive(Debug, Clone, PartialEq, JausMessage)]
#[jaus(code = 0xD701)]
struct TagsV2 {
    #[jaus(count = u8)]
    tags: Vec<TagV2>,
    trailer: u8,
}

fn points() -> Vec<Point> {
    vec![
        Point {
            latitude: 29.5,
            longitude: -82.25,
        },
        Point {
            latitude: -10.0,
            longitude: 170.0,
        },
    ]
}

fn v2_full() -> V2 {
    V2 {
        route_id: 7,
        speed: Some(1200),
        points: Some(points()),
        name: Some("north loop".into()),
        priority: Some(0xDEAD_BEEF),
        comment: Some("added in revision 2".into()),
        waypoints: Some(points()),
    }
}

fn close(a: &[Point], b: &[Point]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(p, q)| {
            (p.latitude - q.latitude).abs() < 1e-7 && (p.longitude - q.longitude).abs() < 1e-7
        })
}

#[test]
fn newer_bytes_decode_as_the_older_revision_with_the_known_fields() {
    let new = v2_full();
    let bytes = new.to_bytes().unwrap();
    let old = V1::decode_body(&bytes).expect("unknown bits at the end are skipped");
    assert_eq!(old.route_id, 7);
    assert_eq!(old.speed, Some(1200));
    assert_eq!(old.name.as_deref(), Some("north loop"));
    assert!(close(old.points.as_deref().unwrap(), &points()));

    // Each appended field alone (scalar, string, list), and none of the known ones.
    let alone = [
        V2 {
            priority: Some(3),
            ..V2::default()
        },
        V2 {
            comment: Some("text".into()),
            ..V2::default()
        },
        V2 {
            waypoints: Some(points()),
            ..V2::default()
        },
        V2 {
            speed: Some(5),
            waypoints: Some(vec![]),
            ..V2::default()
        },
    ];
    for m in alone {
        let old = V1::decode_body(&m.to_bytes().unwrap()).unwrap();
        assert_eq!(old.route_id, m.route_id);
        assert_eq!(old.speed, m.speed);
        assert_eq!(old.points, None);
        assert_eq!(old.name, None);
    }
}

#[test]
fn re_encoding_never_emits_the_unknown_bits_or_their_bytes() {
    let bytes = v2_full().to_bytes().unwrap();
    let old = V1::decode_body(&bytes).unwrap();
    let again = old.to_bytes().unwrap();
    // Presence vector: only V1's bits 0..=2.
    assert_eq!(u16::from_le_bytes([again[0], again[1]]), 0b111);
    // V1's encoding is a prefix of V2's apart from the presence vector.
    assert_eq!(again[2..], bytes[2..again.len()]);
    assert!(again.len() < bytes.len());
}

#[test]
fn older_bytes_decode_as_the_newer_revision_with_the_new_fields_absent() {
    let old = V1 {
        route_id: 9,
        speed: Some(40),
        points: Some(points()),
        name: Some("south".into()),
    };
    let new = V2::decode_body(&old.to_bytes().unwrap()).unwrap();
    assert_eq!(new.route_id, 9);
    assert_eq!(new.speed, Some(40));
    assert_eq!(new.name.as_deref(), Some("south"));
    assert!(close(new.points.as_deref().unwrap(), &points()));
    assert_eq!(
        (new.priority, new.comment, new.waypoints),
        (None, None, None)
    );
}

#[test]
fn an_unknown_bit_in_a_nested_record_is_a_typed_error() {
    let new = TagsV2 {
        tags: vec![
            TagV2 {
                id: 1,
                weight: Some(2),
                colour: None,
            },
            TagV2 {
                id: 3,
                weight: None,
                colour: Some(0x00FF_8800),
            },
        ],
        trailer: 0xAA,
    };
    let bytes = new.to_bytes().unwrap();
    let e = TagsV1::decode_body(&bytes).unwrap_err();
    assert_eq!(
        e.kind(),
        &DecodeErrorKind::UndefinedPresenceBit {
            bit: 1,
            why: UndefinedBit::InRecord
        }
    );
    assert_eq!(e.message(), Some("TagsV1"));
    assert_eq!(e.path(), ["TagV1.presence_vector", "TagsV1.tags"]);
    // Offset of the second record's presence vector: the count, then the first record
    // (presence vector, id, weight).
    assert_eq!(e.offset(), 1 + 4);
    let text = e.to_string();
    assert!(
        text.starts_with("TagsV1: presence bit 1 is not defined by this revision"),
        "{text}"
    );
    assert!(
        text.contains("in field `TagV1.presence_vector` of `TagsV1.tags` at byte 5"),
        "{text}"
    );

    // Without the new field the newer record decodes as the older one.
    let known = TagsV2 {
        tags: vec![TagV2 {
            id: 1,
            weight: Some(2),
            colour: None,
        }],
        trailer: 1,
    };
    let old = TagsV1::decode_body(&known.to_bytes().unwrap()).unwrap();
    assert_eq!(old.tags[0].weight, Some(2));
}

#[test]
fn trailing_bytes_without_unknown_bits_are_still_an_error() {
    let mut bytes = V1 {
        route_id: 1,
        speed: Some(2),
        ..V1::default()
    }
    .to_bytes()
    .unwrap();
    bytes.extend_from_slice(&[0xDE, 0xAD]);
    let e = V1::decode_body(&bytes).unwrap_err();
    assert_eq!(e.kind(), &DecodeErrorKind::TrailingBytes { count: 2 });
    // And a newer message cut short in its known fields is still truncated.
    let cut = &v2_full().to_bytes().unwrap()[..6];
    assert!(matches!(
        V1::decode_body(cut).unwrap_err().kind(),
        DecodeErrorKind::Truncated { .. }
    ));
}

/// A definition with a gap in its bits (2 is not defined, 3 is): a set bit 2 may belong
/// to a field placed before bit 3's, so bit 3's position is unknown.
#[derive(Debug, Clone, PartialEq, Default, JausMessage)]
#[jaus(code = 0xD702, presence = u8)]
struct Gap {
    #[jaus(bit = 0)]
    a: Option<u8>,
    #[jaus(bit = 3)]
    d: Option<u8>,
}

/// A definition whose last field runs to the end of the body.
#[derive(Debug, Clone, PartialEq, Default, JausMessage)]
#[jaus(code = 0xD703, presence = u8)]
struct Tail {
    #[jaus(bit = 0)]
    a: Option<u8>,
    #[jaus(bit = 1, rest)]
    text: Option<String>,
}

#[test]
fn an_unknown_bit_below_a_defined_one_or_before_a_rest_field_is_a_typed_error() {
    let e = Gap::decode_body(&[0b0000_0101, 1, 9]).unwrap_err();
    assert_eq!(
        e.kind(),
        &DecodeErrorKind::UndefinedPresenceBit {
            bit: 2,
            why: UndefinedBit::BelowDefinedBit(3)
        }
    );
    assert_eq!(e.field(), Some("Gap.presence_vector"));
    assert!(e.to_string().contains("below defined bit 3"), "{e}");
    // Bits above every defined one are skipped.
    assert_eq!(
        Gap::decode_body(&[0b0001_1001, 1, 4, 9, 9]).unwrap(),
        Gap {
            a: Some(1),
            d: Some(4)
        }
    );

    // The text would swallow what a newer revision appended under bit 2.
    let e = Tail::decode_body(&[0b0000_0110, b'h', b'i', 7]).unwrap_err();
    assert_eq!(
        e.kind(),
        &DecodeErrorKind::UndefinedPresenceBit {
            bit: 2,
            why: UndefinedBit::RestField
        }
    );
    // Without the text there is nothing to confuse.
    assert_eq!(
        Tail::decode_body(&[0b0000_0101, 3, 7, 7]).unwrap(),
        Tail {
            a: Some(3),
            text: None
        }
    );
}

/// Every message of the set with a presence vector, from its reference vector: a newer
/// revision that sets the next bit above the defined ones and appends bytes decodes to
/// the same message, unless the last field runs to the end of the body and is present.
#[test]
fn every_message_of_the_set_reads_a_newer_revision() {
    use jaus::messages::Message;
    use jaus::CommandCode;
    let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).expect("definitions validate");
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/openjaus33.jsonl"
    ))
    .unwrap();
    let (mut skipped, mut rest) = (0, 0);
    let mut messages = std::collections::BTreeSet::new();
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        let packet = jaus::hex::decode(v["hex"].as_str().unwrap()).unwrap();
        let code = u16::from_le_bytes([packet[2], packet[3]]);
        let Some(m) = spec.message_by_code(code) else {
            continue;
        };
        let Some(p) = m.presence else { continue };
        let highest = m.def.fields.iter().filter_map(|f| f.bit).max().unwrap_or(0);
        let width = 8 * p.bytes() as u32;
        if highest + 1 >= width {
            continue; // no bit left for a newer revision
        }
        let body = &packet[16..];
        let known = Message::decode(CommandCode(code), body).unwrap();
        let mut newer = body.to_vec();
        let mut pv = [0u8; 8];
        pv[..p.bytes()].copy_from_slice(&newer[..p.bytes()]);
        let pv = u64::from_le_bytes(pv) | 1 << (highest + 1);
        newer[..p.bytes()].copy_from_slice(&pv.to_le_bytes()[..p.bytes()]);
        newer.extend_from_slice(&[0x5A, 0xA5, 0x01]);
        match Message::decode(CommandCode(code), &newer) {
            Ok(back) => {
                assert_eq!(format!("{back:?}"), format!("{known:?}"), "{}", m.def.name);
                assert_eq!(back.to_bytes().unwrap(), body, "{}", m.def.name);
                skipped += 1;
                messages.insert(m.def.name.clone());
            }
            Err(e) => {
                assert_eq!(
                    e.kind(),
                    &DecodeErrorKind::UndefinedPresenceBit {
                        bit: highest + 1,
                        why: UndefinedBit::RestField
                    },
                    "{}: {e}",
                    m.def.name
                );
                assert!(
                    m.def
                        .fields
                        .last()
                        .is_some_and(|f| matches!(f.length, Some(jaus_spec::Length::Rest))),
                    "{}",
                    m.def.name
                );
                rest += 1;
            }
        }
    }
    eprintln!(
        "{skipped} vectors of {} messages skipped the appended fields, {rest} refused (rest field)",
        messages.len()
    );
    assert!(skipped > 250 && messages.len() > 30);
}
