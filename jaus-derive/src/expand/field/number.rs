//! Numbers: plain values (integers, floats, any codec type) and scaled integers that
//! carry a real value.

use super::ValueCode;
use crate::expand::model::ScaledSpec;
use proc_macro2::{Ident, TokenStream};
use quote::quote;
use syn::{LitStr, Type};

/// A value written by its own codec, little-endian for numbers.
pub(super) fn plain(ty: &Type, v: &TokenStream, codec: &TokenStream) -> ValueCode {
    ValueCode {
        len: quote!(#codec::Encode::encoded_len(#v)),
        encode: quote!(#codec::Encode::encode(#v, w)?;),
        decode: quote!(<#ty as #codec::Decode>::decode(r)),
        min_len: quote!(<#ty as #codec::Decode>::MIN_LEN),
    }
}

/// An `f64` carried as a scaled integer.
pub(super) fn scaled(
    s: &ScaledSpec,
    v: &TokenStream,
    path: &LitStr,
    codec: &TokenStream,
) -> ValueCode {
    let (t, lo, hi) = scaled_args(s);
    let n = s.int.bytes();
    ValueCode {
        len: quote!(#n),
        encode: encode_scaled(s, &quote!(*#v), path, codec),
        decode: quote!(<#t as #codec::Decode>::decode(r).map(|n| #codec::scale_from::<#t>(n, #lo, #hi))),
        min_len: quote!(#n),
    }
}

/// The integer type and limits of a scaled value.
fn scaled_args(s: &ScaledSpec) -> (Ident, f64, f64) {
    (s.int.ident(), s.lo, s.hi)
}

/// Writes the real `value` (an `f64` expression) as its scaled integer; a value beyond
/// the limits is an error naming the field (`path`), the limits and the unit.
pub(super) fn encode_scaled(
    s: &ScaledSpec,
    value: &TokenStream,
    path: &LitStr,
    codec: &TokenStream,
) -> TokenStream {
    let t = s.int.ident();
    let field = scaled_field(s, path, codec);
    quote!(#codec::Encode::encode(&#codec::scale_to::<#t>(#value, #field)?, w)?;)
}

/// A `&'static ScaledField` of the field `path` with spec `s`: a constant, promoted to
/// a static, so that an encode error can refer to it.
pub(super) fn scaled_field(s: &ScaledSpec, path: &LitStr, codec: &TokenStream) -> TokenStream {
    let (_, lo, hi) = scaled_args(s);
    let unit = &s.unit;
    quote!(&#codec::ScaledField { field: #path, lo: #lo, hi: #hi, unit: #unit })
}

/// Clamps the real value behind `v` (a `&mut f64`) to the limits.
pub(super) fn clamp_scaled(s: &ScaledSpec, v: &TokenStream, codec: &TokenStream) -> TokenStream {
    let (_, lo, hi) = scaled_args(s);
    quote!(*#v = #codec::clamp_scaled(*#v, #lo, #hi);)
}

/// Reads a scaled integer and gives its real value (an `f64` expression; `?` on errors).
pub(super) fn read_scaled(s: &ScaledSpec, codec: &TokenStream) -> TokenStream {
    let (t, lo, hi) = scaled_args(s);
    quote!(#codec::scale_from::<#t>(<#t as #codec::Decode>::decode(r)?, #lo, #hi))
}
