//! Service revisions (issue 45 item 5): `jaus_gen::diff` and the lock file on the
//! dimmer fixtures of `tests/fixtures/services/`, written for these tests (a base
//! service `Link` and a `Dimmer` inheriting it):
//!
//! * `jsidl-a` → `jsidl-b` (JSIDL) and `yaml-a` → `yaml-b` (the same revisions in YAML,
//!   plus a renamed state): a guard added to one transition, a guard removed from
//!   another and its action changed, a new state, a new guarded transition;
//! * `yaml-b` → `yaml-c`: a new version, a state removed, transitions moved, retargeted
//!   and triggered otherwise, entry actions, a method's signature, a new service.
//!
//! The text output of each pair and the lock file of `jsidl-a` are golden files next to
//! the fixtures; after a reviewed change,
//!
//! ```sh
//! UPDATE_GOLDEN=1 cargo test -p jaus-gen --test service_diff
//! ```
//!
//! rewrites them.

mod common;

use jaus_gen::diff::{diff, ChangeKind, Diff, Severity};
use jaus_gen::snapshot::Snapshot;
use jaus_gen::{lock, revision, Builder, Error, LockState};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/services")
}

fn golden(name: &str, text: &str) {
    common::golden_in(
        &dir(),
        "tests/fixtures/services",
        "--test service_diff",
        name,
        text,
    );
}

fn rev(name: &str) -> Snapshot {
    revision::load(&dir().join(name).display().to_string()).unwrap_or_else(|e| panic!("{e}"))
}

fn pair(a: &str, b: &str) -> Diff {
    diff(&rev(a), &rev(b))
}

fn kinds(d: &Diff) -> BTreeSet<ChangeKind> {
    d.changes.iter().map(|c| c.kind).collect()
}

#[test]
fn jsidl_revisions_give_the_golden_text_with_positions_in_the_xml() {
    let d = pair("jsidl-a", "jsidl-b");
    golden("jsidl-a-b.txt", &d.to_text());
    // Every position is in a JSIDL file the vendor edits, never in imported YAML.
    for c in &d.changes {
        for l in [&c.old, &c.new].into_iter().flatten() {
            assert!(l.file.ends_with(".xml"), "{c:?}");
        }
    }
    // The new guard `isWarm()` is written on line 29 of the new Dimmer.xml (in its
    // transition, line 29), the transition it guards was on line 28 of the old one.
    let warm = d
        .changes
        .iter()
        .find(|c| c.kind == ChangeKind::ServiceGuardChanged && c.detail.contains("isWarm"))
        .unwrap();
    let (o, n) = (warm.old.as_ref().unwrap(), warm.new.as_ref().unwrap());
    assert_eq!((o.file.as_str(), o.line), ("Dimmer.xml", 28));
    assert_eq!((n.file.as_str(), n.line), ("Dimmer.xml", 29));
}

#[test]
fn yaml_revisions_give_the_golden_text() {
    golden("yaml-a-b.txt", &pair("yaml-a", "yaml-b").to_text());
    golden("yaml-b-c.txt", &pair("yaml-b", "yaml-c").to_text());
}

#[test]
fn jsidl_and_yaml_of_the_same_revisions_give_the_same_changes() {
    let key = |d: &Diff| -> Vec<(ChangeKind, Severity, String, String)> {
        let mut v: Vec<_> = d
            .changes
            .iter()
            .filter(|c| c.kind != ChangeKind::ServiceStateRenamed)
            .map(|c| (c.kind, c.severity, c.path.clone(), c.detail.clone()))
            .collect();
        v.sort();
        v
    };
    // yaml-b renames state Off (its only other change).
    let y = pair("yaml-a", "yaml-b");
    assert!(kinds(&y).contains(&ChangeKind::ServiceStateRenamed));
    assert_eq!(key(&pair("jsidl-a", "jsidl-b")), key(&y));
}

