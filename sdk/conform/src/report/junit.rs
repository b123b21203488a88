//! JUnit XML: a test suite per component, a test case per check. A failed required
//! check is a `<failure>`, a failed advisory check and an inconclusive one are
//! `<skipped>` with the reason, so CI fails only on required checks.

use std::fmt::Write;

use super::escape;
use crate::check::{Level, Verdict};
use crate::engine::RunReport;

/// The run as JUnit XML.
pub fn junit(run: &RunReport) -> String {
    let mut s = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let failures: usize = run.components.iter().map(|c| c.required_failures()).sum();
    let _ = writeln!(
        s,
        "<testsuites name=\"{}\" tests=\"{}\" failures=\"{failures}\">",
        escape(&run.tool),
        run.checks()
    );
    for c in &run.components {
        let name = format!(
            "{} {}",
            c.address,
            c.component_type.as_deref().unwrap_or("unknown")
        );
        let skipped = c
            .outcomes
            .iter()
            .filter(|o| o.verdict != Verdict::Pass && !o.is_required_failure())
            .count();
        let _ = writeln!(
            s,
            "  <testsuite name=\"{}\" tests=\"{}\" failures=\"{}\" skipped=\"{skipped}\">",
            escape(&name),
            c.outcomes.len(),
            c.required_failures()
        );
        for o in &c.outcomes {
            let _ = write!(
                s,
                "    <testcase classname=\"{}\" name=\"{}\">",
                escape(&name),
                escape(&o.check.id)
            );
            let text = format!(
                "{} ({}: {})",
                o.detail, o.check.rule.source, o.check.rule.text
            );
            match (o.verdict, o.check.level) {
                (Verdict::Pass, _) => {}
                (Verdict::Fail, Level::Required) => {
                    let _ = write!(
                        s,
                        "<failure message=\"{}\">{}</failure>",
                        escape(&o.detail),
                        escape(&text)
                    );
                }
                (Verdict::Fail, Level::Advisory) => {
                    let _ = write!(
                        s,
                        "<skipped message=\"advisory check failed: {}\"/>",
                        escape(&o.detail)
                    );
                }
                (Verdict::Inconclusive, _) => {
                    let _ = write!(
                        s,
                        "<skipped message=\"inconclusive: {}\"/>",
                        escape(&o.detail)
                    );
                }
            }
            s.push_str("</testcase>\n");
        }
        s.push_str("  </testsuite>\n");
    }
    s.push_str("</testsuites>\n");
    s
}
