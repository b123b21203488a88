//! The vendor flow end to end: `vendor/acme.yaml` → `build.rs` (jaus-gen) → typed
//! messages in this crate, depending on the SDK like any vendor crate. Also the golden
//! file of that generated code: a template change shows up as a reviewable diff in
//! `golden/acme.rs` (rewrite it with `UPDATE_GOLDEN=1 cargo test -p jaus-tests --test vendor`).

#[allow(dead_code)]
mod acme {
    include!(concat!(env!("OUT_DIR"), "/messages.rs"));

    /// The vendor's component skeletons (a child of the module holding the messages).
    pub mod components {
        include!(concat!(env!("OUT_DIR"), "/components.rs"));
    }
}

use acme::*;
use jaus::codec::{Decode, Encode};
use jaus::{Address, CommandCode, Header, JausMessage, Packet};

#[test]
fn generated_code_matches_the_golden_file() {
    let generated = std::fs::read_to_string(concat!(env!("OUT_DIR"), "/messages.rs")).unwrap();
    let golden_path = concat!(env!("CARGO_MANIFEST_DIR"), "/golden/acme.rs");
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(golden_path, &generated).unwrap();
    }
    let golden = std::fs::read_to_string(golden_path).unwrap_or_default();
    assert!(
        golden == generated,
        "generated code differs from golden/acme.rs; review and run with UPDATE_GOLDEN=1"
    );
}

fn sample() -> ReportTanks {
    ReportTanks {
        vehicle: "carrier-7".into(),
        tanks: vec![
            Tank {
                kind: TankKind::Hydraulic,
                level: 50.0,
                flags: TankFlags {
                    low: true,
                    leaking: false,
                    sensor_id: 9,
                    reserved: 0,
                },
                label: Some("aft".into()),
                temperatures: Some(vec![-40.0, 20.0, 125.0]),
            },
            Tank {
                kind: TankKind::Unknown(42),
                level: 100.0,
                ..Default::default()
            },
        ],
        readings: Some(vec![
            Reading::Level(7),
            Reading::Temperature(21.5),
            Reading::Missing,
        ]),
        serial: Some(vec![1, 2, 3, 4]),
        uptime: None,
        note: Some("ok".into()),
    }
}

#[test]
fn vendor_message_has_the_documented_wire_form() {
    let m = sample();
    let b = m.to_bytes().unwrap();
    // Presence vector: bits 0 (readings), 3 (serial) and 9 (note).
    assert_eq!(&b[..2], &[0b0000_1001, 0b0000_0010]);
    assert_eq!(&b[2..17], b"carrier-7\0\0\0\0\0\0");
    assert_eq!(b[17], 2, "tank count");
    // Tank 1: presence 0b11, kind 7, level 50 % of a u16 [0, 100] (32768), flags.
    assert_eq!(&b[18..24], &[0b11, 7, 0x00, 0x80, 0b1001_0001, 0x00]);
    assert_eq!(&b[24..28], &[3, b'a', b'f', b't']);
    assert_eq!(b.last(), Some(&0), "the note ends with a NUL");
    let back = ReportTanks::decode_body(&b).unwrap();
    assert_eq!(back.tanks[1].kind, TankKind::Unknown(42));
    assert_eq!(back.readings, m.readings);
    assert_eq!(back.to_bytes().unwrap(), b);
    assert_eq!(ReportTanks::CODE, CommandCode(0xF100));
    assert_eq!(
        Message::decode(ReportTanks::CODE, &b).unwrap(),
        Message::ReportTanks(back)
    );
}

#[test]
fn embedded_messages_decode_through_their_code_field() {
    let inner = QueryTanks { presence_vector: 3 };
    let header = Header::new(
        QueryTanks::CODE,
        Address::new(1, 1, 200, 1),
        Address::new(2, 1, 40, 1),
    );
    let replay = ReplayTanks {
        wrapped_code: QueryTanks::CODE.0,
        wrapped: inner.to_bytes().unwrap(),
        packet: Packet::new(header, inner.to_bytes().unwrap()),
        tail: vec![9, 9],
    };
    let bytes = replay.to_bytes().unwrap();
    let back = ReplayTanks::from_bytes(&bytes).unwrap();
    assert_eq!(back.wrapped_decoded().unwrap(), Message::QueryTanks(inner));
    assert_eq!(back.packet.header.source, Address::new(2, 1, 40, 1));
    assert_eq!(back, replay);
    // A size prefix that disagrees with the embedded packet is a typed error.
    let mut bad = bytes.clone();
    let at = 2 + 4 + 1; // code, u32 size, one body byte
    bad[at] = bad[at].wrapping_add(1);
    assert!(ReplayTanks::from_bytes(&bad).is_err());
}

#[test]
fn vendor_messages_have_json() {
    let json = serde_json::to_string(&Message::ReportTanks(sample())).unwrap();
    assert!(
        json.starts_with(r#"{"message":"ReportTanks","fields":{"vehicle":"carrier-7""#),
        "{json}"
    );
    let back: Message = serde_json::from_str(&json).unwrap();
    assert_eq!(back, Message::ReportTanks(sample()));
    // The vendor's own messages only; the SDK's are in `jaus::messages::MESSAGES`.
    assert_eq!(MESSAGES.len(), 5);
    // A standard message in the vendor's set has the SDK's JSON form and comes back
    // as the standard one.
    let resume = Message::Jaus(jaus::messages::Message::Resume(jaus::messages::Resume {}));
    let json = serde_json::to_string(&resume).unwrap();
    assert_eq!(json, r#"{"message":"Resume","fields":{}}"#);
    assert_eq!(serde_json::from_str::<Message>(&json).unwrap(), resume);
}
