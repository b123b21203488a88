//! The `jaus` command-line tool, run as a process: `decode`, `encode` and `messages`.
//!
//! The binary belongs to the `jaus-cli` package, so `CARGO_BIN_EXE_jaus` is not available
//! here. It is found next to this test's executable (`<target>/<profile>/jaus`, the test
//! runs from `<target>/<profile>/deps/`) after one `cargo build -p jaus --bin jaus`,
//! which is a quick no-op when the binary is up to date and keeps it from going stale.
//! `JAUS_BIN` overrides the path (and skips the build).

mod common;

use common::jaus_bin;
use serde_json::Value;
use std::io::Write;
use std::path::Path;
use std::process::{Command, Output, Stdio};

/// Runs `jaus <args>` with `stdin` as its standard input.
fn run(args: &[&str], stdin: &str) -> Output {
    let mut child = Command::new(jaus_bin())
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start jaus");
    let mut input = child.stdin.take().expect("stdin");
    let text = stdin.to_string();
    // Write from another thread so a full stdout pipe cannot block us.
    let writer = std::thread::spawn(move || {
        input.write_all(text.as_bytes()).expect("write stdin");
    });
    let out = child.wait_with_output().expect("wait for jaus");
    writer.join().expect("stdin writer");
    out
}

fn lines(bytes: &[u8]) -> Vec<String> {
    String::from_utf8(bytes.to_vec())
        .expect("UTF-8 output")
        .lines()
        .map(str::to_string)
        .collect()
}

/// `(command code, hex)` of every reference vector, in file order.
fn vector_hex() -> Vec<(u16, String)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/openjaus33.jsonl");
    std::fs::read_to_string(path)
        .expect("vectors present")
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Value = serde_json::from_str(l).expect("vector is JSON");
            let code = v["header"]["command_code"].as_u64().expect("command code") as u16;
            (code, v["hex"].as_str().expect("hex").to_string())
        })
        .collect()
}

/// The command codes `jaus messages` lists.
fn listed_codes() -> Vec<u16> {
    let out = run(&["messages"], "");
    assert!(out.status.success());
    lines(&out.stdout)
        .iter()
        .filter_map(|l| l.strip_prefix("0x"))
        .map(|l| u16::from_str_radix(&l[..4], 16).expect("hex code"))
        .collect()
}

/// The `N` of a `line N: ...` error.
fn error_line_number(e: &str) -> usize {
    let rest = e
        .strip_prefix("line ")
        .unwrap_or_else(|| panic!("error without line number: {e}"));
    rest.split(':')
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|_| panic!("bad line number in {e}"))
}

#[test]
fn decode_then_encode_reproduces_every_known_vector() {
    let vectors = vector_hex();
    let input: String = vectors.iter().map(|(_, h)| format!("{h}\n")).collect();
    let decoded = run(&["decode"], &input);
    let json = lines(&decoded.stdout);
    let errors = lines(&decoded.stderr);

    // Vectors of groups not defined yet are rejected for their command code only, and no
    // listed message is among them.
    let listed = listed_codes();
    let mut rejected = vec![false; vectors.len()];
    for e in &errors {
        let n = error_line_number(e);
        let (code, _) = vectors[n - 1];
        assert!(
            e.contains(&format!("unknown command code 0x{code:04X}")),
            "vector on line {n} (code 0x{code:04X}) failed for another reason: {e}"
        );
        assert!(
            !listed.contains(&code),
            "`jaus messages` lists 0x{code:04X} but decode rejects it: {e}"
        );
        rejected[n - 1] = true;
    }
    assert_eq!(decoded.status.success(), errors.is_empty());
    let accepted: Vec<&(u16, String)> = vectors
        .iter()
        .zip(&rejected)
        .filter(|(_, r)| !**r)
        .map(|(v, _)| v)
        .collect();
    assert_eq!(
        json.len(),
        accepted.len(),
        "one JSON line per accepted vector"
    );
    assert!(
        json.len() == vectors.len(),
        "only {} of {} vectors decode",
        json.len(),
        vectors.len()
    );

    for (line, (code, _)) in json.iter().zip(&accepted) {
        let v: Value = serde_json::from_str(line).expect("decode prints JSON");
        assert_eq!(
            v["header"]["command_code"].as_u64(),
            Some(u64::from(*code)),
            "{line}"
        );
        assert!(
            v["message"].is_string() && v["fields"].is_object(),
            "{line}"
        );
    }

    let encoded = run(&["encode"], &(json.join("\n") + "\n"));
    assert_eq!(lines(&encoded.stderr), Vec::<String>::new());
    assert!(encoded.status.success());
    let hex = lines(&encoded.stdout);
    assert_eq!(hex.len(), accepted.len());
    let differing: Vec<String> = hex
        .iter()
        .zip(&accepted)
        .zip(&json)
        .filter(|((got, (_, want)), _)| got.as_str() != want.as_str())
        .map(|((got, (_, want)), json)| format!("  in   {want}\n  out  {got}\n  json {json}"))
        .collect();
    assert!(
        differing.is_empty(),
        "{} of {} packets re-encode to different bytes after decode | encode:\n{}",
        differing.len(),
        accepted.len(),
        differing.join("\n")
    );
}

