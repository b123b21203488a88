//! The template context of component interfaces: one generated module per component
//! with its trait, interface marker, modes and dispatch.

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

/// Builds the component contexts of a validated spec.
pub fn build_components(spec: &Spec, gates: bool) -> Vec<ComponentCtx> {
    spec.components
        .iter()
        .filter(|c| spec.is_own(c.source))
        .map(|c| {
            let d = &c.def;
            let mut groups: BTreeSet<String> = BTreeSet::new();
            groups.insert(c.group.clone());
            let mut handlers = Vec::new();
            for (kind, list) in [("command", &d.commands), ("accepts", &d.accepts)] {
                for n in list {
                    let Some(m) = spec.message(n) else { continue };
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
                    handlers.push(HandlerCtx {
                        method: format!("on_{}", snake(n)),
                        message: n.clone(),
                        report: report.map(|r| r.def.name.clone()),
                        pattern,
                        wrap_report,
                        doc: doc.iter().flat_map(|l| if l.is_empty() { vec![String::new()] } else { wrap(l, 88) }).collect(),
                    });
                }
            }
            for n in &d.emits {
                if let Some(m) = spec.message(n) {
                    groups.insert(m.group.clone());
                }
            }
            groups.remove("core");
            let cfg = if gates && !groups.is_empty() {
                let fs: Vec<String> = groups.iter().map(|g| format!("feature = \"{g}\"")).collect();
                Some(if fs.len() == 1 { fs[0].clone() } else { format!("all({})", fs.join(", ")) })
            } else {
                None
            };
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
                let list = |names: &[String]| -> String {
                    if names.is_empty() {
                        "none".into()
                    } else {
                        names.iter().map(|n| format!("[`{n}`]")).collect::<Vec<_>>().join(", ")
                    }
                };
                doc.push(format!("* Commands (from the component in control only): {}", list(&d.commands)));
                doc.push(format!("* Accepted from anyone: {}", list(&d.accepts)));
                doc.push(format!("* Sent on its own: {}", list(&d.emits)));
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
                    needs: pascal(s.needs.as_str()),
                }),
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
