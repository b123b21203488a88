//! Fuzz target `jserial`: see `jaus_tests::fuzz::jserial`.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| jaus_tests::fuzz::jserial(data));
