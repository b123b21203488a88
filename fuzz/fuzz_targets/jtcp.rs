//! Fuzz target `jtcp`: see `jaus_tests::fuzz::jtcp`.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| jaus_tests::fuzz::jtcp(data));
