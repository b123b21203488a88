use jaus::codec::Encode;
use jaus::JausBits;

#[derive(JausBits)]
#[jaus(repr = u8)]
struct Flags {
    #[jaus(bits = 0..=3)]
    mode: u8,
    #[jaus(bit = 2)]
    armed: bool,
}

fn main() {
    let _ = Flags {
        mode: 0,
        armed: false,
    }
    .to_bytes();
}
