//! The judge's findings as the crate's report: per component seen, one outcome per
//! check that has something to judge, its detail naming packets, messages and
//! addresses, its evidence the packets concerned.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write;
use std::time::Duration;

use crate::check::{Check, Exchange, Kind, Level, Outcome, Verdict};
use crate::ComponentReport;

use super::as4::As4;
use super::outsider::Findings;
use super::pairs::Answers;
use super::ra33::Ra33;
use super::{describe, ids, packet_list, Options, Seen, Who};

/// Evidence entries kept per outcome.
const EVIDENCE_CAP: usize = 50;

/// Builds the report.
pub(crate) struct Builder {
    origin: Duration,
    opts: Options,
}

/// The check `id` as data. The engine never runs it: its kind is only a placeholder
/// ([`Kind`] has no offline variant).
fn check(id: &str) -> Check {
    let (title, rule, required) = describe(id);
    Check {
        id: id.into(),
        title: title.into(),
        rule,
        level: if required {
            Level::Required
        } else {
            Level::Advisory
        },
        kind: Kind::Offline,
    }
}

fn outcome(id: &str, verdict: Verdict, detail: String, evidence: Vec<Exchange>) -> Outcome {
    Outcome {
        check: check(id),
        verdict,
        detail,
        evidence,
    }
}

impl Builder {
    pub fn new(origin: Duration, opts: Options) -> Self {
        Builder { origin, opts }
    }

    fn exchange(
        &self,
        time: Duration,
        from: String,
        to: String,
        message: String,
        fields: serde_json::Value,
    ) -> Exchange {
        Exchange {
            t_ms: time.saturating_sub(self.origin).as_secs_f64() * 1e3,
            dir: "captured",
            from,
            to,
            message,
            fields,
        }
    }

    /// One report per component seen or asked, in address order.
    pub fn components(
        &mut self,
        seen: &BTreeMap<Who, Seen>,
        ra33: &Ra33,
        as4: &As4,
    ) -> Vec<ComponentReport> {
        let mut all: BTreeSet<Who> = seen.keys().copied().collect();
        all.extend(ra33.queries.results.keys().map(|k| Who::Ra33(k.0)));
        all.extend(ra33.acks.results.keys().map(|k| Who::Ra33(k.0)));
        all.extend(ra33.outsider.findings.keys().map(|a| Who::Ra33(*a)));
        all.extend(as4.queries.results.keys().map(|k| Who::As4(k.0)));
        all.into_iter()
            .map(|who| {
                let mut outcomes = Vec::new();
                let s = seen.get(&who);
                if let Some(s) = s {
                    outcomes.push(self.malformed(who, s));
                }
                match who {
                    Who::Ra33(a) => {
                        for (required, id) in [(true, ids::QUERY), (false, ids::QUERY_OTHER)] {
                            if let Some(r) = ra33.queries.results.get(&(a, required)) {
                                outcomes.push(self.answers(
                                    id,
                                    who,
                                    r,
                                    "queries",
                                    super::ra33::name_of,
                                ));
                            }
                        }
                        if let Some(r) = ra33.acks.results.get(&(a, true)) {
                            outcomes.push(self.answers(
                                ids::ACKNAK,
                                who,
                                r,
                                "acknowledgement requests",
                                super::ra33::name_of,
                            ));
                        }
                        if let Some(f) = ra33.outsider.findings.get(&a) {
                            outcomes.extend(self.outsider(f));
                        }
                    }
                    Who::As4(id) => {
                        for (required, check) in
                            [(true, ids::AS4_QUERY), (false, ids::AS4_QUERY_OTHER)]
                        {
                            if let Some(r) = as4.queries.results.get(&(id, required)) {
                                outcomes.push(self.answers(
                                    check,
                                    who,
                                    r,
                                    "queries",
                                    super::as4::name_of,
                                ));
                            }
                        }
                    }
                    Who::Socket(..) => {}
                }
                ComponentReport {
                    address: who.to_string(),
                    component_id: match who {
                        Who::Ra33(a) => a.component,
                        Who::As4(id) => id.component,
                        Who::Socket(..) => 0,
                    },
                    component_type: Some(
                        match who {
                            Who::Ra33(_) => "RA 3.3 component",
                            Who::As4(_) => "AS-4 component",
                            Who::Socket(..) => "sender of undecodable datagrams",
                        }
                        .into(),
                    ),
                    identification: s.and_then(|s| s.identification.clone()),
                    outcomes,
                }
            })
            .collect()
    }

