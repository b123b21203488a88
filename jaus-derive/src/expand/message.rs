//! `#[derive(JausMessage)]` and `#[derive(JausRecord)]`: the codec of a struct from the
//! model of its fields, and the command code of a message.

use super::common::{fallback, lit};
use super::field::{self, Parts, Slot};
use super::model::{struct_model, Shape};
use crate::attr::{crate_path, parse_container_attrs, Errors, Int};
use proc_macro2::TokenStream;
use quote::quote;
use syn::{DeriveInput, Ident};

/// Expands `JausMessage` (`is_message`) or `JausRecord`.
pub fn message(input: &DeriveInput, is_message: bool) -> TokenStream {
    let mut errors = Errors::default();
    let allowed: &[&str] = if is_message {
        &["code", "presence", "crate", "name"]
    } else {
        &["presence", "crate"]
    };
    let c = parse_container_attrs(&input.attrs, &mut errors, allowed);
    let k = crate_path(&c);
    if is_message && c.code.is_none() {
        errors.error(
            input.ident.span(),
            "missing `#[jaus(code = 0x....)]`: every message needs its 16-bit command code",
        );
    }
    let model = struct_model(input, &c, &mut errors);
    let ident = &input.ident;
    let (impl_g, ty_g, where_g) = input.generics.split_for_impl();
    let codec = quote!(#k::codec);

    if let Err(e) = errors.finish() {
        return fallback(input, &k, &e, is_message);
    }

    let pv_bytes = model.presence.map_or(0, Int::bytes);
    let names: Vec<&Ident> = model.fields.iter().map(|f| &f.ident).collect();
    let locals: Vec<Ident> = model.fields.iter().map(|f| f.local()).collect();
    let mut parts = Parts::default();
    for f in &model.fields {
        field::add(f, model.presence, &k, &mut parts);
    }
    // Bits the definition defines, and whether a last field that runs to the end of
    // the body is present (fields appended by a newer revision would be taken for it).
    let known = model
        .fields
        .iter()
        .filter_map(|f| match f.shape {
            Shape::Flag(b) => Some(b),
            _ => f.bit,
        })
        .fold(0u64, |m, b| m | 1u64 << b);
    let rest_present = match model.fields.last() {
        Some(f) if f.shape.runs_to_end() => match (f.bit, model.presence) {
            (Some(b), Some(p)) => {
                let p = p.ident();
                quote!(pv & ((1 as #p) << #b) != 0)
            }
            _ => quote!(true),
        },
        _ => quote!(false),
    };
    // The presence vector and then each field, fixed-size runs through one chunk.
    let mut slots: Vec<Option<Slot>> = model
        .presence
        .map(|p| Some(Slot::presence(p)))
        .into_iter()
        .chain(model.fields.iter().map(|f| field::slot(f, &codec)))
        .collect();
    let fused = field::fuse_presence(&mut slots, &model.fields, model.presence);
    // A record of fixed length: lists of it are written through one bounds check.
    let fixed = if is_message || model.presence.is_some() {
        None
    } else {
        field::fixed_whole(&slots, &codec)
    };
    let fixed_fns = fixed.map(|(len, puts)| {
        quote! {
            #[inline(always)]
            fn fixed_len() -> usize {
                #len
            }
            #[inline]
            fn encode_fixed(&self, out: &mut [u8]) -> ::core::result::Result<(), #codec::EncodeError> {
                match out.first_chunk_mut::<#len>() {
                    ::core::option::Option::Some(c) => {
                        #(#puts)*
                        Ok(())
                    }
                    ::core::option::Option::None => self.encode(&mut #codec::Writer::new(out)),
                }
            }
        }
    });
    let pv = field::presence_vector(
        model.presence,
        ident,
        &parts,
        &codec,
        is_message,
        known,
        &rest_present,
        &fused,
    );
    let (pv_compute, pv_decode, pv_skip) = (pv.compute, pv.decode, pv.skip);
    let Parts {
        prelude,
        lens,
        encodes,
        decodes,
        mins,
        clamps,
        ..
    } = parts;
    let slow = model.presence.map(|_| pv.encode).into_iter().chain(encodes);
    let encodes = field::fixed_runs(slots, slow.collect(), &codec);
    let unused_w =
        (model.fields.is_empty() && model.presence.is_none()).then(|| quote!(let _ = w;));
    let encode_body = quote! {
        #unused_w
        #(#prelude)*
        #pv_compute
        #(#encodes)*
        Ok(())
    };
    // A message names itself in an error of a field of a record inside it (the
    // closure is inlined; it only gives the fields' `?` and `return` a place to end).
    let encode_body = if is_message {
        let name = c.name.clone().unwrap_or_else(|| lit(&ident.to_string()));
        quote! {
            match (|| -> ::core::result::Result<(), #codec::EncodeError> { #encode_body })() {
                ::core::result::Result::Err(e) => ::core::result::Result::Err(e.in_message(#name)),
                ok => ok,
            }
        }
    } else {
        encode_body
    };
    // Optional fields by presence bit: what `keep_present` clears.
    let keeps: Vec<TokenStream> = model
        .fields
        .iter()
        .filter_map(|f| {
            let id = &f.ident;
            match (&f.shape, f.bit) {
                (Shape::Flag(b), _) => Some(quote! {
                    if presence_vector & (1u64 << #b) == 0 { self.#id = false; }
                }),
                (_, Some(b)) => Some(quote! {
                    if presence_vector & (1u64 << #b) == 0 { self.#id = ::core::option::Option::None; }
                }),
                _ => None,
            }
        })
        .collect();
    let keep_fn = (!keeps.is_empty()).then(|| {
        quote! {
            #[inline]
            fn keep_present(&mut self, presence_vector: u64) {
                #(#keeps)*
            }
        }
    });
    let clamp_fn = (!clamps.is_empty()).then(|| {
        quote! {
            #[inline]
            fn clamp_to_range(&mut self) {
                #(#clamps)*
            }
        }
    });
    // Records (which may nest, even recursively) count their depth. On an error the
    // reader is abandoned, so only the success path needs to leave.
    let (enter, leave) = if is_message || model.fields.is_empty() {
        (quote!(), quote!())
    } else {
        (quote!(r.enter()?;), quote!(r.leave();))
    };
    let construct = if model.unit {
        quote!(#ident)
    } else {
        quote!(#ident { #(#names: #locals),* })
    };
    let unused_r =
        (model.fields.is_empty() && model.presence.is_none()).then(|| quote!(let _ = r;));
    let msg_impl = is_message.then(|| {
        let code = c.code.map_or(0, |(c, _)| c);
        let name = c.name.clone().unwrap_or_else(|| lit(&ident.to_string()));
        quote! {
            impl #impl_g #k::JausMessage for #ident #ty_g #where_g {
                const CODE: #k::CommandCode = #k::CommandCode(#code);
                const NAME: &'static str = #name;
            }
        }
    });
    quote! {
        // Scaled limits are emitted as literals (e.g. 3.141592653589793), which clippy
        // would flag as approximations of named constants.
        #[allow(clippy::approx_constant)]
        impl #impl_g #codec::Encode for #ident #ty_g #where_g {
            #[inline]
            fn encoded_len(&self) -> usize {
                #pv_bytes #(+ #lens)*
            }
            #[inline]
            #[allow(clippy::redundant_closure_call)]
            fn encode(&self, w: &mut #codec::Writer<'_>) -> ::core::result::Result<(), #codec::EncodeError> {
                #encode_body
            }
            #clamp_fn
            #keep_fn
            #fixed_fns
        }
        #[allow(clippy::approx_constant)]
        impl #impl_g #codec::Decode for #ident #ty_g #where_g {
            const MIN_LEN: usize = #pv_bytes #(+ #mins)*;
            #[inline]
            fn decode(r: &mut #codec::Reader<'_>) -> ::core::result::Result<Self, #codec::DecodeError> {
                #unused_r
                #enter
                #pv_decode
                #(#decodes)*
                #pv_skip
                #leave
                Ok(#construct)
            }
        }
        #msg_impl
    }
}
