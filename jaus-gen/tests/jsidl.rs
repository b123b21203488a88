//! JSIDL end to end: every JSIDL fixture of jaus-jsidl imported at once through
//! `Builder::jsidl`, the Rust generated from it compared with `tests/jsidl/
//! fixtures.messages.rs` (which `tests/tests/jsidl_compile.rs` of the workspace
//! compiles against the SDK), and `jaus-gen diff` between two imports. After reviewing
//! a change, rewrite the golden file with
//!
//! ```sh
//! UPDATE_GOLDEN=1 cargo test -p jaus-gen --test jsidl
//! ```

use jaus_gen::Builder;
use std::path::{Path, PathBuf};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../jaus-jsidl/tests/fixtures/ok")
}

fn fixture_dirs() -> Vec<PathBuf> {
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(fixtures())
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    dirs.sort();
    dirs
}

#[test]
fn imported_fixtures_generate_the_golden_rust() {
    let b = fixture_dirs().into_iter().fold(
        Builder::new()
            .emit_rerun_if_changed(false)
            .runtime_path("::jaus")
            .serde_cfg("all()"),
        |b, d| b.jsidl(d),
    );
    let spec = b.load().unwrap();
    assert_eq!(spec.services.len(), 2);
    let g = b.render().unwrap();
    assert!(g.messages >= 14, "{} messages", g.messages);
    assert!(g.code.contains("pub struct SetDriveTrim"));
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/jsidl/fixtures.messages.rs");
    if std::env::var_os("UPDATE_GOLDEN").is_some() {
        std::fs::write(&path, &g.code).unwrap();
    }
    let golden = std::fs::read_to_string(&path).unwrap();
    assert!(
        golden == g.code,
        "the generated code differs from {}: review, then run `UPDATE_GOLDEN=1 cargo test -p jaus-gen --test jsidl`",
        path.display()
    );
}

#[test]
fn jsidl_and_spec_dirs_do_not_mix() {
    let e = Builder::new()
        .emit_rerun_if_changed(false)
        .spec_dir(jaus_spec::defs_dir())
        .jsidl(fixtures().join("records"))
        .load()
        .unwrap_err();
    assert!(e.to_string().contains("cannot be combined"), "{e}");
}

#[test]
fn a_jsidl_error_names_the_file_and_line() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../jaus-jsidl/tests/fixtures/err/array");
    let e = Builder::new()
        .emit_rerun_if_changed(false)
        .jsidl(dir)
        .load()
        .unwrap_err();
    assert!(matches!(e, jaus_gen::Error::Jsidl(_)));
    assert!(
        e.to_string()
            .contains("Array.xml:8:9: <array name=\"Grid\">"),
        "{e}"
    );
}

/// Two imports of a JSIDL set, the second with a field's type changed, compare as two
/// YAML revisions do: a wire-breaking change of that field.
#[test]
fn diff_between_two_imports() {
    let tmp = std::env::temp_dir().join(format!("jaus-gen-jsidl-diff-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    let (old_xml, new_xml) = (tmp.join("old/records"), tmp.join("new/records"));
    std::fs::create_dir_all(&old_xml).unwrap();
    std::fs::create_dir_all(&new_xml).unwrap();
    let text = std::fs::read_to_string(fixtures().join("records/Records.xml")).unwrap();
    std::fs::write(old_xml.join("Records.xml"), &text).unwrap();
    let changed = text.replace(
        r#"<fixed_field name="Age" field_type="unsigned integer""#,
        r#"<fixed_field name="Age" field_type="unsigned short integer""#,
    );
    assert_ne!(changed, text);
    std::fs::write(new_xml.join("Records.xml"), changed).unwrap();
    let (old_yaml, new_yaml) = (tmp.join("old-yaml"), tmp.join("new-yaml"));
    jaus_jsidl::import(&[&old_xml])
        .unwrap()
        .write(&old_yaml)
        .unwrap();
    jaus_jsidl::import(&[&new_xml])
        .unwrap()
        .write(&new_yaml)
        .unwrap();
    let load = |p: &Path| jaus_gen::revision::load(&p.display().to_string()).unwrap();
    let same = jaus_gen::diff::diff(&load(&old_yaml), &load(&old_yaml));
    assert!(same.changes.is_empty());
    let d = jaus_gen::diff::diff(&load(&old_yaml), &load(&new_yaml));
    let text = d.to_text();
    assert!(text.contains("ReportMarker"), "{text}");
    assert!(text.contains("age"), "{text}");
    assert_eq!(
        d.exit_status(jaus_gen::diff::Severity::WireBreaking),
        1,
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&tmp);
}
