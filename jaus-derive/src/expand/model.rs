//! The model of a message or record: the wire shape of each field and how fields
//! depend on each other, built from the struct and its attributes.

use super::classify::classify;
use super::common::lit;
pub(super) use super::shape::{Elem, Len, ScaledSpec, Shape};
use super::types::{generic_inner, is_int_type, type_name};
use crate::attr::{parse_field_attrs, span_of, ContainerAttrs, Errors, Int};
use proc_macro2::Span;
use syn::{Data, DeriveInput, Fields, Ident, LitStr};

/// One field: its wire shape, presence and links to the fields it depends on.
pub(super) struct FieldModel {
    pub(super) ident: Ident,
    pub(super) bit: Option<u32>,
    /// Optional field present iff this variable is non-zero.
    pub(super) present_if: Option<String>,
    /// This field's value is published as a variable for later fields.
    pub(super) var: Option<String>,
    /// For a `var` field: the sibling list whose length it carries (computed on encode),
    /// and whether that list is optional.
    pub(super) counts: Option<(Ident, bool)>,
    /// A `Vec<u32>` of byte offsets of the elements of this sibling list.
    pub(super) offsets_of: Option<Ident>,
    /// For a list: the sibling offsets field to patch while encoding elements.
    pub(super) patched_by: Option<Ident>,
    pub(super) shape: Shape,
    pub(super) path: LitStr,
    pub(super) span: Span,
}

impl FieldModel {
    /// The local the decoder binds the field's value to: never the field's own name,
    /// which could shadow the decoder's reader (`r`) or another local (a field named
    /// `r`, `pv`, `present`).
    pub(super) fn local(&self) -> Ident {
        let name = self.ident.to_string();
        Ident::new(
            &format!("__jaus_field_{}", name.trim_start_matches("r#")),
            self.ident.span(),
        )
    }
}

/// A message or record: its presence vector and fields, checked and linked.
pub(super) struct StructModel {
    pub(super) presence: Option<Int>,
    pub(super) fields: Vec<FieldModel>,
    pub(super) unit: bool,
}

