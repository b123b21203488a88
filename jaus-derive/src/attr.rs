//! Parsing of `#[jaus(...)]` attributes into plain data, collecting every error.

use proc_macro2::{Span, TokenStream};
use quote::ToTokens;
use syn::parse::Parse;
use syn::spanned::Spanned;
use syn::{Attribute, Expr, Ident, LitInt, LitStr, Path, Token};

/// Collects errors so that all of them are reported at once.
#[derive(Default)]
pub struct Errors(Option<syn::Error>);

impl Errors {
    pub fn push(&mut self, e: syn::Error) {
        match &mut self.0 {
            Some(all) => all.combine(e),
            None => self.0 = Some(e),
        }
    }
    pub fn error(&mut self, span: Span, msg: impl std::fmt::Display) {
        self.push(syn::Error::new(span, msg));
    }
    pub fn finish(self) -> Result<(), syn::Error> {
        self.0.map_or(Ok(()), Err)
    }
}

/// An integer wire type named in an attribute (`u8`, `i32`, ...).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Int {
    U8,
    U16,
    U32,
    U64,
    I8,
    I16,
    I32,
    I64,
}

impl Int {
    pub fn parse(name: &str) -> Option<Int> {
        Some(match name {
            "u8" => Int::U8,
            "u16" => Int::U16,
            "u32" => Int::U32,
            "u64" => Int::U64,
            "i8" => Int::I8,
            "i16" => Int::I16,
            "i32" => Int::I32,
            "i64" => Int::I64,
            _ => return None,
        })
    }
    pub fn bytes(self) -> usize {
        match self {
            Int::U8 | Int::I8 => 1,
            Int::U16 | Int::I16 => 2,
            Int::U32 | Int::I32 => 4,
            Int::U64 | Int::I64 => 8,
        }
    }
    pub fn bits(self) -> u32 {
        self.bytes() as u32 * 8
    }
    pub fn unsigned(self) -> bool {
        matches!(self, Int::U8 | Int::U16 | Int::U32 | Int::U64)
    }
    pub fn ident(self) -> Ident {
        let s = match self {
            Int::U8 => "u8",
            Int::U16 => "u16",
            Int::U32 => "u32",
            Int::U64 => "u64",
            Int::I8 => "i8",
            Int::I16 => "i16",
            Int::I32 => "i32",
            Int::I64 => "i64",
        };
        Ident::new(s, Span::call_site())
    }
}

/// A type name parsed from an attribute, with its span.
#[derive(Clone, Copy)]
pub struct IntSpan {
    pub int: Int,
    pub span: Span,
}

fn parse_int_type(
    input: syn::parse::ParseStream<'_>,
    errors: &mut Errors,
) -> syn::Result<Option<IntSpan>> {
    let ty: Ident = input.parse()?;
    match Int::parse(&ty.to_string()) {
        Some(int) => Ok(Some(IntSpan {
            int,
            span: ty.span(),
        })),
        None => {
            errors.error(
                ty.span(),
                format!("`{ty}` is not an integer wire type; expected one of u8, u16, u32, u64, i8, i16, i32, i64"),
            );
            Ok(None)
        }
    }
}

/// Evaluates a constant real-number expression: literals, unary minus, `*`, `/`, `+`,
/// `-`, parentheses and the path `PI` / `std::f64::consts::PI`.
pub fn eval_f64(e: &Expr) -> Option<f64> {
    match e {
        Expr::Lit(l) => match &l.lit {
            syn::Lit::Float(f) => f.base10_parse().ok(),
            syn::Lit::Int(i) => i.base10_parse::<i64>().ok().map(|v| v as f64),
            _ => None,
        },
        Expr::Unary(u) if matches!(u.op, syn::UnOp::Neg(_)) => eval_f64(&u.expr).map(|v| -v),
        Expr::Paren(p) => eval_f64(&p.expr),
        Expr::Group(g) => eval_f64(&g.expr),
        Expr::Binary(b) => {
            let (l, r) = (eval_f64(&b.left)?, eval_f64(&b.right)?);
            match b.op {
                syn::BinOp::Add(_) => Some(l + r),
                syn::BinOp::Sub(_) => Some(l - r),
                syn::BinOp::Mul(_) => Some(l * r),
                syn::BinOp::Div(_) => Some(l / r),
                _ => None,
            }
        }
        Expr::Path(p) => {
            let last = p.path.segments.last()?.ident.to_string();
            match last.as_str() {
                "PI" => Some(std::f64::consts::PI),
                "TAU" => Some(std::f64::consts::TAU),
                _ => None,
            }
        }
        _ => None,
    }
}

/// `scaled(T, lo, hi)`
#[derive(Clone)]
pub struct Scaled {
    pub int: IntSpan,
    pub lo: Expr,
    pub hi: Expr,
    pub span: Span,
}

