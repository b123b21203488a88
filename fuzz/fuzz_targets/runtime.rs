//! Fuzz target `runtime`: see `jaus_tests::fuzz::runtime`.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| jaus_tests::fuzz::runtime(data));
