//! Robustness: a malformed or unknown packet, then Query Identification must still be
//! answered.

use jaus::messages::{Message, QueryIdentification, QueryLevel};
use jaus::wire::DataFlag;
use jaus::{CommandCode, JausMessage};

use super::talk::Raw;
use super::Ra33Voice;
use crate::check::{Malformed, Verdict};

impl Ra33Voice<'_> {
    /// A command code neither the SDK nor the loaded definitions define.
    fn unknown_code(&self) -> CommandCode {
        (0x1E00u16..0x2000)
            .find(|c| {
                jaus::messages::MESSAGES.iter().all(|m| m.code.0 != *c)
                    && self.spec.message_by_code(*c).is_none()
            })
            .map_or(CommandCode(0x1FFF), CommandCode)
    }

    pub(super) fn robust(&mut self, m: Malformed) -> (Verdict, String) {
        let o = self.voices.outsider;
        let what = match m {
            Malformed::TruncatedBody => {
                // Query Identification's body is one byte: send none.
                self.send_raw(o, Raw::single(QueryIdentification::CODE, &[]));
                "Query Identification without its body"
            }
            Malformed::WrongDataSize => {
                // Query Component Status has no body: announce 10 bytes.
                self.send_raw(
                    o,
                    Raw {
                        data_size: Some(10),
                        ..Raw::single(CommandCode(0x2002), &[])
                    },
                );
                "Query Component Status announcing 10 bytes it does not carry"
            }
            Malformed::UnknownCode => {
                let code = self.unknown_code();
                self.send_raw(o, Raw::single(code, &[0xAB, 0xCD]));
                "a message with an unknown command code"
            }
            Malformed::OutOfRange => {
                // No query level has the value 0xEE.
                self.send_raw(o, Raw::single(QueryIdentification::CODE, &[0xEE]));
                "Query Identification asking for level 0xEE, which no level has"
            }
            Malformed::IncompleteSequence => {
                // The first packet of a two-packet Query Services that never ends,
                // then a last packet of a sequence never begun.
                let filler = [0x5Au8; 200];
                for (flag, sequence) in [(DataFlag::First, 0), (DataFlag::Last, 7)] {
                    self.send_raw(
                        o,
                        Raw {
                            flag,
                            sequence,
                            ..Raw::single(CommandCode(0x2B03), &filler)
                        },
                    );
                }
                "the first packet of a multi-packet message never completed and a last packet of one never begun"
            }
        };
        self.drain(self.opts.settle);
        let q = QueryIdentification {
            query_field: QueryLevel::Component,
        };
        match self.ask(o, q.into()) {
            Some(Message::ReportIdentification(_)) => (
                Verdict::Pass,
                format!("still answers Query Identification after {what}"),
            ),
            _ => (
                Verdict::Fail,
                format!(
                    "no answer to Query Identification within {:?} after {what}",
                    self.opts.wait
                ),
            ),
        }
    }
}
