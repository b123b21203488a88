//! The scenario's checks before and after the sensors and the waypoints: discovery,
//! services, access control, management, the periodic Query Identification, control
//! kept, and last the component given back as found (or Shutdown, when asked).

use std::time::Duration;

use jaus::net::as5669a::As4Id;
use jaus_as4::messages::{
    ComponentState, ControlConfirmation, IdentificationType, Message, NodeServicesQuery,
    QueryControl, QueryIdentification, QueryServices, QueryTimeout, ReleaseControl, RequestControl,
    Resume, Shutdown, Standby,
};

use super::talk::BROADCAST;
use super::Scenario;
use crate::engine::{fail, inconclusive, pass, Found};

/// The services the scenario needs: the name after `urn:jaus:jss:<set>:` and the sets
/// whose URI counts.
const NEEDED: [(&str, &[&str]); 7] = [
    ("Discovery", &["core"]),
    ("AccessControl", &["core"]),
    ("Management", &["core"]),
    ("VelocityStateSensor", &["mobility"]),
    ("LocalPoseSensor", &["mobility"]),
    ("LocalWaypointListDriver", &["mobility"]),
    ("ListManager", &["core", "mobility"]),
];

/// Whether `uri` names service `name` of one of `sets`.
fn is_service(uri: &str, name: &str, sets: &[&str]) -> bool {
    sets.iter().any(|set| {
        uri.strip_prefix("urn:jaus:jss:")
            .and_then(|r| r.strip_prefix(set))
            == Some(&format!(":{name}"))
    })
}

