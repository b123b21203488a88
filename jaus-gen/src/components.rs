//! The template context of component interfaces: one generated module per component
//! with its trait, interface marker, modes and dispatch, and one trait per part that
//! several components share (`parts`), which their traits reach through an accessor.

use std::collections::BTreeSet;

use jaus_spec::{MessageDef, Spec};
use serde::Serialize;

/// One component.
#[derive(Debug, Clone, Serialize)]
pub struct ComponentCtx {
    /// Trait name (PascalCase).
    pub name: String,
    /// Module name (snake_case).
    pub module: String,
    /// Title ("Global Pose Sensor").
    pub title: String,
    /// Component id.
    pub id: u8,
    /// Function text, wrapped.
    pub function: Vec<String>,
    /// Trait documentation lines.
    pub doc: Vec<String>,
    /// `#[cfg(...)]` condition, if gated.
    pub cfg: Option<String>,
    /// One handler per command and accepted message.
    pub handlers: Vec<HandlerCtx>,
    /// Messages it may send on its own.
    pub emits: Vec<EmitCtx>,
    /// Command codes of `commands`.
    pub commands: Vec<String>,
    /// Command codes of `accepts`.
    pub accepts: Vec<String>,
    /// Command codes of `emits`.
    pub emit_codes: Vec<String>,
    /// Takes and sends any message.
    pub any_message: bool,
    /// Commands motion: a required `stop` method.
    pub safe_stop: bool,
    /// Sub-states of Ready.
    pub modes: Option<ModesCtx>,
    /// `file:line` of the definition.
    pub origin: String,
    /// The SDK's stock implementation (`stock:`), if any.
    pub stock: Option<StockCtx>,
    /// The shared parts it routes messages to, in `parts` order.
    pub parts: Vec<PartRef>,
}

/// A part several components share: one generated trait, generic over the interface
/// of the component it serves.
#[derive(Debug, Clone, Serialize)]
pub struct PartCtx {
    /// Trait name (PascalCase).
    pub name: String,
    /// Trait documentation lines.
    pub doc: Vec<String>,
    /// `#[cfg(...)]` condition, if gated.
    pub cfg: Option<String>,
    /// One handler per command and accepted message of the part.
    pub handlers: Vec<HandlerCtx>,
}

/// A part a component shares.
#[derive(Debug, Clone, Serialize)]
pub struct PartRef {
    /// Trait name (PascalCase).
    pub name: String,
    /// The component trait's accessor of the part (`navigation_driver`).
    pub method: String,
    /// Whether the part is generated with the component (`parts::Name`); otherwise it
    /// is the SDK's (`RUNTIME::components::parts::Name`).
    pub own: bool,
}

/// The SDK's stock implementation of a component.
#[derive(Debug, Clone, Serialize)]
pub struct StockCtx {
    /// Its name in node files (`world_model`).
    pub name: String,
    /// The `Hardware` variant it runs over (`Vehicle`).
    pub needs: String,
}

/// A trait method.
#[derive(Debug, Clone, Serialize)]
pub struct HandlerCtx {
    /// Method name (`on_set_global_waypoint`).
    pub method: String,
    /// Message type.
    pub message: String,
    /// Report type returned, for a query.
    pub report: Option<String>,
    /// The match pattern of the message in the component's set, binding `m`.
    pub pattern: String,
    /// Expression turning the report `r` into a message of the component's set.
    pub wrap_report: Option<String>,
    /// Documentation lines.
    pub doc: Vec<String>,
    /// The accessor of the part the message belongs to (`navigation_driver`), if any:
    /// the component trait's default method passes the message to it.
    pub part: Option<String>,
}

/// A message the component may send, with its conversion into the component's set.
#[derive(Debug, Clone, Serialize)]
pub struct EmitCtx {
    /// Message type.
    pub message: String,
    /// Expression turning `msg` into a message of the component's set.
    pub wrap: String,
}

