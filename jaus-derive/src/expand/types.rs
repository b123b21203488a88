//! Inspection of the Rust types of fields: `Option<T>`, `Vec<T>`, integer names.

use crate::attr::Int;
use syn::{GenericArgument, PathArguments, Type};

fn last_segment(ty: &Type) -> Option<&syn::PathSegment> {
    match ty {
        Type::Path(p) if p.qself.is_none() => p.path.segments.last(),
        _ => None,
    }
}

/// `Wrapper<T>` → `T`.
pub(super) fn generic_inner<'a>(ty: &'a Type, wrapper: &str) -> Option<&'a Type> {
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

pub(super) fn type_name(ty: &Type) -> Option<String> {
    let seg = last_segment(ty)?;
    matches!(seg.arguments, PathArguments::None).then(|| seg.ident.to_string())
}

pub(super) fn is_int_type(ty: &Type) -> Option<Int> {
    type_name(ty).and_then(|n| Int::parse(&n))
}