/// Builds the model of a struct, reporting every attribute error to `errors`.
pub(super) fn struct_model(
    input: &DeriveInput,
    c: &ContainerAttrs,
    errors: &mut Errors,
) -> StructModel {
    let struct_name = input.ident.to_string();
    let mut model = StructModel {
        presence: None,
        fields: Vec::new(),
        unit: false,
    };
    if let Some(p) = &c.presence {
        if p.int.unsigned() && p.int != Int::U64 {
            model.presence = Some(p.int);
        } else {
            errors.error(
                p.span,
                "a presence vector is an unsigned integer: u8, u16 or u32",
            );
        }
    }
    let data = match &input.data {
        Data::Struct(s) => s,
        _ => {
            errors.error(input.ident.span(), "this derive applies to a struct");
            return model;
        }
    };
    let named = match &data.fields {
        Fields::Named(n) => n.named.iter().collect::<Vec<_>>(),
        Fields::Unit => {
            model.unit = true;
            Vec::new()
        }
        Fields::Unnamed(u) => {
            errors.error(
                span_of(u),
                "tuple structs are not supported: name the fields",
            );
            return model;
        }
    };
    let mut used_bits: Vec<(u32, String)> = Vec::new();
    let n = named.len();
    for (i, f) in named.into_iter().enumerate() {
        let ident = f.ident.clone().expect("named field");
        let a = parse_field_attrs(&f.attrs, errors, false);
        if a.parse_failed {
            continue;
        }
        let fspan = span_of(&f.ty);
        let optional = generic_inner(&f.ty, "Option");
        let ty = optional.unwrap_or(&f.ty);
        if let Some((b, span)) = a.flag {
            if model.presence.is_none() && c.presence.is_none() {
                errors.error(span, "`flag` needs a presence vector: add `#[jaus(presence = u8|u16|u32)]` to the struct");
            } else if let Some(p) = model.presence {
                if b >= p.bits() {
                    errors.error(
                        span,
                        format!(
                            "flag bit {b} is out of range for a {} presence vector",
                            p.ident()
                        ),
                    );
                }
            }
            if let Some((_, other)) = used_bits.iter().find(|(u, _)| *u == b) {
                errors.error(
                    span,
                    format!("presence bit {b} is already used by field `{other}`"),
                );
            }
            used_bits.push((b, ident.to_string()));
        }
        let present_if = match (&a.present_if, optional.is_some(), a.bit) {
            (Some((v, _)), true, None) => Some(v.clone()),
            (Some((_, span)), false, _) => {
                errors.error(*span, "`present_if` applies to an `Option<T>` field");
                None
            }
            (Some((_, span)), true, Some(_)) => {
                errors.error(*span, "use either `bit` or `present_if`, not both");
                None
            }
            (None, ..) => None,
        };
        let bit = match (a.bit, optional.is_some() && present_if.is_none()) {
            (Some((b, span)), true) => {
                match model.presence {
                    None if c.presence.is_none() => errors.error(
                        span,
                        "`bit` needs a presence vector: add `#[jaus(presence = u8|u16|u32)]` to the struct",
                    ),
                    Some(p) if b >= p.bits() => errors.error(
                        span,
                        format!("presence bit {b} is out of range for a {} presence vector (bits 0..={})", p.ident(), p.bits() - 1),
                    ),
                    _ => {}
                }
                if let Some((_, other)) = used_bits.iter().find(|(u, _)| *u == b) {
                    errors.error(
                        span,
                        format!("presence bit {b} is already used by field `{other}`"),
                    );
                }
                used_bits.push((b, ident.to_string()));
                Some(b)
            }
            (Some((_, span)), false) => {
                errors.error(span, "presence bit on a field that is not an `Option<T>`: optional fields are `Option<T>`");
                None
            }
            (None, true) => {
                errors.error(
                    fspan,
                    "an `Option<T>` field needs its presence bit: `#[jaus(bit = N)]` (or `present_if = \"flag\"`)",
                );
                None
            }
            (None, false) => None,
        };
        if let Some((_, span)) = &a.var {
            if !(is_int_type(ty).is_some_and(Int::unsigned)
                || type_name(ty).as_deref() == Some("bool"))
                || optional.is_some()
            {
                errors.error(
                    *span,
                    "`var` applies to an unsigned integer or `bool` field (not optional)",
                );
            }
        }
        if let Some((_, span)) = &a.offsets {
            let ok = generic_inner(ty, "Vec")
                .is_some_and(|t| type_name(t).as_deref() == Some("u32"))
                && a.count_var.is_some();
            if !ok {
                errors.error(
                    *span,
                    "`offsets` applies to a `Vec<u32>` field with `count_var`",
                );
            }
        }
        if let Some(shape) = classify(ty, &a, fspan, i + 1 == n, errors) {
            model.fields.push(FieldModel {
                path: lit(&format!("{struct_name}.{ident}")),
                span: span_of(&ident),
                present_if,
                var: a.var.as_ref().map(|(v, _)| v.clone()),
                counts: None,
                offsets_of: a
                    .offsets
                    .as_ref()
                    .map(|(v, _)| Ident::new(v, Span::call_site())),
                patched_by: None,
                ident,
                bit,
                shape,
            });
        }
    }
    // Link fields that depend on each other within this struct.
    let snapshot: Vec<(Ident, Option<String>, bool, bool)> = model
        .fields
        .iter()
        .map(|f| {
            let var = match &f.shape {
                Shape::ListVar { var, minus: 0, .. } => Some(var.clone()),
                _ => None,
            };
            (
                f.ident.clone(),
                var,
                f.bit.is_some() || f.present_if.is_some(),
                f.offsets_of.is_some(),
            )
        })
        .collect();
    for f in &mut model.fields {
        if let Some(v) = &f.var {
            f.counts = snapshot
                .iter()
                .find(|(_, lv, _, is_offsets)| lv.as_deref() == Some(v.as_str()) && !is_offsets)
                .map(|(id, _, opt, _)| (id.clone(), *opt));
        }
    }
    let offsets: Vec<(Ident, Ident)> = model
        .fields
        .iter()
        .filter_map(|f| f.offsets_of.clone().map(|t| (f.ident.clone(), t)))
        .collect();
    for (off, target) in offsets {
        match model.fields.iter_mut().find(|f| f.ident == target) {
            Some(t) if matches!(t.shape, Shape::ListVar { .. } | Shape::List { .. }) => {
                t.patched_by = Some(off)
            }
            _ => errors.error(
                off.span(),
                format!("`offsets` names `{target}`, which is not a list field of this struct"),
            ),
        }
    }
    model
}
