//! Generates this crate's messages and component skeletons from `defs/vendor_rover.yaml`
//! (which extends the SDK's definitions) and pins their wire layout in
//! `defs/vendor_rover.lock`: a change of the YAML that changes the wire fails the build
//! with the list of changes until `JAUS_UPDATE_LOCK=1 cargo build` rewrites the lock
//! (review and commit it).

fn main() {
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    if let Err(e) = jaus_gen::Builder::new()
        .overlay("defs/vendor_rover.yaml")
        .lock("defs/vendor_rover.lock")
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
