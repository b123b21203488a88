//! Compile-time behaviour of the codec derives: programs that must build and run
//! (`ui/pass`), and misuses that must be rejected with a precise error (`ui/fail`).

#[test]
fn derive_ui() {
    let t = trybuild::TestCases::new();
    t.pass("ui/pass/*.rs");
    t.compile_fail("ui/fail/*.rs");
}

/// Generated component skeletons: a vendor implementation builds and runs; a handler
/// with the wrong message or report type, a handler outside the interface, sending a
/// message the interface does not emit, and another component's mode transition are
/// compile errors.
#[test]
fn component_ui() {
    let t = trybuild::TestCases::new();
    t.pass("ui/components/pass/*.rs");
    t.compile_fail("ui/components/fail/*.rs");
}

/// Generated AS-4 services: an implementation of a service's trait that leaves out a
/// guard does not compile, and the error names the missing method.
#[test]
fn service_ui() {
    let t = trybuild::TestCases::new();
    t.compile_fail("ui/services/fail/*.rs");
}
