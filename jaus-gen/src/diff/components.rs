//! Component interfaces: ids, the messages they command, accept and emit, modes and
//! transitions.

use super::pair::{has, pair};
use super::{ChangeKind, Differ, Severity};
use crate::snapshot::*;

impl Differ<'_> {
    pub(super) fn components(&mut self) {
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
                // Turned on, the component's lists go (every message now comes to
                // `on_other_message`), and with them the trait methods of its commands
                // and accepted messages: an implementation of one no longer compiles.
                let gone: Vec<String> = c
                    .commands
                    .iter()
                    .chain(&c.accepts)
                    .filter(|e| {
                        !n.commands
                            .iter()
                            .chain(&n.accepts)
                            .any(|x| x.name == e.name)
                    })
                    .map(|e| format!("`{}`", handler(&e.name)))
                    .collect();
                let (sev, detail) = if !n.any_message {
                    (WireBreaking, String::new())
                } else if gone.is_empty() {
                    (Compatible, String::new())
                } else {
                    (
                        SourceBreaking,
                        format!(
                            ": every message now comes to `on_other_message`, and the trait \
                             methods {} are gone: an implementation of them no longer compiles",
                            gone.join(", ")
                        ),
                    )
                };
                self.push(
                    ComponentAnyMessageChanged,
                    sev,
                    n.name.clone(),
                    at.0,
                    at.1,
                    format!("any_message {} → {}{detail}", c.any_message, n.any_message),
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

/// The trait method handling message `name` (`on_report_state`), as the generator names
/// it.
fn handler(name: &str) -> String {
    format!("on_{}", crate::components::snake(name))
}
