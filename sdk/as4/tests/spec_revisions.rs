//! The standard's own revision, Core v1.0 → v1.1, through `jaus-gen diff` as our
//! definitions hold them: `revisions/core-v1.0/` (the first revision, written as
//! `defs/core*.yaml` are) against `defs/core.yaml` and `defs/core_services.yaml`. The
//! classified output is the golden file `revisions/core-v1.0-to-v1.1.txt`, shown in
//! docs/spec-revisions.md; after a reviewed change of either revision,
//!
//! ```sh
//! UPDATE_GOLDEN=1 cargo test -p jaus-as4 --test spec_revisions
//! ```
//!
//! rewrites it.

use std::path::{Path, PathBuf};

use jaus_gen::diff::{diff, ChangeKind, Diff, Severity};
use jaus_gen::revision;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn core_revisions() -> Diff {
    let old = root().join("revisions/core-v1.0");
    let new = format!(
        "{},{}",
        root().join("defs/core.yaml").display(),
        root().join("defs/core_services.yaml").display()
    );
    let load = |r: &str| revision::load(r).unwrap_or_else(|e| panic!("{r}: {e}"));
    diff(&load(&old.display().to_string()), &load(&new))
}

#[test]
fn core_v1_0_to_v1_1_gives_the_golden_text() {
    let text = core_revisions().to_text();
    let path = root().join("revisions/core-v1.0-to-v1.1.txt");
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(&path, &text).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&path).unwrap_or_default();
    if expected != text {
        let d = similar::TextDiff::from_lines(expected.as_str(), text.as_str())
            .unified_diff()
            .header("revisions/core-v1.0-to-v1.1.txt", "produced")
            .to_string();
        panic!(
            "the diff differs from revisions/core-v1.0-to-v1.1.txt; review, then run \
             `UPDATE_GOLDEN=1 cargo test -p jaus-as4 --test spec_revisions`:\n{d}"
        );
    }
}

#[test]
fn core_v1_1_adds_messages_and_changes_none_on_the_wire() {
    let d = core_revisions();
    let added: Vec<&str> = d
        .changes
        .iter()
        .filter(|c| c.kind == ChangeKind::MessageAdded)
        .map(|c| c.path.as_str())
        .collect();
    assert_eq!(added.len(), 16, "{added:?}");
    for m in [
        "CreateCommandEvent",
        "CommandEvent",
        "SetElement",
        "QueryServiceList",
    ] {
        assert!(added.contains(&m), "{m} added: {added:?}");
    }
    // What breaks the wire is in the services (paths with a state or a method) and the
    // service v1.1 dropped; no message or type of both revisions changed.
    let wire: Vec<&str> = d
        .changes
        .iter()
        .filter(|c| c.severity == Severity::WireBreaking)
        .map(|c| c.path.as_str())
        .filter(|p| !p.contains('/') && !p.contains("::"))
        .collect();
    assert_eq!(wire, ["Liveliness"], "wire-breaking outside the machines");
}

#[test]
fn core_v1_1_services_changes_are_classified_where_a_vendor_meets_them() {
    let d = core_revisions();
    let find = |path: &str, kind: ChangeKind| {
        d.changes
            .iter()
            .find(|c| c.path == path && c.kind == kind)
            .unwrap_or_else(|| panic!("no {kind:?} of {path} in:\n{}", d.to_text()))
    };
    // A guard gone from the trait breaks an impl that defines it (E0407).
    let gone = find(
        "AccessControl::is_control_available",
        ChangeKind::ServiceMethodRemoved,
    );
    assert_eq!(gone.severity, Severity::SourceBreaking);
    // The command events' guard and action are new trait methods (E0046).
    for m in [
        "Events::is_command_supported",
        "Events::create_command_event",
    ] {
        assert_eq!(
            find(m, ChangeKind::ServiceMethodAdded).severity,
            Severity::SourceBreaking
        );
    }
    // The List Manager is a new service; the Set Authority guard lost isControlAvailable.
    assert_eq!(
        find("ListManager", ChangeKind::ServiceAdded).severity,
        Severity::Compatible
    );
    assert!(d
        .changes
        .iter()
        .any(|c| c.kind == ChangeKind::ServiceGuardChanged
            && c.detail.contains("isControlAvailable")));
    // Each position is a line of the YAML file the vendor edits.
    for c in &d.changes {
        for l in [&c.old, &c.new].into_iter().flatten() {
            assert!(l.file.ends_with(".yaml") && l.line > 0, "{l:?}");
        }
    }
}
