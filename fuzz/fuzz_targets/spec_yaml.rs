//! Fuzz target `spec_yaml`: see `jaus_tests::fuzz::spec_yaml`.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| jaus_tests::fuzz::spec_yaml(data));
