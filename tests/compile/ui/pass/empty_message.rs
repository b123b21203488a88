//! A message with an empty body, and one that is a unit struct.

use jaus::codec::{Decode, Encode};
use jaus::JausMessage;

#[derive(Debug, PartialEq, JausMessage)]
#[jaus(code = 0x0002)]
struct Shutdown {}

#[derive(Debug, PartialEq, JausMessage)]
#[jaus(code = 0xD001, name = "Standby Now")]
struct StandbyNow;

fn main() {
    assert_eq!(Shutdown::CODE.0, 0x0002);
    assert_eq!(Shutdown::NAME, "Shutdown");
    assert_eq!(Shutdown {}.encoded_len(), 0);
    assert_eq!(Shutdown {}.to_bytes().unwrap(), Vec::<u8>::new());
    assert_eq!(Shutdown::from_bytes(&[]).unwrap(), Shutdown {});
    assert_eq!(Shutdown::decode_body(&[]).unwrap(), Shutdown {});
    assert_eq!(<Shutdown as Decode>::MIN_LEN, 0);
    // An empty body has no room for trailing bytes.
    let e = Shutdown::decode_body(&[0x00]).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("Shutdown: 1 unexpected trailing byte(s)"),
        "{e}"
    );

    assert_eq!(StandbyNow::CODE.0, 0xD001);
    assert_eq!(StandbyNow::NAME, "Standby Now");
    assert_eq!(StandbyNow.to_bytes().unwrap(), Vec::<u8>::new());
    assert_eq!(StandbyNow::from_bytes(&[]).unwrap(), StandbyNow);
    assert!(StandbyNow::from_bytes(&[1, 2]).is_err());
}
