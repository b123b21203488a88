//! # jaus — a JAUS RA 3.3 SDK
//!
//! Typed messages generated at build time from the YAML definitions of `jaus-spec`,
//! a byte-exact wire codec derived from field attributes, and the header/packet types.
//!
//! ```
//! use jaus::codec::{Decode, Encode};
//! use jaus::messages::ReportGlobalPose;
//!
//! let pose = ReportGlobalPose {
//!     latitude: Some(29.65),
//!     longitude: Some(-82.32),
//!     ..Default::default()
//! };
//! let body = pose.to_bytes().unwrap();
//! assert_eq!(body.len(), 2 + 4 + 4); // presence vector + two scaled i32
//! let back = ReportGlobalPose::from_bytes(&body).unwrap();
//! assert!((back.latitude.unwrap() - 29.65).abs() < 1e-7);
//! assert_eq!(back.elevation, None);
//! ```
//!
//! A scaled value beyond its field's range is an encode error, never silently clamped;
//! `clamped()` (or `clamp_to_range()`) saturates every scaled field explicitly.
//! Values received are never clamped.
//!
//! ```
//! use jaus::codec::{Encode, EncodeError};
//! use jaus::messages::ReportGlobalPose;
//!
//! let pose = ReportGlobalPose { latitude: Some(129.5), ..Default::default() };
//! let e = pose.to_bytes().unwrap_err();
//! assert_eq!(e.to_string(), "ReportGlobalPose.latitude: 129.5 outside [-90, 90] deg");
//! assert!(matches!(e, EncodeError::OutOfRange { value, .. } if value == 129.5));
//! let pose = pose.clamped();
//! assert_eq!(pose.latitude, Some(90.0));
//! assert!(pose.to_bytes().is_ok());
//! ```
//!
//! A vendor's own experimental message needs no YAML: derive the codec by hand.
//!
//! ```
//! use jaus::codec::{Decode, Encode};
//! use jaus::{JausMessage, JausRecord};
//!
//! #[derive(Debug, PartialEq, JausRecord)]
//! struct Sample {
//!     #[jaus(scaled(u16, 0.0, 100.0))]
//!     level: f64,
//! }
//!
//! /// Report Tank Levels, an experimental message of our own.
//! #[derive(Debug, PartialEq, JausMessage)]
//! #[jaus(code = 0xD101, presence = u8)]
//! struct ReportTankLevels {
//!     tank: u8,
//!     #[jaus(count = u8)]
//!     samples: Vec<Sample>,
//!     #[jaus(bit = 0, size = u8)]
//!     label: Option<String>,
//! }
//!
//! let m = ReportTankLevels { tank: 2, samples: vec![Sample { level: 100.0 }], label: None };
//! let bytes = m.to_bytes().unwrap();
//! assert_eq!(bytes, [0x00, 0x02, 0x01, 0xFF, 0xFF]);
//! assert_eq!(ReportTankLevels::from_bytes(&bytes).unwrap(), m);
//! assert_eq!(ReportTankLevels::CODE.0, 0xD101);
//! ```

// The derive macros refer to `::jaus`; make that path work inside this crate too.
#![warn(missing_docs)]

extern crate self as jaus;

pub mod calendar;
pub mod clock;
pub mod codec;
#[cfg(feature = "component")]
pub mod component;
pub mod hex;
pub mod hsm;
#[cfg(feature = "serde")]
pub mod json;
pub mod link;
#[cfg(feature = "net")]
pub mod net;
#[cfg(feature = "payload")]
pub mod payload;
#[cfg(feature = "stock")]
pub mod stock;
pub mod wire;

pub use jaus_derive::{JausBits, JausEnum, JausMessage, JausRecord, JausUnion};
pub use wire::{Address, CommandCode, Header, Packet, PacketRef};

/// A message body type with its command code.
pub trait JausMessage: codec::Encode + codec::Decode {
    /// The command code in the header of this message.
    const CODE: CommandCode;
    /// The message name.
    const NAME: &'static str;

    /// Decodes a whole body, naming this message in any error.
    #[inline]
    fn decode_body(body: &[u8]) -> Result<Self, codec::DecodeError> {
        Self::from_bytes(body).map_err(|e| e.in_message(Self::NAME))
    }
}

/// A query message and the report that answers it.
pub trait Query: JausMessage {
    /// The report a component sends back.
    type Report: JausMessage;
}

