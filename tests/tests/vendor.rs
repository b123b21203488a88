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

mod common;

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

/// The vendor's overlay loaded at run time (as `jaus --spec vendor/acme.yaml` does)
/// decodes and encodes the vendor's messages exactly as the generated types: the same
/// JSON and the same bytes, for the enumerations (named and unknown values), bit
/// fields, unions, optional fields, strings of every length rule, embedded bodies and
/// packets of this overlay, and the same verdict on damaged bodies.
#[test]
fn the_run_time_codec_equals_the_generated_one_on_the_vendor_messages() {
    let schema =
        jaus_dynamic::Schema::load(&[concat!(env!("CARGO_MANIFEST_DIR"), "/vendor/acme.yaml")])
            .unwrap_or_else(|e| panic!("{e}"));
    let own: Vec<&str> = schema
        .messages()
        .filter(|m| m.own)
        .map(|m| m.name)
        .collect();
    assert_eq!(own.len(), MESSAGES.len(), "{own:?}");
    let inner = QueryTanks { presence_vector: 3 };
    let header = Header::new(
        QueryTanks::CODE,
        Address::new(1, 1, 200, 1),
        Address::new(2, 1, 40, 1),
    );
    let telemetry = ReportTankTelemetry {
        tank: 2,
        level: 37.5,
        ..Default::default()
    };
    let samples = vec![
        Message::ReportTanks(sample()),
        Message::ReportTanks(ReportTanks {
            vehicle: "x".into(),
            ..sample()
        }),
        Message::QueryTanks(inner.clone()),
        Message::ReplayTanks(ReplayTanks {
            wrapped_code: QueryTanks::CODE.0,
            wrapped: inner.to_bytes().unwrap(),
            packet: Packet::new(header, inner.to_bytes().unwrap()),
            tail: vec![9, 9],
        }),
        Message::SetTankValve(SetTankValve { tank: 1, open: 1 }),
        Message::ReportTankTelemetry(telemetry),
    ];
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut damaged = 0;
    for m in samples {
        let bytes = m.to_bytes().unwrap();
        // What the generated decoder gives (scaled values as received).
        let json = serde_json::to_value(Message::decode(m.code(), &bytes).unwrap()).unwrap();
        let d = schema
            .decode(m.code(), &bytes)
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            serde_json::to_value(&d.fields).unwrap(),
            json["fields"],
            "{}",
            m.name()
        );
        let from_json = schema.from_json(m.name(), &json["fields"]).unwrap();
        assert_eq!(schema.encode(&from_json).unwrap(), bytes, "{}", m.name());
        // Damaged copies: the same verdict, the same value.
        for _ in 0..400 {
            let mut b = bytes.clone();
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            if b.is_empty() || seed.is_multiple_of(5) {
                b.push(seed as u8);
            } else if seed % 5 == 1 {
                b.truncate((seed >> 8) as usize % b.len());
            } else {
                let i = (seed >> 8) as usize % b.len();
                b[i] = (seed >> 32) as u8;
            }
            match (Message::decode(m.code(), &b), schema.decode(m.code(), &b)) {
                (Ok(g), Ok(d)) => {
                    let gj = serde_json::to_value(&g).unwrap();
                    assert_eq!(serde_json::to_value(&d.fields).unwrap(), gj["fields"]);
                    assert_eq!(schema.encode(&d).ok(), g.to_bytes().ok());
                }
                (Err(g), Err(d)) => assert_eq!(g.kind(), d.kind(), "{g} / {d}"),
                (g, d) => panic!(
                    "{} {}: generated {:?}, run-time {:?}",
                    m.name(),
                    jaus::hex::encode(&b),
                    g.map(|_| ()),
                    d.map(|_| ())
                ),
            }
            damaged += 1;
        }
    }
    assert_eq!(damaged, 2400);
}

/// The stock CLI with the overlay given at run time: `encode`, `decode`, `messages`.
#[test]
fn the_cli_speaks_the_vendor_messages_with_spec() {
    let spec = concat!(env!("CARGO_MANIFEST_DIR"), "/vendor/acme.yaml");
    let run = |args: &[&str], stdin: &str| {
        use std::io::Write;
        let mut child = std::process::Command::new(common::jaus_bin())
            .args(args)
            .stdin(std::process::Stdio::piped())
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        child
            .stdin
            .take()
            .unwrap()
            .write_all(stdin.as_bytes())
            .unwrap();
        let out = child.wait_with_output().unwrap();
        (
            out.status.success(),
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    // The generated crate's packet and JSON line.
    let m = Message::ReportTanks(sample());
    let header = Header::new(
        m.code(),
        Address::new(1, 1, 200, 1),
        Address::new(2, 1, 40, 1),
    );
    let packet = Packet::new(header, m.to_bytes().unwrap());
    let hex = jaus::hex::encode(&packet.to_bytes().unwrap());
    let typed = Message::decode(m.code(), &packet.body).unwrap();
    let expected = serde_json::json!({
        "header": serde_json::to_value(packet.header).unwrap(),
        "message": "ReportTanks",
        "fields": serde_json::to_value(&typed).unwrap()["fields"],
    });
    // decode: by name, as the generated crate prints it.
    let (ok, out, err) = run(&["decode", "--spec", spec], &format!("{hex}\n"));
    assert!(ok, "{err}");
    assert!(out.starts_with(r#"{"header":{"#), "{out}");
    let line: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(line, expected);
    // encode: that line back to the same bytes.
    let (ok, back, err) = run(&["encode", "--spec", spec], &out);
    assert!(ok, "{err}");
    assert_eq!(back.trim(), hex);
    // Without the overlay the CLI prints the message raw.
    let (ok, raw, _) = run(&["decode"], &format!("{hex}\n"));
    assert!(ok && raw.contains(r#""message":"Raw""#), "{raw}");
    // A bad value names the message and the field path.
    let (ok, _, err) = run(
        &["encode", "--spec", spec],
        r#"{"header":{"destination":[1,1,1,1],"source":[2,1,40,1]},"message":"ReportTanks","fields":{"vehicle":"v","tanks":[{"kind":"Lava","level":1.0,"flags":{"low":false,"leaking":false,"sensor_id":0}}]}}"#,
    );
    assert!(!ok);
    assert!(
        err.contains("ReportTanks.tanks[0].kind: unknown value `Lava`, expected one of Fuel, Water, Hydraulic"),
        "{err}"
    );
    // messages: the overlay's own listed; one described with its fields.
    let (ok, list, _) = run(&["messages", "--spec", spec], "");
    assert!(
        ok && list.contains("0xF100") && list.contains("ReportTanks (--spec)"),
        "{list}"
    );
    let (ok, one, err) = run(&["messages", "ReportTanks", "--spec", spec], "");
    assert!(
        ok && one.contains("readings") && one.contains("acme.yaml"),
        "{one}{err}"
    );
    // A broken overlay: the file and line.
    let dir = std::env::temp_dir().join(format!("jaus-spec-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.yaml");
    std::fs::write(&bad, "group: bad\nmessages:\n  - name: X\n    code: 0xD000\n    fields:\n      - { name: a, type: NoSuchType }\n").unwrap();
    let (ok, _, err) = run(&["decode", "--spec", bad.to_str().unwrap()], "");
    assert!(
        !ok && err.contains("bad.yaml:6") && err.contains("NoSuchType"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
