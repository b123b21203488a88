//! The generated Wireshark dissector (issue 15 item 1) run by tshark over captures:
//! every OpenJAUS reference vector wrapped in JUDP (and some in "JAUS01.0"), and a
//! multi-packet message. Every packet must dissect without a malformed-packet or Lua
//! error, and every scalar field of the message's top level must show the value
//! `jaus decode` gives (`jaus_tests::tshark`). And the times of a capture we write, as
//! tshark and capinfos read them (issue 47 item 2).

use std::net::SocketAddr;
use std::path::Path;
use std::time::Duration;

use jaus::codec::Encode;
use jaus::net::framing::{split, Framing};
use jaus::wire::Header;
use jaus::JausMessage;
use jaus_client::capture::CaptureWriter;
use jaus_tests::tshark;
use serde_json::Value;

#[path = "common/values.rs"]
mod values;

fn judp(packet: &[u8]) -> Vec<u8> {
    Framing::Judp.encode(packet)
}

/// The hex of every reference vector, in file order.
fn vectors() -> Vec<String> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/openjaus33.jsonl");
    std::fs::read_to_string(path)
        .expect("vectors present")
        .lines()
        .map(|l| {
            let v: Value = serde_json::from_str(l).unwrap();
            v["hex"].as_str().unwrap().to_string()
        })
        .collect()
}