/// A packet of `ReportGlobalPose` with every field present (OpenJAUS vector).
const POSE: &str =
    "02020244f028877624eb7b0b1e001a60ff0175fc208189cd377cf6167a1077e4f38fa5e490ddaf42fff4e5ec1ded";
/// A `SetDataLinkSelect` packet (one body byte).
const SELECT: &str = "9f020102cd2c3f560b256bff010019e4b7";

#[test]
fn malformed_lines_are_reported_one_each_and_good_lines_still_decode() {
    let select = jaus::hex::decode(SELECT).unwrap();
    let pose = jaus::hex::decode(POSE).unwrap();

    // An unknown (experimental, undefined) command code with a consistent header.
    let mut unknown = select.clone();
    unknown[2..4].copy_from_slice(&0xD123u16.to_le_bytes());
    // The body of a known message cut short, with a header that agrees with it.
    let mut short_body = pose[..16 + 9].to_vec();
    short_body[12] = 9;
    short_body[13] &= 0xF0;

    let input = [
        SELECT.to_string(),                // 1 ok
        POSE[..10].to_string(),            // 2 truncated header (5 bytes)
        format!("{SELECT}00"),             // 3 data size mismatch
        jaus::hex::encode(&unknown),       // 4 unknown command code: printed raw
        jaus::hex::encode(&short_body),    // 5 truncated body
        POSE.to_string(),                  // 6 ok
        format!("zz{}", &SELECT[2..]),     // 7 bad hex digit
        SELECT[..SELECT.len() - 1].into(), // 8 odd number of digits
        String::new(),                     // 9 blank: skipped, no output
        POSE.to_uppercase(),               // 10 ok (upper case hex)
    ];
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("jaus-cli-malformed.txt");
    std::fs::write(&path, input.join("\n") + "\n").unwrap();
    let file = std::fs::File::open(&path).unwrap();
    let out = Command::new(jaus_bin())
        .arg("decode")
        .stdin(file)
        .output()
        .expect("run jaus decode");

    assert_eq!(
        out.status.code(),
        Some(1),
        "a malformed line makes the exit status 1"
    );
    let errors = lines(&out.stderr);
    let expected: &[(usize, &[&str])] = &[
        (2, &["truncated header", "5 byte"]),
        (3, &["data size", "header says 1", "2 follow"]),
        (5, &["ReportGlobalPose", "truncated", "longitude"]),
        (7, &["bad hex", "invalid hex digit"]),
        (8, &["bad hex", "odd number of hex digits"]),
    ];
    assert_eq!(
        errors.len(),
        expected.len(),
        "one error line per bad line: {errors:#?}"
    );
    for (e, (n, words)) in errors.iter().zip(expected) {
        assert!(
            e.starts_with(&format!("line {n}: ")),
            "expected an error for line {n}: {e}"
        );
        for w in *words {
            assert!(
                e.contains(w),
                "error for line {n} should mention {w:?}: {e}"
            );
        }
    }
    assert!(
        !errors[2].contains("header"),
        "a short body is not a header problem: {}",
        errors[2]
    );

    let json = lines(&out.stdout);
    let names: Vec<String> = json
        .iter()
        .map(|l| {
            serde_json::from_str::<Value>(l).unwrap()["message"]
                .as_str()
                .unwrap()
                .to_string()
        })
        .collect();
    assert_eq!(
        names,
        [
            "SetDataLinkSelect",
            "Raw",
            "ReportGlobalPose",
            "ReportGlobalPose"
        ]
    );
    assert_eq!(json[2], json[3], "hex case does not matter");
    // A message this set does not define is kept as its code and body, and encodes
    // back to the same bytes.
    let raw: Value = serde_json::from_str(&json[1]).unwrap();
    assert_eq!(raw["fields"]["code"], 0xD123);
    let back = run(&["encode"], &format!("{}\n", json[1]));
    assert_eq!(
        lines(&back.stdout),
        [jaus::hex::encode(&unknown)],
        "{}",
        String::from_utf8_lossy(&back.stderr)
    );
}

