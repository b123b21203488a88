//! The services of a definition set as the generator needs them: each service's state
//! machines merged with those it inherits (`extends`, `redefine`), every guard parsed,
//! every call (guard or action) resolved to the trait that declares it, every trigger
//! parameter to a Rust type, every transition to its trigger key.

use super::guard::{self, Cond};
use crate::components::snake;
use jaus_spec::model::{ActionDef, MachineDef, ServiceTransitionDef, StateDef, TransitionKind};
use jaus_spec::Spec;

/// A trigger parameter's type: its Rust path (from a service module) and its variant
/// name in the shared `Arg` enum.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct ParamTy {
    pub rust: String,
    pub variant: String,
}

/// An argument of a call.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Arg {
    /// A trigger parameter (its field name in the trigger).
    Param { field: String, ty: ParamTy },
    /// A quoted constant, unquoted.
    Const(String),
}

/// A guard or action call.
#[derive(Debug, Clone)]
pub(crate) struct Call {
    /// The service whose trait declares the method.
    pub owner: usize,
    /// The method's name (snake_case).
    pub method: String,
    /// The call as the definition writes it (`isControllingClient(transportData)`).
    pub raw: String,
    pub args: Vec<Arg>,
    pub doc: Option<String>,
    pub origin: String,
}

/// A guard expression over calls.
#[derive(Debug, Clone)]
pub(crate) enum G {
    Call(Call),
    Const(bool),
    Not(Box<G>),
    And(Vec<G>),
    Or(Vec<G>),
}

/// A transition.
#[derive(Debug, Clone)]
pub(crate) struct Trans {
    /// The trigger key (`None`: a default transition).
    pub key: Option<String>,
    /// Where the trigger comes from (`events.transport.Receive`), for docs.
    pub on: Option<String>,
    pub params: Vec<(String, ParamTy)>,
    pub guard: Option<G>,
    pub kind: TransitionKind,
    pub to: Option<String>,
    pub actions: Vec<Call>,
    pub raise: Option<String>,
    pub doc: Option<String>,
    pub origin: String,
}

/// A state.
#[derive(Debug, Clone)]
pub(crate) struct St {
    pub name: String,
    pub initial: Option<String>,
    pub redefine: bool,
    pub entry: Vec<Call>,
    pub exit: Vec<Call>,
    pub transitions: Vec<Trans>,
    pub defaults: Vec<Trans>,
    pub states: Vec<St>,
    pub origin: String,
}

/// A state machine.
#[derive(Debug, Clone)]
pub(crate) struct Mach {
    pub name: String,
    pub doc: Option<String>,
    pub extends: bool,
    pub start: Option<(String, String)>,
    pub states: Vec<St>,
    pub transitions: Vec<Trans>,
    pub defaults: Vec<Trans>,
    pub origin: String,
}

/// `file:line` of a YAML path of source `src`.
pub(crate) fn origin(spec: &Spec, src: usize, path: &str) -> String {
    let f = &spec.sources[src];
    let p = f.index.find(path);
    format!("{}:{}", f.path.display(), p.line)
}

/// The service a service inherits from, by URI and version.
pub(crate) fn parents(spec: &Spec) -> Result<Vec<Option<usize>>, String> {
    let mut out = Vec::new();
    for s in &spec.services {
        let Some(r) = &s.def.inherits else {
            out.push(None);
            continue;
        };
        match spec
            .services
            .iter()
            .position(|p| p.def.id == r.id && p.def.version == r.version)
        {
            Some(p) => out.push(Some(p)),
            None => {
                return Err(format!(
                    "{}: service `{}` inherits `{}` version {}, which is not among the definitions: import the set that defines it with this one",
                    origin(spec, s.source, &format!("{}.inherits", s.path)),
                    s.def.name,
                    r.id,
                    r.version
                ))
            }
        }
    }
    // No cycles: every chain ends.
    for i in 0..out.len() {
        let (mut at, mut n) = (Some(i), 0);
        while let Some(k) = at {
            n += 1;
            if n > out.len() {
                let s = &spec.services[i];
                return Err(format!(
                    "{}: service `{}` inherits from itself through its parents",
                    origin(spec, s.source, &format!("{}.inherits", s.path)),
                    s.def.name
                ));
            }
            at = out[k];
        }
    }
    Ok(out)
}