#[test]
fn the_generated_dissector_shows_every_reference_vector_as_jaus_decode_does() {
    if !tshark::available() {
        return;
    }
    let dir = std::env::temp_dir().join(format!("jaus-wireshark-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).unwrap();
    let lua = dir.join("jaus.lua");
    std::fs::write(&lua, jaus_gen::wireshark::dissector(&spec)).unwrap();

    let vectors = vectors();
    let pcap = dir.join("vectors.pcapng");
    let mut w = CaptureWriter::create(&pcap).unwrap();
    let a: SocketAddr = "127.0.0.1:3794".parse().unwrap();
    let b: SocketAddr = "127.0.0.2:3794".parse().unwrap();
    let mut expected = Vec::new();
    for (i, v) in vectors.iter().enumerate() {
        let packet = jaus::hex::decode(v).unwrap();
        // Every tenth in the "JAUS01.0" framing, the rest in JUDP.
        let datagram = if i % 10 == 0 {
            [b"JAUS01.0".as_slice(), &packet].concat()
        } else {
            judp(&packet)
        };
        w.write(Duration::from_millis(1000 + i as u64), a, b, &datagram)
            .unwrap();
        let json: Value = serde_json::from_str(&jaus::json::decode_line(v).unwrap()).unwrap();
        expected.push(Some(json));
    }
    // A multi-packet message: a Report VKS Feature Class Metadata of 9,000 bytes.
    let big = jaus::messages::ReportVksFeatureClassMetadata {
        feature_class_id: 7,
        metadata: format!("class 7: {}", "x".repeat(9000)),
    };
    let body = big.to_bytes().unwrap();
    assert!(body.len() > 4080);
    let header = Header::new(
        jaus::messages::ReportVksFeatureClassMetadata::CODE,
        jaus::Address::new(1, 2, 3, 4),
        jaus::Address::new(5, 6, 61, 1),
    );
    let parts = split(&header, &body).unwrap();
    assert!(parts.len() >= 2);
    for (k, p) in parts.iter().enumerate() {
        w.write(Duration::from_millis(5000 + k as u64), a, b, &judp(p))
            .unwrap();
    }
    w.flush().unwrap();
    drop(w);

    let packets = tshark::dissect(&lua, &pcap);
    assert_eq!(packets.len(), vectors.len() + parts.len());
    let compared = tshark::check(&packets, &expected);
    // The multi-packet message is reassembled on its last part and every element shown.
    let last = packets.last().unwrap();
    let metadata = last
        .iter()
        .find(|f| f.name == "jaus.ReportVksFeatureClassMetadata.metadata")
        .expect("the reassembled body is dissected");
    assert!(metadata.show.starts_with("class 7: xxx"), "{metadata:?}");
    assert!(packets[vectors.len()]
        .iter()
        .all(|f| f.name != "jaus.ReportVksFeatureClassMetadata.metadata"));
    let fields_compared: usize = compared.values().sum();
    println!(
        "{} packets dissected; {fields_compared} fields of {} message types compared with jaus decode",
        packets.len(),
        compared.len()
    );
    assert!(
        compared.len() >= 100,
        "{} message types compared",
        compared.len()
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A capture we write (`jaus node --capture`, `jaus conform --pcap`) has the times it was
/// given for tshark, capinfos and our reader alike: its interface declares nanoseconds.
/// Without the declaration both tools took them for microseconds (a 12.3 s run lasted
/// 12,277 s and began in the year 58877).
#[test]
fn tshark_capinfos_and_our_reader_agree_on_the_times_of_a_capture() {
    if !tshark::available() || !tshark::capinfos_available() {
        return;
    }
    let dir = std::env::temp_dir().join(format!("jaus-capture-times-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("times.pcapng");
    // 2024-01-02 03:04:05.123456789 UTC, then 12.3 s later.
    let t0 = Duration::new(1_704_164_645, 123_456_789);
    let last = t0 + Duration::from_millis(12_300);
    let a: SocketAddr = "127.0.0.1:3794".parse().unwrap();
    let b: SocketAddr = "127.0.0.2:3794".parse().unwrap();
    let mut w = CaptureWriter::create(&path).unwrap();
    w.write(t0, a, b, &judp(&[0; 16])).unwrap();
    w.write(t0 + Duration::from_millis(5_000), b, a, &judp(&[0; 16]))
        .unwrap();
    w.write(last, a, b, &judp(&[0; 16])).unwrap();
    w.flush().unwrap();
    drop(w);

    // Ours.
    let (ours, _) = jaus_client::capture::read(&path).unwrap();
    assert_eq!(
        (ours[0].time, ours[2].time),
        (t0, last),
        "our reader's first and last times"
    );
    let close = |got: Duration, want: Duration, what: &str| {
        let diff = got.abs_diff(want);
        assert!(
            diff <= Duration::from_micros(1),
            "{what}: {got:?}, expected {want:?}"
        );
    };
    // tshark: every packet's time since the epoch.
    let out = std::process::Command::new("tshark")
        .arg("-r")
        .arg(&path)
        .args(["-T", "fields", "-e", "frame.time_epoch"])
        .output()
        .expect("run tshark");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let times: Vec<Duration> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| tshark::epoch_time(l).unwrap_or_else(|| panic!("tshark printed `{l}`")))
        .collect();
    assert_eq!(times.len(), 3);
    close(times[0], t0, "tshark's first packet");
    close(times[2], last, "tshark's last packet");
    // capinfos: the first packet's time and the duration, as seconds (`-S`), in a
    // table of one row without its header (`-T -r`): file name, then the value.
    let capinfos = |flag: &str| {
        let out = std::process::Command::new("capinfos")
            .args(["-T", "-r", "-S", flag])
            .arg(&path)
            .output()
            .expect("run capinfos");
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = String::from_utf8_lossy(&out.stdout).to_string();
        let value = text
            .trim_end()
            .rsplit('\t')
            .next()
            .unwrap_or("")
            .to_string();
        tshark::epoch_time(&value).unwrap_or_else(|| panic!("capinfos {flag} printed `{text}`"))
    };
    close(capinfos("-a"), t0, "capinfos' first packet time");
    close(capinfos("-u"), last - t0, "capinfos' capture duration");
    println!(
        "tshark, capinfos and our reader: first packet {t0:?} after the epoch, {:?} long",
        last - t0
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The AS-4 definitions built into jaus-as4, as a spec.
fn as4_spec() -> jaus_spec::Spec {
    let texts = jaus_as4::DEFS
        .iter()
        .map(|(name, text)| (Path::new("jaus-as4/defs").join(name), text.to_string()))
        .collect();
    jaus_spec::load_texts(texts).expect("the AS-4 definitions load")
}

/// A decoded AS-4 message as `jaus decode` prints it: `{"message": …, "fields": …}`.
fn as4_json(decoded: &jaus_dynamic::Decoded) -> Value {
    struct Line<'a>(&'a jaus_dynamic::Decoded);
    impl serde::Serialize for Line<'_> {
        fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            use serde::ser::SerializeMap;
            let mut map = s.serialize_map(None)?;
            self.0.serialize_entries(&mut map)?;
            map.end()
        }
    }
    serde_json::to_value(Line(decoded)).unwrap()
}

/// Issue 47 item 3: the dissector generated with the AS-4 definitions reads AS5669A
/// (JUDP version 2) and every AS-4 message of them. A capture of random values of every
/// message (a few each, from the definitions: tests/common/values.rs), a datagram
/// packing three messages, an acknowledgement, a message of three packets, an Event
/// carrying a Report Status, a list element holding a Set Travel Speed and one of a
/// user's format: tshark shows none malformed, every top-level scalar field as our
/// decoder has it, and the embedded messages field by field.
#[test]
fn the_generated_dissector_shows_every_as4_message_as_our_decoder_does() {
    use jaus::net::as5669a::{
        split, write_datagrams, AckNak, As4Header, As4Id, As4Packet, MAX_PAYLOAD,
    };
    use proptest::strategy::{Strategy, ValueTree};
    use proptest::test_runner::TestRunner;

    if !tshark::available() {
        return;
    }
    let dir = std::env::temp_dir().join(format!("jaus-wireshark-as4-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let ra33 = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).unwrap();
    let as4 = as4_spec();
    let lua = dir.join("jaus.lua");
    std::fs::write(&lua, jaus_gen::wireshark::dissector_for(&ra33, Some(&as4))).unwrap();
    let schema = jaus_dynamic::Schema::from_spec(&as4);

    let (a, b): (SocketAddr, SocketAddr) = (
        "127.0.0.1:3794".parse().unwrap(),
        "127.0.0.2:3794".parse().unwrap(),
    );
    let (client, vehicle) = (As4Id::new(200, 1, 1), As4Id::new(126, 1, 11));
    let pcap = dir.join("as4.pcapng");
    let mut w = CaptureWriter::create(&pcap).unwrap();
    let mut expected: Vec<Option<Value>> = Vec::new();
    let mut t = 1000u64;
    let mut sequence = 0u16;
    let mut write = |w: &mut CaptureWriter<_>, datagram: &[u8]| {
        t += 1;
        w.write(Duration::from_millis(t), a, b, datagram).unwrap();
    };
    let packet = |payload: Vec<u8>, sequence: u16| As4Packet {
        header: As4Header::new(vehicle, client),
        payload,
        sequence,
    };
    let encode = |name: &str, fields: Value| -> Vec<u8> {
        let m = schema.from_json(name, &fields).unwrap();
        let mut payload = m.code.0.to_le_bytes().to_vec();
        payload.extend(schema.encode(&m).unwrap());
        payload
    };

    // Random values of every message, three of each.
    let mut runner = TestRunner::deterministic();
    let mut messages = 0;
    for m in &as4.messages {
        let strategy = values::record_strategy(&as4, &m.fields, 0);
        let mut done = 0;
        for _ in 0..200 {
            if done == 3 {
                break;
            }
            let fields = strategy.new_tree(&mut runner).unwrap().current();
            let Ok(dm) = schema.from_json(&m.def.name, &fields) else {
                continue;
            };
            // Values contradicting a count or flag kept elsewhere do not encode.
            let Ok(body) = schema.encode(&dm) else {
                continue;
            };
            let mut payload = m.def.code.0.to_le_bytes().to_vec();
            payload.extend_from_slice(&body);
            if payload.len() > MAX_PAYLOAD {
                continue;
            }
            let decoded = schema.fields_json(dm.code, &body).unwrap();
            sequence = sequence.wrapping_add(1);
            let d = write_datagrams(&[packet(payload, sequence)], 4096).unwrap();
            write(&mut w, &d[0]);
            expected.push(Some(as4_json(&decoded)));
            done += 1;
        }
        assert_eq!(done, 3, "{}: no three random values encode", m.def.name);
        messages += 1;
    }
    assert!(messages >= 100, "{messages} AS-4 messages");

    // Three messages in one datagram, and an acknowledgement.
    let three: Vec<As4Packet> = ["QueryStatus", "QueryControl", "QueryIdentification"]
        .iter()
        .enumerate()
        .map(|(i, name)| {
            let fields = if *name == "QueryIdentification" {
                serde_json::json!({ "query_type": "Subsystem" })
            } else {
                serde_json::json!({})
            };
            packet(encode(name, fields), 100 + i as u16)
        })
        .collect();
    let d = write_datagrams(&three, 4096).unwrap();
    assert_eq!(d.len(), 1);
    write(&mut w, &d[0]);
    expected.push(None);
    let mut asked = packet(encode("QueryStatus", serde_json::json!({})), 7);
    asked.header.ack_nak = AckNak::Request;
    let ack = jaus::net::as5669a::ack(&asked);
    write(&mut w, &write_datagrams(&[ack], 4096).unwrap()[0]);
    expected.push(None);

    // An Event carrying a Report Status; list elements holding a message and not.
    let status = encode(
        "ReportStatus",
        serde_json::json!({ "status": "Emergency", "reserved": 0 }),
    );
    let event = encode(
        "Event",
        serde_json::json!({ "event_id": 4, "sequence_number": 9,
            "report_message": jaus::hex::encode(&status) }),
    );
    write(
        &mut w,
        &write_datagrams(&[packet(event, 200)], 4096).unwrap()[0],
    );
    expected.push(None);
    let speed = encode("SetTravelSpeed", serde_json::json!({ "speed": 2.5 }));
    let elements = encode(
        "SetElement",
        serde_json::json!({ "request_id": 1, "elements": [
            { "uid": 1, "previous_uid": 0, "next_uid": 2, "format": "JausMessage",
              "data": jaus::hex::encode(&speed) },
            { "uid": 2, "previous_uid": 1, "next_uid": 0, "format": "UserDefined",
              "data": "ff" }
        ] }),
    );
    write(
        &mut w,
        &write_datagrams(&[packet(elements, 201)], 4096).unwrap()[0],
    );
    expected.push(None);

    // A message of three packets: a Set Element of 20 elements of 500 bytes each.
    let big_elements: Vec<Value> = (1..=20u16)
        .map(|uid| {
            serde_json::json!({ "uid": uid, "previous_uid": uid - 1,
                "next_uid": if uid == 20 { 0 } else { uid + 1 },
                "format": "UserDefined", "data": jaus::hex::encode(&[uid as u8; 500]) })
        })
        .collect();
    let big = encode(
        "SetElement",
        serde_json::json!({ "request_id": 2, "elements": big_elements }),
    );
    let parts = split(&As4Header::new(vehicle, client), &big, 300, MAX_PAYLOAD).unwrap();
    assert_eq!(parts.len(), 3);
    for p in &parts {
        write(
            &mut w,
            &write_datagrams(std::slice::from_ref(p), 4096).unwrap()[0],
        );
        expected.push(None);
    }
    w.flush().unwrap();
    drop(w);

    let packets = tshark::dissect(&lua, &pcap);
    assert_eq!(packets.len(), expected.len());
    let compared = tshark::check_as(&packets, &expected, "jaus4");
    let n = packets.len();
    let shown = |i: usize, name: &str| packets[i].iter().filter(|f| f.name == name).count();
    // The datagram of three messages shows three.
    let three_at = n - 7;
    assert_eq!(
        shown(three_at, "jaus4.message"),
        3,
        "{:?}",
        packets[three_at]
    );
    // The acknowledgement has no message.
    assert_eq!(shown(three_at + 1, "jaus4.message"), 0);
    assert_eq!(shown(three_at + 1, "as5669a.ack_nak"), 1);
    // The Event's report, field by field.
    let event_at = n - 5;
    let status = packets[event_at]
        .iter()
        .find(|f| f.name == "jaus4.ReportStatus.status")
        .expect("the Event's Report Status is dissected");
    assert!(status.showname.contains("Emergency"), "{status:?}");
    // The element holding a message shows it; the user's one does not.
    let set_at = n - 4;
    let speed = packets[set_at]
        .iter()
        .find(|f| f.name == "jaus4.SetTravelSpeed.speed")
        .expect("the element's Set Travel Speed is dissected");
    assert!(
        (speed.show.parse::<f64>().unwrap() - 2.5).abs() < 0.01,
        "{speed:?}"
    );
    assert_eq!(shown(set_at, "jaus4.message"), 1);
    assert_eq!(
        shown(set_at, "jaus4.embedded_message"),
        1,
        "the element holding a message only"
    );
    assert_eq!(shown(event_at, "jaus4.embedded_message"), 1);
    // The three packets: the last shows the whole message, the others none.
    assert_eq!(
        shown(n - 3, "jaus4.message") + shown(n - 2, "jaus4.message"),
        0
    );
    assert_eq!(shown(n - 1, "jaus4.message"), 1);
    assert_eq!(shown(n - 1, "jaus4.SetElement.request_id"), 1);
    let fields_compared: usize = compared.values().sum();
    println!(
        "{} AS-4 datagrams dissected; {fields_compared} fields of {} messages compared with our decoder",
        packets.len(),
        compared.len()
    );
    // Every message with a scalar field at its top level was compared (the others,
    // queries without fields and messages of lists and records only, were dissected).
    let with_scalars: std::collections::BTreeSet<&str> = expected
        .iter()
        .flatten()
        .filter(|j| {
            j["fields"].as_object().is_some_and(|o| {
                o.values()
                    .any(|v| !(v.is_object() || v.is_array() || v.is_null()))
            })
        })
        .filter_map(|j| j["message"].as_str())
        .collect();
    assert_eq!(
        compared
            .keys()
            .map(String::as_str)
            .collect::<std::collections::BTreeSet<_>>(),
        with_scalars,
        "every AS-4 message with a scalar field compared"
    );
    assert!(compared.len() >= 60, "{} messages compared", compared.len());
    std::fs::remove_dir_all(&dir).ok();
}
