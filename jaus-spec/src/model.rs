//! The typed model of a definition file, as read by `serde_yaml`.

use serde::de::{self, Deserializer};
use serde::Deserialize;
use std::fmt;

mod class;
mod service;
pub use class::MessageClass;
pub use service::*;

/// One YAML definition file: a message group with its shared types, messages and
/// (optionally) component interfaces.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SpecFile {
    /// Group identifier (snake_case); also the cargo feature that selects it.
    pub group: String,
    /// For a vendor's overlay: the definitions it builds on, `jaus` (the SDK's own,
    /// the default) or `none` (a set of its own that names nothing of the SDK's).
    #[serde(default)]
    pub extends: Option<String>,
    /// Human-readable group title.
    #[serde(default)]
    pub title: Option<String>,
    /// What the group is for.
    #[serde(default)]
    pub description: Option<String>,
    /// Shared named types.
    #[serde(default)]
    pub types: Vec<TypeDef>,
    /// Messages.
    #[serde(default)]
    pub messages: Vec<MessageDef>,
    /// Component interfaces.
    #[serde(default)]
    pub components: Vec<ComponentDef>,
    /// Parts that several component interfaces share ([`PartDef`]).
    #[serde(default)]
    pub parts: Vec<PartDef>,
    /// Services with their message sets and protocol behaviour ([`ServiceDef`]).
    #[serde(default)]
    pub services: Vec<ServiceDef>,
}

/// A 16-bit command code, written as an integer or a `"0x...."` string.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Code(pub u16);

impl<'de> Deserialize<'de> for Code {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl de::Visitor<'_> for V {
            type Value = Code;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a 16-bit command code such as 0x4402")
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Code, E> {
                u16::try_from(v)
                    .map(Code)
                    .map_err(|_| E::custom(format!("command code {v} exceeds 0xFFFF")))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Code, E> {
                u16::try_from(v)
                    .map(Code)
                    .map_err(|_| E::custom(format!("command code {v} is not in 0..=0xFFFF")))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Code, E> {
                let t = v.trim();
                let parsed = match t.strip_prefix("0x").or_else(|| t.strip_prefix("0X")) {
                    Some(h) => u16::from_str_radix(h, 16),
                    None => t.parse(),
                };
                parsed
                    .map(Code)
                    .map_err(|_| E::custom(format!("`{v}` is not a 16-bit command code")))
            }
        }
        d.deserialize_any(V)
    }
}

impl fmt::Display for Code {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "0x{:04X}", self.0)
    }
}

/// A message definition.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MessageDef {
    /// PascalCase name, e.g. `ReportGlobalPose`.
    pub name: String,
    /// Command code.
    pub code: Code,
    /// Title as the standard writes it (default: the name split into words).
    #[serde(default)]
    pub title: Option<String>,
    /// What the message means.
    #[serde(default)]
    pub description: Option<String>,
    /// Presence vector type (`u8`, `u16`, `u32`), first in the body, if the message has
    /// optional fields.
    #[serde(default)]
    pub presence: Option<String>,
    /// For a query: the name of its report, where the complement rule (report = query +
    /// 0x2000) does not give it.
    #[serde(default)]
    pub report: Option<String>,
    /// For a query: there is no report (an explicit exception to the complement rule).
    #[serde(default)]
    pub no_report: bool,
    /// For a command: the query whose report reads back what the command sets
    /// (`readback: QueryTravelSpeed`); `jaus conform` checks the value read back.
    #[serde(default)]
    pub readback: Option<String>,
    /// For a command: `access: read` says it changes nothing a controller owns (a
    /// subscription, an event set-up, giving up control), so a node's access policy lets
    /// it through wherever it lets queries through. Commands are writes by default.
    #[serde(default)]
    pub access: Option<Access>,
    /// A vendor/OpenJAUS experimental message.
    #[serde(default)]
    pub experimental: bool,
    /// The message class, for a code whose range does not give one (experimental
    /// codes 0xD000-0xFFFF): an experimental `command` obeys control, an experimental
    /// `query` names its `report:` and is answered like any query.
    #[serde(default)]
    pub class: Option<MessageClass>,
    /// A note about interoperability (deviations of other implementations).
    #[serde(default)]
    pub interop: Option<String>,
    /// Whether the message needs control (AS-4's `is_command`), where that differs
    /// from its class (a Confirm Control in the command range is not one); informational.
    #[serde(default)]
    pub is_command: Option<bool>,
    /// What the component runtime does with this message for every component (the
    /// core service of Report Services); empty for the messages components handle.
    #[serde(default)]
    pub runtime: Vec<RuntimeRole>,
    /// The body's fields, in wire order.
    #[serde(default)]
    pub fields: Vec<FieldDef>,
}

