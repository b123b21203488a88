//! The engine's rules on a voice that talks to nobody: order, selection, skips,
//! checks planned from earlier ones, and each check's evidence its own.

use std::time::{Duration, Instant};

use super::*;
use crate::check::{Exchange, Kind, Level, Rule};
use crate::selection::Selection;

const RULE: Rule = Rule {
    id: "test",
    source: "test",
    text: "test",
};

fn new_check(id: &str, level: Level) -> Check {
    Check {
        id: id.into(),
        title: id.into(),
        rule: RULE,
        level,
        kind: Kind::As4,
    }
}

/// A voice whose first check plans two more, whose `b` cannot run, and which needs
/// `prep` run whatever the selection.
struct Fake {
    clock: Instant,
    evidence: Evidence,
    queue: Vec<Check>,
    ran: Vec<String>,
    started: bool,
}

impl Fake {
    fn new() -> Self {
        let clock = Instant::now();
        Fake {
            clock,
            evidence: Evidence::new(clock),
            queue: vec![new_check("prep", Level::Required)],
            ran: Vec::new(),
            started: false,
        }
    }
}

impl Voice for Fake {
    fn now(&self) -> Instant {
        self.clock
    }
    fn evidence(&mut self) -> &mut Evidence {
        &mut self.evidence
    }
    fn start(&mut self) {
        self.started = true;
    }
    fn next_check(&mut self) -> Option<Check> {
        (!self.queue.is_empty()).then(|| self.queue.remove(0))
    }
    fn skip(&mut self, check: &Check) -> Option<String> {
        (check.id == "b").then(|| "b needs what a has not".into())
    }
    fn needed(&self, check: &Check) -> bool {
        check.id == "prep"
    }
    fn run(&mut self, check: &Check) -> Found {
        self.clock += Duration::from_millis(10);
        self.ran.push(check.id.clone());
        self.evidence.keep(Exchange {
            t_ms: self.evidence.t_ms(self.clock),
            dir: "sent",
            from: "tester".into(),
            to: "target".into(),
            message: format!("for {}", check.id),
            fields: serde_json::Value::Null,
        });
        if check.id == "prep" {
            self.queue = vec![
                new_check("a", Level::Required),
                new_check("b", Level::Required),
            ];
            return pass("planned a and b");
        }
        fail(format!("{} failed", check.id))
    }
    fn subject(&self) -> Subject {
        Subject {
            address: "1.2.3.4".into(),
            component_id: 3,
            component_type: None,
            identification: Some("fake".into()),
        }
    }
    fn dropped(&self) -> u64 {
        7
    }
}

#[test]
fn every_check_runs_in_order_with_its_own_evidence_and_skips_say_why() {
    let mut v = Fake::new();
    let r = check_component(&mut v, None);
    assert!(v.started);
    let ids: Vec<&str> = r.outcomes.iter().map(|o| o.check.id.as_str()).collect();
    assert_eq!(ids, ["prep", "a", "b"]);
    assert_eq!(v.ran, ["prep", "a"], "b is skipped, nothing sent for it");
    assert_eq!(r.outcomes[0].evidence.len(), 1);
    assert_eq!(r.outcomes[0].evidence[0].message, "for prep");
    assert_eq!(r.outcomes[1].evidence[0].message, "for a");
    assert_eq!(
        r.outcomes[1].evidence[0].t_ms, 10.0,
        "timed from its check's start"
    );
    assert!(r.outcomes[2].evidence.is_empty());
    assert_eq!(r.outcomes[2].verdict, Verdict::Inconclusive);
    assert_eq!(r.outcomes[2].detail, "not run: b needs what a has not");
    assert_eq!(r.required_failures(), 1);
    assert_eq!((r.address.as_str(), r.component_id), ("1.2.3.4", 3));
}

#[test]
fn a_selection_leaves_checks_out_runs_what_is_needed_and_sets_levels() {
    let sel = Selection {
        name: "only-a".into(),
        description: String::new(),
        ids: vec!["a".into()],
        picks: vec![crate::selection::Pick {
            id: "a".into(),
            level: Some(crate::selection::LevelName::Advisory),
            line: None,
        }],
    };
    let mut v = Fake::new();
    let r = check_component(&mut v, Some(&sel));
    assert_eq!(v.ran, ["prep", "a"], "prep is needed: it runs, unreported");
    let ids: Vec<&str> = r.outcomes.iter().map(|o| o.check.id.as_str()).collect();
    assert_eq!(ids, ["a"]);
    assert_eq!(r.outcomes[0].check.level, Level::Advisory);
    assert_eq!(r.required_failures(), 0);
    let run = RunReport::new(
        "jaus conform",
        String::new(),
        vec![r],
        v.dropped(),
        Some(&sel),
    );
    assert!(run.tool.ends_with(", profile only-a"), "{}", run.tool);
    assert!(run.passed());
    assert_eq!(run.tester_dropped, 7);
}
