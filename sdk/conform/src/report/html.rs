//! One HTML page per run: a contents list with each component's counts, then per
//! component a table of its checks (id, rule, level, verdict, detail), each with the
//! messages exchanged in a `<details>` and an anchor `v-<address>-<check id>` (the
//! check and rule ids are the catalogue's, [`crate::catalogue`]); a filter shows every
//! check, those that did not pass, or the required failures only.
//!
//! Everything printed is escaped: identification texts and field values come from the
//! network. As a second wall, the page's Content-Security-Policy loads nothing and runs
//! only its own script (by a nonce drawn for the page), so markup that escaped the
//! escaping could still not run.

use std::fmt::Write;

use super::escape;
use crate::check::{Level, Verdict};
use crate::engine::RunReport;

const STYLE: &str =
    "body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse;width:100%}\
td,th{border:1px solid #ccc;padding:4px;vertical-align:top;text-align:left}\
.pass{background:#e6f4e6}.fail{background:#fbe3e3}.inconclusive{background:#f6f1dc}\
pre{margin:0;font-size:85%;white-space:pre-wrap}\
body.only-failed tr.pass,body.only-required tr.check:not(.required-failure){display:none}\
#filter{position:sticky;top:0;background:#fff;padding:.4em 0}";

/// The filter: the body's class says which rows show.
const SCRIPT: &str = "for(const r of document.querySelectorAll('#filter input')){\
r.addEventListener('change',()=>{document.body.className=r.value;});}";

/// A fresh value for the page's script nonce (the standard library's per-process
/// random hash keys, mixed with the time).
fn nonce() -> String {
    use std::hash::{BuildHasher, Hasher};
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u128(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos()),
    );
    format!("{:016x}", h.finish())
}

/// The run as one HTML page.
pub fn html(run: &RunReport) -> String {
    let mut s = String::new();
    let nonce = nonce();
    let _ = write!(
        s,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; style-src 'unsafe-inline'; script-src 'nonce-{nonce}'\">\
<title>{}</title><style>{STYLE}</style></head><body>\n",
        escape(&format!("{}: {}", run.tool, run.peer))
    );
    let _ = writeln!(
        s,
        "<h1>{}</h1><p>Peer {}: {} components, {} checks: <strong>{}</strong></p>",
        escape(&run.tool),
        escape(&run.peer),
        run.components.len(),
        run.checks(),
        if run.passed() {
            "conforms"
        } else {
            "does not conform"
        }
    );
    s.push_str("<p id=\"filter\">Show: \
<label><input type=\"radio\" name=\"show\" value=\"\" checked> every check</label> \
<label><input type=\"radio\" name=\"show\" value=\"only-failed\"> checks that did not pass</label> \
<label><input type=\"radio\" name=\"show\" value=\"only-required\"> required failures</label></p>\n<ul id=\"contents\">\n");
    for c in &run.components {
        let _ = writeln!(
            s,
            "<li><a href=\"#c-{}\">{} {}</a>: {} checks, {} fail ({} required)</li>",
            escape(&c.address),
            escape(&c.address),
            escape(c.component_type.as_deref().unwrap_or("unknown type")),
            c.outcomes.len(),
            c.count(Verdict::Fail),
            c.required_failures()
        );
    }
    s.push_str("</ul>\n");
    for c in &run.components {
        let _ = writeln!(
            s,
            "<h2 id=\"c-{}\">{} {} <small>{}</small></h2><p>{} checks: {} pass, {} fail ({} required), {} inconclusive</p>",
            escape(&c.address),
            escape(&c.address),
            escape(c.component_type.as_deref().unwrap_or("unknown type")),
            escape(c.identification.as_deref().unwrap_or("no identification")),
            c.outcomes.len(),
            c.count(Verdict::Pass),
            c.count(Verdict::Fail),
            c.required_failures(),
            c.count(Verdict::Inconclusive)
        );
        s.push_str("<table><tr><th>Check</th><th>Rule</th><th>Level</th><th>Verdict</th><th>Detail and messages</th></tr>\n");
        for o in &c.outcomes {
            // Each verdict can be linked to; its check and rule ids are those of the
            // catalogue (`jaus conform --list`, docs/conformance.md's `check-<id>` and
            // `rule-<id>` anchors).
            let anchor = escape(&format!("v-{}-{}", c.address, o.check.id).replace(' ', "_"));
            let verdict = match o.verdict {
                Verdict::Pass => "pass",
                Verdict::Fail => "fail",
                Verdict::Inconclusive => "inconclusive",
            };
            let _ = write!(
                s,
                "<tr id=\"{anchor}\" class=\"check {verdict}{}\"><td><a href=\"#{anchor}\">{}</a><br><small>{}</small></td><td><code>{}</code>: {}<br><small>{}</small></td><td>{}</td><td>{verdict}</td><td>{}<details><summary>{} messages</summary><pre>",
                if o.is_required_failure() {
                    " required-failure"
                } else {
                    ""
                },
                escape(&o.check.id),
                escape(&o.check.title),
                escape(o.check.rule.id),
                escape(o.check.rule.text),
                escape(o.check.rule.source),
                match o.check.level {
                    Level::Required => "required",
                    Level::Advisory => "advisory",
                },
                escape(&o.detail),
                o.evidence.len()
            );
            for e in &o.evidence {
                let _ = writeln!(
                    s,
                    "{}",
                    escape(&format!(
                        "{:9.3} ms {:8} {} → {} {} {}",
                        e.t_ms, e.dir, e.from, e.to, e.message, e.fields
                    ))
                );
            }
            s.push_str("</pre></details></td></tr>\n");
        }
        s.push_str("</table>\n");
    }
    let _ = write!(
        s,
        "<script nonce=\"{nonce}\">{SCRIPT}</script>\n</body></html>\n"
    );
    s
}
