//! Every check the tester can run, as data: `jaus conform --list [json]`.
//!
//! The RA 3.3 checks are what [`crate::plan`] plans for each component type of the
//! definitions (a vendor's overlay included), merged by check id with the types each
//! applies to, and the engine's `teardown.as-found`; the AS-4 checks are the IOP
//! judge's ([`crate::as4`]). Each entry carries its id, what it tests, its level and the
//! rule it cites with the rule's source. [`markdown`] renders it as the table of
//! docs/conformance.md (`sdk/conform/tests/docs_table.rs` keeps the two equal).

use jaus_spec::Spec;
use serde::Serialize;

use crate::check::Level;
use crate::selection::Selection;

/// One check of the catalogue.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct Entry {
    /// The check's id (`control.authority_below`, `readback.SetTravelSpeed`).
    pub id: String,
    /// What it tests, in a line.
    pub title: String,
    /// Required or advisory.
    pub level: Level,
    /// The rule it cites (`control.authority`).
    pub rule: &'static str,
    /// Where the rule comes from (`Part 1 §4.3`, `AS5710A`).
    pub source: &'static str,
    /// The rule, in this tool's words.
    pub text: &'static str,
    /// What it runs against: component types by name (`GlobalWaypointDriver`), or
    /// `AS-4 IOP judge`.
    pub applies_to: Vec<String>,
}

/// Every check for the component types of `spec`, then the AS-4 judge's, in the order
/// they first appear.
pub fn catalogue(spec: &Spec) -> Vec<Entry> {
    let mut out: Vec<Entry> = Vec::new();
    for c in &spec.components {
        let name = c.def.name.clone();
        for check in crate::plan::plan(spec, c.def.id) {
            match out.iter_mut().find(|e| e.id == check.id) {
                Some(e) => {
                    if !e.applies_to.contains(&name) {
                        e.applies_to.push(name.clone());
                    }
                }
                None => out.push(Entry {
                    id: check.id,
                    title: check.title,
                    level: check.level,
                    rule: check.rule.id,
                    source: check.rule.source,
                    text: check.rule.text,
                    applies_to: vec![name.clone()],
                }),
            }
        }
    }
    // The engine's clean-up, after the checks it plans, on every component.
    let teardown = crate::ra33::teardown_check();
    out.push(Entry {
        id: teardown.id,
        title: teardown.title,
        level: teardown.level,
        rule: teardown.rule.id,
        source: teardown.rule.source,
        text: teardown.rule.text,
        applies_to: spec.components.iter().map(|c| c.def.name.clone()).collect(),
    });
    for (id, title, rule, level) in crate::as4::CHECKS {
        out.push(Entry {
            id: (*id).to_string(),
            title: (*title).to_string(),
            level: *level,
            rule: rule.id,
            source: rule.source,
            text: rule.text,
            applies_to: vec!["AS-4 IOP judge".into()],
        });
    }
    out
}

/// The catalogue as text: one line per check (id, level, rule and source, title) and
/// what it applies to.
pub fn text(entries: &[Entry]) -> String {
    let mut s = String::new();
    for e in entries {
        let level = match e.level {
            Level::Required => "required",
            Level::Advisory => "advisory",
        };
        s.push_str(&format!(
            "{:<44} {level:<8} {} ({}): {}\n    {}\n    applies to: {}\n",
            e.id,
            e.rule,
            e.source,
            e.title,
            e.text,
            e.applies_to.join(", ")
        ));
    }
    s
}

/// `text` for a Markdown table cell: `|` escaped, lines joined.
fn cell(text: &str) -> String {
    text.replace('|', "\\|").replace('\n', " ")
}

/// The level as the tables print it.
fn level_name(level: Level) -> &'static str {
    match level {
        Level::Required => "required",
        Level::Advisory => "advisory",
    }
}

