//! `#[derive(JausEnum)]`: an enumeration of named values of one unsigned integer,
//! optionally keeping undefined values in an `unknown` variant.

use super::common::{fallback, wire_int};
use super::types::is_int_type;
use crate::attr::{crate_path, for_each_item, parse_container_attrs, skip_item, Errors, Int};
use proc_macro2::TokenStream;
use quote::quote;
use syn::{Data, DeriveInput, Fields, Ident};

/// Expands `JausEnum`.
pub fn enumeration(input: &DeriveInput) -> TokenStream {
    let mut errors = Errors::default();
    let c = parse_container_attrs(&input.attrs, &mut errors, &["repr", "crate"]);
    let k = crate_path(&c);
    let codec = quote!(#k::codec);
    let ident = &input.ident;
    let repr = wire_int(
        c.repr.as_ref(),
        true,
        ident,
        "an enumeration's repr is an unsigned integer: u8, u16, u32 or u64",
        "missing `#[jaus(repr = u8|u16|u32)]`: the wire type of the enumeration",
        &mut errors,
    );
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
                        skip_item(input)?;
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
        return fallback(input, &k, &e, false);
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
