//! From the merged machines to the template context (the methods bound and their
//! signatures are `methods`): triggers, numbered call sites and the state tables.

use super::methods::{bind_owners, doc_lines, short, signatures, Method, Sig};
use super::model::{chain, ident, origin, parents, Arg, Call, Conv, Mach, St, Trans, G};
use super::{
    ArgVariantCtx, EventCtx, FieldCtx, InheritedCtx, MachineCtx, MethodCtx, ReceivedArm,
    ReceivedCtx, ServiceCtx, ServicesCtx, SiteCtx, StateCtx, TransCtx, TriggerCtx,
};
use jaus_spec::model::{FieldDef, TransitionKind};
use jaus_spec::{Int, Spec};
use std::collections::BTreeMap;

/// The template context of every service of `spec`; the error names the service and
/// the file and line.
///
/// `base` is the Rust path of the generated messages of the base definitions the set is
/// built on (`::jaus_as4::messages`), if any: their services are not generated again;
/// a service of the set that inherits one of them calls the inherited guards and actions
/// on an implementation of the base's trait, handed to its `Machines` beside the
/// service's own.
///
/// `delegate` is a service id prefix (`urn:jaus:jss:core:`) naming services of the set
/// itself that the others inherit by delegation, as they would a base's: the delegated
/// services are generated as usual, and a service inheriting one of them calls the
/// inherited guards and actions on a second implementation (its trait does not extend
/// the inherited trait). One implementation of the delegated services (a component's
/// Core) then serves every service built on them, each implemented apart.
///
/// `host` is the path of the crate that hosts a set without base definitions
/// (`crate` for jaus-as4 itself): with it, each service built on a delegated one gets
/// the same `Hosted<S>` adapter as a service on a base.
pub fn build_services(
    spec: &Spec,
    base: Option<&str>,
    delegate: Option<&str>,
    host: Option<&str>,
) -> Result<ServicesCtx, String> {
    let parents = parents(spec)?;
    let n = spec.services.len();
    // A service of the base definitions: not generated here.
    let external = |k: usize| base.is_some() && !spec.is_own(spec.services[k].source);
    let delegated = |k: usize| delegate.is_some_and(|p| spec.services[k].def.id.starts_with(p));
    // A service whose guards and actions a service inheriting it calls on a second
    // implementation.
    let is_base = |k: usize| external(k) || delegated(k);
    let services_path = base.map_or_else(|| "super".to_string(), |b| format!("{b}::services"));
    // Each service's own machines, names resolved against its ancestors.
    let mut own: Vec<Vec<Mach>> = Vec::with_capacity(n);
    for svc in 0..n {
        own.push(
            Conv {
                spec,
                parents: &parents,
                svc,
                base,
            }
            .machines()?,
        );
    }
    bind_owners(&mut own, &parents);
    let (methods, args) = signatures(&mut own, &external)?;
    // Merge, root services first.
    let mut merged: Vec<Option<Vec<Mach>>> = vec![None; n];
    for i in 0..n {
        let c = chain(&parents, i);
        for &k in c.iter().rev() {
            if merged[k].is_some() {
                continue;
            }
            let mut base = match parents[k] {
                Some(p) => merged[p].clone().unwrap_or_default(),
                None => Vec::new(),
            };
            let mine = own[k].clone();
            if parents[k].is_none() {
                if let Some(m) = mine.iter().find(|m| m.extends) {
                    return Err(format!(
                        "{}: service `{}`, state machine `{}` extends a machine, but the service inherits from none",
                        m.origin, spec.services[k].def.name, m.name
                    ));
                }
            }
            super::model::merge(&mut base, mine, &spec.services[k].def.name)?;
            merged[k] = Some(base);
        }
    }
    let mut services = Vec::new();
    let standalone = |_: usize| false;
    for (i, m) in merged.iter().enumerate() {
        if external(i) {
            continue;
        }
        let machines = m.clone().unwrap_or_default();
        // A delegated service is generated as a service of its own (its supertraits are
        // its ancestors); the others call into it.
        let on = Inherit {
            base,
            host,
            services: &services_path,
            is_base: if delegated(i) { &standalone } else { &is_base },
        };
        services.push(service(
            spec,
            i,
            &parents,
            &machines,
            &methods,
            !args.is_empty(),
            &on,
        )?);
    }
    let has_args = methods.values().any(|m| matches!(m.sig, Sig::Slice));
    let args_lt = if args.is_empty() { "" } else { "<'a>" }.to_string();
    let args: Vec<ArgVariantCtx> = args
        .into_iter()
        .map(|(name, ty)| ArgVariantCtx { name, ty })
        .collect();
    Ok(ServicesCtx {
        services,
        has_args,
        args,
        args_lt,
    })
}

