//! Positions in JSIDL: definitions imported from JSIDL are YAML that exists only in
//! memory, so a position in it means nothing to the vendor, who edits the `.xml` files.
//! [`JsidlPositions`] maps a YAML path of an imported file (`services[0].behaviour.
//! machines[0].states[1].transitions[2]`) to the JSIDL element it came from, walking the
//! YAML and the XML side by side: a service is its `service_def`, a machine the
//! `state_machine` of that name, a state the `state` of that name, the n-th transition on
//! a trigger the n-th `transition` of that name, a message the `message_def` of that
//! name, and anything else with a name the first element below of that name. Where the
//! walk cannot follow, the last element it reached is the position.

use super::{label, Loc};
use crate::error::Error;
use jaus_spec::Spec;
use serde_yaml::Value;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// An element of a JSIDL file.
#[derive(Debug)]
struct Elem {
    tag: String,
    /// Its `name` attribute, normalised ([`norm`]).
    name: Option<String>,
    line: usize,
    col: usize,
    children: Vec<usize>,
}

/// One imported file: its YAML and the tree of the JSIDL it came from.
#[derive(Debug)]
struct File {
    yaml: Value,
    xml: Vec<Elem>,
    label: String,
}

/// Maps positions in imported YAML to the JSIDL files they came from.
#[derive(Debug, Default)]
pub struct JsidlPositions {
    /// By index of [`Spec::sources`].
    files: HashMap<usize, File>,
}

/// A name compared across the import's renaming: letters and digits, lower case
/// (`CONTROL_ACCEPTED`, `ControlAccepted` and `controlAccepted` are one name).
fn norm(s: &str) -> String {
    s.chars()
        .filter(|c| c.is_alphanumeric())
        .flat_map(char::to_lowercase)
        .collect()
}

fn tree(path: &Path) -> Result<Vec<Elem>, Error> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let opts = roxmltree::ParsingOptions {
        allow_dtd: false,
        ..Default::default()
    };
    let doc = roxmltree::Document::parse_with_options(&text, opts).map_err(|e| {
        Error::Revision(format!(
            "{}:{}:{}: {e}",
            path.display(),
            e.pos().row,
            e.pos().col
        ))
    })?;
    let mut out: Vec<Elem> = Vec::new();
    let mut ids = HashMap::new();
    for n in doc.root_element().descendants().filter(|n| n.is_element()) {
        let p = doc.text_pos_at(n.range().start);
        let me = out.len();
        ids.insert(n.id(), me);
        if let Some(&up) = n.parent().and_then(|p| ids.get(&p.id())) {
            out[up].children.push(me);
        }
        out.push(Elem {
            tag: n.tag_name().name().to_string(),
            name: n.attribute("name").map(norm),
            line: p.row as usize,
            col: p.col as usize,
            children: Vec::new(),
        });
    }
    Ok(out)
}

/// `key[3]` → (`key`, Some(3)).
fn segment(s: &str) -> (&str, Option<usize>) {
    match s.split_once('[') {
        Some((k, i)) => (k, i.trim_end_matches(']').parse().ok()),
        None => (s, None),
    }
}

impl JsidlPositions {
    /// The positions of `spec`, whose sources at the YAML paths of `origins` were
    /// imported from the JSIDL files they are paired with.
    pub fn new(spec: &Spec, origins: &[(PathBuf, PathBuf)]) -> Result<JsidlPositions, Error> {
        let mut files = HashMap::new();
        for (i, s) in spec.sources.iter().enumerate() {
            let Some((_, xml)) = origins.iter().find(|(y, _)| *y == s.path) else {
                continue;
            };
            let yaml: Value = serde_yaml::from_str(&s.text).unwrap_or(Value::Null);
            files.insert(
                i,
                File {
                    yaml,
                    xml: tree(xml)?,
                    label: label(xml),
                },
            );
        }
        Ok(JsidlPositions { files })
    }

    /// The JSIDL position of a YAML path of source `source`; `None` for a source that
    /// was not imported.
    pub fn locate(&self, source: usize, path: &str) -> Option<Loc> {
        let f = self.files.get(&source)?;
        if f.xml.is_empty() {
            return None;
        }
        let x = &f.xml;
        let mut node = 0;
        let mut v = &f.yaml;
        for seg in path.split('.') {
            let (key, idx) = segment(seg);
            let Some(list) = v.get(key) else { break };
            let item = match idx {
                Some(i) => match list.get(i) {
                    Some(item) => item,
                    None => break,
                },
                None => list,
            };
            let named = |tag: Option<&str>, name: Option<&str>| -> Option<usize> {
                let want = name.map(norm);
                let ok = |e: &Elem| {
                    tag.is_none_or(|t| e.tag == t)
                        && (want.is_none() || e.name.as_ref() == want.as_ref())
                };
                // Breadth first below `node`: the nearest match.
                let mut todo = std::collections::VecDeque::from(x[node].children.clone());
                while let Some(k) = todo.pop_front() {
                    if ok(&x[k]) {
                        return Some(k);
                    }
                    todo.extend(x[k].children.iter().copied());
                }
                None
            };
            let children = |tags: &[&str]| -> Vec<usize> {
                x[node]
                    .children
                    .iter()
                    .copied()
                    .filter(|&k| tags.contains(&x[k].tag.as_str()))
                    .collect()
            };
            let name_of =
                |val: &Value, k: &str| val.get(k).and_then(Value::as_str).map(String::from);
            let next = match (key, idx) {
                ("services", Some(_)) => {
                    if x[0].tag == "service_def" {
                        Some(0)
                    } else {
                        named(Some("service_def"), name_of(item, "name").as_deref())
                    }
                }
                ("behaviour", None) => children(&["protocol_behavior"]).first().copied(),
                ("machines", Some(_)) => {
                    named(Some("state_machine"), name_of(item, "name").as_deref())
                }
                ("states", Some(_)) => {
                    let want = name_of(item, "name").map(|n| norm(&n));
                    children(&["state"])
                        .into_iter()
                        .find(|&k| x[k].name == want)
                }
                ("default", None) => children(&["default_state"]).first().copied(),
                ("transitions", Some(i)) => {
                    // The n-th transition on the same trigger.
                    let on = name_of(item, "on");
                    let nth = (0..i)
                        .filter(|&j| list.get(j).and_then(|t| name_of(t, "on")) == on)
                        .count();
                    let want = on.map(|n| norm(&n));
                    children(&["transition"])
                        .into_iter()
                        .filter(|&k| x[k].name == want)
                        .nth(nth)
                }
                ("default_transitions", Some(i)) => {
                    children(&["default_transition"]).get(i).copied()
                }
                ("entry" | "exit", Some(i)) => children(&[key])
                    .into_iter()
                    .flat_map(|e| x[e].children.clone())
                    .filter(|&k| matches!(x[k].tag.as_str(), "action" | "send_action"))
                    .nth(i),
                ("actions", Some(i)) => children(&["action", "send_action"]).get(i).copied(),
                ("guard", None) => children(&["guard"]).first().copied(),
                ("messages", Some(_)) => {
                    named(Some("message_def"), name_of(item, "name").as_deref())
                }
                _ => name_of(item, "name").and_then(|n| named(None, Some(&n))),
            };
            match next {
                Some(k) => node = k,
                None => break,
            }
            v = item;
        }
        Some(Loc {
            file: f.label.clone(),
            line: x[node].line,
            col: x[node].col,
        })
    }
}
