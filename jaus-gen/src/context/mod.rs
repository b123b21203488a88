//! The template context: every message and type of a spec, with Rust types, derive
//! attributes and documentation already worked out.
//!
//! * [`items`]: what the templates see of each group, type, message, field;
//! * [`wire`]: the Rust type, derive attributes and documentation of a wire form;
//! * [`requirements`]: the SDK groups a vendor's overlay needs.

mod items;
mod requirements;
mod wire;

pub use items::*;
pub use requirements::{requirements, RequireCtx};

use jaus_spec::{Bits, Code, MessageDef, Spec, TypeForm};
use serde::Serialize;
use wire::{all_default, field_ctx, map_wire};

/// Everything the templates see.
#[derive(Debug, Serialize)]
pub struct Context {
    /// Groups in definition order, each with its types and messages.
    pub groups: Vec<GroupCtx>,
    /// Every message, in definition order.
    pub messages: Vec<MessageCtx>,
    /// Query → report pairs.
    pub queries: Vec<QueryCtx>,
    /// Command codes (`0x0001`) of the messages the component runtime takes for every
    /// component (`runtime: [handles]` or `[shares]`), in code order.
    pub runtime_inputs: Vec<String>,
    /// Command codes of the messages the component runtime sends for every component
    /// (`runtime: [emits]`), in code order.
    pub runtime_outputs: Vec<String>,
    /// The set is a vendor's overlay on the SDK's definitions: only its own items are
    /// generated, the SDK's are used from `::jaus::messages`, and its `Message` wraps
    /// the SDK's.
    pub vendor: bool,
    /// The SDK's feature-gated groups the overlay's items use, each with the first use
    /// (`file:line: message X, field y uses type Z`).
    pub requires: Vec<RequireCtx>,
}

/// The `jaus::wire::MessageClass` variant of a message: its explicit class, or its
/// code's range.
fn class_variant(d: &MessageDef) -> &'static str {
    use jaus_spec::MessageClass as C;
    match d.class() {
        C::Command => "Command",
        C::Query => "Query",
        C::Inform => "Inform",
        C::EventSetup => "EventSetup",
        C::EventNotification => "EventNotification",
        C::NodeManagement => "NodeManagement",
        C::Experimental if C::is_reserved_code(d.code.0) => "Reserved",
        C::Experimental => "Experimental",
    }
}

fn doc_lines(text: Option<&str>) -> Vec<String> {
    text.map(|t| t.lines().map(|l| l.trim_end().to_string()).collect())
        .unwrap_or_default()
}

fn fmt_f64(v: f64) -> String {
    format!("{v:?}")
}

fn cfg_of(group: &str, gates: bool) -> Option<String> {
    (gates && group != "core").then(|| format!("feature = \"{group}\""))
}

