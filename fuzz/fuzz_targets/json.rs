//! Fuzz target `json`: see `jaus_tests::fuzz::json`.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| jaus_tests::fuzz::json(data));
