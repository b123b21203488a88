//! A vendor's build script: generates the ACME experimental messages of
//! `vendor/acme.yaml` into this crate with the SDK's generator, as a vendor would, and
//! pins their wire layout in `vendor/acme.lock`: a change of the YAML that changes the
//! layout fails the build with the list of changes until `JAUS_UPDATE_LOCK=1 cargo
//! build` rewrites the lock file (to be reviewed and committed).
//!
//! It also regenerates the AS-4 Core's state machine from jaus-as4's definitions with one
//! transition edited (`regenerate_core`), as a vendor would when the standard revises;
//! `tests/as4_regenerate.rs` runs a component on it. And it generates a vendor's own
//! AS-4 service on jaus-as4's definitions (`as4-vendor/lamp.yaml`, `extends: as4`), as a
//! vendor's build script does (`vendor_as4`); `tests/as4_vendor_service.rs` runs it.
//! And it generates the standard's first revisions as jaus-as4 holds them (Core v1.0 and
//! Manipulator v1.0, `sdk/as4/revisions/`), which `tests/as4_first_revisions.rs` compiles
//! and runs: what `jaus-gen diff` compares is code a vendor could build.

fn main() {
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    regenerate_core(&out);
    vendor_as4(&out);
    first_revisions(&out);
    if let Err(e) = jaus_gen::Builder::new()
        .overlay("vendor/acme.yaml")
        .lock("vendor/acme.lock")
        .runtime_path("::jaus")
        .serde_cfg("all()")
        .out_dir(out)
        .generate()
    {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

/// The edit: in Management, the initial sub-state of Controlled.Available becomes Ready
/// instead of Standby: a client granted control finds the component Ready (it no longer
/// needs to send Resume).
const EDIT_FROM: &str = "                          initial: Standby\n                          states:\n                            - name: Standby\n                              transitions:\n";
const EDIT_TO: &str = "                          initial: Ready\n                          states:\n                            - name: Standby\n                              transitions:\n";

/// Copies jaus-as4's definitions to `OUT_DIR/as4-edited/defs` with [`EDIT_FROM`] replaced
/// by [`EDIT_TO`] in `core_services.yaml`, and generates them into `OUT_DIR/as4-edited`.
fn regenerate_core(out: &str) {
    let defs = std::path::Path::new("../sdk/as4/defs");
    println!("cargo:rerun-if-changed={}", defs.display());
    let dir = std::path::Path::new(out).join("as4-edited");
    let copy = dir.join("defs");
    std::fs::create_dir_all(&copy).expect("create OUT_DIR/as4-edited/defs");
    for entry in std::fs::read_dir(defs).expect("read sdk/as4/defs") {
        let path = entry.expect("a definition file").path();
        let Some(name) = path.file_name() else {
            continue;
        };
        let mut text = std::fs::read_to_string(&path).expect("read a definition file");
        if name == "core_services.yaml" {
            assert!(
                text.contains(EDIT_FROM),
                "sdk/as4/defs/core_services.yaml no longer has the transition tests/build.rs edits (the initial sub-state of Management's Controlled.Available): update EDIT_FROM"
            );
            text = text.replace(EDIT_FROM, EDIT_TO);
        }
        let target = copy.join(name);
        if std::fs::read_to_string(&target).ok().as_deref() != Some(text.as_str()) {
            std::fs::write(target, text).expect("write a definition file");
        }
    }
    // The copy is this script's output, not an input: watch the originals (above).
    if let Err(e) = jaus_gen::Builder::new()
        .emit_rerun_if_changed(false)
        .spec_dir(&copy)
        .runtime_path("::jaus")
        .out_dir(&dir)
        .generate()
    {
        eprintln!("{e}");
        std::process::exit(1);
    }
}

/// Generates `as4-vendor/lamp.yaml` on jaus-as4's definitions (where jaus-as4 says they
/// are, `DEP_JAUS_AS4_DEFS`) into `OUT_DIR/as4-lamp`, and, with its guard edited so that
/// any client may set the level, into `OUT_DIR/as4-lamp-edited`.
fn vendor_as4(out: &str) {
    let defs = std::env::var("DEP_JAUS_AS4_DEFS").expect("jaus-as4 says where its definitions are");
    // `watch`: the edited copy is this script's output, not an input.
    let generate = |spec: &std::path::Path, dir: &std::path::Path, watch: bool| {
        if let Err(e) = jaus_gen::Builder::new()
            .emit_rerun_if_changed(watch)
            .spec_dir(spec)
            .base("as4", &defs, "::jaus_as4")
            .runtime_path("::jaus")
            .out_dir(dir)
            .generate()
        {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    let out = std::path::Path::new(out);
    generate(
        std::path::Path::new("as4-vendor"),
        &out.join("as4-lamp"),
        true,
    );
    // The regeneration promise on a vendor's service: one guard edited.
    let text = std::fs::read_to_string("as4-vendor/lamp.yaml").expect("read as4-vendor/lamp.yaml");
    let from = "condition: \"isControllingClient(transportData) && isLevelValid(msg)\"";
    assert!(
        text.contains(from),
        "as4-vendor/lamp.yaml no longer has the guard tests/build.rs edits"
    );
    let edited = out.join("as4-lamp-edited");
    let spec = edited.join("defs");
    std::fs::create_dir_all(&spec).expect("create OUT_DIR/as4-lamp-edited/defs");
    let text = text.replace(from, "condition: \"isLevelValid(msg)\"");
    let target = spec.join("lamp.yaml");
    if std::fs::read_to_string(&target).ok().as_deref() != Some(text.as_str()) {
        std::fs::write(target, text).expect("write the edited lamp.yaml");
    }
    generate(&spec, &edited, false);
}

/// Generates `sdk/as4/revisions/core-v1.0` with `manipulator-v1.0` (the first revisions
/// of both sets, written as jaus-as4's definitions are) into `OUT_DIR/as4-v1.0`.
fn first_revisions(out: &str) {
    let root = std::path::Path::new("../sdk/as4/revisions");
    let dir = std::path::Path::new(out).join("as4-v1.0");
    std::fs::create_dir_all(&dir).expect("create OUT_DIR/as4-v1.0");
    if let Err(e) = jaus_gen::Builder::new()
        .spec_dir(root.join("core-v1.0"))
        .spec_dir(root.join("manipulator-v1.0"))
        .runtime_path("::jaus")
        .out_dir(&dir)
        .generate()
    {
        eprintln!("{e}");
        std::process::exit(1);
    }
}