/// How a message of `spec` is named inside the component's message set `Message`:
/// directly in the SDK (and a standalone set), inside `Message::Jaus` for a vendor's
/// set when the message is the SDK's.
fn in_set(spec: &Spec, name: &str) -> (String, String) {
    let standard = spec.extends() && spec.message(name).is_some_and(|m| !spec.is_own(m.source));
    if standard {
        (
            format!("Message::Jaus(::jaus::messages::Message::{name}(m))"),
            "Message::Jaus(msg.into())".into(),
        )
    } else {
        (format!("Message::{name}(m)"), "msg.into()".into())
    }
}

/// The modes of a component.
#[derive(Debug, Clone, Serialize)]
pub struct ModesCtx {
    /// Documentation of the mode enum.
    pub doc: Vec<String>,
    /// Initial mode.
    pub initial: String,
    /// Modes.
    pub states: Vec<NamedDoc>,
    /// Transitions.
    pub transitions: Vec<TransitionCtx>,
}

/// A name with documentation lines.
#[derive(Debug, Clone, Serialize)]
pub struct NamedDoc {
    /// Name.
    pub name: String,
    /// Doc lines.
    pub doc: Vec<String>,
}

/// A mode transition.
#[derive(Debug, Clone, Serialize)]
pub struct TransitionCtx {
    /// Name as written (snake_case).
    pub name: String,
    /// Enum variant (PascalCase).
    pub variant: String,
    /// Modes it starts from.
    pub from: Vec<String>,
    /// Mode it leads to.
    pub to: String,
    /// `CoreTransition` variant entered with it.
    pub core: Option<String>,
    /// Doc lines.
    pub doc: Vec<String>,
}

/// Splits prose into lines of at most `width` characters (words are never broken).
pub(crate) fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut out = Vec::new();
    for para in text.split("\n\n") {
        let mut line = String::new();
        for word in para.split_whitespace() {
            // Never start a line with something Markdown reads as a list marker.
            let marker = matches!(word, "+" | "-" | "*")
                || word
                    .strip_suffix('.')
                    .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()));
            if !line.is_empty() && line.len() + 1 + word.len() > width && !marker {
                out.push(std::mem::take(&mut line));
            }
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
        }
        if !line.is_empty() {
            out.push(line);
        }
        out.push(String::new());
    }
    while out.last().is_some_and(String::is_empty) {
        out.pop();
    }
    out
}

/// `GlobalPoseSensor` → `global_pose_sensor`.
pub(crate) fn snake(name: &str) -> String {
    let mut s = String::new();
    let chars: Vec<char> = name.chars().collect();
    for (i, c) in chars.iter().enumerate() {
        if c.is_ascii_uppercase() {
            let prev_lower =
                i > 0 && (chars[i - 1].is_ascii_lowercase() || chars[i - 1].is_ascii_digit());
            let next_lower = chars.get(i + 1).is_some_and(|n| n.is_ascii_lowercase());
            let prev_upper = i > 0 && chars[i - 1].is_ascii_uppercase();
            if i > 0 && (prev_lower || (prev_upper && next_lower)) {
                s.push('_');
            }
            s.push(c.to_ascii_lowercase());
        } else {
            s.push(*c);
        }
    }
    s
}

fn pascal(snake: &str) -> String {
    snake
        .split('_')
        .map(|w| {
            let mut c = w.chars();
            c.next()
                .map(|f| f.to_ascii_uppercase().to_string() + c.as_str())
                .unwrap_or_default()
        })
        .collect()
}

fn title(d: &MessageDef) -> String {
    d.title
        .clone()
        .unwrap_or_else(|| jaus_spec::title_of(&d.name))
}

