//! Every public JSIDL service set imported as published, with the Core version it
//! inherits, generated, and the generated Rust compiled (`cargo check` of a scratch
//! crate holding all of them, on the SDK's `jaus` runtime). Opt-in, as the published
//! files are not in the repository (the JAUS Tool Set's `GUI/resources/xml`):
//!
//! ```sh
//! JAUS_JSIDL_DIR=/path/to/GUI/resources/xml cargo test -p jaus-gen --test public_sets -- --nocapture
//! ```
//!
//! The scratch crate and its build are under the workspace's `target/public-sets`.

use std::path::{Path, PathBuf};
use std::process::Command;

use jaus_gen::Builder;

/// Each set's directory, the Core it is published on, and a module name.
const SETS: &[(&str, Option<&str>, &str)] = &[
    ("urn.jaus.jss.core-v1.0", None, "core10"),
    ("urn.jaus.jss.core-v1.1", None, "core11"),
    (
        "urn.jaus.jss.mobility",
        Some("urn.jaus.jss.core-v1.0"),
        "mobility",
    ),
    (
        "urn.jaus.jss.environmentSensing",
        Some("urn.jaus.jss.core-v1.0"),
        "environment",
    ),
    (
        "urn.jaus.jss.manipulator-v1.0",
        Some("urn.jaus.jss.core-v1.0"),
        "manipulator10",
    ),
    (
        "urn.jaus.jss.manipulator-v2.0",
        Some("urn.jaus.jss.core-v1.1"),
        "manipulator20",
    ),
    (
        "urn.jaus.jss.missionSpooler",
        Some("urn.jaus.jss.core-v1.1"),
        "mission",
    ),
    ("urn.jaus.jss.ugv", Some("urn.jaus.jss.core-v1.1"), "ugv"),
    ("urn.jaus.jss.hmi", Some("urn.jaus.jss.core-v1.0"), "hmi"),
];

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the workspace")
        .to_path_buf()
}

#[test]
fn every_public_set_imports_generates_and_compiles() {
    let Some(root) = std::env::var_os("JAUS_JSIDL_DIR").map(PathBuf::from) else {
        println!("skipped: set JAUS_JSIDL_DIR to import and compile every public JSIDL set");
        return;
    };
    let ws = workspace();
    let scratch = ws.join("target/public-sets");
    let src = scratch.join("src");
    std::fs::create_dir_all(&src).unwrap();
    let mut lib = String::from("#![allow(clippy::all, unused, missing_docs)]\n");
    let mut failures = Vec::new();
    for (set, core, module) in SETS {
        let mut b = Builder::new()
            .emit_rerun_if_changed(false)
            .runtime_path("::jaus");
        if let Some(core) = core {
            b = b.jsidl(root.join(core));
        }
        b = b.jsidl(root.join(set));
        let g = match b.render() {
            Ok(g) => g,
            Err(e) => {
                failures.push(format!("{set}: {e}"));
                continue;
            }
        };
        println!(
            "{set} (on {}): {} services, {} messages, {} types",
            core.unwrap_or("itself"),
            g.service_count,
            g.messages,
            g.types
        );
        assert!(
            g.service_count > 0 && g.messages > 0,
            "{set}: nothing generated"
        );
        let dir = src.join(module);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("messages.rs"), &g.code).unwrap();
        std::fs::write(dir.join("services.rs"), &g.services).unwrap();
        lib.push_str(&format!(
            "pub mod {module} {{\n    include!(\"{module}/messages.rs\");\n    pub mod services {{\n        include!(\"{module}/services.rs\");\n    }}\n}}\n"
        ));
    }
    assert!(failures.is_empty(), "refused:\n{}", failures.join("\n"));
    std::fs::write(src.join("lib.rs"), lib).unwrap();
    std::fs::write(
        scratch.join("Cargo.toml"),
        format!(
            "[package]\nname = \"public-sets\"\nversion = \"0.0.0\"\nedition = \"2021\"\npublish = false\n\n[workspace]\n\n[dependencies]\njaus = {{ path = {:?}, default-features = false }}\nserde = {{ version = \"1\", features = [\"derive\"] }}\n",
            ws.join("sdk/jaus")
        ),
    )
    .unwrap();
    // The workspace's versions of the dependencies, so that the check needs no network.
    std::fs::copy(ws.join("Cargo.lock"), scratch.join("Cargo.lock")).unwrap();
    let out = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
        .args(["check", "--offline", "--quiet", "--message-format=short"])
        .current_dir(&scratch)
        .env("CARGO_TARGET_DIR", scratch.join("target"))
        .env_remove("RUSTFLAGS")
        .output()
        .expect("run cargo check");
    let errors = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "the generated code of the public sets does not compile ({}):\n{errors}",
        scratch.display()
    );
    println!("all {} sets compile ({})", SETS.len(), scratch.display());
}
