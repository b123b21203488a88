//! `jaus-gen new`: the crate it writes is the one committed as `examples/vendor-rover`
//! (a workspace member, so `cargo test --workspace` builds and tests it), `new --as4`'s
//! the one committed as `examples/vendor-lamp`, and bad names
//! and existing files are refused. CI also writes a standalone crate into a temporary
//! directory and builds and tests it against this workspace (`.ci/run`).

use std::path::Path;

use jaus_gen::scaffold::{NewCrate, Sdk};

#[test]
fn the_committed_example_is_what_jaus_gen_new_writes() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/vendor-rover");
    let c = NewCrate {
        name: "vendor-rover".into(),
        sdk: Sdk::Path("../..".into()),
        standalone: false,
        as4: false,
    };
    let mut stale = Vec::new();
    for (path, text) in c.render().unwrap() {
        let committed = std::fs::read_to_string(root.join(&path)).unwrap_or_default();
        if committed != text {
            stale.push(path.display().to_string());
        }
    }
    assert!(
        stale.is_empty(),
        "examples/vendor-rover differs from `jaus-gen new` in {stale:?}: regenerate it (remove the files, then `cargo run -p jaus-gen --features cli -- new vendor-rover --dir examples --sdk-path ../.. --member`)"
    );
}

#[test]
fn the_committed_as4_example_is_what_jaus_gen_new_as4_writes() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/vendor-lamp");
    let c = NewCrate {
        name: "vendor-lamp".into(),
        sdk: Sdk::Path("../..".into()),
        standalone: false,
        as4: true,
    };
    let mut stale = Vec::new();
    for (path, text) in c.render().unwrap() {
        let committed = std::fs::read_to_string(root.join(&path)).unwrap_or_default();
        if committed != text {
            stale.push(path.display().to_string());
        }
    }
    assert!(
        stale.is_empty(),
        "examples/vendor-lamp differs from `jaus-gen new --as4` in {stale:?}: regenerate it (remove the files, then `cargo run -p jaus-gen --features cli -- new vendor-lamp --as4 --dir examples --sdk-path ../.. --member`)"
    );
}

#[test]
fn bad_names_and_existing_files_are_refused() {
    let e = NewCrate::new("Rover!").render().unwrap_err().to_string();
    assert!(e.contains("`Rover!` is not a crate name"), "{e}");
    let dir = std::env::temp_dir().join(format!("jaus-gen-new-{}", std::process::id()));
    let c = NewCrate::new("rover");
    c.write(&dir).unwrap();
    assert!(dir.join("defs/rover.yaml").exists());
    let e = c.write(&dir).unwrap_err().to_string();
    assert!(
        e.contains("exists: `jaus-gen new` writes only into a new crate"),
        "{e}"
    );
    let toml = std::fs::read_to_string(dir.join("Cargo.toml")).unwrap();
    assert!(
        toml.contains("jaus = { version = \"0.1.0\"") && toml.contains("[workspace]"),
        "{toml}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
