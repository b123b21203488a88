use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(code = 0xD001, presence = u8)]
struct M {
    #[jaus(bit = 3)]
    first: Option<u8>,
    #[jaus(bit = 3)]
    second: Option<u8>,
}

fn main() {
    let _ = M {
        first: None,
        second: None,
    }
    .to_bytes();
}
