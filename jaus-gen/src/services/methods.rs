//! Who declares each method a service's machines call, and its signature: calls bound
//! to the services whose traits declare them ([`bind_owners`]), each method's
//! signature from all its call sites ([`signatures`]).

use super::model::{chain, Arg, Call, Mach, St, Trans, G};
use crate::components::wrap;
use std::collections::{BTreeMap, BTreeSet};

/// The shape of one argument position.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Shape {
    Param(String),
    Const,
}

/// How a method is declared.
#[derive(Debug, Clone)]
pub(super) enum Sig {
    /// One parameter per argument: `(name, Rust type)`.
    Typed(Vec<(String, String)>),
    /// Call sites differ: `args: &[Arg<'_>]`.
    Slice,
}

#[derive(Debug, Clone)]
pub(super) struct Method {
    pub(super) guard: bool,
    pub(super) sig: Sig,
    pub(super) doc: Vec<String>,
}

pub(super) fn doc_lines(text: Option<&str>) -> Vec<String> {
    text.map(|t| wrap(t, 86)).unwrap_or_default()
}

pub(super) fn each_call(m: &mut Mach, f: &mut dyn FnMut(&mut Call, bool)) {
    fn g(x: &mut G, f: &mut dyn FnMut(&mut Call, bool)) {
        match x {
            G::Call(c) => f(c, true),
            G::Const(_) => {}
            G::Not(e) => g(e, f),
            G::And(v) | G::Or(v) => v.iter_mut().for_each(|e| g(e, f)),
        }
    }
    fn t(x: &mut Trans, f: &mut dyn FnMut(&mut Call, bool)) {
        if let Some(e) = &mut x.guard {
            g(e, f);
        }
        x.actions.iter_mut().for_each(|c| f(c, false));
    }
    fn s(x: &mut St, f: &mut dyn FnMut(&mut Call, bool)) {
        x.entry.iter_mut().for_each(|c| f(c, false));
        x.exit.iter_mut().for_each(|c| f(c, false));
        x.transitions.iter_mut().for_each(|y| t(y, f));
        x.defaults.iter_mut().for_each(|y| t(y, f));
        x.states.iter_mut().for_each(|y| s(y, f));
    }
    m.transitions.iter_mut().for_each(|y| t(y, f));
    m.defaults.iter_mut().for_each(|y| t(y, f));
    m.states.iter_mut().for_each(|y| s(y, f));
}

/// Binds each call to the service whose trait declares its method. A method named
/// without a prefix belongs to the farthest ancestor that declares it too with the same
/// arguments, so that no trait repeats a supertrait's method; one of the same name but
/// other arguments is the service's own (UGV's `isSupported` of a Set Configuration is
/// not the Events' `isSupported` of a Create Event).
pub(super) fn bind_owners(own: &mut [Vec<Mach>], parents: &[Option<usize>]) {
    let mut declared: BTreeMap<(usize, String), BTreeSet<Vec<Shape>>> = BTreeMap::new();
    for ms in own.iter_mut() {
        for m in ms.iter_mut() {
            each_call(m, &mut |c, _| {
                declared
                    .entry((c.owner, c.method.clone()))
                    .or_default()
                    .insert(c.args.iter().map(shape).collect());
            });
        }
    }
    for ms in own.iter_mut() {
        for m in ms.iter_mut() {
            each_call(m, &mut |c, _| {
                let here: Vec<Shape> = c.args.iter().map(shape).collect();
                if let Some(up) = chain(parents, c.owner).into_iter().rev().find(|a| {
                    declared
                        .get(&(*a, c.method.clone()))
                        .is_some_and(|s| s.contains(&here))
                }) {
                    c.owner = up;
                }
            });
        }
    }
}

pub(super) fn shape(a: &Arg) -> Shape {
    match a {
        Arg::Param { ty, .. } => Shape::Param(ty.rust.clone()),
        Arg::Const(_) => Shape::Const,
    }
}

