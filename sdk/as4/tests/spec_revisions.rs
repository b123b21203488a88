//! The standard's own revisions through `jaus-gen diff` as our definitions hold them:
//! Core v1.0 → v1.1 (`revisions/core-v1.0/`, the first revision written as
//! `defs/core*.yaml` are, against `defs/core.yaml` and `defs/core_services.yaml`) and
//! Manipulator v1.0 → v2.0 (`revisions/manipulator-v1.0/` on `revisions/core-v1.0/`,
//! against `defs/manipulator*.yaml` on the Core v1.1 files). The classified outputs are
//! the golden files `revisions/core-v1.0-to-v1.1.txt` and
//! `revisions/manipulator-v1.0-to-v2.0.txt`, shown in docs/spec-revisions.md; after a
//! reviewed change of a revision,
//!
//! ```sh
//! UPDATE_GOLDEN=1 cargo test -p jaus-as4 --test spec_revisions
//! ```
//!
//! rewrites them.

use std::path::{Path, PathBuf};

use jaus_gen::diff::{diff, Change, ChangeKind, Diff, Severity};
use jaus_gen::revision;
use jaus_gen::snapshot::Snapshot;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

/// The revision of the files and directories `parts` (relative to the crate), loaded as
/// `jaus-gen diff` loads `A,B,...`.
fn load(parts: &[&str]) -> Snapshot {
    let arg: Vec<String> = parts
        .iter()
        .map(|p| root().join(p).display().to_string())
        .collect();
    let arg = arg.join(",");
    revision::load(&arg).unwrap_or_else(|e| panic!("{arg}: {e}"))
}

fn core_revisions() -> Diff {
    diff(
        &load(&["revisions/core-v1.0"]),
        &load(&["defs/core.yaml", "defs/core_services.yaml"]),
    )
}

/// Manipulator v1.0 → v2.0, each on the Core revision it is written on, whole: the
/// Manipulator's changes and the Core's.
fn manipulator_and_core_revisions() -> Diff {
    diff(
        &load(&["revisions/core-v1.0", "revisions/manipulator-v1.0"]),
        &load(&[
            "defs/core.yaml",
            "defs/core_services.yaml",
            "defs/manipulator.yaml",
            "defs/manipulator_services.yaml",
        ]),
    )
}

/// Whether a change is the Manipulator's: it has a position in a manipulator file, in
/// either revision (the List Manager, the set's own in v1.0, moves to the Core).
fn of_the_manipulator(c: &Change) -> bool {
    [&c.old, &c.new]
        .into_iter()
        .flatten()
        .any(|l| l.file.starts_with("manipulator"))
}

/// Manipulator v1.0 → v2.0 without the Core's own changes (the golden file above them).
fn manipulator_revisions() -> Diff {
    let mut d = manipulator_and_core_revisions();
    d.changes.retain(of_the_manipulator);
    d
}

/// Compares the text of `d` with the golden file `revisions/{name}`, or rewrites it
/// under `UPDATE_GOLDEN`.
fn assert_golden(d: &Diff, name: &str) {
    let text = d.to_text();
    let path = root().join("revisions").join(name);
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(&path, &text).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&path).unwrap_or_default();
    if expected != text {
        let d = similar::TextDiff::from_lines(expected.as_str(), text.as_str())
            .unified_diff()
            .header(&format!("revisions/{name}"), "produced")
            .to_string();
        panic!(
            "the diff differs from revisions/{name}; review, then run \
             `UPDATE_GOLDEN=1 cargo test -p jaus-as4 --test spec_revisions`:\n{d}"
        );
    }
}

#[test]
fn core_v1_0_to_v1_1_gives_the_golden_text() {
    assert_golden(&core_revisions(), "core-v1.0-to-v1.1.txt");
}

