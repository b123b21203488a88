//! The control checks that need a comparison to count, without sockets
//! ([`jaus_conform::memory::MemorySession`]): a command from a component not in
//! control that is refused passes only when the controller's own command has the
//! effect; a read-back whose query is never answered is inconclusive; a request below
//! the component's own authority is refused (`control.authority_below`).

use std::any::Any;
use std::time::Instant;

use jaus::component::{Endpoint, Outgoing};
use jaus::net::{Node, NodeConfig};
use jaus::{Address, CommandCode, Header};
use jaus_conform::memory::{MemorySession, TESTER};
use jaus_conform::session::Voices;
use jaus_conform::{report, ComponentReport, Options, Outcome, RunReport, Verdict};
use jaus_node::host::{Host, Stock};

/// Standby (core state command).
const STANDBY: CommandCode = CommandCode(0x0003);
/// Set Travel Speed (a waypoint driver's command, read back by Query Travel Speed).
const SET_TRAVEL_SPEED: CommandCode = CommandCode(0x040A);
/// Query Travel Speed.
const QUERY_TRAVEL_SPEED: CommandCode = CommandCode(0x240A);
/// Request Component Control.
const REQUEST_CONTROL: CommandCode = CommandCode(0x000D);
/// Release Component Control.
const RELEASE_CONTROL: CommandCode = CommandCode(0x000E);
/// Query Component Control.
const QUERY_CONTROL: CommandCode = CommandCode(0x200D);

/// Drops the commands `codes` on arrival, from every sender, controller included.
struct Deaf {
    inner: Box<dyn Endpoint>,
    codes: Vec<CommandCode>,
}

/// Hands the component every Request Component Control at no less than `own`
/// authority: a requester below it is granted control as if it asked at `own`.
struct GrantsAnyone {
    inner: Box<dyn Endpoint>,
    own: u8,
}

/// Carries out every command but never answers Query Travel Speed.
struct SilentQuery {
    inner: Box<dyn Endpoint>,
}

macro_rules! delegate {
    ($t:ty, |$s:ident, $now:ident, $header:ident, $body:ident| $handle:block) => {
        impl Endpoint for $t {
            fn address(&self) -> Address {
                self.inner.address()
            }
            fn handle(&mut self, $now: Instant, $header: &Header, $body: &[u8]) {
                let $s = self;
                $handle
            }
            fn handle_timeout(&mut self, now: Instant) {
                self.inner.handle_timeout(now);
            }
            fn poll_transmit(&mut self) -> Option<Outgoing> {
                self.inner.poll_transmit()
            }
            fn poll_timeout(&self) -> Option<Instant> {
                self.inner.poll_timeout()
            }
            fn as_any(&self) -> &dyn Any {
                self
            }
            fn as_any_mut(&mut self) -> &mut dyn Any {
                self
            }
        }
    };
}

delegate!(Deaf, |s, now, header, body| {
    if !s.codes.contains(&header.command_code) {
        s.inner.handle(now, header, body);
    }
});

delegate!(GrantsAnyone, |s, now, header, body| {
    if header.command_code == REQUEST_CONTROL && body.first().is_some_and(|a| *a < s.own) {
        s.inner.handle(now, header, &[s.own]);
    } else {
        s.inner.handle(now, header, body);
    }
});

delegate!(SilentQuery, |s, now, header, body| {
    if header.command_code != QUERY_TRAVEL_SPEED {
        s.inner.handle(now, header, body);
    }
});

/// A node 1.1 hosting `stock` at `authority`, through `wrap`.
fn node(
    t0: Instant,
    stock: Stock,
    authority: u8,
    wrap: impl Fn(Box<dyn Endpoint>) -> Box<dyn Endpoint>,
) -> Node {
    let mut host = Host::new(1, 1, t0);
    let mut node = Node::new(
        NodeConfig {
            peers: vec![TESTER],
            ..NodeConfig::default()
        },
        t0,
    );
    let entry = jaus_node::host::Entry {
        authority,
        ..Host::entry(stock)
    };
    let built = host.build(&entry).expect("stock component builds");
    node.add_boxed(wrap(built)).expect("added");
    node
}

/// Runs the tester on `stock`'s component 1.1.<id>.1 hosted through `wrap`.
fn run(
    stock_id: u8,
    authority: u8,
    wrap: impl Fn(Box<dyn Endpoint>) -> Box<dyn Endpoint>,
) -> RunReport {
    let t0 = Instant::now();
    let stock = Stock::by_id(stock_id).expect("stock component");
    let node = node(t0, stock, authority, wrap);
    let voices = Voices::on(200, 1);
    let mut session = MemorySession::new(node, &voices, t0).expect("session");
    let spec = jaus_spec::load_sdk().expect("definitions");
    let target = Address::new(1, 1, stock_id, 1);
    let run = jaus_conform::run(&mut session, &spec, voices, &[target], Options::default());
    println!("{}", report::summary(&run));
    run
}

fn outcome<'r>(c: &'r ComponentReport, id: &str) -> &'r Outcome {
    c.outcomes
        .iter()
        .find(|o| o.check.id == id)
        .unwrap_or_else(|| panic!("{id} not planned"))
}