impl MessageDef {
    /// The class of the message: the one its code's range gives, or its explicit
    /// `class:` for an experimental (or reserved) code.
    pub fn class(&self) -> MessageClass {
        match MessageClass::of_code(self.code.0) {
            Some(c) => c,
            None => self.class.unwrap_or(MessageClass::Experimental),
        }
    }

    /// True for a query (by its code's range or its explicit class).
    pub fn is_query(&self) -> bool {
        self.class() == MessageClass::Query
    }
    /// The runtime takes this message for every component (`handles` or `shares`): an
    /// input of the core service in Report Services.
    pub fn runtime_input(&self) -> bool {
        self.runtime
            .iter()
            .any(|r| matches!(r, RuntimeRole::Handles | RuntimeRole::Shares))
    }

    /// The runtime alone handles this message (`handles`): a component interface may
    /// not list it in `commands` or `accepts`.
    pub fn runtime_owned(&self) -> bool {
        self.runtime.contains(&RuntimeRole::Handles)
    }

    /// The runtime sends this message for every component (`emits`): an output of the
    /// core service in Report Services.
    pub fn runtime_output(&self) -> bool {
        self.runtime.contains(&RuntimeRole::Emits)
    }
}

/// What the component runtime does with a message for every component
/// (`runtime: [handles, emits]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RuntimeRole {
    /// The runtime takes it for every component (an input of the core service); a
    /// component interface may not list it in `commands` or `accepts`.
    Handles,
    /// The runtime takes it for every component (an input of the core service), and a
    /// component interface may list it too: the runtime answers what every component
    /// answers (Query Identification of the component itself), the component the rest
    /// (the node manager's identification of its node and subsystem).
    Shares,
    /// The runtime sends it for every component (an output of the core service).
    Emits,
}

impl fmt::Display for RuntimeRole {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            RuntimeRole::Handles => "handles",
            RuntimeRole::Shares => "shares",
            RuntimeRole::Emits => "emits",
        })
    }
}

/// What a command does to its receiver, for access policies (`access:` of a message).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Access {
    /// It changes nothing a controller owns: treated as a query.
    Read,
}

