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
    let (ours, _) = jaus_cli::capture::read(&path).unwrap();
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
