//! Shared by the tests of spec revisions (`diff.rs`, `revisions.rs`): the fixture
//! directory and its golden files; `service_diff.rs` uses the golden-file comparison
//! with fixtures of its own.

// Each test binary uses part of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// `tests/diff`: the revision fixtures and the golden files of their diffs and code.
pub fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/diff")
}

/// Compares `text` with the golden file `name` under [`dir`] (rewritten under
/// `UPDATE_GOLDEN`).
pub fn golden(name: &str, text: &str) {
    golden_in(
        &dir(),
        "tests/diff",
        "--test diff --test revisions",
        name,
        text,
    );
}

/// Compares `text` with the golden file `name` under `dir` (shown as `shown` in the
/// failure, which says to rerun with `UPDATE_GOLDEN=1 cargo test -p jaus-gen {tests}`);
/// rewritten under `UPDATE_GOLDEN`.
pub fn golden_in(dir: &Path, shown: &str, tests: &str, name: &str, text: &str) {
    let path = dir.join(name);
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent).unwrap();
        }
        std::fs::write(&path, text).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&path).unwrap_or_default();
    if expected != text {
        let d = similar::TextDiff::from_lines(expected.as_str(), text)
            .unified_diff()
            .header(&format!("{shown}/{name}"), "produced")
            .to_string();
        panic!(
            "output differs from {shown}/{name}; review, then run \
             `UPDATE_GOLDEN=1 cargo test -p jaus-gen {tests}`:\n{d}"
        );
    }
}
