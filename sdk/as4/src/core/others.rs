//! The Core's other services on their generated machines: Time, Liveness, Discovery and
//! List Manager (`defs/core_services.yaml`). Each inherits a service of the Core's main
//! machine (Access Control, Events or Management) and adds transitions for its own
//! messages; [`OtherMachines`] runs them beside that machine, each following its state
//! ([`jaus::hsm::Machine::follow`]), on the same [`Host`] (their data lent to it as
//! [`Others`](super::machine::Others)), which implements their generated guards and
//! actions over the services' data here.
//!
//! What the definitions decide here, and the code no longer does: who may set the time
//! and change the list (a transition under `Controlled` guarded by
//! `isControllingClient`), which queries are answered in which states, and which
//! messages these services take at all (`RECEIVES` of each).

use jaus::net::as5669a::As4Id;

use super::lists::{answer, Lists};
use super::liveness;
use super::machine::Host;
use crate::messages::services::transport::event::Receive;
use crate::messages::services::{discovery, list_manager, liveness as live, time};
use crate::messages::{
    DeleteElement, Message, QueryConfiguration, QueryElement, QueryIdentification,
    QueryServiceList, QueryServices, QueryTime, RegisterServices, ReportElement,
    ReportElementCount, ReportElementList, SetElement, SetTime,
};
use crate::outgoing::{receive_of, sender_of};

/// The running machines of the Core's other services.
#[derive(Debug, Clone, Default)]
pub(crate) struct OtherMachines {
    time: time::Machines,
    liveness: live::Machines,
    discovery: discovery::Machines,
    list_manager: list_manager::Machines,
}

impl OtherMachines {
    /// Offers `msg` from `from` to each service that takes it (the List Manager only when
    /// `list_manager`), its machine first following the Core's machine at `core_state`:
    /// `None` when none takes it, else whether a transition was taken.
    pub(crate) fn receive(
        &mut self,
        host: &mut Host<'_>,
        msg: &Message,
        from: As4Id,
        core_state: &'static str,
        list_manager: bool,
    ) -> Option<bool> {
        let transport = receive_of(from);
        let code = msg.code();
        if time::RECEIVES.contains(&code) {
            follow(&mut self.time.0, core_state);
            return self.time.receive(host, msg, &transport);
        }
        if live::RECEIVES.contains(&code) {
            follow(&mut self.liveness.0, core_state);
            return self.liveness.receive(host, msg, &transport);
        }
        if discovery::RECEIVES.contains(&code) {
            follow(&mut self.discovery.0, core_state);
            return self.discovery.receive(host, msg, &transport);
        }
        if list_manager && list_manager::RECEIVES.contains(&code) {
            follow(&mut self.list_manager.0, core_state);
            return self.list_manager.receive(host, msg, &transport);
        }
        None
    }

    /// Whether one of these services takes message `code`.
    pub(crate) fn takes(code: jaus::CommandCode, list_manager: bool) -> bool {
        time::RECEIVES.contains(&code)
            || live::RECEIVES.contains(&code)
            || discovery::RECEIVES.contains(&code)
            || (list_manager && list_manager::RECEIVES.contains(&code))
    }
}

/// Each machine follows the Core's (they all extend its ReceiveFSM).
fn follow(m: &mut jaus::hsm::Machines, core_state: &'static str) {
    m.follow_all(core_state);
}

impl time::Time for Host<'_> {
    fn send_report_time(&mut self, msg: &QueryTime, t: &Receive) {
        let now = self.now();
        if let Some(report) = self.others_ref().map(|o| o.time.report(now, msg)) {
            self.send(sender_of(t), report);
        }
    }

    fn set_time(&mut self, msg: &SetTime) {
        let now = self.now();
        let result = match self.others() {
            Some(o) => o.time.set(now, msg),
            None => Err("the Time service's data is not at hand".into()),
        };
        if let Err(why) = result {
            self.refuse(why);
        }
    }
}

impl live::Liveness for Host<'_> {
    fn send_report_heartbeat_pulse(&mut self, t: &Receive) {
        self.send(sender_of(t), liveness::heartbeat());
    }
}

impl discovery::Discovery for Host<'_> {
    fn register_services(&mut self, msg: &RegisterServices, t: &Receive) {
        let result = match self.others() {
            Some(o) => o.discovery.register(sender_of(t), msg.services.clone()),
            None => Err("the Discovery service's data is not at hand".into()),
        };
        if let Err(why) = result {
            self.reach_bound(why);
        }
    }

    fn send_report_configuration(&mut self, msg: &QueryConfiguration, t: &Receive) {
        let report = self
            .others_ref()
            .and_then(|o| o.discovery.configuration(msg.query_type));
        if let Some(r) = report {
            self.send(sender_of(t), r);
        }
    }

    fn send_report_identification(&mut self, msg: &QueryIdentification, t: &Receive) {
        let report = self
            .others_ref()
            .and_then(|o| o.discovery.identify(msg.query_type));
        if let Some(r) = report {
            self.send(sender_of(t), r);
        }
    }

    fn send_report_service_list(&mut self, msg: &QueryServiceList, t: &Receive) {
        let report = self.others_ref().map(|o| o.discovery.service_list(msg));
        if let Some(r) = report {
            self.send(sender_of(t), r);
        }
    }

    fn send_report_services(&mut self, msg: &QueryServices, t: &Receive) {
        let report = self.others_ref().map(|o| o.discovery.services(msg));
        if let Some(r) = report {
            self.send(sender_of(t), r);
        }
    }

    fn send_report_subsystem_list(&mut self, t: &Receive) {
        let report = self.others_ref().map(|o| o.discovery.subsystems());
        if let Some(r) = report {
            self.send(sender_of(t), r);
        }
    }
}

impl Host<'_> {
    /// Runs `f` on the list manager and sends what it returns to the sender.
    fn list_answer(&mut self, t: &Receive, f: impl FnOnce(&mut Lists) -> Option<Message>) {
        let answer = self
            .others()
            .and_then(|o| o.lists.as_deref_mut())
            .and_then(f);
        if let Some(a) = answer {
            self.send(sender_of(t), a);
        }
    }
}

impl list_manager::ListManager for Host<'_> {
    fn element_exists(&self, msg: &QueryElement) -> bool {
        self.others_ref()
            .and_then(|o| o.lists.as_deref())
            .is_some_and(|l| l.get(msg.element_uid).is_some())
    }

    fn delete_element(&mut self, msg: &DeleteElement, t: &Receive) {
        self.list_answer(t, |l| {
            Some(answer(msg.request_id, l.delete(&msg.element_uids)))
        });
    }

    fn send_report_element(&mut self, msg: &QueryElement, t: &Receive) {
        self.list_answer(t, |l| {
            l.get(msg.element_uid)
                .map(|e| ReportElement { element: e.clone() }.into())
        });
    }

    fn send_report_element_count(&mut self, t: &Receive) {
        self.list_answer(t, |l| {
            let element_count = u16::try_from(l.len()).unwrap_or(u16::MAX);
            Some(ReportElementCount { element_count }.into())
        });
    }

    fn send_report_element_list(&mut self, t: &Receive) {
        self.list_answer(t, |l| {
            Some(
                ReportElementList {
                    element_uids: l.uids(),
                }
                .into(),
            )
        });
    }

    fn set_element(&mut self, msg: &SetElement, t: &Receive) {
        self.list_answer(t, |l| Some(answer(msg.request_id, l.set(&msg.elements))));
    }
}
