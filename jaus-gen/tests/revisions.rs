//! A vendor's revisions, as a vendor trial met them (issue 29 items 3-5), on the overlay
//! fixtures of `tests/diff/tractor-*` (a tractor crate from `jaus-gen new`: experimental
//! messages reusing the SDK's `TimeStamp`, an implement controller):
//!
//! * an overlay alone is a revision: it is read on the SDK's definitions, its own items
//!   are compared, and its lock file compares like with like;
//! * a scaling change says what an old peer's value becomes;
//! * every revision the diff calls compatible has its generated code here as a golden
//!   file (`tests/diff/code/`), which `tests/tests/revision_compile.rs` of the workspace
//!   compiles together with vendor code written against the older revision;
//! * a fresh scaffold's definitions change freely until the vendor pins the lock.
//!
//! `UPDATE_GOLDEN=1 cargo test -p jaus-gen --test revisions` rewrites the golden files
//! (`tractor-1-2.txt`, `tractor-2-3.txt`, `code/*.rs`) after a reviewed change.

use jaus_gen::diff::{diff, ChangeKind, Diff, Severity};
use jaus_gen::scaffold::NewCrate;
use jaus_gen::{lock, revision, Builder, Error, LockState};
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

mod common;
use common::{dir, golden};

/// The overlay file of a tractor revision.
fn tractor(n: u32) -> PathBuf {
    dir().join(format!("tractor-{n}/my_tractor.yaml"))
}

fn load(p: &Path) -> jaus_gen::snapshot::Snapshot {
    revision::load(&p.display().to_string()).unwrap_or_else(|e| panic!("{e}"))
}

/// Revision pairs the diff calls compatible: the older revision's vendor code
/// (`code/OLD.vendor.rs`) compiles against the newer one's generated code.
const COMPATIBLE: &[(&str, &str)] = &[("old", "compatible"), ("tractor-1", "tractor-2")];
/// Revision pairs that break something (not compiled against old code).
const BREAKING: &[(&str, &str)] = &[("old", "new"), ("tractor-2", "tractor-3")];

fn rev(name: &str) -> jaus_gen::snapshot::Snapshot {
    load(&dir().join(name))
}

#[test]
fn an_overlay_alone_is_read_on_the_sdk_definitions() {
    // The wall: read as a set of its own, the overlay does not load.
    let alone = jaus_spec::load_dirs(&[dir().join("tractor-1")]).unwrap_err();
    assert!(
        alone.to_string().contains("unknown type `TimeStamp`"),
        "{alone}"
    );
    // As a revision it is an overlay: the SDK's TimeStamp resolves, and only its own
    // items are in it.
    let one = load(&tractor(1));
    let names: Vec<&str> = one.messages.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "SetImplementDepth",
            "ReportImplementState",
            "SetImplementMode"
        ]
    );
    assert_eq!(one.types.len(), 2);
    assert_eq!(one.components.len(), 2);
    // A directory holding only the overlay reads the same.
    assert_eq!(
        diff(&one, &rev("tractor-1")).to_text(),
        "no change\n",
        "directory"
    );
    // The diff lists the overlay's own changes, nothing of the SDK's.
    let d = diff(&one, &load(&tractor(2)));
    golden("tractor-1-2.txt", &d.to_text());
    assert_eq!(d.worst(), Some(Severity::Compatible));
    assert!(d.changes.iter().all(|c| [c.old.as_ref(), c.new.as_ref()]
        .into_iter()
        .flatten()
        .all(|l| l.file == "my_tractor.yaml")));
}

#[test]
fn the_lock_of_an_overlay_compares_like_with_like() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("jaus-gen-overlay-lock");
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).unwrap();
    let path = tmp.join("my_tractor.lock");
    // The lock a vendor's build pins (an overlay: its own items only).
    let g = Builder::new()
        .emit_rerun_if_changed(false)
        .overlay(tractor(1))
        .lock(&path)
        .update_lock(true)
        .render()
        .unwrap();
    assert_eq!(g.lock, LockState::Written);
    let pinned = load(&path);
    assert_eq!(pinned.messages.len(), 3);
    // Lock against the overlay alone: the same changes as overlay against overlay.
    let key = |d: &Diff| -> Vec<(ChangeKind, Severity, String, String)> {
        let mut v: Vec<_> = d
            .changes
            .iter()
            .map(|c| (c.kind, c.severity, c.path.clone(), c.detail.clone()))
            .collect();
        v.sort();
        v
    };
    let two = load(&tractor(2));
    assert_eq!(
        key(&diff(&pinned, &two)),
        key(&diff(&load(&tractor(1)), &two))
    );
    assert!(diff(&pinned, &load(&tractor(1))).changes.is_empty());
}

