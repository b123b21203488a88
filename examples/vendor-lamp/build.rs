//! Generates this crate's AS-4 messages and its service's trait, triggers and state
//! machines from `defs/vendor_lamp.yaml`, on jaus-as4's definitions (`extends: as4`):
//! the service inherits Access Control, whose machines and guards and actions come from
//! jaus-as4 (the component's Core runs them). jaus-as4 says where its definitions are
//! (`DEP_JAUS_AS4_DEFS`, its `links` metadata).

fn main() {
    let out = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    let Ok(as4) = std::env::var("DEP_JAUS_AS4_DEFS") else {
        eprintln!("jaus-as4 did not say where its definitions are (DEP_JAUS_AS4_DEFS): is it a dependency?");
        std::process::exit(1);
    };
    if let Err(e) = jaus_gen::Builder::new()
        .spec_dir("defs")
        .base("as4", as4, "::jaus_as4")
        .out_dir(out)
        .generate()
    {
        // One line per problem, each with file:line.
        for line in e.to_string().lines() {
            println!("cargo:warning={line}");
        }
        eprintln!("{e}");
        std::process::exit(1);
    }
}