/// Every method's signature, from all its call sites in the set.
#[allow(clippy::type_complexity)]
pub(super) fn signatures(
    own: &mut [Vec<Mach>],
    external: &dyn Fn(usize) -> bool,
) -> Result<(BTreeMap<(usize, String), Method>, BTreeMap<String, String>), String> {
    let mut args: BTreeMap<String, String> = BTreeMap::new();
    let mut sites: BTreeMap<(usize, String), Vec<(bool, Call)>> = BTreeMap::new();
    // Calls from the set's own services of methods a base service declares.
    let mut onto_base: Vec<Call> = Vec::new();
    for (k, ms) in own.iter_mut().enumerate() {
        for m in ms.iter_mut() {
            each_call(m, &mut |c, guard| {
                // A delegated service of the set is generated here: a call onto it
                // declares its method as any call does.
                if external(c.owner) && !external(k) {
                    onto_base.push(c.clone());
                    return;
                }
                sites
                    .entry((c.owner, c.method.clone()))
                    .or_default()
                    .push((guard, c.clone()));
            });
        }
    }
    // An inherited method is called as the base declares it: its trait is generated
    // already, from the base's own call sites.
    for c in &onto_base {
        let Some(list) = sites.get(&(c.owner, c.method.clone())) else {
            return Err(format!(
                "{}: `{}` names a method the inherited service does not declare (its definitions never call `{}`): name an action or guard of this service instead",
                c.origin, c.raw, c.method
            ));
        };
        let declared: Vec<Shape> = list[0].1.args.iter().map(shape).collect();
        let uniform = list
            .iter()
            .all(|(_, x)| x.args.iter().map(shape).collect::<Vec<_>>() == declared);
        let here: Vec<Shape> = c.args.iter().map(shape).collect();
        if !uniform || here != declared {
            return Err(format!(
                "{}: `{}` calls an inherited method with other arguments than its definition declares (as at {}): call it as `{}` does",
                c.origin, c.raw, list[0].1.origin, list[0].1.raw
            ));
        }
    }
    let mut out = BTreeMap::new();
    for (key, list) in sites {
        let (guard, first) = (list[0].0, &list[0].1);
        if let Some((_, c)) = list.iter().find(|(g, _)| *g != guard) {
            return Err(format!(
                "{}: `{}` is called as a guard and as an action (also at {}): one method cannot be both",
                c.origin, c.raw, first.origin
            ));
        }
        let shapes: Vec<Shape> = first.args.iter().map(shape).collect();
        let uniform = list
            .iter()
            .all(|(_, c)| c.args.iter().map(shape).collect::<Vec<_>>() == shapes);
        if !uniform && !external(key.0) {
            for (_, c) in &list {
                for a in &c.args {
                    if let Arg::Param { ty, .. } = a {
                        let top = ty.rust.strip_prefix("super::").unwrap_or(&ty.rust);
                        args.insert(ty.variant.clone(), top.to_string());
                    }
                }
            }
        }
        let sig = if uniform {
            let mut names: Vec<(String, String)> = Vec::new();
            for (i, a) in first.args.iter().enumerate() {
                let (mut name, ty) = match a {
                    Arg::Param { field, ty } => (field.clone(), format!("&{}", ty.rust)),
                    Arg::Const(_) => (format!("value{i}"), "&str".to_string()),
                };
                if names.iter().any(|(n, _)| *n == name) {
                    name = format!("{name}{i}");
                }
                names.push((name, ty));
            }
            Sig::Typed(names)
        } else {
            Sig::Slice
        };
        let mut doc = doc_lines(list.iter().find_map(|(_, c)| c.doc.as_deref()));
        if !doc.is_empty() {
            doc.push(String::new());
        }
        let mut calls: Vec<String> = Vec::new();
        for (_, c) in &list {
            if !calls
                .iter()
                .any(|x| x.starts_with(&format!("`{}` ", c.raw)))
            {
                calls.push(format!("`{}` ({})", c.raw, short(&c.origin)));
            }
        }
        let more = calls.len().saturating_sub(3);
        calls.truncate(3);
        doc.push(format!(
            "Called as {}{}.",
            calls.join(", "),
            if more > 0 {
                format!(" and {more} more")
            } else {
                String::new()
            }
        ));
        if matches!(sig, Sig::Slice) {
            doc.push(String::new());
            doc.push(
                "Its call sites pass different arguments: each call's are in `args`, in order."
                    .into(),
            );
        }
        out.insert(key, Method { guard, sig, doc });
    }
    Ok((out, args))
}

/// `file:line` without the file's directory, for generated docs (which must not depend
/// on where the definitions are).
pub(super) fn short(origin: &str) -> String {
    std::path::Path::new(origin)
        .file_name()
        .map_or_else(|| origin.to_string(), |f| f.to_string_lossy().into_owned())
}
