//! `#[derive(JausBits)]`: named bits and bit ranges of one unsigned integer, the
//! undefined bits kept in a `reserved` member.

use super::common::{fallback, lit, wire_int};
use super::types::type_name;
use crate::attr::{crate_path, parse_container_attrs, parse_field_attrs, span_of, Errors, Int};
use proc_macro2::TokenStream;
use quote::quote;
use syn::{Data, DeriveInput, Ident};

/// Expands `JausBits`.
pub fn bits(input: &DeriveInput) -> TokenStream {
    let mut errors = Errors::default();
    let c = parse_container_attrs(&input.attrs, &mut errors, &["repr", "crate"]);
    let k = crate_path(&c);
    let codec = quote!(#k::codec);
    let ident = &input.ident;
    let repr = wire_int(
        c.repr.as_ref(),
        true,
        ident,
        "a bit field's repr is an unsigned integer: u8, u16, u32 or u64",
        "missing `#[jaus(repr = u8|u16|u32)]`: the integer that holds the bits",
        &mut errors,
    );
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
        return fallback(input, &k, &e, false);
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
