//! The regeneration promise on the stock AS-4 Core: `tests/build.rs` regenerates the
//! Core's machine from jaus-as4's definitions with one line edited (Management's
//! Controlled.Available starts in Ready: a client granted control finds the component
//! Ready), as a vendor does when the standard revises; a component runs on each machine
//! (`As4Component::with_machine`, `jaus_as4::core_machine!`) and does what its
//! definition says.

use std::time::Instant;

use jaus::net::as5669a::As4Id;
use jaus_as4::component::As4Component;
use jaus_as4::core::CoreConfig;
use jaus_as4::{ComponentState, Message, QueryStatus, ReportStatus, RequestControl, Resume};

#[allow(clippy::all, clippy::pedantic, dead_code, unused_imports)]
mod edited {
    pub use jaus_as4::messages::*;
    /// The Core services generated from the edited definitions.
    pub mod services {
        include!(concat!(env!("OUT_DIR"), "/as4-edited/services.rs"));
    }
}

jaus_as4::core_machine!(edited::services);

const ME: As4Id = As4Id::new(9, 1, 1);
const CLIENT: As4Id = As4Id::new(42, 1, 1);

fn status(c: &mut As4Component<()>, now: Instant) -> ComponentState {
    let out = c.handle(now, CLIENT, &QueryStatus {}.into(), &mut ());
    match out.as_slice() {
        [o] => match &o.message {
            Message::ReportStatus(ReportStatus { status, .. }) => *status,
            m => panic!("expected Report Status, got {m:?}"),
        },
        _ => panic!("expected one answer, got {out:?}"),
    }
}

#[test]
fn an_edited_transition_changes_what_the_running_component_does() {
    let now = Instant::now();
    let mut stock: As4Component<()> = As4Component::new(ME, CoreConfig::named("stock"));
    let mut regenerated: As4Component<()> = As4Component::with_machine(
        ME,
        CoreConfig::named("edited"),
        Box::new(edited::services::management::Machines::new()),
    );
    for c in [&mut stock, &mut regenerated] {
        assert_eq!(status(c, now), ComponentState::Standby);
        c.handle(
            now,
            CLIENT,
            &RequestControl { authority_code: 5 }.into(),
            &mut (),
        );
        assert_eq!(c.controller(), Some(CLIENT));
    }
    // The stock definition: control granted, the component still in Standby until Resume.
    assert_eq!(status(&mut stock, now), ComponentState::Standby);
    assert_eq!(
        stock.core().machine_state(),
        "Receiving.Ready.Controlled.Available.Standby"
    );
    stock.handle(now, CLIENT, &Resume {}.into(), &mut ());
    assert_eq!(status(&mut stock, now), ComponentState::Ready);
    // The edited definition: the grant itself leads to Ready.
    assert_eq!(status(&mut regenerated, now), ComponentState::Ready);
    assert_eq!(
        regenerated.core().machine_state(),
        "Receiving.Ready.Controlled.Available.Ready"
    );
    // Everything else is the same machine: releasing control returns both to Standby.
    for c in [&mut stock, &mut regenerated] {
        c.handle(now, CLIENT, &jaus_as4::ReleaseControl {}.into(), &mut ());
        assert_eq!(status(c, now), ComponentState::Standby);
        assert_eq!(c.controller(), None);
    }
}
