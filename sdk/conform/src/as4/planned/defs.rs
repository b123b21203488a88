//! The definitions a plan reads: jaus-as4's (every set of `jaus_as4::DEFS`) with a vendor's
//! YAML on them, or a set imported from JSIDL, as `jaus as4-query` loads them; and,
//! per service, the transitions that take a message (which message, in which state,
//! under which guard, doing what), each with the file and line it is written at.

use std::path::PathBuf;

use jaus_dynamic::Schema;
use jaus_spec::{ServiceTransitionDef, Spec, StateDef};

/// A loaded definition set: the validated definitions, the messages' layouts, and the
/// services' transitions.
#[derive(Debug)]
pub struct Definitions {
    spec: Spec,
    schema: Schema,
    services: Vec<ServiceModel>,
}

/// One service of the definitions, as far as a plan needs it.
#[derive(Debug, Clone)]
pub struct ServiceModel {
    /// Its name in the definitions (`LocalPoseSensor`).
    pub name: String,
    /// Its URI.
    pub uri: String,
    /// Its version as written (`"1.0"`).
    pub version: String,
    /// `file:line` of its definition.
    pub at: String,
    /// The URI of the service it inherits, if any.
    pub inherits: Option<String>,
    /// Its transitions taking a message, in definition order.
    pub transitions: Vec<TransitionModel>,
}

/// A transition of a service's machines triggered by a received message.
#[derive(Debug, Clone)]
pub struct TransitionModel {
    /// The message's name.
    pub message: String,
    /// The machine's name.
    pub machine: String,
    /// The state's path (`Receiving.Ready.Controlled`).
    pub state: String,
    /// The guard's condition, if any.
    pub guard: Option<String>,
    /// The actions' names, in order.
    pub actions: Vec<String>,
    /// The messages named by `send` actions' first argument (`Send('ReportX')`).
    pub sends: Vec<String>,
    /// `file:line` of the transition.
    pub at: String,
}

impl TransitionModel {
    /// Whether its guard asks that the sender hold control (`isControllingClient`, not
    /// negated).
    pub fn needs_controller(&self) -> bool {
        self.guard.as_deref().is_some_and(|g| {
            g.split("&&").any(|t| {
                let t = t.trim();
                t.starts_with("isControllingClient")
            })
        })
    }

    /// Whether it has a guard besides `isControllingClient` (a condition on the
    /// message or the service's data: it may not be taken).
    pub fn has_data_guard(&self) -> bool {
        self.guard.as_deref().is_some_and(|g| {
            g.split("&&").any(|t| {
                !t.trim()
                    .trim_start_matches('!')
                    .starts_with("isControllingClient")
            })
        })
    }

    /// Whether its state lies under the component's Ready state of Management
    /// (`...Controlled.Available.Ready`): the component must be Ready for it.
    pub fn needs_ready(&self) -> bool {
        self.state.contains("Available.Ready")
    }
}

impl Definitions {
    /// jaus-as4's definitions with the YAML of the directories `yaml` on them, or (when
    /// `jsidl` is not empty) the JSIDL of those directories imported instead.
    pub fn load(yaml: &[PathBuf], jsidl: &[PathBuf]) -> Result<Definitions, String> {
        let loaded = jaus_dynamic::load_overlaid(jaus_as4::DEFS, "jaus-as4/defs", yaml, jsidl);
        loaded.map(Definitions::from_spec)
    }

    /// jaus-as4's own definitions (every set of `jaus_as4::DEFS`).
    pub fn as4() -> Result<Definitions, String> {
        Definitions::load(&[], &[])
    }

    /// The definitions of a validated set.
    pub fn from_spec(spec: Spec) -> Definitions {
        let schema = Schema::from_spec(&spec);
        let services = spec
            .services
            .iter()
            .map(|s| {
                let src = &spec.sources[s.source];
                let file = src.path.display().to_string();
                let line = |path: &str| src.index.find(path).line;
                let mut transitions = Vec::new();
                if let Some(b) = &s.def.behaviour {
                    for (mi, m) in b.machines.iter().enumerate() {
                        let base = format!("{}.behaviour.machines[{mi}]", s.path);
                        for (si, st) in m.states.iter().enumerate() {
                            walk(
                                &Walk {
                                    schema: &schema,
                                    machine: &m.name,
                                    file: &file,
                                    line: &line,
                                },
                                st,
                                "",
                                &format!("{base}.states[{si}]"),
                                &mut transitions,
                            );
                        }
                    }
                }
                ServiceModel {
                    name: s.def.name.clone(),
                    uri: s.def.id.clone(),
                    version: s.def.version.clone(),
                    at: format!("{file}:{}", line(&s.path)),
                    inherits: s.def.inherits.as_ref().map(|r| r.id.clone()),
                    transitions,
                }
            })
            .collect();
        Definitions {
            spec,
            schema,
            services,
        }
    }

