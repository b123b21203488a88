//! Validation and code generation for each derive, one module per derive.
//!
//! Messages and records go through a model of their fields ([`model`], built by
//! [`classify`]) and the code of each kind of field ([`field`]); enumerations, bit
//! fields and unions are expanded directly. Every derive that found attribute errors
//! emits them through [`fallback`].

mod bits;
mod classify;
mod enumeration;
mod field;
mod message;
mod model;
mod shape;
mod types;
mod union;

pub use bits::bits;
pub use enumeration::enumeration;
pub use message::message;
pub use union::union;

use crate::attr::{Errors, Int, IntSpan};
use proc_macro2::{Span, TokenStream};
use quote::quote;
use syn::{DeriveInput, Ident, LitStr};

/// A string literal of `s` (field paths, variable names).
fn lit(s: &str) -> LitStr {
    LitStr::new(s, Span::call_site())
}

/// The wire integer named by a container attribute (`repr`, `tag`) of type `ident`,
/// or `None` after reporting `wrong` (not unsigned, or `u64` unless `u64_ok`) or
/// `missing` (at the type's name).
fn wire_int(
    attr: Option<&IntSpan>,
    u64_ok: bool,
    ident: &Ident,
    wrong: &str,
    missing: &str,
    errors: &mut Errors,
) -> Option<Int> {
    match attr {
        Some(a) if a.int.unsigned() && (u64_ok || a.int != Int::U64) => Some(a.int),
        Some(a) => {
            errors.error(a.span, wrong);
            None
        }
        None => {
            errors.error(ident.span(), missing);
            None
        }
    }
}

/// What a derive emits after attribute errors: the errors, and impls (of the codec, and
/// of `JausMessage` for a message) whose bodies never run, so that uses of the type
/// report the real error and not a cascade of "trait not implemented" errors.
fn fallback(
    input: &DeriveInput,
    k: &TokenStream,
    error: &syn::Error,
    message: bool,
) -> TokenStream {
    let err = error.to_compile_error();
    let ident = &input.ident;
    let (impl_g, ty_g, where_g) = input.generics.split_for_impl();
    let codec = quote!(#k::codec);
    let msg_impl = message.then(|| {
        quote! {
            impl #impl_g #k::JausMessage for #ident #ty_g #where_g {
                const CODE: #k::CommandCode = #k::CommandCode(0);
                const NAME: &'static str = "";
            }
        }
    });
    quote! {
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
    }
}
