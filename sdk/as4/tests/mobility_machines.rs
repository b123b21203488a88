//! The Mobility services run their generated machines (`defs/mobility_services.yaml`):
//! who may drive, in which state, is what the transitions say, and the component's
//! refusal names the state in which no transition took the message.

use std::time::{Duration, Instant};

use jaus::messages as ra;
use jaus::net::as5669a::As4Id;
use jaus::Address;
use jaus_as4::component::As4Component;
use jaus_as4::core::CoreConfig;
use jaus_as4::mobility::PrimitiveDriver;
use jaus_as4::ra33::{Ra33Side, Targets};
use jaus_as4::service::Service;
use jaus_as4::{
    ComponentState, Message, QueryWrenchEffort, RequestControl, Resume, SetWrenchEffort, Standby,
};

const ME: As4Id = As4Id::new(1, 1, 1);
const OPERATOR: As4Id = As4Id::new(2, 1, 1);
const OTHER: As4Id = As4Id::new(3, 1, 1);
const PD: Address = Address::new(1, 1, 33, 1);

/// The RA 3.3 Set Wrench Effort messages the gateway's side would send to the driver.
fn efforts_sent(side: &mut Ra33Side) -> Vec<ra::SetWrenchEffort> {
    let mut out = Vec::new();
    while let Some((to, m)) = side.poll_transmit() {
        if let (true, ra::Message::SetWrenchEffort(s)) = (to == PD, m) {
            out.push(s);
        }
    }
    out
}

fn forward(x: f64) -> Message {
    SetWrenchEffort {
        propulsive_linear_effort_x: Some(x),
        ..Default::default()
    }
    .into()
}

#[test]
fn the_primitive_driver_obeys_its_controller_in_ready_only() {
    let t = Instant::now();
    let targets = Targets {
        primitive_driver: Some(PD),
        ..Default::default()
    };
    let mut side = Ra33Side::new(
        Address::new(1, 1, 60, 1),
        targets,
        200,
        Duration::from_secs(1),
    );
    let driver = PrimitiveDriver::new(&mut side, t, PD);
    let mut c = As4Component::<Ra33Side>::new(ME, CoreConfig::named("gw")).with_service(driver);
    efforts_sent(&mut side);

    // A query is answered from anyone, in any state.
    let q: Message = QueryWrenchEffort {
        presence_vector: 0x0001,
    }
    .into();
    let out = c.handle(t, OTHER, &q, &mut side);
    assert!(
        matches!(out.as_slice(), [o] if o.to == OTHER && matches!(o.message, Message::ReportWrenchEffort(_))),
        "{out:?}"
    );

    // Not controlled: no transition takes Set Wrench Effort.
    let refused = c.stats().refused;
    assert!(c.handle(t, OPERATOR, &forward(20.0), &mut side).is_empty());
    assert_eq!(c.stats().refused, refused + 1);
    assert!(efforts_sent(&mut side).is_empty());

    // Controlled but in Standby: still none (the transition is under Ready).
    c.handle(
        t,
        OPERATOR,
        &RequestControl { authority_code: 5 }.into(),
        &mut side,
    );
    assert_eq!(c.controller(), Some(OPERATOR));
    assert_eq!(c.state(), ComponentState::Standby);
    c.handle(t, OPERATOR, &forward(20.0), &mut side);
    assert_eq!(c.stats().refused, refused + 2);
    assert!(efforts_sent(&mut side).is_empty());

    // Ready: the efforts reach the RA 3.3 driver, and the machine is where the Core is.
    c.handle(t, OPERATOR, &Resume {}.into(), &mut side);
    assert_eq!(c.state(), ComponentState::Ready);
    c.handle(t, OPERATOR, &forward(20.0), &mut side);
    let sent = efforts_sent(&mut side);
    assert_eq!(sent.len(), 1, "{sent:?}");
    assert_eq!(sent[0].propulsive_linear_effort_x, Some(20.0));
    assert_eq!(c.stats().refused, refused + 2);

    // Another client, even in Ready: refused (the guard is isControllingClient).
    c.handle(t, OTHER, &forward(90.0), &mut side);
    assert_eq!(c.stats().refused, refused + 3);
    assert!(efforts_sent(&mut side).is_empty());

    // Back to Standby: refused again.
    c.handle(t, OPERATOR, &Standby {}.into(), &mut side);
    c.handle(t, OPERATOR, &forward(20.0), &mut side);
    assert_eq!(c.stats().refused, refused + 4);
    assert!(efforts_sent(&mut side)
        .iter()
        .all(|s| s.propulsive_linear_effort_x == Some(0.0)));
}

#[test]
fn a_mobility_service_takes_its_own_messages_only() {
    let t = Instant::now();
    let mut side = Ra33Side::new(
        Address::new(1, 1, 60, 1),
        Targets::default(),
        200,
        Duration::from_secs(1),
    );
    let driver = PrimitiveDriver::new(&mut side, t, PD);
    let own = |code| Service::<Ra33Side>::receives(&driver, code);
    assert!(own(<SetWrenchEffort as jaus::JausMessage>::CODE));
    assert!(own(<QueryWrenchEffort as jaus::JausMessage>::CODE));
    // Management's messages are the Core's, which takes them first.
    assert!(!own(<Resume as jaus::JausMessage>::CODE));
    assert!(!own(<RequestControl as jaus::JausMessage>::CODE));
}