/// The trait method of message `n` (`kind`: "command" or "accepts"), adding the groups
/// of the message and of its report to `groups`; `None` for an unknown message.
fn handler(spec: &Spec, kind: &str, n: &str, groups: &mut BTreeSet<String>) -> Option<HandlerCtx> {
    let m = spec.message(n)?;
    groups.insert(m.group.clone());
    let report = spec.report_of(&m.def);
    if let Some(r) = report {
        groups.insert(r.group.clone());
    }
    let t = title(&m.def);
    let mut doc = vec![format!("Handles [`{n}`] ({}): {t}.", m.def.code)];
    doc.push(String::new());
    doc.push(match (kind, report) {
        ("command", _) => "A command: the runtime calls this only when the sender is the component in control and the component is in Ready or Standby. Return `Err(Refused::Invalid(..))` for values that cannot be executed (the sender gets a NAK if it asked for an acknowledgement).".into(),
        (_, Some(r)) => format!("A query from any component: return the [`{}`] to send back. The same method answers service connections and events on that report.", r.def.name),
        _ => "Accepted from any component.".into(),
    });
    doc.push(String::new());
    doc.push("Not implemented: the message is ignored and counted as unsupported.".into());
    let pattern = in_set(spec, n).0;
    let wrap_report = report.map(|r| in_set(spec, &r.def.name).1.replace("msg", "r"));
    Some(HandlerCtx {
        method: format!("on_{}", snake(n)),
        message: n.to_string(),
        report: report.map(|r| r.def.name.clone()),
        pattern,
        wrap_report,
        doc: doc
            .iter()
            .flat_map(|l| {
                if l.is_empty() {
                    vec![String::new()]
                } else {
                    wrap(l, 88)
                }
            })
            .collect(),
        part: None,
    })
}

/// The groups of every message of a part (and of the reports of its queries), but
/// `core`: the features its trait needs.
fn part_groups(spec: &Spec, d: &jaus_spec::PartDef) -> BTreeSet<String> {
    let mut groups = BTreeSet::new();
    for n in d.commands.iter().chain(&d.accepts).chain(&d.emits) {
        if let Some(m) = spec.message(n) {
            groups.insert(m.group.clone());
            if let Some(r) = spec.report_of(&m.def) {
                groups.insert(r.group.clone());
            }
        }
    }
    groups.remove("core");
    groups
}

/// `#[cfg(...)]` of an item that needs the features of `groups` (`core` removed).
fn cfg_of(groups: &BTreeSet<String>, gates: bool) -> Option<String> {
    if !gates || groups.is_empty() {
        return None;
    }
    let fs: Vec<String> = groups
        .iter()
        .map(|g| format!("feature = \"{g}\""))
        .collect();
    Some(if fs.len() == 1 {
        fs[0].clone()
    } else {
        format!("all({})", fs.join(", "))
    })
}

