//! The validated set: every message, type and field with its resolved form (wire forms,
//! representations, bit-field members, union variants), and what it says about itself
//! (a query's report, the fields others depend on).

use crate::count::CountRef;
use crate::location::Pos;
use crate::model::{
    BitDef, ComponentDef, FieldDef, MessageClass, MessageDef, PartDef, ServiceDef, TypeDef,
    TypeKind, VariantDef,
};
use crate::source::{Source, SpecError};
use std::collections::BTreeSet;
use std::path::Path;

/// A validated message: its definition as written, where it came from, and its body
/// resolved.
#[derive(Debug, Clone)]
pub struct Message {
    /// The definition as written (`def.fields` are the raw field definitions; read
    /// [`Message::fields`] for their resolved form).
    pub def: MessageDef,
    /// Group name.
    pub group: String,
    /// Index into [`Spec::sources`].
    pub source: usize,
    /// YAML path of the definition (`messages[3]`).
    pub path: String,
    /// Presence vector type, if the message has one.
    pub presence: Option<Int>,
    /// The body's fields in wire order, each with its wire form.
    pub fields: Vec<Field>,
}

/// A validated named type: its definition as written, where it came from, and its
/// resolved form.
#[derive(Debug, Clone)]
pub struct Type {
    /// The definition as written (read [`Type::form`] for the resolved fields,
    /// representation, members and variants).
    pub def: TypeDef,
    /// Group name.
    pub group: String,
    /// Index into [`Spec::sources`].
    pub source: usize,
    /// YAML path of the definition (`types[1]`).
    pub path: String,
    /// What the type is, resolved per kind.
    pub form: TypeForm,
}

impl Type {
    /// The fields of a record, in wire order; none for the other kinds.
    pub fn fields(&self) -> &[Field] {
        match &self.form {
            TypeForm::Record { fields, .. } => fields,
            _ => &[],
        }
    }
}

/// A field of a message or record with its wire form, resolved once by validation.
#[derive(Debug, Clone)]
pub struct Field {
    /// The definition as written (name, description, unit, presence bit, dependencies).
    pub def: FieldDef,
    /// How the field is carried on the wire.
    pub wire: Wire,
}

/// The resolved form of a named type, by kind.
#[derive(Debug, Clone)]
pub enum TypeForm {
    /// A sequence of fields.
    Record {
        /// Presence vector type, if the record has one.
        presence: Option<Int>,
        /// The fields in wire order.
        fields: Vec<Field>,
    },
    /// Named integer values (in the definition's `values`).
    Enum {
        /// Integer type of the values.
        repr: Int,
    },
    /// Named bits of an integer.
    Bitfield {
        /// The integer type.
        repr: Int,
        /// The members, in definition order.
        members: Vec<Member>,
    },
    /// A tag followed by the value of the variant it names.
    Union {
        /// Integer type of the tag.
        repr: Int,
        /// The variants, in definition order.
        variants: Vec<Variant>,
    },
}

/// A member of a bit field with its bits resolved.
#[derive(Debug, Clone)]
pub struct Member {
    /// The definition as written.
    pub def: BitDef,
    /// Where it lies.
    pub bits: Bits,
}

/// The bits of a bit-field member.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bits {
    /// One bit (`bit: N`): a flag.
    Flag(u32),
    /// An inclusive range of bits (`bits: [lo, hi]`) holding an unsigned value.
    Range {
        /// Lowest bit.
        lo: u32,
        /// Highest bit.
        hi: u32,
    },
}

/// A union variant with the wire form of its value resolved.
#[derive(Debug, Clone)]
pub struct Variant {
    /// The definition as written.
    pub def: VariantDef,
    /// The value that follows the tag; `None` for a tag-only variant.
    pub wire: Option<Wire>,
}

/// A component with the file it came from.
#[derive(Debug, Clone)]
pub struct Component {
    /// The definition.
    pub def: ComponentDef,
    /// Group name.
    pub group: String,
    /// Index into [`Spec::sources`].
    pub source: usize,
    /// YAML path of the definition.
    pub path: String,
}

