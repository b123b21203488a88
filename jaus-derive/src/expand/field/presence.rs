//! The presence vector: optional fields behind a presence bit (`bit = N`), flags that
//! are a presence bit with no bytes (`flag = N`), and the vector itself, computed on
//! encode and never stored.

use super::dependent::publish_decoded;
use super::{Parts, ValueCode};
use crate::attr::Int;
use crate::expand::common::lit;
use crate::expand::model::FieldModel;
use proc_macro2::{Ident, TokenStream};
use quote::quote;

/// The value of a flag: it has no bytes of its own (its presence bit is its value).
pub(super) fn flag_value(v: &TokenStream, codec: &TokenStream) -> ValueCode {
    let err = quote!(#codec::DecodeError);
    ValueCode {
        len: quote!(0usize),
        encode: quote!(let _ = #v;),
        decode: quote!(Ok::<bool, #err>(false)),
        min_len: quote!(0usize),
    }
}

/// A `bool` that is bit `bit` of the presence vector of type `p`.
pub(super) fn flag(f: &FieldModel, bit: u32, p: &Ident, parts: &mut Parts) {
    let (id, local) = (&f.ident, f.local());
    let set = f.var.as_ref().map(|name| {
        let name = lit(name);
        quote!(w.vars().set(#name, u64::from(self.#id));)
    });
    let set_var_dec = publish_decoded(f);
    parts
        .pv_sets
        .push((id.clone(), quote!(if self.#id { pv |= (1 as #p) << #bit; })));
    parts.encodes.push(quote!(#set));
    parts
        .decodes
        .push(quote!(let #local = pv & ((1 as #p) << #bit) != 0; #set_var_dec));
}

/// An `Option<T>` present when bit `bit` of the presence vector of type `p` is set.
pub(super) fn optional(
    f: &FieldModel,
    bit: u32,
    p: &Ident,
    code: &ValueCode,
    dec: &TokenStream,
    parts: &mut Parts,
) {
    let (id, local) = (&f.ident, f.local());
    let (len, enc) = (&code.len, &code.encode);
    parts
        .lens
        .push(quote!(match &self.#id { Some(v) => #len, None => 0 }));
    parts
        .encodes
        .push(quote!(if let Some(v) = &self.#id { #enc }));
    parts.pv_sets.push((
        id.clone(),
        quote!(if self.#id.is_some() { pv |= (1 as #p) << #bit; }),
    ));
    parts
        .decodes
        .push(quote!(let #local = if pv & ((1 as #p) << #bit) != 0 { Some(#dec) } else { None };));
}

/// Writing and reading the presence vector of type `presence` of struct `ident`, from
/// the bits the fields set (`parts.pv_sets`), and what ends the decoding of a message
/// body after its known fields.
///
/// On decode the bits the definition does not define (`known` are those it does) are
/// checked by `codec::check_presence`: in a message body (`is_message`) the fields a
/// newer revision appends under them are skipped to the end of the body; in a record
/// they are an error. `rest_present` is an expression telling whether the last field
/// runs to the end of the body and is present. The bits of the fields in `fused` are
/// set while those fields are written (see `fixed::fuse_presence`), or by
/// `PresenceCode::fused_sets` before `pv` is written field by field.
#[allow(clippy::too_many_arguments)]
pub(in crate::expand) fn vector(
    presence: Option<Int>,
    ident: &Ident,
    parts: &Parts,
    codec: &TokenStream,
    is_message: bool,
    known: u64,
    rest_present: &TokenStream,
    fused: &[Ident],
) -> PresenceCode {
    let (late, early): (Vec<_>, Vec<_>) =
        parts.pv_sets.iter().partition(|(id, _)| fused.contains(id));
    let pv_sets = early.iter().map(|(_, set)| set);
    let fused_sets = late.iter().map(|(_, set)| set);
    match presence {
        Some(p) => {
            let p = p.ident();
            let name = lit(&format!("{ident}.presence_vector"));
            let check = quote!(#codec::check_presence(u64::from(pv), #known, #is_message, #rest_present, at));
            let on_err = quote!(::core::result::Result::Err(e) => return ::core::result::Result::Err(e.in_field(#name)),);
            let (check, skip) = if is_message {
                (
                    quote!(let undefined = match #check { ::core::result::Result::Ok(v) => v, #on_err };),
                    // Fields of a newer revision, appended under bits this one does
                    // not define: skipped (and never re-emitted).
                    quote!(if undefined {
                        r.rest();
                    }),
                )
            } else {
                (
                    quote!(if let ::core::result::Result::Err(e) = #check {
                        return ::core::result::Result::Err(e.in_field(#name));
                    }),
                    quote!(),
                )
            };
            PresenceCode {
                compute: quote!(let mut pv: #p = 0; #(#pv_sets)*),
                encode: quote!(#(#fused_sets)* #codec::Encode::encode(&pv, w)?;),
                decode: quote! {
                    let at = r.offset();
                    let pv = match <#p as #codec::Decode>::decode(r) {
                        ::core::result::Result::Ok(v) => v,
                        #on_err
                    };
                    #check
                },
                skip,
            }
        }
        None => PresenceCode::default(),
    }
}

/// The code of a presence vector: writing it, reading and checking it, and what ends
/// the decoding of a message body after its known fields.
#[derive(Default)]
pub(in crate::expand) struct PresenceCode {
    /// Computes `pv` from the fields.
    pub(in crate::expand) compute: TokenStream,
    /// Sets the bits of the fused fields, then writes `pv`.
    pub(in crate::expand) encode: TokenStream,
    pub(in crate::expand) decode: TokenStream,
    pub(in crate::expand) skip: TokenStream,
}
