//! The output of a diff: its severity counts, exit status, text and JSON.

use super::{Diff, Severity};
use crate::snapshot::Loc;
use serde::Serialize;
use std::fmt::Write as _;

#[derive(Serialize)]
struct JsonChange<'a> {
    kind: &'a str,
    severity: &'a str,
    path: &'a str,
    old: Option<&'a Loc>,
    new: Option<&'a Loc>,
    detail: &'a str,
    used_by: &'a [String],
}

impl Diff {
    /// The most severe change, if any.
    pub fn worst(&self) -> Option<Severity> {
        self.changes.iter().map(|c| c.severity).max()
    }

    /// Number of changes of severity `s`.
    pub fn count(&self, s: Severity) -> usize {
        self.changes.iter().filter(|c| c.severity == s).count()
    }

    /// True when some change is at least as severe as `fail_on`.
    pub fn fails(&self, fail_on: Severity) -> bool {
        self.worst().is_some_and(|w| w >= fail_on)
    }

    /// The exit status of `jaus-gen diff`: 1 when some change is at least as severe as
    /// `fail_on` (by default [`Severity::WireBreaking`]), else 0. (2, a usage or load
    /// error, comes before any diff.)
    pub fn exit_status(&self, fail_on: Severity) -> u8 {
        u8::from(self.fails(fail_on))
    }

    /// `N wire-breaking, N source-breaking, N compatible`, or `no change`.
    pub fn summary(&self) -> String {
        if self.changes.is_empty() {
            return "no change".into();
        }
        format!(
            "{} change(s): {} wire-breaking, {} source-breaking, {} compatible",
            self.changes.len(),
            self.count(Severity::WireBreaking),
            self.count(Severity::SourceBreaking),
            self.count(Severity::Compatible)
        )
    }

    /// One line per change, grouped by severity (most severe first), then the summary:
    /// `wire-breaking    platform.yaml:115 → platform.yaml:117  SetTravelSpeed.speed: scale [0, 10000] → [0, 327.67]`.
    pub fn to_text(&self) -> String {
        let loc = |l: &Option<Loc>| l.as_ref().map_or("-".to_string(), Loc::to_string);
        let wo = self.changes.iter().map(|c| loc(&c.old).len()).max();
        let wn = self.changes.iter().map(|c| loc(&c.new).len()).max();
        let (wo, wn) = (wo.unwrap_or(0), wn.unwrap_or(0));
        let mut out = String::new();
        let mut last = None;
        for c in &self.changes {
            if last.is_some_and(|s| s != c.severity) {
                out.push('\n');
            }
            last = Some(c.severity);
            let _ = write!(
                out,
                "{:<15}  {:<wo$} → {:<wn$}  {}: {}",
                c.severity.as_str(),
                loc(&c.old),
                loc(&c.new),
                c.path,
                c.detail
            );
            if !c.used_by.is_empty() {
                const SHOWN: usize = 6;
                let mut users = c.used_by[..c.used_by.len().min(SHOWN)].join(", ");
                if c.used_by.len() > SHOWN {
                    let _ = write!(users, " and {} more", c.used_by.len() - SHOWN);
                }
                let _ = write!(out, " (used by {users})");
            }
            out.push('\n');
        }
        if !self.changes.is_empty() {
            out.push('\n');
        }
        out.push_str(&self.summary());
        out.push('\n');
        out
    }

    /// A JSON array of `{kind, severity, path, old: {file, line, col} | null, new,
    /// detail, used_by}`, in the order of [`Diff::changes`].
    pub fn to_json(&self) -> String {
        let v: Vec<JsonChange<'_>> = self
            .changes
            .iter()
            .map(|c| JsonChange {
                kind: c.kind.as_str(),
                severity: c.severity.as_str(),
                path: &c.path,
                old: c.old.as_ref(),
                new: c.new.as_ref(),
                detail: &c.detail,
                used_by: &c.used_by,
            })
            .collect();
        // A `serde_json::Value` (string keys only) always serialises.
        let mut s = serde_json::to_string_pretty(&v).expect("changes serialise");
        s.push('\n');
        s
    }
}