/// The Rust type of an event field.
fn field_ty(f: &FieldDef) -> String {
    let base = if f.scale.is_some() {
        "f64".to_string()
    } else {
        match f.ty.as_str() {
            "string" => "String".into(),
            "bytes" | "message" => "Vec<u8>".into(),
            "flag" => "bool".into(),
            "f32" | "float" => "f32".into(),
            "f64" | "double" | "long float" => "f64".into(),
            "list" => {
                let e = f.of.as_ref().map_or("u8".to_string(), |e| field_ty(&e.0));
                format!("Vec<{e}>")
            }
            t => Int::parse(t).map_or_else(|| t.to_string(), |i| i.rust().to_string()),
        }
    };
    if f.bit.is_some() {
        format!("Option<{base}>")
    } else {
        base
    }
}

fn some<T: std::fmt::Display>(v: Option<T>) -> String {
    v.map_or_else(|| "None".to_string(), |x| format!("Some({x})"))
}

fn list(v: &[u16]) -> String {
    format!(
        "&[{}]",
        v.iter().map(u16::to_string).collect::<Vec<_>>().join(", ")
    )
}

/// What a service of a set built on base definitions (or on delegated services of its
/// own set) inherits from them.
struct Inherit<'a> {
    /// The base's generated messages (`::jaus_as4::messages`), for a set on base
    /// definitions.
    base: Option<&'a str>,
    /// The crate hosting a set without base definitions (`crate`), if it hosts one.
    host: Option<&'a str>,
    /// Where the inherited services' traits are: the base's `services` module, or
    /// `super` for delegated services of the set.
    services: &'a str,
    /// Whether service `k` is one whose guards and actions run on a second
    /// implementation.
    is_base: &'a dyn Fn(usize) -> bool,
}

/// Builds one service's context.
struct Emit<'a> {
    is_base: &'a dyn Fn(usize) -> bool,
    /// Where the inherited services' traits are, for the `Arg` of inherited methods.
    services: &'a str,
    methods: &'a BTreeMap<(usize, String), Method>,
    borrows_args: bool,
    guards: Vec<SiteCtx>,
    actions: Vec<SiteCtx>,
    service: String,
    /// The service and the ancestors whose traits are its supertraits (up to the first
    /// base service), each with its trait's path from the service's module.
    supers: Vec<(usize, String)>,
}

