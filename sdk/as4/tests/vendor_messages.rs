//! A vendor's own AS-4 messages, outside jaus-as4's definitions: they arrive undecoded
//! (`Message::Raw`), reach the service that declares them, need control unless the
//! service says otherwise (whatever their code), and a vendor query can be subscribed to
//! with Create Event.

mod core_common;

use std::time::Instant;

use core_common::*;
use jaus::{CommandCode, RawMessage};
use jaus_as4::core::CoreConfig;
use jaus_as4::service::{Cx, Handled, Request, Service, ServiceId};
use jaus_as4::{
    embedded, ConfirmEventRequest, CreateEvent, EventType, Message, RejectEventRequest,
    RequestControl,
};

/// A vendor command at 0xF012 (a lamp level) and a vendor query at 0xF010 answered by a
/// report at 0xF011.
const SET_LAMP: CommandCode = CommandCode(0xF012);
const QUERY_LAMP: CommandCode = CommandCode(0xF010);
const REPORT_LAMP: CommandCode = CommandCode(0xF011);

#[derive(Debug, Default)]
struct Lamp {
    level: u8,
}

impl<E: 'static> Service<E> for Lamp {
    fn id(&self) -> ServiceId {
        ServiceId::new("urn:acme:Lamp", 1, 0)
    }

    fn receives(&self, code: CommandCode) -> bool {
        code == SET_LAMP || code == QUERY_LAMP
    }

    fn needs_control(&self, code: CommandCode) -> bool {
        code != QUERY_LAMP
    }

    fn needs_ready(&self, _code: CommandCode) -> bool {
        false
    }

    fn handle(&mut self, _cx: &mut Cx<'_, E>, request: &Request<'_>) -> Handled {
        match request.message {
            Message::Raw(r) if r.code == SET_LAMP => {
                self.level = r.body.first().copied().unwrap_or(0);
                Handled::Done
            }
            Message::Raw(r) if r.code == QUERY_LAMP => Handled::Reply(Message::Raw(RawMessage {
                code: REPORT_LAMP,
                body: vec![self.level],
            })),
            _ => Handled::NotMine,
        }
    }
}

fn raw(code: CommandCode, body: &[u8]) -> Message {
    Message::Raw(RawMessage {
        code,
        body: body.to_vec(),
    })
}

#[test]
fn a_vendor_command_needs_control_and_a_vendor_query_is_answered_and_subscribed() {
    let t = Instant::now();
    let mut c: jaus_as4::component::As4Component<()> =
        jaus_as4::component::As4Component::new(ME, CoreConfig::named("lamp"))
            .with_service(Lamp::default());
    let level = |c: &mut jaus_as4::component::As4Component<()>| match only_for(
        &send(c, t, B, raw(QUERY_LAMP, &[])),
        B,
    ) {
        Message::Raw(r) => {
            assert_eq!(r.code, REPORT_LAMP);
            r.body[0]
        }
        m => panic!("expected the vendor report, got {m:?}"),
    };
    // The vendor command at 0xF012 from a client without control: refused, counted.
    assert!(send(&mut c, t, A, raw(SET_LAMP, &[7])).is_empty());
    assert_eq!(c.stats().not_controller, 1);
    assert_eq!(level(&mut c), 0);
    // With control it is carried out.
    send(&mut c, t, A, RequestControl { authority_code: 0 });
    assert!(send(&mut c, t, A, raw(SET_LAMP, &[7])).is_empty());
    assert_eq!(level(&mut c), 7);
    assert_eq!(c.stats().unknown, 0);
    // An undeclared vendor id is counted as unknown.
    assert!(send(&mut c, t, A, raw(CommandCode(0xF0FF), &[])).is_empty());
    assert_eq!(c.stats().unknown, 1);
    // The vendor query subscribed to: confirmed, and its Event carries the report.
    let query = embedded::encode(&raw(QUERY_LAMP, &[])).unwrap();
    let out = send(
        &mut c,
        t,
        B,
        CreateEvent {
            request_id: 3,
            event_type: EventType::Periodic,
            requested_periodic_rate: 5.0,
            query_message: query,
        },
    );
    assert_eq!(out.len(), 2, "{out:?}");
    assert!(
        matches!(
            out[0].message,
            Message::ConfirmEventRequest(ConfirmEventRequest { request_id: 3, .. })
        ),
        "{out:?}"
    );
    match &out[1].message {
        Message::Event(e) => assert_eq!(e.report_message, [0x11, 0xF0, 7]),
        m => panic!("expected the first Event, got {m:?}"),
    }
    // An undeclared vendor query is refused as not supported.
    let query = embedded::encode(&raw(CommandCode(0xF0FE), &[])).unwrap();
    let out = send(
        &mut c,
        t,
        B,
        CreateEvent {
            request_id: 4,
            event_type: EventType::Periodic,
            requested_periodic_rate: 5.0,
            query_message: query,
        },
    );
    assert!(
        matches!(
            only_for(&out, B),
            Message::RejectEventRequest(RejectEventRequest { request_id: 4, .. })
        ),
        "{out:?}"
    );
}
