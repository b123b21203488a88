//! What the Core and the services send and who they are, below both ([`crate::core`] and
//! [`crate::service`] use it): a message with its destination ([`Outgoing`]), a
//! service's URI and version ([`ServiceId`]), and Transport's `Receive` data of a sender
//! ([`receive_of`], [`sender_of`]).

use std::fmt;

use jaus::net::as5669a::As4Id;

use crate::messages::services::transport::event::Receive;
use crate::messages::{ComponentAddress, Message};

/// A service's identity as Discovery reports it: its URI and version.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ServiceId {
    /// The service's URI (`urn:jaus:jss:mobility:LocalPoseSensor`).
    pub uri: &'static str,
    /// Major version.
    pub major: u8,
    /// Minor version.
    pub minor: u8,
}

impl ServiceId {
    /// The service `uri` at version `major.minor`.
    pub const fn new(uri: &'static str, major: u8, minor: u8) -> Self {
        Self { uri, major, minor }
    }
}

impl fmt::Display for ServiceId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} v{}.{}", self.uri, self.major, self.minor)
    }
}

/// A message to send: its destination and the message.
#[derive(Debug, Clone, PartialEq)]
pub struct Outgoing {
    /// The destination.
    pub to: As4Id,
    /// The message.
    pub message: Message,
}

impl Outgoing {
    /// `message` for `to`.
    pub fn new(to: As4Id, message: impl Into<Message>) -> Self {
        Self {
            to,
            message: message.into(),
        }
    }
}

/// Transport's `Receive` data of a message from `from`.
pub fn receive_of(from: As4Id) -> Receive {
    Receive {
        source: ComponentAddress {
            subsystem_id: from.subsystem,
            node_id: from.node,
            component_id: from.component,
        },
    }
}

/// The sender of a message, from Transport's `Receive` data.
pub fn sender_of(transport: &Receive) -> As4Id {
    let s = &transport.source;
    As4Id::new(s.subsystem_id, s.node_id, s.component_id)
}
