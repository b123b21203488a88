use jaus::codec::Encode;
use jaus::JausBits;

#[derive(JausBits)]
#[jaus(repr = u8)]
struct Flags {
    #[jaus(bits = 4..=8)]
    level: u8,
}

fn main() {
    let _ = Flags { level: 0 }.to_bytes();
}