/// The catalogue of `spec` as Markdown (what docs/conformance.md holds between
/// `<!-- checks:begin -->` and `<!-- checks:end -->`): a count, a table of the checks
/// (id, level, the rule cited, what it runs against, what it tests; each row with an
/// anchor `check-<id>`), then a table of the rules they cite (id, source, the rule in
/// this tool's words; anchors `rule-<id>`).
pub fn markdown(spec: &Spec) -> String {
    let all = catalogue(spec);
    let types = spec.components.len();
    let required = all.iter().filter(|e| e.level == Level::Required).count();
    let mut s = format!(
        "{} checks, {required} of them required, with the SDK's definitions ({types} component \
types). Generated from `jaus_conform::catalogue` (`jaus conform --list`) by \
`sdk/conform/tests/docs_table.rs`: do not edit by hand, run \
`UPDATE_DOCS=1 cargo test -p jaus-conform --test docs_table`.\n\n",
        all.len()
    );
    s.push_str("| Check | Level | Rule | Applies to | What it tests |\n|---|---|---|---|---|\n");
    for e in &all {
        let applies = if types > 0 && e.applies_to.len() == types {
            "every component".to_string()
        } else {
            e.applies_to.join(", ")
        };
        s.push_str(&format!(
            "| <a id=\"check-{id}\"></a>`{id}` | {} | [`{rule}`](#rule-{rule}) | {} | {} |\n",
            level_name(e.level),
            cell(&applies),
            cell(&e.title),
            id = e.id,
            rule = e.rule,
        ));
    }
    s.push_str("\n| Rule | Source | The rule, in this tool's words |\n|---|---|---|\n");
    let mut seen: Vec<&str> = Vec::new();
    for e in &all {
        if seen.contains(&e.rule) {
            continue;
        }
        seen.push(e.rule);
        s.push_str(&format!(
            "| <a id=\"rule-{rule}\"></a>`{rule}` | {} | {} |\n",
            cell(e.source),
            cell(e.text),
            rule = e.rule,
        ));
    }
    s
}

/// The entries of `catalogue` that `selection` selects, at the levels it gives them
/// (`jaus conform --list --profile`).
pub fn selected(catalogue: &[Entry], selection: &Selection) -> Vec<Entry> {
    catalogue
        .iter()
        .filter_map(|e| {
            let level = selection.level_of(&e.id, e.level)?;
            Some(Entry { level, ..e.clone() })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_check_is_listed_once_with_its_rule() {
        let spec = jaus_spec::load_sdk().unwrap();
        let all = catalogue(&spec);
        let mut ids: Vec<&str> = all.iter().map(|e| e.id.as_str()).collect();
        let n = ids.len();
        ids.sort_unstable();
        ids.dedup();
        assert_eq!(ids.len(), n, "an id listed twice");
        for id in [
            "control.grant",
            "control.authority_below",
            "readback.SetTravelSpeed",
            "as4.control.release",
            "as4.management.shutdown",
        ] {
            assert!(ids.contains(&id), "{id} missing");
        }
        let wd = all
            .iter()
            .find(|e| e.id == "readback.SetTravelSpeed")
            .unwrap();
        assert!(
            wd.applies_to.iter().any(|a| a == "GlobalWaypointDriver"),
            "{wd:?}"
        );
        assert!(all
            .iter()
            .all(|e| !e.text.is_empty() && !e.source.is_empty()));
        assert!(text(&all).contains("control.authority_below"));
        assert!(ids.contains(&"teardown.as-found"));
    }

    #[test]
    fn markdown_has_a_row_per_check_and_one_per_rule() {
        let spec = jaus_spec::load_sdk().unwrap();
        let all = catalogue(&spec);
        let md = markdown(&spec);
        let rows = md
            .lines()
            .filter(|l| l.starts_with("| <a id=\"check-"))
            .count();
        assert_eq!(rows, all.len());
        assert!(
            md.contains("| <a id=\"rule-control.authority\"></a>"),
            "{md}"
        );
        assert!(md.contains("`core.identification` | required | [`identification`](#rule-identification) | every component |"), "{md}");
        assert_eq!(cell("a|b\nc"), "a\\|b c");
    }
}