/// A field of a message or record, or a list element.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FieldDef {
    /// snake_case name.
    #[serde(default)]
    pub name: String,
    /// Wire type: a basic type, `string`, `bytes`, `list`, `message` or a named type.
    #[serde(rename = "type")]
    pub ty: String,
    /// What the field means.
    #[serde(default)]
    pub description: Option<String>,
    /// Real-value limits `[lower, upper]` of a scaled integer.
    #[serde(default)]
    pub scale: Option<[f64; 2]>,
    /// Unit of the (real) value, e.g. `m`, `rad`, `deg`, `%`, `m/s`.
    #[serde(default)]
    pub unit: Option<String>,
    /// Presence-vector bit; makes the field optional.
    #[serde(default)]
    pub bit: Option<u32>,
    /// Count prefix type of a list, or length prefix type of a string/bytes/message.
    #[serde(default)]
    pub count: Option<String>,
    /// A list whose element count is the value of this earlier field (of the same
    /// record, or of a record or message that contains it) instead of a prefix.
    #[serde(default)]
    pub count_field: Option<String>,
    /// An optional field present exactly when this earlier field (a `flag`, or a
    /// non-zero integer; of this record or one containing it) is set.
    #[serde(default)]
    pub present_if: Option<String>,
    /// A list of u32 byte offsets (from the start of the body) of the elements of this
    /// later list field; computed on encode, informational on decode.
    #[serde(default)]
    pub offsets_of: Option<String>,
    /// For a union-typed field: the earlier field holding its tag, which is then not
    /// sent with the value (a type code given elsewhere).
    #[serde(default)]
    pub tag_field: Option<String>,
    /// Size prefix (byte length) type for a nested value or embedded message.
    #[serde(default)]
    pub size: Option<String>,
    /// Element type of a list (a type name, or a full field definition).
    #[serde(default)]
    pub of: Option<Box<ElemDef>>,
    /// Fixed length in bytes, or `rest` (to the end of the body).
    #[serde(default)]
    pub length: Option<Length>,
    /// A `rest` string ends with a NUL byte on the wire.
    #[serde(default)]
    pub nul: bool,
    /// A fixed-length final string may be shorter on receive.
    #[serde(default)]
    pub accept_short: bool,
    /// For an embedded message body: the field holding its command code.
    #[serde(default)]
    pub code_field: Option<String>,
    /// With `code_field`: the embedded body's code is the complement (query ↔ report)
    /// of that field's code.
    #[serde(default)]
    pub complement: bool,
    /// `embeds: message`: the bytes are a whole message as AS-4 carries one inside
    /// another (a 16-bit little-endian message ID, then the body), e.g. the report of an
    /// AS-4 Event. Tools (the Wireshark dissector, the reference docs) show the message.
    #[serde(default)]
    pub embeds: Option<Embeds>,
    /// With `embeds`: the bytes hold a message only when this condition on an earlier
    /// field of the same body holds: `FIELD == VALUE`, VALUE a value name of the
    /// field's enumeration or an integer (`format == JausMessage`).
    #[serde(default)]
    pub embeds_if: Option<String>,
}

/// What the bytes of a field with `embeds:` hold.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Embeds {
    /// A 16-bit little-endian message ID followed by the message's body.
    Message,
}

/// The condition of an `embeds_if: FIELD == VALUE`: the field's name and the value as
/// written; `None` when `text` is not of that form.
pub fn embeds_condition(text: &str) -> Option<(&str, &str)> {
    let (field, value) = text.split_once("==")?;
    let (field, value) = (field.trim(), value.trim());
    let word = |s: &str| !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    (word(field) && word(value)).then_some((field, value))
}

/// A list element: a type name, or a field definition without a name.
#[derive(Debug, Clone)]
pub struct ElemDef(pub FieldDef);

impl<'de> Deserialize<'de> for ElemDef {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Name(String),
            Def(Box<FieldDef>),
        }
        Ok(ElemDef(match Raw::deserialize(d)? {
            Raw::Name(ty) => FieldDef {
                ty,
                ..FieldDef::default()
            },
            Raw::Def(f) => *f,
        }))
    }
}

/// `length:` of a string or blob.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Length {
    /// Exactly this many bytes.
    Fixed(usize),
    /// To the end of the body.
    Rest,
    /// Up to and including a NUL byte.
    Nul,
}

impl<'de> Deserialize<'de> for Length {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl de::Visitor<'_> for V {
            type Value = Length;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a byte count or `rest`")
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Length, E> {
                Ok(Length::Fixed(v as usize))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Length, E> {
                usize::try_from(v)
                    .map(Length::Fixed)
                    .map_err(|_| E::custom("a length is not negative"))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Length, E> {
                if v == "rest" {
                    Ok(Length::Rest)
                } else if v == "nul" {
                    Ok(Length::Nul)
                } else {
                    Err(E::custom(format!(
                        "`{v}` is not a length: use a number, `rest` or `nul`"
                    )))
                }
            }
        }
        d.deserialize_any(V)
    }
}

