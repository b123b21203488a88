//! Spec revisions: `jaus_gen::diff` on the fixture pair of `tests/diff/` (`old/` →
//! `new/`, every kind of change; `old/` → `compatible/`, compatible changes only), with
//! the expected text and JSON output as golden files compared byte for byte; the lock
//! file of `Builder::lock`; the exit status of `jaus-gen diff`. After a reviewed change
//! of the classifier or of the fixtures,
//!
//! ```sh
//! UPDATE_GOLDEN=1 cargo test -p jaus-gen --test diff
//! ```
//!
//! rewrites the golden files (`expected.txt`, `expected.json`, `compatible.txt`,
//! `old.lock`).

use jaus_gen::diff::{diff, ChangeKind, Diff, Severity};
use jaus_gen::snapshot::Snapshot;
use jaus_gen::{lock, revision, Builder, Error, LockState};
use std::collections::BTreeSet;
use std::path::Path;

mod common;
use common::{dir, golden};

fn snap(name: &str) -> Snapshot {
    let spec = jaus_spec::load_dirs(&[dir().join(name)]).unwrap_or_else(|e| panic!("{e}"));
    Snapshot::from_spec(&spec)
}

fn full() -> Diff {
    diff(&snap("old"), &snap("new"))
}

#[test]
fn full_pair_gives_the_golden_text_and_json() {
    let d = full();
    golden("expected.txt", &d.to_text());
    golden("expected.json", &d.to_json());
}

#[test]
fn compatible_pair_gives_the_golden_text() {
    golden(
        "compatible.txt",
        &diff(&snap("old"), &snap("compatible")).to_text(),
    );
}

#[test]
fn every_change_kind_and_severity_is_in_the_full_pair() {
    let d = full();
    let seen: BTreeSet<ChangeKind> = d.changes.iter().map(|c| c.kind).collect();
    // Service kinds are covered by the service fixtures (`tests/service_diff.rs`).
    let missing: Vec<&str> = ChangeKind::ALL
        .iter()
        .filter(|k| !seen.contains(k) && !k.as_str().starts_with("service-"))
        .map(|k| k.as_str())
        .collect();
    assert!(missing.is_empty(), "not covered by tests/diff: {missing:?}");
    // Kinds whose severity depends on the case appear at both levels.
    for kind in [
        ChangeKind::FieldAdded,
        ChangeKind::BitsAdded,
        ChangeKind::ComponentMessageMoved,
        ChangeKind::ComponentAnyMessageChanged,
    ] {
        let sevs: BTreeSet<Severity> = d
            .changes
            .iter()
            .filter(|c| c.kind == kind)
            .map(|c| c.severity)
            .collect();
        assert!(sevs.len() >= 2, "{kind}: {sevs:?}");
    }
}

#[test]
fn exit_status_is_0_for_compatible_changes_and_1_for_breaking_ones() {
    let compatible = diff(&snap("old"), &snap("compatible"));
    assert!(!compatible.changes.is_empty());
    assert_eq!(compatible.worst(), Some(Severity::Compatible));
    assert_eq!(compatible.exit_status(Severity::WireBreaking), 0);
    assert_eq!(compatible.exit_status(Severity::SourceBreaking), 0);
    assert_eq!(compatible.exit_status(Severity::Compatible), 1);
    let full = full();
    assert_eq!(full.worst(), Some(Severity::WireBreaking));
    assert_eq!(full.exit_status(Severity::WireBreaking), 1);
}

#[test]
fn a_shared_type_change_is_reported_once_with_its_users() {
    let d = full();
    let point: Vec<_> = d
        .changes
        .iter()
        .filter(|c| c.path.starts_with("Point"))
        .collect();
    assert_eq!(point.len(), 1, "{point:?}");
    assert_eq!(point[0].used_by, ["ReportPath", "ReportTarget"]);
    // The messages using it report nothing for it.
    assert!(!d
        .changes
        .iter()
        .any(|c| c.path.starts_with("ReportPath") || c.path.starts_with("ReportTarget")));
}

