use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(code = 0xD001, presence = u8)]
struct M {
    speed: Option<u16>,
}

fn main() {
    let _ = M { speed: None }.to_bytes();
}