impl Scenario<'_> {
    /// Without control the judge's commands prove nothing: why not, when it is not held.
    pub(super) fn needs_control(&self) -> Option<Found> {
        (!self.controlled)
            .then(|| inconclusive("not run: the judge does not hold control (as4.control.request)"))
    }

    /// Brings the component to Ready (Resume when it is not); `Err` says why not.
    pub(super) fn ensure_ready(&mut self) -> Result<(), String> {
        match self.j.status()? {
            ComponentState::Ready => Ok(()),
            _ => {
                self.j.command(Resume {}.into());
                match self.j.status()? {
                    ComponentState::Ready => Ok(()),
                    s => Err(format!("the component is {s:?}, not Ready, after Resume")),
                }
            }
        }
    }

    /// `as4.discovery.identification`.
    pub(super) fn identification(&mut self) -> Found {
        let to = self.j.opts.target.unwrap_or(BROADCAST);
        let q = QueryIdentification {
            query_type: IdentificationType::Subsystem,
        };
        let (report, _, from) = match self.j.ask_raw(to, q.into()) {
            Ok(r) => r,
            Err(e) => return fail(e),
        };
        let Message::ReportIdentification(r) = report else {
            return fail("the answer is not Report Identification");
        };
        self.discovered = Some(from);
        self.identification = Some(r.identification.clone());
        if self.j.opts.target.is_none() {
            self.j.peer = from;
            self.known = true;
        }
        self.j.start_periodic(from);
        let mut note = String::new();
        if let Some(std::net::SocketAddr::V4(v)) = self.j.opts.vehicle {
            let octet = v.ip().octets()[3];
            if u16::from(octet) != from.subsystem {
                note = format!(
                    " (the IOP rules give a team the subsystem id of its IP address's last octet, {octet}; accepted as it is)"
                );
            }
        }
        pass(format!(
            "Report Identification from {from}: `{}` ({:?}, {:?}){note}",
            r.identification, r.query_type, r.entity_type
        ))
    }

    /// `as4.discovery.services`: the component listing the Local Waypoint List Driver
    /// becomes the one under test.
    pub(super) fn services(&mut self) -> Found {
        let to = self.discovered.unwrap_or(self.j.peer);
        let q = QueryServices {
            nodes: vec![NodeServicesQuery {
                node_id: 0xFF,
                component_ids: vec![0xFF],
            }],
        };
        let report = match self.j.ask_raw(to, q.into()) {
            Ok((Message::ReportServices(r), _, _)) => r,
            Ok(_) => return fail("the answer is not Report Services"),
            Err(e) => return fail(e),
        };
        // Every component listed: its id and its URIs.
        let listed: Vec<(As4Id, Vec<String>)> = report
            .nodes
            .iter()
            .flat_map(|n| {
                n.components.iter().map(move |c| {
                    (
                        As4Id::new(to.subsystem, n.node_id, c.component_id),
                        c.services.iter().map(|s| s.uri.clone()).collect(),
                    )
                })
            })
            .collect();
        let has = |uris: &[String], (name, sets): (&str, &[&str])| {
            uris.iter().any(|u| is_service(u, name, sets))
        };
        let missing: Vec<&str> = NEEDED
            .iter()
            .filter(|n| !listed.iter().any(|(_, uris)| has(uris, **n)))
            .map(|n| n.0)
            .collect();
        let driver = listed
            .iter()
            .find(|(_, uris)| has(uris, NEEDED[5]))
            .map(|(id, uris)| (*id, uris.clone()));
        if self.j.opts.target.is_none() {
            if let Some((id, _)) = &driver {
                self.j.peer = *id;
            }
        }
        let all: Vec<String> = listed
            .iter()
            .map(|(id, uris)| format!("{id}: {}", uris.join(", ")))
            .collect();
        if !missing.is_empty() {
            return fail(format!(
                "not listed: {}; listed: {}",
                missing.join(", "),
                if all.is_empty() {
                    "nothing".into()
                } else {
                    all.join("; ")
                }
            ));
        }
        let on_one = driver
            .as_ref()
            .is_some_and(|(_, uris)| NEEDED.iter().all(|n| has(uris, *n)));
        if on_one {
            pass(format!(
                "every service the scenario needs is on {}: {}",
                self.j.peer,
                all.join("; ")
            ))
        } else {
            fail(format!(
                "the services are spread over several components (the IOP rules want them on one); the checks go to {}: {}",
                self.j.peer,
                all.join("; ")
            ))
        }
    }

    /// `as4.control.query`.
    pub(super) fn control_query(&mut self) -> Found {
        match self.j.ask(QueryControl {}.into()) {
            Ok(Message::ReportControl(r)) => {
                let c = &r.controller;
                let id = As4Id::new(c.subsystem_id, c.node_id, c.component_id);
                if id != As4Id::default() && id != self.j.me {
                    self.found_controller = Some(id);
                }
                if id == As4Id::default() {
                    pass("nobody in control")
                } else {
                    pass(format!("{id} in control at authority {}", r.authority_code))
                }
            }
            Ok(m) => fail(format!("Query Control answered by {}", m.name())),
            Err(e) => fail(e),
        }
    }

    /// `as4.control.request`: Request Control, Confirm Control, Report Control naming
    /// the judge; then the judge renews its request before the control timeout.
    pub(super) fn control_request(&mut self) -> Found {
        let authority = self.j.opts.authority;
        self.j.send(
            &RequestControl {
                authority_code: authority,
            }
            .into(),
        );
        let peer = self.j.peer;
        let Some(a) = self
            .j
            .wait_for(self.j.opts.wait, Some(peer), &[0x000F, 0x0010])
        else {
            return fail(format!(
                "no answer to Request Control within {:.1} s",
                self.j.opts.wait.as_secs_f64()
            ));
        };
        let answer =
            jaus_as4::Message::decode(jaus::CommandCode(a.message.message_id), &a.message.body);
        match answer {
            Ok(Message::ConfirmControl(c))
                if c.response_code == ControlConfirmation::ControlAccepted => {}
            Ok(Message::ConfirmControl(c)) => {
                return fail(format!("Confirm Control {:?}", c.response_code))
            }
            Ok(m) => return fail(format!("Request Control answered by {}", m.name())),
            Err(e) => return fail(format!("the answer does not decode: {e}")),
        }
        self.controlled = true;
        // The control timeout: renew at half of it (2 s when not answered).
        let every = match self.j.ask(QueryTimeout {}.into()) {
            Ok(Message::ReportTimeout(t)) if t.timeout == 0 => None,
            Ok(Message::ReportTimeout(t)) => Some(
                (Duration::from_secs(u64::from(t.timeout)) / 2)
                    .clamp(Duration::from_millis(200), Duration::from_secs(2)),
            ),
            _ => Some(Duration::from_secs(2)),
        };
        self.j.keep_control(every);
        match self.j.ask(QueryControl {}.into()) {
            Ok(Message::ReportControl(r)) => {
                let c = &r.controller;
                let id = As4Id::new(c.subsystem_id, c.node_id, c.component_id);
                if id == self.j.me {
                    pass(format!(
                        "Control Accepted; Report Control names {id} at authority {}",
                        r.authority_code
                    ))
                } else {
                    fail(format!(
                        "Control Accepted, but Report Control names {id}, not the judge {}",
                        self.j.me
                    ))
                }
            }
            Ok(m) => fail(format!("Query Control answered by {}", m.name())),
            Err(e) => fail(format!("Control Accepted, but {e}")),
        }
    }

    /// `as4.management.status`.
    pub(super) fn status_check(&mut self) -> Found {
        match self.j.status() {
            Ok(s) => {
                self.found_state = Some(s);
                pass(format!("{s:?}"))
            }
            Err(e) => fail(e),
        }
    }

    /// `as4.management.resume`: from Standby (sent first when the component is Ready,
    /// so that Resume has something to do).
    pub(super) fn resume(&mut self) -> Found {
        if let Some(f) = self.needs_control() {
            return f;
        }
        let before = match self.j.status() {
            Ok(s) => s,
            Err(e) => return inconclusive(e),
        };
        let mut note = String::new();
        if before == ComponentState::Ready {
            self.j.command(Standby {}.into());
            match self.j.status() {
                Ok(ComponentState::Standby) => {
                    note = " (Ready at first: Standby sent before)".into()
                }
                Ok(s) => {
                    return inconclusive(format!(
                    "Ready at first, and {s:?} after Standby: Resume cannot be told from nothing"
                ))
                }
                Err(e) => return inconclusive(e),
            }
        }
        self.j.command(Resume {}.into());
        match self.j.status() {
            Ok(ComponentState::Ready) => pass(format!("Ready after Resume{note}")),
            Ok(s) => fail(format!("{s:?} after Resume, not Ready{note}")),
            Err(e) => fail(format!("after Resume: {e}")),
        }
    }

    /// `as4.management.standby`; Resume afterwards for the commands that follow.
    pub(super) fn standby(&mut self) -> Found {
        if let Some(f) = self.needs_control() {
            return f;
        }
        self.j.command(Standby {}.into());
        let found = match self.j.status() {
            Ok(ComponentState::Standby) => pass("Standby after Standby"),
            Ok(s) => fail(format!("{s:?} after Standby, not Standby")),
            Err(e) => fail(format!("after Standby: {e}")),
        };
        match self.ensure_ready() {
            Ok(()) => found,
            Err(e) => (found.0, format!("{}; then {e}", found.1)),
        }
    }

    /// `as4.discovery.periodic`: the background Query Identification, stopped here.
    pub(super) fn periodic(&mut self) -> Found {
        if !self.j.stop_periodic() {
            return inconclusive("not run: discovery found nobody to ask");
        }
        let p = &self.j.periodic;
        let every = self.j.opts.periodic.as_secs_f64();
        let summary = format!(
            "{} sent every {every:.1} s: {} answered within {:.1} s, {} late, {} not answered; slowest answer {:.0} ms",
            p.sent,
            p.answered,
            self.j.opts.wait.as_secs_f64(),
            p.late,
            p.missed,
            p.worst.as_secs_f64() * 1000.0
        );
        let (sent, answered) = (p.sent, p.answered);
        let evidence = self.j.periodic.evidence.take();
        let found = if sent == 0 {
            inconclusive(summary)
        } else if answered == sent {
            pass(summary)
        } else {
            fail(summary)
        };
        // The queries and their answers are this check's evidence.
        self.j.add_evidence(evidence);
        found
    }

    /// `as4.control.kept`: the renewed requests were confirmed, control never lost.
    pub(super) fn control_kept(&mut self) -> Found {
        if let Some(f) = self.needs_control() {
            return f;
        }
        let k = &self.j.keepalive;
        let summary = format!(
            "Request Control renewed {} times: {} confirmed, {} refused{}, {} Reject Control",
            k.sent,
            k.confirmed,
            k.refused.len(),
            if k.refused.is_empty() {
                String::new()
            } else {
                format!(" (codes {})", k.refused.join(", "))
            },
            k.rejected
        );
        let found = if !k.refused.is_empty() || k.rejected > 0 {
            fail(summary)
        } else {
            match self.j.ask(QueryControl {}.into()) {
                Ok(Message::ReportControl(r)) => {
                    let c = &r.controller;
                    let id = As4Id::new(c.subsystem_id, c.node_id, c.component_id);
                    if id == self.j.me {
                        pass(format!("{summary}; Report Control still names the judge"))
                    } else {
                        fail(format!("{summary}; Report Control names {id}"))
                    }
                }
                _ => inconclusive(format!("{summary}; Query Control not answered")),
            }
        };
        found
    }

    /// `as4.management.shutdown`, last, run only when [`super::As4Options::shutdown`]
    /// asks for it: Report Status Shutdown, or silence.
    pub(super) fn shutdown(&mut self) -> Found {
        if let Some(f) = self.needs_control() {
            return f;
        }
        self.j.keep_control(None);
        self.j.command(Shutdown {}.into());
        match self.j.status() {
            Ok(ComponentState::Shutdown) => pass("Shutdown after Shutdown"),
            Ok(s) => {
                let found = fail(format!("{s:?} after Shutdown"));
                self.release(&found.1);
                found
            }
            Err(_) => {
                pass("the component stopped answering after Shutdown (Query Status not answered)")
            }
        }
    }

    /// `as4.control.release`, last unless Shutdown is asked for: the component is put
    /// back in the state it was found in (Standby, when it was found in Standby and is
    /// Ready now), then Release Control must end the judge's control (Reject Control,
    /// Control Released; Report Control no longer naming the judge). The detail says
    /// what the judge could not restore.
    pub(super) fn release_control(&mut self) -> Found {
        self.j.keep_control(None);
        if let Some(f) = self.needs_control() {
            return f;
        }
        let mut unrestored = Vec::new();
        match (self.found_state, self.j.status()) {
            (Some(ComponentState::Standby), Ok(ComponentState::Ready)) => {
                self.j.command(Standby {}.into());
            }
            (Some(found), Ok(now)) if found != now => unrestored.push(format!(
                "found in {found:?}, {now:?} before the release (only Ready → Standby is restored)"
            )),
            (_, Err(e)) => unrestored.push(format!("the state before the release: {e}")),
            _ => {}
        }
        self.j.send(&ReleaseControl {}.into());
        let peer = self.j.peer;
        let answer = self.j.wait_for(self.j.opts.wait, Some(peer), &[0x0010]);
        self.controlled = false;
        let answer = match answer.map(|a| {
            jaus_as4::Message::decode(jaus::CommandCode(a.message.message_id), &a.message.body)
        }) {
            Some(Ok(Message::RejectControl(r))) => format!("Reject Control {:?}", r.response_code),
            Some(Ok(m)) => format!("answered by {}", m.name()),
            Some(Err(e)) => format!("the answer does not decode: {e}"),
            None => format!(
                "no Reject Control within {:.1} s",
                self.j.opts.wait.as_secs_f64()
            ),
        };
        let holder = match self.j.ask(QueryControl {}.into()) {
            Ok(Message::ReportControl(r)) => {
                let c = &r.controller;
                Some(As4Id::new(c.subsystem_id, c.node_id, c.component_id))
            }
            _ => None,
        };
        match (self.found_state, self.j.status()) {
            (Some(found), Ok(now)) if found != now => {
                unrestored.push(format!("found in {found:?}, left in {now:?}"));
            }
            (_, Err(e)) => unrestored.push(format!("the state left in: {e}")),
            _ => {}
        }
        if let Some(other) = self.found_controller {
            unrestored.push(format!(
                "{other} held control when the judge came: control cannot be handed back"
            ));
        }
        if self.pose_set {
            unrestored.push("the local pose set by Set Local Pose".into());
        }
        if self.listed {
            unrestored.push("the waypoints loaded by Set Element".into());
        }
        let restored = if unrestored.is_empty() {
            "left as found".to_string()
        } else {
            format!("not restored: {}", unrestored.join("; "))
        };
        let me = self.j.me;
        match holder {
            Some(id) if id == me => fail(format!(
                "Release Control: {answer}, but Report Control still names the judge {me}; {restored}"
            )),
            Some(id) if id == As4Id::default() => pass(format!(
                "Release Control: {answer}; Report Control names nobody; {restored}"
            )),
            Some(id) => pass(format!(
                "Release Control: {answer}; Report Control names {id}, not the judge; {restored}"
            )),
            None => inconclusive(format!(
                "Release Control: {answer}; Query Control not answered: the release cannot be seen; {restored}"
            )),
        }
    }

    /// Gives control back after a Shutdown that was not carried out; `why` is the
    /// detail.
    fn release(&mut self, why: &str) -> Found {
        self.j.keep_control(None);
        if self.controlled {
            self.j.send(&ReleaseControl {}.into());
            self.j.drain(self.j.opts.settle);
        }
        inconclusive(why)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn service_uris_match_by_set_and_name() {
        assert!(is_service(
            "urn:jaus:jss:core:Discovery",
            "Discovery",
            &["core"]
        ));
        assert!(is_service(
            "urn:jaus:jss:mobility:ListManager",
            "ListManager",
            &["core", "mobility"]
        ));
        assert!(!is_service(
            "urn:jaus:jss:core:DiscoveryClient",
            "Discovery",
            &["core"]
        ));
        assert!(!is_service(
            "urn:jaus:jss:mobility:Discovery",
            "Discovery",
            &["core"]
        ));
    }
}