/// `[`A`], [`B`]` or "none".
fn link_list(names: &[String]) -> String {
    if names.is_empty() {
        "none".into()
    } else {
        names
            .iter()
            .map(|n| format!("[`{n}`]"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// The part contexts of a validated spec: the overlay's own parts.
pub fn build_parts(spec: &Spec, gates: bool) -> Vec<PartCtx> {
    spec.parts
        .iter()
        .filter(|p| spec.is_own(p.source))
        .map(|p| {
            let d = &p.def;
            let mut groups = part_groups(spec, d);
            let mut handlers = Vec::new();
            for (kind, list) in [("command", &d.commands), ("accepts", &d.accepts)] {
                handlers.extend(list.iter().filter_map(|n| handler(spec, kind, n, &mut groups)));
            }
            groups.remove("core");
            let source = &spec.sources[p.source];
            let origin = format!(
                "{}:{}",
                source.path.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default(),
                source.index.find(&p.path).line
            );
            let title = jaus_spec::title_of(&d.name);
            let method = snake(&d.name);
            let mut doc = vec![format!("{title}: a part that several component interfaces share."), String::new()];
            doc.extend(wrap(&d.description, 88));
            if !d.rules.is_empty() {
                doc.push(String::new());
                doc.push("# Rules".into());
                doc.push(String::new());
                for r in &d.rules {
                    let mut w = wrap(r, 86).into_iter();
                    if let Some(first) = w.next() {
                        doc.push(format!("* {first}"));
                    }
                    doc.extend(w.map(|l| format!("  {l}")));
                }
            }
            doc.push(String::new());
            doc.push("# Messages".into());
            doc.push(String::new());
            doc.push(format!("* Commands (from the component in control only): {}", link_list(&d.commands)));
            doc.push(format!("* Accepted from anyone: {}", link_list(&d.accepts)));
            if !d.optional.is_empty() {
                doc.push(format!("* Handled only by the components that list them: {}", link_list(&d.optional)));
            }
            doc.push(format!("* Sent on its own: {}", link_list(&d.emits)));
            let users: Vec<String> = spec
                .components
                .iter()
                .filter(|c| spec.is_own(c.source) && c.def.parts.contains(&d.name))
                .map(|c| format!("[`{}`]", c.def.name))
                .collect();
            doc.push(String::new());
            doc.push("# Use".into());
            doc.push(String::new());
            doc.extend(wrap(&format!("Shared by {}. `I` is the interface of the component the part serves (its `Interface`), so a handler gets that component's context. Implement the part once, generic over `I` (bounded by what it needs, such as `Emits<M>` to send `M`), or for one interface; then return it from each component trait's `{method}` method (`Some(self)`, or `Some(&mut self.field)`). The component trait's default methods of these messages, and its `initialize`, `state_changed` and `tick`, pass to it.", users.join(", ")), 88));
            doc.push(String::new());
            doc.push(format!("Defined in `{origin}`."));
            PartCtx {
                name: d.name.clone(),
                doc,
                cfg: cfg_of(&groups, gates),
                handlers,
            }
        })
        .collect()
}

/// Builds the component contexts of a validated spec.
pub fn build_components(spec: &Spec, gates: bool) -> Vec<ComponentCtx> {
    spec.components
        .iter()
        .filter(|c| spec.is_own(c.source))
        .map(|c| {
            let d = &c.def;
            let mut groups: BTreeSet<String> = BTreeSet::new();
            groups.insert(c.group.clone());
            let shared: Vec<&jaus_spec::Part> =
                d.parts.iter().filter_map(|n| spec.part(n)).collect();
            for p in &shared {
                groups.extend(part_groups(spec, &p.def));
            }
            let mut handlers = Vec::new();
            for (kind, list) in [("command", &d.commands), ("accepts", &d.accepts)] {
                for n in list {
                    let Some(mut h) = handler(spec, kind, n, &mut groups) else { continue };
                    let part = shared.iter().find(|p| p.def.commands.contains(n) || p.def.accepts.contains(n));
                    if let Some(p) = part {
                        let method = snake(&p.def.name);
                        h.doc.pop();
                        h.doc.extend(wrap(&format!("Not implemented here: passed to the `{}` part that [`{method}`](Self::{method}) returns, if any; otherwise the message is ignored and counted as unsupported.", p.def.name), 88));
                        h.part = Some(method);
                    }
                    handlers.push(h);
                }
            }
            for n in &d.emits {
                if let Some(m) = spec.message(n) {
                    groups.insert(m.group.clone());
                }
            }
            groups.remove("core");
            let cfg = cfg_of(&groups, gates);
            let code_of = |n: &String| spec.message(n).map(|m| format!("{}", m.def.code));
            let source = &spec.sources[c.source];
            let pos = source.index.find(&c.path);
            let origin = format!(
                "{}:{}",
                source.path.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default(),
                pos.line
            );
            let title = jaus_spec::title_of(&d.name);
            let mut doc = vec![format!("{title} (component id {}).", d.id), String::new()];
            doc.extend(wrap(&d.function, 88));
            if let Some(desc) = &d.description {
                doc.push(String::new());
                doc.extend(wrap(desc, 88));
            }
            if !d.rules.is_empty() {
                doc.push(String::new());
                doc.push("# Rules (Part 1)".into());
                doc.push(String::new());
                for r in &d.rules {
                    let mut w = wrap(r, 86).into_iter();
                    if let Some(first) = w.next() {
                        doc.push(format!("* {first}"));
                    }
                    doc.extend(w.map(|l| format!("  {l}")));
                }
            }
            doc.push(String::new());
            doc.push("# Messages".into());
            doc.push(String::new());
            if d.any_message {
                doc.push("A command and control component: it may send any message to any component and receive any message (all arrive in `on_other_message`).".into());
            } else {
                let list = link_list;
                doc.push(format!("* Commands (from the component in control only): {}", list(&d.commands)));
                doc.push(format!("* Accepted from anyone: {}", list(&d.accepts)));
                doc.push(format!("* Sent on its own: {}", list(&d.emits)));
                for p in &shared {
                    let link = if spec.is_own(p.source) {
                        format!("[`{0}`](super::parts::{0})", p.def.name)
                    } else {
                        format!("`{}`", p.def.name)
                    };
                    doc.push(format!("* Shares the {link} part with other components: its messages go to [`{}`](Self::{})", snake(&p.def.name), snake(&p.def.name)));
                }
            }
            doc.push(String::new());
            doc.push(format!("Defined in `{origin}`."));
            let modes = d.modes.as_ref().map(|m| ModesCtx {
                doc: {
                    let mut v = vec![format!("Modes of the {title} within Ready.")];
                    if let Some(t) = &m.description {
                        v.push(String::new());
                        v.extend(wrap(t, 88));
                    }
                    v.push(String::new());
                    v.push("The runtime returns to the initial mode whenever the component leaves Ready.".into());
                    v
                },
                initial: m.initial.clone(),
                states: m
                    .states
                    .iter()
                    .map(|s| NamedDoc {
                        name: s.name.clone(),
                        doc: s.description.as_deref().map(|t| wrap(t, 88)).unwrap_or_else(|| vec![format!("Mode {}.", s.name)]),
                    })
                    .collect(),
                transitions: m
                    .transitions
                    .iter()
                    .map(|t| {
                        let mut doc = vec![format!("`{}` → `{}`.", t.from.join("`, `"), t.to)];
                        if let Some(core) = &t.core {
                            doc.push(format!("The component also enters {core}."));
                        }
                        if let Some(desc) = &t.description {
                            doc.push(String::new());
                            doc.extend(wrap(desc, 88));
                        }
                        TransitionCtx {
                            name: t.name.clone(),
                            variant: pascal(&t.name),
                            from: t.from.clone(),
                            to: t.to.clone(),
                            core: t.core.as_deref().map(|c| match c {
                                "Failure" => "Fail".to_string(),
                                other => other.to_string(),
                            }),
                            doc,
                        }
                    })
                    .collect(),
            });
            ComponentCtx {
                name: d.name.clone(),
                module: snake(&d.name),
                title,
                id: d.id,
                function: wrap(&d.function, 88),
                doc,
                cfg,
                handlers,
                emits: d
                    .emits
                    .iter()
                    .map(|e| EmitCtx {
                        message: e.clone(),
                        wrap: in_set(spec, e).1,
                    })
                    .collect(),
                commands: d.commands.iter().filter_map(code_of).collect(),
                accepts: d.accepts.iter().filter_map(code_of).collect(),
                emit_codes: d.emits.iter().filter_map(code_of).collect(),
                any_message: d.any_message,
                safe_stop: d.safe_stop,
                modes,
                origin,
                stock: d.stock.as_ref().map(|s| StockCtx {
                    name: s.name.clone(),
                    needs: s.needs.variant().to_string(),
                }),
                parts: shared
                    .iter()
                    .map(|p| PartRef {
                        name: p.def.name.clone(),
                        method: snake(&p.def.name),
                        own: spec.is_own(p.source),
                    })
                    .collect(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_wrapping() {
        assert_eq!(snake("GlobalPoseSensor"), "global_pose_sensor");
        assert_eq!(
            snake("SetVKSFeatureClassMetadata"),
            "set_vks_feature_class_metadata"
        );
        assert_eq!(snake("ReportJAUSDataLink2"), "report_jaus_data_link2");
        assert_eq!(pascal("arrive_final"), "ArriveFinal");
        let w = wrap("aaa bbb ccc\n\nddd", 7);
        assert_eq!(w, ["aaa bbb", "ccc", "", "ddd"]);
        assert_eq!(wrap("aaa bbb + ccc", 7), ["aaa bbb +", "ccc"]);
    }
}
