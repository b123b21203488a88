use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(code = 0xD001, presence = u8)]
struct M {
    #[jaus(bit = 0)]
    speed: u16,
}

fn main() {
    let _ = M { speed: 1 }.to_bytes();
}
