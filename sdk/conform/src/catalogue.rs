//! Every check the tester can run, as data: `jaus conform --list [json]`.
//!
//! The RA 3.3 checks are what [`crate::plan`] plans for each component type of the
//! definitions (a vendor's overlay included), merged by check id with the types each
//! applies to; the AS-4 checks are the IOP judge's ([`crate::as4`]). Each entry carries
//! its id, what it tests, its level and the rule it cites with the rule's source.

use jaus_spec::Spec;
use serde::Serialize;

use crate::check::Level;

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
    }
}
