use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(code = 0xD001)]
struct M {
    #[jaus(scaled(i16, -100.0, 100.0))]
    effort: i16,
}

fn main() {
    let _ = M { effort: 1 }.to_bytes();
}
