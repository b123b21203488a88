//! The code of each field of a message or record, by kind of field: what its value
//! costs, writes and reads, and how its presence and its dependencies on other fields
//! wrap that.

mod bytes;
mod dependent;
mod fixed;
mod list;
mod number;
mod presence;

pub(super) use fixed::{encodes as fixed_runs, fuse_presence, slot, whole as fixed_whole, Slot};
pub(super) use presence::vector as presence_vector;

use super::model::{Elem, FieldModel, Shape};
use crate::attr::Int;
use proc_macro2::TokenStream;
use quote::{quote, quote_spanned};

/// The code of a field's value: its encoded length and encoding with the value bound to
/// `v` (a reference), an expression of type `Result<T, DecodeError>` reading it from
/// `r`, and its minimum length on the wire.
pub(super) struct ValueCode {
    len: TokenStream,
    encode: TokenStream,
    decode: TokenStream,
    min_len: TokenStream,
}

/// What the fields contribute to the `Encode` and `Decode` impls of their struct.
#[derive(Default)]
pub(super) struct Parts {
    /// Statements before any field is written (slots of computed offsets).
    pub(super) prelude: Vec<TokenStream>,
    /// Terms of `encoded_len`.
    pub(super) lens: Vec<TokenStream>,
    /// Statements of `encode`, in field order.
    pub(super) encodes: Vec<TokenStream>,
    /// Statements of `decode` binding each field to its name, in field order.
    pub(super) decodes: Vec<TokenStream>,
    /// Terms of `MIN_LEN` (of the fields that are always there).
    pub(super) mins: Vec<TokenStream>,
    /// Statements setting the presence bits in `pv` before it is written, by field.
    pub(super) pv_sets: Vec<(syn::Ident, TokenStream)>,
    /// Statements of `clamp_to_range`: every scaled value clamped to its limits.
    pub(super) clamps: Vec<TokenStream>,
}

/// Adds the code of field `f` of a struct with presence vector `presence`.
pub(super) fn add(f: &FieldModel, presence: Option<Int>, k: &TokenStream, parts: &mut Parts) {
    let codec = quote!(#k::codec);
    let (id, path) = (&f.ident, &f.path);
    let code = value(f, &quote!(v), &codec, &mut parts.prelude);
    let dec = &code.decode;
    let dec = quote_spanned! {f.span=>
        match #dec {
            ::core::result::Result::Ok(v) => v,
            ::core::result::Result::Err(e) => return ::core::result::Result::Err(e.in_field(#path)),
        }
    };
    if let Some(clamp) = clamp(&f.shape, &codec) {
        parts
            .clamps
            .push(if f.bit.is_some() || f.present_if.is_some() {
                quote!(if let Some(v) = &mut self.#id { #clamp })
            } else {
                quote!({ let v = &mut self.#id; #clamp })
            });
    }
    let p = presence.unwrap_or(Int::U32).ident();
    match (&f.shape, f.bit, &f.present_if) {
        (Shape::Flag(bit), ..) => presence::flag(f, *bit, &p, parts),
        (_, Some(bit), _) => presence::optional(f, bit, &p, &code, &dec, parts),
        (_, None, Some(flag)) => dependent::present_if(f, flag, &code, &dec, &codec, parts),
        (_, None, None) => {
            let (len, enc) = (&code.len, &code.encode);
            parts.lens.push(quote!({ let v = &self.#id; #len }));
            parts.encodes.push(match &f.var {
                // A count kept in its own field: written from the list it counts
                // when that list is here, and published for nested lists.
                Some(name) => dependent::var_encode(f, name, &codec),
                None => quote!({ let v = &self.#id; #enc }),
            });
            let set_var_dec = dependent::publish_decoded(f);
            let local = f.local();
            parts.decodes.push(quote!(let #local = #dec; #set_var_dec));
            parts.mins.push(code.min_len);
        }
    }
}

/// Clamps every scaled value of the field's value `v` (a `&mut T`) to its limits, or
/// `None` when the shape holds no value that can have one.
fn clamp(shape: &Shape, codec: &TokenStream) -> Option<TokenStream> {
    let each = |elem: &Elem| match elem {
        Elem::Scaled(s) => number::clamp_scaled(s, &quote!(e), codec),
        Elem::Plain(_) => quote!(#codec::Encode::clamp_to_range(e);),
    };
    match shape {
        Shape::Scaled(s) => Some(number::clamp_scaled(s, &quote!(v), codec)),
        // Any codec type: a record or union clamps its own scaled fields; for the
        // others this does nothing.
        Shape::Plain(_) | Shape::Sized { .. } | Shape::TagVar { .. } => {
            Some(quote!(#codec::Encode::clamp_to_range(v);))
        }
        Shape::List { elem, .. } | Shape::ListVar { elem, .. } => {
            let each = each(elem);
            Some(quote!(for e in v.iter_mut() { #each }))
        }
        Shape::Bytes(_) | Shape::Str { .. } | Shape::Flag(_) => None,
    }
}

/// The code of the value of field `f`, by its shape.
fn value(
    f: &FieldModel,
    v: &TokenStream,
    codec: &TokenStream,
    prelude: &mut Vec<TokenStream>,
) -> ValueCode {
    let path = &f.path;
    match &f.shape {
        Shape::Plain(ty) => number::plain(ty, v, codec),
        Shape::Scaled(s) => number::scaled(s, v, path, codec),
        Shape::List { count, elem } => list::list(*count, elem, v, path, codec),
        Shape::Bytes(len) => bytes::bytes(*len, v, path, codec),
        Shape::Str {
            len,
            nul,
            accept_short,
        } => bytes::string(*len, *nul, *accept_short, v, path, codec),
        Shape::Sized { size, ty } => bytes::sized(*size, ty, v, path, codec),
        Shape::ListVar { var, minus, elem } => {
            dependent::count_var(f, var, *minus, elem, v, codec, prelude)
        }
        Shape::TagVar { ty, var } => dependent::tag_var(ty, var, v, path, codec),
        Shape::Flag(_) => presence::flag_value(v, codec),
    }
}