/// A shared part of component interfaces with the file it came from.
#[derive(Debug, Clone)]
pub struct Part {
    /// The definition.
    pub def: PartDef,
    /// Group name.
    pub group: String,
    /// Index into [`Spec::sources`].
    pub source: usize,
    /// YAML path of the definition (`parts[0]`).
    pub path: String,
}

/// A service with the file it came from.
#[derive(Debug, Clone)]
pub struct Service {
    /// The definition.
    pub def: ServiceDef,
    /// Group name.
    pub group: String,
    /// Index into [`Spec::sources`].
    pub source: usize,
    /// YAML path of the definition (`services[0]`).
    pub path: String,
}

/// A message group, merged over every file that names it.
#[derive(Debug, Clone)]
pub struct Group {
    /// Group identifier.
    pub name: String,
    /// Title.
    pub title: String,
    /// Description.
    pub description: Option<String>,
}

/// A validated set of definitions: every name resolves, and every field carries its
/// resolved wire form ([`Field::wire`]).
#[derive(Debug)]
pub struct Spec {
    /// Every file read, in load order: first the base definitions an overlay extends
    /// (the SDK's, see [`load_overlays`](crate::load_overlays)), then the overlay's own.
    pub sources: Vec<Source>,
    /// How many of the first [`Spec::sources`] are base definitions (0 when the set
    /// extends nothing): their items exist in the SDK already and are not generated
    /// again.
    pub base_sources: usize,
    /// What is legal but probably a mistake (an overlay's message outside the
    /// experimental code range), with file:line.
    pub warnings: Vec<SpecError>,
    /// Groups in first-seen order.
    pub groups: Vec<Group>,
    /// Named types in file order.
    pub types: Vec<Type>,
    /// Messages in file order.
    pub messages: Vec<Message>,
    /// Components in file order.
    pub components: Vec<Component>,
    /// Parts shared by components, in file order.
    pub parts: Vec<Part>,
    /// Services, in file order.
    pub services: Vec<Service>,
}

/// Integer wire types.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Int {
    /// JAUS Byte.
    U8,
    /// JAUS Unsigned Short Integer.
    U16,
    /// JAUS Unsigned Integer.
    U32,
    /// JAUS Unsigned Long Integer.
    U64,
    /// A signed byte (AS-4's JSIDL `byte`; RA 3.3 has none).
    I8,
    /// JAUS Short Integer.
    I16,
    /// JAUS Integer.
    I32,
    /// JAUS Long Integer.
    I64,
}

impl Int {
    /// Parses a Rust-style or JAUS name of an integer type.
    pub fn parse(s: &str) -> Option<Int> {
        Some(match s {
            "u8" | "byte" => Int::U8,
            "u16" | "unsigned short" | "ushort" => Int::U16,
            "u32" | "unsigned integer" | "uint" => Int::U32,
            "u64" | "unsigned long" | "ulong" => Int::U64,
            "i8" | "signed byte" => Int::I8,
            "i16" | "short" => Int::I16,
            "i32" | "integer" | "int" => Int::I32,
            "i64" | "long" => Int::I64,
            _ => return None,
        })
    }
    /// Rust type name.
    pub fn rust(self) -> &'static str {
        match self {
            Int::U8 => "u8",
            Int::U16 => "u16",
            Int::U32 => "u32",
            Int::U64 => "u64",
            Int::I8 => "i8",
            Int::I16 => "i16",
            Int::I32 => "i32",
            Int::I64 => "i64",
        }
    }
    /// Size in bytes.
    pub fn bytes(self) -> usize {
        match self {
            Int::U8 | Int::I8 => 1,
            Int::U16 | Int::I16 => 2,
            Int::U32 | Int::I32 => 4,
            Int::U64 | Int::I64 => 8,
        }
    }
    /// True for the unsigned types.
    pub fn unsigned(self) -> bool {
        matches!(self, Int::U8 | Int::U16 | Int::U32 | Int::U64)
    }
    /// Divisor `D` of a scaled value carried in this type: `scale = (hi - lo) / D`
    /// (those of OpenJAUS 3.3, which the reference vectors follow; see the README).
    pub fn divisor(self) -> f64 {
        match self {
            Int::U8 => 255.0,
            Int::U16 => 65_535.0,
            Int::U32 | Int::I32 => 4_294_967_294.0,
            Int::I8 => 254.0,
            Int::I16 => 65_534.0,
            Int::U64 => 18_446_744_073_709_551_615.0,
            Int::I64 => 18_446_744_073_709_551_614.0,
        }
    }

    /// True for types usable as a count, size or presence vector (u8, u16, u32).
    pub fn is_count(self) -> bool {
        matches!(self, Int::U8 | Int::U16 | Int::U32)
    }
}

