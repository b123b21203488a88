//! Services generated on the Core's services: a vendor's definitions that say `extends:
//! as4` and whose services inherit one of jaus-as4's Core services (Access Control,
//! Management, ...). `jaus-gen` (`Builder::base("as4", ...)`) writes per such service a
//! `Hosted<S>` over the vendor's implementation `S` of the service's own guards and
//! actions; `Hosted<S>` is a [`GeneratedService`], and every [`GeneratedService`] is a
//! [`Service`], so the component runs it as any other:
//!
//! 1. a message the Core does not take and the service's machines do (`RECEIVES`)
//!    arrives: a vendor's message (outside jaus-as4's definitions, `Message::Raw`) is
//!    decoded with the vendor's definitions; an undecodable one is refused, naming the
//!    message and the error;
//! 2. the service's machine first follows the Core's (`hsm::Machine::follow_with`):
//!    the states it inherits are the Core's, so `Receiving.Ready.Controlled` is where
//!    the Core is when the component is controlled; it also follows whenever the
//!    Core's state or controller changes, running the service's own exit and entry
//!    actions of the states left and entered;
//! 3. the trigger runs; inherited guards and actions run on the Core ([`Cx::with_core`]:
//!    `isControllingClient` is the Core's controller), the service's own on `S`;
//! 4. what `S` sent ([`Outbox`]) leaves: the first message to the sender is the reply
//!    (what an event on a vendor's query reports), the rest with the component's output;
//!    no transition taken is a refusal, counted and logged with the state and the
//!    message.
//!
//! The inherited machine is the Core's: a vendor's transition moves between its own
//! sub-states; moving the Core (between Controlled and NotControlled, Standby and Ready)
//! is done by the Core's own messages.

use std::fmt;

use jaus::net::as5669a::As4Id;
use jaus::{CommandCode, JausMessage};

use super::{Cx, Handled, Outgoing, Request, Service, ServiceId};
use crate::core::machine::Host;
use crate::messages::services::transport::event::Receive;
use crate::messages::{ComponentState, Message};
use crate::outgoing::{receive_of, sender_of};

/// What a generated service did with a message ([`GeneratedService::receive`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Taken {
    /// None of its machines takes this message.
    NotMine,
    /// A transition was taken.
    Taken,
    /// The message is the service's, but no transition answers it in the current state
    /// (the state's path is given).
    NoTransition(&'static str),
    /// The message's body does not decode with the service's definitions.
    Undecodable(String),
}

