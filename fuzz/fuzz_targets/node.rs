//! Fuzz target `node`: see `jaus_tests::fuzz::node`.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| jaus_tests::fuzz::node(data));