/// Attributes on a struct field of a message or record.
#[derive(Default)]
pub struct FieldAttrs {
    pub bit: Option<(u32, Span)>,
    pub scaled: Option<Scaled>,
    pub count: Option<IntSpan>,
    pub size: Option<IntSpan>,
    pub fixed: Option<(usize, Span)>,
    pub rest: Option<Span>,
    pub nul: Option<Span>,
    pub accept_short: Option<Span>,
    // Bit-field members:
    pub bits: Option<(u32, u32, Span)>,
    pub reserved: Option<Span>,
    /// An attribute did not parse (already reported): skip further checks of the field.
    pub parse_failed: bool,
    // Dependencies between fields:
    pub var: Option<(String, Span)>,
    pub count_var: Option<(String, Span)>,
    pub present_if: Option<(String, Span)>,
    pub flag: Option<(u32, Span)>,
    pub offsets: Option<(String, Span)>,
    pub nul_terminated: Option<Span>,
    pub tag_var: Option<(String, Span)>,
    /// Unit of a scaled value, for error messages.
    pub unit: Option<(String, Span)>,
}

pub const FIELD_KEYS: &str = "bit, scaled(T, lo, hi), unit, count = T, size = T, fixed = N, rest, nul, accept_short, var, count_var, present_if, flag, offsets, nul_terminated, tag_var";
pub const BITS_FIELD_KEYS: &str = "bit = N, bits = A..=B, reserved";

/// Calls `f` on every `key` or `key = ...` / `key(...)` item of every `#[jaus(...)]`.
pub fn for_each_item(
    attrs: &[Attribute],
    errors: &mut Errors,
    mut f: impl FnMut(&Ident, syn::parse::ParseStream<'_>, &mut Errors) -> syn::Result<()>,
) -> bool {
    let mut failed = false;
    for attr in attrs.iter().filter(|a| a.path().is_ident("jaus")) {
        let res = attr.parse_args_with(|input: syn::parse::ParseStream<'_>| {
            loop {
                if input.is_empty() {
                    break;
                }
                let key: Ident = if input.peek(Token![crate]) {
                    let k: Token![crate] = input.parse()?;
                    Ident::new("crate", k.span)
                } else {
                    input.parse()?
                };
                f(&key, input, errors)?;
                if input.is_empty() {
                    break;
                }
                input.parse::<Token![,]>()?;
            }
            Ok(())
        });
        if let Err(e) = res {
            errors.push(e);
            failed = true;
        }
    }
    failed
}

/// Skips the rest of an unknown item (up to the next `,`) so that parsing can continue
/// and report later items too.
pub fn skip_item(input: syn::parse::ParseStream<'_>) -> syn::Result<()> {
    while !input.is_empty() && !input.peek(Token![,]) {
        input.parse::<proc_macro2::TokenTree>()?;
    }
    Ok(())
}

fn parse_eq<T: Parse>(input: syn::parse::ParseStream<'_>) -> syn::Result<T> {
    input.parse::<Token![=]>()?;
    input.parse()
}

fn lit_u32(lit: &LitInt) -> syn::Result<u32> {
    lit.base10_parse()
}

fn set<T>(slot: &mut Option<T>, v: T, key: &Ident, errors: &mut Errors) {
    if slot.is_some() {
        errors.error(key.span(), format!("duplicate `{key}` attribute"));
    }
    *slot = Some(v);
}

