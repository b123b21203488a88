//! Generates the AS-4 messages of `defs/` (the Core and Mobility service sets, our own
//! YAML, `extends: none`) into `OUT_DIR/messages.rs` with the SDK's generator.

fn main() {
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    if let Err(e) = jaus_gen::Builder::new()
        .spec_dir("defs")
        .runtime_path("::jaus")
        .serde_cfg("feature = \"serde\"")
        .out_dir(out)
        .generate()
    {
        // One line per problem, each with file:line:column.
        for line in e.to_string().lines() {
            println!("cargo:warning={line}");
        }
        eprintln!("{e}");
        std::process::exit(1);
    }
}
