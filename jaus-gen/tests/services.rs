//! Generated AS-4 services: the access-control fixture of `tests/services/access/`
//! (JSIDL written for these tests) imported and generated, compared with
//! `tests/services/access.{messages,services}.rs` (which the workspace's
//! `tests/tests/services.rs` compiles and drives), and the generator's errors. After
//! reviewing a change, rewrite the golden files with
//!
//! ```sh
//! UPDATE_GOLDEN=1 cargo test -p jaus-gen --test services
//! ```

use jaus_gen::Builder;
use std::path::{Path, PathBuf};

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/services")
}

fn check(name: &str, text: &str) {
    let path = dir().join(name);
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(&path, text).unwrap();
    }
    let golden = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        golden == text,
        "the generated code differs from {}: review, then run `UPDATE_GOLDEN=1 cargo test -p jaus-gen --test services`",
        path.display()
    );
}

#[test]
fn the_access_fixture_generates_its_golden_rust() {
    let g = Builder::new()
        .emit_rerun_if_changed(false)
        .runtime_path("::jaus")
        .serde_cfg("all()")
        .jsidl(dir().join("access"))
        .render()
        .unwrap();
    assert_eq!(g.service_count, 2);
    assert!(g.services.contains("pub trait Access: super::link::Link"));
    assert!(g
        .services
        .contains("fn rank_too_low(&self, msg: &AskForControl) -> bool;"));
    check("access.messages.rs", &g.code);
    check("access.services.rs", &g.services);
}

#[test]
fn a_delegated_service_is_inherited_on_a_second_implementation() {
    let g = Builder::new()
        .emit_rerun_if_changed(false)
        .runtime_path("::jaus")
        .serde_cfg("all()")
        .jsidl(dir().join("access"))
        .delegate_inherited("urn:test:access:Link")
        .render()
        .unwrap();
    // Both are generated; Access's trait holds only its own methods, and its machines
    // run the inherited guards and actions on an implementation of Link's trait.
    assert_eq!(g.service_count, 2);
    assert!(g.services.contains("pub trait Link {"), "{}", g.services);
    assert!(g.services.contains("pub trait Access {"));
    assert!(!g.services.contains("pub trait Access: super::link::Link"));
    assert!(g.services.contains("B: super::link::Link + ?Sized"));
    assert!(g.services.contains("inherited: &mut B"));
    // The undelegated rendering is unchanged (the golden test above).
}

/// Writes `yaml` as a one-file definition set and renders it.
fn render(name: &str, yaml: &str) -> Result<jaus_gen::Generated, jaus_gen::Error> {
    let tmp = std::env::temp_dir().join(format!("jaus-gen-services-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    let file = tmp.join(format!("{name}.yaml"));
    std::fs::write(&file, yaml).unwrap();
    let r = Builder::new()
        .emit_rerun_if_changed(false)
        .overlay(&file)
        .render();
    let _ = std::fs::remove_dir_all(&tmp);
    r
}

const ONE: &str = "extends: none
group: g
services:
  - name: Solo
    id: urn:test:Solo
    version: '1.0'
    events: [{ name: Go }]
    behaviour:
      machines:
        - name: M
          states:
            - name: A
              transitions:
                - on: Go
                  guard: { condition: \"ready() && \" }
                  to: A
";

#[test]
fn a_guard_that_does_not_parse_names_service_transition_and_line() {
    let e = render("guard", ONE).unwrap_err().to_string();
    assert!(matches!(
        render("guard", ONE),
        Err(jaus_gen::Error::Services(_))
    ));
    assert!(e.contains("guard.yaml:15"), "{e}");
    assert!(e.contains("service `Solo`, transition `Go`"), "{e}");
    assert!(e.contains("ends early"), "{e}");
}

#[test]
fn a_parent_outside_the_definitions_is_an_error() {
    let yaml = ONE.replace("ready() && ", "ready()").replace(
        "    events:",
        "    inherits: { name: up, id: 'urn:test:Up', version: '2.0' }\n    events:",
    );
    let e = render("parent", &yaml).unwrap_err().to_string();
    assert!(e.contains("parent.yaml:7"), "{e}");
    assert!(
        e.contains(
            "service `Solo` inherits `urn:test:Up` version 2.0, which is not among the definitions"
        ),
        "{e}"
    );
}

#[test]
fn a_target_that_is_no_state_is_an_error() {
    let yaml = ONE
        .replace("ready() && ", "ready()")
        .replace("to: A", "to: B");
    // jaus-spec's validation already refuses it, naming the file and line.
    let e = render("target", &yaml).unwrap_err().to_string();
    assert!(e.contains("`B` is not a state of machine `M`"), "{e}");
}

/// A guard of the name of an inherited guard but with another message is the
/// service's own, called through its trait (both traits declare the name); with the
/// inherited guard's message it is the inherited one. The workspace's
/// `tests/tests/services.rs` compiles the golden files and drives them.
#[test]
fn a_guard_named_as_an_inherited_one_with_another_message_is_the_services_own() {
    let g = Builder::new()
        .emit_rerun_if_changed(false)
        .runtime_path("::jaus")
        .serde_cfg("all()")
        .overlay(dir().join("shadow/shadow.yaml"))
        .render()
        .unwrap();
    let s = &g.services;
    assert!(s.contains("pub trait Dimmer: super::switch::Switch"), "{s}");
    assert!(
        s.contains("fn is_allowed(&self, msg: &SwitchOn) -> bool;"),
        "{s}"
    );
    assert!(
        s.contains("fn is_allowed(&self, msg: &SetLevel) -> bool;"),
        "{s}"
    );
    assert!(
        s.contains("super::dimmer::Dimmer::is_allowed(&*self.0, msg)"),
        "{s}"
    );
    assert!(
        s.contains("super::switch::Switch::is_allowed(&*self.0, msg)"),
        "{s}"
    );
    check("shadow.messages.rs", &g.code);
    check("shadow.services.rs", &g.services);
}
