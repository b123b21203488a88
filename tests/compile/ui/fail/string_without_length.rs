use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(code = 0xD001)]
struct M {
    id: u8,
    name: String,
}

fn main() {
    let _ = M {
        id: 0,
        name: String::new(),
    }
    .to_bytes();
}