#[test]
fn new_guards_and_actions_break_a_vendors_trait_impl_and_removed_ones_are_changes() {
    let d = pair("jsidl-a", "jsidl-b");
    let methods: Vec<(ChangeKind, Severity, &str)> = d
        .changes
        .iter()
        .filter(|c| c.path.contains("::"))
        .map(|c| (c.kind, c.severity, c.path.as_str()))
        .collect();
    use ChangeKind::*;
    use Severity::SourceBreaking;
    assert_eq!(
        methods,
        [
            (ServiceMethodAdded, SourceBreaking, "Dimmer::fade_level"),
            (ServiceMethodAdded, SourceBreaking, "Dimmer::is_busy"),
            (ServiceMethodRemoved, SourceBreaking, "Dimmer::is_in_range"),
            (ServiceMethodAdded, SourceBreaking, "Dimmer::is_warm"),
        ]
    );
    assert!(d.changes.iter().any(|c| c.detail.contains("E0046")));
    assert!(d.fails(Severity::Compatible));
}

#[test]
fn every_service_change_kind_is_covered() {
    let mut seen = kinds(&pair("yaml-a", "yaml-b"));
    seen.extend(kinds(&pair("yaml-b", "yaml-c")));
    // Renamed, reparented and removed services, on a snapshot edited here.
    let a = rev("yaml-a");
    let mut b = a.clone();
    let link = b.services.iter().position(|s| s.name == "Link").unwrap();
    b.services[link].name = "Wire".into();
    let dimmer = b.services.iter().position(|s| s.name == "Dimmer").unwrap();
    b.services[dimmer].inherits = Some("urn:test:dimmer:Other 1.0".into());
    let mut c = a.clone();
    c.services.retain(|s| s.name != "Link");
    let edited = [diff(&a, &b), diff(&a, &c)];
    for d in &edited {
        seen.extend(kinds(d));
    }
    let parent = edited[0]
        .changes
        .iter()
        .find(|c| c.kind == ChangeKind::ServiceParentChanged)
        .unwrap();
    assert_eq!(parent.severity, Severity::WireBreaking);
    let missing: Vec<&str> = ChangeKind::ALL
        .iter()
        .filter(|k| k.as_str().starts_with("service-") && !seen.contains(k))
        .map(|k| k.as_str())
        .collect();
    assert!(missing.is_empty(), "not covered: {missing:?}");
}

#[test]
fn the_lock_pins_services_and_reads_back() {
    let a = rev("jsidl-a");
    let text = lock::to_text(&a);
    golden("jsidl-a.lock", &text);
    let back = lock::parse(&text, "jsidl-a.lock").unwrap();
    assert!(diff(&back, &a).changes.is_empty());
    assert_eq!(lock::to_text(&back), text);
    // The lock of A against B: the same changes as A against B, old positions in the
    // lock file.
    let via = diff(&back, &rev("jsidl-b"));
    let key = |d: &Diff| -> Vec<(ChangeKind, String, String)> {
        let mut v: Vec<_> = d
            .changes
            .iter()
            .map(|c| (c.kind, c.path.clone(), c.detail.clone()))
            .collect();
        v.sort();
        v
    };
    assert_eq!(key(&via), key(&pair("jsidl-a", "jsidl-b")));
    assert!(via
        .changes
        .iter()
        .filter_map(|c| c.old.as_ref())
        .all(|l| l.file == "jsidl-a.lock"));
    let e = lock::parse(
        "version: 1\nservices:\n  - name: X\n    id: \"u\"\n    version: \"1\"\n    transitions:\n      - { state: \"M/S\", kind: jump }\n",
        "x.lock",
    )
    .unwrap_err();
    assert!(e.starts_with("x.lock:7:") && e.contains("`jump`"), "{e}");
}

