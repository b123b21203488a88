//! Runs of bytes: strings, byte blobs and size-prefixed values, with a fixed,
//! prefixed, NUL-terminated or remaining length.

use super::ValueCode;
use crate::attr::Int;
use crate::expand::model::Len;
use proc_macro2::TokenStream;
use quote::quote;
use syn::{LitStr, Type};

/// A `Vec<u8>`.
pub(super) fn bytes(len: Len, v: &TokenStream, path: &LitStr, codec: &TokenStream) -> ValueCode {
    let err = quote!(#codec::DecodeError);
    match len {
        Len::Fixed(n) => ValueCode {
            len: quote!(#n),
            encode: quote!(#codec::put_fixed_bytes(w, #v, #n, #path)?;),
            decode: quote!(r.take(#n).map(|b| b.to_vec())),
            min_len: quote!(#n),
        },
        Len::Size(s) => {
            let (c, n) = (s.ident(), s.bytes());
            ValueCode {
                len: quote!(#n + #v.len()),
                encode: quote!(#codec::put_count::<#c>(w, #v.len(), #path)?; w.put(#v)?;),
                decode: quote!(#codec::get_count::<#c>(r, 1).and_then(|n| r.take(n)).map(|b| b.to_vec())),
                min_len: quote!(#n),
            }
        }
        Len::Rest | Len::Nul => ValueCode {
            len: quote!(#v.len()),
            encode: quote!(w.put(#v)?;),
            decode: quote!(Ok::<_, #err>(r.rest().to_vec())),
            min_len: quote!(0usize),
        },
    }
}

/// A `String`, Latin-1 on the wire; `nul` ends a `rest` string with a NUL byte.
pub(super) fn string(
    len: Len,
    nul: bool,
    accept_short: bool,
    v: &TokenStream,
    path: &LitStr,
    codec: &TokenStream,
) -> ValueCode {
    let err = quote!(#codec::DecodeError);
    match len {
        Len::Nul => ValueCode {
            len: quote!(#codec::latin1_len(#v) + 1),
            encode: quote!(#codec::put_cstring(w, #v, #path)?;),
            decode: quote!(#codec::get_cstring(r)),
            min_len: quote!(1usize),
        },
        Len::Fixed(n) => {
            let min = if accept_short { 0 } else { n };
            ValueCode {
                len: quote!(#n),
                encode: quote!(#codec::put_fixed_string(w, #v, #n, #path)?;),
                decode: quote!(#codec::get_fixed_string(r, #n, #accept_short)),
                min_len: quote!(#min),
            }
        }
        Len::Size(s) => {
            let (c, n) = (s.ident(), s.bytes());
            ValueCode {
                len: quote!(#n + #codec::latin1_len(#v)),
                encode: quote!(#codec::put_count::<#c>(w, #codec::latin1_len(#v), #path)?; #codec::put_latin1(w, #v, #path)?;),
                decode: quote!(#codec::get_count::<#c>(r, 1).and_then(|n| r.take(n)).map(#codec::latin1_to_string)),
                min_len: quote!(#n),
            }
        }
        Len::Rest => {
            let extra = usize::from(nul);
            let term = nul.then(|| quote!(w.put(&[0u8])?;));
            let decode = if nul {
                quote!(Ok::<_, #err>(#codec::get_rest_string(r)))
            } else {
                quote!(Ok::<_, #err>(#codec::latin1_to_string(r.rest())))
            };
            ValueCode {
                len: quote!(#codec::latin1_len(#v) + #extra),
                encode: quote!(#codec::put_latin1(w, #v, #path)?; #term),
                decode,
                min_len: quote!(0usize),
            }
        }
    }
}

/// Any codec value behind its byte length (`size = T`), which must match what the
/// value's decoder consumes.
pub(super) fn sized(
    size: Int,
    ty: &Type,
    v: &TokenStream,
    path: &LitStr,
    codec: &TokenStream,
) -> ValueCode {
    let err = quote!(#codec::DecodeError);
    let (c, n) = (size.ident(), size.bytes());
    ValueCode {
        len: quote!(#n + #codec::Encode::encoded_len(#v)),
        encode: quote!(#codec::put_count::<#c>(w, #codec::Encode::encoded_len(#v), #path)?; #codec::Encode::encode(#v, w)?;),
        decode: quote!((|r: &mut #codec::Reader<'_>| -> ::core::result::Result<#ty, #err> {
            let n = #codec::get_count::<#c>(r, 1)?;
            let mut sub = r.sub(n)?;
            let v = <#ty as #codec::Decode>::decode(&mut sub)?;
            if sub.remaining() != 0 {
                return Err(#err::new(
                    #codec::DecodeErrorKind::SizeMismatch { announced: n, consumed: n - sub.remaining() },
                    sub.offset(),
                ));
            }
            Ok(v)
        })(r)),
        min_len: quote!(#n),
    }
}