/// `i` and its ancestors, nearest first.
pub(crate) fn chain(parents: &[Option<usize>], i: usize) -> Vec<usize> {
    let mut v = vec![i];
    while let Some(p) = v.last().and_then(|&k| parents[k]) {
        v.push(p);
    }
    v
}

/// A name safe as a Rust identifier (a keyword gets a trailing `_`).
pub(crate) fn ident(name: &str) -> String {
    let s = snake(&name.replace(['.', '-', ' '], "_"));
    const KW: &[&str] = &[
        "as", "break", "const", "continue", "crate", "else", "enum", "extern", "false", "fn",
        "for", "if", "impl", "in", "let", "loop", "match", "mod", "move", "mut", "pub", "ref",
        "return", "self", "static", "struct", "super", "trait", "true", "type", "unsafe", "use",
        "where", "while", "async", "await", "dyn", "abstract", "become", "box", "do", "final",
        "macro", "override", "priv", "typeof", "unsized", "virtual", "yield", "try", "gen",
    ];
    if KW.contains(&s.as_str()) {
        format!("{s}_")
    } else {
        s
    }
}

/// Converts the definitions of one service, resolving names against its ancestors.
pub(crate) struct Conv<'a> {
    pub spec: &'a Spec,
    pub parents: &'a [Option<usize>],
    pub svc: usize,
    /// The Rust path of the base definitions' generated messages (`::jaus_as4::messages`)
    /// when the set is built on them: an event of a base service is named there.
    pub base: Option<&'a str>,
}