/// A shared named type.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TypeDef {
    /// PascalCase name.
    pub name: String,
    /// `record`, `enum`, `bitfield` or `union`.
    pub kind: TypeKind,
    /// Integer type of an enum's values, a bitfield, or a union's tag.
    #[serde(default)]
    pub repr: Option<String>,
    /// What the type means.
    #[serde(default)]
    pub description: Option<String>,
    /// Presence vector type of a record.
    #[serde(default)]
    pub presence: Option<String>,
    /// Fields of a record.
    #[serde(default)]
    pub fields: Vec<FieldDef>,
    /// Named values of an enum.
    #[serde(default)]
    pub values: Vec<EnumValue>,
    /// Members of a bitfield.
    #[serde(default)]
    pub bits: Vec<BitDef>,
    /// Variants of a union.
    #[serde(default)]
    pub variants: Vec<VariantDef>,
}

/// The kinds of named type.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TypeKind {
    /// A sequence of fields.
    Record,
    /// Named integer values.
    Enum,
    /// Named bits of an integer.
    Bitfield,
    /// A tag followed by the value of the variant it names.
    Union,
}

/// A named enum value.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnumValue {
    /// PascalCase name.
    pub name: String,
    /// Wire value.
    pub value: u64,
    /// Meaning.
    #[serde(default)]
    pub description: Option<String>,
}

/// A member of a bitfield: one bit (a flag) or a range of bits (a small integer).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BitDef {
    /// snake_case name.
    pub name: String,
    /// A single-bit flag.
    #[serde(default)]
    pub bit: Option<u32>,
    /// An inclusive bit range `[low, high]` holding an unsigned value.
    #[serde(default)]
    pub bits: Option<[u32; 2]>,
    /// Meaning.
    #[serde(default)]
    pub description: Option<String>,
}

/// A union variant.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VariantDef {
    /// PascalCase name.
    pub name: String,
    /// Tag value.
    pub tag: u64,
    /// Type of the value that follows the tag (none for a tag-only variant).
    #[serde(rename = "type", default)]
    pub ty: Option<String>,
    /// Meaning.
    #[serde(default)]
    pub description: Option<String>,
}

/// A component interface: what the generated trait and the component runtime build on.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ComponentDef {
    /// PascalCase name.
    pub name: String,
    /// Component id (Part 1; 1-254).
    pub id: u8,
    /// The Part 1 "Function" text.
    pub function: String,
    /// The Part 1 "Description" text.
    #[serde(default)]
    pub description: Option<String>,
    /// Command-class messages it executes; the runtime takes them only from the
    /// component in control.
    #[serde(default)]
    pub commands: Vec<String>,
    /// Queries it answers and messages it consumes, from any sender.
    #[serde(default)]
    pub accepts: Vec<String>,
    /// Messages it sends on its own initiative (replies to accepted queries are implied).
    #[serde(default)]
    pub emits: Vec<String>,
    /// May send and receive any message (Part 1 command and control components).
    #[serde(default)]
    pub any_message: bool,
    /// Commands motion: its trait gets a required `stop` method the runtime calls on
    /// Emergency, on leaving Ready, and when control is lost.
    #[serde(default)]
    pub safe_stop: bool,
    /// Behaviour rules of Part 1, one sentence each (rendered into the docs).
    #[serde(default)]
    pub rules: Vec<String>,
    /// Component-specific sub-states of the core Ready state.
    #[serde(default)]
    pub modes: Option<ModesDef>,
    /// The SDK's stock implementation of this component, which `jaus node` hosts
    /// (`jaus_node::host`): its name in a node file and the hardware it runs over.
    /// Absent when the SDK ships none.
    #[serde(default)]
    pub stock: Option<StockDef>,
    /// The shared parts ([`PartDef`], by name) it handles as the other components
    /// sharing them do; its lists still name every message of its interface.
    #[serde(default)]
    pub parts: Vec<String>,
}