#[test]
fn changes_carry_positions_on_both_sides() {
    let d = full();
    let c = d
        .changes
        .iter()
        .find(|c| c.path == "SetTravelSpeed.speed")
        .unwrap();
    assert_eq!(c.kind, ChangeKind::FieldScaleChanged);
    let (old, new) = (c.old.as_ref().unwrap(), c.new.as_ref().unwrap());
    assert_eq!((old.file.as_str(), old.line), ("messages.yaml", 8));
    assert_eq!((new.file.as_str(), new.line), ("messages.yaml", 8));
    // What the change does to a value: 1 m/s is 7 counts of the old scale, 0.035 m/s of
    // the new one; the new 1 m/s is 200 counts, 30.52 m/s of the old scale.
    assert_eq!(
        c.detail,
        "scale [0, 10000] → [0, 327.67]: an old peer's 1 m/s arrives as 0.035 m/s; \
         a new peer's 1 m/s arrives at an old peer as 30.52 m/s"
    );
}

#[test]
fn the_sdk_definitions_against_themselves_give_no_change() {
    let spec = jaus_spec::load_dirs(&[jaus_spec::defs_dir()]).unwrap();
    let s = Snapshot::from_spec(&spec);
    let d = diff(&s, &s);
    assert!(d.changes.is_empty(), "{}", d.to_text());
    assert_eq!(d.exit_status(Severity::Compatible), 0);
    assert_eq!(d.to_text(), "no change\n");
    assert_eq!(d.to_json(), "[]\n");
    // Through the lock file too: it reads back to the same layout and the same text.
    let text = lock::to_text(&s);
    let back = lock::parse(&text, "jaus.lock").unwrap();
    assert!(diff(&back, &s).changes.is_empty());
    assert!(diff(&s, &back).changes.is_empty());
    assert_eq!(lock::to_text(&back), text);
}

#[test]
fn a_revision_is_a_directory_a_file_list_or_a_lock_file() {
    let d = dir();
    let files = ["messages.yaml", "types.yaml", "components.yaml"]
        .map(|f| d.join("new").join(f).display().to_string())
        .join(",");
    let a = revision::load(&d.join("old").display().to_string()).unwrap();
    let b = revision::load(&files).unwrap();
    assert_eq!(diff(&a, &b).to_text(), full().to_text());
    // The lock of OLD as the old side: the same changes, positions in the lock file.
    let from_lock = revision::load(&d.join("old.lock").display().to_string()).unwrap();
    let via_lock = diff(&from_lock, &b);
    let key = |d: &Diff| -> Vec<(ChangeKind, Severity, String, String)> {
        d.changes
            .iter()
            .map(|c| (c.kind, c.severity, c.path.clone(), c.detail.clone()))
            .collect()
    };
    let (mut x, mut y) = (key(&via_lock), key(&full()));
    x.sort();
    y.sort();
    assert_eq!(x, y);
    assert!(via_lock
        .changes
        .iter()
        .filter_map(|c| c.old.as_ref())
        .all(|l| l.file == "old.lock"));
}

#[test]
fn a_git_revision_is_read_with_git() {
    // The definitions as committed at HEAD (the working tree may differ).
    let s = revision::load("HEAD:jaus-spec/defs").unwrap_or_else(|e| panic!("{e}"));
    assert!(s.messages.len() >= 150, "{}", s.messages.len());
    assert!(s.messages.iter().all(|m| m.at.file.ends_with(".yaml")));
    let e = revision::load("HEAD:no/such/dir").unwrap_err().to_string();
    assert!(e.contains("HEAD:no/such/dir") && e.contains("git"), "{e}");
    let e = revision::load("no-such-dir").unwrap_err().to_string();
    assert!(e.contains("no such file or directory"), "{e}");
}

#[test]
fn the_lock_file_of_old_is_golden() {
    golden("old.lock", &lock::to_text(&snap("old")));
}

#[test]
fn a_malformed_lock_file_is_an_error_with_its_line() {
    let text = "version: 1\nmessages:\n  - name: X\n    code: 0x0D01\n    fields:\n      - { name: a, wire: \"u9\" }\n";
    let e = lock::parse(text, "x.lock").unwrap_err();
    assert!(e.starts_with("x.lock:6:"), "{e}");
    assert!(e.contains("`u9` is not a wire form"), "{e}");
    let e = lock::parse("version: 2\n", "x.lock").unwrap_err();
    assert!(
        e.starts_with("x.lock:1:") && e.contains("JAUS_UPDATE_LOCK=1"),
        "{e}"
    );
    let e = lock::parse("versoin: 1\n", "x.lock").unwrap_err();
    assert!(
        e.starts_with("x.lock:1:") && e.contains("unknown field"),
        "{e}"
    );
}

