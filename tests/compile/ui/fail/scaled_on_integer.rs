use jaus::codec::Encode;
use jaus::JausMessage;

#[derive(JausMessage)]
#[jaus(code = 0xD001)]
struct M {
    #[jaus(scaled(i16, -100.0, 100.0))]
    effort: i16,
    // A unit belongs to a scaled value.
    #[jaus(unit = "m")]
    length: u16,
}

fn main() {
    let _ = M { effort: 1, length: 2 }.to_bytes();
}