#[test]
fn decode_takes_packets_as_arguments() {
    let out = run(&["decode", SELECT, "0602", POSE], "");
    assert_eq!(out.status.code(), Some(1));
    let errors = lines(&out.stderr);
    assert_eq!(errors.len(), 1, "{errors:?}");
    assert!(
        errors[0].starts_with("line 2: ") && errors[0].contains("truncated header"),
        "{}",
        errors[0]
    );
    assert_eq!(lines(&out.stdout).len(), 2);

    let ok = run(&["decode", POSE], "");
    assert!(ok.status.success());
    assert!(ok.stderr.is_empty());
}

/// `messages --json`: one JSON line per message, with its class; an unknown group is an
/// error (exit 1) listing the groups.
#[test]
fn messages_as_json_and_unknown_groups() {
    let out = run(&["messages", "--json"], "");
    assert!(out.status.success());
    let rows: Vec<serde_json::Value> = lines(&out.stdout)
        .iter()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(rows.len(), jaus::messages::MESSAGES.len());
    let pose = rows
        .iter()
        .find(|r| r["name"] == "QueryGlobalPose")
        .unwrap();
    assert_eq!(pose["code"], 0x2402);
    assert_eq!(pose["class"], "Query");
    assert_eq!(pose["report"], "ReportGlobalPose");
    assert_eq!(pose["group"], "platform");
    let core = run(&["messages", "--json", "--group", "core"], "");
    assert!(lines(&core.stdout).len() < rows.len());
    let bad = run(&["messages", "--group", "platfrom"], "");
    assert_eq!(bad.status.code(), Some(1));
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(
        err.contains("no message group `platfrom`") && err.contains("platform"),
        "{err}"
    );
}

#[test]
fn messages_lists_the_catalogue() {
    let out = run(&["messages"], "");
    assert!(out.status.success());
    let text = lines(&out.stdout);
    let rows: Vec<&String> = text.iter().filter(|l| l.starts_with("0x")).collect();
    assert!(rows.len() >= 90, "only {} messages listed", rows.len());
    assert!(
        rows.iter()
            .any(|r| r.starts_with("0x4402")
                && r.split_whitespace().nth(1) == Some("ReportGlobalPose")),
        "0x4402 ReportGlobalPose missing"
    );
    assert_eq!(
        text.last().map(String::as_str),
        Some(format!("{} messages", rows.len()).as_str())
    );
    // Codes are unique.
    let mut codes: Vec<&str> = rows.iter().map(|r| &r[..6]).collect();
    codes.sort_unstable();
    codes.dedup();
    assert_eq!(codes.len(), rows.len());

    let platform = run(&["messages", "--group", "platform"], "");
    assert!(platform.status.success());
    let prows: Vec<String> = lines(&platform.stdout)
        .into_iter()
        .filter(|l| l.starts_with("0x"))
        .collect();
    assert!(!prows.is_empty() && prows.len() < rows.len());
    assert!(
        prows
            .iter()
            .all(|r| r.split_whitespace().any(|w| w == "platform")),
        "{prows:#?}"
    );
    assert!(prows.iter().any(|r| r.starts_with("0x4402")));
}