impl Conv<'_> {
    fn err(&self, path: &str, what: &str, msg: String) -> String {
        let s = &self.spec.services[self.svc];
        format!(
            "{}: service `{}`, {what}: {msg}",
            origin(self.spec, s.source, path),
            s.def.name
        )
    }

    fn at(&self, path: &str) -> String {
        origin(self.spec, self.spec.services[self.svc].source, path)
    }

    /// The service a dotted prefix (`events.transport`) names, from this one.
    fn owner_of(&self, prefix: &[&str]) -> Option<usize> {
        let mut cur = self.svc;
        for seg in prefix {
            let c = chain(self.parents, cur);
            let hop = c.iter().find(|&&x| {
                self.spec.services[x]
                    .def
                    .inherits
                    .as_ref()
                    .is_some_and(|r| r.name == *seg)
            })?;
            cur = self.parents[*hop]?;
        }
        Some(cur)
    }

    /// The Rust type of a parameter type as written.
    fn param_ty(&self, ty: &str) -> Option<ParamTy> {
        if self.spec.message(ty).is_some() {
            return Some(ParamTy {
                rust: ty.to_string(),
                variant: ty.to_string(),
            });
        }
        let head = ty.split('.').next().unwrap_or(ty);
        for k in chain(self.parents, self.svc) {
            let s = &self.spec.services[k];
            if s.def.events.iter().any(|e| e.name == head) {
                let module = match self.base {
                    Some(b) if !self.spec.is_own(s.source) => format!("{b}::services"),
                    _ => "super".to_string(),
                };
                return Some(ParamTy {
                    rust: format!("{module}::{}::event::{head}", ident(&s.def.name)),
                    variant: format!("{}{head}", s.def.name),
                });
            }
        }
        self.spec.ty(ty).map(|_| ParamTy {
            rust: ty.to_string(),
            variant: ty.to_string(),
        })
    }

    /// A call of `name` with `args`; `params` are the trigger's (field, type) by the
    /// names the definition uses.
    fn call(
        &self,
        path: &str,
        what: &str,
        name: &str,
        args: &[String],
        params: &[(String, String, ParamTy)],
        doc: Option<&String>,
    ) -> Result<Call, String> {
        let segs: Vec<&str> = name.split('.').collect();
        let (base, prefix) = segs.split_last().map_or((name, &[][..]), |(b, p)| (*b, p));
        let owner = self.owner_of(prefix).ok_or_else(|| {
            self.err(
                path,
                what,
                format!(
                    "`{name}`: `{}` names no inherited service",
                    prefix.join(".")
                ),
            )
        })?;
        let mut out = Vec::new();
        for a in args {
            let a = a.trim();
            if let Some(q) = a
                .strip_prefix('\'')
                .and_then(|x| x.strip_suffix('\''))
                .or_else(|| a.strip_prefix('"').and_then(|x| x.strip_suffix('"')))
            {
                out.push(Arg::Const(q.trim().to_string()));
            } else if let Some((_, field, ty)) = params.iter().find(|(n, _, _)| n == a) {
                out.push(Arg::Param {
                    field: field.clone(),
                    ty: ty.clone(),
                });
            } else if a.parse::<f64>().is_ok() {
                out.push(Arg::Const(a.to_string()));
            } else {
                return Err(self.err(
                    path,
                    what,
                    format!("`{name}`: argument `{a}` is neither a parameter of the trigger nor a quoted constant"),
                ));
            }
        }
        Ok(Call {
            owner,
            method: ident(base),
            raw: format!(
                "{name}({})",
                args.iter().map(|a| a.trim()).collect::<Vec<_>>().join(", ")
            ),
            args: out,
            doc: doc.cloned(),
            origin: self.at(path),
        })
    }

    fn actions(
        &self,
        path: &str,
        what: &str,
        list: &[ActionDef],
        params: &[(String, String, ParamTy)],
    ) -> Result<Vec<Call>, String> {
        list.iter()
            .enumerate()
            .map(|(i, a)| {
                let p = format!("{path}[{i}]");
                self.call(&p, what, &a.name, &a.args, params, a.description.as_ref())
            })
            .collect()
    }

    fn cond(
        &self,
        path: &str,
        what: &str,
        c: &Cond,
        params: &[(String, String, ParamTy)],
        doc: Option<&String>,
    ) -> Result<G, String> {
        Ok(match c {
            Cond::Call(n, a) => G::Call(self.call(path, what, n, a, params, doc)?),
            Cond::Const(b) => G::Const(*b),
            Cond::Not(e) => G::Not(Box::new(self.cond(path, what, e, params, doc)?)),
            Cond::And(v) => G::And(
                v.iter()
                    .map(|e| self.cond(path, what, e, params, doc))
                    .collect::<Result<_, _>>()?,
            ),
            Cond::Or(v) => G::Or(
                v.iter()
                    .map(|e| self.cond(path, what, e, params, doc))
                    .collect::<Result<_, _>>()?,
            ),
        })
    }

    fn trans(&self, path: &str, t: &ServiceTransitionDef) -> Result<Trans, String> {
        let what = match &t.on {
            Some(on) => format!("transition `{on}`"),
            None => "default transition".to_string(),
        };
        let mut params = Vec::new();
        for (i, p) in t.parameters.iter().enumerate() {
            let ty = self.param_ty(&p.ty).ok_or_else(|| {
                self.err(
                    &format!("{path}.parameters[{i}].type"),
                    &what,
                    format!("parameter `{}`: `{}` is not a message, an event of the service or its parents, or a type", p.name, p.ty),
                )
            })?;
            params.push((p.name.clone(), ident(&p.name), ty));
        }
        let key = t.on.as_ref().map(|on| {
            let base = on.rsplit('.').next().unwrap_or(on);
            t.parameters
                .iter()
                .find(|p| self.spec.message(&p.ty).is_some())
                .map_or_else(|| base.to_string(), |p| p.ty.clone())
        });
        let guard = match &t.guard {
            None => None,
            Some(g) => {
                let gp = format!("{path}.guard.condition");
                let c = guard::parse(&g.condition)
                    .map_err(|e| self.err(&gp, &what, format!("guard `{}`: {e}", g.condition)))?;
                Some(self.cond(&gp, &what, &c, &params, g.description.as_ref())?)
            }
        };
        let actions = self.actions(&format!("{path}.actions"), &what, &t.actions, &params)?;
        Ok(Trans {
            key,
            on: t.on.clone(),
            params: params.into_iter().map(|(_, f, ty)| (f, ty)).collect(),
            guard,
            kind: t.kind,
            to: t.to.clone(),
            actions,
            raise: t
                .pop
                .as_ref()
                .map(|p| p.name.rsplit('.').next().unwrap_or(&p.name).to_string()),
            doc: t.description.clone(),
            origin: self.at(path),
        })
    }

    fn list(
        &self,
        path: &str,
        key: &str,
        ts: &[ServiceTransitionDef],
    ) -> Result<Vec<Trans>, String> {
        ts.iter()
            .enumerate()
            .map(|(i, t)| self.trans(&format!("{path}.{key}[{i}]"), t))
            .collect()
    }

    fn state(&self, path: &str, s: &StateDef) -> Result<St, String> {
        let what = format!("state `{}`", s.name);
        let mut transitions = self.list(path, "transitions", &s.transitions)?;
        let mut defaults = self.list(path, "default_transitions", &s.default_transitions)?;
        if let Some(d) = &s.default {
            transitions.extend(self.list(
                &format!("{path}.default"),
                "transitions",
                &d.transitions,
            )?);
            defaults.extend(self.list(
                &format!("{path}.default"),
                "default_transitions",
                &d.default_transitions,
            )?);
        }
        Ok(St {
            name: s.name.clone(),
            initial: s.initial.clone(),
            redefine: s.redefine,
            entry: self.actions(&format!("{path}.entry"), &what, &s.entry, &[])?,
            exit: self.actions(&format!("{path}.exit"), &what, &s.exit, &[])?,
            transitions,
            defaults,
            states: s
                .states
                .iter()
                .enumerate()
                .map(|(i, c)| self.state(&format!("{path}.states[{i}]"), c))
                .collect::<Result<_, _>>()?,
            origin: self.at(path),
        })
    }

    /// The service's own machines, with their start states.
    pub(crate) fn machines(&self) -> Result<Vec<Mach>, String> {
        let s = &self.spec.services[self.svc];
        let Some(b) = &s.def.behaviour else {
            return Ok(Vec::new());
        };
        let mut out = Vec::new();
        for (i, m) in b.machines.iter().enumerate() {
            let path = format!("{}.behaviour.machines[{i}]", s.path);
            out.push(self.machine(&path, m)?);
        }
        for (i, st) in b.start.iter().enumerate() {
            let base = st.machine.rsplit('.').next().unwrap_or(&st.machine);
            if let Some(m) = out.iter_mut().find(|m| m.name == base) {
                m.start = Some((
                    st.state.clone(),
                    self.at(&format!("{}.behaviour.start[{i}]", s.path)),
                ));
            }
        }
        Ok(out)
    }

    fn machine(&self, path: &str, m: &MachineDef) -> Result<Mach, String> {
        let (mut transitions, mut defaults) = (Vec::new(), Vec::new());
        if let Some(d) = &m.default {
            transitions = self.list(&format!("{path}.default"), "transitions", &d.transitions)?;
            defaults = self.list(
                &format!("{path}.default"),
                "default_transitions",
                &d.default_transitions,
            )?;
        }
        Ok(Mach {
            name: m.name.rsplit('.').next().unwrap_or(&m.name).to_string(),
            doc: m.description.clone(),
            extends: m.extends,
            start: None,
            states: m
                .states
                .iter()
                .enumerate()
                .map(|(i, s)| self.state(&format!("{path}.states[{i}]"), s))
                .collect::<Result<_, _>>()?,
            transitions,
            defaults,
            origin: self.at(path),
        })
    }
}

