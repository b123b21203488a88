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

mod components;
mod fields;
mod pair;
mod report;
mod scale;
mod services;
mod types;

use crate::snapshot::*;
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::fmt;

use pair::named;

/// How serious a change is, from least to most.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Severity {
    /// Peers built from either revision interoperate, and vendor code written against
    /// the old revision in the forward-compatible style still compiles: struct literals
    /// and patterns of generated types end with `..` (`..Default::default()`), and a
    /// `match` on a generated enum or on `Message` has a `_` arm. (Rust gives no way
    /// to add a field or a variant that code listing all of them survives: such code
    /// breaks, and the change's detail says so.)
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
    /// A new service.
    ServiceAdded = "service-added",
    /// A service is gone.
    ServiceRemoved = "service-removed",
    /// A service's URI and version now have another name.
    ServiceRenamed = "service-renamed",
    /// A service changed its version (or URI).
    ServiceVersionChanged = "service-version-changed",
    /// A service inherits from another service, another version, or nothing.
    ServiceParentChanged = "service-parent-changed",
    /// A new state of a service's machine.
    ServiceStateAdded = "service-state-added",
    /// A state of a service's machine is gone.
    ServiceStateRemoved = "service-state-removed",
    /// A state has another name and the same actions and transitions.
    ServiceStateRenamed = "service-state-renamed",
    /// A state's entry or exit actions changed.
    ServiceStateActionsChanged = "service-state-actions-changed",
    /// A new transition.
    ServiceTransitionAdded = "service-transition-added",
    /// A transition is gone.
    ServiceTransitionRemoved = "service-transition-removed",
    /// The same transition (trigger, guard, actions, target) is in another state.
    ServiceTransitionMoved = "service-transition-moved",
    /// A transition is started by another trigger.
    ServiceTriggerChanged = "service-trigger-changed",
    /// A transition's guard changed, appeared or went.
    ServiceGuardChanged = "service-guard-changed",
    /// A transition's actions changed.
    ServiceActionsChanged = "service-actions-changed",
    /// A transition's kind or target state changed.
    ServiceTargetChanged = "service-target-changed",
    /// A new guard or action method of a service's generated trait.
    ServiceMethodAdded = "service-method-added",
    /// A guard or action method of a service's generated trait is gone.
    ServiceMethodRemoved = "service-method-removed",
    /// A method of a service's generated trait changed its signature.
    ServiceMethodChanged = "service-method-changed",
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
    /// `Component.modes.Mode`, `Service`, `Service/Machine/State.Sub`,
    /// `Service::method`.
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
    d.services();
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
}