#[test]
fn encode_rejects_a_header_code_that_disagrees_with_the_message() {
    let decoded = run(&["decode", POSE], "");
    assert!(decoded.status.success());
    let good = lines(&decoded.stdout).remove(0);
    let mut v: Value = serde_json::from_str(&good).unwrap();
    assert_eq!(v["message"], "ReportGlobalPose");
    v["header"]["command_code"] = Value::from(0x4403);
    let bad = v.to_string();

    let out = run(&["encode"], &format!("{bad}\n{good}\n{{not json\n"));
    assert_eq!(out.status.code(), Some(1));
    let errors = lines(&out.stderr);
    assert_eq!(errors.len(), 2, "{errors:?}");
    assert!(errors[0].starts_with("line 1: "), "{}", errors[0]);
    assert!(
        errors[0].contains("command code") && errors[0].contains("ReportGlobalPose"),
        "{}",
        errors[0]
    );
    assert!(
        errors[1].starts_with("line 3: ") && errors[1].contains("bad JSON"),
        "{}",
        errors[1]
    );
    // The good line is still encoded, to the original bytes.
    assert_eq!(lines(&out.stdout), [POSE]);
}

/// Issue 19: `jaus messages NAME` prints the fields (type, unit, range, bit) and an
/// example line that `encode`/`send` accept; a mistyped name gets suggestions and exit 1.
#[test]
fn messages_describes_one_message_with_an_example_that_parses() {
    let out = run(&["messages", "ReportGlobalPose"], "");
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    for needle in [
        "0x4402",
        "latitude",
        "scaled i32",
        "deg",
        "[-90, 90]",
        "presence vector: u16",
    ] {
        assert!(text.contains(needle), "{needle} missing:\n{text}");
    }
    let example = text
        .lines()
        .skip_while(|l| !l.starts_with("example"))
        .nth(1)
        .expect("example line")
        .trim();
    let parsed = jaus_client::parse_message(example).expect("the example parses");
    assert_eq!(parsed.1.name(), "ReportGlobalPose");
    // Issue 37: the definition's file by name and line, never the build machine's path.
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with("defined in"))
        .expect("the definition's place");
    let defs = std::fs::read_to_string(jaus_spec::defs_dir().join("platform.yaml")).unwrap();
    let at = defs
        .lines()
        .position(|l| l.trim() == "- name: ReportGlobalPose")
        .unwrap()
        + 1;
    assert_eq!(
        line.trim(),
        format!("defined in platform.yaml:{at} (the SDK's definitions)")
    );
    assert!(!text.contains(env!("CARGO_MANIFEST_DIR")), "{text}");
    let bad = run(&["messages", "ReportGlobalPos"], "");
    assert!(!bad.status.success());
    let err = String::from_utf8_lossy(&bad.stderr);
    assert!(err.contains("did you mean ReportGlobalPose"), "{err}");
}

