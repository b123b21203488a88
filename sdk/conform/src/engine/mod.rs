//! The one conformance engine. It runs the checks of one component, one at a time,
//! through a [`Voice`]: the generation's way of talking to the component (RA 3.3's
//! four System Commanders, [`crate::ra33::Ra33Voice`]; the AS-4 judge's client,
//! [`crate::as4`]'s IOP scenario and the checks planned from AS-4 definitions). The
//! engine owns what every run shares, so each rule of it lives here once:
//!
//! * the order: the voice gives its checks one at a time ([`Voice::next_check`]), so a
//!   later check can be planned from what an earlier one found (the services an AS-4
//!   component lists);
//! * the selection of a profile ([`Selection`]): a check it leaves out is not run,
//!   unless the voice needs it run for the checks after it or to leave the component as
//!   found ([`Voice::needed`]); then it runs and is left out of the report;
//! * a check that cannot run is reported Inconclusive, "not run: " and why
//!   ([`Voice::skip`]), with nothing sent;
//! * every check's evidence: the messages of that check only, timed from its start and
//!   bounded ([`Evidence`]);
//! * the reports: [`ComponentReport`] per component, [`RunReport`] per run.

pub mod evidence;

use std::time::{Duration, Instant};

use serde::Serialize;

use crate::check::{Check, Outcome, Verdict};
use crate::selection::Selection;

pub use evidence::Evidence;

/// A verdict and why.
pub type Found = (Verdict, String);

/// A pass, and what was seen.
pub(crate) fn pass(d: impl Into<String>) -> Found {
    (Verdict::Pass, d.into())
}

/// A failure, and how the component broke the rule.
pub(crate) fn fail(d: impl Into<String>) -> Found {
    (Verdict::Fail, d.into())
}

/// No decision, and why.
pub(crate) fn inconclusive(d: impl Into<String>) -> Found {
    (Verdict::Inconclusive, d.into())
}

/// How long the engine waits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Options {
    /// For an answer to a query or a control request.
    pub wait: Duration,
    /// After a command, before reading back what it did (or did not do).
    pub settle: Duration,
}

impl Default for Options {
    /// One second for answers, 200 ms to settle.
    fn default() -> Self {
        Options {
            wait: Duration::from_secs(1),
            settle: Duration::from_millis(200),
        }
    }
}

/// The component a voice tested, as its report names it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Subject {
    /// Its address (RA 3.3) or id (AS-4), or "(not found)".
    pub address: String,
    /// Its component id.
    pub component_id: u8,
    /// Its type, when known.
    pub component_type: Option<String>,
    /// Its identification text, when it answered.
    pub identification: Option<String>,
}

/// One generation's way of testing a component: what to check, in which order, and
/// how each check talks to the component. The engine ([`check_component`]) does the
/// rest.
pub trait Voice {
    /// The session's clock.
    fn now(&self) -> Instant;
    /// The running check's evidence: every message the voice sends or receives for the
    /// component goes in it.
    fn evidence(&mut self) -> &mut Evidence;
    /// Before the first check: what the voice reads to leave the component as found at
    /// the end. Its messages are no check's evidence.
    fn start(&mut self) {}
    /// The next check to run (`None`: done). Called again after each check has run, so
    /// later checks may be planned from what earlier ones found.
    fn next_check(&mut self) -> Option<Check>;
    /// Why `check` cannot run now (it is then reported Inconclusive with nothing sent).
    fn skip(&mut self, _check: &Check) -> Option<String> {
        None
    }
    /// Whether `check` must run even when a profile leaves it out: its steps prepare
    /// the checks after it, or it leaves the component as found.
    fn needed(&self, _check: &Check) -> bool {
        false
    }
    /// Runs `check`.
    fn run(&mut self, check: &Check) -> Found;
    /// The component tested (asked once the checks are done).
    fn subject(&self) -> Subject;
    /// Messages for the tester the session did not keep (a full inbox).
    fn dropped(&self) -> u64;
}

/// What the checks found on one component.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComponentReport {
    /// Its address.
    pub address: String,
    /// Its component id.
    pub component_id: u8,
    /// Its type, when the definitions know the id.
    pub component_type: Option<String>,
    /// Its identification text, when it answered.
    pub identification: Option<String>,
    /// Every check, in the order run.
    pub outcomes: Vec<Outcome>,
}

impl ComponentReport {
    /// How many checks have `verdict`.
    pub fn count(&self, verdict: Verdict) -> usize {
        self.outcomes
            .iter()
            .filter(|o| o.verdict == verdict)
            .count()
    }

    /// Required checks that failed.
    pub fn required_failures(&self) -> usize {
        self.outcomes
            .iter()
            .filter(|o| o.is_required_failure())
            .count()
    }
}

/// Everything one run found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunReport {
    /// The tool and its version.
    pub tool: String,
    /// Where the targets were reached (the peers), for the reader.
    pub peer: String,
    /// One report per component tested.
    pub components: Vec<ComponentReport>,
    /// Packets for the tester's voices that were not kept because its inbox was full
    /// (a target flooding the tester); checks waiting for them may have failed.
    pub tester_dropped: u64,
}

impl RunReport {
    /// A run's report by `tool` (`jaus conform --as4`) of `components` reached through
    /// `peer`, naming the profile of `selection` when a profile chose the checks.
    pub fn new(
        tool: &str,
        peer: String,
        components: Vec<ComponentReport>,
        tester_dropped: u64,
        selection: Option<&Selection>,
    ) -> Self {
        let mut tool = format!("{tool} {}", env!("CARGO_PKG_VERSION"));
        if let Some(sel) = selection {
            tool = format!("{tool}, profile {}", sel.name);
        }
        RunReport {
            tool,
            peer,
            components,
            tester_dropped,
        }
    }

    /// True when no required check failed.
    pub fn passed(&self) -> bool {
        self.components.iter().all(|c| c.required_failures() == 0)
    }

    /// Checks run in all.
    pub fn checks(&self) -> usize {
        self.components.iter().map(|c| c.outcomes.len()).sum()
    }
}

/// Runs the checks of one component through `voice`: those `selection` selects, at the
/// levels it gives them (`None`: every check at its own level).
pub fn check_component(voice: &mut dyn Voice, selection: Option<&Selection>) -> ComponentReport {
    voice.start();
    let mut outcomes = Vec::new();
    while let Some(mut check) = voice.next_check() {
        let level = match selection {
            None => Some(check.level),
            Some(sel) => sel.level_of(&check.id, check.level),
        };
        if level.is_none() && !voice.needed(&check) {
            continue;
        }
        let now = voice.now();
        voice.evidence().begin(now);
        let (verdict, detail) = match voice.skip(&check) {
            Some(why) => inconclusive(format!("not run: {why}")),
            None => voice.run(&check),
        };
        let evidence = voice.evidence().take();
        if let Some(level) = level {
            check.level = level;
            outcomes.push(Outcome {
                check,
                verdict,
                detail,
                evidence,
            });
        }
    }
    let s = voice.subject();
    ComponentReport {
        address: s.address,
        component_id: s.component_id,
        component_type: s.component_type,
        identification: s.identification,
        outcomes,
    }
}

#[cfg(test)]
mod tests;
