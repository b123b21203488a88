use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(code = 0xD001, presence = u8)]
struct M {
    #[jaus(bit = 8)]
    late: Option<u8>,
}

fn main() {
    let _ = M { late: None }.to_bytes();
}
