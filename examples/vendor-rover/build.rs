//! Generates this crate's messages and component skeletons from `defs/vendor_rover.yaml`
//! (which extends the SDK's definitions) and checks their wire layout against
//! `defs/vendor_rover.lock` once you pin it. Until that file exists the definitions change
//! freely (the build warns that they are not pinned); when they are ready for peers,
//! `JAUS_UPDATE_LOCK=1 cargo build` writes it: commit it. From then on a change of the
//! YAML that changes the wire fails the build with the list of changes until the same
//! command updates the lock (review and commit it).

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
