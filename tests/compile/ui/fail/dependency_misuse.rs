//! Misused field dependencies: each attribute on a field of the wrong kind.

use jaus::codec::Encode;
use jaus::JausRecord;

#[derive(JausRecord)]
struct Bad {
    #[jaus(var = "n")]
    n: u8,
    #[jaus(count_var = "n")]
    not_a_list: u16,
    #[jaus(present_if = "n")]
    not_optional: u16,
    #[jaus(tag_var = "n")]
    not_a_union: u32,
    #[jaus(nul_terminated)]
    not_a_string: Vec<u8>,
}

fn main() {
    let _ = Bad { n: 0, not_a_list: 0, not_optional: 0, not_a_union: 0, not_a_string: vec![] }.to_bytes();
}