#[test]
fn outsider_checks_pass_when_the_controller_has_the_effect() {
    let run = run(45, 0, |e| e);
    let c = &run.components[0];
    for id in [
        "state.Standby.outsider",
        "state.Resume.outsider",
        "state.Reset.outsider",
        "state.Shutdown.outsider",
        "outsider.SetTravelSpeed",
    ] {
        let o = outcome(c, id);
        println!("{id}: {}", o.detail);
        assert_eq!(o.verdict, Verdict::Pass, "{id}: {}", o.detail);
        assert!(
            o.detail.contains("from the controller"),
            "{id}: {}",
            o.detail
        );
    }
    // The controller's Shutdown is never sent: Standby stands in for it, and the
    // component is left as found.
    assert!(outcome(c, "state.Shutdown.outsider")
        .detail
        .contains("Shutdown itself is not sent"));
    assert_eq!(outcome(c, "teardown.as-found").verdict, Verdict::Pass);
    assert!(run.passed());
}

#[test]
fn outsider_checks_are_inconclusive_when_the_controller_has_no_effect_either() {
    let run = run(45, 0, |e| {
        Box::new(Deaf {
            inner: e,
            codes: vec![STANDBY, SET_TRAVEL_SPEED],
        })
    });
    let c = &run.components[0];
    for (id, command) in [
        ("state.Standby.outsider", "Standby"),
        ("outsider.SetTravelSpeed", "SetTravelSpeed"),
    ] {
        let o = outcome(c, id);
        assert_eq!(o.verdict, Verdict::Inconclusive, "{id}: {}", o.detail);
        let reason =
            format!("the controller's own {command} had no effect either: nothing to compare");
        assert!(o.detail.contains(&reason), "{id}: {}", o.detail);
    }
    // What the controller could not do fails where it is checked.
    assert_eq!(
        outcome(c, "state.Standby.controller").verdict,
        Verdict::Fail
    );
    assert_eq!(outcome(c, "readback.SetTravelSpeed").verdict, Verdict::Fail);
    // Resume still has its comparison (the controller's Resume works, Standby is
    // reached by nothing: the check cannot set up).
    assert_ne!(outcome(c, "state.Resume.outsider").verdict, Verdict::Fail);
}

#[test]
fn a_read_back_whose_query_is_never_answered_is_inconclusive() {
    let run = run(45, 0, |e| Box::new(SilentQuery { inner: e }));
    let c = &run.components[0];
    let o = outcome(c, "readback.SetTravelSpeed");
    assert_eq!(o.verdict, Verdict::Inconclusive, "{}", o.detail);
    assert!(
        o.detail
            .contains("the read-back query QueryTravelSpeed was not answered"),
        "{}",
        o.detail
    );
    assert_eq!(c.required_failures(), 0);
    assert!(run.passed());
}

#[test]
fn a_request_below_the_components_authority_is_refused() {
    let run = run(45, 50, |e| e);
    let o = outcome(&run.components[0], "control.authority_below");
    assert_eq!(o.verdict, Verdict::Pass, "{}", o.detail);
    assert!(o.detail.contains("authority 49"), "{}", o.detail);
    assert_eq!(o.check.level, jaus_conform::Level::Required);
    assert!(run.passed());
}

#[test]
fn a_component_granting_control_below_its_authority_fails() {
    let run = run(45, 50, |e| Box::new(GrantsAnyone { inner: e, own: 50 }));
    let c = &run.components[0];
    let o = outcome(c, "control.authority_below");
    assert_eq!(o.verdict, Verdict::Fail, "{}", o.detail);
    assert!(
        o.detail.contains("below the component's own 50"),
        "{}",
        o.detail
    );
    let failed: Vec<&str> = c
        .outcomes
        .iter()
        .filter(|o| o.is_required_failure())
        .map(|o| o.check.id.as_str())
        .collect();
    assert_eq!(failed, vec!["control.authority_below"]);
}

#[test]
fn a_component_at_authority_zero_leaves_the_check_inconclusive() {
    let run = run(38, 0, |e| e);
    let o = outcome(&run.components[0], "control.authority_below");
    assert_eq!(o.verdict, Verdict::Inconclusive, "{}", o.detail);
    assert!(o.detail.contains("authority is 0"), "{}", o.detail);
}

#[test]
fn a_component_ignoring_release_fails_the_release_check() {
    // As OpenJAUS 3.3's Communicator: Release Component Control and Query Component
    // Control go unanswered and do nothing.
    for codes in [vec![RELEASE_CONTROL], vec![RELEASE_CONTROL, QUERY_CONTROL]] {
        let run = run(45, 0, |e| {
            Box::new(Deaf {
                inner: e,
                codes: codes.clone(),
            })
        });
        let o = outcome(&run.components[0], "control.release");
        assert_eq!(o.verdict, Verdict::Fail, "{codes:?}: {}", o.detail);
        assert!(
            o.detail.contains("still in control after its Release")
                || o.detail.contains("yet 200.1.40.1's request was refused"),
            "{}",
            o.detail
        );
    }
}
