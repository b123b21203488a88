//! `#[derive(JausUnion)]`: an enum whose variant is chosen by a tag on the wire, read
//! and written with its tag or (for a tag carried by another field) without it.

use super::common::{fallback, lit, wire_int};
use crate::attr::{crate_path, for_each_item, parse_container_attrs, skip_item, Errors};
use proc_macro2::{Span, TokenStream};
use quote::quote;
use syn::{Data, DeriveInput, Fields};

/// Expands `JausUnion`.
pub fn union(input: &DeriveInput) -> TokenStream {
    let mut errors = Errors::default();
    let c = parse_container_attrs(&input.attrs, &mut errors, &["tag", "crate"]);
    let k = crate_path(&c);
    let codec = quote!(#k::codec);
    let ident = &input.ident;
    let tag = wire_int(
        c.tag.as_ref(),
        false,
        ident,
        "a union tag is an unsigned integer: u8, u16 or u32",
        "missing `#[jaus(tag = u8|u16|u32)]`: the wire type of the tag",
        &mut errors,
    );
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
                        skip_item(input)?;
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
        return fallback(input, &k, &e, false);
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
    // Only variants holding a value can hold scaled fields.
    let clamps = variants
        .iter()
        .filter(|(_, _, p)| p.is_some())
        .map(|(v, _, _)| quote!(Self::#v(x) => #codec::Encode::clamp_to_range(x)));
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
            #[allow(unreachable_patterns)]
            fn clamp_to_range(&mut self) {
                match self { #(#clamps,)* _ => {} }
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
