//! Changes between two revisions of a definition set, each classified on a three-level
//! scale (the rules are in `docs/spec-revisions.md` of the repository and in the crate
//! documentation).
//!
//! ```
//! use jaus_gen::diff::{diff, Severity};
//! use jaus_gen::snapshot::Snapshot;
//!
//! let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).unwrap();
//! let snap = Snapshot::from_spec(&spec);
//! let d = diff(&snap, &snap);
//! assert!(d.changes.is_empty());
//! assert!(!d.fails(Severity::WireBreaking));
//! ```

use crate::lock::type_body;
use crate::snapshot::*;
use jaus_spec::{Bits, Int, Wire};
use serde::Serialize;
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::fmt::{self, Write as _};

/// How serious a change is, from least to most.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// Peers built from either revision interoperate and vendor code still compiles.
    Compatible,
    /// Same bytes on the wire, but code written against the old revision may no longer
    /// compile (a renamed message, field, type or mode).
    SourceBreaking,
    /// Peers built from the two revisions may misread or reject each other's packets,
    /// or no longer serve each other.
    WireBreaking,
}

impl Severity {
    /// `compatible`, `source-breaking` or `wire-breaking`.
    pub fn as_str(self) -> &'static str {
        match self {
            Severity::Compatible => "compatible",
            Severity::SourceBreaking => "source-breaking",
            Severity::WireBreaking => "wire-breaking",
        }
    }

    /// Reads [`Severity::as_str`] back.
    pub fn parse(s: &str) -> Option<Severity> {
        Some(match s {
            "compatible" => Severity::Compatible,
            "source-breaking" => Severity::SourceBreaking,
            "wire-breaking" => Severity::WireBreaking,
            _ => return None,
        })
    }
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

