//! Lists of plain or scaled elements behind a count prefix (`count = T`) or to the end
//! of the body (`rest`), and the per-element code shared with `count_var` lists.

use super::number::{encode_scaled, read_scaled};
use super::ValueCode;
use crate::attr::Int;
use crate::expand::model::Elem;
use proc_macro2::TokenStream;
use quote::quote;
use syn::LitStr;

/// A `Vec<E>` with a count prefix of type `count`, or without one (`rest`).
pub(super) fn list(
    count: Option<Int>,
    elem: &Elem,
    v: &TokenStream,
    path: &LitStr,
    codec: &TokenStream,
) -> ValueCode {
    let c = count.map_or(0, Int::bytes);
    let elems = elems_len(elem, v, codec);
    let prefix = count.map(|c| {
        let c = c.ident();
        quote!(#codec::put_count::<#c>(w, #v.len(), #path)?;)
    });
    let each = encode_elems(elem, v, path, codec);
    ValueCode {
        len: quote!(#c + #elems),
        encode: quote!(#prefix #each),
        decode: decode(count, elem, codec),
        min_len: quote!(#c),
    }
}

fn decode(count: Option<Int>, elem: &Elem, codec: &TokenStream) -> TokenStream {
    let err = quote!(#codec::DecodeError);
    match (count, elem) {
        (Some(c), Elem::Plain(ty)) => {
            let c = c.ident();
            quote!(#codec::decode_list::<#c, #ty>(r))
        }
        (None, Elem::Plain(ty)) => quote!(#codec::decode_rest::<#ty>(r)),
        (count, Elem::Scaled(s)) => {
            let n = s.int.bytes();
            let read = read_scaled(s, codec);
            let head = match count {
                Some(c) => {
                    let c = c.ident();
                    quote!(let n = #codec::get_count::<#c>(r, #n)?;)
                }
                None => quote!(let n = r.remaining() / #n;),
            };
            let tail = if count.is_none() {
                quote!(if r.remaining() != 0 {
                    return Err(#err::new(#codec::DecodeErrorKind::TrailingBytes { count: r.remaining() }, r.offset()));
                })
            } else {
                quote!()
            };
            quote!((|r: &mut #codec::Reader<'_>| -> ::core::result::Result<::std::vec::Vec<f64>, #err> {
                #head
                let mut out = ::std::vec::Vec::with_capacity(n);
                for _ in 0..n {
                    out.push(#read);
                }
                #tail
                Ok(out)
            })(r))
        }
    }
}

/// Bytes of the elements of list `v`, without any count.
pub(super) fn elems_len(elem: &Elem, v: &TokenStream, codec: &TokenStream) -> TokenStream {
    match elem {
        Elem::Plain(_) => quote!(#v.iter().map(#codec::Encode::encoded_len).sum::<usize>()),
        Elem::Scaled(s) => {
            let n = s.int.bytes();
            quote!(#v.len() * #n)
        }
    }
}

/// Writes every element of list `v`. Elements of a type whose encodings all have the
/// same length (`Encode::fixed_len`) are written into one slice when the whole list
/// fits; otherwise, as other elements are, one by one (so that an error names the
/// element that does not fit).
pub(super) fn encode_elems(
    elem: &Elem,
    v: &TokenStream,
    path: &LitStr,
    codec: &TokenStream,
) -> TokenStream {
    let each = encode_elem(elem, path, codec);
    let one_by_one = quote!(for e in #v.iter() { #each });
    match elem {
        Elem::Plain(ty) => quote! {
            let k = <#ty as #codec::Encode>::fixed_len();
            match if k == 0 { None } else { #v.len().checked_mul(k).and_then(|n| w.slice_mut(n)) } {
                ::core::option::Option::Some(dst) => {
                    for (e, d) in #v.iter().zip(dst.chunks_exact_mut(k)) {
                        #codec::Encode::encode_fixed(e, d)?;
                    }
                }
                ::core::option::Option::None => { #one_by_one }
            }
        },
        Elem::Scaled(_) => one_by_one,
    }
}

/// Writes the element `e` (a reference).
pub(super) fn encode_elem(elem: &Elem, path: &LitStr, codec: &TokenStream) -> TokenStream {
    match elem {
        Elem::Plain(_) => quote!(#codec::Encode::encode(e, w)?;),
        Elem::Scaled(s) => encode_scaled(s, &quote!(*e), path, codec),
    }
}