/// How long a string or blob is on the wire.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Len {
    /// Exactly `n` bytes, NUL padded.
    Fixed {
        /// Byte count.
        n: usize,
        /// Shorter is accepted on receive (final field only).
        accept_short: bool,
    },
    /// A length prefix of this type.
    Prefix(Int),
    /// To the end of the body.
    Rest {
        /// A NUL terminator is written (strings).
        nul: bool,
    },
    /// Up to and including a NUL byte (C string).
    Nul,
}

/// A field's wire form, resolved.
#[derive(Debug, Clone, PartialEq)]
pub enum Wire {
    /// A plain integer.
    Int(Int),
    /// IEEE-754 single.
    F32,
    /// IEEE-754 double.
    F64,
    /// A real value carried as a scaled integer.
    Scaled {
        /// The integer type.
        int: Int,
        /// Lower limit.
        lo: f64,
        /// Upper limit.
        hi: f64,
    },
    /// A named type, optionally wrapped in a byte-size prefix.
    Named {
        /// The type name.
        name: String,
        /// Its kind.
        kind: TypeKind,
        /// Size prefix type.
        size: Option<Int>,
        /// For a union: the earlier field holding its tag (not sent with the value).
        tag_field: Option<String>,
    },
    /// 8-bit text.
    Str(Len),
    /// Opaque bytes.
    Bytes(Len),
    /// A list; `count: None` runs to the end of the body.
    List {
        /// Count prefix type.
        count: Option<Int>,
        /// Element form.
        elem: Box<Wire>,
    },
    /// A list whose count is the value of an earlier field.
    ListField {
        /// The field holding the count, and the constant subtracted from its value
        /// (`count_field: num_joints - 1`), parsed once by validation.
        field: CountRef,
        /// Element form.
        elem: Box<Wire>,
        /// The list holds byte offsets of the elements of this other list.
        offsets_of: Option<String>,
    },
    /// A presence-vector bit with no bytes (a `bool` in Rust).
    Flag,
    /// A whole embedded JAUS message with its 16-byte header.
    Packet {
        /// Size prefix type.
        size: Option<Int>,
    },
}

impl Spec {
    /// The message named `name`.
    pub fn message(&self, name: &str) -> Option<&Message> {
        self.messages.iter().find(|m| m.def.name == name)
    }

    /// The service named `name`.
    pub fn service(&self, name: &str) -> Option<&Service> {
        self.services.iter().find(|s| s.def.name == name)
    }

    /// The shared part named `name`.
    pub fn part(&self, name: &str) -> Option<&Part> {
        self.parts.iter().find(|p| p.def.name == name)
    }

    /// The message with command code `code`.
    pub fn message_by_code(&self, code: u16) -> Option<&Message> {
        self.messages.iter().find(|m| m.def.code.0 == code)
    }

    /// The named type `name`.
    pub fn ty(&self, name: &str) -> Option<&Type> {
        self.types.iter().find(|t| t.def.name == name)
    }

