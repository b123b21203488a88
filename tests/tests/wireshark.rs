//! The generated Wireshark dissector (issue 15 item 1) run by tshark over captures:
//! every OpenJAUS reference vector wrapped in JUDP (and some in "JAUS01.0"), and a
//! multi-packet message. Every packet must dissect without a malformed-packet or Lua
//! error, and every scalar field of the message's top level must show the value
//! `jaus decode` gives (`jaus_tests::tshark`).

use std::net::SocketAddr;
use std::path::Path;
use std::time::Duration;

use jaus::codec::Encode;
use jaus::net::framing::{split, Framing};
use jaus::wire::Header;
use jaus::JausMessage;
use jaus_cli::capture::CaptureWriter;
use jaus_tests::tshark;
use serde_json::Value;

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
