//! Derive macros implementing the JAUS RA 3.3 wire codec.
//!
//! This crate is the only place where wire layout rules live. Each derive parses its
//! `#[jaus(...)]` attributes, validates them (reporting every problem at once, with the
//! span of the offending attribute or field), and expands to implementations of
//! `jaus::codec::Encode` and `jaus::codec::Decode` (plus `jaus::JausMessage` for
//! messages). On an attribute error a minimal impl is still emitted so that users see
//! the real error and not a cascade of "trait not implemented" errors.
//!
//! | derive | for | container attributes |
//! |---|---|---|
//! | `JausMessage` | a struct that is a whole message body | `code = 0x....` (required), `presence = u8\|u16\|u32`, `name = "Title"`, `crate = "path"` |
//! | `JausRecord` | a struct nested in messages (list element, shared type) | `presence = ...`, `crate = ...` |
//! | `JausEnum` | an enum of named values (`Name = 3` or `#[jaus(value = 3)] Name`) | `repr = u8\|u16\|u32`; optional `#[jaus(unknown)] Unknown(T)` variant preserving undefined values |
//! | `JausBits` | a struct of named bits of one integer | `repr = ...`; fields `#[jaus(bit = N)] bool`, `#[jaus(bits = A..=B)] uN`, `#[jaus(reserved)] uN` |
//! | `JausUnion` | an enum whose variant is chosen by a leading tag | `tag = u8\|u16\|u32`; variants `#[jaus(tag = N)] Name(T)` or unit |
//!
//! Field attributes of messages and records:
//!
//! | attribute | applies to | wire form |
//! |---|---|---|
//! | (none) | integers, `f32`, `f64`, any `Encode + Decode` type | the value, little-endian |
//! | `bit = N` | `Option<T>` | present iff bit N of the presence vector is set; the presence vector is computed on encode, never stored |
//! | `scaled(T, lo, hi)` | `f64`, `Vec<f64>` | integer `T` with `value = n * (hi - lo) / D + bias`; a value beyond the limits is an encode error (`jaus::codec::scale_to`) |
//! | `unit = "deg"` | a `scaled` field | the unit named in its out-of-range errors |
//! | `count = T` | `Vec<E>` | element count as unsigned `T`, then the elements |
//! | `size = T` | `String`, `Vec<u8>`, any codec type | byte length as unsigned `T`, then the bytes |
//! | `fixed = N` | `String`, `Vec<u8>` | exactly N bytes, NUL padded; with `accept_short` a shorter final field is accepted on decode |
//! | `rest` | `String`, `Vec<u8>`, `Vec<E>` (last field) | everything to the end of the body; `nul` adds a terminating NUL to a string |
//! | `nul_terminated` | `String` | the text and a NUL byte |
//! | `var = "name"` | unsigned integer or `bool` | publishes the value for later (possibly nested) fields; a count of a sibling `count_var` list is computed from it on encode |
//! | `count_var = "name"` / `"name - N"` | `Vec<E>` | no prefix: the count is the value of the earlier field `name` (minus `N`); checked on encode |
//! | `flag = N` | `bool` | presence bit `N` with no bytes of its own |
//! | `present_if = "name"` | `Option<T>` | present exactly when the earlier field `name` is non-zero; checked on encode |
//! | `offsets = "list"` | `Vec<u32>` with `count_var` | byte offsets of the elements of `list` from the start of the body: computed on encode when empty, written as given with one per element |
//! | `tag_var = "name"` | a `JausUnion` type | the value without its tag; the tag is the earlier field `name`, checked on encode |
//!
//! `JausMessage`, `JausRecord` and `JausUnion` also implement
//! `Encode::clamp_to_range`, which clamps every scaled field to its limits, through
//! nested records, lists, optional fields and union variants.
//!
//! Fields are encoded in the order they are declared, whatever their presence bits. A
//! newer revision of a message appends optional fields under bits above every bit the
//! older one defines, so a `JausMessage` decoder that finds set bits it does not define
//! decodes the fields it knows and skips the rest of the body; they are never
//! re-emitted. Where that cannot be done safely (an undefined bit in a `JausRecord`, whose
//! end is then unknown; one below a defined bit; one with a present `rest` field) the
//! decoder returns `DecodeErrorKind::UndefinedPresenceBit` (see
//! `jaus::codec::check_presence`).

mod attr;
mod expand;

use proc_macro::TokenStream;
use syn::{parse_macro_input, DeriveInput};

/// Implements the wire codec and `jaus::JausMessage` for a message body struct.
#[proc_macro_derive(JausMessage, attributes(jaus))]
pub fn derive_message(input: TokenStream) -> TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    expand::message(&input, true).into()
}

/// Implements the wire codec for a record nested in messages.
#[proc_macro_derive(JausRecord, attributes(jaus))]
pub fn derive_record(input: TokenStream) -> TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    expand::message(&input, false).into()
}

/// Implements the wire codec for an enumeration of named integer values.
#[proc_macro_derive(JausEnum, attributes(jaus))]
pub fn derive_enum(input: TokenStream) -> TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    expand::enumeration(&input).into()
}

/// Implements the wire codec for a bit field: named bits of one integer.
#[proc_macro_derive(JausBits, attributes(jaus))]
pub fn derive_bits(input: TokenStream) -> TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    expand::bits(&input).into()
}

/// Implements the wire codec for a tagged union: a tag followed by the variant's value.
#[proc_macro_derive(JausUnion, attributes(jaus))]
pub fn derive_union(input: TokenStream) -> TokenStream {
    let input = parse_macro_input!(input as DeriveInput);
    expand::union(&input).into()
}
