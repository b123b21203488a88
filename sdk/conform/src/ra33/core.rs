//! The core queries: identification, services, status, heartbeat, authority.

use std::collections::BTreeSet;

use jaus::messages::{
    Message, QueryComponentAuthority, QueryHeartbeatPulse, QueryIdentification, QueryLevel,
    QueryServices,
};
use jaus::wire::AckNak;

use super::Ra33Voice;
use crate::check::Verdict;

use crate::engine::Found;

impl Ra33Voice<'_> {
    fn no_answer(&self, query: &str) -> Found {
        (
            Verdict::Fail,
            format!("no answer to {query} within {:?}", self.opts.wait),
        )
    }

    pub(super) fn identification(&mut self) -> Found {
        let q = QueryIdentification {
            query_field: QueryLevel::Component,
        };
        match self.ask(self.voices.outsider, q.into()) {
            Some(Message::ReportIdentification(r)) => {
                self.identification = Some(r.identification.clone());
                if r.query_type == QueryLevel::Component {
                    (
                        Verdict::Pass,
                        format!(
                            "identified as {:?} (type {})",
                            r.identification, r.identification_type
                        ),
                    )
                } else {
                    (
                        Verdict::Fail,
                        format!("answered at level {:?}, not Component", r.query_type),
                    )
                }
            }
            _ => self.no_answer("Query Identification"),
        }
    }

    pub(super) fn services(&mut self, inputs: bool) -> Found {
        let Some(Message::ReportServices(r)) =
            self.ask(self.voices.outsider, QueryServices {}.into())
        else {
            return self.no_answer("Query Services");
        };
        let id = u16::from(self.target.component);
        let own = r.services.iter().find(|s| s.service_type == id);
        if !inputs {
            let core = r.services.iter().any(|s| s.service_type == 0);
            return match (core, own.is_some()) {
                (true, true) => (
                    Verdict::Pass,
                    format!(
                        "{} services listed, the core service and service {id}",
                        r.services.len()
                    ),
                ),
                (c, o) => (
                    Verdict::Fail,
                    format!(
                        "missing:{}{}",
                        if c { "" } else { " the core service (type 0)" },
                        if o {
                            String::new()
                        } else {
                            format!(" its own service (type {id})")
                        }
                    ),
                ),
            };
        }
        let Some(def) = self
            .spec
            .components
            .iter()
            .find(|c| c.def.id == self.target.component)
        else {
            return (
                Verdict::Inconclusive,
                "the definitions do not know this component".into(),
            );
        };
        let Some(own) = own else {
            return (
                Verdict::Fail,
                format!("its own service (type {id}) is not listed"),
            );
        };
        let listed: BTreeSet<u16> = r
            .services
            .iter()
            .flat_map(|s| s.input_commands.iter().map(|c| c.command_code))
            .collect();
        let _ = own;
        let wanted: Vec<(&String, u16)> = def
            .def
            .commands
            .iter()
            .chain(&def.def.accepts)
            .filter_map(|n| self.spec.message(n).map(|m| (n, m.def.code.0)))
            .collect();
        let missing: Vec<String> = wanted
            .iter()
            .filter(|(_, c)| !listed.contains(c))
            .map(|(n, c)| format!("{n} (0x{c:04X})"))
            .collect();
        if missing.is_empty() {
            (
                Verdict::Pass,
                format!("all {} messages of its definition are inputs", wanted.len()),
            )
        } else {
            (
                Verdict::Fail,
                format!("not listed as inputs: {}", missing.join(", ")),
            )
        }
    }

    pub(super) fn status_check(&mut self) -> Found {
        match self.status() {
            Some(s) => (Verdict::Pass, format!("state {s:?}")),
            None => self.no_answer("Query Component Status"),
        }
    }

    pub(super) fn heartbeat(&mut self) -> Found {
        match self.ask(self.voices.outsider, QueryHeartbeatPulse {}.into()) {
            Some(_) => (Verdict::Pass, "Report Heartbeat Pulse received".into()),
            None => self.no_answer("Query Heartbeat Pulse"),
        }
    }

    pub(super) fn authority_check(&mut self) -> Found {
        match self.ask(self.voices.outsider, QueryComponentAuthority {}.into()) {
            Some(Message::ReportComponentAuthority(r)) => {
                self.authority = r.authority_code;
                (Verdict::Pass, format!("authority {}", r.authority_code))
            }
            _ => self.no_answer("Query Component Authority"),
        }
    }
}

/// Says how a command was acknowledged.
pub(super) fn ack_text(a: Option<AckNak>) -> &'static str {
    match a {
        Some(AckNak::Ack) => "acknowledged (ACK)",
        Some(AckNak::Nak) => "refused (NAK)",
        _ => "not acknowledged",
    }
}
