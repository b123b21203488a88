//! The generated Wireshark dissector (issue 15 item 1) run by tshark over captures:
//! every OpenJAUS reference vector wrapped in JUDP (and some in "JAUS01.0"), and a
//! multi-packet message. Every packet must dissect without a malformed-packet or Lua
//! error, and every scalar field of the message's top level must show the value
//! `jaus decode` gives.
//!
//! tshark comes from the distribution (`apt-get install tshark`; `.ci/run` installs
//! it). Without it the test says so and passes, unless `JAUS_REQUIRE_TSHARK=1` (set by
//! CI), where a missing tshark is a failure.

use std::collections::BTreeMap;
use std::net::SocketAddr;
use std::path::Path;
use std::process::Command;
use std::time::Duration;

use jaus::codec::Encode;
use jaus::net::framing::{split, Framing};
use jaus::wire::Header;
use jaus::JausMessage;
use jaus_cli::capture::CaptureWriter;
use serde_json::Value;

/// One field of tshark's PDML output.
#[derive(Debug, Clone)]
struct Shown {
    name: String,
    show: String,
    showname: String,
}

fn tshark_available() -> bool {
    let ok = Command::new("tshark")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        assert!(
            std::env::var("JAUS_REQUIRE_TSHARK").as_deref() != Ok("1"),
            "tshark is required (JAUS_REQUIRE_TSHARK=1) but not installed"
        );
        eprintln!("skipping: tshark is not installed (apt-get install tshark)");
    }
    ok
}

fn attr(tag: &str, name: &str) -> String {
    let key = format!(" {name}=\"");
    let Some(i) = tag.find(&key) else {
        return String::new();
    };
    let rest = &tag[i + key.len()..];
    let raw = &rest[..rest.find('"').unwrap_or(rest.len())];
    raw.replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&")
}

/// Runs tshark with the dissector over `pcap`; the fields of each packet.
fn dissect(lua: &Path, pcap: &Path) -> Vec<Vec<Shown>> {
    let out = Command::new("tshark")
        .arg("-X")
        .arg(format!("lua_script:{}", lua.display()))
        .arg("-r")
        .arg(pcap)
        .args(["-T", "pdml"])
        .output()
        .expect("run tshark");
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !stderr.contains("Lua"),
        "tshark reported a Lua problem: {stderr}"
    );
    let pdml = String::from_utf8(out.stdout).expect("UTF-8");
    pdml.split("<packet>")
        .skip(1)
        .map(|p| {
            p.split("<field ")
                .skip(1)
                .map(|f| {
                    let tag = format!(" {}", &f[..f.find('>').unwrap_or(f.len())]);
                    Shown {
                        name: attr(&tag, "name"),
                        show: attr(&tag, "show"),
                        showname: attr(&tag, "showname"),
                    }
                })
                .collect()
        })
        .collect()
}

/// Whether tshark's `shown` value is the decoded `value`.
fn same(value: &Value, shown: &Shown) -> bool {
    match value {
        Value::Number(n) => {
            let want = n.as_f64().unwrap_or(f64::NAN);
            let got: f64 = shown.show.parse().unwrap_or(f64::NAN);
            // tshark rounds what it prints (15 significant digits for a double, 6 for
            // a float): equal to within the digits shown.
            let mantissa = shown.show.split(['e', 'E']).next().unwrap_or("");
            let digits = mantissa
                .trim_start_matches(['-', '0', '.'])
                .chars()
                .filter(char::is_ascii_digit)
                .count()
                .max(1);
            let tolerance = 10f64.powi(1 - digits as i32) * want.abs().max(1e-300);
            (want - got).abs() <= tolerance || want == got
        }
        // Strings, enum names (`name (value)` in the label) and bytes (hex; tshark puts
        // colons between the bytes).
        Value::String(s) => {
            shown.show == *s
                || shown.showname.contains(&format!(": {s} ("))
                || shown.show.replace(':', "") == *s
        }
        Value::Bool(b) => {
            let t = matches!(shown.show.as_str(), "True" | "1" | "true");
            t == *b
        }
        _ => true,
    }
}

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
    if !tshark_available() {
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
        expected.push(json);
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

    let packets = dissect(&lua, &pcap);
    assert_eq!(packets.len(), vectors.len() + parts.len());
    let mut compared: BTreeMap<String, usize> = BTreeMap::new();
    for (i, (fields, json)) in packets.iter().zip(&expected).enumerate() {
        for f in fields {
            assert!(
                !matches!(
                    f.name.as_str(),
                    "jaus.malformed" | "_ws.malformed" | "_ws.lua.error"
                ) && !f.showname.contains("Malformed")
                    && !f.showname.contains("Lua Error"),
                "packet {i} ({}): {f:?}",
                json["message"]
            );
        }
        let name = json["message"].as_str().unwrap();
        let message = fields
            .iter()
            .find(|f| f.name == "jaus.message")
            .map(|f| f.show.clone());
        assert_eq!(message.as_deref(), Some(name), "packet {i}");
        let Some(obj) = json["fields"].as_object() else {
            continue;
        };
        for (field, value) in obj {
            if value.is_object() || value.is_array() || value.is_null() {
                continue;
            }
            let key = format!("jaus.{name}.{field}");
            let shown = fields
                .iter()
                .find(|f| f.name == key)
                .unwrap_or_else(|| panic!("packet {i}: {key} not shown"));
            assert!(
                same(value, shown),
                "packet {i}: {key} = {value}, tshark shows {shown:?}"
            );
            *compared.entry(name.to_string()).or_default() += 1;
        }
    }
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
