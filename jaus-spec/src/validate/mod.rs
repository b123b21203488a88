//! Validation of a whole definition set, and resolution of every field into its wire
//! form. Every rule reports with the position of the offending key and names the
//! message/type and field concerned. The validated [`Spec`] is built only when no rule
//! is broken, so every field, representation and bit-field member in it is resolved.
//!
//! The rules, by what they look at:
//! - [`names`]: group, type and message names;
//! - [`wire`]: one field definition resolved into its wire form;
//! - [`fields`]: the fields of a message or record (names, presence bits, the fields
//!   they depend on);
//! - [`types`]: named types (enum values, bit-field members, union variants, records
//!   that contain themselves);
//! - [`messages`]: command codes, classes, reports and runtime roles;
//! - [`components`]: component interfaces and their modes;
//! - [`parts`]: parts shared by component interfaces;
//! - [`services`]: services, their events and state machines.

mod components;
mod fields;
mod messages;
mod names;
mod parts;
mod readback;
mod services;
mod stock;
mod types;
mod wire;

use crate::model::{MessageClass, MessageDef, TypeDef};
use crate::resolved::{Component, Group, Message, Part, Service, Spec, Type, TypeForm};
use crate::source::{Source, SpecError};
use fields::Body;

/// A definition as parsed, with the file it came from.
#[derive(Debug)]
pub(crate) struct Parsed<D> {
    /// The definition.
    pub def: D,
    /// Group name.
    pub group: String,
    /// Index into [`Draft::sources`].
    pub source: usize,
    /// YAML path of the definition (`messages[3]`).
    pub path: String,
}

/// Every file parsed, nothing checked or resolved yet.
#[derive(Debug)]
pub(crate) struct Draft {
    /// How many of the first sources are the base definitions an overlay extends.
    pub base_sources: usize,
    pub sources: Vec<Source>,
    pub groups: Vec<Group>,
    pub types: Vec<Parsed<TypeDef>>,
    pub messages: Vec<Parsed<MessageDef>>,
    pub components: Vec<Component>,
    pub parts: Vec<Part>,
    pub services: Vec<Service>,
}

impl Draft {
    fn message(&self, name: &str) -> Option<&Parsed<MessageDef>> {
        self.messages.iter().find(|m| m.def.name == name)
    }

    fn ty(&self, name: &str) -> Option<&Parsed<TypeDef>> {
        self.types.iter().find(|t| t.def.name == name)
    }

    fn report_of(&self, query: &MessageDef) -> Option<&Parsed<MessageDef>> {
        crate::resolved::report_of(
            query,
            |n| self.message(n),
            |c| self.messages.iter().find(|m| m.def.code.0 == c),
        )
    }
}

/// The set being checked and the problems found so far.
struct Ctx<'a> {
    spec: &'a Draft,
    errors: Vec<SpecError>,
}

impl Ctx<'_> {
    /// Reports `message` at the YAML `path` of source `source`, about `context`.
    fn err(&mut self, source: usize, path: &str, context: String, message: impl Into<String>) {
        let s = &self.spec.sources[source];
        self.errors.push(SpecError {
            file: s.path.clone(),
            pos: s.index.find(path),
            context,
            message: message.into(),
        });
    }
}

/// Checks every rule on the parsed files and resolves them into a [`Spec`], or returns
/// every problem found, in file order.
pub(crate) fn validate(draft: Draft) -> Result<Spec, Vec<SpecError>> {
    let mut cx = Ctx {
        spec: &draft,
        errors: Vec::new(),
    };
    names::check_groups(&mut cx);
    names::check_type_and_message_names(&mut cx);
    messages::check_codes(&mut cx);
    let forms = types::check_types(&mut cx);
    types::check_record_cycles(&mut cx);
    let bodies = messages::check_messages(&mut cx);
    components::check_components(&mut cx);
    parts::check_parts(&mut cx);
    readback::check_readbacks(&mut cx);
    services::check_services(&mut cx);
    cx.errors.extend(stock::check(&draft));
    let mut errors = cx.errors;
    // Every definition that could not be resolved reported why, so with no errors
    // every form and body is there.
    let forms: Option<Vec<TypeForm>> = forms.into_iter().collect();
    let bodies: Option<Vec<Body>> = bodies.into_iter().collect();
    match (forms, bodies) {
        (Some(forms), Some(bodies)) if errors.is_empty() => Ok(assemble(draft, forms, bodies)),
        _ => {
            debug_assert!(
                !errors.is_empty(),
                "a definition failed to resolve silently"
            );
            errors.sort_by(|a, b| {
                (&a.file, a.pos.line, a.pos.column).cmp(&(&b.file, b.pos.line, b.pos.column))
            });
            Err(errors)
        }
    }
}

/// The validated spec: each parsed definition with its resolved form.
fn assemble(draft: Draft, forms: Vec<TypeForm>, bodies: Vec<Body>) -> Spec {
    let warnings = overlay_warnings(&draft);
    Spec {
        base_sources: draft.base_sources,
        warnings,
        sources: draft.sources,
        groups: draft.groups,
        types: draft
            .types
            .into_iter()
            .zip(forms)
            .map(|(t, form)| Type {
                def: t.def,
                group: t.group,
                source: t.source,
                path: t.path,
                form,
            })
            .collect(),
        messages: draft
            .messages
            .into_iter()
            .zip(bodies)
            .map(|(m, (presence, fields))| Message {
                def: m.def,
                group: m.group,
                source: m.source,
                path: m.path,
                presence,
                fields,
            })
            .collect(),
        components: draft.components,
        parts: draft.parts,
        services: draft.services,
    }
}

/// What is legal but probably wrong in a vendor's overlay: a message of its own with a
/// code outside the experimental range, which a later revision of the standard may
/// take.
fn overlay_warnings(draft: &Draft) -> Vec<SpecError> {
    if draft.base_sources == 0 {
        return Vec::new();
    }
    draft
        .messages
        .iter()
        .filter(|m| {
            m.source >= draft.base_sources && !MessageClass::is_experimental_code(m.def.code.0)
        })
        .map(|m| {
            let s = &draft.sources[m.source];
            SpecError {
                file: s.path.clone(),
                pos: s.index.find(&format!("{}.code", m.path)),
                context: format!("message `{}`", m.def.name),
                message: format!(
                    "code {} is outside the experimental range {}: a later revision of the standard may give it to another message",
                    m.def.code,
                    MessageClass::Experimental.codes_text()
                ),
            }
        })
        .collect()
}
