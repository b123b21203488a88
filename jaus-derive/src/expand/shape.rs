//! The wire shape of one field: how its bytes are laid out, what its length depends on.

use crate::attr::Int;
use syn::Type;

/// How the length of a string or byte run is known on the wire.
#[derive(Clone, Copy)]
pub(super) enum Len {
    Fixed(usize),
    Size(Int),
    Rest,
    /// Up to and including a NUL byte.
    Nul,
}

/// The element of a list.
#[allow(clippy::large_enum_variant)] // built once per field at compile time
pub(super) enum Elem {
    Plain(Type),
    Scaled(ScaledSpec),
}

/// A real value carried as integer `int` scaled over `lo..=hi`.
#[derive(Clone)]
pub(super) struct ScaledSpec {
    pub(super) int: Int,
    pub(super) lo: f64,
    pub(super) hi: f64,
    /// Unit of the real value (empty if none), for error messages.
    pub(super) unit: String,
}

/// The wire form of one field.
pub(super) enum Shape {
    Plain(Type),
    Scaled(ScaledSpec),
    List {
        count: Option<Int>,
        elem: Elem,
    },
    Bytes(Len),
    Str {
        len: Len,
        nul: bool,
        accept_short: bool,
    },
    /// A list whose count is the value of an earlier field (`count_var`).
    ListVar {
        var: String,
        /// `count_var = "n - 1"`: the count is the variable minus this.
        minus: u64,
        elem: Elem,
    },
    /// A presence-vector bit with no bytes of its own (`flag = N` on a `bool`).
    Flag(u32),
    /// A union whose tag is the value of an earlier field (`tag_var`).
    TagVar {
        ty: Type,
        var: String,
    },
    Sized {
        size: Int,
        ty: Type,
    },
}

impl Shape {
    /// Whether the field takes every byte left in the body (`rest`).
    pub(super) fn runs_to_end(&self) -> bool {
        matches!(
            self,
            Shape::Bytes(Len::Rest)
                | Shape::Str { len: Len::Rest, .. }
                | Shape::List { count: None, .. }
        )
    }
}