macro_rules! kinds {
    ($($(#[$doc:meta])* $v:ident = $s:literal,)*) => {
        /// What changed. [`ChangeKind::as_str`] is the stable name used in the JSON output.
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub enum ChangeKind {
            $($(#[$doc])* $v,)*
        }
        impl ChangeKind {
            /// Every kind, in declaration order.
            pub const ALL: &'static [ChangeKind] = &[$(ChangeKind::$v,)*];
            /// The stable name, e.g. `field-scale-changed`.
            pub fn as_str(self) -> &'static str {
                match self { $(ChangeKind::$v => $s,)* }
            }
        }
    };
}

kinds! {
    /// A new message.
    MessageAdded = "message-added",
    /// A message is gone.
    MessageRemoved = "message-removed",
    /// A message kept its name and changed its command code.
    MessageCodeChanged = "message-code-changed",
    /// A command code now has another message name.
    MessageRenamed = "message-renamed",
    /// The presence vector of a message or record changed type, appeared or went.
    PresenceChanged = "presence-changed",
    /// A new field.
    FieldAdded = "field-added",
    /// A field is gone.
    FieldRemoved = "field-removed",
    /// A field changed its place relative to the others.
    FieldMoved = "field-moved",
    /// A field at the same place with the same wire form has another name.
    FieldRenamed = "field-renamed",
    /// A field's wire type changed.
    FieldTypeChanged = "field-type-changed",
    /// The limits of a scaled value changed.
    FieldScaleChanged = "field-scale-changed",
    /// The integer carrying a scaled value changed.
    FieldScaleIntChanged = "field-scale-int-changed",
    /// The unit of a value changed.
    FieldUnitChanged = "field-unit-changed",
    /// A field's presence bit changed, appeared or went.
    FieldBitChanged = "field-bit-changed",
    /// The field a value is present by (`present_if`) changed.
    FieldPresentIfChanged = "field-present-if-changed",
    /// A list's count prefix or count field changed.
    FieldCountChanged = "field-count-changed",
    /// A string's or blob's length, or a value's size prefix, changed.
    FieldLengthChanged = "field-length-changed",
    /// A new named type.
    TypeAdded = "type-added",
    /// A named type is gone.
    TypeRemoved = "type-removed",
    /// A named type has another name and the same layout.
    TypeRenamed = "type-renamed",
    /// A named type changed kind (record, enum, bit field, union).
    TypeKindChanged = "type-kind-changed",
    /// An enumeration's integer type changed.
    EnumReprChanged = "enum-repr-changed",
    /// A new enumeration value.
    EnumValueAdded = "enum-value-added",
    /// An enumeration value is gone.
    EnumValueRemoved = "enum-value-removed",
    /// An enumeration value kept its name and changed its number.
    EnumValueChanged = "enum-value-changed",
    /// A number now has another name.
    EnumValueReused = "enum-value-reused",
    /// A bit field's integer type changed.
    BitfieldReprChanged = "bitfield-repr-changed",
    /// A new bit-field member.
    BitsAdded = "bits-added",
    /// A bit-field member is gone.
    BitsRemoved = "bits-removed",
    /// A bit-field member moved or changed width.
    BitsMoved = "bits-moved",
    /// A bit-field member with the same bits has another name.
    BitsRenamed = "bits-renamed",
    /// A union's tag type changed.
    UnionReprChanged = "union-repr-changed",
    /// A new union variant.
    VariantAdded = "variant-added",
    /// A union variant is gone.
    VariantRemoved = "variant-removed",
    /// A union variant changed its tag.
    VariantTagChanged = "variant-tag-changed",
    /// A union variant's value changed type.
    VariantTypeChanged = "variant-type-changed",
    /// A union variant with the same tag and value has another name.
    VariantRenamed = "variant-renamed",
    /// A new component interface.
    ComponentAdded = "component-added",
    /// A component interface is gone.
    ComponentRemoved = "component-removed",
    /// A component id now has another name.
    ComponentRenamed = "component-renamed",
    /// A component changed its id.
    ComponentIdChanged = "component-id-changed",
    /// `any_message` changed.
    ComponentAnyMessageChanged = "component-any-message-changed",
    /// A message was added to `commands`, `accepts` or `emits`.
    ComponentMessageAdded = "component-message-added",
    /// A message was removed from `commands`, `accepts` or `emits`.
    ComponentMessageRemoved = "component-message-removed",
    /// A message moved between `commands` and `accepts`.
    ComponentMessageMoved = "component-message-moved",
    /// A new mode.
    ComponentModeAdded = "component-mode-added",
    /// A mode is gone.
    ComponentModeRemoved = "component-mode-removed",
    /// The initial mode changed.
    ComponentInitialModeChanged = "component-initial-mode-changed",
    /// A new mode transition.
    ComponentTransitionAdded = "component-transition-added",
    /// A mode transition is gone.
    ComponentTransitionRemoved = "component-transition-removed",
    /// A mode transition's modes or core state changed.
    ComponentTransitionChanged = "component-transition-changed",
}

impl fmt::Display for ChangeKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// One change.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Change {
    /// What changed.
    pub kind: ChangeKind,
    /// How serious it is.
    pub severity: Severity,
    /// The item: `Message`, `Message.field`, `Type.value`, `Component.accepts.Message`,
    /// `Component.modes.Mode`.
    pub path: String,
    /// Where it was in the old revision (or where its owner was, for something added);
    /// `None` for a message, type or component that is new.
    pub old: Option<Loc>,
    /// Where it is in the new revision (or where its owner is, for something removed);
    /// `None` for a message, type or component that is gone.
    pub new: Option<Loc>,
    /// What changed, old → new.
    pub detail: String,
    /// For a change inside a named type: the messages that use the type, directly or
    /// through other types.
    pub used_by: Vec<String>,
}

/// Every change between two revisions, sorted: most severe first, then by item and
/// position.
#[derive(Debug, Clone, Default)]
pub struct Diff {
    /// The changes.
    pub changes: Vec<Change>,
}

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
        let mut s = serde_json::to_string_pretty(&v).expect("changes serialise");
        s.push('\n');
        s
    }
}

