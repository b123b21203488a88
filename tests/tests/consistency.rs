//! The definition language and the runtime agree on the scaled-integer divisors (the
//! generator documents resolutions with the former, the codec scales with the latter).

use jaus::codec::ScaledRepr;
use jaus_spec::Int;

#[test]
fn scaled_divisors_agree() {
    assert_eq!(Int::U8.divisor(), <u8 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::U16.divisor(), <u16 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::U32.divisor(), <u32 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::U64.divisor(), <u64 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::I16.divisor(), <i16 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::I32.divisor(), <i32 as ScaledRepr>::DIVISOR);
    assert_eq!(Int::I64.divisor(), <i64 as ScaledRepr>::DIVISOR);
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
    assert_eq!(jaus::messages::MESSAGES.len(), 160);
}
