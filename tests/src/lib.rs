//! Harnesses shared by the coverage-guided fuzzers (`fuzz/`, cargo-fuzz) and the test
//! suite, which replays every committed corpus entry through them on stable
//! (`tests/fuzz_corpus.rs`). Each takes arbitrary bytes, must never panic, and checks
//! its own invariants with `assert!` (a failed assertion is a finding). Also the tshark
//! helpers of the dissector tests ([`tshark`]).

pub mod fuzz;
pub mod tshark;