/// Every change from `old` to `new`, classified.
pub fn diff(old: &Snapshot, new: &Snapshot) -> Diff {
    let mut d = Differ {
        old,
        new,
        renames: HashMap::new(),
        users: BTreeMap::new(),
        changes: Vec::new(),
    };
    d.users(old);
    d.users(new);
    d.types();
    d.messages();
    d.components();
    let mut changes = d.changes;
    changes.sort_by(|a, b| {
        let pos = |c: &Change| c.new.clone().or_else(|| c.old.clone());
        let top = |c: &Change| c.path.split('.').next().unwrap_or("").to_string();
        b.severity
            .cmp(&a.severity)
            .then_with(|| top(a).cmp(&top(b)))
            .then_with(|| {
                let (pa, pb) = (pos(a), pos(b));
                (pa.as_ref().map(|l| (l.line, l.col)), &a.path, a.kind).cmp(&(
                    pb.as_ref().map(|l| (l.line, l.col)),
                    &b.path,
                    b.kind,
                ))
            })
    });
    Diff { changes }
}

struct Differ<'a> {
    old: &'a Snapshot,
    new: &'a Snapshot,
    /// Types renamed: old name → new name.
    renames: HashMap<String, String>,
    /// Messages using each type (by name, in either revision).
    users: BTreeMap<String, BTreeSet<String>>,
    changes: Vec<Change>,
}

/// The named types a wire form refers to.
fn named<'w>(w: &'w Wire, out: &mut Vec<&'w str>) {
    match w {
        Wire::Named { name, .. } => out.push(name),
        Wire::List { elem, .. } | Wire::ListField { elem, .. } => named(elem, out),
        _ => {}
    }
}

fn bits_text(b: Bits) -> String {
    match b {
        Bits::Flag(n) => format!("bit {n}"),
        Bits::Range { lo, hi } => format!("bits [{lo}, {hi}]"),
    }
}

fn pv_text(p: Option<Int>) -> &'static str {
    p.map_or("none", Int::rust)
}

fn opt_text(o: &Option<String>) -> String {
    o.as_deref()
        .map_or("none".to_string(), |s| format!("`{s}`"))
}

/// Positions of a list's items in their longest run that kept its relative order
/// (a longest increasing subsequence of new positions taken in old order).
fn kept_order(seq: &[usize]) -> BTreeSet<usize> {
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
fn has<'l>(l: &'l [Entry], name: &str) -> Option<&'l Loc> {
    l.iter().find(|e| e.name == name).map(|e| &e.at)
}

/// Two lists of named items paired: by name first; then each old item whose name is
/// gone with the first new item whose name is new and that `same` says is the same thing
/// under another name (a renamed message with its code, an enum number reused).
struct Paired<'a, T> {
    /// (old, new, paired by `same` rather than by name).
    both: Vec<(&'a T, &'a T, bool)>,
    removed: Vec<&'a T>,
    added: Vec<&'a T>,
}

fn pair<'a, T>(
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

/// What a field comparison works on: one side of a message or record.
struct Body<'b> {
    presence: Option<Int>,
    fields: &'b [FieldSnap],
    at: &'b Loc,
}

