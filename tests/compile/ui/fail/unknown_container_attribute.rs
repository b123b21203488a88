use jaus::codec::Encode;
use jaus::JausRecord;

#[derive(JausRecord)]
#[jaus(code = 0xD001)]
struct R {
    value: u8,
}

fn main() {
    let _ = R { value: 0 }.to_bytes();
}