/// A set of messages a component speaks: the SDK's own [`messages::Message`], or a
/// vendor's generated set, which wraps it and adds the vendor's messages. The component
/// runtime, [`component::Component`], is generic over it: it decodes what arrives with
/// [`MessageSet::decode`], takes the core messages through [`MessageSet::standard`]
/// and hands everything else to the component's behaviour as the set's own type.
pub trait MessageSet:
    codec::Encode + Clone + std::fmt::Debug + PartialEq + Send + Sync + 'static
{
    /// Decodes a body of the message with command code `code`; a code the set does not
    /// define decodes to a raw message ([`RawMessage`]), never to an error.
    fn decode(code: CommandCode, body: &[u8]) -> Result<Self, codec::DecodeError>;
    /// The command code of this message.
    fn code(&self) -> CommandCode;
    /// The name of this message.
    fn name(&self) -> &'static str;
    /// The message as one of the SDK's standard messages (or a raw one), if it is.
    fn standard(&self) -> Option<&messages::Message>;
    /// A standard message as a message of this set.
    fn from_standard(m: messages::Message) -> Self;
    /// The query that report `report` answers (the complement rule for the standard
    /// ranges, the definitions' `report:` for experimental queries).
    fn query_of(report: CommandCode) -> Option<CommandCode>;
    /// The report answering query `query`.
    fn report_of(query: CommandCode) -> Option<CommandCode>;
    /// The catalogue row of `code` in this set.
    fn info(code: CommandCode) -> Option<&'static MessageInfo>;
}

/// A message of the SDK's standard set (implemented for each by the generator): what a
/// vendor's message set wraps. A vendor component with `any_message: true` may send
/// every one of them.
pub trait StandardMessage: JausMessage + Into<messages::Message> {}

/// A message the message set does not define: an experimental message of another
/// vendor, or one of a newer revision of the standard. Its command code and body are
/// kept exactly as received, so that it is handed to a component
/// (`on_other_message`), passed on by nodes, printed and sent by the CLI unchanged.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct RawMessage {
    /// Command code (decimal, or a hex string such as `"0xD123"`, in JSON).
    #[cfg_attr(feature = "serde", serde(with = "crate::hex::code"))]
    pub code: CommandCode,
    /// The body (a hex string in JSON).
    #[cfg_attr(feature = "serde", serde(with = "crate::hex::serde"))]
    pub body: Vec<u8>,
}

impl codec::Encode for RawMessage {
    fn encoded_len(&self) -> usize {
        self.body.len()
    }
    fn encode(&self, w: &mut codec::Writer<'_>) -> Result<(), codec::EncodeError> {
        w.put(&self.body)
    }
}

/// A row of the message catalogue ([`messages::MESSAGES`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MessageInfo {
    /// Command code.
    pub code: CommandCode,
    /// Rust/struct name.
    pub name: &'static str,
    /// Title as the standard writes it.
    pub title: &'static str,
    /// Message group (also the cargo feature that selects it).
    pub group: &'static str,
    /// For a query, the name of the report answering it.
    pub report: Option<&'static str>,
    /// Not part of RA 3.3.
    pub experimental: bool,
    /// Its class: given by the code's range, or by the definition (`class:`) for an
    /// experimental code.
    pub class: wire::MessageClass,
    /// A command that changes nothing a controller owns (`access: read` in the
    /// definitions: subscriptions, event set-up, giving up control): an access policy
    /// treats it as a query.
    pub read_only: bool,
    /// Whether only the controlling client may send it: AS-4's `is_command` where the
    /// definition gives it, else whether its class is Command. The AS-4 runtime enforces
    /// control by this, whatever the code.
    pub needs_control: bool,
}

impl MessageInfo {
    /// The catalogue row of `code`.
    pub fn of(code: CommandCode) -> Option<&'static MessageInfo> {
        messages::MESSAGES.iter().find(|m| m.code == code)
    }
}

/// The generated component skeletons: per component of Part 1 (and the node manager)
/// a module with the vendor trait, its interface, its modes and the dispatch that runs
/// it under [`component::Component`].
#[cfg(feature = "component")]
pub mod components {
    include!(concat!(env!("OUT_DIR"), "/components.rs"));
}

/// The generated message set: one struct per message, shared types, and the
/// [`messages::Message`] enum over all of them.
pub mod messages {
    include!(concat!(env!("OUT_DIR"), "/messages.rs"));

    /// The generated state machines of the definitions' `services:`: the RA 3.3 core
    /// states (`jaus-spec/defs/core_states.yaml`), whose table
    /// [`CoreState::apply`](crate::component::CoreState::apply) runs with [`crate::hsm`].
    #[allow(clippy::all)]
    pub mod services {
        include!(concat!(env!("OUT_DIR"), "/services.rs"));
    }
}

/// The Rust examples of the workspace's README.md, compiled and run as doctests
/// (`cargo test -p jaus --doc`), so that the README shows code that works.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeExamples;
