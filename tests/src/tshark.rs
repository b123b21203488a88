//! tshark with the generated dissector (`jaus-gen wireshark`), for the tests that check
//! it against `jaus decode` (tests/wireshark.rs, tests/udp.rs).
//!
//! tshark comes from the distribution (`apt-get install tshark`; `.ci/run` installs it).
//! Without it [`available`] says so and the tests pass, unless `JAUS_REQUIRE_TSHARK=1`
//! (set by CI), where a missing tshark is a failure.

use std::path::Path;
use std::process::Command;

use serde_json::Value;

/// One field of tshark's PDML output.
#[derive(Debug, Clone)]
pub struct Shown {
    /// Field abbreviation (`jaus.ReportGlobalPose.latitude`).
    pub name: String,
    /// The value as shown.
    pub show: String,
    /// The label.
    pub showname: String,
}

/// Whether tshark runs here; without it, a note (and a failure when
/// `JAUS_REQUIRE_TSHARK=1`).
pub fn available() -> bool {
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

/// Whether capinfos (Wireshark's, in the same Debian package set as tshark) runs here;
/// without it, a note (and a failure when `JAUS_REQUIRE_TSHARK=1`).
pub fn capinfos_available() -> bool {
    let ok = Command::new("capinfos")
        .arg("-v")
        .output()
        .is_ok_and(|o| o.status.success());
    if !ok {
        assert!(
            std::env::var("JAUS_REQUIRE_TSHARK").as_deref() != Ok("1"),
            "capinfos is required (JAUS_REQUIRE_TSHARK=1) but not installed"
        );
        eprintln!("skipping: capinfos is not installed (apt-get install tshark)");
    }
    ok
}

/// A time tshark or capinfos prints as seconds since the epoch (`1704164645.123456789`,
/// as many fraction digits as the tool gives).
pub fn epoch_time(text: &str) -> Option<std::time::Duration> {
    let (secs, frac) = text.trim().split_once('.').unwrap_or((text.trim(), ""));
    let digits: String = frac.chars().take(9).collect();
    let nanos: u32 = format!("{digits:0<9}").parse().ok()?;
    Some(std::time::Duration::new(secs.parse().ok()?, nanos))
}

fn attr(tag: &str, name: &str) -> String {
    let key = format!(" {name}=\"");
    let Some(i) = tag.find(&key) else {
        return String::new();
    };
    let rest = &tag[i + key.len()..];
    let raw = &rest[..rest.find('"').unwrap_or(rest.len())];
    unescape(raw)
}

/// XML text with its entities replaced: the five named ones and numeric ones
/// (`&#x27;`, `&#39;`), as tshark writes them.
fn unescape(raw: &str) -> String {
    let mut out = String::with_capacity(raw.len());
    let mut rest = raw;
    while let Some(i) = rest.find('&') {
        out.push_str(&rest[..i]);
        let tail = &rest[i..];
        let Some(end) = tail.find(';') else {
            out.push_str(tail);
            return out;
        };
        let entity = &tail[1..end];
        let c = match entity {
            "quot" => Some('"'),
            "apos" => Some('\''),
            "lt" => Some('<'),
            "gt" => Some('>'),
            "amp" => Some('&'),
            _ => entity
                .strip_prefix("#x")
                .and_then(|h| u32::from_str_radix(h, 16).ok())
                .or_else(|| entity.strip_prefix('#').and_then(|d| d.parse().ok()))
                .and_then(char::from_u32),
        };
        match c {
            Some(c) => out.push(c),
            None => out.push_str(&tail[..=end]),
        }
        rest = &tail[end + 1..];
    }
    out.push_str(rest);
    out
}

/// Runs tshark with the dissector over `pcap`; the fields of each packet.
pub fn dissect(lua: &Path, pcap: &Path) -> Vec<Vec<Shown>> {
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
pub fn same(value: &Value, shown: &Shown) -> bool {
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

/// Checks the packets tshark showed: none malformed or with a Lua error, and for each
/// packet whose decoded JSON (`jaus decode`'s form) is given, its message name and every
/// scalar field of its top level as `jaus decode` has them. Returns the number of fields
/// compared per message name.
pub fn check(
    packets: &[Vec<Shown>],
    decoded: &[Option<Value>],
) -> std::collections::BTreeMap<String, usize> {
    check_as(packets, decoded, "jaus")
}

/// [`check`] for the messages of the protocol whose fields begin with `prefix`
/// (`jaus` for RA 3.3, `jaus4` for AS-4).
pub fn check_as(
    packets: &[Vec<Shown>],
    decoded: &[Option<Value>],
    prefix: &str,
) -> std::collections::BTreeMap<String, usize> {
    let mut compared = std::collections::BTreeMap::new();
    for (i, fields) in packets.iter().enumerate() {
        for f in fields {
            assert!(
                !matches!(
                    f.name.as_str(),
                    "jaus.malformed"
                        | "jaus4.malformed"
                        | "as5669a.malformed"
                        | "_ws.malformed"
                        | "_ws.lua.error"
                ) && !f.showname.contains("Malformed")
                    && !f.showname.contains("Lua Error"),
                "packet {i}: {f:?}"
            );
        }
        let Some(Some(json)) = decoded.get(i) else {
            continue;
        };
        let name = json["message"].as_str().unwrap_or_default();
        let message = fields
            .iter()
            .find(|f| f.name == format!("{prefix}.message"))
            .map(|f| f.show.clone());
        assert_eq!(message.as_deref(), Some(name), "packet {i}");
        let Some(obj) = json["fields"].as_object() else {
            continue;
        };
        for (field, value) in obj {
            if value.is_object() || value.is_array() || value.is_null() {
                continue;
            }
            let key = format!("{prefix}.{name}.{field}");
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
    compared
}
