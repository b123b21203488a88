//! Generates the typed message set from the jaus-spec definitions, and the runtime's
//! types that jaus-spec's lists define (`Hardware`).

fn main() {
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    let result = jaus_gen::Builder::new()
        .spec_dir(jaus_spec::defs_dir())
        .feature_gates(true)
        .runtime_path("crate")
        .serde_cfg("feature = \"serde\"")
        .out_dir(&out)
        .generate()
        .and_then(|_| {
            let path = std::path::Path::new(&out).join("hardware.rs");
            jaus_gen::write_if_changed(&path, &jaus_gen::runtime::hardware_code()?)
        });
    if let Err(e) = result {
        // One line per problem, each with file:line:column, so the vendor knows what to fix.
        for line in e.to_string().lines() {
            println!("cargo:warning={line}");
        }
        eprintln!("{e}");
        std::process::exit(1);
    }
}
