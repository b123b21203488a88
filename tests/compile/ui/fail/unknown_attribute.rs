use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(code = 0xD001)]
struct M {
    #[jaus(little_endian)]
    speed: u16,
}

fn main() {
    let _ = M { speed: 1 }.to_bytes();
}
