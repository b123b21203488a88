//! What people read: a terminal summary, JSON, JUnit XML (for CI systems) and one HTML
//! page per run.

mod html;
mod junit;

pub use html::html;
pub use junit::junit;

use std::fmt::Write;

use crate::check::{Level, Verdict};
use crate::engine::RunReport;

/// The run as pretty JSON.
pub fn json(run: &RunReport) -> String {
    serde_json::to_string_pretty(run).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}

/// The terminal summary: per component a count of its checks by verdict and each
/// failure with its detail; last the totals.
pub fn summary(run: &RunReport) -> String {
    let mut s = String::new();
    let (mut pass, mut fail, mut inc, mut req) = (0, 0, 0, 0);
    for c in &run.components {
        let (p, f, i) = (
            c.count(Verdict::Pass),
            c.count(Verdict::Fail),
            c.count(Verdict::Inconclusive),
        );
        pass += p;
        fail += f;
        inc += i;
        req += c.required_failures();
        let _ = writeln!(
            s,
            "{} {} ({}): {} checks: {p} pass, {f} fail ({} required), {i} inconclusive",
            c.address,
            c.component_type.as_deref().unwrap_or("unknown type"),
            c.identification.as_deref().unwrap_or("no identification"),
            c.outcomes.len(),
            c.required_failures(),
        );
        for o in c.outcomes.iter().filter(|o| o.verdict != Verdict::Pass) {
            let _ = writeln!(
                s,
                "  {} {} [{}{}]: {}",
                match o.verdict {
                    Verdict::Fail => "FAIL",
                    _ => "INCONCLUSIVE",
                },
                o.check.id,
                match o.check.level {
                    Level::Required => "required",
                    Level::Advisory => "advisory",
                },
                if o.verdict == Verdict::Fail {
                    format!("; {}", o.check.rule.source)
                } else {
                    String::new()
                },
                o.detail
            );
        }
    }
    if run.tester_dropped > 0 {
        let _ = writeln!(
            s,
            "the tester's inbox was full: {} packets from the target were not kept (checks waiting for them may have failed)",
            run.tester_dropped
        );
    }
    let _ = writeln!(
        s,
        "{} components, {} checks: {pass} pass, {fail} fail ({req} required), {inc} inconclusive: {}",
        run.components.len(),
        run.checks(),
        if run.passed() { "CONFORMS" } else { "DOES NOT CONFORM" }
    );
    s
}

/// `text` with the characters XML and HTML give meaning to escaped.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for ch in text.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            // Control characters XML 1.0 cannot carry.
            c if (c as u32) < 0x20 && !matches!(c, '\n' | '\r' | '\t') => {
                let _ = write!(out, "\u{FFFD}");
            }
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::{Check, Exchange, Kind, Outcome};
    use crate::plan::rules;
    use crate::ComponentReport;

    /// A run whose every text came from a hostile network.
    fn hostile() -> RunReport {
        let evil = "<script>alert('x')</script>&\"";
        RunReport {
            tool: "jaus conform".into(),
            peer: evil.into(),
            components: vec![ComponentReport {
                address: "1.1.33.1".into(),
                component_id: 33,
                component_type: Some("PrimitiveDriver".into()),
                identification: Some(evil.into()),
                outcomes: vec![Outcome {
                    check: Check {
                        id: "core.identification".into(),
                        title: "t".into(),
                        rule: rules::IDENTIFICATION,
                        level: Level::Required,
                        kind: Kind::Identification,
                    },
                    verdict: Verdict::Fail,
                    detail: evil.into(),
                    evidence: vec![Exchange {
                        t_ms: 0.0,
                        dir: "received",
                        from: "1.1.33.1".into(),
                        to: "200.1.40.4".into(),
                        message: "ReportIdentification".into(),
                        fields: serde_json::json!({ "identification": evil }),
                    }],
                }],
            }],
            tester_dropped: 0,
        }
    }

    #[test]
    fn html_and_junit_escape_what_the_network_sent() {
        let run = hostile();
        for page in [html(&run), junit(&run)] {
            assert!(!page.contains("<script>"), "{page}");
            assert!(page.contains("&lt;script&gt;"), "{page}");
        }
        assert_eq!(junit(&run).matches("<failure ").count(), 1);
        assert!(!run.passed());
    }

    #[test]
    fn escape_replaces_markup_and_control_characters() {
        assert_eq!(
            escape("a<b>&\"'\u{1}\n"),
            "a&lt;b&gt;&amp;&quot;&#39;\u{FFFD}\n"
        );
    }
}