    /// The report answering a query message, by the complement rule (report = query +
    /// 0x2000) or the query's explicit `report:`; `None` for non-queries and for
    /// queries marked `no_report`.
    pub fn report_of(&self, query: &MessageDef) -> Option<&Message> {
        report_of(query, |n| self.message(n), |c| self.message_by_code(c))
    }

    /// The file and the `line:column` of a YAML path in source `source` (an index
    /// into [`Spec::sources`]): `messages[3]` (a message: the position of its first
    /// key), `messages[3].fields[2]` (a field), `types[1].values[0]` (an enum value),
    /// `components[0].accepts[4]` (an entry of a component's list). Every item of the
    /// model carries its `source` and `path`; a field's path is its owner's path plus
    /// `.fields[i]`, `i` its index in the resolved field list. A path that is not in
    /// the file gives the position of its nearest ancestor.
    pub fn locate(&self, source: usize, path: &str) -> (&Path, Pos) {
        let s = &self.sources[source];
        (s.path.as_path(), s.index.find(path))
    }

    /// True when the set is an overlay on base definitions ([`load_overlays`](crate::load_overlays)).
    pub fn extends(&self) -> bool {
        self.base_sources > 0
    }

    /// True when the item from source `source` is the overlay's own (not a base
    /// definition).
    pub fn is_own(&self, source: usize) -> bool {
        source >= self.base_sources
    }

    /// Every source file path (for `cargo:rerun-if-changed`).
    pub fn source_paths(&self) -> impl Iterator<Item = &Path> {
        self.sources.iter().map(|s| s.path.as_path())
    }

    /// Names of the fields other fields depend on anywhere in the set: the field a
    /// list's count is kept in (`count_field`, [`Wire::ListField`]), the field an
    /// optional field is present by (`present_if`) and the field holding a union's tag
    /// (`tag_field`), in list elements too. Such fields publish their value while
    /// encoding and decoding (`var` in the derive), in the generated types and in
    /// `jaus-dynamic` alike.
    pub fn vars(&self) -> BTreeSet<String> {
        fn counts(w: &Wire, out: &mut BTreeSet<String>) {
            match w {
                Wire::ListField { field, elem, .. } => {
                    out.insert(field.field.clone());
                    counts(elem, out);
                }
                Wire::List { elem, .. } => counts(elem, out),
                _ => {}
            }
        }
        fn others(f: &FieldDef, out: &mut BTreeSet<String>) {
            out.extend(f.present_if.iter().cloned());
            out.extend(f.tag_field.iter().cloned());
            if let Some(e) = &f.of {
                others(&e.0, out);
            }
        }
        let mut out = BTreeSet::new();
        let bodies = self
            .messages
            .iter()
            .map(|m| m.fields.as_slice())
            .chain(self.types.iter().map(|t| t.fields()));
        for f in bodies.flatten() {
            counts(&f.wire, &mut out);
            others(&f.def, &mut out);
        }
        out
    }
}

/// The report of `query` found by name (its `report:`) or by code (the complement rule).
pub(crate) fn report_of<'a, M>(
    query: &MessageDef,
    by_name: impl FnOnce(&str) -> Option<&'a M>,
    by_code: impl FnOnce(u16) -> Option<&'a M>,
) -> Option<&'a M> {
    if !query.is_query() || query.no_report {
        return None;
    }
    match &query.report {
        Some(name) => by_name(name),
        // The complement rule holds for the standard query range only.
        None => MessageClass::report_code(query.code.0).and_then(by_code),
    }
}

/// Splits `PascalCase` into words: `ReportGlobalPose` → `Report Global Pose`.
pub fn title_of(name: &str) -> String {
    let mut out = String::new();
    let chars: Vec<char> = name.chars().collect();
    for (i, &c) in chars.iter().enumerate() {
        let boundary = i > 0
            && c.is_uppercase()
            && (chars[i - 1].is_lowercase() || chars.get(i + 1).is_some_and(|n| n.is_lowercase()));
        if boundary {
            out.push(' ');
        }
        out.push(c);
    }
    out
}