impl Emit<'_> {
    fn call_expr(&mut self, c: &Call) -> String {
        let slice = matches!(
            self.methods
                .get(&(c.owner, c.method.clone()))
                .map(|m| &m.sig),
            Some(Sig::Slice)
        );
        // An inherited method of a base service takes the base's `Arg`.
        let arg = if (self.is_base)(c.owner) {
            format!("{}::Arg", self.services)
        } else {
            "super::Arg".to_string()
        };
        let args: Vec<String> = c
            .args
            .iter()
            .map(|a| match (a, slice) {
                (Arg::Const(v), false) => format!("{v:?}"),
                (Arg::Param { field, .. }, false) => field.clone(),
                (Arg::Const(v), true) => format!("{arg}::Const({v:?})"),
                (Arg::Param { field, ty }, true) => {
                    format!("{arg}::{}({field})", ty.variant)
                }
            })
            .collect();
        // The service's own methods are on its implementation; inherited ones of a base
        // service on the base's.
        let on = if (self.is_base)(c.owner) { 1 } else { 0 };
        let args = if slice {
            format!("&[{}]", args.join(", "))
        } else {
            args.join(", ")
        };
        // Two traits of the service's supertrait chain declaring a method of the same
        // name (with other arguments) would make `self.0.method()` ambiguous (E0034):
        // call it through its trait.
        let shadowed = on == 0
            && self
                .supers
                .iter()
                .any(|(k, _)| *k != c.owner && self.methods.contains_key(&(*k, c.method.clone())));
        match self.supers.iter().find(|(k, _)| *k == c.owner) {
            Some((_, path)) if shadowed => {
                let guard = self
                    .methods
                    .get(&(c.owner, c.method.clone()))
                    .is_some_and(|m| m.guard);
                let me = if guard { "&*self.0" } else { "&mut *self.0" };
                let sep = if args.is_empty() { "" } else { ", " };
                format!("{path}::{}({me}{sep}{args})", c.method)
            }
            _ => format!("self.{on}.{}({args})", c.method),
        }
    }

    fn pattern(n: usize, key: Option<&str>, c: &Call) -> String {
        let fields: Vec<&str> = c
            .args
            .iter()
            .filter_map(|a| match a {
                Arg::Param { field, .. } => Some(field.as_str()),
                Arg::Const(_) => None,
            })
            .collect();
        match (key, fields.is_empty()) {
            (Some(k), false) => {
                let mut f: Vec<&str> = Vec::new();
                for x in fields {
                    if !f.contains(&x) {
                        f.push(x);
                    }
                }
                format!("({n}, Some(Trigger::{k} {{ {}, .. }}))", f.join(", "))
            }
            _ => format!("({n}, _)"),
        }
    }

    fn site(&mut self, guard: bool, key: Option<&str>, c: &Call) -> Result<u16, String> {
        if key.is_none() && c.args.iter().any(|a| matches!(a, Arg::Param { .. })) {
            return Err(format!(
                "{}: service `{}`: `{}` uses a trigger parameter where there is no trigger (an entry or exit action, or a default transition)",
                c.origin, self.service, c.raw
            ));
        }
        let call = self.call_expr(c);
        let v = if guard {
            &mut self.guards
        } else {
            &mut self.actions
        };
        let n = v.len();
        let follows = key.is_none() && !(self.is_base)(c.owner);
        v.push(SiteCtx {
            pattern: Self::pattern(n, key, c),
            call,
            follows,
        });
        u16::try_from(n)
            .map_err(|_| format!("service `{}`: more than 65535 call sites", self.service))
    }

    fn expr(&mut self, key: Option<&str>, g: &G) -> Result<String, String> {
        Ok(match g {
            G::Call(c) => format!("hsm::Expr::Call({})", self.site(true, key, c)?),
            G::Const(b) => format!("hsm::Expr::Const({b})"),
            G::Not(e) => format!("hsm::Expr::Not(&{})", self.expr(key, e)?),
            G::And(v) | G::Or(v) => {
                let items = v
                    .iter()
                    .map(|e| self.expr(key, e))
                    .collect::<Result<Vec<_>, _>>()?;
                let op = if matches!(g, G::And(_)) { "And" } else { "Or" };
                format!("hsm::Expr::{op}(&[{}])", items.join(", "))
            }
        })
    }

    fn actions(&mut self, key: Option<&str>, calls: &[Call]) -> Result<String, String> {
        let ids = calls
            .iter()
            .map(|c| self.site(false, key, c))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(list(&ids))
    }

    fn trans(&mut self, t: &Trans, ids: &BTreeMap<String, usize>) -> Result<TransCtx, String> {
        let key = t.key.as_deref();
        let guard = match &t.guard {
            Some(g) => format!("Some(&{})", self.expr(key, g)?),
            None => "None".into(),
        };
        let actions = self.actions(key, &t.actions)?;
        let target = match (&t.to, t.kind) {
            (Some(to), TransitionKind::Simple | TransitionKind::Push) => Some(
                *ids.get(to).ok_or_else(|| {
                    format!(
                        "{}: service `{}`: `{to}` is not a state of the machine (with the inherited states)",
                        t.origin, self.service
                    )
                })?,
            ),
            _ => None,
        };
        let kind = match t.kind {
            TransitionKind::Internal => "Internal",
            TransitionKind::Simple => "Simple",
            TransitionKind::Push => "Push",
            TransitionKind::Pop => "Pop",
        };
        Ok(TransCtx {
            trigger: some(key.map(|k| format!("{k:?}"))),
            guard,
            kind: kind.into(),
            target: some(target),
            actions,
            raise: some(t.raise.as_ref().map(|k| format!("{k:?}"))),
            origin: short(&t.origin),
        })
    }
}

