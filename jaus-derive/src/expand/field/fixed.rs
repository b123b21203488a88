//! Runs of fixed-size fields written through one bounds check: the presence vector and
//! the consecutive numbers and scaled values after it (optional or not) are written
//! into a chunk of the writer's buffer as long as their largest encoding, at offsets the
//! derive knows (constants until the first optional field). When fewer bytes are left
//! the run is written field by field, as every other field is, so that the error names
//! the field that does not fit.

use super::number::scaled_field;
use crate::attr::Int;
use crate::expand::model::{FieldModel, Shape};
use crate::expand::types::{is_int_type, type_name};
use proc_macro2::{Ident, TokenStream};
use quote::quote;

/// A field (or the presence vector) as a member of a run.
pub(in crate::expand) struct Slot {
    /// Bytes on the wire when present.
    size: usize,
    /// `self.<field>`, or `None` for the presence vector.
    field: Option<TokenStream>,
    /// Written only when `Some`.
    optional: bool,
    /// The bytes (`[u8; size]`) of the value bound to `v` (a reference); `?` on errors.
    bytes: TokenStream,
    /// Sets the field's presence bit in `pv` when it is written (a fused field).
    set: Option<TokenStream>,
    /// The presence vector, written after the fields of its run that set its bits.
    last: bool,
}

impl Slot {
    /// The presence vector, held in `pv` of type `p`.
    pub(in crate::expand) fn presence(p: Int) -> Slot {
        Slot {
            size: p.bytes(),
            field: None,
            optional: false,
            bytes: quote!(pv.to_le_bytes()),
            set: None,
            last: false,
        }
    }
}

/// Field `f` as a member of a run, or `None` when it cannot be one (its size is not
/// known to the derive, or it publishes or reads a variable).
pub(in crate::expand) fn slot(f: &FieldModel, codec: &TokenStream) -> Option<Slot> {
    if f.var.is_some() || f.present_if.is_some() {
        return None;
    }
    let (size, bytes) = match &f.shape {
        Shape::Scaled(s) => {
            let t = s.int.ident();
            let field = scaled_field(s, &f.path, codec);
            (
                s.int.bytes(),
                quote!(#codec::scale_to::<#t>(*v, #field)?.to_le_bytes()),
            )
        }
        Shape::Plain(ty) => {
            let size = match is_int_type(ty) {
                Some(i) => i.bytes(),
                None => match type_name(ty).as_deref() {
                    Some("f32") => 4,
                    Some("f64") => 8,
                    _ => return None,
                },
            };
            (size, quote!(v.to_le_bytes()))
        }
        // No bytes of its own.
        Shape::Flag(_) => (0, quote!()),
        _ => return None,
    };
    let id = &f.ident;
    Some(Slot {
        size,
        field: Some(quote!(self.#id)),
        optional: f.bit.is_some(),
        bytes: if size == 0 { quote!() } else { bytes },
        set: None,
        last: false,
    })
}

/// When the presence vector (`slots[0]`) starts a run, the optional fields of that run
/// set their own bits as they are written and the vector is written last: each is
/// tested once. Returns those fields, whose bits the vector's computation leaves out.
pub(in crate::expand) fn fuse_presence(
    slots: &mut [Option<Slot>],
    fields: &[FieldModel],
    presence: Option<Int>,
) -> Vec<Ident> {
    let Some(p) = presence else {
        return Vec::new();
    };
    let n = slots.iter().skip(1).take_while(|s| s.is_some()).count();
    let run = &mut slots[1..=n];
    if !run.iter().flatten().any(|s| s.size > 0) {
        return Vec::new();
    }
    let p = p.ident();
    let mut fused = Vec::new();
    for (s, f) in run.iter_mut().zip(fields) {
        if let (Some(s), Some(b)) = (s.as_mut(), f.bit) {
            if s.optional {
                s.set = Some(quote!(pv |= (1 as #p) << #b;));
                fused.push(f.ident.clone());
            }
        }
    }
    if let Some(Some(pv)) = slots.first_mut() {
        pv.last = true;
    }
    fused
}

/// The encode statements of a struct: `slow[i]` is the statement of item `i` (the
/// presence vector first if any, then the fields), `slots[i]` that item as a member of
/// a run. Runs of at least two items with bytes are written through one chunk.
pub(in crate::expand) fn encodes(
    slots: Vec<Option<Slot>>,
    slow: Vec<TokenStream>,
    codec: &TokenStream,
) -> Vec<TokenStream> {
    let mut out = Vec::new();
    let mut run: Vec<(Slot, TokenStream)> = Vec::new();
    for (slot, slow) in slots.into_iter().zip(slow) {
        match slot {
            Some(s) => run.push((s, slow)),
            None => {
                flush(&mut run, &mut out, codec);
                out.push(slow);
            }
        }
    }
    flush(&mut run, &mut out, codec);
    out
}

/// Emits the pending run (and empties it).
fn flush(run: &mut Vec<(Slot, TokenStream)>, out: &mut Vec<TokenStream>, codec: &TokenStream) {
    let items = std::mem::take(run);
    if items.iter().filter(|(s, _)| s.size > 0).count() < 2 {
        out.extend(items.into_iter().map(|(_, slow)| slow));
        return;
    }
    let max: usize = items.iter().map(|(s, _)| s.size).sum();
    // Constant offsets up to the first optional field, then a running offset.
    let mut at = 0usize;
    let mut dynamic = false;
    let mut fast = Vec::new();
    let mut last = None;
    for (s, _) in &items {
        if s.size == 0 {
            continue;
        }
        let (bytes, size) = (&s.bytes, s.size);
        if s.last {
            last = Some(quote!(#codec::put_at(c, #at, #bytes);));
            at += size;
            continue;
        }
        let set = &s.set;
        if s.optional && !dynamic {
            fast.push(quote!(let mut o: usize = #at;));
            dynamic = true;
        }
        let put = if dynamic {
            quote!(#codec::put_at(c, o, #bytes); o += #size;)
        } else {
            quote!(#codec::put_at(c, #at, #bytes);)
        };
        at += size;
        fast.push(match (&s.field, s.optional) {
            (Some(field), true) => quote!(if let Some(v) = &#field { #put #set }),
            (Some(field), false) => quote!({ let v = &#field; #put }),
            (None, _) => put,
        });
    }
    let slow = items.iter().map(|(_, slow)| slow);
    let (take, written) = if dynamic {
        (quote!(w.chunk_mut::<#max>()), quote!(w.advance(o);))
    } else {
        (quote!(w.array_mut::<#max>()), quote!())
    };
    out.push(quote! {
        match #take {
            ::core::option::Option::Some(c) => {
                #(#fast)*
                #last
                #written
            }
            ::core::option::Option::None => {
                #(#slow)*
            }
        }
    });
}

/// A record whose fields are all always-present numbers or scaled values: its length
/// and the statements writing it into `c: &mut [u8; len]` (`?` on errors).
pub(in crate::expand) fn whole(
    slots: &[Option<Slot>],
    codec: &TokenStream,
) -> Option<(usize, Vec<TokenStream>)> {
    let mut at = 0usize;
    let mut puts = Vec::new();
    for s in slots {
        let s = s.as_ref()?;
        let field = s.field.as_ref()?;
        if s.optional || s.size == 0 {
            return None;
        }
        let bytes = &s.bytes;
        puts.push(quote!({ let v = &#field; #codec::put_at(c, #at, #bytes); }));
        at += s.size;
    }
    (at > 0).then_some((at, puts))
}
