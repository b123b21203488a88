//! What `jaus-gen diff` calls compatible keeps vendor code compiling: code written
//! against an old revision (`jaus-gen/tests/diff/code/*.vendor.rs`) is compiled here
//! against the code generated from that revision and from every revision the diff calls
//! compatible with it (`jaus-gen/tests/diff/code/*.messages.rs`, `*.components.rs`,
//! golden files that `cargo test -p jaus-gen --test revisions` holds equal to the
//! generator's output and whose diffs it holds compatible). The rule the vendor code
//! follows, and that makes "compatible" true of it, is in docs/spec-revisions.md: struct
//! literals and patterns of generated types end with `..`, and a `match` on a generated
//! enum or on `Message` has a `_` arm. (Without `..`, a field added under a new presence
//! bit stops a struct literal with E0063: `tests/compile/ui/fail/revision_added_field.rs`.)

/// A module holding the code generated from revision `$rev` and, in `vendor`, the old
/// code `$code` compiled against it.
macro_rules! revision {
    ($m:ident, $rev:literal, $code:literal $(, components: $c:literal)?) => {
        #[allow(dead_code, unused_imports, clippy::match_single_binding)]
        mod $m {
            include!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../jaus-gen/tests/diff/code/",
                $rev,
                ".messages.rs"
            ));
            $(
                pub mod components {
                    include!(concat!(
                        env!("CARGO_MANIFEST_DIR"),
                        "/../jaus-gen/tests/diff/code/",
                        $c,
                        ".components.rs"
                    ));
                }
            )?
            pub mod vendor {
                use super::*;
                include!(concat!(
                    env!("CARGO_MANIFEST_DIR"),
                    "/../jaus-gen/tests/diff/code/",
                    $code
                ));
            }
        }
    };
}

revision!(tractor_1, "tractor-1", "tractor-1.vendor.rs", components: "tractor-1");
revision!(tractor_1_on_2, "tractor-2", "tractor-1.vendor.rs", components: "tractor-2");
revision!(old, "old", "old.vendor.rs");
revision!(old_on_compatible, "compatible", "old.vendor.rs");

/// Every generated file of `jaus-gen/tests/diff/code/` is compiled above.
#[test]
fn every_compatible_revision_is_compiled() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../jaus-gen/tests/diff/code");
    let mut files: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|f| f.ends_with(".messages.rs") || f.ends_with(".components.rs"))
        .collect();
    files.sort();
    assert_eq!(
        files,
        [
            "compatible.messages.rs",
            "old.messages.rs",
            "tractor-1.components.rs",
            "tractor-1.messages.rs",
            "tractor-2.components.rs",
            "tractor-2.messages.rs",
        ],
        "add the new revisions to the revision! list above"
    );
}

/// The old code runs on the new revision, and the two revisions' peers read each
/// other's bytes.
#[test]
fn old_vendor_code_runs_on_the_compatible_revision_and_the_peers_interoperate() {
    use jaus::codec::Encode;
    use jaus::JausMessage;
    use std::time::Instant;

    let t0 = Instant::now();
    let (_old, _new) = (
        tractor_1::vendor::controller(t0),
        tractor_1_on_2::vendor::controller(t0),
    );
    let _ = (
        tractor_1::vendor::logger(t0),
        tractor_1_on_2::vendor::logger(t0),
    );

    let old = tractor_1::vendor::Implement {
        depth: 1.0,
        mode: tractor_1::ImplementMode::Working,
    }
    .report();
    let new = tractor_1_on_2::vendor::Implement {
        depth: 1.0,
        mode: tractor_1_on_2::ImplementMode::Working,
    }
    .report();
    // The old code built the new message without knowing `draft_force`: absent.
    assert_eq!(new.draft_force, None);
    assert_eq!(old.to_bytes().unwrap(), new.to_bytes().unwrap());

    // A new peer's report with the new field decodes at an old peer, which skips it.
    let with_force = tractor_1_on_2::ReportImplementState {
        draft_force: Some(1500.0),
        ..new.clone()
    };
    let at_old =
        tractor_1::ReportImplementState::decode_body(&with_force.to_bytes().unwrap()).unwrap();
    let old_sent = tractor_1::ReportImplementState::decode_body(&old.to_bytes().unwrap()).unwrap();
    assert_eq!(at_old, old_sent);
    assert_eq!(tractor_1::vendor::depth_and_lock(&at_old), (1.0, true));
    // A value the old revision does not know arrives as Unknown, and the old code's
    // `_` arm takes the new one.
    let floating =
        tractor_1_on_2::Message::ReportImplementState(tractor_1_on_2::ReportImplementState {
            mode: tractor_1_on_2::ImplementMode::Floating,
            ..new
        });
    assert_eq!(tractor_1_on_2::vendor::describe(&floating), "another mode");
    let bytes = floating.to_bytes().unwrap();
    let at_old = tractor_1::Message::decode(floating.code(), &bytes).unwrap();
    assert_eq!(tractor_1::vendor::describe(&at_old), "another mode");

    // The set of its own: the same code, the same bytes.
    let (a, b) = (
        old::vendor::state(2.5),
        old_on_compatible::vendor::state(2.5),
    );
    assert_eq!(a.to_bytes().unwrap(), b.to_bytes().unwrap());
    assert_eq!(
        old_on_compatible::vendor::speed_of(&b),
        old::vendor::speed_of(&a)
    );
    assert_eq!(
        old::vendor::status().to_bytes().unwrap(),
        old_on_compatible::vendor::status().to_bytes().unwrap()
    );
    assert!(old_on_compatible::vendor::moving(
        old_on_compatible::Mode::Run
    ));
    assert!(!old_on_compatible::vendor::moving(
        old_on_compatible::Mode::Slow
    ));
    let _ = old::ReportState::CODE;
}
