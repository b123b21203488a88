//! The definition language and the runtime agree on the scaled-integer divisors (the
//! generator documents resolutions with the former, the codec scales with the latter)
//! and on the command-code ranges of the message classes and the complement rule (the
//! definitions classify and pair messages with the former, the runtime routes with the
//! latter), and the core service of Report Services says what it always said.

use jaus::codec::ScaledRepr;
use jaus::components::global_pose_sensor::{self, GlobalPoseSensor};
use jaus::messages::{Message, QueryServices, RUNTIME_INPUTS, RUNTIME_OUTPUTS};
use jaus::{Address, CommandCode, Header, JausMessage};
use jaus_spec::Int;

#[test]
fn scaled_divisors_agree() {
    assert_eq!(Int::U8.divisor(), <u8 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::U16.divisor(), <u16 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::U32.divisor(), <u32 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::U64.divisor(), <u64 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::I8.divisor(), <i8 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::I16.divisor(), <i16 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::I32.divisor(), <i32 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::I64.divisor(), <i64 as ScaledRepr>::DIVISOR);
}

/// `jaus::wire::MessageClass` of a code by `jaus_spec::MessageClass`'s table.
fn class_by_spec(code: u16) -> jaus::wire::MessageClass {
    use jaus::wire::MessageClass as W;
    use jaus_spec::MessageClass as S;
    match S::of_code(code) {
        Some(S::Command) => W::Command,
        Some(S::Query) => W::Query,
        Some(S::Inform) => W::Inform,
        Some(S::EventSetup) => W::EventSetup,
        Some(S::EventNotification) => W::EventNotification,
        Some(S::NodeManagement) => W::NodeManagement,
        Some(S::Experimental) => unreachable!("no range of the standard is experimental"),
        None if S::is_reserved_code(code) => W::Reserved,
        None => {
            assert!(S::is_experimental_code(code), "0x{code:04X}");
            W::Experimental
        }
    }
}

#[test]
fn message_classes_agree_on_every_code() {
    use jaus_spec::MessageClass as S;
    for code in 0..=u16::MAX {
        let c = CommandCode(code);
        assert_eq!(c.class(), class_by_spec(code), "class of 0x{code:04X}");
        let complement = S::report_code(code).or_else(|| S::query_code(code));
        assert_eq!(
            c.complement().map(|c| c.0),
            complement,
            "complement of 0x{code:04X}"
        );
    }
}

#[test]
fn every_query_in_the_catalogue_names_its_report() {
    for m in jaus::messages::MESSAGES {
        if m.code.class() == jaus::wire::MessageClass::Query {
            let report = m
                .report
                .unwrap_or_else(|| panic!("{} has no report", m.name));
            let r = jaus::messages::MESSAGES
                .iter()
                .find(|x| x.name == report)
                .unwrap();
            assert_eq!(Some(r.code), m.code.complement(), "{} → {}", m.name, r.name);
        }
    }
    // The 160 of OpenJAUS 3.3 and the SDK's own experimental Report Refusal (0xDF01), which
    // the runtime sends without listing it in Report Services (the core service lists what
    // OpenJAUS lists).
    assert_eq!(jaus::messages::MESSAGES.len(), 161);
    assert!(jaus::messages::MESSAGES
        .iter()
        .any(|m| m.code.0 == 0xDF01 && m.experimental));
}

/// The core service (type 0) of Report Services, as OpenJAUS lists it: the messages the
/// definitions mark `runtime:`, in code order. A YAML edit that changes a flag changes
/// what every component tells its peers; if that is the intent, change these lists too.
#[test]
fn the_core_service_lists_what_it_always_listed() {
    const INPUTS: &[u16] = &[
        0x0001, 0x0002, 0x0003, 0x0004, 0x0005, 0x0006, 0x0007, 0x0008, 0x0009, 0x000A, 0x000B,
        0x000C, 0x000D, 0x000E, 0x000F, 0x0010, 0x0011, 0x01F0, 0x01F1, 0x01F2, 0x2001, 0x2002,
        0x200D, 0x2011, 0x21F0, 0x2202, 0x2B00, 0x2B03,
    ];
    const OUTPUTS: &[u16] = &[
        0x0008, 0x0009, 0x000C, 0x000D, 0x000F, 0x0010, 0x01F3, 0x01F4, 0x4001, 0x4002, 0x400D,
        0x4011, 0x41F0, 0x41F1, 0x4202, 0x4B00, 0x4B03,
    ];
    let codes = |l: &[CommandCode]| l.iter().map(|c| c.0).collect::<Vec<_>>();
    assert_eq!(codes(RUNTIME_INPUTS), INPUTS);
    assert_eq!(codes(RUNTIME_OUTPUTS), OUTPUTS);

    // On the wire: the Report Services of a running component.
    struct Gps;
    impl GlobalPoseSensor for Gps {}
    let now = std::time::Instant::now();
    let (me, peer) = (Address::new(1, 1, 38, 1), Address::new(1, 2, 40, 1));
    let mut c = global_pose_sensor::component(me, Gps, Default::default(), now);
    c.handle_timeout(now);
    let query = Header::new(QueryServices::CODE, me, peer);
    c.handle_message(now, &query, &Message::QueryServices(QueryServices {}));
    let report = std::iter::from_fn(|| c.poll_transmit())
        .find_map(|t| match t.message {
            Some(Message::ReportServices(r)) => Some(r),
            _ => None,
        })
        .expect("Report Services sent");
    let core = &report.services[0];
    assert_eq!(core.service_type, 0);
    let listed =
        |l: &[jaus::messages::ServiceCommand]| l.iter().map(|s| s.command_code).collect::<Vec<_>>();
    assert_eq!(listed(&core.input_commands), INPUTS);
    assert_eq!(listed(&core.output_commands), OUTPUTS);
}
