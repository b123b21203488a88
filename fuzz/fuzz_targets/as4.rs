//! Fuzz target `as4`: see `jaus_tests::fuzz::as4`.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| jaus_tests::fuzz::as4(data));