/// A service whose machines were generated on the Core's services. `jaus-gen` writes
/// the implementation (`Hosted<S>` in each generated service module); the vendor writes
/// `S`, the service's own guards and actions, and its [`Outbox`].
pub trait GeneratedService: fmt::Debug + Send + 'static {
    /// Its URI and version.
    fn id(&self) -> ServiceId;

    /// Whether its machines take message `code`.
    fn receives(&self, code: CommandCode) -> bool;

    /// Whether message `code` needs control before the machines see it. Default: no;
    /// the machines decide (a transition guarded by `isControllingClient`).
    fn needs_control(&self, code: CommandCode) -> bool {
        let _ = code;
        false
    }

    /// Makes the inherited part of its machines follow the Core's machine, now at
    /// `core_state` (a path of the Core's machine), running the service's own exit and
    /// entry actions of the states left and entered (the generated `Machines::follow`).
    fn follow(&mut self, core_state: &'static str);

    /// Offers `message` from `transport`'s sender to its machines, the inherited guards
    /// and actions running on `core`.
    fn receive(&mut self, core: &mut Host<'_>, message: &Message, transport: &Receive) -> Taken;

    /// What its actions sent since the last call, taken.
    fn take_output(&mut self) -> Vec<Outgoing>;

    /// Its machines' current states, `machine: path` (for logs and tests).
    fn states(&self) -> Vec<(&'static str, &'static str)>;
}

impl<E: 'static, G: GeneratedService> Service<E> for G {
    fn id(&self) -> ServiceId {
        GeneratedService::id(self)
    }

    fn receives(&self, code: CommandCode) -> bool {
        GeneratedService::receives(self, code)
    }

    fn needs_control(&self, code: CommandCode) -> bool {
        GeneratedService::needs_control(self, code)
    }

    fn needs_ready(&self, _code: CommandCode) -> bool {
        // The machines decide: a transition under `Ready` is what needs Ready.
        false
    }

    fn state_changed(&mut self, cx: &mut Cx<'_, E>, _from: ComponentState, _to: ComponentState) {
        self.follow(cx.core_state());
        for o in self.take_output() {
            cx.send(o);
        }
    }

    fn controller_changed(&mut self, cx: &mut Cx<'_, E>, _controller: Option<As4Id>) {
        // Controlled and NotControlled are states of the Core's machine too.
        self.follow(cx.core_state());
        for o in self.take_output() {
            cx.send(o);
        }
    }

    fn handle(&mut self, cx: &mut Cx<'_, E>, request: &Request<'_>) -> Handled {
        self.follow(cx.core_state());
        let transport = receive_of(request.from);
        let taken = cx.with_core(|core| self.receive(core, request.message, &transport));
        let mut reply = None;
        for o in self.take_output() {
            if reply.is_none() && o.to == request.from {
                reply = Some(o.message);
            } else {
                cx.send(o);
            }
        }
        match taken {
            Taken::NotMine => Handled::NotMine,
            Taken::Taken => reply.map_or(Handled::Done, Handled::Reply),
            Taken::NoTransition(state) => Handled::Refused(format!(
                "{}: no transition for {} in state {state}",
                GeneratedService::id(self),
                request.message.name()
            )),
            Taken::Undecodable(why) => Handled::Refused(why),
        }
    }
}

/// What a generated service's own actions send: put one in the implementation of the
/// service's guards and actions, and send from the actions. A vendor's message (outside
/// jaus-as4's definitions) travels as its encoded body; one that cannot be encoded (a
/// string past its limit) is not sent, counted and logged.
#[derive(Debug, Default, Clone)]
pub struct Outbox {
    out: Vec<Outgoing>,
    unencodable: u64,
}

impl Outbox {
    /// An empty outbox.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sends `message` to `to`.
    pub fn send<M: JausMessage>(&mut self, to: As4Id, message: &M) {
        let encoded = match message.to_bytes() {
            Ok(body) => Message::decode(M::CODE, &body)
                .map_err(|e| format!("does not decode as written: {e}")),
            Err(e) => Err(e.to_string()),
        };
        match encoded {
            Ok(m) => self.out.push(Outgoing { to, message: m }),
            Err(e) => {
                self.unencodable += 1;
                tracing::warn!(message = M::NAME, %to, "not sent: {e}");
            }
        }
    }

    /// Sends `message` back to the sender of the message being handled (`transport` is
    /// the trigger's Transport `Receive` data).
    pub fn reply<M: JausMessage>(&mut self, transport: &Receive, message: &M) {
        self.send(sender_of(transport), message);
    }

    /// What was sent since the last call, taken.
    pub fn take(&mut self) -> Vec<Outgoing> {
        std::mem::take(&mut self.out)
    }

    /// Messages that could not be encoded (not sent).
    pub fn unencodable(&self) -> u64 {
        self.unencodable
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn receive_data_round_trips_the_sender() {
        let a = As4Id::new(30, 2, 7);
        assert_eq!(sender_of(&receive_of(a)), a);
    }

    #[test]
    fn the_outbox_carries_a_message_of_the_definitions_typed() {
        let mut o = Outbox::new();
        let to = As4Id::new(1, 1, 1);
        o.send(to, &crate::messages::QueryStatus {});
        let out = o.take();
        assert_eq!(out.len(), 1);
        assert!(matches!(out[0].message, Message::QueryStatus(_)));
        assert!(o.take().is_empty());
    }
}