/// Issue 19: `"fields"` may be left out for a message without fields, and a whole
/// packet line as `decode` prints it is accepted with its destination.
#[test]
fn messages_parse_without_fields_and_from_decode_lines() {
    let (to, m) = jaus_client::parse_message(r#"{"message":"QueryHeartbeatPulse"}"#).unwrap();
    assert_eq!((to, m.name()), (None, "QueryHeartbeatPulse"));
    let decoded = jaus::json::decode_line(jaus::json::REFERENCE_PACKETS[0].1).unwrap();
    let (to, m) = jaus_client::parse_message(&decoded).unwrap();
    assert_eq!(to, Some(jaus::Address::new(1, 2, 3, 4)));
    assert_eq!(m.name(), "ReportGlobalPose");
}

/// Issue 19, defect 3: the default socket is port 3794 on a loopback address other
/// than the peer's (JUDP peers answer port 3794 of the sender's address).
#[test]
fn the_default_socket_is_port_3794_on_an_address_of_its_own() {
    let peer: std::net::SocketAddr = "127.0.0.1:3794".parse().unwrap();
    let s = jaus_client::bind_socket(None, &[peer]).unwrap();
    let local = s.local_addr().unwrap();
    assert_eq!(local.port(), 3794);
    assert_ne!(local.ip(), peer.ip());
    assert!(local.ip().is_loopback());
}

/// `jaus wireshark` writes the dissector of the definitions built into the binary, both
/// generations: every RA 3.3 and every AS-4 message in its table, the embedded messages
/// marked; a vendor's AS-4 directory adds its messages, and a bad one is an error naming
/// the option.
#[test]
fn jaus_wireshark_writes_the_dissector_of_both_generations() {
    let dir = std::env::temp_dir().join(format!("jaus-cli-wireshark-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let vendor = dir.join("vendor");
    std::fs::create_dir_all(&vendor).unwrap();
    std::fs::write(
        vendor.join("acme.yaml"),
        "group: acme\nmessages:\n  - name: ReportAcmeBattery\n    code: 0xD401\n    fields:\n      - { name: percent, type: u8, unit: \"%\", description: \"Charge.\" }\n",
    )
    .unwrap();
    let lua = dir.join("jaus.lua");
    let out = run(
        &[
            "wireshark",
            "--out",
            lua.to_str().unwrap(),
            "--as4-spec",
            vendor.to_str().unwrap(),
        ],
        "",
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let said = String::from_utf8_lossy(&out.stdout);
    // jaus-as4's messages and the vendor's one.
    let as4 = format!("AS-4 {} messages", jaus_as4::MESSAGES.len() + 1);
    assert!(said.contains(&as4), "{said}");
    let text = std::fs::read_to_string(&lua).unwrap();
    let as4 = &text[text.find("\nAS4_MESSAGES = {").unwrap()..];
    assert!(as4.contains("[0xD401] = { name = \"ReportAcmeBattery\""));
    assert!(as4.contains("name = \"report_message\"") && as4.contains("embeds = true"));
    assert!(text.contains("\nMESSAGES = {\n  [0x0001] = { name = \"SetComponentAuthority\""));

    let bad = dir.join("bad");
    std::fs::create_dir_all(&bad).unwrap();
    std::fs::write(
        bad.join("bad.yaml"),
        "group: acme\nmessages:\n  - name: x\n",
    )
    .unwrap();
    let out = run(
        &[
            "wireshark",
            "--out",
            lua.to_str().unwrap(),
            "--as4-spec",
            bad.to_str().unwrap(),
        ],
        "",
    );
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--as4-spec") && err.contains("bad.yaml"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn jaus_ros2_runs_the_bridge_and_reports_a_silent_robot() {
    // No ROS 2 robot on this DDS domain: after the watchdog time (500 ms) the bridge
    // says so, holds its commands at zero (zero twists published) and prints its
    // counters when it stops.
    let port = common::free_port();
    let out = Command::new(jaus_bin())
        .args(["ros2", "--seconds", "1.5", "--domain", "111"])
        .arg("--bind")
        .arg(format!("127.0.0.1:{port}"))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{l}: {e}")))
        .collect();
    assert!(lines.iter().any(|l| l["event"] == "ros_silent"), "{text}");
    let stats = &lines.last().expect("a stats line")["stats"];
    assert_eq!(stats["odom"], 0, "{text}");
    assert!(stats["published_zero"].as_u64().unwrap_or(0) >= 1, "{text}");
}