/// States in preorder with their paths and parents.
fn flatten<'m>(
    states: &'m [St],
    parent: Option<usize>,
    prefix: &str,
    out: &mut Vec<(&'m St, String, Option<usize>)>,
) {
    for s in states {
        let path = if prefix.is_empty() {
            s.name.clone()
        } else {
            format!("{prefix}.{}", s.name)
        };
        let id = out.len();
        out.push((s, path.clone(), parent));
        flatten(&s.states, Some(id), &path, out);
    }
}

fn service(
    spec: &Spec,
    i: usize,
    parents: &[Option<usize>],
    machines: &[Mach],
    methods: &BTreeMap<(usize, String), Method>,
    args: bool,
    on: &Inherit<'_>,
) -> Result<ServiceCtx, String> {
    let s = &spec.services[i];
    let d = &s.def;
    let mut e = Emit {
        is_base: on.is_base,
        services: on.services,
        methods,
        borrows_args: args,
        guards: Vec::new(),
        actions: Vec::new(),
        service: d.name.clone(),
        supers: chain(parents, i)
            .into_iter()
            .take_while(|k| !(on.is_base)(*k))
            .map(|k| {
                let n = &spec.services[k].def.name;
                (k, format!("super::{}::{n}", ident(n)))
            })
            .collect(),
    };
    // Triggers: the union of the parameters of every transition with the key.
    let mut triggers: Vec<TriggerCtx> = Vec::new();
    let mut trig_types: BTreeMap<(String, String), (String, String)> = BTreeMap::new();
    let mut all: Vec<&Trans> = Vec::new();
    fn collect<'m>(st: &'m [St], all: &mut Vec<&'m Trans>) {
        for s in st {
            all.extend(s.transitions.iter().chain(&s.defaults));
            collect(&s.states, all);
        }
    }
    for m in machines {
        all.extend(m.transitions.iter().chain(&m.defaults));
        collect(&m.states, &mut all);
    }
    for t in &all {
        let Some(k) = &t.key else { continue };
        let at = match triggers.iter().position(|x| x.variant == *k) {
            Some(at) => at,
            None => {
                let carries_message = t
                    .params
                    .iter()
                    .any(|(_, ty)| spec.message(&ty.rust).is_some());
                let mut doc = vec![match &t.on {
                    Some(on) if on != k && carries_message => format!("`{on}` carrying [`{k}`]."),
                    Some(on) => format!("`{on}`."),
                    None => format!("`{k}`."),
                }];
                let more = match d.events.iter().find(|ev| ev.name == *k) {
                    Some(ev) => doc_lines(ev.description.as_deref()),
                    None => doc_lines(t.doc.as_deref()),
                };
                if !more.is_empty() {
                    doc.push(String::new());
                    doc.extend(more);
                }
                triggers.push(TriggerCtx {
                    variant: k.clone(),
                    doc,
                    fields: Vec::new(),
                });
                triggers.len() - 1
            }
        };
        for (field, ty) in &t.params {
            let slot = (k.clone(), field.clone());
            match trig_types.get(&slot) {
                Some((rust, first)) if *rust != ty.rust => {
                    return Err(format!(
                        "{}: service `{}`: trigger `{k}` has parameter `{field}` of type `{}` here and `{rust}` at {first}",
                        t.origin, d.name, ty.rust
                    ))
                }
                Some(_) => {}
                None => {
                    trig_types.insert(slot, (ty.rust.clone(), t.origin.clone()));
                    triggers[at].fields.push(FieldCtx {
                        name: field.clone(),
                        ty: format!("&'a {}", ty.rust),
                        doc: Vec::new(),
                    });
                }
            }
        }
    }
    let borrows = triggers.iter().any(|t| !t.fields.is_empty());
    let received = received(spec, &triggers, on);
    let mut out_machines = Vec::new();
    let (mut state_count, mut transition_count) = (0, 0);
    for m in machines {
        let mut flat = Vec::new();
        flatten(&m.states, None, "", &mut flat);
        let ids: BTreeMap<String, usize> = flat
            .iter()
            .enumerate()
            .map(|(k, (_, p, _))| (p.clone(), k))
            .collect();
        let start = match &m.start {
            Some((path, at)) => *ids.get(path).ok_or_else(|| {
                format!(
                    "{at}: service `{}`: start state `{path}` is not a state of machine `{}`",
                    d.name, m.name
                )
            })?,
            None => 0,
        };
        let mut states = Vec::new();
        for (st, path, parent) in &flat {
            let initial = match &st.initial {
                Some(init) => Some(*ids.get(&format!("{path}.{init}")).ok_or_else(|| {
                    format!(
                        "{}: service `{}`: initial state `{init}` is not a sub-state of `{path}`",
                        st.origin, d.name
                    )
                })?),
                None => None,
            };
            let entry = e.actions(None, &st.entry)?;
            let exit = e.actions(None, &st.exit)?;
            let transitions = st
                .transitions
                .iter()
                .map(|t| e.trans(t, &ids))
                .collect::<Result<Vec<_>, _>>()?;
            let defaults = st
                .defaults
                .iter()
                .map(|t| e.trans(t, &ids))
                .collect::<Result<Vec<_>, _>>()?;
            transition_count += transitions.len() + defaults.len();
            states.push(StateCtx {
                name: st.name.clone(),
                path: path.clone(),
                parent: some(*parent),
                initial: some(initial),
                entry,
                exit,
                transitions,
                defaults,
            });
        }
        state_count += states.len();
        let transitions = m
            .transitions
            .iter()
            .map(|t| e.trans(t, &ids))
            .collect::<Result<Vec<_>, _>>()?;
        let defaults = m
            .defaults
            .iter()
            .map(|t| e.trans(t, &ids))
            .collect::<Result<Vec<_>, _>>()?;
        transition_count += transitions.len() + defaults.len();
        let mut doc = vec![format!("State machine `{}` of [`{}`]", m.name, d.name)];
        doc[0].push_str(if m.extends || parents[i].is_some() {
            " (with what it inherits)."
        } else {
            "."
        });
        if let Some(x) = &m.doc {
            doc.push(String::new());
            doc.extend(doc_lines(Some(x)));
        }
        out_machines.push(MachineCtx {
            name: m.name.clone(),
            ident: ident(&m.name).to_uppercase(),
            doc,
            start,
            states,
            transitions,
            defaults,
        });
    }
    // The trait's own methods: guards, then actions, by name.
    let mut own: Vec<(&String, &Method)> = methods
        .iter()
        .filter(|((owner, _), _)| *owner == i)
        .map(|((_, name), m)| (name, m))
        .collect();
    own.sort_by_key(|(name, m)| (!m.guard, (*name).clone()));
    let methods_ctx = own
        .into_iter()
        .map(|(name, m)| {
            let recv = if m.guard { "&self" } else { "&mut self" };
            let params = match &m.sig {
                Sig::Typed(v) => v.iter().map(|(n, t)| format!(", {n}: {t}")).collect(),
                Sig::Slice => format!(
                    ", args: &[super::Arg{}]",
                    if e.borrows_args { "<'_>" } else { "" }
                ),
            };
            let ret = if m.guard { " -> bool" } else { "" };
            MethodCtx {
                sig: format!("fn {name}({recv}{params}){ret}"),
                doc: m.doc.clone(),
            }
        })
        .collect();
    let events = d
        .events
        .iter()
        .map(|ev| EventCtx {
            name: ev.name.clone(),
            doc: {
                let mut v = vec![format!("Internal event `{}` of [`{}`].", ev.name, d.name)];
                let more = doc_lines(ev.description.as_deref());
                if !more.is_empty() {
                    v.push(String::new());
                    v.extend(more);
                }
                v
            },
            fields: ev
                .fields
                .iter()
                .map(|f| FieldCtx {
                    name: ident(&f.name),
                    ty: field_ty(f),
                    doc: doc_lines(f.description.as_deref()),
                })
                .collect(),
        })
        .collect();
    let mut doc = vec![format!(
        "The {} service (`{}` version {}).",
        d.name, d.id, d.version
    )];
    for text in [
        d.description.as_deref(),
        d.assumptions.as_deref().map(|a| a.trim()),
    ] {
        let lines = doc_lines(text);
        if !lines.is_empty() {
            doc.push(String::new());
            doc.extend(lines);
        }
    }
    // A `Hosted` adapter when the service inherits a base (or delegated) service and
    // its messages arrive with Transport's `Receive` data alone (the JSIDL convention):
    // on the base's crate, whose `Message` carries the set's messages raw, or on the
    // crate hosting the set, whose `Message` is the set's own.
    let hosting = match on.base {
        Some(b) => Some((b.trim_end_matches("::messages").to_string(), true)),
        None => on.host.map(|h| (h.to_string(), false)),
    };
    let hosting = hosting.filter(|_| {
        chain(parents, i).into_iter().any(|k| (on.is_base)(k))
            && received.as_ref().is_some_and(|r| {
                r.params.len() == 1 && r.params[0].ty.ends_with("::transport::event::Receive")
            })
    });
    let hosted_raw = hosting.as_ref().is_some_and(|h| h.1);
    let hosted = hosting.map(|h| h.0);
    let version = {
        let mut it = d
            .version
            .split('.')
            .map(|x| x.trim().parse::<u8>().unwrap_or(0));
        (it.next().unwrap_or(0), it.next().unwrap_or(0))
    };
    Ok(ServiceCtx {
        name: d.name.clone(),
        module: ident(&d.name),
        id: format!("{} {}", d.id, d.version),
        doc,
        origin: short(&origin(spec, s.source, &s.path)),
        supertrait: parents[i].filter(|p| !(on.is_base)(*p)).map(|p| {
            let n = &spec.services[p].def.name;
            format!("super::{}::{n}", ident(n))
        }),
        inherited: chain(parents, i)
            .into_iter()
            .find(|k| (on.is_base)(*k))
            .map(|k| {
                let n = &spec.services[k].def.name;
                let b = on.services;
                InheritedCtx {
                    name: n.clone(),
                    path: format!("{b}::{}::{n}", ident(n)),
                    machines: format!("{b}::{}::Machines", ident(n)),
                    tables: format!("{b}::{}::MACHINES", ident(n)),
                }
            }),
        hosted,
        hosted_raw,
        uri: d.id.clone(),
        major: version.0,
        minor: version.1,
        events,
        methods: methods_ctx,
        lt: if borrows { "<'a>" } else { "" }.into(),
        lt_anon: if borrows { "<'_>" } else { "" }.into(),
        triggers,
        guards: e.guards,
        actions: e.actions,
        machines: out_machines,
        received,
        state_count,
        transition_count,
    })
}

