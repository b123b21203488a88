use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(code = 0xD001)]
struct M {
    #[jaus(rest)]
    data: Vec<u8>,
    checksum: u16,
}

fn main() {
    let _ = M {
        data: vec![],
        checksum: 0,
    }
    .to_bytes();
}
