use jaus::codec::Encode;
use jaus::JausEnum;

#[derive(Clone, Copy, JausEnum)]
#[jaus(repr = u8)]
enum Mode {
    #[jaus(value = 0)]
    Standby,
    Ready,
}

fn main() {
    let _ = Mode::Standby.to_bytes();
    let _ = Mode::Ready;
}