/// Builds the template context of a validated spec.
pub fn build_context(spec: &Spec, gates: bool, rt: &str) -> Context {
    let mut groups: Vec<GroupCtx> = spec
        .groups
        .iter()
        .map(|g| GroupCtx {
            name: g.name.clone(),
            module: if matches!(g.name.as_str(), "core" | "std" | "alloc") {
                format!("{}_messages", g.name)
            } else {
                g.name.clone()
            },
            title: g.title.clone(),
            doc: doc_lines(g.description.as_deref()),
            cfg: cfg_of(&g.name, gates),
            types: Vec::new(),
            messages: Vec::new(),
        })
        .collect();
    let vendor = spec.extends();
    for t in &spec.types {
        if !spec.is_own(t.source) {
            continue;
        }
        let d = &t.def;
        let mut tc = TypeCtx {
            name: d.name.clone(),
            kind: format!("{:?}", d.kind).to_lowercase(),
            repr: String::new(),
            doc: doc_lines(d.description.as_deref()),
            container_attr: String::new(),
            default: false,
            copy: false,
            fields: Vec::new(),
            values: Vec::new(),
            bits: Vec::new(),
            variants: Vec::new(),
        };
        match &t.form {
            TypeForm::Record { presence, fields } => {
                tc.container_attr =
                    presence.map_or_else(String::new, |p| format!("presence = {}", p.rust()));
                tc.fields = fields.iter().map(|f| field_ctx(spec, f, rt)).collect();
                tc.default = all_default(spec, fields);
            }
            TypeForm::Enum { repr } => {
                tc.repr = repr.rust().to_string();
                tc.container_attr = format!("repr = {}", tc.repr);
                tc.values = d
                    .values
                    .iter()
                    .map(|v| {
                        let mut doc = doc_lines(v.description.as_deref());
                        if doc.is_empty() {
                            doc.push(format!("{} ({}).", jaus_spec::title_of(&v.name), v.value));
                        }
                        ValueCtx {
                            name: v.name.clone(),
                            value: v.value,
                            doc,
                        }
                    })
                    .collect();
                tc.default = !tc.values.is_empty();
                tc.copy = true;
            }
            TypeForm::Bitfield { repr, members } => {
                tc.repr = repr.rust().to_string();
                tc.container_attr = format!("repr = {}", tc.repr);
                tc.bits = members
                    .iter()
                    .map(|b| {
                        let (ty, attr, extra) = match b.bits {
                            Bits::Flag(x) => (
                                "bool".to_string(),
                                format!("bit = {x}"),
                                format!("Bit {x}."),
                            ),
                            Bits::Range { lo, hi } => {
                                let w = hi - lo + 1;
                                let ty = if w <= 8 {
                                    "u8"
                                } else if w <= 16 {
                                    "u16"
                                } else if w <= 32 {
                                    "u32"
                                } else {
                                    "u64"
                                };
                                (
                                    ty.to_string(),
                                    format!("bits = {lo}..={hi}"),
                                    format!("Bits {lo}-{hi}."),
                                )
                            }
                        };
                        let mut doc = doc_lines(b.def.description.as_deref());
                        if !doc.is_empty() {
                            doc.push(String::new());
                        }
                        doc.push(extra);
                        BitCtx {
                            name: b.def.name.clone(),
                            ty,
                            attr,
                            doc,
                        }
                    })
                    .collect();
                tc.default = true;
                tc.copy = true;
            }
            TypeForm::Union { repr, variants } => {
                tc.repr = repr.rust().to_string();
                tc.container_attr = format!("tag = {}", tc.repr);
                tc.variants = variants
                    .iter()
                    .map(|v| {
                        let m = v.wire.as_ref().map(|w| map_wire(w, rt));
                        VariantCtx {
                            name: v.def.name.clone(),
                            tag: v.def.tag,
                            serde: m.as_ref().map(|m| m.serde.join(", ")).unwrap_or_default(),
                            ty: m.map(|m| m.ty),
                            doc: doc_lines(v.def.description.as_deref()),
                        }
                    })
                    .collect();
            }
        }
        if let Some(g) = groups.iter_mut().find(|g| g.name == t.group) {
            g.types.push(tc);
        }
    }
    let mut messages = Vec::new();
    for m in &spec.messages {
        if !spec.is_own(m.source) {
            continue;
        }
        let d = &m.def;
        let title = d
            .title
            .clone()
            .unwrap_or_else(|| jaus_spec::title_of(&d.name));
        let mut doc = vec![format!("{title} ({}).", d.code)];
        if !doc_lines(d.description.as_deref()).is_empty() {
            doc.push(String::new());
            doc.extend(doc_lines(d.description.as_deref()));
        }
        if let Some(i) = &d.interop {
            doc.push(String::new());
            doc.push("Interoperability:".into());
            doc.extend(doc_lines(Some(i)));
        }
        let report = spec.report_of(d).map(|r| r.def.name.clone());
        if let Some(r) = &report {
            doc.push(String::new());
            doc.push(format!("Answered by [`{r}`]."));
        }
        if d.experimental {
            doc.push(String::new());
            doc.push("Experimental (not part of RA 3.3).".into());
        }
        let mut container = vec![format!("code = {}", d.code)];
        if let Some(p) = m.presence {
            container.push(format!("presence = {}", p.rust()));
        }
        let embedded = m
            .fields
            .iter()
            .map(|f| &f.def)
            .filter_map(|f| {
                f.code_field.as_ref().map(|c| EmbeddedCtx {
                    field: f.name.clone(),
                    code_field: c.clone(),
                    complement: f.complement,
                    optional: f.bit.is_some(),
                })
            })
            .collect();
        let mc = MessageCtx {
            name: d.name.clone(),
            code: format!("{}", d.code),
            title,
            group: m.group.clone(),
            cfg: cfg_of(&m.group, gates),
            doc,
            container_attr: container.join(", "),
            default: all_default(spec, &m.fields),
            fields: m.fields.iter().map(|f| field_ctx(spec, f, rt)).collect(),
            embedded,
            report,
            experimental: d.experimental,
            class: class_variant(d).into(),
            read_only: d.access == Some(jaus_spec::Access::Read),
            needs_control: d
                .is_command
                .unwrap_or(d.class() == jaus_spec::MessageClass::Command),
        };
        if let Some(g) = groups.iter_mut().find(|g| g.name == m.group) {
            g.messages.push(mc.clone());
        }
        messages.push(mc);
    }
    let queries = spec
        .messages
        .iter()
        .filter(|q| spec.is_own(q.source))
        .filter_map(|q| {
            let r = spec.report_of(&q.def)?;
            let cfg = match (cfg_of(&q.group, gates), cfg_of(&r.group, gates)) {
                (Some(a), Some(b)) if a != b => Some(format!("all({a}, {b})")),
                (Some(a), _) | (None, Some(a)) => Some(a),
                (None, None) => None,
            };
            Some(QueryCtx {
                query: q.def.name.clone(),
                report: r.def.name.clone(),
                query_code: q.def.code.to_string(),
                report_code: r.def.code.to_string(),
                cfg,
            })
        })
        .collect();
    if vendor {
        groups.retain(|g| !g.types.is_empty() || !g.messages.is_empty());
    }
    let runtime_codes = |role: fn(&MessageDef) -> bool| {
        let mut codes: Vec<Code> = spec
            .messages
            .iter()
            .filter(|m| spec.is_own(m.source) && role(&m.def))
            .map(|m| m.def.code)
            .collect();
        codes.sort();
        codes.iter().map(Code::to_string).collect()
    };
    Context {
        groups,
        messages,
        queries,
        runtime_inputs: runtime_codes(MessageDef::runtime_input),
        runtime_outputs: runtime_codes(MessageDef::runtime_output),
        vendor,
        requires: if vendor {
            requirements(spec)
        } else {
            Vec::new()
        },
    }
}
