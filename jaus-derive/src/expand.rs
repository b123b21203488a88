//! Validation and code generation for each derive.

use crate::attr::{
    crate_path, eval_f64, for_each_item, parse_container_attrs, parse_field_attrs, span_of,
    ContainerAttrs, Errors, FieldAttrs, Int, IntSpan, Scaled,
};
use proc_macro2::{Span, TokenStream};
use quote::{format_ident, quote, quote_spanned};
use syn::{Data, DeriveInput, Fields, GenericArgument, Ident, LitStr, PathArguments, Type};

// ---------------------------------------------------------------------------------
// Type inspection helpers.

fn last_segment(ty: &Type) -> Option<&syn::PathSegment> {
    match ty {
        Type::Path(p) if p.qself.is_none() => p.path.segments.last(),
        _ => None,
    }
}

/// `Wrapper<T>` → `T`.
fn generic_inner<'a>(ty: &'a Type, wrapper: &str) -> Option<&'a Type> {
    let seg = last_segment(ty)?;
    if seg.ident != wrapper {
        return None;
    }
    match &seg.arguments {
        PathArguments::AngleBracketed(a) if a.args.len() == 1 => match &a.args[0] {
            GenericArgument::Type(t) => Some(t),
            _ => None,
        },
        _ => None,
    }
}

fn type_name(ty: &Type) -> Option<String> {
    let seg = last_segment(ty)?;
    matches!(seg.arguments, PathArguments::None).then(|| seg.ident.to_string())
}

fn is_int_type(ty: &Type) -> Option<Int> {
    type_name(ty).and_then(|n| Int::parse(&n))
}

fn lit(s: &str) -> LitStr {
    LitStr::new(s, Span::call_site())
}

// ---------------------------------------------------------------------------------
// Struct model.

#[derive(Clone, Copy)]
enum Len {
    Fixed(usize),
    Size(Int),
    Rest,
    /// Up to and including a NUL byte.
    Nul,
}

#[allow(clippy::large_enum_variant)] // built once per field at compile time
enum Elem {
    Plain(Type),
    Scaled(ScaledSpec),
}

#[derive(Clone)]
struct ScaledSpec {
    int: Int,
    lo: f64,
    hi: f64,
}

enum Shape {
    Plain(Type),
    Scaled(ScaledSpec),
    List {
        count: Option<Int>,
        elem: Elem,
    },
    Bytes(Len),
    Str {
        len: Len,
        nul: bool,
        accept_short: bool,
    },
    /// A list whose count is the value of an earlier field (`count_var`).
    ListVar {
        var: String,
        /// `count_var = "n - 1"`: the count is the variable minus this.
        minus: u64,
        elem: Elem,
    },
    /// A presence-vector bit with no bytes of its own (`flag = N` on a `bool`).
    Flag(u32),
    /// A union whose tag is the value of an earlier field (`tag_var`).
    TagVar {
        ty: Type,
        var: String,
    },
    Sized {
        size: Int,
        ty: Type,
    },
}

struct FieldModel {
    ident: Ident,
    bit: Option<u32>,
    /// Optional field present iff this variable is non-zero.
    present_if: Option<String>,
    /// This field's value is published as a variable for later fields.
    var: Option<String>,
    /// For a `var` field: the sibling list whose length it carries (computed on encode),
    /// and whether that list is optional.
    counts: Option<(Ident, bool)>,
    /// A `Vec<u32>` of byte offsets of the elements of this sibling list.
    offsets_of: Option<Ident>,
    /// For a list: the sibling offsets field to patch while encoding elements.
    patched_by: Option<Ident>,
    shape: Shape,
    path: LitStr,
    span: Span,
}

