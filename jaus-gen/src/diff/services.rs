//! Services (AS-4 service sets): the services themselves, their parents, the states and
//! transitions of their machines, and the methods of their generated traits.
//!
//! A transition is known by its state, its trigger and the trigger's parameter types;
//! several with the same key (one trigger, different guards) are paired by equal
//! definitions first, then by equal guards, then in order. A state is renamed when a
//! state of the same machine and parent went and one came with the same entry and exit
//! actions and the same transitions.

use super::pair::pair;
use super::{ChangeKind, Differ, Severity};
use crate::snapshot::*;
use std::collections::BTreeMap;

/// The methods' consequences for a vendor's implementation of the trait.
const ADDED: &str = "a vendor's implementation of the trait no longer compiles \
                     (E0046: not all trait items implemented)";
const REMOVED: &str = "a vendor's implementation that defines it no longer compiles \
                       (E0407: method is not a member of the trait)";

/// The trigger as shown: message parameters only (`on events.transport.Receive(RequestControl)`),
/// without the field paths of the transport data that every received message carries.
fn trigger(t: &TransSnap) -> String {
    let shown: Vec<&str> = t
        .params
        .iter()
        .filter(|p| !p.contains('.'))
        .map(String::as_str)
        .collect();
    match &t.on {
        Some(on) if shown.is_empty() => format!("on {on}"),
        Some(on) => format!("on {on}({})", shown.join(", ")),
        None => "any trigger".into(),
    }
}

fn guard_text(g: &Option<String>) -> String {
    g.as_deref()
        .map_or("no guard".to_string(), |g| format!("[{g}]"))
}

fn target_text(t: &TransSnap) -> String {
    match &t.to {
        Some(to) => format!("{} to {to}", t.kind),
        None => t.kind.clone(),
    }
}

fn list_text(v: &[String]) -> String {
    if v.is_empty() {
        "none".into()
    } else {
        v.join("; ")
    }
}

/// A transition's definition apart from where it is: guard, kind, target, actions.
type Body<'t> = (
    &'t Option<String>,
    &'t str,
    &'t Option<String>,
    &'t [String],
);

/// Whether two transitions of the same key are paired in one pass.
type Same = dyn Fn(&TransSnap, &TransSnap) -> bool;

/// What makes two transitions the same.
fn body(t: &TransSnap) -> Body<'_> {
    (&t.guard, &t.kind, &t.to, &t.actions)
}

/// The transitions out of state `path` (and its default state), by trigger.
fn out_of<'s>(s: &'s ServiceSnap, path: &str) -> Vec<(String, Body<'s>)> {
    let default = format!("{path} (default)");
    let mut v: Vec<_> = s
        .transitions
        .iter()
        .filter(|t| t.state == path || t.state == default)
        .map(|t| (trigger(t), body(t)))
        .collect();
    v.sort();
    v
}

/// The state `path` of the old revision under its new name.
fn renamed(path: &str, renames: &BTreeMap<String, String>) -> String {
    for (old, new) in renames {
        if path == old {
            return new.clone();
        }
        if let Some(rest) = path.strip_prefix(old.as_str()) {
            if rest.starts_with('.') || rest.starts_with(' ') {
                return format!("{new}{rest}");
            }
        }
    }
    path.to_string()
}

/// The machine and the parent path of a state (`M/A.B.C` → `M/A.B`).
fn parent_of(path: &str) -> &str {
    match path.rfind(['.', '/']) {
        Some(i) => &path[..i],
        None => "",
    }
}

