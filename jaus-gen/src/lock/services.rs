//! The `services:` part of a lock file: per service its URI, version and parent, the
//! methods of its generated trait, its states, and one line per transition, so that a
//! changed guard or action is a one-line diff in review.
//!
//! ```yaml
//! services:
//!   - name: Lamp
//!     id: "urn:acme:Lamp"
//!     version: "1.0"
//!     methods:
//!       - { name: is_allowed, guard: true, sig: "fn is_allowed(&self, msg: &SetLamp) -> bool" }
//!     states:
//!       - { path: "LampFSM/Off", entry: ["init()"] }
//!     transitions:
//!       - { state: "LampFSM/Off", on: "Switch", params: ["SetLamp"], guard: "isAllowed(msg)", kind: simple, to: "On", actions: ["turnOn(msg)"] }
//! ```

use super::{name, quoted};
use crate::snapshot::{Loc, MethodSnap, ServiceSnap, StateSnap, TransSnap};
use serde::Deserialize;
use std::fmt::Write as _;

fn strings(v: &[String]) -> String {
    let q: Vec<String> = v.iter().map(|s| quoted(s)).collect();
    format!("[{}]", q.join(", "))
}

/// Writes the `services:` part (nothing for a set without services, so that the lock
/// files of message sets stay as they were).
pub(super) fn write(out: &mut String, services: &[ServiceSnap]) {
    if services.is_empty() {
        return;
    }
    out.push_str("services:\n");
    for s in services {
        let _ = writeln!(out, "  - name: {}", name(&s.name));
        let _ = writeln!(out, "    id: {}", quoted(&s.id));
        let _ = writeln!(out, "    version: {}", quoted(&s.version));
        if let Some(p) = &s.inherits {
            let _ = writeln!(out, "    inherits: {}", quoted(p));
        }
        if !s.methods.is_empty() {
            out.push_str("    methods:\n");
        }
        for m in &s.methods {
            let _ = write!(
                out,
                "      - {{ name: {}, guard: {}",
                name(&m.name),
                m.guard
            );
            if let Some(sig) = &m.sig {
                let _ = write!(out, ", sig: {}", quoted(sig));
            }
            out.push_str(" }\n");
        }
        if !s.states.is_empty() {
            out.push_str("    states:\n");
        }
        for st in &s.states {
            let _ = write!(out, "      - {{ path: {}", quoted(&st.path));
            if !st.entry.is_empty() {
                let _ = write!(out, ", entry: {}", strings(&st.entry));
            }
            if !st.exit.is_empty() {
                let _ = write!(out, ", exit: {}", strings(&st.exit));
            }
            out.push_str(" }\n");
        }
        if !s.transitions.is_empty() {
            out.push_str("    transitions:\n");
        }
        for t in &s.transitions {
            let _ = write!(out, "      - {{ state: {}", quoted(&t.state));
            if let Some(on) = &t.on {
                let _ = write!(out, ", on: {}", quoted(on));
            }
            if !t.params.is_empty() {
                let _ = write!(out, ", params: {}", strings(&t.params));
            }
            if let Some(g) = &t.guard {
                let _ = write!(out, ", guard: {}", quoted(g));
            }
            let _ = write!(out, ", kind: {}", t.kind);
            if let Some(to) = &t.to {
                let _ = write!(out, ", to: {}", quoted(to));
            }
            if !t.actions.is_empty() {
                let _ = write!(out, ", actions: {}", strings(&t.actions));
            }
            out.push_str(" }\n");
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct LockService {
    name: String,
    id: String,
    version: String,
    #[serde(default)]
    inherits: Option<String>,
    #[serde(default)]
    methods: Vec<LockMethod>,
    #[serde(default)]
    states: Vec<LockState>,
    #[serde(default)]
    transitions: Vec<LockTransition>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockMethod {
    name: String,
    guard: bool,
    #[serde(default)]
    sig: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockState {
    path: String,
    #[serde(default)]
    entry: Vec<String>,
    #[serde(default)]
    exit: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LockTransition {
    state: String,
    #[serde(default)]
    on: Option<String>,
    #[serde(default)]
    params: Vec<String>,
    #[serde(default)]
    guard: Option<String>,
    kind: String,
    #[serde(default)]
    to: Option<String>,
    #[serde(default)]
    actions: Vec<String>,
}

/// The services of a lock file; `at` gives the position of a YAML path in it, `err` an
/// error there.
pub(super) fn read(
    list: Vec<LockService>,
    at: &dyn Fn(&str) -> Loc,
    err: &dyn Fn(&str, String) -> String,
) -> Result<Vec<ServiceSnap>, String> {
    let mut out = Vec::new();
    for (i, s) in list.into_iter().enumerate() {
        let path = format!("services[{i}]");
        let mut transitions = Vec::new();
        for (j, t) in s.transitions.into_iter().enumerate() {
            let p = format!("{path}.transitions[{j}]");
            if !matches!(t.kind.as_str(), "internal" | "simple" | "push" | "pop") {
                return Err(err(
                    &format!("{p}.kind"),
                    format!(
                        "`{}` is not a transition kind: `internal`, `simple`, `push` or `pop`",
                        t.kind
                    ),
                ));
            }
            transitions.push(TransSnap {
                state: t.state,
                on: t.on,
                params: t.params,
                guard: t.guard,
                kind: t.kind,
                to: t.to,
                actions: t.actions,
                at: at(&p),
            });
        }
        out.push(ServiceSnap {
            methods: s
                .methods
                .into_iter()
                .enumerate()
                .map(|(j, m)| MethodSnap {
                    name: m.name,
                    guard: m.guard,
                    sig: m.sig,
                    at: at(&format!("{path}.methods[{j}]")),
                })
                .collect(),
            states: s
                .states
                .into_iter()
                .enumerate()
                .map(|(j, st)| StateSnap {
                    path: st.path,
                    entry: st.entry,
                    exit: st.exit,
                    at: at(&format!("{path}.states[{j}]")),
                })
                .collect(),
            transitions,
            name: s.name,
            id: s.id,
            version: s.version,
            inherits: s.inherits,
            at: at(&path),
        });
    }
    Ok(out)
}
