//! Generates the AS-4 messages of `defs/` (the Core and Mobility service sets, our own
//! YAML, `extends: none`) into `OUT_DIR/messages.rs` with the SDK's generator, and
//! tells dependent crates' build scripts where they are (`DEP_JAUS_AS4_DEFS`).

fn main() {
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    // For the build scripts of dependent crates (`links = "jaus_as4"`): where the
    // definitions are, `DEP_JAUS_AS4_DEFS`, to build a vendor's `extends: as4` set on.
    let manifest = std::env::var("CARGO_MANIFEST_DIR").expect("cargo sets CARGO_MANIFEST_DIR");
    println!(
        "cargo:defs={}",
        std::path::Path::new(&manifest).join("defs").display()
    );
    if let Err(e) = jaus_gen::Builder::new()
        .spec_dir("defs")
        .runtime_path("::jaus")
        // The Core's services are inherited by delegation: a Mobility service's trait
        // holds only its own guards and actions, the inherited ones run on the Core.
        .delegate_inherited("urn:jaus:jss:core:")
        // jaus-as4 hosts its own services: each gets a `Hosted<S>` adapter.
        .hosted_by("crate")
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
