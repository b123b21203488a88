//! The offline commands of the `jaus` CLI: the message catalogue, `decode`/`encode` of
//! JSON lines, and the tour.

use std::io::Write;

use jaus::json::{decode_line, encode_line, REFERENCE_PACKETS};
use jaus::messages::MESSAGES;

use jaus_client::catalogue::Catalogue;

/// Runs `f` over every non-empty line, printing results to `out` and one error line
/// per failure to `err`. Returns false if any line failed.
pub fn run_lines(
    lines: impl Iterator<Item = String>,
    out: &mut impl Write,
    err: &mut impl Write,
    f: impl Fn(&str) -> Result<String, String>,
) -> bool {
    let mut ok = true;
    for (i, line) in lines.enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        match f(&line) {
            Ok(s) => {
                let _ = writeln!(out, "{s}");
            }
            Err(e) => {
                ok = false;
                let _ = writeln!(err, "line {}: {e}", i + 1);
            }
        }
    }
    ok
}

/// Checks that `group` names a message group (with the closest names when it does not).
pub fn check_group(group: Option<&str>) -> Result<(), String> {
    let Some(g) = group else { return Ok(()) };
    let all = groups();
    if all.contains(&g) {
        return Ok(());
    }
    Err(format!(
        "no message group `{g}` (groups: {})",
        all.join(", ")
    ))
}

/// Prints the message catalogue as a table.
pub fn print_messages(out: &mut impl Write, group: Option<&str>, catalogue: &Catalogue) {
    let _ = writeln!(out, "{:<8} {:<40} {:<22} report", "code", "name", "group");
    let mut n = 0;
    let mut rows: Vec<_> = MESSAGES
        .iter()
        .filter(|m| group.is_none_or(|g| g == m.group))
        .collect();
    rows.sort_by_key(|m| m.code);
    for m in rows {
        n += 1;
        let _ = writeln!(
            out,
            "{:<8} {:<40} {:<22} {}",
            m.code.to_string(),
            if m.experimental {
                format!("{} (experimental)", m.name)
            } else {
                m.name.to_string()
            },
            m.group,
            m.report.unwrap_or("")
        );
    }
    if group.is_none() {
        for (code, name, report) in catalogue.own_messages() {
            n += 1;
            let _ = writeln!(
                out,
                "{:<8} {:<40} {:<22} {}",
                code.to_string(),
                format!("{name} (--spec)"),
                "",
                report.unwrap_or("")
            );
        }
    }
    let _ = writeln!(out, "{n} messages");
}

/// Prints the message catalogue as JSON lines (`jaus messages --json`).
pub fn print_messages_json(out: &mut impl Write, group: Option<&str>, catalogue: &Catalogue) {
    let mut rows: Vec<_> = MESSAGES
        .iter()
        .filter(|m| group.is_none_or(|g| g == m.group))
        .collect();
    rows.sort_by_key(|m| m.code);
    for m in rows {
        let line = serde_json::json!({
            "code": m.code.0,
            "name": m.name,
            "title": m.title,
            "group": m.group,
            "class": format!("{:?}", m.class),
            "report": m.report,
            "experimental": m.experimental,
        });
        let _ = writeln!(out, "{line}");
    }
    if group.is_none() {
        for (code, name, report) in catalogue.own_messages() {
            let line = serde_json::json!({
                "code": code.0,
                "name": name,
                "title": jaus_spec::title_of(name),
                "group": "--spec",
                "class": format!("{:?}", catalogue.class_of(code)),
                "report": report,
                "experimental": true,
            });
            let _ = writeln!(out, "{line}");
        }
    }
}

/// `jaus tour`: decodes the reference packets, shows their JSON, re-encodes them and
/// checks the bytes are identical.
pub fn tour(out: &mut impl Write) -> bool {
    let mut ok = true;
    let _ = writeln!(
        out,
        "JAUS RA 3.3 SDK: {} messages in {} groups\n",
        MESSAGES.len(),
        groups().len()
    );
    for (title, hex) in REFERENCE_PACKETS {
        let _ = writeln!(out, "{title}\n  packet  {hex}");
        match decode_line(hex)
            .map_err(|e| e.to_string())
            .and_then(|json| {
                let back = encode_line(&json).map_err(|e| e.to_string())?;
                Ok((json, back))
            }) {
            Ok((json, back)) => {
                let same = back == *hex;
                ok &= same;
                let _ = writeln!(out, "  decoded {json}");
                let _ = writeln!(
                    out,
                    "  re-encoded identical: {}\n",
                    if same { "yes" } else { "NO" }
                );
            }
            Err(e) => {
                ok = false;
                let _ = writeln!(out, "  error: {e}\n");
            }
        }
    }
    ok
}

fn groups() -> Vec<&'static str> {
    let mut g: Vec<&str> = MESSAGES.iter().map(|m| m.group).collect();
    g.dedup();
    g
}
