use jaus::codec::Encode;
use jaus::JausMessage;

// Every problem is reported at once, each at its own field.
#[derive(JausMessage)]
#[jaus(code = 0xD001, presence = u8)]
struct M {
    enabled: bool,
    #[jaus(bit = 9)]
    late: Option<u8>,
    #[jaus(count = u8)]
    name: String,
}

fn main() {
    let _ = M {
        enabled: true,
        late: None,
        name: String::new(),
    }
    .to_bytes();
}