pub fn parse_field_attrs(attrs: &[Attribute], errors: &mut Errors, in_bits: bool) -> FieldAttrs {
    let mut out = FieldAttrs::default();
    let failed = for_each_item(attrs, errors, |key, input, errors| {
        let k = key.to_string();
        match k.as_str() {
            "bit" => {
                let lit: LitInt = parse_eq(input)?;
                set(&mut out.bit, (lit_u32(&lit)?, lit.span()), key, errors);
            }
            "bits" if in_bits => {
                input.parse::<Token![=]>()?;
                let lo: LitInt = input.parse()?;
                input.parse::<Token![..=]>()?;
                let hi: LitInt = input.parse()?;
                let span = lo.span().join(hi.span()).unwrap_or(lo.span());
                set(
                    &mut out.bits,
                    (lit_u32(&lo)?, lit_u32(&hi)?, span),
                    key,
                    errors,
                );
            }
            "reserved" if in_bits => set(&mut out.reserved, key.span(), key, errors),
            "scaled" if !in_bits => {
                let content;
                syn::parenthesized!(content in input);
                let int = parse_int_type(&content, errors)?;
                content.parse::<Token![,]>()?;
                let lo: Expr = content.parse()?;
                content.parse::<Token![,]>()?;
                let hi: Expr = content.parse()?;
                if let Some(int) = int {
                    set(
                        &mut out.scaled,
                        Scaled {
                            int,
                            lo,
                            hi,
                            span: key.span(),
                        },
                        key,
                        errors,
                    );
                }
            }
            "count" if !in_bits => {
                input.parse::<Token![=]>()?;
                if let Some(t) = parse_int_type(input, errors)? {
                    set(&mut out.count, t, key, errors);
                }
            }
            "size" if !in_bits => {
                input.parse::<Token![=]>()?;
                if let Some(t) = parse_int_type(input, errors)? {
                    set(&mut out.size, t, key, errors);
                }
            }
            "fixed" if !in_bits => {
                let lit: LitInt = parse_eq(input)?;
                set(
                    &mut out.fixed,
                    (lit.base10_parse()?, lit.span()),
                    key,
                    errors,
                );
            }
            "rest" if !in_bits => set(&mut out.rest, key.span(), key, errors),
            "nul_terminated" if !in_bits => set(&mut out.nul_terminated, key.span(), key, errors),
            "var" | "count_var" | "present_if" | "offsets" | "tag_var" | "unit" if !in_bits => {
                let lit: LitStr = parse_eq(input)?;
                let slot = match k.as_str() {
                    "var" => &mut out.var,
                    "count_var" => &mut out.count_var,
                    "present_if" => &mut out.present_if,
                    "tag_var" => &mut out.tag_var,
                    "unit" => &mut out.unit,
                    _ => &mut out.offsets,
                };
                set(slot, (lit.value(), lit.span()), key, errors);
            }
            "flag" if !in_bits => {
                let lit: LitInt = parse_eq(input)?;
                set(&mut out.flag, (lit_u32(&lit)?, lit.span()), key, errors);
            }
            "nul" if !in_bits => set(&mut out.nul, key.span(), key, errors),
            "accept_short" if !in_bits => set(&mut out.accept_short, key.span(), key, errors),
            _ => {
                errors.error(
                    key.span(),
                    format!(
                        "unknown jaus field attribute `{k}`; expected one of: {}",
                        if in_bits { BITS_FIELD_KEYS } else { FIELD_KEYS }
                    ),
                );
                skip_item(input)?;
            }
        }
        Ok(())
    });
    out.parse_failed = failed;
    out
}

/// Attributes on the container (struct or enum).
#[derive(Default)]
pub struct ContainerAttrs {
    pub code: Option<(u16, Span)>,
    pub presence: Option<IntSpan>,
    pub repr: Option<IntSpan>,
    pub tag: Option<IntSpan>,
    pub krate: Option<Path>,
    pub name: Option<LitStr>,
}

pub fn parse_container_attrs(
    attrs: &[Attribute],
    errors: &mut Errors,
    allowed: &[&str],
) -> ContainerAttrs {
    let mut out = ContainerAttrs::default();
    for_each_item(attrs, errors, |key, input, errors| {
        let k = key.to_string();
        if !allowed.contains(&k.as_str()) {
            errors.error(
                key.span(),
                if k == "code" {
                    format!(
                        "`code` belongs on `#[derive(JausMessage)]`; this derive takes: {}",
                        allowed.join(", ")
                    )
                } else {
                    format!(
                        "unknown jaus container attribute `{k}`; expected one of: {}",
                        allowed.join(", ")
                    )
                },
            );
            skip_item(input)?;
            return Ok(());
        }
        match k.as_str() {
            "code" => {
                let lit: LitInt = parse_eq(input)?;
                match lit.base10_parse::<u16>() {
                    Ok(v) => set(&mut out.code, (v, lit.span()), key, errors),
                    Err(_) => errors.error(
                        lit.span(),
                        "a command code is a 16-bit value (0x0000..=0xFFFF)",
                    ),
                }
            }
            "presence" | "repr" | "tag" => {
                input.parse::<Token![=]>()?;
                if let Some(t) = parse_int_type(input, errors)? {
                    let slot = match k.as_str() {
                        "presence" => &mut out.presence,
                        "repr" => &mut out.repr,
                        _ => &mut out.tag,
                    };
                    set(slot, t, key, errors);
                }
            }
            "crate" => {
                let s: LitStr = parse_eq(input)?;
                set(&mut out.krate, s.parse()?, key, errors);
            }
            "name" => {
                let s: LitStr = parse_eq(input)?;
                set(&mut out.name, s, key, errors);
            }
            _ => unreachable!("checked against `allowed`"),
        }
        Ok(())
    });
    out
}

/// The path of the runtime crate (`::jaus` unless overridden).
pub fn crate_path(c: &ContainerAttrs) -> TokenStream {
    match &c.krate {
        Some(p) => p.to_token_stream(),
        None => quote::quote!(::jaus),
    }
}

/// Span helper for any node.
pub fn span_of<T: Spanned>(t: &T) -> Span {
    t.span()
}
