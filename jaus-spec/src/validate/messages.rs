//! Messages: unique command codes, a body (see [`super::fields`]), a class that agrees
//! with the code, a report for every query, and the runtime roles.

use super::fields::{check_fields, Body};
use super::{Ctx, Parsed};
use crate::model::{MessageClass, MessageDef, RuntimeRole};
use std::collections::HashMap;

/// Command codes are unique across the set.
pub(super) fn check_codes(cx: &mut Ctx<'_>) {
    let spec = cx.spec;
    let mut codes: HashMap<u16, &Parsed<MessageDef>> = HashMap::new();
    for m in &spec.messages {
        if let Some(first) = codes.insert(m.def.code.0, m) {
            let o = &spec.sources[first.source];
            let pos = o.index.find(&first.path);
            cx.err(
                m.source,
                &format!("{}.code", m.path),
                format!("message `{}`", m.def.name),
                format!(
                    "duplicate command code {} (also `{}` at {}:{}:{})",
                    m.def.code,
                    first.def.name,
                    o.path.display(),
                    pos.line,
                    pos.column
                ),
            );
        }
    }
}

/// Checks every message and resolves its body; `None` for a body with an error
/// reported.
pub(super) fn check_messages(cx: &mut Ctx<'_>) -> Vec<Option<Body>> {
    let spec = cx.spec;
    let mut bodies = Vec::with_capacity(spec.messages.len());
    for m in &spec.messages {
        let ctx = format!("message `{}`", m.def.name);
        bodies.push(check_fields(
            cx,
            m.source,
            &m.path,
            &ctx,
            &m.def.presence,
            &m.def.fields,
        ));
        check_runtime(cx, m, &ctx);
        check_class(cx, m, &ctx);
        check_report(cx, m, &ctx);
        check_access(cx, m, &ctx);
    }
    bodies
}

/// `access: read` marks a command that changes nothing a controller owns; queries,
/// reports and the other classes are reads already.
fn check_access(cx: &mut Ctx<'_>, m: &Parsed<MessageDef>, ctx: &str) {
    let reads = matches!(
        m.def.class(),
        MessageClass::Query
            | MessageClass::Inform
            | MessageClass::EventNotification
            | MessageClass::NodeManagement
    );
    if m.def.access.is_some() && reads {
        cx.err(
            m.source,
            &format!("{}.access", m.path),
            ctx.to_string(),
            format!(
                "`access: read` applies to commands (and event set-up); `{}` is a {} message, which an access policy reads as a read already",
                m.def.name,
                m.def.class().as_str()
            ),
        );
    }
}

/// An explicit `class:` is for experimental codes: it may not contradict the class
/// the code's range gives, nor say `experimental`.
fn check_class(cx: &mut Ctx<'_>, m: &Parsed<MessageDef>, ctx: &str) {
    let code = m.def.code.0;
    let Some(explicit) = m.def.class else { return };
    match MessageClass::of_code(code) {
        Some(by_code) if by_code != explicit => cx.err(
            m.source,
            &format!("{}.class", m.path),
            ctx.to_string(),
            format!(
                "`class: {}` contradicts the code 0x{code:04X}, which is a {} code; `class:` is for experimental codes ({})",
                explicit.as_str(),
                by_code.as_str(),
                MessageClass::Experimental.codes_text()
            ),
        ),
        _ if explicit == MessageClass::Experimental => cx.err(
            m.source,
            &format!("{}.class", m.path),
            ctx.to_string(),
            "`class: experimental` says nothing: name the class (command, query, inform, ...) or leave `class` out",
        ),
        _ => {}
    }
}

/// `report:` is for queries and names a message; a query without one has a report by
/// the complement rule, or is marked `no_report`.
fn check_report(cx: &mut Ctx<'_>, m: &Parsed<MessageDef>, ctx: &str) {
    let spec = cx.spec;
    let code = m.def.code.0;
    let is_query = m.def.is_query();
    if let Some(r) = &m.def.report {
        if !is_query {
            cx.err(
                m.source,
                &format!("{}.report", m.path),
                ctx.to_string(),
                format!(
                    "`report` applies to query messages ({}, or `class: query` for an experimental code)",
                    MessageClass::Query.codes_text()
                ),
            );
        } else if spec.message(r).is_none() {
            cx.err(
                m.source,
                &format!("{}.report", m.path),
                ctx.to_string(),
                format!("report `{r}` is not defined"),
            );
        }
    } else if is_query && !m.def.no_report && spec.report_of(&m.def).is_none() {
        let hint = if let Some(report) = MessageClass::report_code(code) {
            format!(
                "define the message with code 0x{report:04X} (the complement rule), name it with `report:`, or mark the query `no_report: true`"
            )
        } else {
            "an experimental query names its report with `report:` (or is marked `no_report: true`)"
                .to_string()
        };
        cx.err(
            m.source,
            &format!("{}.code", m.path),
            ctx.to_string(),
            format!("query {} has no report: {hint}", m.def.code),
        );
    }
}

/// `runtime:` names each role once, and `handles` and `shares` exclude each other.
fn check_runtime(cx: &mut Ctx<'_>, m: &Parsed<MessageDef>, ctx: &str) {
    let roles = &m.def.runtime;
    for (i, role) in roles.iter().enumerate() {
        if roles[..i].contains(role) {
            cx.err(
                m.source,
                &format!("{}.runtime[{i}]", m.path),
                ctx.to_string(),
                format!("runtime role `{role}` is listed twice"),
            );
        }
    }
    if m.def.runtime_owned() && roles.contains(&RuntimeRole::Shares) {
        cx.err(
            m.source,
            &format!("{}.runtime", m.path),
            ctx.to_string(),
            "runtime roles `handles` and `shares` exclude each other: `handles` keeps the message from component interfaces, `shares` lets them list it too",
        );
    }
}