/// A part of several component interfaces (`parts:` of a file): messages that Part 1
/// gives the same meaning in each, and the behaviour that goes with them. The generator
/// emits one trait for it; each component that shares it (`parts: [Name]`) routes
/// those messages to it.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PartDef {
    /// PascalCase name (the trait's).
    pub name: String,
    /// What the components share, for the trait's documentation.
    pub description: String,
    /// Command-class messages of the part: every sharing component lists them in
    /// `commands`.
    #[serde(default)]
    pub commands: Vec<String>,
    /// Accepted messages of the part: every sharing component lists them in `accepts`.
    #[serde(default)]
    pub accepts: Vec<String>,
    /// Messages the part sends on its own: every sharing component lists them in
    /// `emits`.
    #[serde(default)]
    pub emits: Vec<String>,
    /// Entries of `commands` and `accepts` a sharing component may leave out (it then
    /// never receives them); one that lists them lists them in the same role.
    #[serde(default)]
    pub optional: Vec<String>,
    /// Behaviour rules shared by the components, one sentence each (rendered into the
    /// docs).
    #[serde(default)]
    pub rules: Vec<String>,
}

/// The SDK's stock implementation of a component (`stock:` of a component).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StockDef {
    /// Its name in a node file's `host:` list (snake_case, unique; usually the
    /// component's module name, `global_pose_sensor` for `GlobalPoseSensor`).
    pub name: String,
    /// The hardware it runs over (default: none).
    #[serde(default)]
    pub needs: Hardware,
}

/// Declares [`Hardware`] from its one list: each kind's variant, YAML name and meaning.
/// jaus-gen generates the runtime's `jaus::component::Hardware` from the same list
/// ([`Hardware::ALL`], [`Hardware::variant`], [`Hardware::as_str`], [`Hardware::doc`]).
macro_rules! hardware {
    ($(#[doc = $doc:literal] $(#[$extra:meta])* $variant:ident = $name:literal,)+) => {
        /// The hardware a stock component runs over (`stock.needs` of a component).
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Deserialize)]
        pub enum Hardware {
            $(
                #[doc = $doc]
                $(#[$extra])*
                #[serde(rename = $name)]
                $variant,
            )+
        }

        impl Hardware {
            /// Every kind, in the order of the definitions.
            pub const ALL: &'static [Hardware] = &[$(Hardware::$variant),+];

            /// The name as written in the YAML (`vehicle`).
            pub fn as_str(self) -> &'static str {
                match self {
                    $(Hardware::$variant => $name,)+
                }
            }

            /// The Rust variant's name (`Vehicle`).
            pub fn variant(self) -> &'static str {
                match self {
                    $(Hardware::$variant => stringify!($variant),)+
                }
            }

            /// What the kind is (its doc comment, one line).
            pub fn doc(self) -> &'static str {
                match self {
                    $(Hardware::$variant => $doc.trim_ascii(),)+
                }
            }
        }
    };
}

hardware! {
    /// None: it works on messages alone (a driver above the Primitive Driver, a store).
    #[default]
    None = "none",
    /// The vehicle: its actuators, or its pose and velocity.
    Vehicle = "vehicle",
    /// A range scanner on the vehicle.
    Scanner = "scanner",
    /// A pan/tilt camera on the vehicle.
    Camera = "camera",
    /// A manipulator arm: its joints' actuators and sensors.
    Arm = "arm",
    /// Data links to other subsystems (a radio, a tether).
    Links = "links",
}

/// Sub-states of Ready and the legal transitions between them.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModesDef {
    /// What the modes track.
    #[serde(default)]
    pub description: Option<String>,
    /// The mode on entering Ready (and after leaving it).
    pub initial: String,
    /// The modes.
    pub states: Vec<ModeDef>,
    /// The legal transitions.
    #[serde(default)]
    pub transitions: Vec<TransitionDef>,
}

/// One mode.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModeDef {
    /// PascalCase name.
    pub name: String,
    /// Meaning.
    #[serde(default)]
    pub description: Option<String>,
}

/// One legal mode transition.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransitionDef {
    /// snake_case name.
    pub name: String,
    /// Modes it may start from.
    pub from: Vec<String>,
    /// Mode it leads to.
    pub to: String,
    /// Core state the component enters with it (`Standby` or `Failure`).
    #[serde(default)]
    pub core: Option<String>,
    /// When it happens.
    #[serde(default)]
    pub description: Option<String>,
}