/// Merges a service's own machines into those it inherits: a machine that `extends`
/// one of the parent's adds its states and transitions (a state of the same name that
/// `redefine`s the parent's extends it: its transitions are tried before the parent's,
/// its entry actions run after and its exit actions before the parent's, its `initial`
/// wins; a state of the same name without `redefine` replaces the parent's); its start
/// state, if it gives one, wins. Other machines are added.
pub(crate) fn merge(
    inherited: &mut Vec<Mach>,
    own: Vec<Mach>,
    service: &str,
) -> Result<(), String> {
    for m in own {
        if !m.extends {
            inherited.push(m);
            continue;
        }
        let Some(p) = inherited.iter_mut().find(|p| p.name == m.name) else {
            return Err(format!(
                "{}: service `{service}`, state machine `{}` extends a machine no inherited service has",
                m.origin, m.name
            ));
        };
        if m.start.is_some() {
            p.start = m.start;
        }
        if m.doc.is_some() {
            p.doc = m.doc;
        }
        p.transitions.splice(0..0, m.transitions);
        p.defaults.splice(0..0, m.defaults);
        merge_states(&mut p.states, m.states);
    }
    Ok(())
}

fn merge_states(parent: &mut Vec<St>, child: Vec<St>) {
    for c in child {
        match parent.iter_mut().find(|p| p.name == c.name) {
            Some(p) if c.redefine => {
                if c.initial.is_some() {
                    p.initial = c.initial;
                }
                p.entry.extend(c.entry);
                p.exit.splice(0..0, c.exit);
                p.transitions.splice(0..0, c.transitions);
                p.defaults.splice(0..0, c.defaults);
                merge_states(&mut p.states, c.states);
            }
            Some(p) => *p = c,
            None => parent.push(c),
        }
    }
}