    /// The validated definitions.
    pub fn spec(&self) -> &Spec {
        &self.spec
    }

    /// The messages' layouts.
    pub fn schema(&self) -> &Schema {
        &self.schema
    }

    /// Every service, in definition order.
    pub fn services(&self) -> &[ServiceModel] {
        &self.services
    }

    /// The service with `uri` whose version is `major.minor`, else one of the same
    /// major version.
    pub fn service(&self, uri: &str, major: u8, minor: u8) -> Option<&ServiceModel> {
        let of = |s: &&ServiceModel| s.uri == uri;
        let version = |s: &ServiceModel| {
            let mut v = s.version.split('.').map(|p| p.trim().parse::<u8>().ok());
            (v.next().flatten(), v.next().flatten().unwrap_or(0))
        };
        self.services
            .iter()
            .filter(of)
            .find(|s| version(s) == (Some(major), minor))
            .or_else(|| {
                self.services
                    .iter()
                    .filter(of)
                    .find(|s| version(s).0 == Some(major))
            })
    }

    /// Whether the service `uri` is, or inherits (at any depth), the service `base`.
    pub fn inherits(&self, uri: &str, base: &str) -> bool {
        let mut at = Some(uri.to_string());
        for _ in 0..32 {
            match at {
                Some(u) if u == base => return true,
                Some(u) => {
                    at = self
                        .services
                        .iter()
                        .find(|s| s.uri == u)
                        .and_then(|s| s.inherits.clone())
                }
                None => return false,
            }
        }
        false
    }

    /// The message definition named `name`.
    pub fn message(&self, name: &str) -> Option<&jaus_spec::Message> {
        self.spec.messages.iter().find(|m| m.def.name == name)
    }

    /// Whether message `name` needs control: its `is_command`, else a command by its
    /// code's class (as jaus-as4 decides it).
    pub fn needs_control(&self, name: &str) -> bool {
        let Some(m) = self.message(name) else {
            return false;
        };
        m.def.is_command.unwrap_or_else(|| {
            self.schema
                .message(name)
                .is_some_and(|l| l.class == jaus_spec::MessageClass::Command)
        })
    }
}

/// What [`walk`] carries down the states.
struct Walk<'a> {
    schema: &'a Schema,
    machine: &'a str,
    file: &'a str,
    line: &'a dyn Fn(&str) -> usize,
}

/// The transitions of `st` and its sub-states taking a message of the schema.
fn walk(w: &Walk<'_>, st: &StateDef, parent: &str, yaml: &str, out: &mut Vec<TransitionModel>) {
    let path = if parent.is_empty() {
        st.name.clone()
    } else {
        format!("{parent}.{}", st.name)
    };
    for (ti, t) in st.transitions.iter().enumerate() {
        if let Some(m) = model(w, t, &path, &format!("{yaml}.transitions[{ti}]")) {
            out.push(m);
        }
    }
    for (si, sub) in st.states.iter().enumerate() {
        walk(w, sub, &path, &format!("{yaml}.states[{si}]"), out);
    }
}

fn model(
    w: &Walk<'_>,
    t: &ServiceTransitionDef,
    state: &str,
    yaml: &str,
) -> Option<TransitionModel> {
    let message = t
        .parameters
        .iter()
        .map(|p| p.ty.as_str())
        .find(|ty| w.schema.message(ty).is_some())?;
    let sends = t
        .actions
        .iter()
        .filter(|a| a.send)
        .filter_map(|a| a.args.first())
        .map(|a| a.trim_matches(|c| c == '\'' || c == '"').to_string())
        .filter(|n| w.schema.message(n).is_some())
        .collect();
    Some(TransitionModel {
        message: message.to_string(),
        machine: w.machine.to_string(),
        state: state.to_string(),
        guard: t.guard.as_ref().map(|g| g.condition.clone()),
        actions: t.actions.iter().map(|a| a.name.clone()).collect(),
        sends,
        at: format!("{}:{}", w.file, (w.line)(yaml)),
    })
}
