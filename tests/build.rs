//! A vendor's build script: generates the ACME experimental messages of
//! `vendor/acme.yaml` into this crate with the SDK's generator, as a vendor would, and
//! pins their wire layout in `vendor/acme.lock`: a change of the YAML that changes the
//! layout fails the build with the list of changes until `JAUS_UPDATE_LOCK=1 cargo
//! build` rewrites the lock file (to be reviewed and committed).

fn main() {
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
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
