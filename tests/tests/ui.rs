//! Compile-time behaviour of the codec derives: programs that must build and run
//! (`ui/pass`), and misuses that must be rejected with a precise error (`ui/fail`).

#[test]
fn derive_ui() {
    let t = trybuild::TestCases::new();
    t.pass("ui/pass/*.rs");
    t.compile_fail("ui/fail/*.rs");
}
