//! Shared pieces of the Core runtime tests: clients, a component, a toy service.
#![allow(dead_code)]

use std::sync::{Arc, Mutex};
use std::time::Instant;

use jaus::net::as5669a::As4Id;
use jaus::{CommandCode, JausMessage};
use jaus_as4::component::{As4Component, Outgoing};
use jaus_as4::core::CoreConfig;
use jaus_as4::service::{Cx, Handled, Request, Service, ServiceId};
use jaus_as4::{ComponentState, Message, QueryTravelSpeed, ReportTravelSpeed, SetTravelSpeed};

/// The component under test.
pub const ME: As4Id = As4Id::new(7, 1, 1);
/// Three clients.
pub const A: As4Id = As4Id::new(42, 1, 1);
pub const B: As4Id = As4Id::new(42, 1, 2);
pub const C: As4Id = As4Id::new(43, 1, 1);

/// The toy service's id.
pub const SPEEDO: ServiceId = ServiceId::new("urn:test:Speedo", 2, 3);

/// A toy service: Set Travel Speed (a command) and Query Travel Speed; it records what
/// the component told it.
#[derive(Debug, Default)]
pub struct Speedo {
    pub speed: f64,
    pub log: Arc<Mutex<Vec<String>>>,
}

impl<E: 'static> Service<E> for Speedo {
    fn id(&self) -> ServiceId {
        SPEEDO
    }

    fn receives(&self, code: CommandCode) -> bool {
        code == SetTravelSpeed::CODE || code == QueryTravelSpeed::CODE
    }

    fn handle(&mut self, _cx: &mut Cx<'_, E>, request: &Request<'_>) -> Handled {
        match request.message {
            Message::SetTravelSpeed(s) => {
                self.speed = s.speed;
                Handled::Done
            }
            Message::QueryTravelSpeed(_) => {
                Handled::Reply(ReportTravelSpeed { speed: self.speed }.into())
            }
            _ => Handled::NotMine,
        }
    }

    fn state_changed(&mut self, _cx: &mut Cx<'_, E>, from: ComponentState, to: ComponentState) {
        self.log
            .lock()
            .unwrap()
            .push(format!("state {from:?}->{to:?}"));
    }

    fn controller_changed(&mut self, _cx: &mut Cx<'_, E>, controller: Option<As4Id>) {
        self.log
            .lock()
            .unwrap()
            .push(format!("controller {controller:?}"));
    }
}

/// A component with `config` and the toy service; the service's log.
pub fn component(config: CoreConfig) -> (As4Component<()>, Arc<Mutex<Vec<String>>>) {
    let speedo = Speedo::default();
    let log = speedo.log.clone();
    (As4Component::new(ME, config).with_service(speedo), log)
}

/// Sends `msg` from `from` and returns what comes out.
pub fn send(
    c: &mut As4Component<()>,
    now: Instant,
    from: As4Id,
    msg: impl Into<Message>,
) -> Vec<Outgoing> {
    c.handle(now, from, &msg.into(), &mut ())
}

/// The single message that `out` holds for `to`.
pub fn only_for(out: &[Outgoing], to: As4Id) -> Message {
    let mine: Vec<_> = out.iter().filter(|o| o.to == to).collect();
    assert_eq!(mine.len(), 1, "one message for {to} expected in {out:?}");
    mine[0].message.clone()
}
