use jaus::codec::Encode;
use jaus::JausUnion;

#[derive(JausUnion)]
#[jaus(tag = u8)]
enum Target {
    #[jaus(tag = 0)]
    Nothing,
    Id(u16),
}

fn main() {
    let _ = Target::Nothing.to_bytes();
    let _ = Target::Id(1);
}
