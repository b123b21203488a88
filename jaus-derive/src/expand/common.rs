//! What the derives share: string literals, the wire integer of a container
//! attribute, and the impls emitted after attribute errors.

use crate::attr::{Errors, Int, IntSpan};
use proc_macro2::{Span, TokenStream};
use quote::quote;
use syn::{DeriveInput, Ident, LitStr};

/// A string literal of `s` (field paths, variable names).
pub(super) fn lit(s: &str) -> LitStr {
    LitStr::new(s, Span::call_site())
}

/// The wire integer named by a container attribute (`repr`, `tag`) of type `ident`,
/// or `None` after reporting `wrong` (not unsigned, or `u64` unless `u64_ok`) or
/// `missing` (at the type's name).
pub(super) fn wire_int(
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
pub(super) fn fallback(
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
