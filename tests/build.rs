//! A vendor's build script: generates the ACME experimental messages of
//! `vendor/acme.yaml` into this crate with the SDK's generator, as a vendor would.

fn main() {
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    if let Err(e) = jaus_gen::Builder::new()
        .overlay("vendor/acme.yaml")
        .runtime_path("::jaus")
        .serde_cfg("all()")
        .out_dir(out)
        .generate()
    {
        eprintln!("{e}");
        std::process::exit(1);
    }
}
