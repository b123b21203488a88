use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(code = 0xD001)]
struct M {
    #[jaus(count = i16)]
    items: Vec<u16>,
}

fn main() {
    let _ = M { items: vec![] }.to_bytes();
}
