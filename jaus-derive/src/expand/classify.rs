//! Classification of one field: its Rust type and attributes checked against each other
//! and turned into a [`Shape`].

use super::shape::{Elem, Len, ScaledSpec, Shape};
use super::types::{generic_inner, is_int_type, type_name};
use crate::attr::{eval_f64, span_of, Errors, FieldAttrs, Int, IntSpan, Scaled};
use jaus_spec::CountRef;
use proc_macro2::Span;
use syn::Type;

fn scaled_spec(s: &Scaled, unit: Option<&str>, errors: &mut Errors) -> Option<ScaledSpec> {
    let lo = eval_f64(&s.lo);
    let hi = eval_f64(&s.hi);
    if lo.is_none() {
        errors.error(
            span_of(&s.lo),
            "the lower limit must be a constant number (e.g. `-90.0`, `-PI`)",
        );
    }
    if hi.is_none() {
        errors.error(
            span_of(&s.hi),
            "the upper limit must be a constant number (e.g. `90.0`, `PI`)",
        );
    }
    let (lo, hi) = (lo?, hi?);
    if lo.is_nan() || hi.is_nan() || lo >= hi || !lo.is_finite() || !hi.is_finite() {
        errors.error(
            span_of(&s.lo),
            format!("lower limit {lo} must be below upper limit {hi}"),
        );
        return None;
    }
    if s.int.int == Int::I8 {
        errors.error(
            s.int.span,
            "i8 is not a JAUS scaled-integer type; use u8, u16, u32, u64, i16, i32 or i64",
        );
        return None;
    }
    Some(ScaledSpec {
        int: s.int.int,
        lo,
        hi,
        unit: unit.unwrap_or_default().to_string(),
    })
}

fn require_unsigned(t: &IntSpan, what: &str, errors: &mut Errors) -> Option<Int> {
    if !t.int.unsigned() || t.int == Int::U64 {
        errors.error(
            t.span,
            format!("{what} type must be an unsigned integer: u8, u16 or u32"),
        );
        None
    } else {
        Some(t.int)
    }
}