/// The dispatch of received messages: every trigger with one parameter of a message type
/// gets an arm, when all of them have the same other parameters (names and types, in
/// order); `None` when no trigger carries a message or their other parameters differ
/// (the trait and tables are generated all the same; the owner builds triggers itself).
fn received(spec: &Spec, triggers: &[TriggerCtx], on: &Inherit<'_>) -> Option<ReceivedCtx> {
    let is_message = |ty: &str| {
        let name = ty.trim_start_matches("&'a ");
        spec.message(name).is_some()
    };
    let mut params: Option<Vec<(String, String)>> = None;
    let mut arms = Vec::new();
    for t in triggers {
        let mut carried = t.fields.iter().filter(|f| is_message(&f.ty));
        let Some(m) = carried.next() else { continue };
        if carried.next().is_some() || m.ty.trim_start_matches("&'a ") != t.variant {
            return None;
        }
        let rest: Vec<(String, String)> = t
            .fields
            .iter()
            .filter(|f| f.name != m.name)
            .map(|f| (f.name.clone(), f.ty.trim_start_matches("&'a ").to_string()))
            .collect();
        match &params {
            Some(p) if *p != rest => return None,
            Some(_) => {}
            None => params = Some(rest),
        }
        // A base message is in the set's `Message` as the base's.
        let from_base = on.base.filter(|_| {
            spec.message(&t.variant)
                .is_some_and(|x| !spec.is_own(x.source))
        });
        arms.push(ReceivedArm {
            pattern: match from_base {
                Some(b) => format!("Message::Jaus({b}::Message::{}({}))", t.variant, m.name),
                None => format!("Message::{}({})", t.variant, m.name),
            },
            message: t.variant.clone(),
            field: m.name.clone(),
        });
    }
    let params = params?;
    arms.sort_by(|a, b| a.message.cmp(&b.message));
    Some(ReceivedCtx {
        params: params
            .into_iter()
            .map(|(name, ty)| FieldCtx {
                name,
                ty,
                doc: Vec::new(),
            })
            .collect(),
        arms,
    })
}