fn build(spec: &str, lock: &Path, update: bool) -> Result<LockState, Error> {
    Builder::new()
        .emit_rerun_if_changed(false)
        .spec_dir(dir().join(spec))
        .lock(lock)
        .update_lock(update)
        .render()
        .map(|g| g.lock)
}

#[test]
fn a_build_fails_on_a_layout_that_differs_from_its_lock_until_it_is_updated() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("jaus-gen-lock");
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    let lock = tmp.join("jaus.lock");

    // No lock file: nothing is pinned, nothing is checked, nothing is written.
    assert_eq!(build("old", &lock, false).unwrap(), LockState::Unpinned);
    assert_eq!(build("new", &lock, false).unwrap(), LockState::Unpinned);
    assert!(!lock.exists());
    // Pinning (`JAUS_UPDATE_LOCK=1 cargo build`) writes it.
    assert_eq!(build("old", &lock, true).unwrap(), LockState::Written);
    let written = std::fs::read_to_string(&lock).unwrap();
    assert_eq!(written, lock::to_text(&snap("old")));
    // Same layout: nothing to do.
    assert_eq!(build("old", &lock, false).unwrap(), LockState::Matches);

    // A breaking revision fails, naming the change with both positions and the command.
    let e = build("new", &lock, false).unwrap_err();
    assert!(matches!(e, Error::Lock(_)), "{e:?}");
    let msg = e.to_string();
    assert!(
        msg.contains("jaus.lock: the wire layout of the definitions differs"),
        "{msg}"
    );
    assert!(
        msg.contains("wire-breaking")
            && msg.contains("→ messages.yaml:8 ")
            && msg.contains("SetTravelSpeed.speed: scale [0, 10000] → [0, 327.67]"),
        "{msg}"
    );
    assert!(msg.contains("    JAUS_UPDATE_LOCK=1 cargo build"), "{msg}");
    assert_eq!(
        std::fs::read_to_string(&lock).unwrap(),
        written,
        "left alone"
    );

    // Compatible changes fail too: the lock always holds the layout built from.
    let msg = build("compatible", &lock, false).unwrap_err().to_string();
    assert!(
        msg.contains("compatible") && !msg.contains("wire-breaking  "),
        "{msg}"
    );

    // After the update the build passes, and the lock holds the new layout.
    build("new", &lock, true).unwrap();
    assert_eq!(
        std::fs::read_to_string(&lock).unwrap(),
        lock::to_text(&snap("new"))
    );
    build("new", &lock, false).unwrap();

    // Comments and formatting of the lock file are not its layout.
    let edited = format!(
        "# reviewed in PR 12\n{}",
        std::fs::read_to_string(&lock).unwrap()
    );
    std::fs::write(&lock, &edited).unwrap();
    build("new", &lock, false).unwrap();
    assert_eq!(std::fs::read_to_string(&lock).unwrap(), edited);
}

/// The binary's exit status and output (built with `--features cli`).
#[cfg(feature = "cli")]
mod cli {
    use super::dir;
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
    fn diff_exits_0_1_or_2() {
        let (code, out, _) = run(&["diff", "old", "compatible"]);
        assert_eq!(code, 0, "{out}");
        assert_eq!(
            out,
            std::fs::read_to_string(dir().join("compatible.txt")).unwrap()
        );
        let (code, _, _) = run(&["diff", "old", "compatible", "--fail-on", "compatible"]);
        assert_eq!(code, 1);
        let (code, out, _) = run(&["diff", "old", "new"]);
        assert_eq!(code, 1);
        assert_eq!(
            out,
            std::fs::read_to_string(dir().join("expected.txt")).unwrap()
        );
        let (code, out, _) = run(&["diff", "old", "new", "--format", "json"]);
        assert_eq!(code, 1);
        assert_eq!(
            out,
            std::fs::read_to_string(dir().join("expected.json")).unwrap()
        );
        let (code, _, err) = run(&["diff", "old", "missing"]);
        assert_eq!(code, 2);
        assert!(err.contains("missing: no such file or directory"), "{err}");
        let (code, _, _) = run(&["diff", "old"]);
        assert_eq!(code, 2, "usage error");
    }

    #[test]
    fn diff_of_a_git_revision_outside_a_repository_says_so() {
        let tmp = std::env::temp_dir();
        let out = Command::new(env!("CARGO_BIN_EXE_jaus-gen"))
            .args(["diff", "HEAD:defs", "HEAD:defs"])
            .current_dir(&tmp)
            .output()
            .unwrap();
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(2));
        assert!(err.contains("not in a git repository"), "{err}");
    }
}
