//! The message classes and the command-code ranges the standard gives them (Part 1).

use serde::Deserialize;
use std::ops::RangeInclusive;

/// The class of a message (Part 1; the command-code ranges of the standard).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MessageClass {
    /// Changes the state of the receiver (0x0000-0x1FFF); executed only for the
    /// component in control when a component lists it in `commands`.
    Command,
    /// Asks for information (0x2000-0x3FFF), answered by a report.
    Query,
    /// Carries information (0x4000-0x5FFF): reports.
    Inform,
    /// Event setup (0x6000-0x7FFF, deprecated in RA 3.3).
    EventSetup,
    /// Event notification (0x8000-0x9FFF, deprecated in RA 3.3).
    EventNotification,
    /// Node management (0xA000-0xBFFF).
    NodeManagement,
    /// An experimental code without an explicit class: handled like an inform message.
    Experimental,
}

impl MessageClass {
    /// The command-code ranges of the standard (Part 1): the one table every check of
    /// jaus-spec, jaus-gen and jaus-jsidl reads (through [`of_code`](Self::of_code),
    /// [`codes`](Self::codes), [`is_experimental_code`](Self::is_experimental_code),
    /// [`report_code`](Self::report_code)). The runtime's `jaus::wire::MessageClass`
    /// is checked against it code by code (`tests/tests/consistency.rs`).
    const RANGES: [(Self, u16, u16); 6] = [
        (Self::Command, 0x0000, 0x1FFF),
        (Self::Query, 0x2000, 0x3FFF),
        (Self::Inform, 0x4000, 0x5FFF),
        (Self::EventSetup, 0x6000, 0x7FFF),
        (Self::EventNotification, 0x8000, 0x9FFF),
        (Self::NodeManagement, 0xA000, 0xBFFF),
    ];

    /// The experimental codes (0xD000-0xFFFF): a definition states their class, and a
    /// later revision of the standard gives none of them to another message. The codes
    /// between the classes' ranges and these (0xC000-0xCFFF) are reserved.
    pub const EXPERIMENTAL_CODES: RangeInclusive<u16> = 0xD000..=0xFFFF;

    /// How far a query's report is above the query (the complement rule, docs/wire.md
    /// §3.3): Report X = Query X + 0x2000, from the query range to the inform range.
    const COMPLEMENT: u16 = 0x2000;

    /// The class the standard gives a code, `None` for reserved and experimental codes
    /// (0xC000-0xFFFF), whose class a definition may state.
    pub fn of_code(code: u16) -> Option<Self> {
        Self::RANGES
            .iter()
            .find(|(_, first, last)| (*first..=*last).contains(&code))
            .map(|(c, _, _)| *c)
    }

    /// The codes the standard gives the class; `None` for
    /// [`Experimental`](Self::Experimental) (see [`EXPERIMENTAL_CODES`](Self::EXPERIMENTAL_CODES)).
    pub fn codes(self) -> Option<RangeInclusive<u16>> {
        Self::RANGES
            .iter()
            .find(|(c, _, _)| *c == self)
            .map(|(_, first, last)| *first..=*last)
    }

    /// The class's codes as error messages write them (`0x2000-0x3FFF`).
    pub fn codes_text(self) -> String {
        let r = self.codes().unwrap_or(Self::EXPERIMENTAL_CODES);
        format!("0x{:04X}-0x{:04X}", r.start(), r.end())
    }

    /// Whether `code` is in the experimental range (0xD000-0xFFFF).
    pub fn is_experimental_code(code: u16) -> bool {
        Self::EXPERIMENTAL_CODES.contains(&code)
    }

    /// Whether `code` is reserved by the standard (0xC000-0xCFFF): in no class's range
    /// and not experimental.
    pub fn is_reserved_code(code: u16) -> bool {
        Self::of_code(code).is_none() && !Self::is_experimental_code(code)
    }

    /// The code of the report answering the query with code `query` by the complement
    /// rule (`query + 0x2000`); `None` outside the standard query range (an
    /// experimental query names its report).
    pub fn report_code(query: u16) -> Option<u16> {
        (Self::of_code(query) == Some(Self::Query)).then(|| query + Self::COMPLEMENT)
    }

    /// The code of the query a report (inform) code answers by the complement rule
    /// (`report - 0x2000`); `None` outside the standard inform range.
    pub fn query_code(report: u16) -> Option<u16> {
        (Self::of_code(report) == Some(Self::Inform)).then(|| report - Self::COMPLEMENT)
    }

    /// The YAML spelling.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Command => "command",
            Self::Query => "query",
            Self::Inform => "inform",
            Self::EventSetup => "event_setup",
            Self::EventNotification => "event_notification",
            Self::NodeManagement => "node_management",
            Self::Experimental => "experimental",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::MessageClass as C;

    #[test]
    fn ranges_cover_the_standard_classes_then_reserved_then_experimental() {
        let mut next = 0u32;
        for (class, first, last) in C::RANGES {
            assert_eq!(u32::from(first), next, "{class:?}");
            assert_eq!(class.codes(), Some(first..=last));
            next = u32::from(last) + 1;
        }
        assert_eq!(next, 0xC000);
        assert!(C::is_reserved_code(0xC000) && C::is_reserved_code(0xCFFF));
        assert!(!C::is_reserved_code(0xBFFF) && !C::is_reserved_code(0xD000));
        assert!(C::is_experimental_code(0xD000) && !C::is_experimental_code(0xCFFF));
        assert_eq!(C::Query.codes_text(), "0x2000-0x3FFF");
        assert_eq!(C::Experimental.codes_text(), "0xD000-0xFFFF");
    }

    #[test]
    fn the_complement_rule_pairs_queries_and_reports() {
        assert_eq!(C::report_code(0x2002), Some(0x4002));
        assert_eq!(C::query_code(0x4002), Some(0x2002));
        assert_eq!(C::report_code(0x3FFF), Some(0x5FFF));
        assert_eq!(C::report_code(0x4002), None);
        assert_eq!(C::report_code(0xD002), None);
        assert_eq!(C::query_code(0x6000), None);
    }
}
