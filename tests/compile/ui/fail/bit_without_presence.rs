use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(code = 0xD001)]
struct M {
    #[jaus(bit = 0)]
    speed: Option<u16>,
}

fn main() {
    let _ = M { speed: None }.to_bytes();
}
