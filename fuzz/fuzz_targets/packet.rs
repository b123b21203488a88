//! Fuzz target `packet`: see `jaus_tests::fuzz::packet`.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| jaus_tests::fuzz::packet(data));
