//! One HTML page per run: per component a table of its checks (id, rule, level,
//! verdict, detail), each with the messages exchanged in a `<details>`. Everything
//! printed is escaped: identification texts and field values come from the network.

use std::fmt::Write;

use super::escape;
use crate::check::{Level, Verdict};
use crate::RunReport;

const STYLE: &str =
    "body{font-family:sans-serif;margin:1.5em}table{border-collapse:collapse;width:100%}\
td,th{border:1px solid #ccc;padding:4px;vertical-align:top;text-align:left}\
.pass{background:#e6f4e6}.fail{background:#fbe3e3}.inconclusive{background:#f6f1dc}\
pre{margin:0;font-size:85%;white-space:pre-wrap}";

/// The run as one HTML page.
pub fn html(run: &RunReport) -> String {
    let mut s = String::new();
    let _ = write!(
        s,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{}</title><style>{STYLE}</style></head><body>\n",
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
    for c in &run.components {
        let _ = writeln!(
            s,
            "<h2 id=\"{}\">{} {} <small>{}</small></h2><p>{} checks: {} pass, {} fail ({} required), {} inconclusive</p>",
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
            let verdict = match o.verdict {
                Verdict::Pass => "pass",
                Verdict::Fail => "fail",
                Verdict::Inconclusive => "inconclusive",
            };
            let _ = write!(
                s,
                "<tr class=\"{verdict}\"><td>{}<br><small>{}</small></td><td>{}<br><small>{}</small></td><td>{}</td><td>{verdict}</td><td>{}<details><summary>{} messages</summary><pre>",
                escape(&o.check.id),
                escape(&o.check.title),
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
    s.push_str("</body></html>\n");
    s
}