#[test]
fn a_scale_change_says_what_an_old_peers_value_becomes() {
    let d = diff(&load(&tractor(2)), &load(&tractor(3)));
    golden("tractor-2-3.txt", &d.to_text());
    let c = d
        .changes
        .iter()
        .find(|c| c.path == "ReportImplementState.depth")
        .unwrap();
    assert_eq!(
        (c.kind, c.severity),
        (ChangeKind::FieldScaleChanged, Severity::WireBreaking)
    );
    assert_eq!(
        c.detail,
        "scale [0, 1.5] → [0, 2]: an old peer's 1 m arrives as 1.333 m; \
         a new peer's 1 m arrives at an old peer as 0.75 m"
    );
}

/// The YAML files of a revision directory, in name order.
fn yaml_files(name: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir().join(name))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "yaml"))
        .collect();
    files.sort();
    files
}

/// The code a vendor's build generates from a revision (each YAML file as an overlay,
/// as `Builder::overlay` reads it: on the SDK's definitions unless `extends: none`).
fn generate(name: &str) -> jaus_gen::Generated {
    yaml_files(name)
        .iter()
        .fold(
            Builder::new()
                .emit_rerun_if_changed(false)
                .runtime_path("::jaus"),
            |b, f| b.overlay(f),
        )
        .render()
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn compatible_revisions_have_their_code_golden_for_the_compile_test() {
    for &(old, new) in COMPATIBLE {
        let d = diff(&rev(old), &rev(new));
        assert_eq!(
            d.worst(),
            Some(Severity::Compatible),
            "{old} → {new}:\n{}",
            d.to_text()
        );
    }
    for &(old, new) in BREAKING {
        assert!(diff(&rev(old), &rev(new)).worst() > Some(Severity::Compatible));
    }
    // Every revision of a compatible pair, old and new, has its code in `code/`.
    // A set of its own (`old`, `compatible`) has no components the workspace can compile
    // (they name the SDK's messages): its messages only.
    let mut expected = BTreeSet::new();
    for name in COMPATIBLE.iter().flat_map(|&(a, b)| [a, b]) {
        let g = generate(name);
        golden(&format!("code/{name}.messages.rs"), &g.code);
        expected.insert(format!("{name}.messages.rs"));
        let texts: Vec<(PathBuf, String)> = yaml_files(name)
            .into_iter()
            .map(|p| {
                let t = std::fs::read_to_string(&p).unwrap();
                (p, t)
            })
            .collect();
        if revision::own_set(&texts).is_none() {
            golden(&format!("code/{name}.components.rs"), &g.components);
            expected.insert(format!("{name}.components.rs"));
        }
    }
    if std::env::var_os("UPDATE_GOLDEN").is_none() {
        let present: BTreeSet<String> = std::fs::read_dir(dir().join("code"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|f| f.ends_with(".messages.rs") || f.ends_with(".components.rs"))
            .collect();
        assert_eq!(present, expected, "stale files in tests/diff/code");
    }
}

#[test]
fn the_compiled_pair_covers_every_kind_the_diff_can_call_compatible() {
    // Every kind some fixture pair classifies compatible...
    let mut compatible_kinds = BTreeSet::new();
    for &(old, new) in COMPATIBLE.iter().chain(BREAKING) {
        for c in diff(&rev(old), &rev(new)).changes {
            if c.severity == Severity::Compatible {
                compatible_kinds.insert(c.kind);
            }
        }
    }
    // ...is in the overlay pair whose components compile too.
    let covered: BTreeSet<ChangeKind> = diff(&rev("tractor-1"), &rev("tractor-2"))
        .changes
        .iter()
        .map(|c| c.kind)
        .collect();
    let missing: Vec<_> = compatible_kinds.difference(&covered).collect();
    assert!(
        missing.is_empty(),
        "not in tractor-1 → tractor-2: {missing:?}"
    );
    assert!(compatible_kinds.len() >= 10, "{compatible_kinds:?}");
}

/// A build of a scaffolded crate: its build script's `Builder`, in the crate.
fn build(root: &Path, update: bool) -> Result<LockState, Error> {
    Builder::new()
        .emit_rerun_if_changed(false)
        .overlay(root.join("defs/my_tractor.yaml"))
        .lock(root.join("defs/my_tractor.lock"))
        .update_lock(update)
        .render()
        .map(|g| g.lock)
}

#[test]
fn a_fresh_scaffold_is_edited_freely_until_its_lock_is_pinned() {
    let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("jaus-gen-new-my-tractor");
    let _ = std::fs::remove_dir_all(&root);
    NewCrate::new("my-tractor").write(&root).unwrap();
    let yaml = root.join("defs/my_tractor.yaml");
    let lock_path = root.join("defs/my_tractor.lock");
    // The example texts fit any crate: nothing says "vehicle" of a tractor.
    let text = std::fs::read_to_string(&yaml).unwrap();
    assert!(
        text.contains("description: Experimental messages and components of the my-tractor crate."),
        "{text}"
    );
    assert!(!text.contains("vehicle"), "{text}");

    // The first build pins nothing.
    assert_eq!(build(&root, false).unwrap(), LockState::Unpinned);
    assert!(!lock_path.exists());
    // The wall: replacing the example messages was four wire-breaking "removed" lines.
    // Now the vendor's first edit builds.
    std::fs::copy(tractor(1), &yaml).unwrap();
    assert_eq!(build(&root, false).unwrap(), LockState::Unpinned);
    assert!(!lock_path.exists());
    // The note the build prints under cargo names the command that pins it.
    let note = lock::unpinned_note(&lock_path);
    assert!(
        note.contains("not pinned yet") && note.contains("    JAUS_UPDATE_LOCK=1 cargo build"),
        "{note}"
    );

    // Pinned (`JAUS_UPDATE_LOCK=1 cargo build`), the layout is checked from then on.
    assert_eq!(build(&root, true).unwrap(), LockState::Written);
    assert_eq!(build(&root, false).unwrap(), LockState::Matches);
    std::fs::copy(tractor(2), &yaml).unwrap();
    std::fs::copy(tractor(3), &yaml).unwrap();
    let e = build(&root, false).unwrap_err().to_string();
    assert!(
        e.contains("my_tractor.lock: the wire layout of the definitions differs")
            && e.contains("SetImplementDepth.depth: scale [0, 1.5] → [0, 2]: an old peer's 1 m arrives as 1.333 m")
            && e.contains("    JAUS_UPDATE_LOCK=1 cargo build"),
        "{e}"
    );
    std::fs::remove_dir_all(&root).ok();
}

/// The binary, as the vendor ran it (built with `--features cli`).
#[cfg(feature = "cli")]
mod cli {
    use super::tractor;
    use std::path::Path;
    use std::process::Command;

    fn run(dir: &Path, args: &[&str]) -> (i32, String, String) {
        let out = Command::new(env!("CARGO_BIN_EXE_jaus-gen"))
            .args(args)
            .current_dir(dir)
            .output()
            .unwrap();
        (
            out.status.code().unwrap(),
            String::from_utf8(out.stdout).unwrap(),
            String::from_utf8(out.stderr).unwrap(),
        )
    }

    fn git(dir: &Path, args: &[&str]) {
        let ok = Command::new("git")
            .args(["-c", "user.name=t", "-c", "user.email=t@example.invalid"])
            .args(args)
            .current_dir(dir)
            .output()
            .unwrap()
            .status
            .success();
        assert!(ok, "git {args:?}");
    }

    /// `jaus-gen diff HEAD:defs/my_tractor.yaml defs/my_tractor.yaml` in a vendor's
    /// repository: the overlay alone, at a git revision and on disk.
    #[test]
    fn diff_and_lock_take_an_overlay_alone() {
        let repo = Path::new(env!("CARGO_TARGET_TMPDIR")).join("jaus-gen-overlay-repo");
        let _ = std::fs::remove_dir_all(&repo);
        std::fs::create_dir_all(repo.join("defs")).unwrap();
        let yaml = repo.join("defs/my_tractor.yaml");
        std::fs::copy(tractor(1), &yaml).unwrap();
        git(&repo, &["init", "-q"]);
        git(&repo, &["add", "."]);
        git(&repo, &["commit", "-q", "-m", "revision 1"]);
        std::fs::copy(tractor(2), &yaml).unwrap();

        let (code, out, err) = run(
            &repo,
            &["diff", "HEAD:defs/my_tractor.yaml", "defs/my_tractor.yaml"],
        );
        assert_eq!(code, 0, "{out}{err}");
        assert_eq!(
            out,
            std::fs::read_to_string(super::dir().join("tractor-1-2.txt")).unwrap()
        );
        let (code, out, _) = run(&repo, &["diff", "HEAD:defs", "defs"]);
        assert_eq!(code, 0);
        assert!(
            out.ends_with("14 change(s): 0 wire-breaking, 0 source-breaking, 14 compatible\n"),
            "{out}"
        );

        // The lock of the overlay alone: its own items, compared like with like.
        let (code, out, err) = run(
            &repo,
            &[
                "lock",
                "--overlay",
                "defs/my_tractor.yaml",
                "defs/my_tractor.lock",
            ],
        );
        assert_eq!(code, 0, "{out}{err}");
        let lock = std::fs::read_to_string(repo.join("defs/my_tractor.lock")).unwrap();
        assert_eq!(lock.matches("  - name: ").count(), 6 + 3 + 3, "{lock}");
        let (code, out, _) = run(
            &repo,
            &["lock", "--check", "--spec", "defs", "defs/my_tractor.lock"],
        );
        assert_eq!((code, out.as_str()), (0, "no change\n"));
        std::fs::copy(tractor(3), &yaml).unwrap();
        let (code, out, _) = run(
            &repo,
            &["diff", "defs/my_tractor.lock", "defs/my_tractor.yaml"],
        );
        assert_eq!(code, 1);
        assert!(
            out.ends_with("2 change(s): 2 wire-breaking, 0 source-breaking, 0 compatible\n"),
            "{out}"
        );
        std::fs::remove_dir_all(&repo).ok();
    }
}
