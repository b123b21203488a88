//! Snapshot tests of the generator: one tiny fixture per feature of the definition
//! language and of the component layer in `tests/golden/`, each with the code it must
//! generate next to it (`NAME.messages.rs`, and `NAME.components.rs` when it defines
//! components, `NAME.services.rs` when it defines services), compared byte for byte. A change to a template or to the generator
//! shows up here as a diff to review; after reviewing, rewrite the files with
//!
//! ```sh
//! UPDATE_GOLDEN=1 cargo test -p jaus-gen --test golden
//! ```
//!
//! A fixture is `NAME.yaml`, then any `NAME.*.yaml` (more groups) in name order.
//! It is generated for a crate depending on the SDK (`::jaus`) with serde on; a first
//! line `# jaus-gen: feature_gates` turns the feature gates on. The golden files also
//! compile: `tests/tests/golden_compile.rs` of the workspace includes every one.

use jaus_gen::Builder;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

/// Every fixture: its name and its YAML files in load order.
fn fixtures() -> BTreeMap<String, Vec<PathBuf>> {
    let mut all: Vec<PathBuf> = std::fs::read_dir(golden_dir())
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "yaml"))
        .collect();
    all.sort();
    let mut fixtures: BTreeMap<String, Vec<PathBuf>> = BTreeMap::new();
    for p in all {
        let file = p.file_name().unwrap().to_string_lossy().into_owned();
        let name = file.split('.').next().unwrap().to_string();
        let files = fixtures.entry(name.clone()).or_default();
        if file == format!("{name}.yaml") {
            files.insert(0, p);
        } else {
            files.push(p);
        }
    }
    fixtures
}

fn builder(files: &[PathBuf]) -> Builder {
    let main = std::fs::read_to_string(&files[0]).unwrap();
    let gates = main
        .lines()
        .next()
        .is_some_and(|l| l.trim() == "# jaus-gen: feature_gates");
    files.iter().fold(
        Builder::new()
            .emit_rerun_if_changed(false)
            .runtime_path("::jaus")
            .serde_cfg("all()")
            .feature_gates(gates),
        |b, f| b.overlay(f),
    )
}

/// Compares `generated` with the golden file at `path` (rewriting it under
/// `UPDATE_GOLDEN`); returns a unified diff when they differ.
fn check(path: &Path, generated: Option<&str>) -> Option<String> {
    let name = path.file_name().unwrap().to_string_lossy().into_owned();
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        match generated {
            Some(text) => std::fs::write(path, text).unwrap(),
            None => {
                let _ = std::fs::remove_file(path);
            }
        }
        return None;
    }
    let golden = std::fs::read_to_string(path).ok();
    if golden.as_deref() == generated {
        return None;
    }
    let (old, new) = (golden.as_deref().unwrap_or(""), generated.unwrap_or(""));
    let diff = similar::TextDiff::from_lines(old, new)
        .unified_diff()
        .context_radius(3)
        .header(&format!("golden/{name}"), "generated")
        .to_string();
    Some(diff)
}

#[test]
fn every_fixture_generates_its_golden_files() {
    let fixtures = fixtures();
    assert!(fixtures.len() >= 18, "{} fixtures", fixtures.len());
    let dir = golden_dir();
    let mut failures = Vec::new();
    for (name, files) in &fixtures {
        let g = builder(files)
            .render()
            .unwrap_or_else(|e| panic!("fixture {name}: {e}"));
        let components = (g.component_count > 0).then_some(g.components.as_str());
        let services = (g.service_count > 0).then_some(g.services.as_str());
        for (path, text) in [
            (
                dir.join(format!("{name}.messages.rs")),
                Some(g.code.as_str()),
            ),
            (dir.join(format!("{name}.components.rs")), components),
            (dir.join(format!("{name}.services.rs")), services),
        ] {
            failures.extend(check(&path, text));
        }
    }
    assert!(
        failures.is_empty(),
        "generated code differs from the golden files; review the diff, then run \
         `UPDATE_GOLDEN=1 cargo test -p jaus-gen --test golden`:\n\n{}",
        failures.join("\n")
    );
}

#[test]
fn no_golden_file_without_its_fixture() {
    let fixtures = fixtures();
    for e in std::fs::read_dir(golden_dir()).unwrap() {
        let file = e.unwrap().file_name().to_string_lossy().into_owned();
        let name = file.split('.').next().unwrap();
        assert!(
            fixtures.contains_key(name),
            "tests/golden/{file} belongs to no fixture"
        );
    }
}