#[test]
fn a_jsidl_build_lists_lock_changes_at_xml_lines() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("jaus-gen-service-lock");
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    let lock = tmp.join("dimmer.lock");
    let build = |rev: &str, update: bool| -> Result<LockState, Error> {
        Builder::new()
            .emit_rerun_if_changed(false)
            .jsidl(dir().join(rev))
            .lock(&lock)
            .update_lock(update)
            .render()
            .map(|g| g.lock)
    };
    assert_eq!(build("jsidl-a", true).unwrap(), LockState::Written);
    assert_eq!(build("jsidl-a", false).unwrap(), LockState::Matches);
    let msg = build("jsidl-b", false).unwrap_err().to_string();
    assert!(msg.contains("service-") || msg.contains("guard"), "{msg}");
    assert!(
        msg.contains("→ Dimmer.xml:29 ") && msg.contains("isWarm()"),
        "{msg}"
    );
    assert!(!msg.contains(".yaml"), "positions in imported YAML: {msg}");
}

/// The binary (built with `--features cli`).
#[cfg(feature = "cli")]
mod cli {
    use super::dir;
    use std::path::Path;
    use std::process::Command;

    fn run(args: &[&str]) -> (i32, String, String) {
        let out = Command::new(env!("CARGO_BIN_EXE_jaus-gen"))
            .args(args)
            .current_dir(dir())
            .output()
            .unwrap();
        (
            out.status.code().unwrap(),
            String::from_utf8(out.stdout).unwrap(),
            String::from_utf8(out.stderr).unwrap(),
        )
    }

    #[test]
    fn fail_on_compatible_fails_on_a_removed_guard() {
        // yaml-a with one guard call removed, nothing else.
        let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("jaus-gen-removed-guard");
        let _ = std::fs::remove_dir_all(&tmp);
        std::fs::create_dir_all(&tmp).unwrap();
        for f in ["dimmer.yaml", "link.yaml", "messages.yaml"] {
            let text = std::fs::read_to_string(dir().join("yaml-a").join(f)).unwrap();
            let text = text.replace("isAllowed(msg) && isInRange(msg)", "isAllowed(msg)");
            std::fs::write(tmp.join(f), text).unwrap();
        }
        let new = tmp.display().to_string();
        let (code, out, err) = run(&["diff", "yaml-a", &new, "--fail-on", "compatible"]);
        assert_eq!(code, 1, "{out}{err}");
        assert!(out.contains("Dimmer::is_in_range: guard"), "{out}");
        assert!(out.contains("2 change(s)"), "{out}");
        let (code, out, _) = run(&["diff", "yaml-a", "yaml-a", "--fail-on", "compatible"]);
        assert_eq!((code, out.as_str()), (0, "no change\n"));
    }

    #[test]
    fn diff_reads_jsidl_directories_and_lock_check_reports_a_guard() {
        let (code, out, _) = run(&["diff", "--jsidl", "jsidl-a", "jsidl-b"]);
        assert_eq!(code, 1);
        assert_eq!(
            out,
            std::fs::read_to_string(dir().join("jsidl-a-b.txt")).unwrap()
        );
        let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("jaus-gen-lock-check");
        let _ = std::fs::remove_dir_all(&tmp);
        std::fs::create_dir_all(&tmp).unwrap();
        let lock = tmp.join("dimmer.lock").display().to_string();
        let (code, _, err) = run(&["lock", "--spec", "jsidl-a", &lock]);
        assert_eq!(code, 0, "{err}");
        let (code, _, err) = run(&["lock", "--spec", "jsidl-a", &lock, "--check"]);
        assert_eq!(code, 0, "{err}");
        let (code, out, err) = run(&["lock", "--spec", "jsidl-b", &lock, "--check"]);
        assert_eq!(code, 1);
        assert!(
            out.contains("guard [isAllowed(msg) && isInRange(msg)] → [isAllowed(msg)]"),
            "{out}"
        );
        assert!(err.contains("differs from the definitions"), "{err}");
    }
}