fn scaled_spec(s: &Scaled, errors: &mut Errors) -> Option<ScaledSpec> {
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
fn classify(
    ty: &Type,
    a: &FieldAttrs,
    field_span: Span,
    is_last: bool,
    errors: &mut Errors,
) -> Option<Shape> {
    let name = type_name(ty);
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
                Elem::Scaled(scaled_spec(sc, errors)?)
            }
            Some(sc) => {
                errors.error(sc.span, "`scaled` applies to `Vec<f64>`");
                return None;
            }
            None => Elem::Plain(inner.clone()),
        };
        // `name` or `name - N`.
        let (name, minus) = match var.split_once('-') {
            Some((n, m)) => match m.trim().parse::<u64>() {
                Ok(m) => (n.trim().to_string(), m),
                Err(_) => {
                    errors.error(*span, "`count_var` is a field name, optionally minus a constant: \"n\" or \"n - 1\"");
                    return None;
                }
            },
            None => (var.trim().to_string(), 0),
        };
        return Some(Shape::ListVar {
            var: name,
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
        let spec = scaled_spec(s, errors)?;
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

struct StructModel {
    presence: Option<Int>,
    fields: Vec<FieldModel>,
    unit: bool,
}

fn struct_model(input: &DeriveInput, c: &ContainerAttrs, errors: &mut Errors) -> StructModel {
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

// ---------------------------------------------------------------------------------
// Code generation for structs.

fn len_expr(shape: &Shape, v: &TokenStream, k: &TokenStream) -> TokenStream {
    let codec = quote!(#k::codec);
    match shape {
        Shape::Plain(_) => quote!(#codec::Encode::encoded_len(#v)),
        Shape::Scaled(s) => {
            let n = s.int.bytes();
            quote!(#n)
        }
        Shape::List { count, elem } => {
            let c = count.map_or(0, Int::bytes);
            match elem {
                Elem::Plain(_) => {
                    quote!(#c + #v.iter().map(#codec::Encode::encoded_len).sum::<usize>())
                }
                Elem::Scaled(s) => {
                    let n = s.int.bytes();
                    quote!(#c + #v.len() * #n)
                }
            }
        }
        Shape::Bytes(len) => match len {
            Len::Fixed(n) => quote!(#n),
            Len::Size(s) => {
                let c = s.bytes();
                quote!(#c + #v.len())
            }
            Len::Rest | Len::Nul => quote!(#v.len()),
        },
        Shape::Str { len, nul, .. } => match len {
            Len::Nul => quote!(#codec::latin1_len(#v) + 1),
            Len::Fixed(n) => quote!(#n),
            Len::Size(s) => {
                let c = s.bytes();
                quote!(#c + #codec::latin1_len(#v))
            }
            Len::Rest => {
                let extra = usize::from(*nul);
                quote!(#codec::latin1_len(#v) + #extra)
            }
        },
        Shape::Sized { size, .. } => {
            let c = size.bytes();
            quote!(#c + #codec::Encode::encoded_len(#v))
        }
        Shape::ListVar { elem, .. } => match elem {
            Elem::Plain(_) => quote!(#v.iter().map(#codec::Encode::encoded_len).sum::<usize>()),
            Elem::Scaled(s) => {
                let n = s.int.bytes();
                quote!(#v.len() * #n)
            }
        },
        Shape::Flag(_) => quote!(0usize),
        Shape::TagVar { .. } => quote!(#v.value_len()),
    }
}

fn scaled_args(s: &ScaledSpec) -> (Ident, f64, f64) {
    (s.int.ident(), s.lo, s.hi)
}

fn encode_stmt(shape: &Shape, v: &TokenStream, path: &LitStr, k: &TokenStream) -> TokenStream {
    let codec = quote!(#k::codec);
    match shape {
        // Written by the caller, which knows the neighbouring fields.
        Shape::ListVar { .. } | Shape::Flag(_) => quote!(let _ = #v;),
        Shape::TagVar { var, .. } => {
            let var = lit(var);
            quote! {
                let expected = w.var(#var, #path)?;
                if #v.tag() != expected {
                    return Err(#codec::EncodeError::TagMismatch { field: #path, tag: #v.tag(), tag_field: #var, expected });
                }
                #v.encode_value(w)?;
            }
        }
        Shape::Plain(_) => quote!(#codec::Encode::encode(#v, w)?;),
        Shape::Scaled(s) => {
            let (t, lo, hi) = scaled_args(s);
            quote!(#codec::Encode::encode(&#codec::scale_to::<#t>(*#v, #lo, #hi, #path)?, w)?;)
        }
        Shape::List { count, elem } => {
            let prefix = count.map(|c| {
                let c = c.ident();
                quote!(#codec::put_count::<#c>(w, #v.len(), #path)?;)
            });
            let each = match elem {
                Elem::Plain(_) => quote!(#codec::Encode::encode(e, w)?;),
                Elem::Scaled(s) => {
                    let (t, lo, hi) = scaled_args(s);
                    quote!(#codec::Encode::encode(&#codec::scale_to::<#t>(*e, #lo, #hi, #path)?, w)?;)
                }
            };
            quote!(#prefix for e in #v.iter() { #each })
        }
        Shape::Bytes(len) => match len {
            Len::Fixed(n) => quote!(#codec::put_fixed_bytes(w, #v, #n, #path)?;),
            Len::Size(s) => {
                let c = s.ident();
                quote!(#codec::put_count::<#c>(w, #v.len(), #path)?; w.put(#v)?;)
            }
            Len::Rest | Len::Nul => quote!(w.put(#v)?;),
        },
        Shape::Str { len, nul, .. } => match len {
            Len::Nul => quote!(#codec::put_cstring(w, #v, #path)?;),
            Len::Fixed(n) => quote!(#codec::put_fixed_string(w, #v, #n, #path)?;),
            Len::Size(s) => {
                let c = s.ident();
                quote!(#codec::put_count::<#c>(w, #codec::latin1_len(#v), #path)?; #codec::put_latin1(w, #v, #path)?;)
            }
            Len::Rest => {
                let term = nul.then(|| quote!(w.put(&[0u8])?;));
                quote!(#codec::put_latin1(w, #v, #path)?; #term)
            }
        },
        Shape::Sized { size, .. } => {
            let c = size.ident();
            quote!(#codec::put_count::<#c>(w, #codec::Encode::encoded_len(#v), #path)?; #codec::Encode::encode(#v, w)?;)
        }
    }
}

/// An expression of type `Result<T, DecodeError>` reading the field from `r`.
fn decode_expr(shape: &Shape, k: &TokenStream) -> TokenStream {
    let codec = quote!(#k::codec);
    let err = quote!(#codec::DecodeError);
    match shape {
        Shape::Plain(ty) => quote!(<#ty as #codec::Decode>::decode(r)),
        Shape::Scaled(s) => {
            let (t, lo, hi) = scaled_args(s);
            quote!(<#t as #codec::Decode>::decode(r).map(|n| #codec::scale_from::<#t>(n, #lo, #hi)))
        }
        Shape::List { count, elem } => match (count, elem) {
            (Some(c), Elem::Plain(ty)) => {
                let c = c.ident();
                quote!(#codec::decode_list::<#c, #ty>(r))
            }
            (None, Elem::Plain(ty)) => quote!(#codec::decode_rest::<#ty>(r)),
            (count, Elem::Scaled(s)) => {
                let (t, lo, hi) = scaled_args(s);
                let n = s.int.bytes();
                let head = match count {
                    Some(c) => {
                        let c = c.ident();
                        quote!(let n = #codec::get_count::<#c>(r, #n)?;)
                    }
                    None => quote!(let n = r.remaining() / #n;),
                };
                let tail = if count.is_none() {
                    quote!(if r.remaining() != 0 {
                        return Err(#err::new(#codec::DecodeErrorKind::TrailingBytes { count: r.remaining() }, r.offset()));
                    })
                } else {
                    quote!()
                };
                quote!((|r: &mut #codec::Reader<'_>| -> ::core::result::Result<::std::vec::Vec<f64>, #err> {
                    #head
                    let mut out = ::std::vec::Vec::with_capacity(n);
                    for _ in 0..n {
                        out.push(#codec::scale_from::<#t>(<#t as #codec::Decode>::decode(r)?, #lo, #hi));
                    }
                    #tail
                    Ok(out)
                })(r))
            }
        },
        Shape::Bytes(len) => match len {
            Len::Fixed(n) => quote!(r.take(#n).map(|b| b.to_vec())),
            Len::Size(s) => {
                let c = s.ident();
                quote!(#codec::get_count::<#c>(r, 1).and_then(|n| r.take(n)).map(|b| b.to_vec()))
            }
            Len::Rest | Len::Nul => quote!(Ok::<_, #err>(r.rest().to_vec())),
        },
        Shape::Str {
            len,
            nul,
            accept_short,
        } => match len {
            Len::Fixed(n) => quote!(#codec::get_fixed_string(r, #n, #accept_short)),
            Len::Size(s) => {
                let c = s.ident();
                quote!(#codec::get_count::<#c>(r, 1).and_then(|n| r.take(n)).map(#codec::latin1_to_string))
            }
            Len::Nul => quote!(#codec::get_cstring(r)),
            Len::Rest if *nul => quote!(Ok::<_, #err>(#codec::get_rest_string(r))),
            Len::Rest => quote!(Ok::<_, #err>(#codec::latin1_to_string(r.rest()))),
        },
        Shape::TagVar { ty, var } => {
            let var = lit(var);
            quote!(r.var(#var).and_then(|tag| <#ty>::decode_value(tag, r)))
        }
        Shape::ListVar { var, minus, elem } => {
            let var = lit(var);
            let (ty, min, read) = match elem {
                Elem::Plain(ty) => (
                    quote!(#ty),
                    quote!(<#ty as #codec::Decode>::MIN_LEN),
                    quote!(<#ty as #codec::Decode>::decode(r)?),
                ),
                Elem::Scaled(s) => {
                    let (t, lo, hi) = scaled_args(s);
                    let n = s.int.bytes();
                    (
                        quote!(f64),
                        quote!(#n),
                        quote!(#codec::scale_from::<#t>(<#t as #codec::Decode>::decode(r)?, #lo, #hi)),
                    )
                }
            };
            quote!((|r: &mut #codec::Reader<'_>| -> ::core::result::Result<::std::vec::Vec<#ty>, #err> {
                let n = r.var(#var)?.saturating_sub(#minus);
                let n = r.check_count(n, #min)?;
                let mut out = ::std::vec::Vec::with_capacity(n.min(r.remaining()));
                for _ in 0..n {
                    out.push(#read);
                }
                Ok(out)
            })(r))
        }
        Shape::Flag(_) => quote!(Ok::<bool, #err>(false)),
        Shape::Sized { size, ty } => {
            let c = size.ident();
            quote!((|r: &mut #codec::Reader<'_>| -> ::core::result::Result<#ty, #err> {
                let n = #codec::get_count::<#c>(r, 1)?;
                let mut sub = r.sub(n)?;
                let v = <#ty as #codec::Decode>::decode(&mut sub)?;
                if sub.remaining() != 0 {
                    return Err(#err::new(
                        #codec::DecodeErrorKind::SizeMismatch { announced: n, consumed: n - sub.remaining() },
                        sub.offset(),
                    ));
                }
                Ok(v)
            })(r))
        }
    }
}

fn min_len(shape: &Shape, k: &TokenStream) -> TokenStream {
    match shape {
        Shape::Plain(ty) => quote!(<#ty as #k::codec::Decode>::MIN_LEN),
        Shape::Scaled(s) => {
            let n = s.int.bytes();
            quote!(#n)
        }
        Shape::List { count, .. } => {
            let n = count.map_or(0, Int::bytes);
            quote!(#n)
        }
        Shape::Bytes(Len::Fixed(n)) => quote!(#n),
        Shape::Str {
            len: Len::Fixed(n),
            accept_short,
            ..
        } => {
            let n = if *accept_short { 0 } else { *n };
            quote!(#n)
        }
        Shape::Bytes(Len::Size(s))
        | Shape::Str {
            len: Len::Size(s), ..
        }
        | Shape::Sized { size: s, .. } => {
            let n = s.bytes();
            quote!(#n)
        }
        Shape::Bytes(Len::Rest) | Shape::Str { len: Len::Rest, .. } => quote!(0usize),
        Shape::Str { len: Len::Nul, .. } => quote!(1usize),
        Shape::ListVar { .. } | Shape::Flag(_) | Shape::TagVar { .. } | Shape::Bytes(Len::Nul) => {
            quote!(0usize)
        }
    }
}

/// Expands `JausMessage` (`is_message`) or `JausRecord`.
pub fn message(input: &DeriveInput, is_message: bool) -> TokenStream {
    let mut errors = Errors::default();
    let allowed: &[&str] = if is_message {
        &["code", "presence", "crate", "name"]
    } else {
        &["presence", "crate"]
    };
    let c = parse_container_attrs(&input.attrs, &mut errors, allowed);
    let k = crate_path(&c);
    if is_message && c.code.is_none() {
        errors.error(
            input.ident.span(),
            "missing `#[jaus(code = 0x....)]`: every message needs its 16-bit command code",
        );
    }
    let model = struct_model(input, &c, &mut errors);
    let ident = &input.ident;
    let (impl_g, ty_g, where_g) = input.generics.split_for_impl();
    let codec = quote!(#k::codec);

    if let Err(e) = errors.finish() {
        // Still provide the impls so that uses of the type do not cascade into errors.
        let err = e.to_compile_error();
        let msg_impl = is_message.then(|| {
            quote! {
                impl #impl_g #k::JausMessage for #ident #ty_g #where_g {
                    const CODE: #k::CommandCode = #k::CommandCode(0);
                    const NAME: &'static str = "";
                }
            }
        });
        return quote! {
            #err
            impl #impl_g #codec::Encode for #ident #ty_g #where_g {
                fn encoded_len(&self) -> usize { unreachable!() }
                fn encode(&self, _: &mut #codec::Writer<'_>) -> ::core::result::Result<(), #codec::EncodeError> { unreachable!() }
            }
            impl #impl_g #codec::Decode for #ident #ty_g #where_g {
                const MIN_LEN: usize = 0;
                fn decode(_: &mut #codec::Reader<'_>) -> ::core::result::Result<Self, #codec::DecodeError> { unreachable!() }
            }
            #msg_impl
        };
    }

    let pv_bytes = model.presence.map_or(0, Int::bytes);
    let mut lens = Vec::new();
    let mut encodes = Vec::new();
    let mut decodes = Vec::new();
    let mut mins = Vec::new();
    let mut pv_sets = Vec::new();
    let names: Vec<&Ident> = model.fields.iter().map(|f| &f.ident).collect();
    let mut prelude = Vec::new();
    for f in &model.fields {
        let id = &f.ident;
        let v = quote!(v);
        let len = match &f.offsets_of {
            // Computed offsets: one u32 per element of the target list.
            Some(target) => quote!({ let _ = #v; 4 * self.#target.len() }),
            None => len_expr(&f.shape, &v, &k),
        };
        let path = &f.path;
        let enc = match &f.shape {
            Shape::ListVar { var, minus, elem } => {
                let var = lit(var);
                let each = match elem {
                    Elem::Plain(_) => quote!(#codec::Encode::encode(e, w)?;),
                    Elem::Scaled(s) => {
                        let (t, lo, hi) = scaled_args(s);
                        quote!(#codec::Encode::encode(&#codec::scale_to::<#t>(*e, #lo, #hi, #path)?, w)?;)
                    }
                };
                let (n, body) = match &f.offsets_of {
                    // Offsets are computed, never taken from the value: reserve them
                    // now and patch each while the target list is written.
                    // Offsets given with one per element are written as given (a received
                    // message re-encodes byte for byte); otherwise they are computed:
                    // reserved now and patched while the target list is written.
                    Some(target) => {
                        let slot = format_ident!("__offsets_{}", id);
                        prelude.push(quote!(let mut #slot: ::core::option::Option<usize> = None;));
                        (
                            quote!(self.#target.len()),
                            quote! {
                                if #v.len() == n {
                                    for o in #v.iter() { #codec::Encode::encode(o, w)?; }
                                } else {
                                    #slot = Some(w.reserve(4 * n)?);
                                }
                            },
                        )
                    }
                    None => {
                        let patch = f.patched_by.as_ref().map(|o| {
                            let slot = format_ident!("__offsets_{}", o);
                            quote! {
                                if let Some(at) = #slot {
                                    let here = u32::try_from(w.position()).unwrap_or(u32::MAX);
                                    w.patch(at + 4 * i, &here.to_le_bytes());
                                }
                            }
                        });
                        (
                            quote!(#v.len()),
                            quote!(for (i, e) in #v.iter().enumerate() { let _ = i; #patch #each }),
                        )
                    }
                };
                quote! {
                    let expected = w.var(#var, #path)?.saturating_sub(#minus);
                    let n = #n;
                    if n as u64 != expected {
                        return Err(#codec::EncodeError::CountMismatch { field: #path, len: n, count_field: #var, expected });
                    }
                    #body
                }
            }
            Shape::Flag(_) => quote!(let _ = #v;),
            _ => encode_stmt(&f.shape, &v, &f.path, &k),
        };
        let dec = decode_expr(&f.shape, &k);
        let dec = quote_spanned! {f.span=>
            match #dec {
                ::core::result::Result::Ok(v) => v,
                ::core::result::Result::Err(e) => return ::core::result::Result::Err(e.in_field(#path)),
            }
        };
        // Publishing the value for later fields.
        let set_var_dec = f.var.as_ref().map(|name| {
            let name = lit(name);
            quote!(r.vars().set(#name, #id as u64);)
        });
        let p = model.presence.unwrap_or(Int::U32).ident();
        match (&f.shape, f.bit, &f.present_if) {
            (Shape::Flag(bit), ..) => {
                let set = f.var.as_ref().map(|name| {
                    let name = lit(name);
                    quote!(w.vars().set(#name, u64::from(self.#id));)
                });
                pv_sets.push(quote!(if self.#id { pv |= (1 as #p) << #bit; }));
                encodes.push(quote!(#set));
                decodes.push(quote!(let #id = pv & ((1 as #p) << #bit) != 0; #set_var_dec));
            }
            (_, Some(bit), _) => {
                lens.push(quote!(match &self.#id { Some(v) => #len, None => 0 }));
                encodes.push(quote!(if let Some(v) = &self.#id { #enc }));
                pv_sets.push(quote!(if self.#id.is_some() { pv |= (1 as #p) << #bit; }));
                decodes.push(quote!(let #id = if pv & ((1 as #p) << #bit) != 0 { Some(#dec) } else { None };));
            }
            (_, None, Some(flag)) => {
                let flag = lit(flag);
                lens.push(quote!(match &self.#id { Some(v) => #len, None => 0 }));
                encodes.push(quote! {
                    let want = w.var(#flag, #path)? != 0;
                    if want != self.#id.is_some() {
                        return Err(#codec::EncodeError::PresenceMismatch { field: #path, flag: #flag, expected: want });
                    }
                    if let Some(v) = &self.#id { #enc }
                });
                decodes.push(quote! {
                    let present = match r.var(#flag) {
                        Ok(x) => x != 0,
                        Err(e) => return Err(e.in_field(#path)),
                    };
                    let #id = if present { Some(#dec) } else { None };
                });
            }
            (_, None, None) => {
                lens.push(quote!({ let v = &self.#id; #len }));
                let enc = match (&f.var, &f.counts) {
                    // A count kept in its own field: written from the list it counts
                    // when that list is here, and published for nested lists.
                    (Some(name), counts) => {
                        let name = lit(name);
                        let Shape::Plain(ty) = &f.shape else {
                            unreachable!("checked: var fields are integers")
                        };
                        let value = match counts {
                            Some((list, true)) => {
                                quote!(match &self.#list { Some(l) => Some(l.len()), None => None })
                            }
                            Some((list, false)) => quote!(Some(self.#list.len())),
                            None => quote!(None::<usize>),
                        };
                        quote! {
                            let v: #ty = match #value {
                                Some(n) => <#ty>::try_from(n).map_err(|_| #codec::EncodeError::CountOverflow {
                                    field: #path, count: n, max: <#ty>::MAX as usize,
                                })?,
                                None => self.#id,
                            };
                            w.vars().set(#name, v as u64);
                            #codec::Encode::encode(&v, w)?;
                        }
                    }
                    (None, _) => quote!({ let v = &self.#id; #enc }),
                };
                encodes.push(enc);
                decodes.push(quote!(let #id = #dec; #set_var_dec));
                mins.push(min_len(&f.shape, &k));
            }
        }
    }
    let (pv_encode, pv_decode) = match model.presence {
        Some(p) => {
            let p = p.ident();
            let name = lit(&format!("{ident}.presence_vector"));
            (
                quote!(let mut pv: #p = 0; #(#pv_sets)* #codec::Encode::encode(&pv, w)?;),
                quote!(let pv = match <#p as #codec::Decode>::decode(r) {
                    ::core::result::Result::Ok(v) => v,
                    ::core::result::Result::Err(e) => return ::core::result::Result::Err(e.in_field(#name)),
                };),
            )
        }
        None => (quote!(), quote!()),
    };
    // Records (which may nest, even recursively) count their depth. On an error the
    // reader is abandoned, so only the success path needs to leave.
    let (enter, leave) = if is_message || model.fields.is_empty() {
        (quote!(), quote!())
    } else {
        (quote!(r.enter()?;), quote!(r.leave();))
    };
    let construct = if model.unit {
        quote!(#ident)
    } else {
        quote!(#ident { #(#names),* })
    };
    let unused_w =
        (model.fields.is_empty() && model.presence.is_none()).then(|| quote!(let _ = w;));
    let unused_r =
        (model.fields.is_empty() && model.presence.is_none()).then(|| quote!(let _ = r;));
    let msg_impl = is_message.then(|| {
        let code = c.code.map_or(0, |(c, _)| c);
        let name = c.name.clone().unwrap_or_else(|| lit(&ident.to_string()));
        quote! {
            impl #impl_g #k::JausMessage for #ident #ty_g #where_g {
                const CODE: #k::CommandCode = #k::CommandCode(#code);
                const NAME: &'static str = #name;
            }
        }
    });
    quote! {
        // Scaled limits are emitted as literals (e.g. 3.141592653589793), which clippy
        // would flag as approximations of named constants.
        #[allow(clippy::approx_constant)]
        impl #impl_g #codec::Encode for #ident #ty_g #where_g {
            #[inline]
            fn encoded_len(&self) -> usize {
                #pv_bytes #(+ #lens)*
            }
            #[inline]
            fn encode(&self, w: &mut #codec::Writer<'_>) -> ::core::result::Result<(), #codec::EncodeError> {
                #unused_w
                #(#prelude)*
                #pv_encode
                #(#encodes)*
                Ok(())
            }
        }
        #[allow(clippy::approx_constant)]
        impl #impl_g #codec::Decode for #ident #ty_g #where_g {
            const MIN_LEN: usize = #pv_bytes #(+ #mins)*;
            #[inline]
            fn decode(r: &mut #codec::Reader<'_>) -> ::core::result::Result<Self, #codec::DecodeError> {
                #unused_r
                #enter
                #pv_decode
                #(#decodes)*
                #leave
                Ok(#construct)
            }
        }
        #msg_impl
    }
}

// ---------------------------------------------------------------------------------
// Enumerations.

pub fn enumeration(input: &DeriveInput) -> TokenStream {
    let mut errors = Errors::default();
    let c = parse_container_attrs(&input.attrs, &mut errors, &["repr", "crate"]);
    let k = crate_path(&c);
    let codec = quote!(#k::codec);
    let ident = &input.ident;
    let repr = match &c.repr {
        Some(r) if r.int.unsigned() => Some(r.int),
        Some(r) => {
            errors.error(
                r.span,
                "an enumeration's repr is an unsigned integer: u8, u16, u32 or u64",
            );
            None
        }
        None => {
            errors.error(
                ident.span(),
                "missing `#[jaus(repr = u8|u16|u32)]`: the wire type of the enumeration",
            );
            None
        }
    };
    let mut known = Vec::new();
    let mut unknown: Option<Ident> = None;
    match &input.data {
        Data::Enum(e) => {
            let mut seen: Vec<(u64, String)> = Vec::new();
            for v in &e.variants {
                let mut is_unknown = false;
                let mut attr_value: Option<u64> = None;
                for_each_item(&v.attrs, &mut errors, |key, input, errors| {
                    if key == "unknown" {
                        is_unknown = true;
                    } else if key == "value" {
                        input.parse::<syn::Token![=]>()?;
                        let l: syn::LitInt = input.parse()?;
                        attr_value = Some(l.base10_parse()?);
                    } else {
                        errors.error(key.span(), format!("unknown jaus variant attribute `{key}`; expected `value = N` or `unknown`"));
                        while !input.is_empty() && !input.peek(syn::Token![,]) {
                            input.parse::<proc_macro2::TokenTree>()?;
                        }
                    }
                    Ok(())
                });
                if is_unknown {
                    let ok = matches!(&v.fields, Fields::Unnamed(u) if u.unnamed.len() == 1
                        && Some(is_int_type(&u.unnamed[0].ty)) == Some(repr));
                    if !ok {
                        errors.error(
                            v.ident.span(),
                            "the `unknown` variant must hold the raw value: `Unknown(<repr>)`",
                        );
                    }
                    unknown = Some(v.ident.clone());
                    continue;
                }
                if !matches!(v.fields, Fields::Unit) {
                    errors.error(v.ident.span(), "enumeration variants are unit variants with a value (`Name = 3`); use JausUnion for variants with data");
                    continue;
                }
                let value = match (&v.discriminant, attr_value) {
                    (None, Some(v)) => Some(v),
                    (
                        Some((
                            _,
                            syn::Expr::Lit(syn::ExprLit {
                                lit: syn::Lit::Int(i),
                                ..
                            }),
                        )),
                        None,
                    ) => i.base10_parse::<u64>().ok(),
                    _ => None,
                };
                match value {
                    Some(val) => {
                        if let Some((_, other)) = seen.iter().find(|(s, _)| *s == val) {
                            errors.error(v.ident.span(), format!("value {val} is already used by `{other}`"));
                        }
                        if let Some(r) = repr {
                            if r.bits() < 64 && val >> r.bits() != 0 {
                                errors.error(v.ident.span(), format!("value {val} does not fit in {}", r.ident()));
                            }
                        }
                        seen.push((val, v.ident.to_string()));
                        known.push((v.ident.clone(), val));
                    }
                    None => errors.error(v.ident.span(), "each variant needs exactly one wire value: `Name = 3` or `#[jaus(value = 3)]`"),
                }
            }
        }
        _ => errors.error(ident.span(), "JausEnum applies to an enum"),
    }
    if let Err(e) = errors.finish() {
        let err = e.to_compile_error();
        return quote! {
            #err
            impl #codec::Encode for #ident {
                fn encoded_len(&self) -> usize { unreachable!() }
                fn encode(&self, _: &mut #codec::Writer<'_>) -> ::core::result::Result<(), #codec::EncodeError> { unreachable!() }
            }
            impl #codec::Decode for #ident {
                const MIN_LEN: usize = 0;
                fn decode(_: &mut #codec::Reader<'_>) -> ::core::result::Result<Self, #codec::DecodeError> { unreachable!() }
            }
        };
    }
    let repr = repr.expect("checked").ident();
    let n = Int::parse(&repr.to_string()).expect("int").bytes();
    let lits: Vec<(Ident, proc_macro2::Literal)> = known
        .iter()
        .map(|(v, val)| (v.clone(), proc_macro2::Literal::u64_unsuffixed(*val)))
        .collect();
    let to_arms = lits.iter().map(|(v, val)| quote!(Self::#v => #val));
    let from_arms = lits.iter().map(|(v, val)| quote!(#val => Some(Self::#v)));
    let (unknown_to, decode_other) = match &unknown {
        Some(u) => (quote!(Self::#u(v) => *v,), quote!(Ok(Self::#u(v)))),
        None => (
            quote!(),
            quote!(Err(#codec::DecodeError::new(#codec::DecodeErrorKind::UndefinedValue { value: v as u64 }, at))),
        ),
    };
    let from_arms2 = lits.iter().map(|(v, val)| quote!(#val => Ok(Self::#v)));
    quote! {
        impl #ident {
            /// The value of this variant on the wire.
            pub fn to_repr(&self) -> #repr {
                match self { #(#to_arms,)* #unknown_to }
            }
            /// The named variant with wire value `v`, if the definition names one.
            pub fn from_repr(v: #repr) -> ::core::option::Option<Self> {
                #[allow(unreachable_patterns)]
                match v { #(#from_arms,)* _ => None }
            }
        }
        impl #codec::Encode for #ident {
            #[inline]
            fn encoded_len(&self) -> usize { #n }
            #[inline]
            fn encode(&self, w: &mut #codec::Writer<'_>) -> ::core::result::Result<(), #codec::EncodeError> {
                #codec::Encode::encode(&self.to_repr(), w)
            }
        }
        impl #codec::Decode for #ident {
            const MIN_LEN: usize = #n;
            #[inline]
            fn decode(r: &mut #codec::Reader<'_>) -> ::core::result::Result<Self, #codec::DecodeError> {
                let at = r.offset();
                let v = <#repr as #codec::Decode>::decode(r)?;
                let _ = at;
                #[allow(unreachable_patterns)]
                match v { #(#from_arms2,)* _ => #decode_other }
            }
        }
    }
}

// ---------------------------------------------------------------------------------
// Bit fields.

pub fn bits(input: &DeriveInput) -> TokenStream {
    let mut errors = Errors::default();
    let c = parse_container_attrs(&input.attrs, &mut errors, &["repr", "crate"]);
    let k = crate_path(&c);
    let codec = quote!(#k::codec);
    let ident = &input.ident;
    let repr = match &c.repr {
        Some(r) if r.int.unsigned() => Some(r.int),
        Some(r) => {
            errors.error(
                r.span,
                "a bit field's repr is an unsigned integer: u8, u16, u32 or u64",
            );
            None
        }
        None => {
            errors.error(
                ident.span(),
                "missing `#[jaus(repr = u8|u16|u32)]`: the integer that holds the bits",
            );
            None
        }
    };
    let width = repr.map_or(64, Int::bits);
    let mut defined: u64 = 0;
    let mut taken: Vec<(u64, String, u32, u32)> = Vec::new();
    let mut members = Vec::new(); // (ident, lo, hi, is_bool)
    let mut reserved: Option<Ident> = None;
    match &input.data {
        Data::Struct(s) => {
            for f in &s.fields {
                let Some(id) = f.ident.clone() else {
                    errors.error(span_of(f), "name the fields of a bit field");
                    continue;
                };
                let a = parse_field_attrs(&f.attrs, &mut errors, true);
                let tname = type_name(&f.ty);
                if a.reserved.is_some() {
                    if tname.as_deref().and_then(Int::parse) != repr {
                        errors.error(
                            span_of(&f.ty),
                            "the `reserved` field has the repr type and holds the undefined bits",
                        );
                    }
                    reserved = Some(id);
                    continue;
                }
                let (lo, hi, span) = match (a.bit, a.bits) {
                    (Some((b, s)), None) => (b, b, s),
                    (None, Some(r)) => r,
                    _ => {
                        errors.error(span_of(&id), "each member of a bit field needs `bit = N` (a bool) or `bits = A..=B` (an unsigned integer)");
                        continue;
                    }
                };
                if lo > hi || hi >= width {
                    errors.error(
                        span,
                        format!(
                            "bits {lo}..={hi} are out of range: the field has bits 0..={}",
                            width - 1
                        ),
                    );
                    continue;
                }
                let mask = if hi - lo + 1 == 64 {
                    u64::MAX
                } else {
                    ((1u64 << (hi - lo + 1)) - 1) << lo
                };
                if let Some((_, other, olo, ohi)) = taken.iter().find(|(m, ..)| m & mask != 0) {
                    errors.error(
                        span,
                        format!("bits {lo}..={hi} overlap member `{other}` (bits {olo}..={ohi})"),
                    );
                }
                taken.push((mask, id.to_string(), lo, hi));
                defined |= mask;
                let is_bool = tname.as_deref() == Some("bool");
                if a.bit.is_some() && !is_bool {
                    errors.error(span_of(&f.ty), "a single `bit` member is a `bool`");
                    continue;
                }
                if a.bits.is_some() {
                    match tname.as_deref().and_then(Int::parse) {
                        Some(t) if t.unsigned() && t.bits() > hi - lo => {}
                        _ => {
                            errors.error(span_of(&f.ty), format!("a {}-bit member needs an unsigned integer type at least that wide", hi - lo + 1));
                            continue;
                        }
                    }
                }
                members.push((id, lo, hi, is_bool, f.ty.clone()));
            }
        }
        _ => errors.error(ident.span(), "JausBits applies to a struct"),
    }
    if let Err(e) = errors.finish() {
        let err = e.to_compile_error();
        return quote! {
            #err
            impl #codec::Encode for #ident {
                fn encoded_len(&self) -> usize { unreachable!() }
                fn encode(&self, _: &mut #codec::Writer<'_>) -> ::core::result::Result<(), #codec::EncodeError> { unreachable!() }
            }
            impl #codec::Decode for #ident {
                const MIN_LEN: usize = 0;
                fn decode(_: &mut #codec::Reader<'_>) -> ::core::result::Result<Self, #codec::DecodeError> { unreachable!() }
            }
        };
    }
    let repr_i = repr.expect("checked");
    let rt = repr_i.ident();
    let n = repr_i.bytes();
    let mut enc = Vec::new();
    let mut dec = Vec::new();
    for (id, lo, hi, is_bool, ty) in &members {
        let path = lit(&format!("{ident}.{id}"));
        let w = hi - lo + 1;
        let mask: u64 = if w == 64 { u64::MAX } else { (1u64 << w) - 1 };
        if *is_bool {
            enc.push(quote!(if self.#id { x |= 1u64 << #lo; }));
            dec.push(quote!(#id: (x >> #lo) & 1 != 0));
        } else {
            enc.push(quote! {
                let v = self.#id as u64;
                if v > #mask {
                    return Err(#codec::EncodeError::BitsOverflow { field: #path, value: v, width: #w });
                }
                x |= v << #lo;
            });
            dec.push(quote!(#id: ((x >> #lo) & #mask) as #ty));
        }
    }
    let undefined = !defined
        & if width == 64 {
            u64::MAX
        } else {
            (1u64 << width) - 1
        };
    if let Some(r) = &reserved {
        enc.push(quote!(x |= (self.#r as u64) & #undefined;));
        dec.push(quote!(#r: (x & #undefined) as #rt));
    }
    quote! {
        impl #codec::Encode for #ident {
            #[inline]
            fn encoded_len(&self) -> usize { #n }
            #[inline]
            fn encode(&self, w: &mut #codec::Writer<'_>) -> ::core::result::Result<(), #codec::EncodeError> {
                let mut x: u64 = 0;
                #(#enc)*
                #codec::Encode::encode(&(x as #rt), w)
            }
        }
        impl #codec::Decode for #ident {
            const MIN_LEN: usize = #n;
            #[inline]
            fn decode(r: &mut #codec::Reader<'_>) -> ::core::result::Result<Self, #codec::DecodeError> {
                let x = <#rt as #codec::Decode>::decode(r)? as u64;
                Ok(Self { #(#dec,)* })
            }
        }
    }
}

// ---------------------------------------------------------------------------------
// Tagged unions.

pub fn union(input: &DeriveInput) -> TokenStream {
    let mut errors = Errors::default();
    let c = parse_container_attrs(&input.attrs, &mut errors, &["tag", "crate"]);
    let k = crate_path(&c);
    let codec = quote!(#k::codec);
    let ident = &input.ident;
    let tag = match &c.tag {
        Some(t) if t.int.unsigned() && t.int != Int::U64 => Some(t.int),
        Some(t) => {
            errors.error(t.span, "a union tag is an unsigned integer: u8, u16 or u32");
            None
        }
        None => {
            errors.error(
                ident.span(),
                "missing `#[jaus(tag = u8|u16|u32)]`: the wire type of the tag",
            );
            None
        }
    };
    let mut variants = Vec::new();
    match &input.data {
        Data::Enum(e) => {
            let mut seen: Vec<(u64, String)> = Vec::new();
            for v in &e.variants {
                let mut t: Option<(u64, Span)> = None;
                for_each_item(&v.attrs, &mut errors, |key, input, errors| {
                    if key == "tag" {
                        input.parse::<syn::Token![=]>()?;
                        let l: syn::LitInt = input.parse()?;
                        t = Some((l.base10_parse()?, l.span()));
                    } else {
                        errors.error(
                            key.span(),
                            format!("unknown jaus variant attribute `{key}`; expected `tag = N`"),
                        );
                        while !input.is_empty() && !input.peek(syn::Token![,]) {
                            input.parse::<proc_macro2::TokenTree>()?;
                        }
                    }
                    Ok(())
                });
                let Some((val, span)) = t else {
                    errors.error(
                        v.ident.span(),
                        "each variant needs its tag: `#[jaus(tag = N)]`",
                    );
                    continue;
                };
                if let Some((_, other)) = seen.iter().find(|(s, _)| *s == val) {
                    errors.error(span, format!("tag {val} is already used by `{other}`"));
                }
                seen.push((val, v.ident.to_string()));
                let payload = match &v.fields {
                    Fields::Unit => None,
                    Fields::Unnamed(u) if u.unnamed.len() == 1 => Some(u.unnamed[0].ty.clone()),
                    _ => {
                        errors.error(
                            v.ident.span(),
                            "a union variant is a unit variant or holds one value: `Name(T)`",
                        );
                        continue;
                    }
                };
                variants.push((v.ident.clone(), val, payload));
            }
        }
        _ => errors.error(ident.span(), "JausUnion applies to an enum"),
    }
    if let Err(e) = errors.finish() {
        let err = e.to_compile_error();
        return quote! {
            #err
            impl #codec::Encode for #ident {
                fn encoded_len(&self) -> usize { unreachable!() }
                fn encode(&self, _: &mut #codec::Writer<'_>) -> ::core::result::Result<(), #codec::EncodeError> { unreachable!() }
            }
            impl #codec::Decode for #ident {
                const MIN_LEN: usize = 0;
                fn decode(_: &mut #codec::Reader<'_>) -> ::core::result::Result<Self, #codec::DecodeError> { unreachable!() }
            }
        };
    }
    let tag = tag.expect("checked");
    let tt = tag.ident();
    let n = tag.bytes();
    let mut lens = Vec::new();
    let mut encs = Vec::new();
    let mut decs = Vec::new();
    for (v, val, payload) in &variants {
        let path = lit(&format!("{ident}::{v}"));
        match payload {
            Some(ty) => {
                lens.push(quote!(Self::#v(x) => #n + #codec::Encode::encoded_len(x)));
                encs.push(quote!(Self::#v(x) => { #codec::Encode::encode(&(#val as #tt), w)?; #codec::Encode::encode(x, w) }));
                decs.push(quote!(#val => match <#ty as #codec::Decode>::decode(r) {
                    Ok(x) => Ok(Self::#v(x)),
                    Err(e) => Err(e.in_field(#path)),
                }));
            }
            None => {
                lens.push(quote!(Self::#v => #n));
                encs.push(quote!(Self::#v => #codec::Encode::encode(&(#val as #tt), w)));
                decs.push(quote!(#val => Ok(Self::#v)));
            }
        }
    }
    // Tag and value apart: for unions whose tag is carried elsewhere (a type code in
    // another field or message).
    let tags = variants.iter().map(|(v, val, p)| {
        if p.is_some() {
            quote!(Self::#v(_) => #val)
        } else {
            quote!(Self::#v => #val)
        }
    });
    let value_encs = variants.iter().map(|(v, _, p)| {
        if p.is_some() {
            quote!(Self::#v(x) => #codec::Encode::encode(x, w))
        } else {
            quote!(Self::#v => Ok(()))
        }
    });
    let value_lens = variants.iter().map(|(v, _, p)| {
        if p.is_some() {
            quote!(Self::#v(x) => #codec::Encode::encoded_len(x))
        } else {
            quote!(Self::#v => 0)
        }
    });
    quote! {
        impl #ident {
            /// The tag of this variant.
            pub fn tag(&self) -> u64 {
                match self { #(#tags,)* }
            }

            /// Reads the value of the variant with tag `tag` (the tag itself is not read).
            pub fn decode_value(tag: u64, r: &mut #codec::Reader<'_>) -> ::core::result::Result<Self, #codec::DecodeError> {
                let at = r.offset();
                match tag {
                    #(#decs,)*
                    other => Err(#codec::DecodeError::new(#codec::DecodeErrorKind::UndefinedValue { value: other }, at)),
                }
            }

            /// Writes the value without the tag.
            pub fn encode_value(&self, w: &mut #codec::Writer<'_>) -> ::core::result::Result<(), #codec::EncodeError> {
                match self { #(#value_encs,)* }
            }

            /// Bytes of the value without the tag.
            pub fn value_len(&self) -> usize {
                match self { #(#value_lens,)* }
            }
        }
        impl #codec::Encode for #ident {
            #[inline]
            fn encoded_len(&self) -> usize { match self { #(#lens,)* } }
            #[inline]
            fn encode(&self, w: &mut #codec::Writer<'_>) -> ::core::result::Result<(), #codec::EncodeError> {
                match self { #(#encs,)* }
            }
        }
        impl #codec::Decode for #ident {
            const MIN_LEN: usize = #n;
            fn decode(r: &mut #codec::Reader<'_>) -> ::core::result::Result<Self, #codec::DecodeError> {
                let at = r.offset();
                let tag = <#tt as #codec::Decode>::decode(r)?;
                match Self::decode_value(tag as u64, r) {
                    // An undefined tag is reported where the tag is.
                    Err(e) if matches!(e.kind(), #codec::DecodeErrorKind::UndefinedValue { .. }) && e.offset() == at + #n => {
                        Err(#codec::DecodeError::new(e.kind().clone(), at))
                    }
                    other => other,
                }
            }
        }
    }
}