    /// Whether every packet `who` sent decoded.
    fn malformed(&self, who: Who, s: &Seen) -> Outcome {
        let id = match who {
            Who::As4(_) | Who::Socket(_, true) => ids::AS4_MALFORMED,
            _ => ids::MALFORMED,
        };
        let bad = s.malformed.len() as u64 + s.malformed_more;
        let mut d = String::new();
        if bad > 0 {
            let numbers: Vec<u64> = s.malformed.iter().map(|b| b.number).collect();
            let _ = write!(
                d,
                "{bad} of {} packets from {who} do not decode ({}): ",
                bad + s.decoded + s.pieces,
                packet_list(&numbers, s.malformed_more)
            );
            let shown: Vec<String> = s
                .malformed
                .iter()
                .take(5)
                .map(|b| format!("packet {} (to {}): {}", b.number, b.to, b.error))
                .collect();
            d.push_str(&shown.join("; "));
        } else {
            let _ = write!(d, "{} packets from {who} decode", s.decoded);
        }
        if s.pieces > 0 {
            let _ = write!(
                d,
                "; {} pieces of multi-packet messages (not decoded alone)",
                s.pieces
            );
        }
        if !s.unknown.is_empty() {
            let codes: Vec<String> = s.unknown.iter().map(|c| format!("{c:#06X}")).collect();
            let _ = write!(
                d,
                "; codes the definitions do not know (kept raw): {}",
                codes.join(", ")
            );
        }
        let evidence = s
            .malformed
            .iter()
            .take(EVIDENCE_CAP)
            .map(|b| {
                self.exchange(
                    b.time,
                    who.to_string(),
                    b.to.clone(),
                    "raw".into(),
                    serde_json::json!({ "packet": b.number, "error": b.error }),
                )
            })
            .collect();
        let verdict = if bad > 0 {
            Verdict::Fail
        } else {
            Verdict::Pass
        };
        outcome(id, verdict, d, evidence)
    }

    /// Whether `who` answered what it was sent (queries or acknowledgement requests).
    fn answers(
        &self,
        id: &str,
        who: Who,
        r: &Answers<impl std::fmt::Display + Copy>,
        what: &str,
        name: fn(u16) -> String,
    ) -> Outcome {
        let window = self.opts.window.as_secs_f64();
        let answered = r.latencies.len();
        let mut d = format!(
            "{who}: {answered} of {} {what} answered within {window:.1} s",
            r.judged()
        );
        if let Some(l) = r.latency_text() {
            let _ = write!(d, " ({l})");
        }
        if r.negative > 0 {
            let _ = write!(d, ", {} of them with NAK", r.negative);
        }
        if r.missing() > 0 {
            let numbers: Vec<u64> = r.unanswered.iter().map(|p| p.number).collect();
            let shown: Vec<String> = r
                .unanswered
                .iter()
                .take(10)
                .map(|p| format!("{} from {} (packet {})", name(p.code), p.asker, p.number))
                .collect();
            let _ = write!(d, "; not answered: {}", shown.join(", "));
            if r.missing() > shown.len() as u64 {
                let _ = write!(d, "; in all {}", packet_list(&numbers, r.unanswered_more));
            }
        }
        if !r.cut.is_empty() {
            let numbers: Vec<u64> = r.cut.iter().map(|p| p.number).collect();
            let _ = write!(
                d,
                "; not judged, the capture ending less than {window:.1} s after them: {}",
                packet_list(&numbers, 0)
            );
        }
        let verdict = if r.missing() > 0 {
            Verdict::Fail
        } else if r.judged() > 0 {
            Verdict::Pass
        } else {
            Verdict::Inconclusive
        };
        let evidence = r
            .unanswered
            .iter()
            .take(EVIDENCE_CAP)
            .map(|p| {
                self.exchange(
                    p.time,
                    p.asker.to_string(),
                    who.to_string(),
                    name(p.code),
                    serde_json::json!({ "packet": p.number, "answered": false }),
                )
            })
            .collect();
        outcome(id, verdict, d, evidence)
    }

