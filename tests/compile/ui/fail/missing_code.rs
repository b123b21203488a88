use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(presence = u8)]
struct NoCode {
    value: u8,
}

fn main() {
    let _ = NoCode { value: 1 }.to_bytes();
    let _ = NoCode::CODE;
}
