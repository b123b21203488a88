//! The items the templates iterate: groups, types, messages, fields, values, bits,
//! variants, embedded bodies, queries.

use serde::Serialize;

/// One group.
#[derive(Debug, Serialize)]
pub struct GroupCtx {
    /// Identifier.
    pub name: String,
    /// Rust module name (the identifier, except where it would shadow a crate: `core`
    /// becomes `core_messages`).
    pub module: String,
    /// Title.
    pub title: String,
    /// Description lines.
    pub doc: Vec<String>,
    /// `#[cfg(...)]` condition text, if gated.
    pub cfg: Option<String>,
    /// Named types.
    pub types: Vec<TypeCtx>,
    /// Messages.
    pub messages: Vec<MessageCtx>,
}

/// A named type.
#[derive(Debug, Serialize)]
pub struct TypeCtx {
    /// Rust name.
    pub name: String,
    /// `record`, `enum`, `bitfield` or `union`.
    pub kind: String,
    /// Integer type of enum/bitfield/union tag.
    pub repr: String,
    /// Doc lines.
    pub doc: Vec<String>,
    /// `#[jaus(...)]` container attribute contents.
    pub container_attr: String,
    /// Derive `Default`.
    pub default: bool,
    /// Derive `Copy`.
    pub copy: bool,
    /// Record fields.
    pub fields: Vec<FieldCtx>,
    /// Enum values.
    pub values: Vec<ValueCtx>,
    /// Bitfield members.
    pub bits: Vec<BitCtx>,
    /// Union variants.
    pub variants: Vec<VariantCtx>,
}

/// A message.
#[derive(Debug, Clone, Serialize)]
pub struct MessageCtx {
    /// Rust name.
    pub name: String,
    /// Command code as `0x4402`.
    pub code: String,
    /// Title.
    pub title: String,
    /// Group identifier.
    pub group: String,
    /// `#[cfg(...)]` condition, if gated.
    pub cfg: Option<String>,
    /// Doc lines.
    pub doc: Vec<String>,
    /// `#[jaus(...)]` container attribute contents.
    pub container_attr: String,
    /// Derive `Default`.
    pub default: bool,
    /// Fields.
    pub fields: Vec<FieldCtx>,
    /// Accessors decoding embedded message bodies.
    pub embedded: Vec<EmbeddedCtx>,
    /// Report answering this query.
    pub report: Option<String>,
    /// Experimental.
    pub experimental: bool,
    /// Variant of `jaus::wire::MessageClass` (`Command`, `Query`, ...).
    pub class: String,
    /// `access: read`: a command that changes nothing a controller owns.
    pub read_only: bool,
    /// Whether it needs control (`is_command`, else a command by class).
    pub needs_control: bool,
}

/// A struct field.
#[derive(Debug, Clone, Serialize)]
pub struct FieldCtx {
    /// Rust name.
    pub name: String,
    /// Rust type.
    pub ty: String,
    /// `#[jaus(...)]` contents (empty for none).
    pub attr: String,
    /// `serde(...)` contents (empty for none).
    pub serde: String,
    /// Doc lines.
    pub doc: Vec<String>,
}

/// An enum value.
#[derive(Debug, Serialize)]
pub struct ValueCtx {
    /// Variant name.
    pub name: String,
    /// Wire value.
    pub value: u64,
    /// Doc lines.
    pub doc: Vec<String>,
}

/// A bitfield member.
#[derive(Debug, Serialize)]
pub struct BitCtx {
    /// Field name.
    pub name: String,
    /// Rust type.
    pub ty: String,
    /// `#[jaus(...)]` contents.
    pub attr: String,
    /// Doc lines.
    pub doc: Vec<String>,
}

/// A union variant.
#[derive(Debug, Serialize)]
pub struct VariantCtx {
    /// Variant name.
    pub name: String,
    /// Tag.
    pub tag: u64,
    /// Payload type, if any.
    pub ty: Option<String>,
    /// `serde(...)` contents for the payload, if any.
    pub serde: String,
    /// Doc lines.
    pub doc: Vec<String>,
}

/// An embedded message body with its code in another field.
#[derive(Debug, Clone, Serialize)]
pub struct EmbeddedCtx {
    /// The bytes field.
    pub field: String,
    /// The field holding the code.
    pub code_field: String,
    /// The body's code is the complement of that code.
    pub complement: bool,
    /// The field is optional: the accessor returns `None` when it is absent.
    pub optional: bool,
}

/// A query and its report.
#[derive(Debug, Serialize)]
pub struct QueryCtx {
    /// Query name.
    pub query: String,
    /// Report name.
    pub report: String,
    /// Query command code (`0x2402`).
    pub query_code: String,
    /// Report command code.
    pub report_code: String,
    /// Combined cfg.
    pub cfg: Option<String>,
}