    /// What the commands from clients not in control did.
    fn outsider(&self, f: &Findings) -> Vec<Outcome> {
        let mut out = Vec::new();
        let watched = f.obeyed.len() + f.refused.len() + f.unseen.len();
        if watched > 0 || f.undecided > 0 {
            let mut parts = Vec::new();
            let mut evidence = Vec::new();
            for o in f.obeyed.iter().take(5) {
                let c = &o.cmd;
                parts.push(format!(
                    "{} from {} (not in control; {} was) at packet {} was carried out: Report Component Status at packet {} shows {:?}{} {:.1} ms after it",
                    c.name,
                    c.from,
                    o.controller,
                    c.number,
                    o.report.0,
                    o.report.2,
                    o.before.map(|b| format!(" (was {b:?})")).unwrap_or_default(),
                    o.report.1.saturating_sub(c.time).as_secs_f64() * 1e3,
                ));
            }
            for o in f.obeyed.iter().take(EVIDENCE_CAP / 2) {
                let c = &o.cmd;
                evidence.push(self.exchange(
                    c.time,
                    c.from.to_string(),
                    c.to.to_string(),
                    c.name.into(),
                    serde_json::json!({ "packet": c.number }),
                ));
                evidence.push(self.exchange(
                    o.report.1,
                    c.to.to_string(),
                    String::new(),
                    "ReportComponentStatus".into(),
                    serde_json::json!({ "packet": o.report.0, "primary_status_code": format!("{:?}", o.report.2) }),
                ));
            }
            if f.obeyed.len() > 5 {
                parts.push(format!("{} more carried out", f.obeyed.len() - 5));
            }
            if !f.refused.is_empty() {
                parts.push(format!(
                    "refused, the state reported after them unchanged: {}",
                    packet_list(&f.refused, 0)
                ));
            }
            if !f.unseen.is_empty() {
                parts.push(format!(
                    "no Report Component Status within {:.1} s to tell: {}",
                    self.opts.window.as_secs_f64(),
                    packet_list(&f.unseen, 0)
                ));
            }
            if f.undecided > 0 {
                parts.push(format!(
                    "{} whose effect could not show (already in that state, or the controller's own command followed)",
                    f.undecided
                ));
            }
            let verdict = if !f.obeyed.is_empty() {
                Verdict::Fail
            } else if !f.refused.is_empty() {
                Verdict::Pass
            } else {
                Verdict::Inconclusive
            };
            let mut d = format!(
                "state commands from clients not in control: {}",
                parts.join("; ")
            );
            if f.other > 0 {
                let _ = write!(
                    d,
                    "; {} other commands from them not judged (their effect needs a read-back)",
                    f.other
                );
            }
            out.push(outcome(ids::OUTSIDER, verdict, d, evidence));
        }
        if !f.acked.is_empty() || f.naked > 0 {
            let shown: Vec<String> = f
                .acked
                .iter()
                .take(10)
                .map(|(c, ack)| {
                    format!(
                        "{} from {} (packet {}) acknowledged with ACK (packet {ack})",
                        c.name, c.from, c.number
                    )
                })
                .collect();
            let verdict = if f.acked.is_empty() {
                Verdict::Pass
            } else {
                Verdict::Fail
            };
            let d = format!(
                "commands from clients not in control: {} acknowledged with ACK{}{}",
                f.acked.len(),
                if shown.is_empty() {
                    String::new()
                } else {
                    format!(": {}", shown.join(", "))
                },
                if f.naked > 0 {
                    format!("; {} refused with NAK", f.naked)
                } else {
                    String::new()
                }
            );
            out.push(outcome(ids::OUTSIDER_ACK, verdict, d, Vec::new()));
        }
        out
    }
}
