//! Read-back pairs (`readback:` of a command): the command is a command, the query it
//! names is a defined query with a report, and the report carries at least one field of
//! the command by name (what `jaus conform` compares). A query field named like a
//! command field (`waypoint_number`) selects what is read back.

use super::{Ctx, Parsed};
use crate::model::{MessageClass, MessageDef};

/// Checks every `readback:`.
pub(super) fn check_readbacks(cx: &mut Ctx<'_>) {
    let spec = cx.spec;
    for m in &spec.messages {
        if let Some(q) = &m.def.readback {
            check_one(cx, m, q);
        }
    }
}

fn check_one(cx: &mut Ctx<'_>, m: &Parsed<MessageDef>, query: &str) {
    let spec = cx.spec;
    let ctx = format!("message `{}`", m.def.name);
    let path = format!("{}.readback", m.path);
    if m.def.class() != MessageClass::Command {
        cx.err(
            m.source,
            &path,
            ctx,
            format!(
                "`readback` applies to command messages ({}, or `class: command`)",
                MessageClass::Command.codes_text()
            ),
        );
        return;
    }
    let Some(q) = spec.message(query) else {
        cx.err(
            m.source,
            &path,
            ctx,
            format!("read-back query `{query}` is not defined"),
        );
        return;
    };
    if !q.def.is_query() {
        cx.err(
            m.source,
            &path,
            ctx,
            format!(
                "`{query}` is not a query (code {}): `readback` names the query that reads the value back",
                q.def.code
            ),
        );
        return;
    }
    let Some(report) = spec.report_of(&q.def) else {
        cx.err(
            m.source,
            &path,
            ctx,
            format!("read-back query `{query}` has no report to compare"),
        );
        return;
    };
    let shared = m
        .def
        .fields
        .iter()
        .filter(|f| report.def.fields.iter().any(|r| r.name == f.name))
        .count();
    if shared == 0 {
        cx.err(
            m.source,
            &path,
            ctx,
            format!(
                "report `{}` of `{query}` has no field named like a field of `{}`: nothing to compare",
                report.def.name, m.def.name
            ),
        );
    }
}
