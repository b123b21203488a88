//! Fields that depend on earlier fields of the body: published variables (`var`), lists
//! counted by one (`count_var`), byte offsets of a list (`offsets`), optional fields
//! present by one (`present_if`) and unions tagged by one (`tag_var`).

use super::list::{elems_len, encode_elem, encode_elems};
use super::number::read_scaled;
use super::{Parts, ValueCode};
use crate::expand::common::lit;
use crate::expand::model::{Elem, FieldModel, Shape};
use proc_macro2::TokenStream;
use quote::{format_ident, quote};
use syn::Type;

/// A list whose count is the variable `var` minus `minus`; when the field holds the
/// offsets of another list, the offsets are computed while that list is written.
pub(super) fn count_var(
    f: &FieldModel,
    var: &str,
    minus: u64,
    elem: &Elem,
    v: &TokenStream,
    codec: &TokenStream,
    prelude: &mut Vec<TokenStream>,
) -> ValueCode {
    let err = quote!(#codec::DecodeError);
    let (id, path) = (&f.ident, &f.path);
    let var = lit(var);
    let len = match &f.offsets_of {
        // Computed offsets: one u32 per element of the target list.
        Some(target) => quote!({ let _ = #v; 4 * self.#target.len() }),
        None => elems_len(elem, v, codec),
    };
    let each = encode_elem(elem, path, codec);
    let (n, body) = match &f.offsets_of {
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
            let body = match patch {
                Some(patch) => {
                    quote!(for (i, e) in #v.iter().enumerate() { #patch #each })
                }
                None => encode_elems(elem, v, path, codec),
            };
            (quote!(#v.len()), body)
        }
    };
    let encode = quote! {
        let expected = w.var(#var, #path)?.saturating_sub(#minus);
        let n = #n;
        if n as u64 != expected {
            return Err(#codec::EncodeError::CountMismatch { field: #path, len: n, count_field: #var, expected });
        }
        #body
    };
    let (ty, min, read) = match elem {
        Elem::Plain(ty) => (
            quote!(#ty),
            quote!(<#ty as #codec::Decode>::MIN_LEN),
            quote!(<#ty as #codec::Decode>::decode(r)?),
        ),
        Elem::Scaled(s) => {
            let n = s.int.bytes();
            (quote!(f64), quote!(#n), read_scaled(s, codec))
        }
    };
    let decode = quote!((|r: &mut #codec::Reader<'_>| -> ::core::result::Result<::std::vec::Vec<#ty>, #err> {
        let n = r.var(#var)?.saturating_sub(#minus);
        let n = r.check_count(n, #min)?;
        let mut out = ::std::vec::Vec::with_capacity(n.min(r.remaining()));
        for _ in 0..n {
            out.push(#read);
        }
        Ok(out)
    })(r));
    ValueCode {
        len,
        encode,
        decode,
        min_len: quote!(0usize),
    }
}

/// A union without its tag; the tag is the variable `var`.
pub(super) fn tag_var(
    ty: &Type,
    var: &str,
    v: &TokenStream,
    path: &syn::LitStr,
    codec: &TokenStream,
) -> ValueCode {
    let var = lit(var);
    ValueCode {
        len: quote!(#v.value_len()),
        encode: quote! {
            let expected = w.var(#var, #path)?;
            if #v.tag() != expected {
                return Err(#codec::EncodeError::TagMismatch { field: #path, tag: #v.tag(), tag_field: #var, expected });
            }
            #v.encode_value(w)?;
        },
        decode: quote!(r.var(#var).and_then(|tag| <#ty>::decode_value(tag, r))),
        min_len: quote!(0usize),
    }
}

/// An optional field present exactly when the variable `flag` is non-zero.
pub(super) fn present_if(
    f: &FieldModel,
    flag: &str,
    code: &ValueCode,
    dec: &TokenStream,
    codec: &TokenStream,
    parts: &mut Parts,
) {
    let (id, path, local) = (&f.ident, &f.path, f.local());
    let (len, enc) = (&code.len, &code.encode);
    let flag = lit(flag);
    parts
        .lens
        .push(quote!(match &self.#id { Some(v) => #len, None => 0 }));
    parts.encodes.push(quote! {
        let want = w.var(#flag, #path)? != 0;
        if want != self.#id.is_some() {
            return Err(#codec::EncodeError::PresenceMismatch { field: #path, flag: #flag, expected: want });
        }
        if let Some(v) = &self.#id { #enc }
    });
    parts.decodes.push(quote! {
        let present = match r.var(#flag) {
            Ok(x) => x != 0,
            Err(e) => return Err(e.in_field(#path)),
        };
        let #local = if present { Some(#dec) } else { None };
    });
}

/// Writes a field that publishes its value as the variable `name`: when the list it
/// counts is in this struct the value is that list's length, else the field's own.
pub(super) fn var_encode(f: &FieldModel, name: &str, codec: &TokenStream) -> TokenStream {
    let (id, path) = (&f.ident, &f.path);
    let name = lit(name);
    let Shape::Plain(ty) = &f.shape else {
        unreachable!("checked: var fields are integers")
    };
    let value = match &f.counts {
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

/// After decoding a `var` field: publishes its value for later fields.
pub(super) fn publish_decoded(f: &FieldModel) -> Option<TokenStream> {
    let local = f.local();
    f.var.as_ref().map(|name| {
        let name = lit(name);
        quote!(r.vars().set(#name, #local as u64);)
    })
}
