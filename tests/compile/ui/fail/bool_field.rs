use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(code = 0xD001)]
struct M {
    enabled: bool,
}

fn main() {
    let _ = M { enabled: true }.to_bytes();
}
