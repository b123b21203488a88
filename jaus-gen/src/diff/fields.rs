//! Fields of messages and records, and the messages themselves: wire forms compared up
//! to renamed types, fields matched by name then position, additions checked against
//! the forward-compatibility rule.

use super::pair::{kept_order, opt_text, pair, pv_text, runs_to_end, Body};
use super::scale::{self, Scaling};
use super::{ChangeKind, Differ, Severity};
use crate::snapshot::*;
use jaus_spec::Wire;
use std::collections::{BTreeSet, HashMap};

impl Differ<'_> {
    /// Wire forms equal up to renamed types (a type's kind change is reported at the
    /// type).
    pub(super) fn wire_eq(&self, o: &Wire, n: &Wire) -> bool {
        match (o, n) {
            (
                Wire::Named {
                    name: a,
                    size: sa,
                    tag_field: ta,
                    ..
                },
                Wire::Named {
                    name: b,
                    size: sb,
                    tag_field: tb,
                    ..
                },
            ) => self.same_type(a, b) && sa == sb && ta == tb,
            (Wire::List { count: a, elem: ea }, Wire::List { count: b, elem: eb }) => {
                a == b && self.wire_eq(ea, eb)
            }
            (
                Wire::ListField {
                    field: a,
                    elem: ea,
                    offsets_of: oa,
                },
                Wire::ListField {
                    field: b,
                    elem: eb,
                    offsets_of: ob,
                },
            ) => a == b && oa == ob && self.wire_eq(ea, eb),
            _ => o == n,
        }
    }

    fn same_type(&self, old: &str, new: &str) -> bool {
        self.renames.get(old).map_or(old == new, |r| r == new)
    }

    /// What differs between two wire forms: (kind, detail). `units` are the old and new
    /// units of the value, for what a scaling change does to it.
    fn wire_changes(
        &self,
        o: &Wire,
        n: &Wire,
        prefix: &str,
        units: (Option<&str>, Option<&str>),
        out: &mut Vec<(ChangeKind, String)>,
    ) {
        if self.wire_eq(o, n) {
            return;
        }
        match (o, n) {
            (
                &Wire::Scaled {
                    int: oi,
                    lo: ol,
                    hi: oh,
                },
                &Wire::Scaled {
                    int: ni,
                    lo: nl,
                    hi: nh,
                },
            ) => {
                // What the old count means to a new peer, on the last line of the two.
                let effect = scale::consequence(
                    Scaling {
                        int: oi,
                        lo: ol,
                        hi: oh,
                    },
                    Scaling {
                        int: ni,
                        lo: nl,
                        hi: nh,
                    },
                    units.0,
                    units.1,
                )
                .map_or_else(
                    || {
                        if oi.bytes() != ni.bytes() {
                            ": every later byte moves".to_string()
                        } else {
                            String::new()
                        }
                    },
                    |e| format!(": {e}"),
                );
                let limits = (ol, oh) != (nl, nh);
                if oi != ni {
                    out.push((
                        ChangeKind::FieldScaleIntChanged,
                        format!(
                            "{prefix}scaled integer {} → {}{}",
                            oi.rust(),
                            ni.rust(),
                            if limits { "" } else { &effect }
                        ),
                    ));
                }
                if limits {
                    out.push((
                        ChangeKind::FieldScaleChanged,
                        format!("{prefix}scale [{ol}, {oh}] → [{nl}, {nh}]{effect}"),
                    ));
                }
            }
            (Wire::Str(_), Wire::Str(_)) | (Wire::Bytes(_), Wire::Bytes(_)) => {
                out.push((
                    ChangeKind::FieldLengthChanged,
                    format!("{prefix}{} → {}", wire_text(o), wire_text(n)),
                ));
            }
            (Wire::Packet { .. }, Wire::Packet { .. }) => out.push((
                ChangeKind::FieldLengthChanged,
                format!("{prefix}{} → {}", wire_text(o), wire_text(n)),
            )),
            (
                Wire::Named {
                    name: a,
                    size: sa,
                    tag_field: ta,
                    ..
                },
                Wire::Named {
                    name: b,
                    size: sb,
                    tag_field: tb,
                    ..
                },
            ) => {
                if !self.same_type(a, b) {
                    out.push((
                        ChangeKind::FieldTypeChanged,
                        format!("{prefix}type {a} → {b}"),
                    ));
                }
                if sa != sb {
                    out.push((
                        ChangeKind::FieldLengthChanged,
                        format!("{prefix}size prefix {} → {}", pv_text(*sa), pv_text(*sb)),
                    ));
                }
                if ta != tb {
                    out.push((
                        ChangeKind::FieldTypeChanged,
                        format!("{prefix}tag_field {} → {}", opt_text(ta), opt_text(tb)),
                    ));
                }
            }
            (
                Wire::List { elem: ea, .. } | Wire::ListField { elem: ea, .. },
                Wire::List { elem: eb, .. } | Wire::ListField { elem: eb, .. },
            ) => {
                let head = |w: &Wire| {
                    let t = wire_text(w);
                    t.split(" of ").next().unwrap_or(&t).to_string()
                };
                let (ho, hn) = (head(o), head(n));
                if ho != hn {
                    out.push((
                        ChangeKind::FieldCountChanged,
                        format!("{prefix}{ho} → {hn}"),
                    ));
                }
                self.wire_changes(ea, eb, &format!("{prefix}element: "), units, out);
            }
            _ => out.push((
                ChangeKind::FieldTypeChanged,
                format!("{prefix}{} → {}", wire_text(o), wire_text(n)),
            )),
        }
    }

    /// Compares the fields of a message (`in_message`) or record named `owner`.
    pub(super) fn fields(
        &mut self,
        owner: &str,
        in_message: bool,
        o: Body<'_>,
        n: Body<'_>,
        users: &[String],
    ) {
        use ChangeKind::*;
        use Severity::*;
        if o.presence != n.presence {
            self.push(
                PresenceChanged,
                WireBreaking,
                owner.to_string(),
                Some(o.at),
                Some(n.at),
                format!(
                    "presence vector {} → {}",
                    pv_text(o.presence),
                    pv_text(n.presence)
                ),
                users,
            );
        }
        let oi: HashMap<&str, usize> = o
            .fields
            .iter()
            .enumerate()
            .map(|(i, f)| (f.name.as_str(), i))
            .collect();
        let ni: HashMap<&str, usize> = n
            .fields
            .iter()
            .enumerate()
            .map(|(i, f)| (f.name.as_str(), i))
            .collect();
        // Pairs (old index, new index, renamed).
        let mut pairs: Vec<(usize, usize, bool)> = Vec::new();
        for (i, f) in o.fields.iter().enumerate() {
            if let Some(&j) = ni.get(f.name.as_str()) {
                pairs.push((i, j, false));
            } else if let Some(g) = n.fields.get(i) {
                let renamed = !oi.contains_key(g.name.as_str())
                    && self.wire_eq(&f.wire, &g.wire)
                    && f.bit == g.bit
                    && f.present_if == g.present_if;
                if renamed {
                    pairs.push((i, i, true));
                }
            }
        }
        let order: Vec<usize> = pairs.iter().map(|p| p.1).collect();
        let kept = kept_order(&order);
        let matched_new: BTreeSet<usize> = pairs.iter().map(|p| p.1).collect();
        let matched_old: BTreeSet<usize> = pairs.iter().map(|p| p.0).collect();
        for &(i, j, renamed) in &pairs {
            let (f, g) = (&o.fields[i], &n.fields[j]);
            let path = format!("{owner}.{}", g.name);
            let push = |s: &mut Self, kind, sev, detail: String| {
                s.push(
                    kind,
                    sev,
                    path.clone(),
                    Some(&f.at),
                    Some(&g.at),
                    detail,
                    users,
                )
            };
            if renamed {
                push(
                    self,
                    FieldRenamed,
                    SourceBreaking,
                    format!(
                        "renamed `{}` → `{}` (same position and wire form)",
                        f.name, g.name
                    ),
                );
            }
            if !kept.contains(&j) {
                push(
                    self,
                    FieldMoved,
                    WireBreaking,
                    format!("moved from position {} to {}", i + 1, j + 1),
                );
            }
            let mut wc = Vec::new();
            self.wire_changes(
                &f.wire,
                &g.wire,
                "",
                (f.unit.as_deref(), g.unit.as_deref()),
                &mut wc,
            );
            for (kind, detail) in wc {
                push(self, kind, WireBreaking, detail);
            }
            if f.bit != g.bit {
                let b = |b: Option<u32>| b.map_or("mandatory".to_string(), |b| format!("bit {b}"));
                push(
                    self,
                    FieldBitChanged,
                    WireBreaking,
                    format!("presence {} → {}", b(f.bit), b(g.bit)),
                );
            }
            if f.present_if != g.present_if {
                push(
                    self,
                    FieldPresentIfChanged,
                    WireBreaking,
                    format!(
                        "present_if {} → {}",
                        opt_text(&f.present_if),
                        opt_text(&g.present_if)
                    ),
                );
            }
            if f.unit != g.unit {
                push(
                    self,
                    FieldUnitChanged,
                    Compatible,
                    format!(
                        "unit {} → {} (same bytes, another meaning: check the code using it)",
                        opt_text(&f.unit),
                        opt_text(&g.unit)
                    ),
                );
            }
        }
        for (i, f) in o.fields.iter().enumerate() {
            if !matched_old.contains(&i) {
                self.push(
                    FieldRemoved,
                    WireBreaking,
                    format!("{owner}.{}", f.name),
                    Some(&f.at),
                    Some(n.at),
                    format!("removed ({})", wire_text(&f.wire)),
                    users,
                );
            }
        }
        for (j, g) in n.fields.iter().enumerate() {
            if matched_new.contains(&j) {
                continue;
            }
            let trailing = (j + 1..n.fields.len()).all(|k| !matched_new.contains(&k));
            let why_not = if !in_message {
                Some("a record's bytes are followed by others: older decoders cannot skip the new ones".to_string())
            } else if !trailing {
                Some("not at the end of the message".to_string())
            } else if let Some(b) = g.bit {
                let highest_old = o.fields.iter().filter_map(|f| f.bit).max();
                let old_runs_to_end = o.fields.last().is_some_and(|f| runs_to_end(&f.wire));
                if o.presence.is_none() || o.presence != n.presence {
                    Some("the presence vector is new or changed".to_string())
                } else if let Some(u) = o.fields.iter().find(|f| f.bit == Some(b)) {
                    Some(format!("bit {b} was `{}`'s", u.name))
                } else if highest_old.is_some_and(|h| b < h) {
                    // The forward-compatibility rule: an older decoder can skip only bits
                    // above every bit it defines (a lower one may sit between its fields).
                    Some(format!(
                        "bit {b} is below bit {} of the older revision: older decoders refuse it",
                        highest_old.unwrap_or_default()
                    ))
                } else if old_runs_to_end {
                    Some("the older revision's last field runs to the end of the body: older decoders would read the new bytes into it".to_string())
                } else {
                    None
                }
            } else {
                Some("mandatory (no presence bit)".to_string())
            };
            let (sev, detail) = match why_not {
                None => (
                    Compatible,
                    format!(
                        "added at the end under new presence bit {} ({}): older decoders skip it; \
                         struct literals and patterns of {owner} without `..` no longer compile",
                        g.bit.unwrap_or_default(),
                        wire_text(&g.wire)
                    ),
                ),
                Some(why) => (
                    WireBreaking,
                    format!("added ({}): {why}", wire_text(&g.wire)),
                ),
            };
            self.push(
                FieldAdded,
                sev,
                format!("{owner}.{}", g.name),
                Some(o.at),
                Some(&g.at),
                detail,
                users,
            );
        }
    }

    pub(super) fn messages(&mut self) {
        use ChangeKind::*;
        use Severity::*;
        let p = pair(
            &self.old.messages,
            &self.new.messages,
            |m| &m.name,
            |a, b| a.code == b.code,
        );
        for m in p.removed {
            self.push(
                MessageRemoved,
                WireBreaking,
                m.name.clone(),
                Some(&m.at),
                None,
                format!("removed (0x{:04X})", m.code),
                &[],
            );
        }
        for n in p.added {
            self.push(
                MessageAdded,
                Compatible,
                n.name.clone(),
                None,
                Some(&n.at),
                format!(
                    "added (0x{:04X}); a `match` on `Message` without a `_` arm no longer compiles",
                    n.code
                ),
                &[],
            );
        }
        for (m, n, renamed) in p.both {
            if renamed {
                self.push(
                    MessageRenamed,
                    SourceBreaking,
                    n.name.clone(),
                    Some(&m.at),
                    Some(&n.at),
                    format!(
                        "renamed {} → {} (same code 0x{:04X})",
                        m.name, n.name, n.code
                    ),
                    &[],
                );
            }
            if m.code != n.code {
                self.push(
                    MessageCodeChanged,
                    WireBreaking,
                    n.name.clone(),
                    Some(&m.at),
                    Some(&n.at),
                    format!("command code 0x{:04X} → 0x{:04X}", m.code, n.code),
                    &[],
                );
            }
            self.fields(
                &n.name,
                true,
                Body {
                    presence: m.presence,
                    fields: &m.fields,
                    at: &m.at,
                },
                Body {
                    presence: n.presence,
                    fields: &n.fields,
                    at: &n.at,
                },
                &[],
            );
        }
    }
}
