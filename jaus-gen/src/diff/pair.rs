//! Helpers of the comparison: lists of named items paired across revisions, the order
//! a list kept, and the texts of wire details.

use crate::snapshot::*;
use jaus_spec::{Bits, Int, Wire};
use std::collections::BTreeSet;

/// The named types a wire form refers to.
pub(super) fn named<'w>(w: &'w Wire, out: &mut Vec<&'w str>) {
    match w {
        Wire::Named { name, .. } => out.push(name),
        Wire::List { elem, .. } | Wire::ListField { elem, .. } => named(elem, out),
        _ => {}
    }
}

pub(super) fn bits_text(b: Bits) -> String {
    match b {
        Bits::Flag(n) => format!("bit {n}"),
        Bits::Range { lo, hi } => format!("bits [{lo}, {hi}]"),
    }
}

pub(super) fn pv_text(p: Option<Int>) -> &'static str {
    p.map_or("none", Int::rust)
}

pub(super) fn opt_text(o: &Option<String>) -> String {
    o.as_deref()
        .map_or("none".to_string(), |s| format!("`{s}`"))
}

/// Positions of a list's items in their longest run that kept its relative order
/// (a longest increasing subsequence of new positions taken in old order).
pub(super) fn kept_order(seq: &[usize]) -> BTreeSet<usize> {
    let n = seq.len();
    let mut len = vec![1usize; n];
    let mut prev = vec![usize::MAX; n];
    for i in 0..n {
        for j in 0..i {
            if seq[j] < seq[i] && len[j] + 1 > len[i] {
                len[i] = len[j] + 1;
                prev[i] = j;
            }
        }
    }
    let mut kept = BTreeSet::new();
    let Some(mut i) = (0..n).max_by_key(|&i| (len[i], std::cmp::Reverse(i))) else {
        return kept;
    };
    loop {
        kept.insert(seq[i]);
        if prev[i] == usize::MAX {
            break;
        }
        i = prev[i];
    }
    kept
}

/// Where `name` is in a component's list, if it is there.
pub(super) fn has<'l>(l: &'l [Entry], name: &str) -> Option<&'l Loc> {
    l.iter().find(|e| e.name == name).map(|e| &e.at)
}

/// Two lists of named items paired: by name first; then each old item whose name is
/// gone with the first new item whose name is new and that `same` says is the same thing
/// under another name (a renamed message with its code, an enum number reused).
pub(super) struct Paired<'a, T> {
    /// (old, new, paired by `same` rather than by name).
    pub(super) both: Vec<(&'a T, &'a T, bool)>,
    pub(super) removed: Vec<&'a T>,
    pub(super) added: Vec<&'a T>,
}

pub(super) fn pair<'a, T>(
    old: &'a [T],
    new: &'a [T],
    name: impl Fn(&T) -> &str,
    same: impl Fn(&T, &T) -> bool,
) -> Paired<'a, T> {
    let old_names: BTreeSet<&str> = old.iter().map(&name).collect();
    let mut taken = vec![false; new.len()];
    let mut both = Vec::new();
    let mut removed = Vec::new();
    for o in old {
        let by_name = new.iter().position(|n| name(n) == name(o));
        let other = by_name.map(|k| (k, false)).or_else(|| {
            (0..new.len())
                .find(|&k| !taken[k] && !old_names.contains(name(&new[k])) && same(o, &new[k]))
                .map(|k| (k, true))
        });
        match other {
            Some((k, by_same)) => {
                taken[k] = true;
                both.push((o, &new[k], by_same));
            }
            None => removed.push(o),
        }
    }
    let added = new
        .iter()
        .zip(&taken)
        .filter(|(_, t)| !**t)
        .map(|(n, _)| n)
        .collect();
    Paired {
        both,
        removed,
        added,
    }
}

/// Whether a field of this form takes the rest of the body.
pub(super) fn runs_to_end(w: &Wire) -> bool {
    matches!(
        w,
        Wire::Str(jaus_spec::Len::Rest { .. })
            | Wire::Bytes(jaus_spec::Len::Rest { .. })
            | Wire::List { count: None, .. }
    )
}

/// What a field comparison works on: one side of a message or record.
pub(super) struct Body<'b> {
    pub(super) presence: Option<Int>,
    pub(super) fields: &'b [FieldSnap],
    pub(super) at: &'b Loc,
}