#[test]
fn manipulator_v1_0_to_v2_0_gives_the_golden_text() {
    assert_golden(&manipulator_revisions(), "manipulator-v1.0-to-v2.0.txt");
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

/// The paths of the changes of `d` of kind `kind`.
fn paths(d: &Diff, kind: ChangeKind) -> Vec<&str> {
    d.changes
        .iter()
        .filter(|c| c.kind == kind)
        .map(|c| c.path.as_str())
        .collect()
}

#[test]
fn manipulator_v2_0_splits_services_and_changes_one_report_on_the_wire() {
    let d = manipulator_revisions();
    // Nine services are new in v2.0: the specification, motion profile and tool offset
    // services v1.0's sensors and drivers did the work of, the Manipulator List Driver,
    // and three drivers under new names.
    let mut added = paths(&d, ChangeKind::ServiceAdded);
    added.sort_unstable();
    assert_eq!(
        added,
        [
            "ManipulatorJointMotionProfile",
            "ManipulatorJointPositionListDriver",
            "ManipulatorJointVelocityDriver",
            "ManipulatorListDriver",
            "ManipulatorSpecificationService",
            "ManipulatorToolOffsetService",
            "PanTiltJointVelocityDriver",
            "PanTiltMotionProfileService",
            "PanTiltSpecificationService",
        ]
    );
    // Their v1.0 names are gone (a new URI is not a rename), peers lose them.
    let mut removed = paths(&d, ChangeKind::ServiceRemoved);
    removed.sort_unstable();
    assert_eq!(
        removed,
        [
            "ManipulatorJointPositionsListDriver",
            "ManipulatorJointVelocitiesDriver",
            "PanTiltJointVelocitiesDriver",
        ]
    );
    // The set's List Manager becomes the Core's (another URI: wire-breaking); the pose
    // list driver inherits the new Manipulator List Driver instead.
    let find = |path: &str, kind: ChangeKind| {
        d.changes
            .iter()
            .find(|c| c.path == path && c.kind == kind)
            .unwrap_or_else(|| panic!("no {kind:?} of {path} in:\n{}", d.to_text()))
    };
    let lm = find("ListManager", ChangeKind::ServiceVersionChanged);
    assert_eq!(lm.severity, Severity::WireBreaking);
    assert!(
        lm.detail.contains("urn:jaus:jss:core:ListManager 1.1"),
        "{}",
        lm.detail
    );
    assert_eq!(lm.new.as_ref().unwrap().file, "core_services.yaml");
    let parent = find(
        "ManipulatorEndEffectorPoseListDriver",
        ChangeKind::ServiceParentChanged,
    );
    assert_eq!(parent.severity, Severity::WireBreaking);
    assert!(parent.detail.contains("ManipulatorListDriver 2.0"));
    // Every service kept moves to 2.0 (across a major version) and to Core v1.1.
    let versions = paths(&d, ChangeKind::ServiceVersionChanged);
    assert_eq!(
        versions.len(),
        17,
        "16 services and the List Manager: {versions:?}"
    );
    assert!(d
        .changes
        .iter()
        .filter(|c| c.kind == ChangeKind::ServiceVersionChanged)
        .all(|c| c.severity == Severity::WireBreaking));
    // Nineteen messages renamed (plural to singular, Motion Profile to Joint Motion
    // Profile), with their IDs: what breaks is the source.
    let renamed: Vec<&Change> = d
        .changes
        .iter()
        .filter(|c| c.kind == ChangeKind::MessageRenamed)
        .collect();
    assert_eq!(renamed.len(), 19, "{}", d.to_text());
    assert!(renamed
        .iter()
        .all(|c| c.severity == Severity::SourceBreaking));
    assert!(renamed
        .iter()
        .any(|c| c.path == "SetJointMotionProfile" && c.detail.contains("SetMotionProfile")));
    // On the wire, only Report Manipulator Specifications changes: bounding-cylinder
    // radii at the end of the four joint records (their bytes are followed by others),
    // and the joint names under a new presence bit at the end (compatible).
    let wire: Vec<&Change> = d
        .changes
        .iter()
        .filter(|c| c.severity == Severity::WireBreaking)
        .filter(|c| !c.path.contains('/') && !c.path.contains("::"))
        .filter(|c| !c.kind.as_str().starts_with("service-"))
        .collect();
    assert_eq!(wire.len(), 6, "{wire:#?}");
    for c in &wire {
        assert_eq!(c.kind, ChangeKind::FieldAdded);
        assert!(c.path.contains("_bounding_cylinder_radius"), "{}", c.path);
        assert_eq!(c.used_by, ["ReportManipulatorSpecifications"]);
    }
    let names = find(
        "ReportManipulatorSpecifications.joint_names",
        ChangeKind::FieldAdded,
    );
    assert_eq!(names.severity, Severity::Compatible);
    // No message comes or goes: the List Manager's ten move to the Core unchanged.
    assert!(paths(&d, ChangeKind::MessageAdded).is_empty());
    assert!(paths(&d, ChangeKind::MessageRemoved).is_empty());
}

#[test]
fn manipulator_v1_0_to_v2_0_leaves_out_only_the_cores_changes() {
    // What the Manipulator's golden file leaves out of the whole diff is the Core's own
    // v1.0 → v1.1, as its golden file holds it; what it keeps has its positions in the
    // YAML a vendor edits.
    let core = core_revisions();
    let whole = manipulator_and_core_revisions();
    let left_out: Vec<&Change> = whole
        .changes
        .iter()
        .filter(|c| !of_the_manipulator(c))
        .collect();
    assert!(!left_out.is_empty());
    for c in &left_out {
        assert!(core.changes.contains(c), "not a change of the Core: {c:?}");
    }
    // The Core's changes not among them: what the Manipulator set already had in v1.0,
    // the List Manager's service (here a change of the set's own), messages and types.
    let kinds: Vec<ChangeKind> = core
        .changes
        .iter()
        .filter(|c| !left_out.contains(c))
        .map(|c| c.kind)
        .collect();
    assert_eq!(kinds.len(), 14, "{kinds:?}");
    let count = |k: ChangeKind| kinds.iter().filter(|&&x| x == k).count();
    assert_eq!(count(ChangeKind::ServiceAdded), 1);
    assert_eq!(count(ChangeKind::MessageAdded), 10);
    assert_eq!(count(ChangeKind::TypeAdded), 3);
    for c in manipulator_revisions().changes {
        for l in [&c.old, &c.new].into_iter().flatten() {
            assert!(l.file.ends_with(".yaml") && l.line > 0, "{l:?}");
        }
    }
}
