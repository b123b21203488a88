//! Profiles in a run: a memory session against a stock Global Waypoint Driver, planned
//! by a profile file of two checks (one at another level), and by `ra33-core`.

use std::time::Instant;

use jaus::net::{Node, NodeConfig};
use jaus::Address;
use jaus_conform::memory::{MemorySession, TESTER};
use jaus_conform::profile::{self, Profile, Selection};
use jaus_conform::session::Voices;
use jaus_conform::{report, Level, Options, RunReport};
use jaus_node::host::{Host, Stock};

/// The stock Global Waypoint Driver's id.
const GWD: u8 = 45;

/// The tester on 1.1.45.1 (a stock Global Waypoint Driver), planned by `sel`.
fn run(sel: &Selection) -> RunReport {
    let t0 = Instant::now();
    let mut host = Host::new(1, 1, t0);
    let mut node = Node::new(
        NodeConfig {
            peers: vec![TESTER],
            ..NodeConfig::default()
        },
        t0,
    );
    let stock = Stock::by_id(GWD).expect("stock component");
    let built = host
        .build(&Host::entry(stock))
        .expect("stock component builds");
    node.add_boxed(built).expect("added");
    let voices = Voices::on(200, 1);
    let mut session = MemorySession::new(node, &voices, t0).expect("session");
    let spec = jaus_spec::load_sdk().expect("definitions");
    let target = Address::new(1, 1, GWD, 1);
    let run = profile::run(
        &mut session,
        &spec,
        voices,
        &[target],
        Options::default(),
        sel,
    );
    println!("{}", report::summary(&run));
    run
}

fn select(p: &Profile) -> Selection {
    let spec = jaus_spec::load_sdk().expect("definitions");
    p.select(&jaus_conform::catalogue::catalogue(&spec))
        .expect("the profile's ids are known")
}

#[test]
fn a_profile_file_of_two_checks_runs_those_two_at_its_levels() {
    let path = std::env::temp_dir().join(format!("jaus-profile-{}.yaml", std::process::id()));
    std::fs::write(
        &path,
        "name: two-checks\n\
         description: Status and the grant, the grant advisory.\n\
         checks:\n  \
           - id: control.grant\n    \
             level: advisory\n  \
           - id: core.status\n",
    )
    .expect("profile written");
    let p = Profile::load(&path).expect("profile loads");
    let _ = std::fs::remove_file(&path);
    let sel = select(&p);
    assert_eq!(sel.ids, ["core.status", "control.grant"]);
    let run = run(&sel);
    let c = &run.components[0];
    let got: Vec<(&str, Level)> = c
        .outcomes
        .iter()
        .map(|o| (o.check.id.as_str(), o.check.level))
        .collect();
    // The plan's order; control.grant (required in the catalogue) at the profile's
    // level; the teardown ran but is not reported (not selected).
    assert_eq!(
        got,
        [
            ("core.status", Level::Required),
            ("control.grant", Level::Advisory)
        ]
    );
    assert!(run.passed(), "{}", report::summary(&run));
    // The report says which profile ran.
    assert!(run.tool.ends_with(", profile two-checks"), "{}", run.tool);
    assert!(report::json(&run).contains("profile two-checks"));
    assert!(report::html(&run).contains("profile two-checks"));
}

#[test]
fn ra33_core_runs_the_core_checks_and_the_teardown() {
    let sel = select(&Profile::builtin("ra33-core").expect("built in"));
    let run = run(&sel);
    let c = &run.components[0];
    assert!(c.outcomes.iter().all(|o| sel.selects(&o.check.id)));
    for id in [
        "core.identification",
        "control.authority_below",
        "robust.truncated",
    ] {
        assert!(c.outcomes.iter().any(|o| o.check.id == id), "{id} missing");
    }
    // The driver's own checks are not planned.
    assert!(!c
        .outcomes
        .iter()
        .any(|o| o.check.id.starts_with("query.") || o.check.id == "readback.SetTravelSpeed"));
    // The teardown, reported, cites the rule the catalogue lists for it.
    let teardown = c
        .outcomes
        .iter()
        .find(|o| o.check.id == "teardown.as-found")
        .expect("teardown reported");
    assert_eq!(teardown.check.rule, jaus_conform::plan::rules::TEARDOWN);
    assert_eq!(c.required_failures(), 0, "{}", report::summary(&run));
}