/// Classifies one field from its Rust type and attributes.
pub(super) fn classify(
    ty: &Type,
    a: &FieldAttrs,
    field_span: Span,
    is_last: bool,
    errors: &mut Errors,
) -> Option<Shape> {
    let name = type_name(ty);
    let unit = a.unit.as_ref().map(|(u, _)| u.as_str());
    if let (Some((_, span)), None) = (&a.unit, &a.scaled) {
        errors.error(
            *span,
            "`unit` names the unit of a scaled value: it goes with `scaled(T, lo, hi)`",
        );
    }
    let count = a
        .count
        .as_ref()
        .and_then(|c| require_unsigned(c, "count", errors));
    let size = a
        .size
        .as_ref()
        .and_then(|c| require_unsigned(c, "size", errors));
    if let Some(span) = a.rest {
        if !is_last {
            errors.error(
                span,
                "`rest` consumes the rest of the body, so it is only allowed on the last field",
            );
        }
    }
    if let Some(span) = a.accept_short {
        if a.fixed.is_none() {
            errors.error(span, "`accept_short` only applies to a `fixed = N` field");
        } else if !is_last {
            errors.error(span, "`accept_short` is only allowed on the last field");
        }
    }
    let lens = [a.fixed.is_some(), a.size.is_some(), a.rest.is_some()]
        .iter()
        .filter(|b| **b)
        .count();
    if lens > 1 {
        errors.error(field_span, "use only one of `fixed`, `size` and `rest`");
    }
    let len = match (a.fixed, size, a.rest) {
        (Some((n, _)), _, _) => Some(Len::Fixed(n)),
        (_, Some(s), _) => Some(Len::Size(s)),
        (_, _, Some(_)) => Some(Len::Rest),
        _ if a.nul_terminated.is_some() => Some(Len::Nul),
        _ => None,
    };
    if let Some(span) = a.nul_terminated {
        if name.as_deref() != Some("String") || lens > 0 {
            errors.error(
                span,
                "`nul_terminated` applies to a `String` field without `fixed`, `size` or `rest`",
            );
            return None;
        }
    }
    if let Some((var, span)) = &a.tag_var {
        if lens > 0 || a.count.is_some() || a.scaled.is_some() || is_int_type(ty).is_some() {
            errors.error(
                *span,
                "`tag_var` applies to a field whose type is a `JausUnion`",
            );
            return None;
        }
        return Some(Shape::TagVar {
            ty: ty.clone(),
            var: var.clone(),
        });
    }
    if let Some(span) = a.nul {
        if !(name.as_deref() == Some("String") && a.rest.is_some()) {
            errors.error(span, "`nul` only applies to a `String` field with `rest`");
        }
    }

    if let Some((bit, span)) = a.flag {
        if name.as_deref() != Some("bool") {
            errors.error(
                span,
                "`flag` applies to a `bool` field: it is a presence bit with no bytes",
            );
            return None;
        }
        return Some(Shape::Flag(bit));
    }
    if let Some((var, span)) = &a.count_var {
        let Some(inner) = generic_inner(ty, "Vec") else {
            errors.error(*span, "`count_var` applies to a `Vec<T>` field");
            return None;
        };
        if a.count.is_some() || a.rest.is_some() {
            errors.error(*span, "use one of `count = T`, `count_var` and `rest`");
            return None;
        }
        let elem = match &a.scaled {
            Some(sc) if type_name(inner).as_deref() == Some("f64") => {
                Elem::Scaled(scaled_spec(sc, unit, errors)?)
            }
            Some(sc) => {
                errors.error(sc.span, "`scaled` applies to `Vec<f64>`");
                return None;
            }
            None => Elem::Plain(inner.clone()),
        };
        // `name` or `name - N`: read as jaus-spec reads `count_field`.
        let Ok(CountRef { field, minus }) = CountRef::parse(var) else {
            errors.error(
                *span,
                "`count_var` is a field name, optionally minus a constant: \"n\" or \"n - 1\"",
            );
            return None;
        };
        return Some(Shape::ListVar {
            var: field,
            minus,
            elem,
        });
    }

    // Scaled values.
    if let Some(s) = &a.scaled {
        if let Some(int) = is_int_type(ty) {
            errors.error(
                s.span,
                format!("scaled attribute on an integer field (`{}`): a scaled field holds the real value, declare it as `f64`", int.ident()),
            );
            return None;
        }
        let spec = scaled_spec(s, unit, errors)?;
        if name.as_deref() == Some("f64") {
            if a.count.is_some() || len.is_some() {
                errors.error(
                    field_span,
                    "a scaled `f64` takes no `count`, `size`, `fixed` or `rest`",
                );
            }
            return Some(Shape::Scaled(spec));
        }
        if let Some(inner) = generic_inner(ty, "Vec") {
            if type_name(inner).as_deref() == Some("f64") {
                return list_shape(count, a, Elem::Scaled(spec), errors, field_span);
            }
        }
        errors.error(
            s.span,
            "`scaled` applies to an `f64` field (or `Vec<f64>` with `count`)",
        );
        return None;
    }

    match name.as_deref() {
        Some("bool") => {
            errors.error(
                field_span,
                "JAUS has no wire boolean: put the flag in a bit field (`#[derive(JausBits)]`)",
            );
            return None;
        }
        Some("String") => {
            if a.count.is_some() {
                errors.error(
                    field_span,
                    "a `String` takes `size = T` (byte length prefix), not `count`",
                );
                return None;
            }
            return match len {
                Some(len) => Some(Shape::Str {
                    len,
                    nul: a.nul.is_some(),
                    accept_short: a.accept_short.is_some(),
                }),
                None => {
                    errors.error(field_span, "a `String` field needs its wire form: `fixed = N`, `size = u8|u16|u32` or `rest`");
                    None
                }
            };
        }
        _ => {}
    }
    if let Some(inner) = generic_inner(ty, "Vec") {
        if type_name(inner).as_deref() == Some("u8") && a.count.is_none() {
            return match len {
                Some(len) => Some(Shape::Bytes(len)),
                None => {
                    errors.error(
                        field_span,
                        "a `Vec<u8>` field needs `fixed = N`, `size = T`, `count = T` or `rest`",
                    );
                    None
                }
            };
        }
        if matches!(len, Some(Len::Fixed(_)) | Some(Len::Size(_))) {
            errors.error(
                field_span,
                "a list takes `count = T` (element count) or `rest`, not `fixed`/`size`",
            );
            return None;
        }
        return list_shape(count, a, Elem::Plain(inner.clone()), errors, field_span);
    }
    if a.count.is_some() {
        errors.error(
            a.count.as_ref().map_or(field_span, |c| c.span),
            "`count` applies to a `Vec<T>` field",
        );
        return None;
    }
    match len {
        Some(Len::Size(s)) => Some(Shape::Sized {
            size: s,
            ty: ty.clone(),
        }),
        Some(_) => {
            errors.error(
                field_span,
                "`fixed` and `rest` apply to `String`, `Vec<u8>` or list fields",
            );
            None
        }
        None => Some(Shape::Plain(ty.clone())),
    }
}

fn list_shape(
    count: Option<Int>,
    a: &FieldAttrs,
    elem: Elem,
    errors: &mut Errors,
    span: Span,
) -> Option<Shape> {
    match (count, a.rest) {
        (Some(c), None) => Some(Shape::List {
            count: Some(c),
            elem,
        }),
        (None, Some(_)) => Some(Shape::List { count: None, elem }),
        (None, None) if a.count.is_some() => None, // bad count type, already reported
        _ => {
            errors.error(
                span,
                "a list field needs `count = u8|u16|u32` (count prefix) or `rest`",
            );
            None
        }
    }
}