impl Differ<'_> {
    pub(super) fn services(&mut self) {
        use ChangeKind::*;
        use Severity::*;
        let p = pair(
            &self.old.services,
            &self.new.services,
            |s| &s.name,
            |a, b| a.id == b.id && a.version == b.version,
        );
        for s in p.removed {
            self.push(
                ServiceRemoved,
                WireBreaking,
                s.name.clone(),
                Some(&s.at),
                None,
                format!("service {} {} removed: peers lose it", s.id, s.version),
                &[],
            );
        }
        for n in p.added {
            self.push(
                ServiceAdded,
                Compatible,
                n.name.clone(),
                None,
                Some(&n.at),
                format!(
                    "service {} {} added ({} states, {} transitions, {} trait methods)",
                    n.id,
                    n.version,
                    n.states.len(),
                    n.transitions.len(),
                    n.methods.len()
                ),
                &[],
            );
        }
        for (o, n, by_id) in p.both {
            if by_id {
                self.push(
                    ServiceRenamed,
                    SourceBreaking,
                    n.name.clone(),
                    Some(&o.at),
                    Some(&n.at),
                    format!(
                        "renamed {} → {} (same {} {}): its trait is renamed",
                        o.name, n.name, n.id, n.version
                    ),
                    &[],
                );
            }
            self.service(o, n);
        }
    }

    fn service(&mut self, o: &ServiceSnap, n: &ServiceSnap) {
        use ChangeKind::*;
        use Severity::*;
        let (oa, na) = (Some(&o.at), Some(&n.at));
        if o.id != n.id || o.version != n.version {
            let major = |v: &str| v.split('.').next().unwrap_or("").to_string();
            let sev = if o.id != n.id || major(&o.version) != major(&n.version) {
                WireBreaking
            } else {
                Compatible
            };
            self.push(
                ServiceVersionChanged,
                sev,
                n.name.clone(),
                oa,
                na,
                format!("{} {} → {} {}", o.id, o.version, n.id, n.version),
                &[],
            );
        }
        if o.inherits != n.inherits {
            let id = |s: &Option<String>| {
                s.as_deref()
                    .map(|x| x.split(' ').next().unwrap_or("").to_string())
            };
            let (sev, why) = if id(&o.inherits) == id(&n.inherits) {
                (
                    SourceBreaking,
                    "another version of the parent: the inherited machines and supertrait follow it",
                )
            } else {
                (
                    WireBreaking,
                    "another parent: the inherited messages, machines and supertrait change",
                )
            };
            let t = |s: &Option<String>| s.clone().unwrap_or_else(|| "nothing".into());
            self.push(
                ServiceParentChanged,
                sev,
                n.name.clone(),
                oa,
                na,
                format!("inherits {} → {}: {why}", t(&o.inherits), t(&n.inherits)),
                &[],
            );
        }
        let renames = self.states(o, n);
        self.transitions(o, n, &renames);
        self.methods(o, n);
    }

    /// States added, removed, renamed or with other entry or exit actions; the renames,
    /// old path → new path.
    fn states(&mut self, o: &ServiceSnap, n: &ServiceSnap) -> BTreeMap<String, String> {
        use ChangeKind::*;
        use Severity::*;
        let same = |a: &StateSnap, b: &StateSnap| {
            parent_of(&a.path) == parent_of(&b.path)
                && a.entry == b.entry
                && a.exit == b.exit
                && out_of(o, &a.path) == out_of(n, &b.path)
                && !out_of(o, &a.path).is_empty()
        };
        let p = pair(&o.states, &n.states, |s| &s.path, same);
        let mut renames = BTreeMap::new();
        for s in p.removed {
            self.push(
                ServiceStateRemoved,
                WireBreaking,
                format!("{}/{}", n.name, s.path),
                Some(&s.at),
                Some(&n.at),
                "state removed: what a peer got from the service in it is gone".into(),
                &[],
            );
        }
        for s in p.added {
            self.push(
                ServiceStateAdded,
                Compatible,
                format!("{}/{}", n.name, s.path),
                Some(&o.at),
                Some(&s.at),
                "state added".into(),
                &[],
            );
        }
        for (a, b, by_same) in p.both {
            let path = format!("{}/{}", n.name, b.path);
            if by_same {
                renames.insert(a.path.clone(), b.path.clone());
                self.push(
                    ServiceStateRenamed,
                    SourceBreaking,
                    path.clone(),
                    Some(&a.at),
                    Some(&b.at),
                    format!(
                        "renamed {} → {} (same actions and transitions): code naming the state by its path changes",
                        a.path, b.path
                    ),
                    &[],
                );
            }
            for (what, x, y) in [("entry", &a.entry, &b.entry), ("exit", &a.exit, &b.exit)] {
                if x != y {
                    self.push(
                        ServiceStateActionsChanged,
                        WireBreaking,
                        path.clone(),
                        Some(&a.at),
                        Some(&b.at),
                        format!("{what} actions {} → {}", list_text(x), list_text(y)),
                        &[],
                    );
                }
            }
        }
        renames
    }

    /// Transitions added, removed, or with another trigger, guard, actions or target.
    fn transitions(
        &mut self,
        o: &ServiceSnap,
        n: &ServiceSnap,
        renames: &BTreeMap<String, String>,
    ) {
        use ChangeKind::*;
        use Severity::*;
        // Old transitions keyed under their states' new names.
        let key = |t: &TransSnap, state: String| (state, t.on.clone(), t.params.clone());
        let mut old_left: Vec<Option<&TransSnap>> = o.transitions.iter().map(Some).collect();
        let mut new_left: Vec<Option<&TransSnap>> = n.transitions.iter().map(Some).collect();
        let old_key: Vec<_> = o
            .transitions
            .iter()
            .map(|t| key(t, renamed(&t.state, renames)))
            .collect();
        let new_key: Vec<_> = n
            .transitions
            .iter()
            .map(|t| key(t, t.state.clone()))
            .collect();
        let mut pairs: Vec<(&TransSnap, &TransSnap)> = Vec::new();
        // Same key, then: the same definition, the same guard, any.
        let passes: [&Same; 3] = [
            &|a, b| body(a) == body(b),
            &|a, b| a.guard == b.guard,
            &|_, _| true,
        ];
        for same in passes {
            for i in 0..old_left.len() {
                let Some(a) = old_left[i] else { continue };
                let hit = (0..new_left.len())
                    .find(|&j| new_left[j].is_some_and(|b| new_key[j] == old_key[i] && same(a, b)));
                if let Some(b) = hit.and_then(|j| new_left[j].take()) {
                    pairs.push((a, b));
                    old_left[i] = None;
                }
            }
        }
        // The same transition in another state.
        for i in 0..old_left.len() {
            let Some(a) = old_left[i] else { continue };
            let hit = (0..new_left.len()).find(|&j| {
                new_left[j].is_some_and(|b| {
                    (&new_key[j].1, &new_key[j].2) == (&old_key[i].1, &old_key[i].2)
                        && body(a) == body(b)
                })
            });
            if let Some(j) = hit {
                let b = &n.transitions[j];
                self.push(
                    ServiceTransitionMoved,
                    WireBreaking,
                    format!("{}/{}", n.name, b.state),
                    Some(&a.at),
                    Some(&b.at),
                    format!(
                        "transition {} {} moved from state {}: it is taken in other states",
                        trigger(b),
                        guard_text(&b.guard),
                        a.state
                    ),
                    &[],
                );
                old_left[i] = None;
                new_left[j] = None;
            }
        }
        // Another trigger in the same state, the rest the same.
        for i in 0..old_left.len() {
            let Some(a) = old_left[i] else { continue };
            let hit = (0..new_left.len()).find(|&j| {
                new_left[j].is_some_and(|b| new_key[j].0 == old_key[i].0 && body(a) == body(b))
            });
            if let Some(j) = hit {
                let b = &n.transitions[j];
                self.push(
                    ServiceTriggerChanged,
                    WireBreaking,
                    format!("{}/{}", n.name, b.state),
                    Some(&a.at),
                    Some(&b.at),
                    format!("transition {} → {}", trigger(a), trigger(b)),
                    &[],
                );
                old_left[i] = None;
                new_left[j] = None;
            }
        }
        for a in old_left.into_iter().flatten() {
            self.push(
                ServiceTransitionRemoved,
                WireBreaking,
                format!("{}/{}", n.name, renamed(&a.state, renames)),
                Some(&a.at),
                Some(&n.at),
                format!(
                    "transition {} {} removed: the service no longer does {} there",
                    trigger(a),
                    guard_text(&a.guard),
                    list_text(&a.actions)
                ),
                &[],
            );
        }
        for b in new_left.into_iter().flatten() {
            self.push(
                ServiceTransitionAdded,
                Compatible,
                format!("{}/{}", n.name, b.state),
                Some(&o.at),
                Some(&b.at),
                format!(
                    "transition {} {} added ({}; actions {})",
                    trigger(b),
                    guard_text(&b.guard),
                    target_text(b),
                    list_text(&b.actions)
                ),
                &[],
            );
        }
        for (a, b) in pairs {
            let path = format!("{}/{}", n.name, b.state);
            let at = (Some(&a.at), Some(&b.at));
            if a.guard != b.guard {
                let what = match (&a.guard, &b.guard) {
                    (Some(g), None) => format!("guard [{g}] removed: now taken whatever it said"),
                    (None, Some(g)) => format!("guard [{g}] added: now taken only when it holds"),
                    _ => format!(
                        "guard {} → {}: now taken in other cases",
                        guard_text(&a.guard),
                        guard_text(&b.guard)
                    ),
                };
                self.push(
                    ServiceGuardChanged,
                    WireBreaking,
                    path.clone(),
                    at.0,
                    at.1,
                    format!("transition {}: {what}", trigger(b)),
                    &[],
                );
            }
            if a.actions != b.actions {
                self.push(
                    ServiceActionsChanged,
                    WireBreaking,
                    path.clone(),
                    at.0,
                    at.1,
                    format!(
                        "transition {} {}: actions {} → {}",
                        trigger(b),
                        guard_text(&b.guard),
                        list_text(&a.actions),
                        list_text(&b.actions)
                    ),
                    &[],
                );
            }
            let to_old = a.to.as_deref().map(|t| renamed(t, renames));
            if a.kind != b.kind || to_old.as_deref() != b.to.as_deref() {
                self.push(
                    ServiceTargetChanged,
                    WireBreaking,
                    path.clone(),
                    at.0,
                    at.1,
                    format!(
                        "transition {} {}: {} → {}",
                        trigger(b),
                        guard_text(&b.guard),
                        target_text(a),
                        target_text(b)
                    ),
                    &[],
                );
            }
        }
    }

    /// Methods of the generated trait added, removed or with another signature.
    fn methods(&mut self, o: &ServiceSnap, n: &ServiceSnap) {
        use ChangeKind::*;
        use Severity::*;
        let kind = |m: &MethodSnap| if m.guard { "guard" } else { "action" };
        let p = pair(&o.methods, &n.methods, |m| &m.name, |_, _| false);
        for m in p.removed {
            let sig = m.sig.as_deref().unwrap_or(&m.name);
            self.push(
                ServiceMethodRemoved,
                SourceBreaking,
                format!("{}::{}", n.name, m.name),
                Some(&m.at),
                Some(&n.at),
                format!(
                    "{} `{sig}` removed from trait `{}`: {REMOVED}",
                    kind(m),
                    n.name
                ),
                &[],
            );
        }
        for m in p.added {
            let sig = m.sig.as_deref().unwrap_or(&m.name);
            self.push(
                ServiceMethodAdded,
                SourceBreaking,
                format!("{}::{}", n.name, m.name),
                Some(&o.at),
                Some(&m.at),
                format!("{} `{sig}` added to trait `{}`: {ADDED}", kind(m), n.name),
                &[],
            );
        }
        for (a, b, _) in p.both {
            let changed = match (&a.sig, &b.sig) {
                (Some(x), Some(y)) => x != y,
                _ => a.guard != b.guard,
            };
            if changed {
                let t = |m: &MethodSnap| {
                    m.sig
                        .clone()
                        .unwrap_or_else(|| format!("{} {}", kind(m), m.name))
                };
                self.push(
                    ServiceMethodChanged,
                    SourceBreaking,
                    format!("{}::{}", n.name, b.name),
                    Some(&a.at),
                    Some(&b.at),
                    format!(
                        "`{}` → `{}`: a vendor's implementation no longer compiles (E0053/E0050)",
                        t(a),
                        t(b)
                    ),
                    &[],
                );
            }
        }
    }
}