impl Differ<'_> {
    // One argument per field of a Change: a builder would be longer at every call site.
    #[allow(clippy::too_many_arguments)]
    fn push(
        &mut self,
        kind: ChangeKind,
        severity: Severity,
        path: String,
        old: Option<&Loc>,
        new: Option<&Loc>,
        detail: String,
        used_by: &[String],
    ) {
        self.changes.push(Change {
            kind,
            severity,
            path,
            old: old.cloned(),
            new: new.cloned(),
            detail,
            used_by: used_by.to_vec(),
        });
    }

    /// Records which messages use which types in `s`.
    fn users(&mut self, s: &Snapshot) {
        let by_name: HashMap<&str, &TypeSnap> =
            s.types.iter().map(|t| (t.name.as_str(), t)).collect();
        for m in &s.messages {
            let mut todo = Vec::new();
            for f in &m.fields {
                named(&f.wire, &mut todo);
            }
            let mut seen = BTreeSet::new();
            while let Some(t) = todo.pop() {
                if !seen.insert(t) {
                    continue;
                }
                self.users
                    .entry(t.to_string())
                    .or_default()
                    .insert(m.name.clone());
                match by_name.get(t).map(|t| &t.form) {
                    Some(FormSnap::Record { fields, .. }) => {
                        for f in fields {
                            named(&f.wire, &mut todo);
                        }
                    }
                    Some(FormSnap::Union { variants, .. }) => {
                        for w in variants.iter().filter_map(|v| v.wire.as_ref()) {
                            named(w, &mut todo);
                        }
                    }
                    _ => {}
                }
            }
        }
    }

    fn users_of(&self, old: &str, new: &str) -> Vec<String> {
        let mut u: BTreeSet<String> = BTreeSet::new();
        for n in [old, new] {
            if let Some(s) = self.users.get(n) {
                u.extend(s.iter().cloned());
            }
        }
        u.into_iter().collect()
    }

    /// Wire forms equal up to renamed types (a type's kind change is reported at the
    /// type).
    fn wire_eq(&self, o: &Wire, n: &Wire) -> bool {
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

    /// What differs between two wire forms: (kind, detail).
    fn wire_changes(&self, o: &Wire, n: &Wire, prefix: &str, out: &mut Vec<(ChangeKind, String)>) {
        if self.wire_eq(o, n) {
            return;
        }
        match (o, n) {
            (
                Wire::Scaled {
                    int: oi,
                    lo: ol,
                    hi: oh,
                },
                Wire::Scaled {
                    int: ni,
                    lo: nl,
                    hi: nh,
                },
            ) => {
                if oi != ni {
                    out.push((
                        ChangeKind::FieldScaleIntChanged,
                        format!("{prefix}scaled integer {} → {}", oi.rust(), ni.rust()),
                    ));
                }
                if (ol, oh) != (nl, nh) {
                    out.push((
                        ChangeKind::FieldScaleChanged,
                        format!("{prefix}scale [{ol}, {oh}] → [{nl}, {nh}]"),
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
                self.wire_changes(ea, eb, &format!("{prefix}element: "), out);
            }
            _ => out.push((
                ChangeKind::FieldTypeChanged,
                format!("{prefix}{} → {}", wire_text(o), wire_text(n)),
            )),
        }
    }

    /// Compares the fields of a message (`in_message`) or record named `owner`.
    fn fields(
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
            self.wire_changes(&f.wire, &g.wire, "", &mut wc);
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
                        "added at the end under new presence bit {} ({}): older decoders skip it",
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

    fn messages(&mut self) {
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
                format!("added (0x{:04X})", n.code),
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

    fn types(&mut self) {
        use ChangeKind::*;
        use Severity::*;
        let p = pair(
            &self.old.types,
            &self.new.types,
            |t| &t.name,
            |a, b| type_body(&a.form) == type_body(&b.form),
        );
        for (t, n, renamed) in &p.both {
            if *renamed {
                self.renames.insert(t.name.clone(), n.name.clone());
            }
        }
        for t in p.removed {
            let users = self.users_of(&t.name, &t.name);
            self.push(
                TypeRemoved,
                SourceBreaking,
                t.name.clone(),
                Some(&t.at),
                None,
                format!(
                    "{} removed (its uses are reported where they changed)",
                    kind_name(t.form.kind())
                ),
                &users,
            );
        }
        for n in p.added {
            let users = self.users_of(&n.name, &n.name);
            self.push(
                TypeAdded,
                Compatible,
                n.name.clone(),
                None,
                Some(&n.at),
                format!("{} added", kind_name(n.form.kind())),
                &users,
            );
        }
        for (t, n, _) in p.both {
            let users = self.users_of(&t.name, &n.name);
            let at = (Some(&t.at), Some(&n.at));
            if t.name != n.name {
                self.push(
                    TypeRenamed,
                    SourceBreaking,
                    n.name.clone(),
                    at.0,
                    at.1,
                    format!("renamed {} → {} (same layout)", t.name, n.name),
                    &users,
                );
                continue;
            }
            let path = n.name.clone();
            match (&t.form, &n.form) {
                (
                    FormSnap::Record {
                        presence: op,
                        fields: of,
                    },
                    FormSnap::Record {
                        presence: np,
                        fields: nf,
                    },
                ) => self.fields(
                    &path,
                    false,
                    Body {
                        presence: *op,
                        fields: of,
                        at: &t.at,
                    },
                    Body {
                        presence: *np,
                        fields: nf,
                        at: &n.at,
                    },
                    &users,
                ),
                (
                    FormSnap::Enum {
                        repr: or,
                        values: ov,
                    },
                    FormSnap::Enum {
                        repr: nr,
                        values: nv,
                    },
                ) => {
                    if or != nr {
                        self.push(
                            EnumReprChanged,
                            WireBreaking,
                            path.clone(),
                            at.0,
                            at.1,
                            format!("repr {} → {}", or.rust(), nr.rust()),
                            &users,
                        );
                    }
                    self.enum_values(&path, t, n, ov, nv, &users);
                }
                (
                    FormSnap::Bitfield {
                        repr: or,
                        members: om,
                    },
                    FormSnap::Bitfield {
                        repr: nr,
                        members: nm,
                    },
                ) => {
                    if or != nr {
                        self.push(
                            BitfieldReprChanged,
                            WireBreaking,
                            path.clone(),
                            at.0,
                            at.1,
                            format!("repr {} → {}", or.rust(), nr.rust()),
                            &users,
                        );
                    }
                    self.members(&path, t, n, om, nm, &users);
                }
                (
                    FormSnap::Union {
                        repr: or,
                        variants: ov,
                    },
                    FormSnap::Union {
                        repr: nr,
                        variants: nv,
                    },
                ) => {
                    if or != nr {
                        self.push(
                            UnionReprChanged,
                            WireBreaking,
                            path.clone(),
                            at.0,
                            at.1,
                            format!("tag {} → {}", or.rust(), nr.rust()),
                            &users,
                        );
                    }
                    self.variants(&path, t, n, ov, nv, &users);
                }
                (a, b) => self.push(
                    TypeKindChanged,
                    WireBreaking,
                    path,
                    at.0,
                    at.1,
                    format!("{} → {}", kind_name(a.kind()), kind_name(b.kind())),
                    &users,
                ),
            }
        }
    }

    fn enum_values(
        &mut self,
        path: &str,
        t: &TypeSnap,
        n: &TypeSnap,
        ov: &[ValueSnap],
        nv: &[ValueSnap],
        users: &[String],
    ) {
        use ChangeKind::*;
        use Severity::*;
        let p = pair(ov, nv, |v| &v.name, |a, b| a.value == b.value);
        for (v, w, reused) in p.both {
            if reused {
                self.push(
                    EnumValueReused,
                    WireBreaking,
                    format!("{path}.{}", w.name),
                    Some(&v.at),
                    Some(&w.at),
                    format!("value {} was {}, now {}", v.value, v.name, w.name),
                    users,
                );
            } else if w.value != v.value {
                self.push(
                    EnumValueChanged,
                    WireBreaking,
                    format!("{path}.{}", v.name),
                    Some(&v.at),
                    Some(&w.at),
                    format!("value {} → {}", v.value, w.value),
                    users,
                );
            }
        }
        for v in p.removed {
            self.push(
                EnumValueRemoved,
                WireBreaking,
                format!("{path}.{}", v.name),
                Some(&v.at),
                Some(&n.at),
                format!("value {} removed", v.value),
                users,
            );
        }
        for w in p.added {
            match ov.iter().find(|v| v.value == w.value) {
                Some(v) => self.push(
                    EnumValueReused,
                    WireBreaking,
                    format!("{path}.{}", w.name),
                    Some(&v.at),
                    Some(&w.at),
                    format!(
                        "value {} was {} (moved away), now {}",
                        w.value, v.name, w.name
                    ),
                    users,
                ),
                None => self.push(
                    EnumValueAdded,
                    Compatible,
                    format!("{path}.{}", w.name),
                    Some(&t.at),
                    Some(&w.at),
                    format!(
                        "value {} added (older decoders keep it as Unknown({}))",
                        w.value, w.value
                    ),
                    users,
                ),
            }
        }
    }

    fn members(
        &mut self,
        path: &str,
        t: &TypeSnap,
        n: &TypeSnap,
        om: &[MemberSnap],
        nm: &[MemberSnap],
        users: &[String],
    ) {
        use ChangeKind::*;
        use Severity::*;
        let p = pair(om, nm, |m| &m.name, |a, b| a.bits == b.bits);
        for (m, w, renamed) in p.both {
            if renamed {
                self.push(
                    BitsRenamed,
                    SourceBreaking,
                    format!("{path}.{}", w.name),
                    Some(&m.at),
                    Some(&w.at),
                    format!(
                        "renamed `{}` → `{}` ({})",
                        m.name,
                        w.name,
                        bits_text(w.bits)
                    ),
                    users,
                );
            } else if w.bits != m.bits {
                self.push(
                    BitsMoved,
                    WireBreaking,
                    format!("{path}.{}", m.name),
                    Some(&m.at),
                    Some(&w.at),
                    format!("{} → {}", bits_text(m.bits), bits_text(w.bits)),
                    users,
                );
            }
        }
        for m in p.removed {
            self.push(
                BitsRemoved,
                WireBreaking,
                format!("{path}.{}", m.name),
                Some(&m.at),
                Some(&n.at),
                format!("{} removed", bits_text(m.bits)),
                users,
            );
        }
        for w in p.added {
            let (lo, hi) = bit_range(w.bits);
            let overlap = om.iter().find(|m| {
                let (a, b) = bit_range(m.bits);
                a <= hi && lo <= b
            });
            let (sev, detail) = match overlap {
                None => (
                    Compatible,
                    format!(
                        "{} added in unused bits (older decoders keep them as reserved)",
                        bits_text(w.bits)
                    ),
                ),
                Some(m) => (
                    WireBreaking,
                    format!(
                        "{} added over `{}`'s old {}",
                        bits_text(w.bits),
                        m.name,
                        bits_text(m.bits)
                    ),
                ),
            };
            self.push(
                BitsAdded,
                sev,
                format!("{path}.{}", w.name),
                Some(&t.at),
                Some(&w.at),
                detail,
                users,
            );
        }
    }

    fn variants(
        &mut self,
        path: &str,
        t: &TypeSnap,
        n: &TypeSnap,
        ov: &[VariantSnap],
        nv: &[VariantSnap],
        users: &[String],
    ) {
        use ChangeKind::*;
        use Severity::*;
        let same_value = |a: &Option<Wire>, b: &Option<Wire>| match (a, b) {
            (Some(a), Some(b)) => self.wire_eq(a, b),
            (None, None) => true,
            _ => false,
        };
        let text = |w: &Option<Wire>| w.as_ref().map_or("no value".to_string(), wire_text);
        let p = pair(
            ov,
            nv,
            |v| &v.name,
            |a, b| a.tag == b.tag && same_value(&a.wire, &b.wire),
        );
        let mut changes = Vec::new();
        for (v, w, renamed) in p.both {
            let at = (Some(&v.at), Some(&w.at));
            if renamed {
                changes.push((
                    VariantRenamed,
                    SourceBreaking,
                    &w.name,
                    at,
                    format!("renamed {} → {} (tag {})", v.name, w.name, w.tag),
                ));
                continue;
            }
            if w.tag != v.tag {
                changes.push((
                    VariantTagChanged,
                    WireBreaking,
                    &w.name,
                    at,
                    format!("tag {} → {}", v.tag, w.tag),
                ));
            }
            if !same_value(&v.wire, &w.wire) {
                changes.push((
                    VariantTypeChanged,
                    WireBreaking,
                    &w.name,
                    at,
                    format!("{} → {}", text(&v.wire), text(&w.wire)),
                ));
            }
        }
        for v in p.removed {
            changes.push((
                VariantRemoved,
                WireBreaking,
                &v.name,
                (Some(&v.at), Some(&n.at)),
                format!("tag {} removed", v.tag),
            ));
        }
        for w in p.added {
            changes.push((
                VariantAdded,
                WireBreaking,
                &w.name,
                (Some(&t.at), Some(&w.at)),
                format!(
                    "tag {} added ({}): older decoders reject a value with an unknown tag",
                    w.tag,
                    text(&w.wire)
                ),
            ));
        }
        for (kind, sev, name, (o, n), detail) in changes {
            self.push(kind, sev, format!("{path}.{name}"), o, n, detail, users);
        }
    }

    fn components(&mut self) {
        use ChangeKind::*;
        use Severity::*;
        let p = pair(
            &self.old.components,
            &self.new.components,
            |c| &c.name,
            |a, b| a.id == b.id,
        );
        for c in p.removed {
            self.push(
                ComponentRemoved,
                WireBreaking,
                c.name.clone(),
                Some(&c.at),
                None,
                format!("component id {} removed: peers lose its services", c.id),
                &[],
            );
        }
        for n in p.added {
            self.push(
                ComponentAdded,
                Compatible,
                n.name.clone(),
                None,
                Some(&n.at),
                format!("component id {} added", n.id),
                &[],
            );
        }
        for (c, n, renamed) in p.both {
            let at = (Some(&c.at), Some(&n.at));
            if renamed {
                self.push(
                    ComponentRenamed,
                    SourceBreaking,
                    n.name.clone(),
                    at.0,
                    at.1,
                    format!("renamed {} → {} (same id {})", c.name, n.name, n.id),
                    &[],
                );
            }
            if c.id != n.id {
                self.push(
                    ComponentIdChanged,
                    WireBreaking,
                    n.name.clone(),
                    at.0,
                    at.1,
                    format!("component id {} → {}", c.id, n.id),
                    &[],
                );
            }
            if c.any_message != n.any_message {
                let sev = if n.any_message {
                    Compatible
                } else {
                    WireBreaking
                };
                self.push(
                    ComponentAnyMessageChanged,
                    sev,
                    n.name.clone(),
                    at.0,
                    at.1,
                    format!("any_message {} → {}", c.any_message, n.any_message),
                    &[],
                );
            }
            self.interface(c, n);
            self.modes(c, n);
        }
    }

    fn interface(&mut self, c: &ComponentSnap, n: &ComponentSnap) {
        use ChangeKind::*;
        use Severity::*;
        let lists = |x: &'_ ComponentSnap| {
            [
                ("commands", x.commands.clone()),
                ("accepts", x.accepts.clone()),
                ("emits", x.emits.clone()),
            ]
        };
        let (ol, nl) = (lists(c), lists(n));
        for (k, (key, olist)) in ol.iter().enumerate() {
            let nlist = &nl[k].1;
            for e in olist {
                // A component that now takes and sends every message still serves it.
                if has(nlist, &e.name).is_some() || n.any_message {
                    continue;
                }
                let path = format!("{}.{key}.{}", n.name, e.name);
                let moved = match *key {
                    "commands" => has(&n.accepts, &e.name).map(|at| {
                        (Compatible, at, "moved from commands to accepts: now executed from any sender".to_string())
                    }),
                    "accepts" => has(&n.commands, &e.name).map(|at| {
                        (WireBreaking, at, "moved from accepts to commands: now executed only from the component in control".to_string())
                    }),
                    _ => None,
                };
                match moved {
                    Some((sev, at, detail)) => self.push(
                        ComponentMessageMoved,
                        sev,
                        path,
                        Some(&e.at),
                        Some(at),
                        detail,
                        &[],
                    ),
                    None => {
                        let (sev, detail) = match *key {
                            "emits" => (
                                SourceBreaking,
                                format!(
                                    "no longer emitted: `Ctx::send` of {} no longer compiles",
                                    e.name
                                ),
                            ),
                            _ => (
                                WireBreaking,
                                format!(
                                    "removed from {key}: peers sending {} are no longer served",
                                    e.name
                                ),
                            ),
                        };
                        self.push(
                            ComponentMessageRemoved,
                            sev,
                            path,
                            Some(&e.at),
                            Some(&n.at),
                            detail,
                            &[],
                        )
                    }
                }
            }
            for e in nlist {
                // A component that took every message served this one already.
                if has(olist, &e.name).is_some() || c.any_message {
                    continue;
                }
                let moved = match *key {
                    "commands" => has(&c.accepts, &e.name).is_some(),
                    "accepts" => has(&c.commands, &e.name).is_some(),
                    _ => false,
                };
                if moved {
                    continue;
                }
                self.push(
                    ComponentMessageAdded,
                    Compatible,
                    format!("{}.{key}.{}", n.name, e.name),
                    Some(&c.at),
                    Some(&e.at),
                    format!("added to {key}"),
                    &[],
                );
            }
        }
    }

    fn modes(&mut self, c: &ComponentSnap, n: &ComponentSnap) {
        use ChangeKind::*;
        use Severity::*;
        let empty = Vec::new();
        let (os, ns) = (
            c.modes.as_ref().map_or(&empty, |m| &m.states),
            n.modes.as_ref().map_or(&empty, |m| &m.states),
        );
        let (ot, nt) = (
            c.modes.as_ref().map_or(&[][..], |m| &m.transitions[..]),
            n.modes.as_ref().map_or(&[][..], |m| &m.transitions[..]),
        );
        let base = format!("{}.modes", n.name);
        let tbase = format!("{}.transitions", n.name);
        if let (Some(a), Some(b)) = (&c.modes, &n.modes) {
            if a.initial.name != b.initial.name {
                self.push(
                    ComponentInitialModeChanged,
                    SourceBreaking,
                    base.clone(),
                    Some(&a.initial.at),
                    Some(&b.initial.at),
                    format!("initial mode {} → {}", a.initial.name, b.initial.name),
                    &[],
                );
            }
        }
        for s in os {
            if !ns.iter().any(|x| x.name == s.name) {
                self.push(
                    ComponentModeRemoved,
                    SourceBreaking,
                    format!("{base}.{}", s.name),
                    Some(&s.at),
                    Some(&n.at),
                    "mode removed".into(),
                    &[],
                );
            }
        }
        for s in ns {
            if !os.iter().any(|x| x.name == s.name) {
                self.push(
                    ComponentModeAdded,
                    SourceBreaking,
                    format!("{base}.{}", s.name),
                    Some(&c.at),
                    Some(&s.at),
                    "mode added (a new variant of the generated `Mode` enum)".into(),
                    &[],
                );
            }
        }
        let tt = |t: &TransitionSnap| {
            format!(
                "from [{}] to {}{}",
                t.from.join(", "),
                t.to,
                t.core
                    .as_deref()
                    .map_or(String::new(), |c| format!(" (core {c})"))
            )
        };
        for t in ot {
            match nt.iter().find(|x| x.name == t.name) {
                Some(u) => {
                    if tt(t) != tt(u) {
                        self.push(
                            ComponentTransitionChanged,
                            SourceBreaking,
                            format!("{tbase}.{}", t.name),
                            Some(&t.at),
                            Some(&u.at),
                            format!("{} → {}", tt(t), tt(u)),
                            &[],
                        );
                    }
                }
                None => self.push(
                    ComponentTransitionRemoved,
                    SourceBreaking,
                    format!("{tbase}.{}", t.name),
                    Some(&t.at),
                    Some(&n.at),
                    format!(
                        "transition {} removed (a variant of the generated `Transition` enum)",
                        tt(t)
                    ),
                    &[],
                ),
            }
        }
        for u in nt {
            if !ot.iter().any(|x| x.name == u.name) {
                self.push(
                    ComponentTransitionAdded,
                    SourceBreaking,
                    format!("{tbase}.{}", u.name),
                    Some(&c.at),
                    Some(&u.at),
                    format!(
                        "transition {} added (a new variant of the generated `Transition` enum)",
                        tt(u)
                    ),
                    &[],
                );
            }
        }
    }
}

/// Whether a field of this form takes the rest of the body.
fn runs_to_end(w: &Wire) -> bool {
    matches!(
        w,
        Wire::Str(jaus_spec::Len::Rest { .. })
            | Wire::Bytes(jaus_spec::Len::Rest { .. })
            | Wire::List { count: None, .. }
    )
}
